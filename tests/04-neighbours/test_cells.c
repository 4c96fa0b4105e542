/* test_cells.c — stage 04, cell lists (lz/cells.h): Morton numbers, the cell of a
 * lattice site and of a point, the block and the half block, the linked lists and
 * the fixed arrays, and every close pair found once.
 *
 * The references use their own arithmetic: Morton codes bit by bit, cells from
 * points built inside a known cell, blocks by brute force over all cells, pairs by
 * all O(N²) pairs or by a sort-and-sweep. The grids of the unit tests are made by
 * hand (their Morton ranks from the bit-by-bit codes), and the pair tests also bin
 * and link their points by hand, so no other graded function runs while a test is set
 * up and each test pays for one function. The last test runs the whole chain as a
 * user does (lz_cells_alloc, binning, linking, pairs) and checks every step of it. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/cells.h"
#include "lztest.h"


/* ---- references and hand-made grids ---- */


static const char *order_name(lz_cells_order o)
{
	return o == LZ_CELLS_MORTON ? "Morton" : "row-major";
}

/* The Morton code bit by bit: bit b of x to bit dim·b, of y to dim·b + 1, of z to
 * 3b + 2 (21 bits per coordinate in 3D, 32 in 2D). */
static uint64_t bf_morton(int dim, uint32_t x, uint32_t y, uint32_t z)
{
	uint64_t code = 0;
	for (int b = 0; b < (dim == 3 ? 21 : 32); b++) {
		code |= (uint64_t)(x >> b & 1) << (dim * b);
		code |= (uint64_t)(y >> b & 1) << (dim * b + 1);
		if (dim == 3)
			code |= (uint64_t)(z >> b & 1) << (3 * b + 2);
	}
	return code;
}

/* The coordinates of row-major cell q of an m^dim grid, x fastest. */
static void bf_decode(int dim, int32_t m, size_t q, int32_t *cx)
{
	cx[0] = (int32_t)(q % (size_t)m);
	cx[1] = (int32_t)(q / (size_t)m % (size_t)m);
	cx[2] = dim == 3 ? (int32_t)(q / ((size_t)m * (size_t)m)) : 0;
}

/* The coordinates of the cell with storage index s, from the grid's unrank table. */
static void bf_coords(const lz_cells *c, size_t s, int32_t *cx)
{
	bf_decode(c->dim, c->m, c->unrank ? c->unrank[s] : s, cx);
}

typedef struct {
	uint64_t code;
	uint32_t q;
} keyed;

static int keyed_cmp(const void *a, const void *b)
{
	const keyed *p = a, *q = b;
	return (p->code > q->code) - (p->code < q->code);
}

/* A grid of m^dim cells in a box of side L, as lz_cells_alloc makes it but by hand:
 * Morton ranks by sorting the bit-by-bit codes, no block tables, lists and arrays
 * with room for nmax particles and cap per cell (garbage in them: the graded code
 * must set what it uses). shift = -1 (a grid for points). */
static lz_cells *hand_grid(int dim, int32_t m, double L, int periodic, lz_cells_order order,
                           size_t nmax, size_t cap)
{
	lz_cells *c = calloc(1, sizeof *c);
	ck_assert(c != NULL);
	c->dim = dim;
	c->periodic = periodic;
	c->side = L;
	c->cutoff = L / m;
	c->m = m;
	c->width = L / m;
	c->inv_width = m / L;
	c->shift = -1;
	c->ncells = (size_t)m * (size_t)m * (dim == 3 ? (size_t)m : 1);
	c->order = order;
	c->nfull = dim == 3 ? 27 : 9;
	c->nhalf = dim == 3 ? 14 : 5;
	if (order == LZ_CELLS_MORTON) {
		keyed *k = malloc(c->ncells * sizeof *k);
		c->rank = malloc(c->ncells * sizeof *c->rank);
		c->unrank = malloc(c->ncells * sizeof *c->unrank);
		ck_assert(k && c->rank && c->unrank);
		for (size_t q = 0; q < c->ncells; q++) {
			int32_t cx[3];
			bf_decode(dim, m, q, cx);
			k[q] = (keyed){bf_morton(dim, (uint32_t)cx[0], (uint32_t)cx[1], (uint32_t)cx[2]),
			               (uint32_t)q};
		}
		qsort(k, c->ncells, sizeof *k, keyed_cmp);
		for (size_t s = 0; s < c->ncells; s++) {
			c->unrank[s] = k[s].q;
			c->rank[k[s].q] = (uint32_t)s;
		}
		free(k);
	}
	c->nmax = nmax;
	c->of = malloc(nmax * sizeof *c->of);
	c->head = malloc((c->ncells + 1) * sizeof *c->head);
	c->next = malloc(nmax * sizeof *c->next);
	ck_assert(c->of && c->head && c->next);
	for (size_t q = 0; q <= c->ncells; q++)
		c->head[q] = 12345;
	for (size_t i = 0; i < nmax; i++)
		c->next[i] = 777;
	c->cap = cap;
	if (cap > 0) {
		c->count = malloc((c->ncells + 1) * sizeof *c->count);
		c->slot = malloc((c->ncells + 1) * cap * sizeof *c->slot);
		ck_assert(c->count && c->slot);
		for (size_t q = 0; q <= c->ncells; q++)
			c->count[q] = 99;
		for (size_t k = 0; k < (c->ncells + 1) * cap; k++)
			c->slot[k] = 4242;
	}
	return c;
}

/* A lattice grid by hand: side L = 2^k sites, cells of 2^shift sites. */
static lz_cells *hand_lattice(int dim, int32_t L, int shift, lz_cells_order order)
{
	lz_cells *c = hand_grid(dim, L >> shift, L, 1, order, 1, 0);
	c->shift = shift;
	return c;
}

/* "(x, y)" or "(x, y, z)" into buf. */
static const char *fmt_cell(char *buf, size_t size, int dim, const int32_t *cx)
{
	if (dim == 3)
		snprintf(buf, size, "(%d, %d, %d)", cx[0], cx[1], cx[2]);
	else
		snprintf(buf, size, "(%d, %d)", cx[0], cx[1]);
	return buf;
}

/* ---- Morton codes ---- */

LZ_TEST(morton_small_cases_by_hand)
{
	static const struct {
		uint32_t x, y;
		uint64_t want;
	} two[] = {{0, 0, 0}, {1, 0, 1}, {0, 1, 2}, {1, 1, 3}, {2, 0, 4}, {0, 2, 8}, {3, 3, 15},
	           {5, 3, 27}};
	for (size_t k = 0; k < sizeof two / sizeof two[0]; k++) {
		uint64_t got = lz_morton(2, two[k].x, two[k].y, 0);
		LZ_REQUIRE(got == two[k].want, "lz_morton(2, %u, %u, 0) = %llu, expected %llu: bit b "
		              "of x goes to bit 2b of the code, bit b of y to bit 2b + 1", two[k].x,
		              two[k].y, (unsigned long long)got, (unsigned long long)two[k].want);
	}
	for (uint32_t k = 0; k < 8; k++) {
		uint32_t x = k & 1, y = k >> 1 & 1, z = k >> 2;
		uint64_t got = lz_morton(3, x, y, z);
		LZ_REQUIRE(got == k, "lz_morton(3, %u, %u, %u) = %llu, expected %u: the 8 corners of "
		              "a 2x2x2 block are numbered x + 2y + 4z", x, y, z,
		              (unsigned long long)got, k);
	}
	LZ_REQUIRE(lz_morton(3, 2, 0, 0) == 8 && lz_morton(3, 0, 2, 0) == 16 &&
	              lz_morton(3, 0, 0, 2) == 32, "lz_morton(3, ...): bit 1 of x, y, z must go to "
	              "code bits 3, 4, 5 (got %llu, %llu, %llu for (2,0,0), (0,2,0), (0,0,2); "
	              "expected 8, 16, 32)", (unsigned long long)lz_morton(3, 2, 0, 0),
	              (unsigned long long)lz_morton(3, 0, 2, 0), (unsigned long long)lz_morton(3, 0, 0, 2));
	/* The first bits past what the 32-bit recipes keep: x = 2^10 in 3D goes to bit 30,
	 * y = 2^16 in 2D to bit 33. */
	LZ_REQUIRE(lz_morton(3, 1024, 0, 0) == UINT64_C(1) << 30 &&
	              lz_morton(2, 0, 65536, 0) == UINT64_C(1) << 33, "lz_morton(3, 1024, 0, 0) = "
	              "%#llx and lz_morton(2, 0, 65536, 0) = %#llx, expected bit 30 and bit 33 alone: "
	              "a 32-bit bit spread keeps only 10 bits per coordinate in 3D, 16 in 2D",
	              (unsigned long long)lz_morton(3, 1024, 0, 0),
	              (unsigned long long)lz_morton(2, 0, 65536, 0));
	uint64_t got = lz_morton(2, 1, 1, 12345);
	LZ_REQUIRE(got == 3, "lz_morton(2, 1, 1, 12345) = %llu, expected 3: in 2D the z "
	              "argument must be ignored", (unsigned long long)got);
}
END_TEST

/* Inside an aligned block of side 2^j, its 2^dim sub-blocks of side 2^(j-1) must come
 * in the order x first, then y, then z: the sub-block holding cx starts at the block's
 * code plus (bit j-1 of x + 2·bit j-1 of y + 4·bit j-1 of z) runs of 2^((j-1)·dim).
 * Consecutive runs alone allow any order of the sub-blocks (x and y swapped, say). */
static void check_sub_block_order(int dim, uint32_t m, int j, const int32_t *cx,
                                  const uint64_t *code)
{
	int32_t big[3], sub[3];
	for (int a = 0; a < 3; a++) {
		big[a] = cx[a] >> j << j;
		sub[a] = cx[a] >> (j - 1) << (j - 1);
	}
	size_t qb = (size_t)big[0] + m * ((size_t)big[1] + m * (size_t)big[2]);
	size_t qs = (size_t)sub[0] + m * ((size_t)sub[1] + m * (size_t)sub[2]);
	int place = (cx[0] >> (j - 1) & 1) + 2 * (cx[1] >> (j - 1) & 1) + 4 * (cx[2] >> (j - 1) & 1);
	uint64_t part = (uint64_t)1 << ((j - 1) * dim), want = code[qb] + (uint64_t)place * part;
	LZ_REQUIRE(code[qs] == want, "%dD: the block of side %d at (%d, %d, %d) starts at code %llu, "
	      "so its sub-block of side %d at (%d, %d, %d), number %d in the order x, then y%s, "
	      "should start at code %llu; it starts at %llu. Bit b of x goes to the lowest place "
	      "of each group (bit dim·b), then y, then z", dim, 1 << j, big[0], big[1], big[2],
	      (unsigned long long)code[qb], 1 << (j - 1), sub[0], sub[1], sub[2], place,
	      dim == 3 ? ", then z" : "", (unsigned long long)want, (unsigned long long)code[qs]);
}

