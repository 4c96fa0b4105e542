/* stage03.h — brute-force references and hand-made fixtures shared by the stage-03
 * suites (static inline: a suite uses what it needs). They use their own arithmetic,
 * never the graded code.
 *
 * The fixtures build a shape, a field or a well the way the library would, but with
 * every table filled by a brute-force scan instead of the graded functions. A test
 * that starts from them calls only the function it grades, so its points follow that
 * function: a wrong lz_shape_fill_moves costs the shape tests, not every field test
 * (the library's own allocators, which run the graded code, are tested in
 * tests/lib/). Every fixture is freed by the library's lz_*_free. */
#ifndef STAGE03_H
#define STAGE03_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/field.h"
#include "lz/lattice.h"
#include "lz/shape.h"
#include "lz/well.h"

/* The squared length of an integer displacement, from the Cartesian picture: on the
 * triangular lattice (x, y) is the point (x + y/2, y √3/2), whose 4 × length² is
 * (2x + y)² + 3y², an integer. */
static inline int64_t bf_d2(lz_lattice_kind kind, int64_t x, int64_t y, int64_t z)
{
	if (kind == LZ_LATTICE_TRIANGULAR)
		return ((2 * x + y) * (2 * x + y) + 3 * y * y) / 4;
	if (kind >= LZ_LATTICE_CUBIC)
		return x * x + y * y + z * z;
	return x * x + y * y;
}

/* d mod L, taken into (-L/2, L/2]. */
static inline int64_t bf_reduce(int64_t d, int64_t L)
{
	d %= L;
	if (d < 0)
		d += L;
	return d > L / 2 ? d - L : d;
}

/* The minimum-image squared distance of p and q (any integer coordinates). Each
 * component is first taken into (-L/2, L/2]: on the square and cubic lattices every
 * term of d2 is then as small as it gets, so that image is the nearest. On the
 * sheared triangular lattice the images one period further are tried too; two or
 * more periods away cannot win, since there |dx| >= 3L/2 and d2 >= 3dx²/4 >= 27L²/16,
 * above the 3L²/4 that the reduced image never exceeds. */
static inline int64_t bf_min_d2(lz_lattice_kind kind, int64_t L, const int32_t *p,
                                const int32_t *q)
{
	int three = kind >= LZ_LATTICE_CUBIC;
	int64_t dx = bf_reduce((int64_t)p[0] - q[0], L), dy = bf_reduce((int64_t)p[1] - q[1], L);
	int64_t dz = three ? bf_reduce((int64_t)p[2] - q[2], L) : 0;
	if (kind != LZ_LATTICE_TRIANGULAR)
		return bf_d2(kind, dx, dy, dz);
	int64_t best = INT64_MAX;
	for (int a = -1; a <= 1; a++)
		for (int b = -1; b <= 1; b++) {
			int64_t d2 = bf_d2(kind, dx + a * L, dy + b * L, 0);
			best = d2 < best ? d2 : best;
		}
	return best;
}

/* (2R)² as a real number: a pair at integer d2 overlaps iff d2 < sigma². */
static inline double bf_sigma2(double R) { return 4.0 * R * R; }


static inline lz_site rand_site(gsl_rng *rng, int dim, int64_t L)
{
	lz_site c = {0, 0, 0};
	c.x = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
	c.y = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
	if (dim == 3)
		c.z = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
	return c;
}

/* ---- shapes --------------------------------------------------------------- */

/* 1 if offset (x, y, z) is in the shape: d2 < r2, the strict rule of lz/shape.h. */
static inline int bf_in(const lz_shape *s, int64_t x, int64_t y, int64_t z)
{
	return bf_d2(s->kind, x, y, s->dim == 3 ? z : 0) < s->r2;
}

/* A shape of radius r as lz_shape_alloc hands it to lz_shape_fill_points: the
 * geometry set (kind, dim, r2 = ceil(r²), reach, cap, the direction table) and room
 * for the points and for every step table (cap points each: more than any table
 * needs), nothing filled. */
