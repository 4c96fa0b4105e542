/* test_stage04_cells.c — the library half of lz/cells.h, which students do not write:
 * the input checks of lz_cells_alloc and lz_cells_alloc_lattice (with the allowed
 * range in the message), the size of the grid, the round trip between storage index
 * and cell coordinates in both orders, the padding of the block tables with the empty
 * cell, the memory count, the cell-ordered permutation (a stable counting sort) and
 * the refusals of binning. The grids are real ones, so the graded code runs inside
 * lz_cells_alloc (the reference, as this suite always does in `make check`). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/cells.h"
#include "lztest.h"
#include "support.h"


static lz_cells *grid(int dim, double L, double rc, int periodic, lz_cells_order order,
                      size_t nmax, size_t cap)
{
	lz_cells *c = lz_cells_alloc(dim, L, rc, periodic, order, nmax, cap);
	ck_assert_msg(c != NULL, "lz_cells_alloc(%d, L = %g, rc = %g, periodic = %d): %s", dim, L,
	              rc, periodic, lz_error_message());
	return c;
}

/* The Morton code bit by bit (the test's own, not the graded one). */
static uint64_t bf_morton(int dim, uint32_t x, uint32_t y, uint32_t z)
{
	uint64_t code = 0;
	for (int b = 0; b < 21; b++) {
		code |= (uint64_t)(x >> b & 1) << (dim * b);
		code |= (uint64_t)(y >> b & 1) << (dim * b + 1);
		if (dim == 3)
			code |= (uint64_t)(z >> b & 1) << (3 * b + 2);
	}
	return code;
}

LZ_TEST(cells_alloc_rejects_bad_input)
{
	lz_test_clear_error();
	lz_test_refused(lz_cells_alloc(1, 10, 1, 1, LZ_CELLS_ROW, 10, 0) == NULL, "dim 1",
	                "dim = 1", "2 or 3");
	lz_test_refused(lz_cells_alloc(4, 10, 1, 1, LZ_CELLS_ROW, 10, 0) == NULL, "dim 4",
	                "dim = 4", "2 or 3");
	lz_test_refused(lz_cells_alloc(2, 0, 1, 1, LZ_CELLS_ROW, 10, 0) == NULL, "L = 0",
	                "L = 0", "positive");
	lz_test_refused(lz_cells_alloc(2, -3, 1, 0, LZ_CELLS_ROW, 10, 0) == NULL, "L < 0",
	                "L = -3", "positive");
	lz_test_refused(lz_cells_alloc(2, NAN, 1, 0, LZ_CELLS_ROW, 10, 0) == NULL, "L = nan",
	                "L = nan", "finite");
	lz_test_refused(lz_cells_alloc(2, INFINITY, 1, 0, LZ_CELLS_ROW, 10, 0) == NULL,
	                "L = inf", "L = inf", NULL);
	lz_test_refused(lz_cells_alloc(2, 10, 0, 1, LZ_CELLS_ROW, 10, 0) == NULL, "rc = 0",
	                "rc = 0", "positive");
	lz_test_refused(lz_cells_alloc(3, 10, -1, 1, LZ_CELLS_ROW, 10, 0) == NULL, "rc < 0",
	                "rc = -1", NULL);
	lz_test_refused(lz_cells_alloc(3, 10, NAN, 1, LZ_CELLS_ROW, 10, 0) == NULL, "rc = nan",
	                "rc = nan", NULL);
	lz_test_refused(lz_cells_alloc(3, 10, INFINITY, 0, LZ_CELLS_ROW, 10, 0) == NULL,
	                "rc = inf", "rc = inf", NULL);
	lz_test_refused(lz_cells_alloc(2, 10, 4, 1, LZ_CELLS_ROW, 10, 0) == NULL,
	                "periodic rc > L/3", "rc = 4", "rc <= L/3 = 3.33333");
	/* 0.3 / 3 < 0.1 in floating point: the message shows L/3 to the last digit. */
	lz_test_refused(lz_cells_alloc(2, 0.3, 0.1, 1, LZ_CELLS_ROW, 10, 0) == NULL,
	                "L = 0.3, rc = 0.1", "L/3 = 0.09999999999999", NULL);
	lz_test_refused(lz_cells_alloc(2, 10, 1, 1, LZ_CELLS_ROW, 0, 0) == NULL, "nmax = 0",
	                "nmax = 0", "2147483647");
	lz_test_refused(lz_cells_alloc(2, 10, 1, 1, LZ_CELLS_ROW, (size_t)1 << 31, 0) == NULL,
	                "nmax = 2^31", "nmax = 2147483648", "<= 2147483647");
	lz_test_refused(lz_cells_alloc(2, 10, 1, 1, LZ_CELLS_ROW, 10, (size_t)1 << 31) == NULL,
	                "cap = 2^31", "cap = 2147483648", "<= 2147483647");
	lz_test_refused(lz_cells_alloc(2, 10, 1, 1, (lz_cells_order)7, 10, 0) == NULL,
	                "order 7", "order 7", "LZ_CELLS_MORTON");
	lz_cells_free(NULL);
}
END_TEST