LZ_TEST(morton_is_a_bijection_with_consecutive_blocks)
{
	for (int dim = 2; dim <= 3; dim++)
		for (int k = 0; k <= (dim == 2 ? 6 : 4); k++) {
			uint32_t m = 1u << k;
			size_t n = (size_t)1 << (dim * k);
			uint64_t *code = malloc(n * sizeof *code);
			char *seen = calloc(n, 1);
			ck_assert(code && seen);
			for (size_t q = 0; q < n; q++) {
				int32_t cx[3];
				bf_decode(dim, (int32_t)m, q, cx);
				code[q] = lz_morton(dim, (uint32_t)cx[0], (uint32_t)cx[1], (uint32_t)cx[2]);
				LZ_REQUIRE(code[q] < n && !seen[code[q]], "%dD grid of %u^%d cells: cell "
				              "(%d, %d, %d) has Morton code %llu, %s; the codes of the cells of a "
				              "2^k grid must be exactly 0 .. m^dim - 1, each once", dim, m, dim,
				              cx[0], cx[1], cx[2], (unsigned long long)code[q],
				              code[q] >= n ? "beyond m^dim - 1" : "already given to another cell");
				seen[code[q]] = 1;
			}
			/* Every aligned block of side 2^j holds one run of 2^(j·dim) codes. */
			for (int j = 1; j <= k; j++) {
				uint64_t run = (uint64_t)1 << (j * dim);
				for (size_t q = 0; q < n; q++) {
					int32_t cx[3], corner[3];
					bf_decode(dim, (int32_t)m, q, cx);
					for (int a = 0; a < 3; a++)
						corner[a] = cx[a] >> j << j;
					size_t qc = (size_t)corner[0] + m * ((size_t)corner[1] + m * (size_t)corner[2]);
					uint64_t base = code[qc];
					LZ_REQUIRE(base % run == 0 && code[q] >= base && code[q] < base + run,
					              "%dD: cell (%d, %d, %d) has code %llu, but its aligned block "
					              "of side %d starting at (%d, %d, %d) (code %llu) should hold "
					              "the %llu consecutive codes from a multiple of %llu: "
					              "interleave the bits, x lowest", dim, cx[0], cx[1], cx[2],
					              (unsigned long long)code[q], 1 << j, corner[0], corner[1],
					              corner[2], (unsigned long long)base, (unsigned long long)run,
					              (unsigned long long)run);
					check_sub_block_order(dim, m, j, cx, code);
				}
			}
			free(code);
			free(seen);
		}
}
END_TEST

LZ_TEST(morton_matches_bit_by_bit_up_to_the_largest_coordinates)
{
	for (int b = 0; b < 21; b++) {
		uint32_t v = 1u << b;
		uint64_t gx = lz_morton(3, v, 0, 0), gy = lz_morton(3, 0, v, 0), gz = lz_morton(3, 0, 0, v);
		LZ_REQUIRE(gx == (uint64_t)1 << 3 * b && gy == (uint64_t)1 << (3 * b + 1) &&
		              gz == (uint64_t)1 << (3 * b + 2), "3D: bit %d alone in x, y or z gave "
		              "codes %#llx, %#llx, %#llx; expected bits %d, %d, %d — the high bits need "
		              "64-bit arithmetic from the start", b, (unsigned long long)gx,
		              (unsigned long long)gy, (unsigned long long)gz, 3 * b, 3 * b + 1, 3 * b + 2);
	}
	for (int b = 0; b < 32; b++) {
		uint32_t v = 1u << b;
		uint64_t gx = lz_morton(2, v, 0, 0), gy = lz_morton(2, 0, v, 0);
		LZ_REQUIRE(gx == (uint64_t)1 << 2 * b && gy == (uint64_t)1 << (2 * b + 1),
		              "2D: bit %d alone in x or y gave codes %#llx, %#llx; expected bits %d and "
		              "%d (all 32 bits of a 2D coordinate count; shift in 64 bits)", b,
		              (unsigned long long)gx, (unsigned long long)gy, 2 * b, 2 * b + 1);
	}
	uint32_t top3 = (1u << 21) - 1, top2 = (1u << 31) - 1;
	LZ_REQUIRE(lz_morton(3, top3, top3, top3) == (UINT64_C(1) << 63) - 1,
	              "lz_morton(3, 2^21-1, 2^21-1, 2^21-1) = %#llx, expected 63 one bits",
	              (unsigned long long)lz_morton(3, top3, top3, top3));
	LZ_REQUIRE(lz_morton(2, top2, top2, 0) == (UINT64_C(1) << 62) - 1,
	              "lz_morton(2, 2^31-1, 2^31-1, 0) = %#llx, expected 62 one bits",
	              (unsigned long long)lz_morton(2, top2, top2, 0));
	LZ_REQUIRE(lz_morton(2, UINT32_MAX, 0, 0) == UINT64_C(0x5555555555555555),
	              "lz_morton(2, 2^32-1, 0, 0) = %#llx, expected the even bits 0x5555555555555555",
	              (unsigned long long)lz_morton(2, UINT32_MAX, 0, 0));
	gsl_rng *rng = lz_test_rng(401);
	for (int t = 0; t < 20000; t++) {
		int dim = 2 + t % 2;
		uint32_t x = (uint32_t)gsl_rng_get(rng), y = (uint32_t)gsl_rng_get(rng),
		         z = (uint32_t)gsl_rng_get(rng);
		if (dim == 3) {
			x &= top3;
			y &= top3;
			z &= top3;
		}
		uint64_t got = lz_morton(dim, x, y, z), want = bf_morton(dim, x, y, dim == 3 ? z : 0);
		LZ_REQUIRE(got == want, "lz_morton(%d, %u, %u, %u) = %#llx, but interleaving the "
		              "bits one by one gives %#llx", dim, x, y, z, (unsigned long long)got,
		              (unsigned long long)want);
	}
	gsl_rng_free(rng);
}
END_TEST

/* ---- the cell of a lattice site ---- */

LZ_TEST(site_cell_is_the_high_bits)
{
	static const struct {
		int dim;
		int32_t L;
		int shift;
	} grids[] = {{2, 64, 0}, {2, 64, 2}, {2, 64, 4}, {2, 128, 3}, {3, 32, 0}, {3, 32, 1},
	             {3, 32, 3}, {3, 64, 4}};
	gsl_rng *rng = lz_test_rng(402);
	for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++)
		for (int o = 0; o < 2; o++) {
			int dim = grids[g].dim, s = grids[g].shift;
			int32_t L = grids[g].L, w = 1 << s;
			lz_cells *c = hand_lattice(dim, L, s, o ? LZ_CELLS_MORTON : LZ_CELLS_ROW);
			/* the corners (0 and L-1 on every axis), cell edges, then random sites */
			size_t n = 2000;
			int32_t *r = malloc(n * (size_t)dim * sizeof *r);
			for (size_t i = 0; i < n; i++)
				for (int k = 0; k < dim; k++) {
					int32_t v;
					if (i < 8)
						v = (i >> k & 1) ? L - 1 : 0;
					else if (i < 16)
						v = (i >> k & 1) ? w : w - 1;
					else
						v = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
					r[i * (size_t)dim + (size_t)k] = v;
				}
			for (size_t i = 0; i < n; i++) {
				const int32_t *ri = r + i * (size_t)dim;
				size_t got = lz_cells_of_site(c, ri);
				int32_t site[3] = {ri[0], ri[1], dim == 3 ? ri[2] : 0}, want[3] = {0, 0, 0},
				        cx[3] = {0, 0, 0};
				char b1[64], b2[64], b3[64];
				for (int k = 0; k < dim; k++)
					want[k] = site[k] / w;
				LZ_REQUIRE(got < c->ncells, "%dD lattice grid, L = %d, cells of %d sites, %s "
				              "order: site %s was put in cell %zu, but the cells are numbered "
				              "0 .. %zu", dim, L, w, order_name(c->order),
				              fmt_cell(b1, 64, dim, site), got, c->ncells - 1);
				bf_coords(c, got, cx);
				LZ_REQUIRE(memcmp(cx, want, sizeof cx) == 0, "%dD lattice grid, L = %d, cells "
				              "of w = %d sites (shift %d), %s order: site %s was put in cell "
				              "%zu, which is the cell %s; it belongs to the cell %s = site / w "
				              "(cell coordinates are r >> shift, and lz_cells_index turns them "
				              "into the storage index)", dim, L, w, s, order_name(c->order),
				              fmt_cell(b1, 64, dim, site), got, fmt_cell(b2, 64, dim, cx),
				              fmt_cell(b3, 64, dim, want));
			}
			free(r);
			lz_cells_free(c);
		}
	gsl_rng_free(rng);
}
END_TEST

/* ---- the cell of a point ---- */

/* Check the cell of point x (dim coordinates) against the expected cell coordinates
 * want[]; `why` says what is special about the point. */
static void check_point(const lz_cells *c, const double *x, const int32_t *want, const char *why)
{
	size_t got = lz_cells_of_point(c, x);
	int dim = c->dim;
	LZ_REQUIRE(got < c->ncells, "%dD %s box of side L = %g, %d cells per side: a point "
	              "(%.17g, %.17g, ...) went to cell %zu, but the cells are numbered 0 .. %zu "
	              "(%s)", dim, c->periodic ? "periodic" : "walled", c->side, c->m, x[0], x[1],
	              got, c->ncells - 1, why);
	int32_t cx[3] = {0, 0, 0};
	bf_coords(c, got, cx);
	for (int k = 0; k < dim; k++)
		LZ_REQUIRE(cx[k] == want[k], "%dD %s box of side L = %g cut into %d cells of width "
		              "w = %g, %s order: the point with coordinate %d = %.17g belongs to cell "
		              "coordinate %d, but lz_cells_of_point put it in a cell with coordinate "
		              "%d — %s", dim, c->periodic ? "periodic" : "walled", c->side, c->m,
		              c->width, order_name(c->order), k, x[k], want[k], cx[k], why);
}

