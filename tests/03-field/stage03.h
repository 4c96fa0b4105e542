/* stage03.h — brute-force references shared by the stage-03 suites (static inline: a
 * suite uses what it needs). They use their own arithmetic, never the graded code. */
#ifndef STAGE03_H
#define STAGE03_H

#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/field.h"
#include "lz/lattice.h"
#include "lz/shape.h"

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

/* The minimum-image squared distance by trying every image shift in -2..2. */
static inline int64_t bf_min_d2(lz_lattice_kind kind, int64_t L, const int32_t *p,
                                const int32_t *q)
{
	int three = kind >= LZ_LATTICE_CUBIC;
	int64_t best = INT64_MAX;
	for (int a = -2; a <= 2; a++)
		for (int b = -2; b <= 2; b++)
			for (int c = three ? -2 : 0; c <= (three ? 2 : 0); c++) {
				int64_t d2 = bf_d2(kind, p[0] - q[0] + a * L, p[1] - q[1] + b * L,
				                   three ? p[2] - q[2] + c * L : 0);
				if (d2 < best)
					best = d2;
			}
	return best;
}

/* (2R)² as a real number: a pair at integer d2 overlaps iff d2 < sigma². */
static inline double bf_sigma2(double R) { return 4.0 * R * R; }

static inline gsl_rng *rng_new(unsigned long seed)
{
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, seed);
	return r;
}

static inline lz_site rand_site(gsl_rng *rng, int dim, int64_t L)
{
	lz_site c = {0, 0, 0};
	c.x = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
	c.y = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
	if (dim == 3)
		c.z = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
	return c;
}

static inline void place(lz_field *f, lz_site c)
{
	ck_assert_msg(lz_field_place(f, c) == LZ_OK, "lz_field_place(%d, %d, %d): %s", c.x, c.y,
	              c.z, lz_error_message());
}

static inline lz_field *field_new(lz_lattice_kind kind, int64_t L, double R)
{
	lz_field *f = lz_field_alloc(kind, L, R);
	ck_assert_msg(f != NULL, "lz_field_alloc(%s, L = %lld, R = %g): %s",
	              lz_lattice_name(kind), (long long)L, R, lz_error_message());
	return f;
}

/* Site number s of a box of side L as coordinates (x fastest). */
static inline void bf_site(int dim, int64_t L, size_t s, int32_t *p)
{
	p[0] = (int32_t)(s % (size_t)L);
	p[1] = (int32_t)(s / (size_t)L % (size_t)L);
	p[2] = dim == 3 ? (int32_t)(s / (size_t)(L * L)) : 0;
}

/* Fail unless every cell equals the number of centres within σ of it (brute force
 * over all periodic images) and nfree is the number of zero cells. */
static inline void check_field_brute(const lz_field *f, const char *what)
{
	int dim = f->dim;
	int64_t L = f->side;
	size_t zeros = 0;
	double s2 = bf_sigma2(f->radius);
	for (size_t s = 0; s < f->nsites; s++) {
		int32_t p[3];
		bf_site(dim, L, s, p);
		unsigned want = 0;
		for (size_t j = 0; j < f->n; j++) {
			int32_t q[3] = {f->r[j * dim], f->r[j * dim + 1], dim == 3 ? f->r[j * dim + 2] : 0};
			want += (double)bf_min_d2(f->kind, L, p, q) < s2;
		}
		unsigned got = f->cell[lz_field_index(f, p[0], p[1], p[2])];
		ck_assert_msg(got == want, "%s: site (%d, %d, %d) of the %s field holds %u, but %u "
		              "centres of radius R = %g lie closer than 2R to it (a site must count "
		              "every particle whose excluded disk covers it)", what, p[0], p[1], p[2],
		              lz_lattice_name(f->kind), got, want, f->radius);
		zeros += want == 0;
	}
	ck_assert_msg(f->nfree == zeros, "%s: nfree = %zu but %zu sites are free (cell == 0): "
	              "the free-site count must change whenever a cell leaves or reaches 0",
	              what, f->nfree, zeros);
}

/* Add non-overlapping particles at random until there are n (or 200 n tries have
 * been made), each checked by brute force against those already there: no graded
 * test decides where they go. */
static inline void brute_config(lz_field *f, gsl_rng *rng, size_t n)
{
	int dim = f->dim;
	double s2 = bf_sigma2(f->radius);
	for (size_t t = 0; t < 200 * n && f->n < n; t++) {
		lz_site c = rand_site(rng, dim, f->side);
		int32_t p[3] = {c.x, c.y, c.z};
		int ok = 1;
		for (size_t j = 0; j < f->n && ok; j++) {
			int32_t q[3] = {f->r[j * dim], f->r[j * dim + 1], dim == 3 ? f->r[j * dim + 2] : 0};
			ok = (double)bf_min_d2(f->kind, f->side, p, q) >= s2;
		}
		if (ok)
			place(f, c);
	}
}

#endif