LZ_TEST(cells_alloc_lattice_rejects_bad_input)
{
	lz_test_clear_error();
	lz_test_refused(lz_cells_alloc_lattice(LZ_NLATTICES, 64, 2, LZ_CELLS_ROW, 10, 0) == NULL,
	                "kind", "kind 6", NULL);
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_SQUARE, 48, 2, LZ_CELLS_ROW, 10, 0) == NULL,
	                "side 48", "48", NULL);
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_SQUARE, 2, 0.5, LZ_CELLS_ROW, 10, 0) == NULL,
	                "side 2", "L = 2", "L >= 4");
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_SQUARE, 64, 0, LZ_CELLS_ROW, 10, 0) == NULL,
	                "rc 0", "rc = 0", "positive");
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_CUBIC, 64, NAN, LZ_CELLS_ROW, 10, 0) == NULL,
	                "rc nan", "rc = nan", NULL);
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_SQUARE, 64, 17, LZ_CELLS_ROW, 10, 0) == NULL,
	                "square rc = 17 in L = 64", "rc = 17", "rc <= 16");
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_CUBIC, 64, 1e300, LZ_CELLS_ROW, 10, 0) == NULL,
	                "cubic rc = 1e300", "rc = 1e+300", "rc <= 16");
	/* triangular: the reach is ceil(2 rc / sqrt 3) <= 16, so rc <= 8 sqrt 3 = 13.8564 */
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_TRIANGULAR, 64, 14, LZ_CELLS_ROW, 10, 0) == NULL,
	                "triangular rc = 14 in L = 64", "rc = 14", "rc <= 13.856");
	lz_test_refused(lz_cells_alloc_lattice(LZ_LATTICE_SQUARE, 64, 2, LZ_CELLS_ROW, 0, 0) == NULL,
	                "nmax 0", "nmax = 0", NULL);
	/* the largest allowed cutoffs work: cells of L/4 */
	lz_cells *c = lz_cells_alloc_lattice(LZ_LATTICE_SQUARE, 64, 16, LZ_CELLS_ROW, 10, 0);
	ck_assert_msg(c && c->m == 4 && c->shift == 4, "square L = 64, rc = 16: %s",
	              c ? "expected 4 cells of 16" : lz_error_message());
	lz_cells_free(c);
	c = lz_cells_alloc_lattice(LZ_LATTICE_TRIANGULAR, 64, 13.856, LZ_CELLS_MORTON, 10, 0);
	ck_assert_msg(c && c->m == 4, "triangular L = 64, rc = 13.856: %s",
	              c ? "expected 4 cells of 16" : lz_error_message());
	lz_cells_free(c);
}
END_TEST

