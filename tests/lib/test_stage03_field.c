/* test_stage03_field.c — the library half of lz/shape.h, lz/field.h and lz/well.h,
 * which students do not write: the input checks of lz_shape_alloc, lz_field_alloc,
 * lz_field_alloc_in and lz_well_alloc (all made before any graded code runs), the
 * coverage, the room of the particle list, the free-site scan and the site index.
 * These call no graded function (fields are built by hand on the stack), so they
 * pass with the stubs as well. The last tests build real fields, so they run the
 * graded code too (the reference, as this suite always does in `make check`): a box
 * inside a larger allocated lattice is the same simulation, and the largest fields
 * allowed are allocated and used. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/field.h"
#include "lz/shape.h"
#include "lz/walk.h"
#include "lz/well.h"
#include "lztest.h"
#include "support.h"

LZ_TEST(shape_alloc_rejects_bad_input)
{
	ck_assert(lz_shape_alloc(LZ_NLATTICES, 2) == NULL);
	ck_assert(lz_shape_alloc(LZ_LATTICE_SQUARE, 0) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "positive"), "%s", lz_error_message());
	ck_assert(lz_shape_alloc(LZ_LATTICE_SQUARE, -1.5) == NULL);
	ck_assert(lz_shape_alloc(LZ_LATTICE_SQUARE, NAN) == NULL);
	ck_assert(lz_shape_alloc(LZ_LATTICE_SQUARE, INFINITY) == NULL);
	ck_assert(lz_shape_alloc(LZ_LATTICE_CUBIC, 200) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "too large") && strstr(lz_error_message(), "127"),
	              "a 3D shape beyond the box limit should say the largest radius: %s",
	              lz_error_message());
	ck_assert(lz_shape_alloc(LZ_LATTICE_SQUARE, 3000) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "2047"), "%s", lz_error_message());
}
END_TEST

LZ_TEST(field_alloc_rejects_bad_input)
{
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 48, 2) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "48"), "the message should name the side: %s",
	              lz_error_message());
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 1, 0.2) == NULL);
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 0, 1) == NULL);
	ck_assert(lz_field_alloc(LZ_NLATTICES, 64, 1) == NULL);
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 64, 0) == NULL);
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 64, -2) == NULL);
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 64, NAN) == NULL);
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 64, 16.5) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "too large") && strstr(lz_error_message(), "R <= 16"),
	              "the radius limit should give the allowed range: %s", lz_error_message());
	ck_assert(lz_field_alloc(LZ_LATTICE_CUBIC, 2048, 2) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "L <= 1024"), "a field beyond 2^30 sites "
	              "should say the largest side: %s", lz_error_message());
	ck_assert(lz_field_alloc(LZ_LATTICE_SQUARE, 65536, 2) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "L <= 32768"), "%s", lz_error_message());
}
END_TEST

LZ_TEST(field_coverage_is_the_packing_fraction)
{
	lz_field f = {.kind = LZ_LATTICE_SQUARE, .dim = 2, .side = 64, .radius = 2, .n = 100};
	ck_assert(fabs(lz_field_coverage(&f) - 400 * M_PI / 4096) < 1e-15);
	f.kind = LZ_LATTICE_TRIANGULAR;
	ck_assert(fabs(lz_field_coverage(&f) - 400 * M_PI / (4096 * sqrt(3) / 2)) < 1e-14);
	lz_field g = {.kind = LZ_LATTICE_CUBIC, .dim = 3, .side = 16, .radius = 1, .n = 3};
	ck_assert(fabs(lz_field_coverage(&g) - lz_walk_packing(LZ_LATTICE_CUBIC, 16, 1, 3)) < 1e-15);
	g.n = 0;
	ck_assert(lz_field_coverage(&g) == 0);
}
END_TEST

LZ_TEST(field_index_reserve_and_free_scan)
{
	/* The index is x | y << shift | z << 2 shift, every coordinate wrapped. */
	lz_field f = {.kind = LZ_LATTICE_CUBIC, .dim = 3, .side = 8, .mask = 7, .shift = 3,
	              .nsites = 512};
	ck_assert(lz_field_index(&f, 1, 2, 3) == 1 + 2 * 8 + 3 * 64);
	ck_assert(lz_field_index(&f, -1, 8, 17) == 7 + 0 * 8 + 1 * 64);
	f.dim = 2;
	ck_assert(lz_field_index(&f, 9, -1, 5) == 1 + 7 * 8);
	f.dim = 3;
	uint8_t cell[512] = {0};
	f.cell = cell;
	ck_assert(lz_field_count_free(&f) == 512);
	cell[0] = 1;
	cell[511] = 255;
	ck_assert(lz_field_count_free(&f) == 510);
	ck_assert(lz_field_reserve(&f, 0) == LZ_OK && f.cap == 0);
	ck_assert(lz_field_reserve(&f, 1) == LZ_OK && f.cap >= 1 && f.r);
	ck_assert(lz_field_reserve(&f, 1000) == LZ_OK && f.cap >= 1000);
	f.r[3 * 999 + 2] = 42;  /* the whole room is writable (ASan checks) */
	free(f.r);
}
END_TEST


