/* test_lattice.c — distances on the square, triangular and cubic lattices and the
 * minimum image in power-of-two boxes: exact values, the triangular formula against
 * sheared Cartesian coordinates, and every answer against a brute-force search over
 * the periodic images. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/lattice.h"

static const lz_lattice_kind all_kinds[] = {
	LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE8, LZ_LATTICE_TRIANGULAR,
	LZ_LATTICE_CUBIC, LZ_LATTICE_CUBIC18, LZ_LATTICE_CUBIC26,
};
#define NKINDS (sizeof all_kinds / sizeof all_kinds[0])

/* The test's own metric, in 64 bits: never the function under test. */
static int64_t metric(lz_lattice_kind kind, int64_t x, int64_t y, int64_t z)
{
	if (kind == LZ_LATTICE_TRIANGULAR)
		return x * x + x * y + y * y;
	if (kind >= LZ_LATTICE_CUBIC)
		return x * x + y * y + z * z;
	return x * x + y * y;
}

/* The smallest distance² over the images (d + a L) with |a| <= 2: the nearest image
 * of a displacement already in (-2L, 2L) is among them. */
static int64_t brute_min(lz_lattice_kind kind, int64_t L, int64_t dx, int64_t dy, int64_t dz)
{
	int three = kind >= LZ_LATTICE_CUBIC;
	int64_t best = INT64_MAX;
	for (int a = -2; a <= 2; a++)
		for (int b = -2; b <= 2; b++)
			for (int c = three ? -2 : 0; c <= (three ? 2 : 0); c++) {
				int64_t d = metric(kind, dx + a * L, dy + b * L, three ? dz + c * L : 0);
				if (d < best)
					best = d;
			}
	return best;
}

/* A box built here, the table by the test's own rule, so that min_dist2 is tested
 * apart from lz_lattice_dctable. */
static lz_lattice_box *box_by_hand(lz_lattice_kind kind, int32_t L)
{
	lz_lattice_box *b = malloc(sizeof *b);
	b->kind = kind;
	b->dim = kind >= LZ_LATTICE_CUBIC ? 3 : 2;
	b->side = L;
	b->mask = L - 1;
	b->dc = malloc((size_t)L * sizeof *b->dc);
	for (int32_t u = 0; u < L; u++)
		b->dc[u] = 2 * u <= L ? u : u - L;
	return b;
}

LZ_TEST(dist2_square_and_cubic_exact)
{
	static const struct { int32_t x, y, z; int64_t sq, cu; } cases[] = {
		{0, 0, 0, 0, 0}, {1, 0, 0, 1, 1}, {0, -1, 0, 1, 1}, {1, 1, 0, 2, 2},
		{3, 4, 0, 25, 25}, {-3, 4, 12, 25, 169}, {1, 1, 1, 2, 3}, {-2, -2, -1, 8, 9},
		{0, 0, 7, 0, 49}, {100, -200, 300, 50000, 140000},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		int32_t x = cases[i].x, y = cases[i].y, z = cases[i].z;
		for (size_t k = 0; k < NKINDS; k++) {
			lz_lattice_kind kind = all_kinds[k];
			if (kind == LZ_LATTICE_TRIANGULAR)
				continue;
			int64_t want = kind >= LZ_LATTICE_CUBIC ? cases[i].cu : cases[i].sq;
			int64_t got = lz_lattice_dist2(kind, x, y, z);
			ck_assert_msg(got == want, "%s lattice: distance² of (%d, %d, %d) is %" PRId64
			              ", got %" PRId64 " — dx² + dy² in 2D (dz is ignored there), "
			              "dx² + dy² + dz² in 3D; square8 and cubic18/26 are the same "
			              "lattices as square and cubic", lz_lattice_name(kind), x, y, z,
			              want, got);
		}
	}
}
END_TEST

