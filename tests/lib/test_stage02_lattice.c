/* test_stage02_lattice.c — the library half of lz/lattice.h and lz/gr.h, which students
 * do not write: lattice names, direction tables, the side check, the exact integer
 * root and shell measure, and the input checks of the box and the g(r) accumulator.
 * None of these tests calls a graded function, so they pass with the stubs as well. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lz/gr.h"
#include "lz/lattice.h"
#include "lztest.h"

LZ_TEST(lattice_names_parse)
{
	for (int k = 0; k < LZ_NLATTICES; k++) {
		lz_lattice_kind got = LZ_NLATTICES;
		const char *name = lz_lattice_name((lz_lattice_kind)k);
		ck_assert_msg(lz_lattice_parse(name, &got) == LZ_OK && got == (lz_lattice_kind)k,
		              "the name '%s' does not parse back to kind %d", name, k);
	}
	lz_lattice_kind kind;
	ck_assert(lz_lattice_parse("hexagonal", &kind) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "hexagonal") && strstr(lz_error_message(),
	              "triangular"), "the message should name the bad lattice and the choices: %s",
	              lz_error_message());
	ck_assert(lz_lattice_parse(NULL, &kind) == LZ_EINVAL);
	ck_assert(lz_lattice_parse("Square", &kind) == LZ_EINVAL);
}
END_TEST

LZ_TEST(lattice_dim_and_cell_volume)
{
	static const int dims[LZ_NLATTICES] = {2, 2, 2, 3, 3, 3};
	for (int k = 0; k < LZ_NLATTICES; k++)
		ck_assert_int_eq(lz_lattice_dim((lz_lattice_kind)k), dims[k]);
	ck_assert_int_eq(lz_lattice_dim(LZ_NLATTICES), 0);
	ck_assert(lz_lattice_cell_volume(LZ_LATTICE_SQUARE) == 1.0);
	ck_assert(lz_lattice_cell_volume(LZ_LATTICE_CUBIC26) == 1.0);
	ck_assert(fabs(lz_lattice_cell_volume(LZ_LATTICE_TRIANGULAR) - 0.8660254037844386) < 1e-15);
}
END_TEST

LZ_TEST(lattice_direction_tables)
{
	/* Counts, distinct non-zero unit steps, opposite at i + n/2, the nearest shell of
	 * each lattice, and the 2D tables counterclockwise. */
	static const int want_n[LZ_NLATTICES] = {4, 8, 6, 6, 18, 26};
	for (int k = 0; k < LZ_NLATTICES; k++) {
		lz_lattice_kind kind = (lz_lattice_kind)k;
		int n;
		const lz_site *d = lz_lattice_dirs(kind, &n);
		ck_assert_msg(d && n == want_n[k], "%s: %d directions, want %d",
		              lz_lattice_name(kind), n, want_n[k]);
		int shells[4] = {0, 0, 0, 0};
		for (int i = 0; i < n; i++) {
			lz_site a = d[i], o = d[(i + n / 2) % n];
			ck_assert_msg(o.x == -a.x && o.y == -a.y && o.z == -a.z, "%s: direction %d "
			              "(%d,%d,%d) has not its opposite at %d", lz_lattice_name(kind), i,
			              a.x, a.y, a.z, (i + n / 2) % n);
			ck_assert(abs(a.x) <= 1 && abs(a.y) <= 1 && abs(a.z) <= 1);
			ck_assert(lz_lattice_dim(kind) == 3 || a.z == 0);
			int m = abs(a.x) + abs(a.y) + abs(a.z);
			ck_assert(m >= 1);
			/* The true squared length, by the lattice's own geometry. */
			int len2 = kind == LZ_LATTICE_TRIANGULAR ? a.x * a.x + a.x * a.y + a.y * a.y : m;
			ck_assert_msg(len2 < 4, "%s: direction %d is too long", lz_lattice_name(kind), i);
			shells[len2]++;
			for (int j = 0; j < i; j++)
				ck_assert_msg(memcmp(&d[j], &a, sizeof a) != 0, "%s: directions %d and %d "
				              "are the same", lz_lattice_name(kind), j, i);
			if (lz_lattice_dim(kind) == 2) {
				lz_site b = d[(i + 1) % n];
				/* Cartesian cross product of consecutive directions > 0 (sheared: the
				 * Cartesian x is x + y/2 on the triangular lattice). */
				double ax = a.x + (kind == LZ_LATTICE_TRIANGULAR ? 0.5 * a.y : 0.0);
				double bx = b.x + (kind == LZ_LATTICE_TRIANGULAR ? 0.5 * b.y : 0.0);
				ck_assert_msg(ax * b.y - a.y * bx > 0.0, "%s: directions %d and %d are not "
				              "counterclockwise", lz_lattice_name(kind), i, (i + 1) % n);
			}
		}
		ck_assert(d[0].x == 1 && d[0].y == 0 && d[0].z == 0);
		if (kind == LZ_LATTICE_TRIANGULAR)
			ck_assert_msg(shells[1] == 6, "triangular: all six neighbours at distance 1");
		if (kind >= LZ_LATTICE_CUBIC)
			ck_assert(shells[1] == 6 && shells[2] == (n >= 18 ? 12 : 0) &&
			          shells[3] == (n == 26 ? 8 : 0));
	}
	int n = 99;
	ck_assert(lz_lattice_dirs(LZ_NLATTICES, &n) == NULL && n == 0);
}
END_TEST