LZ_TEST(well_alloc_rejects_bad_input)
{
	/* Hand-made fields (R = 2, L = 32 and 16): every check runs before graded code. */
	lz_field f = {.kind = LZ_LATTICE_SQUARE, .dim = 2, .side = 32, .mask = 31, .shift = 5,
	              .nsites = 1024, .radius = 2};
	lz_field small = f;
	small.side = 16;
	small.mask = 15;
	lz_test_clear_error();
	static const struct { double lambda, depth, T; const char *says; } bad[] = {
		{1, 1, 1, "lambda = 1:"}, {0.5, 1, 1, "lambda = 0.5"}, {3.01, 1, 1, "lambda = 3.01"},
		{NAN, 1, 1, "lambda = nan"}, {INFINITY, 1, 1, "lambda = inf"},
		{1.5, -1, 1, "depth = -1"}, {1.5, NAN, 1, "depth = nan"},
		{1.5, INFINITY, 1, "depth = inf"}, {1.5, 1, 0, "temperature = 0"},
		{1.5, 1, -2, "temperature = -2"}, {1.5, 1, NAN, "temperature = nan"},
		{1.5, 1, INFINITY, "temperature = inf"},
	};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		char call[128];
		snprintf(call, sizeof call, "lz_well_alloc(lambda = %g, depth = %g, T = %g)",
		         bad[k].lambda, bad[k].depth, bad[k].T);
		lz_test_refused(lz_well_alloc(&f, bad[k].lambda, bad[k].depth, bad[k].T) == NULL,
		                call, bad[k].says, NULL);
	}
	ck_assert_msg(strstr(lz_error_message(), "positive"), "%s", lz_error_message());
	lz_test_refused(lz_well_alloc(&f, 0.9, 1, 1) == NULL, "lambda 0.9", "(1, 3]", NULL);
	/* rw = 2.5 · 4 = 10: 2·rw = 20 > L = 16. The largest λ here is 16 / 8 = 2. */
	lz_test_refused(lz_well_alloc(&small, 2.5, 1, 1) == NULL,
	                "a well wider than half the box", "lambda <= 2", NULL);
	ck_assert_msg(strstr(lz_error_message(), "rw = 10"), "%s", lz_error_message());
	lz_test_refused(lz_well_alloc(NULL, 2, 1, 1) == NULL, "lz_well_alloc(NULL, ...)",
	                "NULL", NULL);
	lz_well_free(NULL);
}
END_TEST

LZ_TEST(field_alloc_in_rejects_bad_pitch)
{
	lz_test_clear_error();
	lz_test_refused(lz_field_alloc_in(LZ_LATTICE_SQUARE, 32, 2, 16) == NULL,
	                "pitch below L", "pitch = 16", NULL);
	ck_assert_msg(strstr(lz_error_message(), "L = 32"), "%s", lz_error_message());
	lz_test_refused(lz_field_alloc_in(LZ_LATTICE_SQUARE, 32, 2, 48) == NULL,
	                "pitch not a power of two", "pitch = 48", NULL);
	lz_test_refused(lz_field_alloc_in(LZ_LATTICE_SQUARE, 32, 2, 0) == NULL, "pitch 0",
	                "pitch = 0", NULL);
	lz_test_refused(lz_field_alloc_in(LZ_LATTICE_SQUARE, 32, 2, -64) == NULL,
	                "a negative pitch", "pitch = -64", NULL);
	lz_test_refused(lz_field_alloc_in(LZ_LATTICE_SQUARE, 64, 2, 65536) == NULL,
	                "2D pitch beyond 2^30 sites", "pitch <= 32768", NULL);
	lz_test_refused(lz_field_alloc_in(LZ_LATTICE_CUBIC, 16, 2, 2048) == NULL,
	                "3D pitch beyond 2^30 sites", "pitch <= 1024", NULL);
}
END_TEST