static inline lz_shape *bf_shape_blank(lz_lattice_kind kind, double r)
{
	lz_shape *s = calloc(1, sizeof *s);
	LZ_REQUIRE(s != NULL, "no memory for a shape");
	s->kind = kind;
	s->dim = lz_lattice_dim(kind);
	s->radius = r;
	s->r2 = (int64_t)ceil(r * r);
	s->reach = (int32_t)lz_lattice_reach(kind, r);
	size_t side = 2 * (size_t)s->reach + 1;
	s->cap = side * side * (s->dim == 3 ? side : 1);
	s->dirs = lz_lattice_dirs(kind, &s->ndir);
	s->pts = malloc(s->cap * sizeof *s->pts);
	s->nmove = calloc((size_t)s->ndir, sizeof *s->nmove);
	s->capmove = calloc((size_t)s->ndir, sizeof *s->capmove);
	s->head = calloc((size_t)s->ndir, sizeof *s->head);
	s->tail = calloc((size_t)s->ndir, sizeof *s->tail);
	s->self = calloc((size_t)s->ndir, sizeof *s->self);
	LZ_REQUIRE(s->pts && s->nmove && s->capmove && s->head && s->tail && s->self,
	           "no memory for a shape of %zu points", s->cap);
	for (int d = 0; d < s->ndir; d++) {
		s->capmove[d] = s->cap;
		s->head[d] = malloc(s->cap * sizeof **s->head);
		s->tail[d] = malloc(s->cap * sizeof **s->tail);
		LZ_REQUIRE(s->head[d] && s->tail[d], "no memory for the step tables");
	}
	return s;
}

/* Fill pts by scanning the bounding box (in a scrambled order when rng is given: the
 * points may come in any order). */
static inline void bf_shape_points(lz_shape *s, gsl_rng *rng)
{
	int32_t R = s->reach, zr = s->dim == 3 ? R : 0;
	s->n = 0;
	for (int32_t z = -zr; z <= zr; z++)
		for (int32_t y = -R; y <= R; y++)
			for (int32_t x = -R; x <= R; x++)
				if (bf_in(s, x, y, z))
					s->pts[s->n++] = (lz_site){x, y, z};
	for (size_t k = s->n; rng && k > 1; k--) {
		size_t j = (size_t)gsl_rng_uniform_int(rng, (unsigned long)k);
		lz_site t = s->pts[k - 1];
		s->pts[k - 1] = s->pts[j];
		s->pts[j] = t;
	}
}

/* Fill the step tables from their definitions: head = (S + e) \ S, tail = S \ (S + e),
 * self = [e in S]. */
static inline void bf_shape_moves(lz_shape *s)
{
	for (int d = 0; d < s->ndir; d++) {
		lz_site e = s->dirs[d];
		size_t nh = 0, nt = 0;
		for (size_t k = 0; k < s->n; k++) {
			lz_site p = s->pts[k];
			if (!bf_in(s, p.x + e.x, p.y + e.y, p.z + e.z))
				s->head[d][nh++] = (lz_site){p.x + e.x, p.y + e.y, p.z + e.z};
			if (!bf_in(s, p.x - e.x, p.y - e.y, p.z - e.z))
				s->tail[d][nt++] = p;
		}
		LZ_REQUIRE(nh == nt, "fixture: %zu heads but %zu tails", nh, nt);
		s->nmove[d] = nh;
		s->self[d] = bf_in(s, e.x, e.y, e.z);
	}
}

/* A complete shape, built without the graded code. */
static inline lz_shape *bf_shape_new(lz_lattice_kind kind, double r)
{
	lz_shape *s = bf_shape_blank(kind, r);
	bf_shape_points(s, NULL);
	bf_shape_moves(s);
	return s;
}

/* ---- fields --------------------------------------------------------------- */

/* An empty field as lz_field_alloc_in builds it — box of side L in a lattice of side
 * pitch, the sites outside the box at 255 — with its excluded shape (radius 2R) from
 * bf_shape_new. */
static inline lz_field *bf_field_new_in(lz_lattice_kind kind, int64_t L, double R,
                                        int64_t pitch)
{
	lz_field *f = calloc(1, sizeof *f);
	LZ_REQUIRE(f != NULL, "no memory for a field");
	f->kind = kind;
	f->dim = lz_lattice_dim(kind);
	f->side = (int32_t)L;
	f->mask = (int32_t)(L - 1);
	while (((int64_t)1 << f->shift) < pitch)
		f->shift++;
	size_t P = (size_t)pitch, box = (size_t)L * (size_t)L * (f->dim == 3 ? (size_t)L : 1);
	f->nsites = P * P * (f->dim == 3 ? P : 1);
	f->nfree = box;
	f->radius = R;
	f->cell = calloc(f->nsites, 1);
	LZ_REQUIRE(f->cell != NULL, "no memory for a field of %zu sites", f->nsites);
	for (size_t s = 0; s < f->nsites; s++) {
		size_t x = s & (P - 1), y = (s >> f->shift) & (P - 1), z = s >> (2 * f->shift);
		if (x >= (size_t)L || y >= (size_t)L || z >= (size_t)L)
			f->cell[s] = UINT8_MAX;
	}
	f->excl = bf_shape_new(kind, 2 * R);
	return f;
}

static inline lz_field *bf_field_new(lz_lattice_kind kind, int64_t L, double R)
{
	return bf_field_new_in(kind, L, R, L);
}