LZ_TEST(dist2_triangular_matches_sheared_cartesian)
{
	/* Site (i, j) is at (i + j/2, j √3/2): the squared Cartesian length, an integer. */
	static const struct { int32_t x, y; int64_t d2; } known[] = {
		{1, 0, 1}, {0, 1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 3}, {2, -1, 3},
		{2, 0, 4}, {2, 1, 7}, {3, -5, 19}, {-4, -4, 48},
	};
	for (size_t i = 0; i < sizeof known / sizeof known[0]; i++) {
		int64_t got = lz_lattice_dist2(LZ_LATTICE_TRIANGULAR, known[i].x, known[i].y, 0);
		ck_assert_msg(got == known[i].d2, "triangular lattice: distance² of (%d, %d) is %"
		              PRId64 ", got %" PRId64 " — in sheared coordinates it is dx² + dx·dy "
		              "+ dy² (the six neighbours (±1,0), (0,±1), ±(1,-1) all at 1)",
		              known[i].x, known[i].y, known[i].d2, got);
	}
	/* Far displacements, beyond 32-bit products: 4 d² = (2dx + dy)² + 3 dy² holds
	 * exactly in 64 bits for these. */
	static const int32_t far[][2] = {{65536, 32768}, {-40000, 50000}, {46341, -1},
	                                 {1 << 29, 1 << 29}, {1 << 29, -(1 << 28)},
	                                 {-(1 << 29), (1 << 29) - 1}};
	for (size_t i = 0; i < sizeof far / sizeof far[0]; i++) {
		int64_t x = far[i][0], y = far[i][1], want = ((2 * x + y) * (2 * x + y) + 3 * y * y) / 4;
		int64_t got = lz_lattice_dist2(LZ_LATTICE_TRIANGULAR, far[i][0], far[i][1], 0);
		ck_assert_msg(got == want, "triangular lattice: distance² of (%d, %d) is %" PRId64
		              ", got %" PRId64 " — widen to int64_t before multiplying", far[i][0],
		              far[i][1], want, got);
	}
	for (int32_t x = -30; x <= 30; x++)
		for (int32_t y = -30; y <= 30; y++) {
			double cx = x + 0.5 * y, cy = 0.5 * sqrt(3.0) * y;
			double want = cx * cx + cy * cy;
			int64_t got = lz_lattice_dist2(LZ_LATTICE_TRIANGULAR, x, y, 7);
			LZ_REQUIRE(fabs((double)got - want) < 1e-9 * (1.0 + want), "triangular "
			           "lattice: (%d, %d) is at Cartesian distance² %.6f, got %" PRId64
			           " (with dz = 7, which a 2D lattice must ignore) — is the sign of "
			           "the cross term dx·dy right?", x, y, want, got);
		}
}
END_TEST

LZ_TEST(dist2_no_overflow_at_largest_box)
{
	/* Half the largest box, and far beyond: 32-bit products wrap here. */
	const int32_t h = LZ_LATTICE_SIDE_MAX / 2, big = INT32_C(1) << 30;
	int32_t vals[] = {h, -h, big, -big};
	for (size_t a = 0; a < 4; a++)
		for (size_t b = 0; b < 4; b++)
			for (size_t k = 0; k < NKINDS; k++) {
				lz_lattice_kind kind = all_kinds[k];
				int32_t x = vals[a], y = vals[b], z = vals[(a + b) % 4];
				int64_t want = metric(kind, x, y, z), got = lz_lattice_dist2(kind, x, y, z);
				ck_assert_msg(got == want, "%s lattice: distance² of (%d, %d, %d) is %"
				              PRId64 ", got %" PRId64 " — form the products in int64_t: "
				              "(int64_t)dx * dx, not dx * dx in 32 bits",
				              lz_lattice_name(kind), x, y, z, want, got);
			}
}
END_TEST

LZ_TEST(dctable_is_the_saw_tooth)
{
	/* Thesis fig. 2.16, L = 16: 0..8 then -7..-1. */
	static const int32_t fig216[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, -7, -6, -5, -4, -3, -2, -1};
	int32_t dc[16];
	ck_assert_msg(lz_lattice_dctable(16, dc) == LZ_OK, "lz_lattice_dctable refused side 16: "
	              "%s", lz_error_message());
	for (int u = 0; u < 16; u++)
		ck_assert_msg(dc[u] == fig216[u], "side 16: dc[%d] = %d, expected %d (thesis fig. "
		              "2.16: u up to L/2 = 8 stays, above it u - L)", u, dc[u], fig216[u]);
	/* Every side: dc[u] ≡ u mod L, in (-L/2, L/2], so it is the nearest image. */
	int32_t *t = malloc(LZ_LATTICE_SIDE_MAX * sizeof *t);
	for (int64_t L = 1; L <= LZ_LATTICE_SIDE_MAX; L *= 2) {
		ck_assert_msg(lz_lattice_dctable(L, t) == LZ_OK, "lz_lattice_dctable refused side "
		              "%" PRId64 ", a power of two: %s", L, lz_error_message());
		for (int64_t u = 0; u < L; u++) {
			int64_t d = t[u];
			LZ_REQUIRE(((d - u) % L) == 0 && 2 * d <= L && 2 * d > -L, "side %" PRId64
			           ": dc[%" PRId64 "] = %" PRId64 " — it must be u or u - L, "
			           "whichever is in (-L/2, L/2]", L, u, d);
		}
	}
	free(t);
}
END_TEST