/* A cutoff far below the box allows more cells than LZ_CELLS_MAX: the grid stops at
 * the largest side that keeps m^dim within it (2048 in 2D, 161 in 3D), with cells
 * wider than the cutoff. */
LZ_TEST(cells_alloc_caps_the_grid_at_the_most_cells)
{
	for (int dim = 2; dim <= 3; dim++) {
		lz_cells *c = grid(dim, 1e4, 1e-3, 1, LZ_CELLS_ROW, 1, 0);
		int32_t want = dim == 2 ? 2048 : 161;
		ck_assert_msg(c->m == want && c->ncells <= LZ_CELLS_MAX &&
		              (size_t)(c->m + 1) * (c->m + 1) * (dim == 3 ? (size_t)(c->m + 1) : 1) >
		                      LZ_CELLS_MAX && c->width >= 1e-3,
		              "%dD, L = 1e4, rc = 1e-3: m = %d, %zu cells (the most is %zu, side %d)",
		              dim, c->m, c->ncells, LZ_CELLS_MAX, want);
		lz_cells_free(c);
	}
}
END_TEST

LZ_TEST(cells_alloc_sizes_the_grid)
{
	lz_cells *c = grid(2, 10, 1, 1, LZ_CELLS_ROW, 100, 0);
	ck_assert(c->m == 10 && c->ncells == 100 && c->width == 1 && c->inv_width == 1);
	ck_assert(c->shift == -1 && c->nfull == 9 && c->nhalf == 5 && c->periodic == 1);
	ck_assert(!c->rank && !c->unrank && !c->count && !c->slot && c->cap == 0 && c->n == 0);
	for (size_t q = 0; q <= c->ncells; q++)
		ck_assert_msg(c->head[q] == -1, "head[%zu] = %d after allocation", q, c->head[q]);
	lz_cells_free(c);
	c = grid(3, 10, 3.4, 0, LZ_CELLS_MORTON, 10, 3);
	ck_assert(c->m == 2 && c->ncells == 8 && c->nfull == 27 && c->nhalf == 14 && c->periodic == 0);
	for (size_t q = 0; q <= c->ncells; q++)
		ck_assert(c->count[q] == 0);
	lz_cells_free(c);
	c = grid(2, 0.3, 0.1, 0, LZ_CELLS_ROW, 10, 0);  /* 0.3 / 3 < 0.1: two cells */
	ck_assert_msg(c->m == 2 && c->width >= 0.1, "L = 0.3, rc = 0.1: m = %d, w = %.17g", c->m,
	              c->width);
	lz_cells_free(c);
	c = grid(3, 1, 5, 0, LZ_CELLS_ROW, 10, 0);  /* rc > L with walls: one cell */
	ck_assert(c->m == 1 && c->ncells == 1);
	lz_cells_free(c);
	/* m = floor(L / rc) and L / m >= rc, over random sizes */
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 4001);
	for (int t = 0; t < 200; t++) {
		double L = 1 + 30 * gsl_rng_uniform(rng), rc = L / (3 + 40 * gsl_rng_uniform(rng));
		c = grid(2, L, rc, 1, LZ_CELLS_ROW, 1, 0);
		ck_assert_msg(c->width >= rc && L / (c->m + 1) < rc && c->width == L / c->m,
		              "L = %.17g, rc = %.17g: m = %d, w = %.17g", L, rc, c->m, c->width);
		lz_cells_free(c);
	}
	gsl_rng_free(rng);
	/* lattice grids: w = the power of two >= the reach */
	static const struct {
		lz_lattice_kind kind;
		int64_t L;
		double rc;
		int shift;
	} lat[] = {{LZ_LATTICE_SQUARE, 64, 3, 2}, {LZ_LATTICE_SQUARE, 64, 0.5, 0},
	           {LZ_LATTICE_SQUARE, 64, 4, 2}, {LZ_LATTICE_TRIANGULAR, 64, 3, 2},
	           {LZ_LATTICE_TRIANGULAR, 64, 3.5, 3}, {LZ_LATTICE_SQUARE8, 128, 4.5, 3},
	           {LZ_LATTICE_CUBIC, 32, 2, 1}, {LZ_LATTICE_CUBIC26, 32, 7.9, 3}};
	for (size_t k = 0; k < sizeof lat / sizeof lat[0]; k++) {
		c = lz_cells_alloc_lattice(lat[k].kind, lat[k].L, lat[k].rc, LZ_CELLS_MORTON, 5, 0);
		ck_assert_msg(c != NULL, "%s", lz_error_message());
		ck_assert_msg(c->shift == lat[k].shift && c->m == (int32_t)(lat[k].L >> lat[k].shift) &&
		              c->width == (double)(1 << lat[k].shift) && c->side == (double)lat[k].L &&
		              c->periodic == 1 && c->cutoff == lat[k].rc,
		              "lattice kind %d, L = %lld, rc = %g: shift %d, m %d (expected shift %d)",
		              (int)lat[k].kind, (long long)lat[k].L, lat[k].rc, c->shift, c->m,
		              lat[k].shift);
		lz_cells_free(c);
	}
}
END_TEST