LZ_TEST(lattice_side_check_names_allowed_sizes)
{
	for (int64_t L = 1; L <= LZ_LATTICE_SIDE_MAX; L *= 2)
		ck_assert_msg(lz_lattice_side_check(L) == LZ_OK, "side %lld refused", (long long)L);
	static const struct { int64_t side; const char *says; } bad[] = {
		{0, "power of two"}, {-8, "-8"}, {3, "2 and 4"}, {1000, "512 and 1024"},
		{65537, "65536"}, {131072, "65536"},
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		ck_assert(lz_lattice_side_check(bad[i].side) == LZ_EINVAL);
		ck_assert_msg(strstr(lz_error_message(), bad[i].says), "side %lld: the message '%s' "
		              "should mention '%s'", (long long)bad[i].side, lz_error_message(),
		              bad[i].says);
	}
}
END_TEST

LZ_TEST(lattice_box_alloc_rejects_bad_input)
{
	ck_assert(lz_lattice_box_alloc(LZ_NLATTICES, 16) == NULL);
	ck_assert(lz_lattice_box_alloc(LZ_LATTICE_SQUARE, 12) == NULL);
	ck_assert(strstr(lz_error_message(), "8 and 16"));
	ck_assert(lz_lattice_box_alloc(LZ_LATTICE_CUBIC, 0) == NULL);
	ck_assert(lz_lattice_box_alloc(LZ_LATTICE_TRIANGULAR, 2 * LZ_LATTICE_SIDE_MAX) == NULL);
	lz_lattice_box_free(NULL);
}
END_TEST

LZ_TEST(isqrt64_exact)
{
	for (uint64_t r = 0; r < 200000; r++) {
		LZ_REQUIRE_TRUE(lz_isqrt64(r * r) == r);
		if (r > 0)
			LZ_REQUIRE_TRUE(lz_isqrt64(r * r - 1) == r - 1);
	}
	/* Near 2^64 a double cannot hold r² exactly and its root rounds either way. */
	for (uint64_t r = UINT64_C(4294967295) - 1000; r <= UINT64_C(4294967295) - 1; r++) {
		LZ_REQUIRE_TRUE(lz_isqrt64(r * r) == r);
		LZ_REQUIRE_TRUE(lz_isqrt64(r * r + 2 * r) == r);
		LZ_REQUIRE_TRUE(lz_isqrt64(r * r - 1) == r - 1);
	}
	ck_assert(lz_isqrt64(UINT64_MAX) == UINT32_MAX);
	ck_assert(lz_isqrt64((UINT64_C(1) << 52) + 1) == (UINT64_C(1) << 26));
}
END_TEST

LZ_TEST(shell_volume_exact_formula)
{
	for (int k = 0; k < 50; k++) {
		double a = M_PI * ((k + 1.0) * (k + 1.0) - (double)k * k);
		double v = 4.0 * M_PI / 3.0 * (pow(k + 1.0, 3) - pow(k, 3));
		ck_assert(fabs(lz_shell_volume(2, k) - a) < 1e-12 * a);
		ck_assert(fabs(lz_shell_volume(3, k) - v) < 1e-12 * v);
	}
}
END_TEST

LZ_TEST(gr_alloc_rejects_bad_input)
{
	/* Every check comes before the lattice points are counted. */
	ck_assert(lz_gr_alloc(LZ_NLATTICES, 64, 8, 10) == NULL);
	ck_assert(lz_gr_alloc(LZ_LATTICE_SQUARE, 48, 8, 10) == NULL);
	ck_assert(strstr(lz_error_message(), "32 and 64"));
	ck_assert(lz_gr_alloc(LZ_LATTICE_SQUARE, 64, 33, 10) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "max_r = 33") && strstr(lz_error_message(), "[1, 32]"),
	              "max_r beyond half the box: '%s'", lz_error_message());
	ck_assert(lz_gr_alloc(LZ_LATTICE_TRIANGULAR, 2, 2, 10) == NULL);
	ck_assert(lz_gr_alloc(LZ_LATTICE_CUBIC, 64, 0, 10) == NULL);
	ck_assert(lz_gr_alloc(LZ_LATTICE_CUBIC, 4096, LZ_GR_MAX_SHELLS_3D + 1, 10) == NULL);
	ck_assert(strstr(lz_error_message(), "512"));
	ck_assert(lz_gr_alloc(LZ_LATTICE_SQUARE, 16384, LZ_GR_MAX_SHELLS_2D + 1, 10) == NULL);
	ck_assert(lz_gr_alloc(LZ_LATTICE_SQUARE, 64, 8, 1) == NULL);
	ck_assert(strstr(lz_error_message(), "at least 2"));
	lz_gr_free(NULL);
}
END_TEST

LZ_TEST(gr_add_pair_bins_by_shell)
{
	/* A hand-made accumulator of 4 shells: d2 = k² opens shell k, d2 >= 16 is beyond. */
	uint32_t shell_of[16];
	uint64_t pairs[4] = {0, 0, 0, 0}, lattice[4] = {1, 8, 16, 20};
	for (int d2 = 0; d2 < 16; d2++)
		shell_of[d2] = lz_isqrt64((uint64_t)d2);
	lz_gr g = {.kind = LZ_LATTICE_SQUARE, .dim = 2, .side = 8, .nshells = 4, .n = 2,
	           .d2max = 16, .shell_of = shell_of, .pairs = pairs, .lattice = lattice};
	static const int64_t d2s[] = {0, 1, 3, 4, 8, 9, 15, 16, 25, 1000000};
	for (size_t i = 0; i < sizeof d2s / sizeof d2s[0]; i++)
		lz_gr_add_pair(&g, d2s[i]);
	lz_gr_end_sample(&g);
	ck_assert(pairs[0] == 1 && pairs[1] == 2 && pairs[2] == 2 && pairs[3] == 2);
	ck_assert(g.beyond == 3 && g.nsamples == 1);
}
END_TEST
