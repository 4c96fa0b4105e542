/* test_stage03_field.c — the library half of lz/shape.h and lz/field.h, which
 * students do not write: the input checks of lz_shape_alloc and lz_field_alloc (all
 * made before any graded code runs), the coverage, the room of the particle list,
 * the free-site scan and the site index. None of these tests calls a graded function
 * (fields are built by hand on the stack), so they pass with the stubs as well. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/field.h"
#include "lz/shape.h"
#include "lz/walk.h"
#include "lztest.h"

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