static inline void bf_centre(const lz_field *f, size_t j, int32_t *q)
{
	const int32_t *r = f->r + j * (size_t)f->dim;
	q[0] = r[0];
	q[1] = r[1];
	q[2] = f->dim == 3 ? r[2] : 0;
}

/* Add a particle at c (wrapped) and paint its excluded shape, keeping nfree: what
 * lz_field_place does, done here without it. */
static inline void bf_put(lz_field *f, lz_site c)
{
	LZ_REQUIRE(lz_field_reserve(f, f->n + 1) == LZ_OK, "%s", lz_error_message());
	int32_t p[3] = {c.x & f->mask, c.y & f->mask, f->dim == 3 ? c.z & f->mask : 0};
	for (int k = 0; k < f->dim; k++)
		f->r[f->n * (size_t)f->dim + (size_t)k] = p[k];
	f->n++;
	const lz_shape *s = f->excl;
	for (size_t k = 0; k < s->n; k++) {
		uint8_t *v = f->cell + lz_field_index(f, p[0] + s->pts[k].x, p[1] + s->pts[k].y,
		                                      p[2] + s->pts[k].z);
		LZ_REQUIRE(*v < UINT8_MAX, "fixture: a pile of 255 particles");
		f->nfree -= *v == 0;
		(*v)++;
	}
}

/* Take the last particle away again (bf_put undone). */
static inline void bf_unput_last(lz_field *f)
{
	int32_t p[3];
	bf_centre(f, f->n - 1, p);
	const lz_shape *s = f->excl;
	for (size_t k = 0; k < s->n; k++) {
		uint8_t *v = f->cell + lz_field_index(f, p[0] + s->pts[k].x, p[1] + s->pts[k].y,
		                                      p[2] + s->pts[k].z);
		(*v)--;
		f->nfree += *v == 0;
	}
	f->n--;
}

/* Site number s of a box of side L as coordinates (x fastest). */
static inline void bf_site(int dim, int64_t L, size_t s, int32_t *p)
{
	p[0] = (int32_t)(s % (size_t)L);
	p[1] = (int32_t)(s / (size_t)L % (size_t)L);
	p[2] = dim == 3 ? (int32_t)(s / (size_t)(L * L)) : 0;
}

static inline size_t bf_box_sites(const lz_field *f)
{
	size_t L = (size_t)f->side;
	return L * L * (f->dim == 3 ? L : 1);
}

/* Fail unless every centre lies in the box, [0, L) in every coordinate. */
static inline void check_centres_in_box(const lz_field *f, const char *what)
{
	for (size_t j = 0; j < f->n; j++) {
		int32_t q[3];
		bf_centre(f, j, q);
		for (int a = 0; a < f->dim; a++)
			LZ_REQUIRE(q[a] >= 0 && q[a] < f->side, "%s: coordinate %d of particle %zu is "
			           "%d, outside the box [0, %d): a centre must be stored wrapped (& mask)",
			           what, a, j, q[a], (int)f->side);
	}
}

/* Fail unless every cell equals the number of centres within σ of it (brute force
 * over the periodic images), nfree is the number of zero cells, and every centre is
 * in the box. O(L^dim · n): for small fields. */
static inline void check_field_brute(const lz_field *f, const char *what)
{
	int dim = f->dim;
	int64_t L = f->side;
	size_t zeros = 0, box = bf_box_sites(f);
	double s2 = bf_sigma2(f->radius);
	check_centres_in_box(f, what);
	for (size_t s = 0; s < box; s++) {
		int32_t p[3], q[3];
		bf_site(dim, L, s, p);
		unsigned want = 0;
		for (size_t j = 0; j < f->n; j++) {
			bf_centre(f, j, q);
			want += (double)bf_min_d2(f->kind, L, p, q) < s2;
		}
		unsigned got = f->cell[lz_field_index(f, p[0], p[1], p[2])];
		LZ_REQUIRE(got == want, "%s: site (%d, %d, %d) of the %s field holds %u, but %u "
		           "centres of radius R = %g lie closer than 2R to it (a site must count "
		           "every particle whose excluded disk covers it)", what, p[0], p[1], p[2],
		           lz_lattice_name(f->kind), got, want, f->radius);
		zeros += want == 0;
	}
	LZ_REQUIRE(f->nfree == zeros, "%s: nfree = %zu but %zu sites are free (cell == 0): "
	           "the free-site count must change whenever a cell leaves or reaches 0",
	           what, f->nfree, zeros);
}

/* The cells the centres of f should give, painted with the test's own shape into
 * want[] (nsites bytes, 255 outside the box); returns the number of free box sites.
 * O(n |S| + L^dim): the check for large fields. */