LZ_TEST(cells_coords_and_index_round_trip)
{
	static const struct {
		int dim;
		double L;
		lz_cells_order order;
	} g[] = {{2, 10, LZ_CELLS_ROW}, {2, 10, LZ_CELLS_MORTON}, {2, 16, LZ_CELLS_MORTON},
	         {3, 5, LZ_CELLS_MORTON}, {3, 3, LZ_CELLS_ROW}, {3, 8, LZ_CELLS_MORTON}};
	for (size_t k = 0; k < sizeof g / sizeof g[0]; k++) {
		lz_cells *c = grid(g[k].dim, g[k].L, 1, 1, g[k].order, 1, 0);
		int dim = c->dim;
		uint64_t last = 0;
		for (size_t s = 0; s < c->ncells; s++) {
			int32_t cx[3] = {0, 0, 0};
			lz_cells_coords(c, s, cx);
			for (int a = 0; a < dim; a++)
				LZ_REQUIRE_TRUE(cx[a] >= 0 && cx[a] < c->m);
			LZ_REQUIRE(lz_cells_index(c, cx) == s, "%dD m = %d %s: cell %zu -> (%d, %d, %d) "
			              "-> %zu", dim, c->m, g[k].order ? "Morton" : "row", s, cx[0], cx[1],
			              cx[2], lz_cells_index(c, cx));
			size_t q = (size_t)cx[0] + (size_t)c->m * ((size_t)cx[1] + (size_t)c->m * (size_t)cx[2]);
			if (g[k].order == LZ_CELLS_ROW) {
				LZ_REQUIRE_TRUE(q == s);
				continue;
			}
			LZ_REQUIRE_TRUE(c->unrank[s] == q && c->rank[q] == s);
			uint64_t code = bf_morton(dim, (uint32_t)cx[0], (uint32_t)cx[1], (uint32_t)cx[2]);
			LZ_REQUIRE(s == 0 || code > last, "Morton order: cell %zu has code %llu, not "
			              "above the previous %llu", s, (unsigned long long)code,
			              (unsigned long long)last);
			if ((c->m & (c->m - 1)) == 0)
				LZ_REQUIRE(code == s, "m = %d is a power of two: cell %zu has code %llu",
				              c->m, s, (unsigned long long)code);
			last = code;
		}
		lz_cells_free(c);
	}
}
END_TEST