LZ_TEST(dctable_extremes_side_two_and_largest)
{
	int32_t two[2] = {99, 99};
	ck_assert_msg(lz_lattice_dctable(2, two) == LZ_OK && two[0] == 0 && two[1] == 1,
	              "side 2: the table must be {0, 1} (1 = L/2 keeps its sign), got {%d, %d}",
	              two[0], two[1]);
	const int32_t L = LZ_LATTICE_SIDE_MAX;
	int32_t *t = malloc((size_t)L * sizeof *t);
	ck_assert_msg(lz_lattice_dctable(L, t) == LZ_OK, "the largest side %d was refused: %s",
	              L, lz_error_message());
	ck_assert_msg(t[L - 1] == -1 && t[L / 2] == L / 2 && t[L / 2 + 1] == -(L / 2 - 1),
	              "side %d: at the mask boundary dc[L-1] = %d (want -1), dc[L/2] = %d (want "
	              "%d), dc[L/2+1] = %d (want %d)", L, t[L - 1], t[L / 2], L / 2, t[L / 2 + 1],
	              -(L / 2 - 1));
	free(t);
}
END_TEST

LZ_TEST(dctable_rejects_bad_sides)
{
	static const int64_t bad[] = {0, -4, 3, 12, 100, 1000, 65535, 2 * LZ_LATTICE_SIDE_MAX,
	                              INT64_C(1) << 40};
	int32_t guard[4] = {7, 7, 7, 7};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		int status = lz_lattice_dctable(bad[i], guard);
		ck_assert_msg(status == LZ_EINVAL, "lz_lattice_dctable(%" PRId64 ") returned %d; a side "
		              "that is not a power of two in [1, %d] must give LZ_EINVAL (masks wrap "
		              "wrongly otherwise) — lz_lattice_side_check says it in words",
		              bad[i], status, LZ_LATTICE_SIDE_MAX);
		ck_assert_msg(strlen(lz_error_message()) > 0, "side %" PRId64 " was refused without "
		              "a message: report it with lz_error (lz_lattice_side_check)", bad[i]);
		ck_assert_msg(guard[0] == 7 && guard[3] == 7, "side %" PRId64 " was refused but the "
		              "table was written: check the side before touching dc", bad[i]);
	}
	/* The allowed sides next to the refused ones are accepted and filled: u up to L/2
	 * stays, above it u - L (the smallest, 1 and 2, by hand: {0} and {0, 1}). */
	static const int64_t good[] = {1, 2, 4, 16, 64, 128, 65536};
	int32_t *t = malloc(LZ_LATTICE_SIDE_MAX * sizeof *t);
	for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
		int64_t L = good[i];
		ck_assert_msg(lz_lattice_dctable(L, t) == LZ_OK, "lz_lattice_dctable refused side %"
		              PRId64 ", a power of two in [1, %d]: %s", L, LZ_LATTICE_SIDE_MAX,
		              lz_error_message());
		for (int64_t u = 0; u < L; u++)
			LZ_REQUIRE(t[u] == (2 * u <= L ? u : u - L), "side %" PRId64 ", next to a refused "
			           "side: dc[%" PRId64 "] = %d, expected %" PRId64, L, u, t[u],
			           2 * u <= L ? u : u - L);
	}
	free(t);
}
END_TEST

static void min_image_against_brute_force(lz_lattice_kind kind, int32_t L, const char *hint)
{
	lz_lattice_box *b = box_by_hand(kind, L);
	int three = kind >= LZ_LATTICE_CUBIC;
	int32_t zlo = three ? -L : 0, zhi = three ? L - 1 : 0;
	for (int32_t x = -L; x < L; x++)
		for (int32_t y = -L; y < L; y++)
			for (int32_t z = zlo; z <= zhi; z++) {
				int64_t want = brute_min(kind, L, x, y, z);
				int64_t got = lz_lattice_min_dist2(b, x, y, z);
				LZ_REQUIRE(got == want, "%s lattice, box side %d: the nearest image of "
				           "(%d, %d, %d) is at distance² %" PRId64 ", got %" PRId64 " — %s",
				           lz_lattice_name(kind), L, x, y, z, want, got, hint);
			}
	lz_lattice_box_free(b);
}

