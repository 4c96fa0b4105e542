/* shapes — lesson 03, experiment 1 (§2, §3): what a painted particle looks like, and
 * why moving it is cheap.
 *
 * Pictures: the excluded disk of a square-lattice particle (r = 2R = 8) split into the
 * points a step along +x keeps, gains (head) and loses (tail) — thesis fig. 2.9; and
 * circles of radius 6, 8, 10 and 10.9 on the triangular lattice, drawn once where the
 * sites really are and once in the sheared storage coordinates, where they are
 * ellipses x² + xy + y² < r² — thesis fig. 2.14.
 *
 * Counts: for r = 3 .. 96 on square8 (axis and diagonal steps), triangular and
 * cubic26 (face, edge and corner steps), the points |S| of the shape against the
 * continuum area (volume) over the area per site, and the head points of every step
 * against the continuum value of the crescent a step of length a sweeps: 2ra in 2D,
 * πr²a in 3D (the lens formula to first order in a/r), over the area per site. The
 * head grows like the perimeter (surface), the shape like the area (volume): the
 * move costs r^(dim-1), placement r^dim.
 *
 * Checks: at the largest radii every count is within 1 % (|S|) and 3 % (heads) of the
 * continuum.
 *
 * Usage: shapes OUTDIR [--quick]   (the same size either way: well under a second)
 * Writes OUTDIR/shapes.dat, shapes_cost.dat and shapes.json.
 */
#include <math.h>
#include <stdio.h>

#include "lz/error.h"
#include "lz/lattice.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/shape.h"

#define SQRT3_2 0.86602540378443865

/* Cartesian position of lattice offset (x, y): the triangular lattice is sheared. */
static void cartesian(lz_lattice_kind kind, int32_t x, int32_t y, double *cx, double *cy)
{
	int tri = kind == LZ_LATTICE_TRIANGULAR;
	*cx = x + (tri ? 0.5 * y : 0.0);
	*cy = tri ? SQRT3_2 * y : y;
}

/* 1 if p is in the set pts[0 .. n) (a linear search: pictures are small). */
static int has(const lz_site *pts, size_t n, lz_site p)
{
	for (size_t k = 0; k < n; k++)
		if (pts[k].x == p.x && pts[k].y == p.y)
			return 1;
	return 0;
}

static void row(lz_data *d, int panel, int set, lz_lattice_kind kind, lz_site p)
{
	double v[6] = {panel, set, p.x, p.y, 0, 0};
	cartesian(kind, p.x, p.y, &v[4], &v[5]);
	lz_data_row(d, v);
}

/* Panel 0: body (set 0), head (1) and tail (2) of a +x step of the square disk. */
static int picture_step(lz_data *d)
{
	lz_shape *s = lz_shape_alloc(LZ_LATTICE_SQUARE, 8);
	if (!s)
		return LZ_EINVAL;
	for (size_t k = 0; k < s->n; k++)
		if (!has(s->tail[0], s->nmove[0], s->pts[k]))
			row(d, 0, 0, s->kind, s->pts[k]);
	for (size_t k = 0; k < s->nmove[0]; k++) {
		row(d, 0, 1, s->kind, s->head[0][k]);
		row(d, 0, 2, s->kind, s->tail[0][k]);
	}
	lz_shape_free(s);
	return LZ_OK;
}

/* Panel 1: the rim (points with an axis neighbour outside) of triangular circles. */
static int picture_ellipses(lz_data *d)
{
	static const double radius[] = {6, 8, 10, 10.9};
	for (int c = 0; c < 4; c++) {
		lz_shape *s = lz_shape_alloc(LZ_LATTICE_TRIANGULAR, radius[c]);
		if (!s)
			return LZ_EINVAL;
		for (size_t k = 0; k < s->n; k++) {
			lz_site p = s->pts[k];
			if (!lz_shape_contains(s, p.x + 1, p.y, 0) || !lz_shape_contains(s, p.x - 1, p.y, 0) ||
			    !lz_shape_contains(s, p.x, p.y + 1, 0) || !lz_shape_contains(s, p.x, p.y - 1, 0))
				row(d, 1, c, s->kind, p);
		}
		lz_shape_free(s);
	}
	return LZ_OK;
}

