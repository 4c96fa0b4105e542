/* walk_lib.c — hard-disk walkers on a lattice: allocation, hand-made and random
 * starts, the packing fraction and an overlap count (lz/walk.h). The moves themselves
 * are graded (solutions/02-lattice/walk.c). */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_randist.h>

#include "lz/bits.h"
#include "lz/error.h"
#include "lz/walk.h"


double lz_walk_packing(lz_lattice_kind kind, int64_t side, double radius, size_t n)
{
	int dim = lz_lattice_dim(kind);
	if (dim == 0 || side < 1)
		return NAN;
	double L = (double)side, cell = lz_lattice_cell_volume(kind);
	if (dim == 2)
		return (double)n * M_PI * radius * radius / (L * L * cell);
	return (double)n * (4.0 / 3.0) * M_PI * radius * radius * radius / (L * L * L * cell);
}

double lz_walk_row_spacing(lz_lattice_kind kind)
{
	if (lz_lattice_dim(kind) == 0)
		return 0;
	return kind == LZ_LATTICE_TRIANGULAR ? 0.86602540378443865 : 1.0;
}

double lz_walk_slit_packing(int dim, int64_t side, double width, double radius, size_t n)
{
	if ((dim != 2 && dim != 3) || side < 1 || !(width > 0))
		return NAN;
	double L = (double)side;
	if (dim == 2)
		return (double)n * M_PI * radius * radius / (L * width);
	return (double)n * (4.0 / 3.0) * M_PI * radius * radius * radius / (L * L * width);
}

lz_walk *lz_walk_alloc(lz_lattice_kind kind, int64_t side, double radius, size_t n,
                       lz_walk_motion motion)
{
	int dim = lz_lattice_kind_side_check(kind, side);
	if (dim == 0)
		return NULL;
	if (side < 2)
		return lz_error(LZ_EINVAL, "side = 1: a walker needs a box of side 2 or more"), NULL;
	if (!(radius > 0) || !isfinite(radius))
		return lz_error(LZ_EINVAL, "radius = %g lattice units must be positive", radius),
		       NULL;
	if (4.0 * radius > (double)side)
		return lz_error(LZ_EINVAL, "radius = %g lattice units is too large for a box of side "
		                "%lld: the diameter 2R = %g must be at most L/2 = %lld (or a disk "
		                "would touch its own periodic image); take R <= %lld or a larger box",
		                radius, (long long)side, 2 * radius, (long long)side / 2,
		                (long long)side / 4), NULL;
	if (n == 0)
		return lz_error(LZ_EINVAL, "n = 0 walkers: give at least one"), NULL;
	if (motion != LZ_WALK_RANDOM && motion != LZ_WALK_BALLISTIC)
		return lz_error(LZ_EINVAL, "motion %d is neither random walk nor ballistic",
		                (int)motion), NULL;
	double eta = lz_walk_packing(kind, side, radius, n);
	double close = dim == 2 ? LZ_WALK_CLOSE_2D : LZ_WALK_CLOSE_3D;
	if (eta > close)
		return lz_error(LZ_EINVAL, "n = %zu disks of radius %g in a box of side %lld have "
		                "packing fraction %.4f, beyond close packing %.4f: no such "
		                "configuration exists", n, radius, (long long)side, eta, close), NULL;
	lz_walk *w = calloc(1, sizeof *w);
	if (!w)
		return lz_error(LZ_ENOMEM, "no memory for %zu walkers", n), NULL;
	w->r = calloc(n * (size_t)dim, sizeof *w->r);
	w->dir = calloc(n, sizeof *w->dir);
	if (!w->r || !w->dir) {
		lz_walk_free(w);
		return lz_error(LZ_ENOMEM, "no memory for %zu walkers", n), NULL;
	}
	w->box = lz_lattice_box_alloc(kind, side);
	if (!w->box) {
		lz_walk_free(w);
		return NULL;
	}
	w->dim = dim;
	w->n = n;
	w->radius = radius;
	w->sigma2 = (int64_t)ceil(4.0 * radius * radius);
	w->motion = motion;
	w->dirs = lz_lattice_dirs(kind, &w->ndir);
	w->lo = 0;
	w->hi = (int32_t)(side - 1);
	return w;
}

void lz_walk_free(lz_walk *w)
{
	if (!w)
		return;
	lz_lattice_box_free(w->box);
	free(w->r);
	free(w->dir);
	free(w);
}

int lz_walk_set_slit(lz_walk *w, double width)
{
	double h = lz_walk_row_spacing(w->box->kind), R = w->radius;
	double widest = (double)w->box->side * h;
	if (!(width <= widest))
		return lz_error(LZ_EINVAL, "slit width %g is wider than the box can hold: at most "
		                "L·h = %g lattice units for side L = %d (row spacing h = %g); take a "
		                "larger box", width, widest, (int)w->box->side, h);
	double lo = ceil(R / h), hi = floor((width - R) / h);
	if (!(lo <= hi))
		return lz_error(LZ_EINVAL, "slit width %g leaves no row for a centre of radius %g "
		                "between the walls: it must be at least %g (2R = %g, up to the "
		                "first row of spacing %g that fits)", width, R, lo * h + R, 2 * R, h);
	w->slit = 1;
	w->slit_width = width;
	w->lo = (int32_t)lo;
	w->hi = (int32_t)hi;
	return LZ_OK;
}