LZ_TEST(point_cell_wraps_into_the_periodic_box)
{
	static const struct {
		int dim;
		int32_t m;
		double L;
		lz_cells_order order;
	} grids[] = {{2, 7, 10.5, LZ_CELLS_ROW}, {2, 7, 10.5, LZ_CELLS_MORTON},
	             {2, 8, 8.0, LZ_CELLS_MORTON}, {3, 5, 5.0, LZ_CELLS_MORTON},
	             {3, 4, 7.25, LZ_CELLS_ROW}, {3, 3, 2.75, LZ_CELLS_MORTON},
	             {2, 3, 14.6, LZ_CELLS_MORTON}};  /* 14.6: a hair below L rounds up to m */
	gsl_rng *rng = lz_test_rng(403);
	for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
		int dim = grids[g].dim;
		int32_t m = grids[g].m;
		double L = grids[g].L, w = L / m;
		lz_cells *c = hand_grid(dim, m, L, 1, grids[g].order, 1, 0);
		/* Points built inside a known cell, some of them several periods away. */
		for (int t = 0; t < 3000; t++) {
			double x[3];
			int32_t want[3] = {0, 0, 0};
			int far = 0;
			for (int k = 0; k < dim; k++) {
				want[k] = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)m);
				double f = 0.01 + 0.98 * gsl_rng_uniform(rng);
				long p = t % 3 == 0 ? 0 : (long)gsl_rng_uniform_int(rng, 9) - 4;
				if (t % 50 == 7)
					p = k % 2 ? 123456789 : -123456789;
				far |= p != 0;
				x[k] = (want[k] + f) * w + (double)p * L;
			}
			check_point(c, x, want, far ? "a coordinate outside [0, L) must first be wrapped "
			            "into the box (fmod keeps the sign of x: add L to a negative result)"
			            : "its cell coordinate is floor(x / w)");
		}
		/* The edges, on every axis (the other coordinates in the middle). */
		const struct {
			double x;
			int32_t cell;
			const char *why;
		} edge[] = {
			{0.0, 0, "x = 0 is in the first cell"},
			{-0.0, 0, "x = -0.0 is x = 0, in the first cell"},
			{L, 0, "x = L is x = 0 by periodicity: the first cell"},
			{nextafter(L, 0), m - 1, "x a hair below L belongs to the last cell m - 1, even "
			 "when x·(m/L) rounds up to m"},
			{-1e-17, m - 1, "x a hair below 0 wraps to a hair below L: the last cell "
			 "(take m - 1 when -1e-17 + L rounds to L)"},
			{-1e-300, m - 1, "x a hair below 0 wraps to a hair below L: the last cell "
			 "(take m - 1 when -1e-300 + L rounds to L)"},
			{-L, 0, "x = -L is x = 0 by periodicity"},
			{fma(3, L, -3 * L) == 0 ? 3 * L : -L, 0, "x = 3L is x = 0 by periodicity"},
			{-0.5 * w, m - 1, "x = -w/2 wraps to L - w/2, in the last cell"},
			{L + 0.5 * w, 0, "x = L + w/2 wraps to w/2, in the first cell"},
			{-5 * L - 0.5 * w, m - 1, "x = -5L - w/2 wraps to L - w/2, in the last cell"},
			{7 * L + 1.5 * w, 1, "x = 7L + 1.5w wraps to 1.5w, in cell 1"},
		};
		for (size_t e = 0; e < sizeof edge / sizeof edge[0]; e++)
			for (int k = 0; k < dim; k++) {
				double x[3] = {(m / 2 + 0.5) * w, (m / 2 + 0.5) * w, (m / 2 + 0.5) * w};
				int32_t want[3] = {m / 2, m / 2, m / 2};
				x[k] = edge[e].x;
				want[k] = edge[e].cell;
				check_point(c, x, want, edge[e].why);
			}
		/* Random coordinates over five periods each way, against floor(x / w) mod m
		 * (points within round-off of a cell boundary are left out). */
		for (int t = 0; t < 3000; t++) {
			double x[3];
			int32_t want[3] = {0, 0, 0};
			int clear = 1;
			for (int k = 0; k < dim; k++) {
				x[k] = (gsl_rng_uniform(rng) - 0.5) * 10 * L;
				double u = x[k] / w;
				long q = (long)floor(u);
				clear &= fabs(u - nearbyint(u)) > 1e-9;
				want[k] = (int32_t)(((q % m) + m) % m);
			}
			if (clear)
				check_point(c, x, want, "its cell coordinate is floor(x / w) mod m");
		}
		lz_cells_free(c);
	}
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(point_cell_with_walls_clamps_to_the_edge_cells)
{
	static const struct {
		int dim;
		int32_t m;
		double L;
		lz_cells_order order;
	} grids[] = {{2, 6, 9.0, LZ_CELLS_ROW}, {3, 4, 6.0, LZ_CELLS_MORTON}, {2, 3, 14.6, LZ_CELLS_ROW},
	             {2, 1, 3.0, LZ_CELLS_ROW}, {2, 2, 5.0, LZ_CELLS_MORTON},
	             {3, 5, 5.5, LZ_CELLS_MORTON}};
	gsl_rng *rng = lz_test_rng(404);
	for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
		int dim = grids[g].dim;
		int32_t m = grids[g].m;
		double L = grids[g].L, w = L / m;
		lz_cells *c = hand_grid(dim, m, L, 0, grids[g].order, 1, 0);
		for (int t = 0; t < 2000; t++) {
			double x[3];
			int32_t want[3] = {0, 0, 0};
			for (int k = 0; k < dim; k++) {
				want[k] = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)m);
				x[k] = (want[k] + 0.01 + 0.98 * gsl_rng_uniform(rng)) * w;
			}
			check_point(c, x, want, "inside the box its cell coordinate is floor(x / w)");
		}
		const struct {
			double x;
			int32_t cell;
			const char *why;
		} edge[] = {
			{0.0, 0, "x = 0 is in the first cell"},
			{L, m - 1, "with walls x = L is on the far wall: the last cell, not a wrap to 0"},
			{nextafter(L, 0), m - 1, "x a hair below L is in the last cell m - 1"},
			{-w / 3, 0, "with walls a point beyond the wall at 0 goes to the nearest edge "
			 "cell, 0 (no wrap)"},
			{L + 0.2 * w, m - 1, "with walls a point beyond the wall at L goes to the nearest "
			 "edge cell, m - 1 (no wrap)"},
			{4 * L, m - 1, "with walls a point beyond the wall at L goes to the last cell"},
			{-1e10, 0, "a point far beyond the wall at 0 goes to cell 0 (compare before "
			 "converting: (int)(x / w) overflows)"},
			{1e10, m - 1, "a point far beyond the wall at L goes to cell m - 1 (compare "
			 "before converting: (int)(x / w) overflows)"},
		};
		for (size_t e = 0; e < sizeof edge / sizeof edge[0]; e++)
			for (int k = 0; k < dim; k++) {
				double x[3] = {(m / 2 + 0.5) * w, (m / 2 + 0.5) * w, (m / 2 + 0.5) * w};
				int32_t want[3] = {m / 2, m / 2, m / 2};
				x[k] = edge[e].x;
				want[k] = edge[e].cell;
				check_point(c, x, want, edge[e].why);
			}
		lz_cells_free(c);
	}
	gsl_rng_free(rng);
}
END_TEST

/* ---- the block and the half block ---- */

/* 1 if cells a and b (storage indices) differ by -1, 0 or +1 on every axis, through
 * the wrap in a periodic box. */
static int bf_touch(const lz_cells *c, size_t a, size_t b)
{
	int32_t ca[3], cb[3];
	bf_coords(c, a, ca);
	bf_coords(c, b, cb);
	for (int k = 0; k < c->dim; k++) {
		int32_t d = cb[k] - ca[k];
		if (c->periodic)
			d = ((d % c->m) + c->m) % c->m;
		if (!(d == 0 || d == 1 || (c->periodic ? d == c->m - 1 : d == -1)))
			return 0;
	}
	return 1;
}

/* The block (half = 0) or half block of cell s into out, checked for the basics:
 * a sane count, s first, every entry a real cell next to s, no entry twice. */
static int get_block(const lz_cells *c, size_t s, int half, uint32_t *out)
{
	char b1[64], b2[64];
	int32_t cs[3] = {0, 0, 0}, ct[3] = {0, 0, 0};
	bf_coords(c, s, cs);
	for (int k = 0; k < 27; k++)
		out[k] = UINT32_MAX;
	int n = lz_cells_stencil(c, s, half, out);
	int most = half ? c->nhalf : c->nfull;
	const char *what = half ? "half block" : "block";
	LZ_REQUIRE(n >= 1 && n <= most, "%dD %s grid of %d cells per side: the %s of cell %zu "
	              "%s has %d cells; it can have 1 to %d", c->dim, c->periodic ? "periodic" :
	              "walled", c->m, what, s, fmt_cell(b1, 64, c->dim, cs), n, most);
	LZ_REQUIRE(out[0] == s, "%dD grid of %d cells per side: the %s of cell %zu starts with "
	              "%u; the cell itself must come first", c->dim, c->m, what, s, out[0]);
	for (int k = 0; k < n; k++) {
		LZ_REQUIRE(out[k] < c->ncells, "%dD grid of %d^%d cells: entry %d of the %s of "
		              "cell %zu is %u, but the cells are numbered 0 .. %zu", c->dim, c->m,
		              c->dim, k, what, s, out[k], c->ncells - 1);
		bf_coords(c, out[k], ct);
		LZ_REQUIRE(bf_touch(c, s, out[k]), "%dD %s grid of %d cells per side, %s order: the "
		              "%s of cell %s lists cell %u %s, which is not next to it%s", c->dim,
		              c->periodic ? "periodic" : "walled", c->m, order_name(c->order), what,
		              fmt_cell(b1, 64, c->dim, cs), out[k], fmt_cell(b2, 64, c->dim, ct),
		              c->periodic ? " even through the wrap (are neighbour coordinates turned "
		              "into storage indices with lz_cells_index?)" : " (with walls there is no "
		              "wrap: a neighbour beyond a wall is left out)");
		for (int j = 0; j < k; j++)
			LZ_REQUIRE(out[j] != out[k], "%dD %s grid of %d cells per side: the %s of cell "
			              "%s lists cell %u %s twice: each offset must give one cell", c->dim,
			              c->periodic ? "periodic" : "walled", c->m, what,
			              fmt_cell(b1, 64, c->dim, cs), out[k], fmt_cell(b2, 64, c->dim, ct));
	}
	return n;
}

/* The grids of the block tests: m = 3 (the smallest periodic grid) and up, both orders. */
static const struct {
	int dim;
	int32_t m;
} block_grids[] = {{2, 3}, {2, 4}, {2, 5}, {2, 7}, {3, 3}, {3, 4}, {3, 5}};
#define NBLOCK_GRIDS (sizeof block_grids / sizeof block_grids[0])

LZ_TEST(block_is_the_touching_cells_with_wrap)
{
	uint32_t out[27];
	for (size_t g = 0; g < NBLOCK_GRIDS; g++)
		for (int o = 0; o < 2; o++) {
			int dim = block_grids[g].dim;
			int32_t m = block_grids[g].m;
			lz_cells *c = hand_grid(dim, m, 2.0 * m, 1, o ? LZ_CELLS_MORTON : LZ_CELLS_ROW, 1, 0);
			for (size_t s = 0; s < c->ncells; s++) {
				int n = get_block(c, s, 0, out);
				int32_t cs[3] = {0, 0, 0};
				char b1[64];
				bf_coords(c, s, cs);
				LZ_REQUIRE(n == c->nfull, "%dD periodic grid of %d cells per side, %s order: "
				              "the block of cell %s has %d cells; with the wrap every cell has "
				              "%d (itself and all its neighbours, also across the box edge)", dim,
				              m, order_name(c->order), fmt_cell(b1, 64, dim, cs), n, c->nfull);
				/* The half block is half of it: the cell and one of each pair of
				 * opposite neighbours. */
				int nh = get_block(c, s, 1, out);
				LZ_REQUIRE(nh == c->nhalf, "%dD periodic grid of %d cells per side, %s order: the "
				              "half block of cell %s has %d cells; it is the cell and one of each "
				              "of the %d pairs of opposite neighbours, %d in all", dim, m,
				              order_name(c->order), fmt_cell(b1, 64, dim, cs), nh,
				              (c->nfull - 1) / 2, c->nhalf);
			}
			/* n distinct touching cells, and there are exactly nfull of those. */
			lz_cells_free(c);
		}
}
END_TEST