LZ_TEST(cells_block_tables_are_padded_with_the_empty_cell)
{
	lz_cells *c = grid(2, 4, 1, 0, LZ_CELLS_MORTON, 1, 0);
	uint32_t empty = (uint32_t)c->ncells;
	for (int k = 0; k < c->nfull; k++)
		ck_assert(c->full[c->ncells * 9 + (size_t)k] == empty);
	for (int k = 0; k < c->nhalf; k++)
		ck_assert(c->half[c->ncells * 5 + (size_t)k] == empty);
	for (size_t s = 0; s < c->ncells; s++) {
		int32_t cx[2];
		lz_cells_coords(c, s, cx);
		int inside = (cx[0] > 0 && cx[0] < 3) + (cx[1] > 0 && cx[1] < 3);
		int want = inside == 2 ? 9 : inside == 1 ? 6 : 4, real = 0;
		for (int k = 0; k < 9; k++) {
			uint32_t e = c->full[s * 9 + (size_t)k];
			ck_assert(e <= empty);
			if (e < empty) {
				ck_assert_msg(k == real, "the real cells come first in a row");
				real++;
			}
		}
		ck_assert_msg(c->full[s * 9] == s && real == want, "cell (%d, %d) of a walled 4x4 grid: "
		              "%d cells in its row, expected %d", cx[0], cx[1], real, want);
	}
	lz_cells_free(c);
	c = grid(3, 3, 1, 1, LZ_CELLS_ROW, 1, 0);
	for (size_t k = 0; k < (c->ncells + 1) * 27; k++)
		ck_assert(k >= c->ncells * 27 ? c->full[k] == c->ncells : c->full[k] < c->ncells);
	for (size_t k = 0; k < c->ncells * 14; k++)
		ck_assert(c->half[k] < c->ncells);
	lz_cells_free(c);
}
END_TEST

LZ_TEST(cells_bytes_counts_every_table)
{
	lz_cells *a = grid(2, 10, 1, 1, LZ_CELLS_ROW, 100, 0);
	lz_cells *b = grid(2, 10, 1, 1, LZ_CELLS_MORTON, 100, 0);
	lz_cells *d = grid(2, 10, 1, 1, LZ_CELLS_ROW, 100, 7);
	lz_cells *e = grid(2, 10, 1, 1, LZ_CELLS_ROW, 300, 0);
	size_t base = sizeof(lz_cells) + 4 * (101 * (9 + 5) + 101 + 2 * 100);
	ck_assert_msg(lz_cells_bytes(a) == base, "bytes = %zu, expected %zu (struct, tables, head, "
	              "of and next)", lz_cells_bytes(a), base);
	ck_assert_msg(lz_cells_bytes(b) - lz_cells_bytes(a) == 4 * 2 * 100, "the Morton ranks "
	              "cost 2 words per cell: %zu", lz_cells_bytes(b) - lz_cells_bytes(a));
	ck_assert_msg(lz_cells_bytes(d) - lz_cells_bytes(a) == 4 * 101 * (1 + 7), "the arrays cost "
	              "(1 + cap) words per cell: %zu", lz_cells_bytes(d) - lz_cells_bytes(a));
	ck_assert_msg(lz_cells_bytes(e) - lz_cells_bytes(a) == 4 * 2 * 200, "of and next cost 2 "
	              "words per particle of room: %zu", lz_cells_bytes(e) - lz_cells_bytes(a));
	lz_cells_free(a);
	lz_cells_free(b);
	lz_cells_free(d);
	lz_cells_free(e);
}
END_TEST

/* Fail unless perm is a permutation of 0 .. n-1 that lists the cells in storage order
 * and the particles of a cell by increasing index. */
static void check_perm(const lz_cells *c, const uint32_t *perm)
{
	char *seen = calloc(c->n + 1, 1);
	for (size_t k = 0; k < c->n; k++) {
		LZ_REQUIRE(perm[k] < c->n && !seen[perm[k]], "perm[%zu] = %u: not a permutation",
		              k, perm[k]);
		seen[perm[k]] = 1;
		if (k > 0) {
			uint32_t p = perm[k - 1], q = perm[k];
			LZ_REQUIRE(c->of[p] < c->of[q] || (c->of[p] == c->of[q] && p < q), "perm lists "
			              "%u (cell %u) before %u (cell %u)", p, c->of[p], q, c->of[q]);
		}
	}
	free(seen);
}