int lz_walk_set(lz_walk *w, size_t i, lz_site s, int d)
{
	if (i >= w->n)
		return lz_error(LZ_EINVAL, "particle %zu does not exist: there are %zu", i, w->n);
	if (d < 0 || d >= w->ndir)
		return lz_error(LZ_EINVAL, "direction %d is not in [0, %d)", d, w->ndir);
	uint32_t m = (uint32_t)w->box->mask;
	int32_t site[3] = {(int32_t)((uint32_t)s.x & m), (int32_t)((uint32_t)s.y & m),
	                   (int32_t)((uint32_t)s.z & m)};
	if (!lz_walk_row_allowed(w, site[w->dim - 1]))
		return lz_error(LZ_EINVAL, "site row %d is outside the slit's rows %d .. %d",
		                (int)site[w->dim - 1], (int)w->lo, (int)w->hi);
	for (int c = 0; c < w->dim; c++)
		w->r[i * (size_t)w->dim + (size_t)c] = site[c];
	w->dir[i] = d;
	return LZ_OK;
}

static int overlaps_any(const lz_walk *w, const int32_t *p, size_t upto)
{
	int dim = w->dim;
	for (size_t j = 0; j < upto; j++) {
		const int32_t *q = w->r + j * (size_t)dim;
		if (lz_lattice_min_dist2(w->box, p[0] - q[0], p[1] - q[1],
		                         dim == 3 ? p[2] - q[2] : 0) < w->sigma2)
			return 1;
	}
	return 0;
}

/* The packing fraction of the region the centres may use: the box, or the slit. */
static double packing_of(const lz_walk *w)
{
	if (w->slit)
		return lz_walk_slit_packing(w->dim, w->box->side, w->slit_width, w->radius, w->n);
	return lz_walk_packing(w->box->kind, w->box->side, w->radius, w->n);
}

int lz_walk_place(lz_walk *w, gsl_rng *rng, unsigned long max_tries)
{
	if (max_tries == 0)
		max_tries = 10000;
	int dim = w->dim;
	unsigned long L = (unsigned long)w->box->side;
	unsigned long rows = (unsigned long)(w->hi - w->lo + 1);
	for (size_t i = 0; i < w->n; i++) {
		int32_t *p = w->r + i * (size_t)dim;
		unsigned long t = 0;
		do {
			if (t++ == max_tries)
				return lz_error(LZ_EPHYS, "could place only %zu of n = %zu disks of radius "
				                "%g (packing %.4f asked%s) in %lu random tries for the next "
				                "one: random placement jams near packing 0.547 in 2D "
				                "(0.38 in 3D); ask for fewer or smaller particles", i, w->n,
				                w->radius, packing_of(w), w->slit ? " in the slit" : "",
				                max_tries);
			for (int c = 0; c < dim - 1; c++)
				p[c] = (int32_t)gsl_rng_uniform_int(rng, L);
			p[dim - 1] = w->lo + (int32_t)gsl_rng_uniform_int(rng, rows);
		} while (overlaps_any(w, p, i));
		w->dir[i] = (int)gsl_rng_uniform_int(rng, (unsigned long)w->ndir);
	}
	return LZ_OK;
}

int lz_walk_place_grid(lz_walk *w, gsl_rng *rng)
{
	int dim = w->dim;
	int32_t step = (int32_t)ceil(2 * w->radius), L = w->box->side;
	/* Along a periodic axis m·step <= L keeps the wrap-around gap >= step too. */
	size_t across = (size_t)(L / step);
	size_t rows = w->slit ? (size_t)((w->hi - w->lo) / step) + 1 : across;
	size_t cap = rows * across * (dim == 3 ? across : 1);
	if (w->n > cap)
		return lz_error(LZ_EPHYS, "a grid of spacing %d holds %zu disks of radius %g here, "
		                "fewer than n = %zu", (int)step, cap, w->radius, w->n);
	size_t *all = malloc(cap * sizeof *all), *pick = malloc(w->n * sizeof *pick);
	if (!all || !pick) {
		free(all);
		free(pick);
		return lz_error(LZ_ENOMEM, "no memory for a grid of %zu points", cap);
	}
	for (size_t k = 0; k < cap; k++)
		all[k] = k;
	gsl_ran_choose(rng, pick, w->n, all, cap, sizeof *all);  /* sorted: shuffle below */
	gsl_ran_shuffle(rng, pick, w->n, sizeof *pick);
	for (size_t i = 0; i < w->n; i++) {
		int32_t *p = w->r + i * (size_t)dim;
		size_t k = pick[i];
		p[dim - 1] = w->lo + (int32_t)(k % rows) * step;
		k /= rows;
		for (int c = 0; c < dim - 1; c++, k /= across)
			p[c] = (int32_t)(k % across) * step;
		w->dir[i] = (int)gsl_rng_uniform_int(rng, (unsigned long)w->ndir);
	}
	free(all);
	free(pick);
	return LZ_OK;
}

size_t lz_walk_overlaps(const lz_walk *w)
{
	size_t count = 0;
	for (size_t i = 1; i < w->n; i++) {
		const int32_t *p = w->r + i * (size_t)w->dim;
		for (size_t j = 0; j < i; j++) {
			const int32_t *q = w->r + j * (size_t)w->dim;
			if (lz_lattice_min_dist2(w->box, p[0] - q[0], p[1] - q[1],
			                         w->dim == 3 ? p[2] - q[2] : 0) < w->sigma2)
				count++;
		}
	}
	return count;
}