static inline size_t bf_paint_all(const lz_field *f, uint8_t *want)
{
	memset(want, UINT8_MAX, f->nsites);
	size_t box = bf_box_sites(f), zeros = 0;
	for (size_t s = 0; s < box; s++) {
		int32_t p[3];
		bf_site(f->dim, f->side, s, p);
		want[lz_field_index(f, p[0], p[1], p[2])] = 0;
	}
	const lz_shape *sh = f->excl;
	for (size_t j = 0; j < f->n; j++) {
		int32_t q[3];
		bf_centre(f, j, q);
		for (size_t k = 0; k < sh->n; k++) {
			uint8_t *v = want + lz_field_index(f, q[0] + sh->pts[k].x, q[1] + sh->pts[k].y,
			                                   q[2] + sh->pts[k].z);
			*v += *v < UINT8_MAX;
		}
	}
	for (size_t s = 0; s < box; s++) {
		int32_t p[3];
		bf_site(f->dim, f->side, s, p);
		zeros += want[lz_field_index(f, p[0], p[1], p[2])] == 0;
	}
	return zeros;
}

/* Fail unless the field is the sum of its particles' shapes (bf_paint_all), nfree
 * counts its zero cells and every centre is in the box. */
static inline void check_field_exact(const lz_field *f, const char *what)
{
	check_centres_in_box(f, what);
	uint8_t *want = malloc(f->nsites);
	LZ_REQUIRE(want != NULL, "no memory");
	size_t zeros = bf_paint_all(f, want);
	for (size_t s = 0; s < f->nsites; s++)
		LZ_REQUIRE(f->cell[s] == want[s], "%s: cell %zu of the %s field holds %u, but the "
		           "particles' excluded shapes cover it %u times (every cell must count "
		           "the particles whose shape covers it)", what, s,
		           lz_lattice_name(f->kind), f->cell[s], want[s]);
	free(want);
	LZ_REQUIRE(f->nfree == zeros, "%s: nfree = %zu but %zu sites are free (cell == 0): "
	           "the free-site count must change whenever a cell leaves or reaches 0",
	           what, f->nfree, zeros);
}

/* 1 if a centre at p would lie closer than σ to a particle of f other than `skip`. */
static inline int bf_clashes(const lz_field *f, const int32_t *p, size_t skip)
{
	double s2 = bf_sigma2(f->radius);
	for (size_t j = 0; j < f->n; j++) {
		int32_t q[3];
		bf_centre(f, j, q);
		if (j != skip && (double)bf_min_d2(f->kind, f->side, p, q) < s2)
			return 1;
	}
	return 0;
}

static inline int rng_same(const gsl_rng *a, const gsl_rng *b)
{
	return memcmp(gsl_rng_state(a), gsl_rng_state(b), gsl_rng_size(a)) == 0;
}

/* Add non-overlapping particles at random until there are n (or 200 n tries have
 * been made), each checked by brute force against those already there: no graded
 * code decides where they go or paints them. */
static inline void brute_config(lz_field *f, gsl_rng *rng, size_t n)
{
	double s2 = bf_sigma2(f->radius);
	for (size_t t = 0; t < 200 * n && f->n < n; t++) {
		lz_site c = rand_site(rng, f->dim, f->side);
		int32_t p[3] = {c.x, c.y, c.z}, q[3];
		int ok = 1;
		for (size_t j = 0; j < f->n && ok; j++) {
			bf_centre(f, j, q);
			ok = (double)bf_min_d2(f->kind, f->side, p, q) >= s2;
		}
		if (ok)
			bf_put(f, c);
	}
}

/* ---- wells ---------------------------------------------------------------- */

/* A well of range rw = lambda · 2R on f as lz_well_alloc builds it — its shape from
 * bf_shape_new, painted for the particles of f, the Metropolis table from its
 * definition min(1, exp(depth k / kT)) — without the graded code. */
static inline lz_well *bf_well_new(const lz_field *f, double lambda, double depth, double T)
{
	lz_well *w = calloc(1, sizeof *w);
	LZ_REQUIRE(w != NULL, "no memory for a well");
	w->range = lambda * 2 * f->radius;
	w->depth = depth;
	w->temperature = T;
	w->cell = calloc(f->nsites, 1);
	LZ_REQUIRE(w->cell != NULL, "no memory for a well field");
	w->shape = bf_shape_new(f->kind, w->range);
	const lz_shape *s = w->shape;
	for (size_t j = 0; j < f->n; j++) {
		int32_t q[3];
		bf_centre(f, j, q);
		for (size_t k = 0; k < s->n; k++)
			w->cell[lz_field_index(f, q[0] + s->pts[k].x, q[1] + s->pts[k].y,
			                       q[2] + s->pts[k].z)]++;
	}
	for (int k = -LZ_WELL_KMAX; k <= LZ_WELL_KMAX; k++)
		w->accept[k + LZ_WELL_KMAX] = k >= 0 ? 1.0 : exp(depth * k / T);
	return w;
}

#endif