LZ_TEST(cells_permutation_is_a_stable_counting_sort)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 4002);
	size_t n = 5000;
	lz_cells *c = grid(2, 10, 1, 1, LZ_CELLS_MORTON, n, 0);
	uint32_t *perm = malloc(n * sizeof *perm);
	c->n = n;
	for (size_t i = 0; i < n; i++)
		c->of[i] = (uint32_t)gsl_rng_uniform_int(rng, 7) * 13;  /* few cells, many ties */
	ck_assert(lz_cells_permutation(c, perm) == LZ_OK);
	check_perm(c, perm);
	double *x = malloc(3 * n * sizeof *x);
	for (size_t k = 0; k < 3 * n; k++)
		x[k] = 6 * gsl_rng_uniform(rng);
	lz_cells *d = grid(3, 6, 1, 1, LZ_CELLS_MORTON, n, 0);
	ck_assert(lz_cells_bin_points(d, n, x) == LZ_OK);
	ck_assert(lz_cells_permutation(d, perm) == LZ_OK);
	check_perm(d, perm);
	d->n = 0;
	ck_assert(lz_cells_permutation(d, perm) == LZ_OK);
	free(x);
	free(perm);
	lz_cells_free(c);
	lz_cells_free(d);
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(cells_bin_rejects_bad_input)
{
	lz_test_clear_error();
	lz_cells *c = grid(2, 10, 1, 1, LZ_CELLS_ROW, 10, 0);
	double x[24] = {0};
	int32_t r[24] = {0};
	ck_assert(lz_cells_bin_points(c, 11, x) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "n = 11") && strstr(lz_error_message(), "nmax = 10"),
	              "%s", lz_error_message());
	ck_assert(lz_cells_bin_sites(c, 2, r) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "lz_cells_alloc_lattice"), "%s", lz_error_message());
	ck_assert(lz_cells_bin_points(c, 3, x) == LZ_OK && c->n == 3);
	x[5] = NAN;
	ck_assert(lz_cells_bin_points(c, 4, x) == LZ_EINVAL && c->n == 0);
	ck_assert_msg(strstr(lz_error_message(), "point 2") && strstr(lz_error_message(), "nan"),
	              "%s", lz_error_message());
	x[5] = -INFINITY;
	ck_assert(lz_cells_bin_points(c, 4, x) == LZ_EINVAL);
	ck_assert(lz_cells_bin_points(c, 0, x) == LZ_OK && c->n == 0);
	lz_cells_free(c);
	c = lz_cells_alloc_lattice(LZ_LATTICE_CUBIC, 32, 2, LZ_CELLS_MORTON, 8, 0);
	ck_assert_msg(c != NULL, "%s", lz_error_message());
	r[7] = 32;
	ck_assert(lz_cells_bin_sites(c, 3, r) == LZ_EINVAL && c->n == 0);
	ck_assert_msg(strstr(lz_error_message(), "site 2") && strstr(lz_error_message(), "= 32"),
	              "%s", lz_error_message());
	r[7] = -1;
	ck_assert(lz_cells_bin_sites(c, 3, r) == LZ_EINVAL);
	r[7] = 31;
	ck_assert(lz_cells_bin_sites(c, 9, r) == LZ_EINVAL);
	ck_assert(lz_cells_bin_sites(c, 8, r) == LZ_OK && c->n == 8);
	ck_assert(c->of[2] == lz_cells_index(c, (int32_t[]){0, 15, 0}));
	/* a lattice grid bins points as well */
	for (int k = 0; k < 24; k++)
		x[k] = k + 0.5;
	ck_assert(lz_cells_bin_points(c, 8, x) == LZ_OK && c->n == 8);
	ck_assert(c->of[1] == lz_cells_index(c, (int32_t[]){1, 2, 2}));
	lz_cells_free(c);
}
END_TEST