LZ_TEST(block_with_walls_stops_at_the_walls)
{
	static const struct {
		int dim;
		int32_t m;
	} grids[] = {{2, 1}, {2, 2}, {2, 3}, {2, 5}, {3, 1}, {3, 2}, {3, 4}};
	uint32_t out[27];
	for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++)
		for (int o = 0; o < 2; o++) {
			int dim = grids[g].dim;
			int32_t m = grids[g].m;
			lz_cells *c = hand_grid(dim, m, 1.5 * m, 0, o ? LZ_CELLS_MORTON : LZ_CELLS_ROW, 1, 0);
			for (size_t s = 0; s < c->ncells; s++) {
				int n = get_block(c, s, 0, out), want = 1;
				int32_t cs[3] = {0, 0, 0};
				bf_coords(c, s, cs);
				for (int k = 0; k < dim; k++)  /* 3 neighbours per axis, 2 at a wall, 1 at two */
					want *= 1 + (cs[k] > 0) + (cs[k] < m - 1);
				char b1[64];
				LZ_REQUIRE(n == want, "%dD box with walls, %d cells per side, %s order: the "
				              "block of cell %s has %d cells, expected %d (a cell on %s has "
				              "no neighbours beyond the wall: 4 or 6 in 2D corners and edges, "
				              "8, 12 or 18 in 3D)", dim, m, order_name(c->order),
				              fmt_cell(b1, 64, dim, cs), n, want, want < c->nfull ?
				              "the edge" : "the inside");
				/* Its half block holds cells of the block only (get_block), and away
				 * from the walls it is the cell and one of each opposite pair. */
				int nh = get_block(c, s, 1, out);
				LZ_REQUIRE(want < c->nfull || nh == c->nhalf, "%dD box with walls, %d cells per "
				              "side, %s order: the half block of the inner cell %s has %d cells; "
				              "away from the walls it is the cell and one of each of the %d "
				              "pairs of opposite neighbours, %d in all", dim, m,
				              order_name(c->order), fmt_cell(b1, 64, dim, cs), nh,
				              (c->nfull - 1) / 2, c->nhalf);
			}
			lz_cells_free(c);
		}
}
END_TEST

/* Every pair of touching cells in exactly one of their two half blocks. */
static void check_half_blocks(lz_cells *c)
{
	size_t nc = c->ncells;
	uint32_t *h = malloc(nc * 27 * sizeof *h);
	int *nh = malloc(nc * sizeof *nh);
	char b1[64], b2[64];
	for (size_t s = 0; s < nc; s++) {
		nh[s] = get_block(c, s, 1, h + s * 27);
		if (c->periodic) {
			int32_t cs[3] = {0, 0, 0};
			bf_coords(c, s, cs);
			LZ_REQUIRE(nh[s] == c->nhalf, "%dD periodic grid of %d cells per side: the half "
			              "block of cell %s has %d cells, expected %d (itself and half of its "
			              "%d neighbours)", c->dim, c->m, fmt_cell(b1, 64, c->dim, cs), nh[s],
			              c->nhalf, c->nfull - 1);
		}
	}
	for (size_t s = 0; s < nc; s++)
		for (size_t t = s + 1; t < nc; t++) {
			if (!bf_touch(c, s, t))
				continue;
			int times = 0;
			for (int k = 1; k < nh[s]; k++)
				times += h[s * 27 + (size_t)k] == t;
			for (int k = 1; k < nh[t]; k++)
				times += h[t * 27 + (size_t)k] == s;
			int32_t cs[3] = {0, 0, 0}, ct[3] = {0, 0, 0};
			bf_coords(c, s, cs);
			bf_coords(c, t, ct);
			LZ_REQUIRE(times == 1, "%dD %s grid of %d cells per side, %s order: the touching "
			              "cells %s and %s appear in %d of their two half blocks, expected "
			              "exactly one — %s", c->dim, c->periodic ? "periodic" : "walled", c->m,
			              order_name(c->order), fmt_cell(b1, 64, c->dim, cs),
			              fmt_cell(b2, 64, c->dim, ct), times, times ? "their particle pairs "
			              "would be counted twice (take only the forward offsets)" : "their "
			              "particle pairs would never be compared");
		}
	free(h);
	free(nh);
}

LZ_TEST(half_block_holds_each_touching_pair_once)
{
	for (size_t g = 0; g < NBLOCK_GRIDS; g++)
		for (int v = 0; v < 4; v++) {
			int periodic = v < 2;
			lz_cells *c = hand_grid(block_grids[g].dim, block_grids[g].m, 1.0 * block_grids[g].m,
			                        periodic, v % 2 ? LZ_CELLS_MORTON : LZ_CELLS_ROW, 1, 0);
			check_half_blocks(c);
			lz_cells_free(c);
		}
}
END_TEST

LZ_TEST(half_block_is_the_forward_half)
{
	static const struct {
		int dim;
		int32_t m;
		int periodic;
	} grids[] = {{2, 3, 1}, {2, 4, 0}, {3, 3, 1}, {3, 4, 1}, {3, 3, 0}};
	uint32_t out[27];
	char b1[64], b2[64];
	for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
		int dim = grids[g].dim;
		int32_t m = grids[g].m;
		lz_cells *c = hand_grid(dim, m, 1.0 * m, grids[g].periodic, LZ_CELLS_MORTON, 1, 0);
		for (size_t s = 0; s < c->ncells; s++) {
			int n = get_block(c, s, 1, out);
			int32_t cs[3] = {0, 0, 0};
			bf_coords(c, s, cs);
			/* the expected count: self and the forward offsets that stay inside */
			int want = 1;
			for (int d = dim == 3 ? -1 : 0; d <= (dim == 3 ? 1 : 0); d++)
				for (int b = -1; b <= 1; b++)
					for (int a = -1; a <= 1; a++) {
						int fwd = d > 0 || (d == 0 && (b > 0 || (b == 0 && a > 0)));
						int32_t off[3] = {a, b, d};
						int in = 1;
						for (int k = 0; k < dim; k++)
							in &= c->periodic || (cs[k] + off[k] >= 0 && cs[k] + off[k] < m);
						want += fwd && in;
					}
			LZ_REQUIRE(n == want, "%dD grid, m = %d: the half block of cell %s has %d cells, "
			              "the forward half has %d", dim, m, fmt_cell(b1, 64, dim, cs), n, want);
			for (int k = 1; k < n; k++) {
				int32_t ct[3] = {0, 0, 0}, off[3] = {0, 0, 0};
				bf_coords(c, out[k], ct);
				for (int a = 0; a < dim; a++) {
					off[a] = ct[a] - cs[a];
					if (off[a] > 1)
						off[a] -= m;
					if (off[a] < -1)
						off[a] += m;
				}
				int fwd = off[2] > 0 || (off[2] == 0 && (off[1] > 0 || (off[1] == 0 && off[0] > 0)));
				LZ_REQUIRE(fwd, "%dD grid, m = %d: the half block of cell %s lists %s, at "
				              "offset (%d, %d, %d); the header's half block takes the offsets "
				              "(a, b, c) with c > 0, or c = 0 and b > 0, or c = b = 0 and a > 0",
				              dim, m, fmt_cell(b1, 64, dim, cs), fmt_cell(b2, 64, dim, ct),
				              off[0], off[1], off[2]);
			}
		}
		lz_cells_free(c);
	}
}
END_TEST

/* ---- linked lists and fixed arrays ---- */

/* Fail unless head[]/next[] list every particle in the list of its cell, once, every
 * list ends, and the extra cell ncells is empty. */
static void check_links(const lz_cells *c, const char *what)
{
	size_t n = c->n, nc = c->ncells;
	char *seen = calloc(n + 1, 1);
	for (size_t q = 0; q <= nc; q++) {
		int32_t i = c->head[q];
		if (q == nc)
			LZ_REQUIRE(i == -1, "%s: the extra cell %zu (the always-empty one) has head %d; "
			              "it must be -1 so that loops over a block with a missing cell find "
			              "nobody — set every head, 0 .. ncells, to -1 first", what, nc, i);
		while (i != -1) {
			LZ_REQUIRE(i >= 0 && (size_t)i < n, "%s: the list of cell %zu reaches %d, which "
			              "is not a particle (0 .. %zu): are all heads set to -1 before "
			              "linking, so that every list ends with -1?", what, q, i, n - 1);
			LZ_REQUIRE(c->of[i] == q, "%s: particle %d is in the list of cell %zu, but it "
			              "lives in cell of[%d] = %u (a list left over from an earlier call?)",
			              what, i, q, i, c->of[i]);
			LZ_REQUIRE(!seen[i], "%s: particle %d is met twice in the lists (a list that "
			              "loops back on itself never ends)", what, i);
			seen[i] = 1;
			i = c->next[i];
		}
	}
	for (size_t i = 0; i < n; i++)
		LZ_REQUIRE(seen[i], "%s: particle %zu (cell %u) is in no list: every particle must "
		              "be reachable from the head of its cell", what, i, c->of[i]);
	free(seen);
}

LZ_TEST(link_lists_every_particle_in_its_cell)
{
	gsl_rng *rng = lz_test_rng(405);
	for (int v = 0; v < 2; v++) {
		lz_cells *c = v == 0 ? hand_grid(2, 5, 5.0, 1, LZ_CELLS_ROW, 400, 0)
		                     : hand_grid(3, 3, 3.0, 1, LZ_CELLS_MORTON, 400, 0);
		char what[160];
		c->n = 400;
		for (size_t i = 0; i < c->n; i++)
			c->of[i] = (uint32_t)gsl_rng_uniform_int(rng, c->ncells);
		snprintf(what, sizeof what, "%zu particles in random cells of %zu", c->n, c->ncells);
		lz_cells_link(c);
		check_links(c, what);
		/* Again, with every particle moved into the first few cells. */
		for (size_t i = 0; i < c->n; i++)
			c->of[i] = (uint32_t)(i % 3);
		lz_cells_link(c);
		check_links(c, "linking again after the particles moved to cells 0, 1, 2 (the old "
		            "lists must be forgotten)");
		c->n = 300;
		for (size_t i = 0; i < c->n; i++)
			c->of[i] = (uint32_t)c->ncells - 1;
		lz_cells_link(c);
		check_links(c, "300 particles all in the last cell");
		c->n = 1;
		c->of[0] = 2;
		lz_cells_link(c);
		check_links(c, "a single particle (N = 1)");
		c->n = 0;
		lz_cells_link(c);
		check_links(c, "no particles at all (every list empty)");
		lz_cells_free(c);
	}
	gsl_rng_free(rng);
}
END_TEST

/* Fail unless count[] and slot[] hold exactly the particles of each cell, in
 * increasing index, and the extra cell is empty. */