/* Run RSA to `target` on both fields from the same seed; fail unless they agree. */
static void rsa_both(lz_field *f, lz_field *g, unsigned long seed, size_t target)
{
	gsl_rng *a = lz_test_rng(seed), *b = lz_test_rng(seed);
	int ja = -1, jb = -1;
	ck_assert(lz_field_rsa(f, a, target, &ja) == LZ_OK && lz_field_rsa(g, b, target, &jb) == LZ_OK);
	ck_assert_msg(f->n == g->n && ja == jb && f->nfree == g->nfree && f->tries == g->tries,
	              "%s L = %d: RSA in a box of pitch %d placed %zu particles (nfree %zu, %llu "
	              "draws), the plain box %zu (nfree %zu, %llu draws), from the same seed",
	              lz_lattice_name(f->kind), (int)f->side, 1 << g->shift, g->n, g->nfree,
	              (unsigned long long)g->tries, f->n, f->nfree, (unsigned long long)f->tries);
	ck_assert_msg(memcmp(f->r, g->r, f->n * (size_t)f->dim * sizeof *f->r) == 0,
	              "RSA in a larger lattice put the particles elsewhere");
	ck_assert_msg(lz_field_count_free(g) == g->nfree, "a scan of the larger lattice finds "
	              "%zu free sites, nfree says %zu", lz_field_count_free(g), g->nfree);
	gsl_rng_free(a);
	gsl_rng_free(b);
}

/* The same Metropolis walk with a square well on both fields, from the same seed. */
static void walk_both(lz_field *f, lz_field *g, unsigned long seed)
{
	lz_well *wf = lz_well_alloc(f, 1.5, 1, 0.8), *wg = lz_well_alloc(g, 1.5, 1, 0.8);
	ck_assert_msg(wf && wg, "lz_well_alloc: %s", lz_error_message());
	ck_assert(lz_well_energy(wf, f) == lz_well_energy(wg, g));
	gsl_rng *a = lz_test_rng(seed), *b = lz_test_rng(seed);
	for (int t = 0; t < 20000; t++) {
		size_t i = gsl_rng_uniform_int(a, f->n);
		int d = (int)gsl_rng_uniform_int(a, (unsigned long)f->excl->ndir);
		gsl_rng_uniform_int(b, g->n);
		gsl_rng_uniform_int(b, (unsigned long)g->excl->ndir);
		LZ_REQUIRE_TRUE(lz_field_try_move(f, wf, i, d, a) == lz_field_try_move(g, wg, i, d, b));
	}
	ck_assert_msg(memcmp(f->r, g->r, f->n * (size_t)f->dim * sizeof *f->r) == 0 &&
	              lz_well_energy(wf, f) == lz_well_energy(wg, g) && f->nfree == g->nfree,
	              "%s: the same Metropolis walk in a larger lattice ended elsewhere",
	              lz_lattice_name(f->kind));
	lz_well_free(wf);
	lz_well_free(wg);
	gsl_rng_free(a);
	gsl_rng_free(b);
}

/* lz_well_alloc paints the wells of the particles already in the field: every site
 * counts the centres within rw (strict, minimum image), checked by brute force on a
 * square lattice with pairs inside, on and beyond the well's edge and across the box
 * edge; the energy is then -ε times the pairs with d < rw. */
LZ_TEST(well_alloc_paints_the_particles_already_there)
{
	static const int32_t at[][2] = {{10, 10}, {16, 10}, {10, 15}, {40, 40}, {47, 40},
	                                {62, 5}, {3, 5}, {30, 62}, {30, 3}};
	const size_t n = sizeof at / sizeof at[0];
	const int32_t L = 64;
	lz_field *f = lz_field_alloc(LZ_LATTICE_SQUARE, L, 2);
	ck_assert_msg(f, "%s", lz_error_message());
	for (size_t i = 0; i < n; i++)
		ck_assert_msg(lz_field_place(f, (lz_site){at[i][0], at[i][1], 0}) == LZ_OK,
		              "placing (%d, %d): %s", at[i][0], at[i][1], lz_error_message());
	lz_well *w = lz_well_alloc(f, 1.5, 1, 1);  /* rw = 6 */
	ck_assert_msg(w, "%s", lz_error_message());
	size_t pairs = 0;
	for (int32_t x = 0; x < L; x++)
		for (int32_t y = 0; y < L; y++) {
			int want = 0;
			for (size_t i = 0; i < n; i++) {
				int32_t dx = abs(x - at[i][0]), dy = abs(y - at[i][1]);
				dx = dx > L / 2 ? L - dx : dx;
				dy = dy > L / 2 ? L - dy : dy;
				want += dx * dx + dy * dy < 36;
			}
			int got = w->cell[lz_field_index(f, x, y, 0)];
			LZ_REQUIRE(got == want, "site (%d, %d) lies in %d wells of radius 6, the well "
			           "field says %d", x, y, want, got);
		}
	for (size_t i = 0; i < n; i++)
		pairs += w->cell[lz_field_index(f, at[i][0], at[i][1], 0)] - 1;
	/* Inside: (10,10)-(10,15) at 5, and across the edge (62,5)-(3,5) and
	 * (30,62)-(30,3) at 5; (10,10)-(16,10) at exactly 6 and (40,40)-(47,40) are out. */
	ck_assert_msg(pairs == 2 * 3, "the centres see %zu partners in their wells, expected "
	              "6 (3 pairs)", pairs);
	ck_assert_msg(lz_well_energy(w, f) == -(double)pairs / 2, "E = %g for %zu pairs",
	              lz_well_energy(w, f), pairs / 2);
	lz_well_free(w);
	lz_field_free(f);
}
END_TEST