/* The continuum crescent a step of Cartesian length a sweeps, in sites. */
static double crescent(int dim, double r, double a, double cell)
{
	return (dim == 2 ? 2 * r * a : M_PI * r * r * a) / cell;
}

/* One row per (lattice, r, direction); the worst relative errors at the largest r go
 * to *err_n and *err_h. */
static int counts(lz_data *d, lz_lattice_kind kind, double rmax, double *err_n,
                  double *err_h)
{
	double cell = lz_lattice_cell_volume(kind);
	for (double r = 3; r <= rmax; r *= 2) {
		lz_shape *s = lz_shape_alloc(kind, r);
		if (!s)
			return LZ_EINVAL;
		double area = (s->dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r) / cell;
		for (int k = 0; k < s->ndir; k++) {
			lz_site e = s->dirs[k];
			double a = sqrt((double)lz_lattice_dist2(kind, e.x, e.y, e.z));
			double want = crescent(s->dim, r, a, cell);
			double v[7] = {kind, r, k, a, (double)s->n / area, (double)s->nmove[k] / want,
			               (double)s->nmove[k]};
			lz_data_row(d, v);
			if (r * 2 > rmax) {
				*err_n = fmax(*err_n, fabs(v[4] - 1));
				*err_h = fmax(*err_h, fabs(v[5] - 1));
			}
		}
		lz_shape_free(s);
	}
	return LZ_OK;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "03", &L) != LZ_OK)
		return 2;
	static const char *const pn[] = {"panel", "set", "x", "y", "X", "Y"};
	lz_data *d = lz_lesson_data(&L, "shapes.dat", "panel 0: body (set 0), head (1), tail "
	                            "(2) of a +x step, square r = 8; panel 1: rims of "
	                            "triangular circles r = 6, 8, 10, 10.9 (set 0..3); x y "
	                            "storage, X Y Cartesian", 6, pn, NULL);
	if (!d || picture_step(d) != LZ_OK || picture_ellipses(d) != LZ_OK ||
	    lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	static const char *const cn[] = {"lattice", "r", "dir", "a", "points_over_area",
	                                 "head_over_crescent", "head"};
	static const char *const cu[] = {"", "lattice units", "", "lattice units", "", "", ""};
	lz_data *c = lz_lesson_data(&L, "shapes_cost.dat", "shape points over the continuum "
	                            "area (volume) per site, head points of each step over the "
	                            "continuum crescent 2ra (πr²a in 3D) per site", 7, cn, cu);
	double err_n = 0, err_h = 0;
	if (!c || counts(c, LZ_LATTICE_SQUARE8, 96, &err_n, &err_h) != LZ_OK ||
	    counts(c, LZ_LATTICE_TRIANGULAR, 96, &err_n, &err_h) != LZ_OK ||
	    counts(c, LZ_LATTICE_CUBIC26, 48, &err_n, &err_h) != LZ_OK ||
	    lz_data_close(c) != LZ_OK)
		return lz_lesson_error(&L);
	printf("largest radii: |S| within %.2f %% of the continuum area: %s\n", 100 * err_n,
	       lz_lesson_check(&L, err_n < 0.01));
	printf("largest radii: every head within %.2f %% of the crescent 2ra (πr²a): %s\n",
	       100 * err_h, lz_lesson_check(&L, err_h < 0.03));

	lz_json *j = lz_lesson_json(&L, "shapes.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_num(j, "area_error_max", err_n);
	lz_json_num(j, "head_error_max", err_h);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "shape and head counts against the continuum");
}