LZ_TEST(min_image_square_cubic_brute_force)
{
	const char *hint = "mask each component ((uint32_t)d & mask, negative d too) and look "
	                   "it up in b->dc before squaring";
	for (int32_t L = 2; L <= 32; L *= 2) {
		min_image_against_brute_force(LZ_LATTICE_SQUARE, L, hint);
		min_image_against_brute_force(LZ_LATTICE_SQUARE8, L, hint);
		if (L <= 16) {
			min_image_against_brute_force(LZ_LATTICE_CUBIC, L, hint);
			min_image_against_brute_force(LZ_LATTICE_CUBIC26, L, hint);
		}
	}
}
END_TEST

LZ_TEST(min_image_triangular_exact_hexagon)
{
	/* The component-wise table alone fails here first: (L/2, L/4) in a box of side L
	 * has the nearer image (-L/2, L/4) (thesis fig. 2.15). */
	const char *hint = "after the table, when dx and dy have the same sign the images "
	                   "(dx ∓ L, dy) and (dx, dy ∓ L) can be nearer — the nearest-image "
	                   "region of the rhombus is a hexagon, not a sheared square";
	for (int32_t L = 1; L <= 64; L *= 2)
		min_image_against_brute_force(LZ_LATTICE_TRIANGULAR, L, hint);
}
END_TEST

LZ_TEST(min_image_largest_box_and_mask_boundary)
{
	/* Raw displacements at the mask boundary and far outside the box, every kind. */
	const int32_t L = LZ_LATTICE_SIDE_MAX, h = L / 2;
	const int32_t raw[] = {0, 1, -1, h, -h, h + 1, -(h + 1), L - 1, -(L - 1), L, -L,
	                       3 * L + 5, INT32_MIN, INT32_MAX, h / 2, -(h / 2) - 3};
	const size_t nraw = sizeof raw / sizeof raw[0];
	for (size_t k = 0; k < NKINDS; k++) {
		lz_lattice_box *b = box_by_hand(all_kinds[k], L);
		for (size_t i = 0; i < nraw; i++)
			for (size_t j = 0; j < nraw; j++) {
				int32_t x = raw[i], y = raw[j], z = raw[(i + 2 * j) % nraw];
				/* Reduce into (-L, L) first with exact arithmetic, then search. */
				int64_t want = brute_min(all_kinds[k], L, (int64_t)x % L, (int64_t)y % L,
				                         (int64_t)z % L);
				int64_t got = lz_lattice_min_dist2(b, x, y, z);
				LZ_REQUIRE(got == want, "%s lattice, box side %d: the raw displacement "
				           "(%d, %d, %d) has nearest-image distance² %" PRId64 ", got %"
				           PRId64 " — mask with (uint32_t) so that negative and huge "
				           "differences wrap, and square in int64_t",
				           lz_lattice_name(all_kinds[k]), L, x, y, z, want, got);
				int64_t back = lz_lattice_min_dist2(b, x == INT32_MIN ? 0 : -x,
				                                    y == INT32_MIN ? 0 : -y,
				                                    z == INT32_MIN ? 0 : -z);
				LZ_REQUIRE(back == got, "%s lattice: the displacement (%d, %d, %d) and its "
				           "reverse give distances² %" PRId64 " and %" PRId64 "; a pair is "
				           "as far from one end as from the other",
				           lz_lattice_name(all_kinds[k]), x, y, z, got, back);
			}
		lz_lattice_box_free(b);
	}
}
END_TEST

LZ_TEST(min_image_random_pairs_large_triangular_box)
{
	/* 1024-sided rhombus, random site pairs: exact against all images. */
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 2402);
	const int32_t L = 1024;
	lz_lattice_box *b = box_by_hand(LZ_LATTICE_TRIANGULAR, L);
	for (int t = 0; t < 200000; t++) {
		int32_t x1 = (int32_t)gsl_rng_uniform_int(rng, L), y1 = (int32_t)gsl_rng_uniform_int(rng, L);
		int32_t x2 = (int32_t)gsl_rng_uniform_int(rng, L), y2 = (int32_t)gsl_rng_uniform_int(rng, L);
		int64_t want = brute_min(LZ_LATTICE_TRIANGULAR, L, x1 - x2, y1 - y2, 0);
		int64_t got = lz_lattice_min_dist2(b, x1 - x2, y1 - y2, 0);
		LZ_REQUIRE(got == want, "triangular lattice, box side %d: sites (%d, %d) and (%d, "
		           "%d) are at nearest-image distance² %" PRId64 ", got %" PRId64 " — a "
		           "pair across the long diagonal of the rhombus needs the hexagon "
		           "correction", L, x1, y1, x2, y2, want, got);
	}
	lz_lattice_box_free(b);
	gsl_rng_free(rng);
}
END_TEST