LZ_TEST(field_in_a_larger_lattice_is_the_same_simulation)
{
	static const struct { lz_lattice_kind kind; int L; double R; } pc[] = {
		{LZ_LATTICE_SQUARE, 64, 2}, {LZ_LATTICE_TRIANGULAR, 32, 1.5}, {LZ_LATTICE_CUBIC, 16, 1.2},
	};
	for (size_t k = 0; k < sizeof pc / sizeof pc[0]; k++) {
		int L = pc[k].L, P = 4 * L;
		lz_field *f = lz_field_alloc(pc[k].kind, L, pc[k].R);
		lz_field *g = lz_field_alloc_in(pc[k].kind, L, pc[k].R, P);
		LZ_REQUIRE(f && g, "%s", lz_error_message());
		size_t box = f->nsites, fenced = 0;
		LZ_REQUIRE(g->nsites == box * (f->dim == 3 ? 64 : 16) && g->nfree == box,
		              "pitch 4L: %zu sites allocated (expected %zu), %zu free (expected the "
		              "box's %zu)", g->nsites, box * (f->dim == 3 ? 64 : 16), g->nfree, box);
		for (size_t s = 0; s < g->nsites; s++)
			fenced += g->cell[s] == 255;
		LZ_REQUIRE(fenced == g->nsites - box, "%zu sites hold 255, expected the %zu "
		              "outside the box", fenced, g->nsites - box);
		rsa_both(f, g, 61 + k, box / 400);
		rsa_both(f, g, 67 + k, 0);
		walk_both(f, g, 71 + k);
		lz_field_free(f);
		lz_field_free(g);
	}
}
END_TEST

/* The largest field of `kind` (2^30 sites, 1 GiB: calloc hands out untouched pages, so
 * this is fast) with one particle on the far corner, whose shape wraps round to the
 * origin; then the next power of two is refused, naming the limit. */
static void largest(lz_lattice_kind kind, int64_t L, const char *limit)
{
	lz_field *f = lz_field_alloc(kind, L, 2);
	ck_assert_msg(f != NULL, "%s L = %lld is within 2^30 sites and must be allowed: %s",
	              lz_lattice_name(kind), (long long)L, lz_error_message());
	ck_assert(f->nsites == (size_t)1 << 30 && f->nfree == f->nsites);
	int32_t c = (int32_t)(L - 1);
	ck_assert(lz_field_place(f, (lz_site){c, c, f->dim == 3 ? c : 0}) == LZ_OK);
	ck_assert_msg(f->nfree == f->nsites - f->excl->n, "one particle in the largest field: "
	              "nfree = %zu, expected %zu", f->nfree, f->nsites - f->excl->n);
	ck_assert_msg(f->cell[0] == 1 && f->cell[lz_field_index(f, c, c, c)] == 1,
	              "the corner particle must cover its own site and, wrapped, the origin");
	ck_assert(lz_field_remove(f, 0) == LZ_OK && f->nfree == f->nsites && f->cell[0] == 0);
	lz_field_free(f);
	lz_test_refused(lz_field_alloc(kind, 2 * L, 2) == NULL, "the next power of two", limit,
	                NULL);
}

LZ_TEST(field_size_limits)
{
	lz_test_clear_error();
	largest(LZ_LATTICE_SQUARE, 32768, "L <= 32768");
	largest(LZ_LATTICE_CUBIC, 1024, "L <= 1024");
}
END_TEST