static void check_arrays(const lz_cells *c, const char *what)
{
	size_t nc = c->ncells;
	uint32_t *want = calloc(nc + 1, sizeof *want);
	for (size_t i = 0; i < c->n; i++)
		want[c->of[i]]++;
	for (size_t q = 0; q <= nc; q++) {
		LZ_REQUIRE(c->count[q] == want[q], "%s: count[%zu] = %u, but %u particles live in "
		              "cell %zu%s", what, q, c->count[q], want[q], q, q == nc ? " (the extra, "
		              "always-empty cell: reset all ncells + 1 counts)" : " (are the counts "
		              "reset to 0 first?)");
		const uint32_t *s = c->slot + q * c->cap;
		for (uint32_t k = 0; k < c->count[q]; k++) {
			LZ_REQUIRE(s[k] < c->n && c->of[s[k]] == q, "%s: slot %u of cell %zu holds %u, "
			              "which is not a particle of that cell", what, k, q, s[k]);
			LZ_REQUIRE(k == 0 || s[k] > s[k - 1], "%s: cell %zu lists particle %u after %u; "
			              "the particles of a cell must be in increasing index (go through "
			              "the particles in order)", what, q, s[k], s[k - 1]);
		}
	}
	free(want);
}

LZ_TEST(fill_arrays_match_the_cells_in_index_order)
{
	gsl_rng *rng = lz_test_rng(406);
	for (int v = 0; v < 2; v++) {
		size_t nc = v == 0 ? 36 : 27, n = 500;
		uint32_t *of = malloc(n * sizeof *of), *per = calloc(nc, sizeof *per), most = 0;
		for (size_t i = 0; i < n; i++) {
			of[i] = (uint32_t)gsl_rng_uniform_int(rng, nc);
			if (++per[of[i]] > most)
				most = per[of[i]];
		}
		/* cap = the fullest cell's count: one cell is exactly full, which is fine */
		lz_cells *c = v == 0 ? hand_grid(2, 6, 6.0, 1, LZ_CELLS_ROW, n, most)
		                     : hand_grid(3, 3, 3.0, 0, LZ_CELLS_MORTON, n, most);
		memcpy(c->of, of, n * sizeof *of);
		c->n = n;
		char what[160];
		snprintf(what, sizeof what, "%zu particles in %zu cells, cap = %u (the fullest cell "
		         "exactly full)", n, nc, most);
		int st = lz_cells_fill(c);
		LZ_REQUIRE(st == LZ_OK, "%s: lz_cells_fill returned %d (%s), expected LZ_OK: a cell "
		              "holding exactly cap particles is full, not overfull", what, st,
		              lz_error_message());
		check_arrays(c, what);
		c->n = 7;
		for (size_t i = 0; i < 7; i++)
			c->of[i] = (uint32_t)(nc - 1 - i % 2);
		LZ_REQUIRE(lz_cells_fill(c) == LZ_OK, "7 particles in two cells: %s",
		              lz_error_message());
		check_arrays(c, "filling again with 7 particles in the last two cells (the old counts "
		             "must be forgotten)");
		c->n = 1;
		c->of[0] = 0;
		ck_assert(lz_cells_fill(c) == LZ_OK);
		check_arrays(c, "a single particle (N = 1)");
		lz_cells_free(c);
		free(of);
		free(per);
	}
	gsl_rng_free(rng);
}
END_TEST

/* 1 if the decimal number v appears in s as a whole number. */
static int says_number(const char *s, unsigned long v)
{
	char num[32];
	snprintf(num, sizeof num, "%lu", v);
	size_t len = strlen(num);
	for (const char *p = strstr(s, num); p; p = strstr(p + 1, num))
		if ((p == s || p[-1] < '0' || p[-1] > '9') && (p[len] < '0' || p[len] > '9'))
			return 1;
	return 0;
}

LZ_TEST(fill_refuses_an_overfull_cell)
{
	/* 36 cells, cap 4; cell 17 gets its fifth particle last. */
	lz_cells *c = hand_grid(2, 6, 6.0, 1, LZ_CELLS_ROW, 200, 4);
	c->n = 141;
	for (size_t i = 0; i < 140; i++)
		c->of[i] = (uint32_t)(i % 35 < 17 ? i % 35 : i % 35 + 1);
	for (size_t i = 136; i < 140; i++)
		c->of[i] = 17;
	c->of[140] = 17;
	int st = lz_cells_fill(c);
	LZ_REQUIRE(st == LZ_EPHYS, "cell 17 receives 5 particles but has room for cap = 4: "
	              "lz_cells_fill returned %d, expected LZ_EPHYS (%d) — a fixed array must "
	              "refuse the extra particle, never drop it silently", st, LZ_EPHYS);
	const char *msg = lz_error_message();
	LZ_REQUIRE(says_number(msg, 17) && says_number(msg, 4), "the error message should name "
	              "the cell (17) and its capacity (cap = 4) so the user knows what to enlarge; "
	              "it says: \"%s\"", msg);
	c->n = 140;  /* the same without the fifth: cell 17 exactly full */
	st = lz_cells_fill(c);
	LZ_REQUIRE(st == LZ_OK, "every cell holds at most cap = 4 particles (cell 17 exactly 4), "
	              "but lz_cells_fill returned %d: %s", st, lz_error_message());
	check_arrays(c, "cells filled up to cap = 4");
	lz_cells_free(c);
	c = hand_grid(2, 3, 3.0, 1, LZ_CELLS_ROW, 10, 0);
	c->n = 3;
	c->of[0] = c->of[1] = c->of[2] = 0;
	st = lz_cells_fill(c);
	LZ_REQUIRE(st == LZ_EINVAL, "a grid allocated with cap = 0 has no arrays: "
	              "lz_cells_fill must return LZ_EINVAL (%d), got %d", LZ_EINVAL, st);
	lz_cells_free(c);
}
END_TEST

/* ---- pairs ---- */

static int key_cmp(const void *a, const void *b)
{
	uint64_t p = *(const uint64_t *)a, q = *(const uint64_t *)b;
	return (p > q) - (p < q);
}

static uint64_t pair_key(uint32_t i, uint32_t j)
{
	return i < j ? (uint64_t)i << 32 | j : (uint64_t)j << 32 | i;
}

/* The distance of points a and b, the nearest image in a periodic box: each
 * |difference| reduced mod L, then L minus it if that is shorter. */
static double bf_dist(int dim, double L, int periodic, const double *a, const double *b)
{
	double s = 0;
	for (int k = 0; k < dim; k++) {
		double d = fabs(a[k] - b[k]);
		if (periodic) {
			d = fmod(d, L);
			if (d > L - d)
				d = L - d;
		}
		s += d * d;
	}
	return sqrt(s);
}

/* All pairs closer than rc, by comparing every pair (sorted keys). */
static uint64_t *bf_pairs(const double *x, size_t n, int dim, double L, int periodic, double rc,
                          size_t *np)
{
	size_t cap = 1024, k = 0;
	uint64_t *keys = malloc(cap * sizeof *keys);
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++) {
			const double *a = x + i * (size_t)dim, *b = x + j * (size_t)dim;
			double s = 0;
			for (int t = 0; t < dim; t++) {
				double d = fabs(a[t] - b[t]);
				if (periodic) {
					d = fmod(d, L);
					if (d > L - d)
						d = L - d;
				}
				s += d * d;
			}
			if (s < rc * rc) {
				if (k == cap)
					keys = realloc(keys, (cap *= 2) * sizeof *keys);
				keys[k++] = pair_key((uint32_t)i, (uint32_t)j);
			}
		}
	*np = k;
	return keys;
}

/* A line about pair (i, j) for a failure message: distance, cells, a hint. */
static const char *describe(char *buf, size_t size, const lz_cells *c, const double *x, double rc,
                            uint64_t key)
{
	uint32_t i = (uint32_t)(key >> 32), j = (uint32_t)key;
	int dim = c->dim;
	const double *a = x + (size_t)i * (size_t)dim, *b = x + (size_t)j * (size_t)dim;
	double d = bf_dist(dim, c->side, c->periodic, a, b);
	int across = 0;
	for (int k = 0; k < dim; k++)
		across |= c->periodic && fabs(a[k] - b[k]) > 0.5 * c->side;
	int32_t ca[3] = {0, 0, 0}, cb[3] = {0, 0, 0};
	char s1[64], s2[64];
	bf_coords(c, c->of[i], ca);
	bf_coords(c, c->of[j], cb);
	snprintf(buf, size, "(%u, %u) at distance %.17g (rc = %.17g), in cells %s and %s%s", i, j,
	         d, rc, fmt_cell(s1, 64, dim, ca), fmt_cell(s2, 64, dim, cb),
	         across ? ", near each other through the periodic boundary (nearest image)" : "");
	return buf;
}

/* ---- pair scans on grids, bins and lists made here ---- */

/* The pair tests below give lz_cells_pairs a grid whose block tables, bins and linked
 * lists the test made itself, so that they pay for the pair scan alone; the last test
 * of the file runs the whole chain as a user does. */

/* 1 if the offset (a, b, d) is in the header's forward half. */
static int bf_forward(int a, int b, int d)
{
	return d > 0 || (d == 0 && (b > 0 || (b == 0 && a > 0)));
}

/* The storage index of the cell at offset off from the cell coordinates cs, wrapped in
 * a periodic box; ncells (the empty cell) when it lies beyond a wall. */
static uint32_t bf_neighbour(const lz_cells *c, const int32_t *cs, const int *off)
{
	int32_t nb[3] = {0, 0, 0}, m = c->m;
	for (int k = 0; k < c->dim; k++) {
		nb[k] = cs[k] + off[k];
		if (nb[k] < 0 || nb[k] >= m) {
			if (!c->periodic)
				return (uint32_t)c->ncells;
			nb[k] = (nb[k] + m) % m;
		}
	}
	size_t q = (size_t)nb[0] + (size_t)m * ((size_t)nb[1] + (size_t)m * (size_t)nb[2]);
	return c->rank ? c->rank[q] : (uint32_t)q;
}

/* Shuffle a[0 .. n) (Fisher-Yates). */
static void shuffle_u32(gsl_rng *g, uint32_t *a, size_t n)
{
	for (size_t k = n; k > 1; k--) {
		size_t j = gsl_rng_uniform_int(g, k);
		uint32_t t = a[k - 1];
		a[k - 1] = a[j];
		a[j] = t;
	}
}

/* The block tables of a hand-made grid: row s of full[] holds s and its touching
 * cells, row s of half[] s and the forward ones, the empty cell ncells for every
 * neighbour beyond a wall. With g, the entries after the first are shuffled (the empty
 * ones too): the header fixes only that the cell itself comes first. */
static void hand_tables(lz_cells *c, gsl_rng *g)
{
	size_t nc = c->ncells, nf = (size_t)c->nfull, nh = (size_t)c->nhalf;
	c->full = malloc((nc + 1) * nf * sizeof *c->full);
	c->half = malloc((nc + 1) * nh * sizeof *c->half);
	ck_assert(c->full && c->half);
	int dz = c->dim == 3;
	for (size_t s = 0; s <= nc; s++) {
		uint32_t *f = c->full + s * nf, *h = c->half + s * nh;
		size_t kf = 1, kh = 1;
		f[0] = h[0] = (uint32_t)s;
		int32_t cs[3] = {0, 0, 0};
		if (s < nc)
			bf_coords(c, s, cs);
		for (int d = -dz; d <= dz && s < nc; d++)
			for (int b = -1; b <= 1; b++)
				for (int a = -1; a <= 1; a++) {
					if (a == 0 && b == 0 && d == 0)
						continue;
					uint32_t t = bf_neighbour(c, cs, (int[]){a, b, d});
					f[kf++] = t;
					if (bf_forward(a, b, d))
						h[kh++] = t;
				}
		while (kf < nf)
			f[kf++] = (uint32_t)nc;
		while (kh < nh)
			h[kh++] = (uint32_t)nc;
		if (g) {
			shuffle_u32(g, f + 1, nf - 1);
			shuffle_u32(g, h + 1, nh - 1);
		}
	}
}

/* A hand-made grid for points, with shuffled block tables (see hand_tables). */
static lz_cells *pair_grid(gsl_rng *g, int dim, int32_t m, double L, int periodic,
                           lz_cells_order order, size_t nmax)
{
	lz_cells *c = hand_grid(dim, m, L, periodic, order, nmax, 0);
	hand_tables(c, g);
	return c;
}

/* The cells per side that lz_cells_alloc chooses for a cutoff rc: the most that keep
 * the cell side L / m >= rc. */
static int32_t cells_for(double L, double rc)
{
	int32_t m = (int32_t)floor(L / rc);
	while (m > 1 && L / m < rc)
		m--;
	return m < 1 ? 1 : m;
}

/* Bin the points xbin[0 .. n·dim) (inside the box, or on a wall) by floor(x / w), and
 * link them, every particle pushed at its cell's head: the lists run in decreasing
 * index, the opposite of what lz_cells_link makes. */
static void hand_bin_link(lz_cells *c, const double *xbin, size_t n)
{
	int dim = c->dim;
	int32_t m = c->m;
	c->n = n;
	for (size_t q = 0; q <= c->ncells; q++)
		c->head[q] = -1;
	for (size_t i = 0; i < n; i++) {
		size_t q = 0, stride = 1;
		for (int k = 0; k < dim; k++, stride *= (size_t)m) {
			double u = floor(xbin[i * (size_t)dim + (size_t)k] / c->width);
			int32_t cx = u < 0 ? 0 : u >= m ? m - 1 : (int32_t)u;
			q += stride * (size_t)cx;
		}
		c->of[i] = c->rank ? c->rank[q] : (uint32_t)q;
		c->next[i] = c->head[c->of[i]];
		c->head[c->of[i]] = (int32_t)i;
	}
}

/* Scan grid c (binned and linked on these points) for pairs closer than rc, and fail
 * unless they are exactly the sorted keys want[0 .. nwant); then count again with no
 * room at all (out = NULL, cap = 0): the count must not change. */
static void check_pairs(const lz_cells *c, const double *x, size_t n, double rc,
                        const uint64_t *want, size_t nwant, const char *what)
{
	size_t cap = nwant + 16;
	lz_pair *out = malloc(cap * sizeof *out);
	size_t got = lz_cells_pairs(c, x, rc, out, cap), stored = got < cap ? got : cap;
	uint64_t *keys = malloc((stored + 1) * sizeof *keys);
	for (size_t k = 0; k < stored; k++) {
		LZ_REQUIRE(out[k].i < out[k].j && out[k].j < n, "%s: pair number %zu is (%u, %u); "
		              "pairs must be (i, j) with i < j < N = %zu%s", what, k, out[k].i, out[k].j,
		              n, out[k].i == out[k].j ? " (a particle met itself: is its own cell "
		              "scanned twice, once as its list and once in the half block?)" : "");
		keys[k] = pair_key(out[k].i, out[k].j);
	}
	qsort(keys, stored, sizeof *keys, key_cmp);
	char line[320];
	for (size_t k = 1; k < stored; k++)
		LZ_REQUIRE(keys[k] != keys[k - 1], "%s: the pair %s was found twice — compare the "
		              "particles of a cell only with those after them in its list, and the "
		              "other cells only through the half block", what,
		              describe(line, sizeof line, c, x, rc, keys[k]));
	size_t a = 0, b = 0;
	while (a < nwant || b < stored) {
		if (b == stored || (a < nwant && want[a] < keys[b]))
			ck_abort_msg("%s: %zu pairs found, %zu expected; missed %s", what, got, nwant,
			             describe(line, sizeof line, c, x, rc, want[a]));
		if (a == nwant || keys[b] < want[a])
			ck_abort_msg("%s: %zu pairs found, %zu expected; the pair %s is not closer than rc "
			             "(a pair counts when distance² < rc², strictly, with the nearest "
			             "image in a periodic box)", what, got, nwant,
			             describe(line, sizeof line, c, x, rc, keys[b]));
		a++;
		b++;
	}
	LZ_REQUIRE(got == nwant, "%s: lz_cells_pairs returned %zu, but there are %zu pairs "
	              "(the return value is the number of pairs)", what, got, nwant);
	size_t counted = lz_cells_pairs(c, x, rc, NULL, 0);
	LZ_REQUIRE(counted == nwant, "%s: with no room for pairs (out = NULL, cap = 0) "
	              "lz_cells_pairs returned %zu, but there are %zu: like snprintf it must count "
	              "every pair, stored or not", what, counted, nwant);
	free(out);
	free(keys);
}

/* Bin and link xbin by hand, then check the scan of the points x (the same points, or
 * the same shifted by whole periods). */
static void pairs_case(lz_cells *c, const double *xbin, const double *x, size_t n, double rc,
                       const uint64_t *want, size_t nwant, const char *what)
{
	hand_bin_link(c, xbin, n);
	check_pairs(c, x, n, rc, want, nwant, what);
}

/* Make the last 8 of n points four pairs along x at the boundary of rc: exactly rc
 * apart (not a pair: distance² < rc² is strict) and a hair closer (a pair), in the
 * open and through the boundary x = 0 = L — the latter only when the difference
 * L - (L - rc) comes out as rc exactly. Each pair at its own height (y, z). */
static void exact_pairs(double *x, size_t n, int dim, double L, double rc)
{
	double near = nextafter(rc, 0), across = L - rc;
	ck_assert(n >= 8 && near * near < rc * rc);
	double gap[4] = {rc, near, L - across == rc ? across : 0.5 * L, nextafter(across, L)};
	for (int p = 0; p < 4; p++) {
		double *a = x + (n - 8 + 2 * (size_t)p) * (size_t)dim, *b = a + dim;
		for (int k = 1; k < dim; k++)
			a[k] = b[k] = (0.125 + 0.25 * p) * L;
		a[0] = 0;
		b[0] = gap[p];
	}
}

/* Grid, points and reference for one random configuration; exact: add pairs at
 * exactly rc and a hair closer (exact_pairs). */
static void random_pairs_case(gsl_rng *rng, int dim, double L, double rc_grid, double rc,
                              int periodic, lz_cells_order order, size_t n, int shifted)
{
	double *x = malloc(n * (size_t)dim * sizeof *x), *xbin = malloc(n * (size_t)dim * sizeof *x);
	for (size_t k = 0; k < n * (size_t)dim; k++)
		x[k] = gsl_rng_uniform(rng) * L;
	if (!periodic && n > 4) {
		x[0] = 0;
		x[(size_t)dim] = L;
		x[2 * (size_t)dim + 1] = L;
	}
	if (!shifted && n >= 40)
		exact_pairs(x, n, dim, L, rc);
	size_t nwant;
	uint64_t *want = bf_pairs(x, n, dim, L, periodic, rc, &nwant);
	memcpy(xbin, x, n * (size_t)dim * sizeof *x);
	if (shifted)  /* the same points, given several periods away: the same pairs */
		for (size_t k = 0; k < n * (size_t)dim; k++)
			x[k] += L * (double)((long)gsl_rng_uniform_int(rng, 7) - 3);
	lz_cells *c = pair_grid(rng, dim, cells_for(L, rc_grid), L, periodic, order, n);
	char what[320];
	snprintf(what, sizeof what, "%dD %s box L = %g, %zu random points (%.2g per cell), grid of "
	         "%d^%d cells for rc = %g, %s order, pairs closer than rc = %g%s", dim,
	         periodic ? "periodic" : "walled", L, n, (double)n / (double)c->ncells, c->m, dim,
	         rc_grid, order_name(order), rc, shifted ? ", coordinates given outside the box "
	         "(shifted by whole periods)" : n >= 40 ? ", among them pairs at exactly rc and a "
	         "hair closer, also through the boundary" : "");
	pairs_case(c, xbin, x, n, rc, want, nwant, what);
	lz_cells_free(c);
	free(want);
	free(x);
	free(xbin);
}

LZ_TEST(pairs_match_brute_force_2d)
{
	gsl_rng *rng = lz_test_rng(407);
	static const size_t ns[] = {50, 400, 1500};
	for (int periodic = 1; periodic >= 0; periodic--)
		for (int o = 0; o < 2; o++)
			for (size_t k = 0; k < 3; k++)
				random_pairs_case(rng, 2, 10.0, 1.0, 1.0, periodic,
				                  o ? LZ_CELLS_MORTON : LZ_CELLS_ROW, ns[k], 0);
	random_pairs_case(rng, 2, 9.7, 1.3, 1.3, 1, LZ_CELLS_MORTON, 800, 0);
	random_pairs_case(rng, 2, 9.7, 1.3, 1.3, 0, LZ_CELLS_MORTON, 800, 0);
	random_pairs_case(rng, 2, 10.0, 1.0, 0.6, 1, LZ_CELLS_ROW, 800, 0);
	random_pairs_case(rng, 2, 10.0, 1.0, 1.0, 1, LZ_CELLS_MORTON, 800, 1);
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(pairs_match_brute_force_3d)
{
	gsl_rng *rng = lz_test_rng(408);
	static const size_t ns[] = {100, 800, 2000};
	for (int periodic = 1; periodic >= 0; periodic--)
		for (int o = 0; o < 2; o++)
			for (size_t k = 0; k < 3; k++)
				random_pairs_case(rng, 3, 6.0, 1.0, 1.0, periodic,
				                  o ? LZ_CELLS_MORTON : LZ_CELLS_ROW, ns[k], 0);
	random_pairs_case(rng, 3, 5.5, 1.1, 1.1, 1, LZ_CELLS_MORTON, 1000, 0);
	random_pairs_case(rng, 3, 5.5, 1.1, 1.1, 0, LZ_CELLS_ROW, 1000, 0);
	random_pairs_case(rng, 3, 6.0, 1.0, 1.0, 1, LZ_CELLS_ROW, 800, 1);
	gsl_rng_free(rng);
}
END_TEST

/* Two points in a box of side 3 with cells of side exactly rc = 1 (m = 3): the
 * number of pairs must be `want` (0 or 1). */
static void two_points(gsl_rng *g, int dim, int periodic, const double *p, const double *q,
                       size_t want, const char *why)
{
	double x[6];
	memcpy(x, p, (size_t)dim * sizeof *x);
	memcpy(x + dim, q, (size_t)dim * sizeof *x);
	lz_cells *c = pair_grid(g, dim, 3, 3.0, periodic, LZ_CELLS_ROW, 2);
	uint64_t key = pair_key(0, 1);
	char what[320];
	snprintf(what, sizeof what, "%dD %s box L = 3 cut in 3 cells of side exactly rc = 1, two "
	         "points (%.17g, %.17g%s) and (%.17g, %.17g%s): %s", dim, periodic ? "periodic" :
	         "walled", p[0], p[1], dim == 3 ? ", ..." : "", q[0], q[1], dim == 3 ? ", ..." : "",
	         why);
	pairs_case(c, x, x, 2, 1.0, &key, want, what);
	lz_cells_free(c);
}

LZ_TEST(pairs_at_exactly_the_cutoff_and_across_the_boundary)
{
	double below15 = nextafter(1.5, 0), above225 = nextafter(2.25, 3);
	gsl_rng *rng = lz_test_rng(409);
	two_points(rng, 2, 1, (double[]){0.5, 0.5}, (double[]){1.5, 0.5}, 0,
	           "distance exactly rc is not a pair (distance² < rc², strictly)");
	two_points(rng, 2, 1, (double[]){0.5, 0.5}, (double[]){below15, 0.5}, 1,
	           "a hair closer than rc, in neighbouring cells, is a pair");
	two_points(rng, 2, 1, (double[]){0.25, 1.5}, (double[]){2.25, 1.5}, 0,
	           "distance exactly rc through the periodic boundary is not a pair");
	two_points(rng, 2, 1, (double[]){0.25, 1.5}, (double[]){above225, 1.5}, 1,
	           "a hair closer than rc through the periodic boundary is a pair");
	two_points(rng, 2, 1, (double[]){0.1, 0.1}, (double[]){2.9, 2.9}, 1,
	           "opposite corners of the box are 0.28 apart through the corner: a pair");
	two_points(rng, 2, 1, (double[]){0.0, 1.0}, (double[]){2.0, 1.0}, 0,
	           "x = 0 and x = 2, both on cell edges, are exactly rc apart through the "
	           "boundary: not a pair");
	two_points(rng, 2, 1, (double[]){0.0, 0.0}, (double[]){nextafter(2.0, 3), 0.0}, 1,
	           "x = 0 and x = 2 + ulp are 1 - ulp apart through the boundary: a pair");
	two_points(rng, 2, 0, (double[]){0.1, 0.1}, (double[]){2.9, 2.9}, 0,
	           "with walls there is no wrap: opposite corners are far apart");
	two_points(rng, 2, 0, (double[]){0.5, 2.5}, (double[]){below15, 2.5}, 1,
	           "a hair closer than rc with walls is a pair");
	two_points(rng, 2, 0, (double[]){0.5, 2.5}, (double[]){1.5, 2.5}, 0,
	           "distance exactly rc with walls is not a pair");
	two_points(rng, 3, 1, (double[]){0.5, 0.5, 0.5}, (double[]){0.5, 0.5, below15}, 1,
	           "a hair closer than rc along z is a pair");
	two_points(rng, 3, 1, (double[]){0.5, 0.5, 0.5}, (double[]){0.5, 1.5, 0.5}, 0,
	           "distance exactly rc is not a pair");
	two_points(rng, 3, 1, (double[]){0.1, 0.1, 0.1}, (double[]){2.9, 2.9, 2.9}, 1,
	           "opposite corners of the box are 0.35 apart through the corner: a pair");
	two_points(rng, 3, 1, (double[]){0.1, 2.9, 1.5}, (double[]){2.9, 0.1, 1.5}, 1,
	           "x and y both wrap: 0.28 apart, a pair");
	/* Random points in the smallest periodic grids, m = 3 and w = rc. */
	random_pairs_case(rng, 2, 3.0, 1.0, 1.0, 1, LZ_CELLS_ROW, 80, 0);
	random_pairs_case(rng, 2, 3.0, 1.0, 1.0, 1, LZ_CELLS_MORTON, 80, 0);
	random_pairs_case(rng, 3, 3.0, 1.0, 1.0, 1, LZ_CELLS_MORTON, 150, 0);
	random_pairs_case(rng, 3, 3.0, 1.0, 1.0, 0, LZ_CELLS_ROW, 150, 0);
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(pairs_of_one_two_and_crowded_cells)
{
	gsl_rng *rng = lz_test_rng(410);
	double one[2] = {4.2, 7.7};
	lz_cells *c = pair_grid(rng, 2, 10, 10.0, 1, LZ_CELLS_MORTON, 400);
	pairs_case(c, one, one, 1, 1.0, NULL, 0, "a single point (N = 1): no pair");
	uint64_t key = pair_key(0, 1);
	double across_x[4] = {0.1, 5.0, 9.8, 5.2}, across_y[4] = {5.0, 9.95, 5.3, 0.05};
	double far[4] = {1.0, 1.0, 6.0, 6.0};
	pairs_case(c, across_x, across_x, 2, 1.0, &key, 1,
	           "N = 2, 0.36 apart across the periodic boundary at x = 0 = L");
	pairs_case(c, across_y, across_y, 2, 1.0, &key, 1,
	           "N = 2, 0.32 apart across the periodic boundary at y = 0 = L");
	pairs_case(c, far, far, 2, 1.0, &key, 0, "N = 2, far apart: no pair");
	double exact[4] = {0.25, 5.0, 9.25, 5.0};
	pairs_case(c, exact, exact, 2, 1.0, &key, 0, "N = 2, exactly rc apart across the periodic "
	           "boundary at x = 0 = L: no pair (distance² < rc², strictly)");
	/* 300 points in one cell, the cell (4, 7): many pairs, all in one list. */
	size_t n = 300, nwant;
	double *x = malloc(2 * n * sizeof *x);
	for (size_t i = 0; i < n; i++) {
		x[2 * i] = 4 + gsl_rng_uniform(rng);
		x[2 * i + 1] = 7 + gsl_rng_uniform(rng);
	}
	uint64_t *want = bf_pairs(x, n, 2, 10.0, 1, 1.0, &nwant);
	pairs_case(c, x, x, n, 1.0, want, nwant, "300 points all in one cell");
	free(want);
	/* 40 points within 0.05 of each other: all 780 pairs. */
	for (size_t i = 0; i < 40; i++) {
		x[2 * i] = 9.98 + 0.03 * gsl_rng_uniform(rng);
		x[2 * i + 1] = 0.01 + 0.03 * gsl_rng_uniform(rng);
	}
	want = bf_pairs(x, 40, 2, 10.0, 1, 1.0, &nwant);
	ck_assert(nwant == 780);
	pairs_case(c, x, x, 40, 1.0, want, nwant, "40 points in a tight cluster on the boundary "
	           "x = L (every pair closer than rc)");
	free(want);
	free(x);
	lz_cells_free(c);
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(pairs_count_all_even_when_out_is_too_small)
{
	gsl_rng *rng = lz_test_rng(411);
	size_t n = 500, nwant;
	double *x = malloc(2 * n * sizeof *x);
	for (size_t k = 0; k < 2 * n; k++)
		x[k] = 10 * gsl_rng_uniform(rng);
	exact_pairs(x, n, 2, 10.0, 1.0);
	uint64_t *want = bf_pairs(x, n, 2, 10.0, 1, 1.0, &nwant);
	ck_assert(nwant > 100);
	lz_cells *c = pair_grid(rng, 2, 10, 10.0, 1, LZ_CELLS_ROW, n);
	hand_bin_link(c, x, n);
	size_t cap = nwant / 3;
	lz_pair *out = malloc(nwant * sizeof *out);
	for (size_t k = 0; k < nwant; k++)
		out[k] = (lz_pair){UINT32_MAX, UINT32_MAX};
	size_t got = lz_cells_pairs(c, x, 1.0, out, cap);
	LZ_REQUIRE(got == nwant, "%zu random points with room for only %zu pairs: "
	              "lz_cells_pairs returned %zu, but there are %zu pairs — like snprintf it "
	              "must count every pair, stored or not", n, cap, got, nwant);
	for (size_t k = 0; k < nwant; k++) {
		if (k >= cap) {
			LZ_REQUIRE(out[k].i == UINT32_MAX && out[k].j == UINT32_MAX, "room for %zu "
			              "pairs, but out[%zu] was written: only the first cap pairs may be "
			              "stored (the rest of the array belongs to the caller)", cap, k);
			continue;
		}
		uint64_t key = pair_key(out[k].i, out[k].j);
		LZ_REQUIRE(out[k].i < out[k].j && bsearch(&key, want, nwant, sizeof *want, key_cmp),
		              "out[%zu] = (%u, %u) is not a pair closer than rc", k, out[k].i, out[k].j);
	}
	got = lz_cells_pairs(c, x, 1.0, NULL, 0);
	LZ_REQUIRE(got == nwant, "counting only (out = NULL, cap = 0): lz_cells_pairs returned "
	              "%zu, expected %zu", got, nwant);
	free(out);
	free(want);
	free(x);
	lz_cells_free(c);
	gsl_rng_free(rng);
}
END_TEST

/* ---- a million points: sort-and-sweep reference ---- */

typedef struct {
	double x, y;
	uint32_t id;
	int32_t strip;
} swept;

static int swept_cmp(const void *a, const void *b)
{
	const swept *p = a, *q = b;
	if (p->strip != q->strip)
		return (p->strip > q->strip) - (p->strip < q->strip);
	return (p->x > q->x) - (p->x < q->x);
}

/* The first index in a[0 .. n) with x >= v (a sorted by x), n if none. */
static size_t lower_x(const swept *a, size_t n, double v)
{
	size_t lo = 0, hi = n;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		if (a[mid].x < v)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

static double swept_d2(const swept *a, const swept *b, double L)
{
	double dx = fabs(a->x - b->x), dy = fabs(a->y - b->y);
	dx = dx > L - dx ? L - dx : dx;
	dy = dy > L - dy ? L - dy : dy;
	return dx * dx + dy * dy;
}

/* All pairs closer than rc among n points in [0, L)^2, periodic, without cells: the
 * points are cut into S horizontal strips of height >= rc and sorted by x in each;
 * a pair lies in one strip or in two consecutive ones (with wrap), and within an
 * x-window of width rc, found by walking the sorted strips (with wrap in x). */
static uint64_t *sweep_pairs(const double *xy, size_t n, double L, double rc, size_t *np)
{
	int32_t S = (int32_t)floor(L / rc) - 1;
	double h = L / S, rc2 = rc * rc;
	swept *p = malloc(n * sizeof *p);
	size_t *first = calloc((size_t)S + 1, sizeof *first), cap = n, k = 0;
	uint64_t *keys = malloc(cap * sizeof *keys);
	for (size_t i = 0; i < n; i++) {
		int32_t s = (int32_t)(xy[2 * i + 1] / h);
		p[i] = (swept){xy[2 * i], xy[2 * i + 1], (uint32_t)i, s < S ? s : S - 1};
	}
	qsort(p, n, sizeof *p, swept_cmp);
	for (size_t i = 0; i < n; i++)
		first[p[i].strip + 1]++;
	for (int32_t s = 0; s < S; s++)
		first[s + 1] += first[s];
	for (int32_t s = 0; s < S; s++) {
		const swept *A = p + first[s], *B = p + first[(s + 1) % S];
		size_t na = first[s + 1] - first[s], nb = first[(s + 1) % S + 1] - first[(s + 1) % S];
		for (size_t a = 0; a < na; a++) {
			/* the same strip: forward in x (cyclic) while dx < rc */
			for (size_t step = 1; step < na; step++) {
				const swept *q = A + (a + step) % na;
				double dx = q->x - A[a].x;
				if (dx < 0)
					dx += L;
				if (dx >= rc)
					break;
				if (swept_d2(A + a, q, L) < rc2) {
					if (k == cap)
						keys = realloc(keys, (cap *= 2) * sizeof *keys);
					keys[k++] = pair_key(A[a].id, q->id);
				}
			}
			/* the next strip: the window [x - rc, x + rc) (cyclic) */
			double lo = A[a].x - rc;
			if (lo < 0)
				lo += L;
			size_t start = lower_x(B, nb, lo);
			for (size_t step = 0; step < nb; step++) {
				const swept *q = B + (start + step) % nb;
				double dx = q->x - lo;
				if (dx < 0)
					dx += L;
				if (dx >= 2 * rc)
					break;
				if (swept_d2(A + a, q, L) < rc2) {
					if (k == cap)
						keys = realloc(keys, (cap *= 2) * sizeof *keys);
					keys[k++] = pair_key(A[a].id, q->id);
				}
			}
		}
	}
	qsort(keys, k, sizeof *keys, key_cmp);
	free(p);
	free(first);
	*np = k;
	return keys;
}

LZ_TEST(pairs_of_a_million_points)
{
	size_t n = 1000000, nwant;
	double L = 1000, rc = 1;
	gsl_rng *rng = lz_test_rng(412);
	double *x = malloc(2 * n * sizeof *x);
	for (size_t k = 0; k < 2 * n; k++)
		x[k] = L * gsl_rng_uniform(rng);
	exact_pairs(x, n, 2, L, rc);
	uint64_t *want = sweep_pairs(x, n, L, rc, &nwant);
	lz_cells *c = pair_grid(rng, 2, 1000, L, 1, LZ_CELLS_MORTON, n);
	pairs_case(c, x, x, n, rc, want, nwant, "10^6 random points in a 2D periodic box L = 1000, "
	           "rc = 1 (one point per cell on average, pairs at exactly rc and a hair closer among "
	           "them; reference: a sort-and-sweep)");
	lz_cells_free(c);
	free(want);
	free(x);
	gsl_rng_free(rng);
}
END_TEST

/* ---- the whole chain, as a user runs it ---- */

static int u32_cmp(const void *a, const void *b)
{
	uint32_t p = *(const uint32_t *)a, q = *(const uint32_t *)b;
	return (p > q) - (p < q);
}

/* Fail unless the grid lz_cells_alloc made is the header's: in Morton order the cells
 * sorted by their bit-interleaved codes (lz_morton), and every row of the block tables
 * the touching cells (lz_cells_stencil), compared as sets with a hand-made grid. */
static void check_alloc_grid(const lz_cells *c, const char *what)
{
	lz_cells *h = hand_grid(c->dim, c->m, c->side, c->periodic, c->order, 1, 0);
	char b1[64];
	int32_t cx[3] = {0, 0, 0};
	for (size_t q = 0; c->rank && q < c->ncells; q++) {
		bf_decode(c->dim, c->m, q, cx);
		LZ_REQUIRE(c->rank[q] == h->rank[q], "%s: lz_cells_alloc stored the cell %s at place %u "
		      "of the Morton order, but sorting the cells by their codes (bit b of x at bit "
		      "dim·b, then y, then z) puts it at place %u: are lz_morton's codes the "
		      "header's?", what, fmt_cell(b1, 64, c->dim, cx), c->rank[q], h->rank[q]);
	}
	hand_tables(h, NULL);
	for (int half = 0; half < 2; half++) {
		size_t w = (size_t)(half ? c->nhalf : c->nfull);
		const uint32_t *got = half ? c->half : c->full, *want = half ? h->half : h->full;
		uint32_t a[27], b[27];
		for (size_t s = 0; s < c->ncells; s++) {
			memcpy(a, got + s * w, w * sizeof *a);
			memcpy(b, want + s * w, w * sizeof *b);
			qsort(a, w, sizeof *a, u32_cmp);
			qsort(b, w, sizeof *b, u32_cmp);
			bf_coords(c, s, cx);
			for (size_t k = 0; k < w; k++)
				LZ_REQUIRE(a[k] == b[k], "%s: the %s of cell %s, as lz_cells_alloc stored it "
				      "from lz_cells_stencil, is not the set of the %s cells: sorted, "
				      "entry %zu is %u where %u was expected (%zu stands for a cell beyond "
				      "a wall)", what, half ? "half block" : "block",
				      fmt_cell(b1, 64, c->dim, cx), half ? "forward touching" : "touching",
				      k, a[k], b[k], c->ncells);
		}
	}
	lz_cells_free(h);
}

/* The cell coordinate of coordinate x by the header's rule: wrapped into [0, L) in a
 * periodic box (a wrapped value that rounds to L was a hair below it: the last cell),
 * clamped to the edge cells with walls, then floor(x / w). *face is set to the inner
 * cell face x lies within round-off of (either side is right there), else to -1. */
static int32_t bf_axis_cell(const lz_cells *c, double x, int32_t *face)
{
	double L = c->side;
	int32_t m = c->m;
	*face = -1;
	if (c->periodic) {
		x = fmod(x, L);
		if (x < 0)
			x += L;
		if (x >= L)
			return m - 1;
	} else if (x <= 0) {
		return 0;
	} else if (x >= L) {
		return m - 1;
	}
	double u = x / c->width, f = nearbyint(u);
	if (fabs(u - f) < 1e-9 && f > 0 && f < m)
		*face = (int32_t)f;
	int32_t k = (int32_t)floor(u);
	return k >= m ? m - 1 : k;
}

/* Fail unless every point sits in its cell (bf_axis_cell on each axis). */
static void check_bins(const lz_cells *c, const double *x, size_t n, const char *what)
{
	int dim = c->dim;
	char b1[64], b2[64];
	for (size_t i = 0; i < n; i++) {
		const double *p = x + i * (size_t)dim;
		int32_t got[3] = {0, 0, 0}, want[3] = {0, 0, 0};
		int ok = 1;
		bf_coords(c, c->of[i], got);
		for (int k = 0; k < dim; k++) {
			int32_t face;
			want[k] = bf_axis_cell(c, p[k], &face);
			ok &= got[k] == want[k] || (face >= 0 && (got[k] == face || got[k] == face - 1));
		}
		LZ_REQUIRE(ok, "%s: lz_cells_bin_points put point %zu at (%.17g, %.17g%s) in the cell "
		      "%s; it belongs to %s (lz_cells_of_point: floor(x / w) after wrapping into "
		      "[0, L) in a periodic box, the nearest edge cell beyond a wall, m - 1 when "
		      "round-off gives m)", what, i, p[0], p[1], dim == 3 ? ", ..." : "",
		      fmt_cell(b1, 64, dim, got), fmt_cell(b2, 64, dim, want));
	}
}

/* n points in grid c (random, the first eight on the box's edges: 0, a hair below L, L
 * itself and a hair below 0 or beyond the wall), given whole periods away when shifted,
 * else with pairs at exactly rc and a hair closer (exact_pairs): bin, link and scan
 * them with the graded functions, checking each step. */
static void pipeline_round(lz_cells *c, gsl_rng *rng, size_t n, int shifted, const char *what)
{
	int dim = c->dim;
	double L = c->side, *x = malloc(n * (size_t)dim * sizeof *x);
	ck_assert(x != NULL && n >= 8);
	for (size_t k = 0; k < n * (size_t)dim; k++)
		x[k] = gsl_rng_uniform(rng) * L;
	double edge[4] = {0.0, nextafter(L, 0), L, c->periodic ? -1e-300 : -0.25 * c->width};
	for (size_t e = 0; e < 8; e++)
		x[e * (size_t)dim + e % (size_t)dim] = edge[e / 2];
	if (shifted)
		for (size_t k = 0; k < n * (size_t)dim; k++)
			x[k] += L * (double)((long)gsl_rng_uniform_int(rng, 7) - 3);
	else
		exact_pairs(x, n, dim, L, c->cutoff);
	LZ_REQUIRE(lz_cells_bin_points(c, n, x) == LZ_OK, "%s, %zu points: lz_cells_bin_points "
	      "refused them: %s", what, n, lz_error_message());
	check_bins(c, x, n, what);
	lz_cells_link(c);
	check_links(c, what);
	size_t nwant;
	uint64_t *want = bf_pairs(x, n, dim, L, c->periodic, c->cutoff, &nwant);
	check_pairs(c, x, n, c->cutoff, want, nwant, what);
	free(want);
	free(x);
}

/* lz_cells_alloc, lz_cells_bin_points, lz_cells_link and lz_cells_pairs in a row: the
 * grid, the bins, the lists and the pairs are each checked, so this test pays only
 * when every graded function of the chain is right. Twice on each grid, the second
 * time with fewer points: binning and linking again must forget the first lists. */
LZ_TEST(pipeline_alloc_bin_link_pairs_as_a_user_does)
{
	static const struct {
		int dim;
		double L, rc;
		int periodic;
		lz_cells_order order;
		int shifted;
		size_t n;
	} cs[] = {
		{2, 10.0, 1.0, 1, LZ_CELLS_MORTON, 0, 600}, {2, 9.7, 1.3, 0, LZ_CELLS_ROW, 0, 500},
		{2, 14.6, 4.8, 1, LZ_CELLS_MORTON, 1, 120}, {2, 14.6, 4.8, 0, LZ_CELLS_MORTON, 0, 120},
		{3, 6.0, 1.0, 1, LZ_CELLS_ROW, 1, 600}, {3, 5.5, 1.1, 0, LZ_CELLS_MORTON, 0, 500},
		{3, 4.0, 1.0, 1, LZ_CELLS_MORTON, 0, 300},
	};
	gsl_rng *rng = lz_test_rng(413);
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		lz_cells *c = lz_cells_alloc(cs[k].dim, cs[k].L, cs[k].rc, cs[k].periodic, cs[k].order,
		                             cs[k].n, 0);
		LZ_REQUIRE(c != NULL, "lz_cells_alloc(%d, L = %g, rc = %g, %s, %s order): %s (it runs "
		      "lz_cells_stencil and, in Morton order, lz_morton, and checks their answers)",
		      cs[k].dim, cs[k].L, cs[k].rc, cs[k].periodic ? "periodic" : "walls",
		      order_name(cs[k].order), lz_error_message());
		char what[256];
		snprintf(what, sizeof what, "%dD %s box L = %g, grid from lz_cells_alloc for rc = %g "
		         "(%d^%d cells, %s order)%s", cs[k].dim, cs[k].periodic ? "periodic" : "walled",
		         cs[k].L, cs[k].rc, c->m, cs[k].dim, order_name(cs[k].order), cs[k].shifted ?
		         ", points given whole periods away" : "");
		check_alloc_grid(c, what);
		pipeline_round(c, rng, cs[k].n, cs[k].shifted, what);
		pipeline_round(c, rng, cs[k].n / 2, cs[k].shifted, what);
		lz_cells_free(c);
	}
	gsl_rng_free(rng);
}
END_TEST
