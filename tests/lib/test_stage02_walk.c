/* test_stage02_walk.c — the library half of lz/walk.h and the `walk` method, which
 * students do not write: the packing fraction, the input checks of lz_walk_alloc
 * (all made before any graded code runs) and the scene checks of method walk. None
 * of these tests calls a graded function, so they pass with the stubs as well. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lz/lattice.h"
#include "method.h"
#include "scene.h"
#include "lz/profile.h"
#include "lz/walk.h"
#include "lztest.h"
#include "support.h"

LZ_TEST(walk_packing_fraction)
{
	/* 100 disks of R = 2 on 64² square sites: 100·4π/4096. */
	ck_assert(fabs(lz_walk_packing(LZ_LATTICE_SQUARE, 64, 2, 100) - 400 * M_PI / 4096) < 1e-15);
	/* Triangular sites own √3/2 each. */
	ck_assert(fabs(lz_walk_packing(LZ_LATTICE_TRIANGULAR, 64, 2, 100) -
	               400 * M_PI / (4096 * sqrt(3) / 2)) < 1e-14);
	ck_assert(fabs(lz_walk_packing(LZ_LATTICE_CUBIC, 16, 1, 3) - 4 * M_PI / 4096) < 1e-15);
	ck_assert(isnan(lz_walk_packing(LZ_NLATTICES, 16, 1, 3)));
}
END_TEST

LZ_TEST(walk_alloc_rejects_bad_input)
{
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 100, 2, 10, LZ_WALK_RANDOM) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "100"), "the message should name the side: %s",
	              lz_error_message());
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 1, 0.2, 1, LZ_WALK_RANDOM) == NULL);
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 17, 1, LZ_WALK_RANDOM) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "too large") && strstr(lz_error_message(), "16"),
	              "radius too large: %s", lz_error_message());
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 0, 1, LZ_WALK_RANDOM) == NULL);
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 64, NAN, 1, LZ_WALK_RANDOM) == NULL);
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 2, 0, LZ_WALK_RANDOM) == NULL);
	ck_assert(lz_walk_alloc(LZ_NLATTICES, 64, 2, 1, LZ_WALK_RANDOM) == NULL);
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 2, 1, (lz_walk_motion)7) == NULL);
	/* 300 disks of R = 2 on 64²: η = 0.92 > π/√12. */
	ck_assert(lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 2, 300, LZ_WALK_RANDOM) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "close packing"), "beyond close packing: %s",
	              lz_error_message());
}
END_TEST

static int bind_walk(const char *assignments)
{
	return lzt_bind(&lz_method_walk, assignments);
}

LZ_TEST(walk_scene_checks)
{
	ck_assert_msg(lz_method_find("walk") == &lz_method_walk, "method walk is not registered");
	ck_assert_msg(bind_walk("n=10") == LZ_OK, "a minimal walk scene: %s", lz_error_message());
	ck_assert_msg(bind_walk("packing=0.3;lattice=triangular;observe=gr") == LZ_OK,
	              "a packing scene: %s", lz_error_message());
	ck_assert_msg(bind_walk("lattice=cubic;size=32;radius=2;packing=0.2") == LZ_OK, "3D: %s",
	              lz_error_message());
	ck_assert(bind_walk("size=100;n=10") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "100"));
	ck_assert(bind_walk("size=64;radius=17;n=1") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "too large"));
	ck_assert(bind_walk("radius=3") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "exactly one"));
	ck_assert(bind_walk("n=10;packing=0.3") == LZ_EINVAL);
	ck_assert(bind_walk("n=300;radius=2") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "close packing"));
	ck_assert(bind_walk("lattice=cubic;size=16;radius=2;packing=0.8") == LZ_EINVAL);
	ck_assert(bind_walk("packing=1e-6") == LZ_EINVAL);
	ck_assert(bind_walk("n=1;observe=gr") == LZ_EINVAL);
	ck_assert(bind_walk("n=10;lattice=hexagonal") == LZ_EINVAL);
	ck_assert(bind_walk("n=10;motion=levy") == LZ_EINVAL);
	/* Slits: the walls need their width and refuse g(r); packing is of the slit. */
	ck_assert_msg(bind_walk("packing=0.4;walls=slit;slit_width=20;observe=profile") == LZ_OK,
	              "a slit scene: %s", lz_error_message());
	ck_assert_msg(bind_walk("lattice=cubic26;size=32;radius=2;packing=0.2;walls=slit;"
	                        "slit_width=20") == LZ_OK, "a 3D slit: %s", lz_error_message());
	ck_assert(bind_walk("n=10;walls=slit") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "needs slit_width"));
	ck_assert(bind_walk("n=10;slit_width=20") == LZ_EINVAL);
	ck_assert(bind_walk("n=10;walls=slit;slit_width=5") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "at least 6"));
	ck_assert(bind_walk("n=10;walls=slit;slit_width=100") == LZ_EINVAL);
	ck_assert(bind_walk("n=10;walls=slit;slit_width=20;observe=gr") == LZ_EINVAL);
	/* 30 disks of R = 3 fill 0.21 of the 64² box but 0.66 of a slit 20 wide. */
	ck_assert(bind_walk("n=30;walls=slit;slit_width=20") == LZ_OK);
	ck_assert(bind_walk("n=45;walls=slit;slit_width=20") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "slit"));
}
END_TEST

LZ_TEST(walk_slit_rows_and_bad_widths)
{
	/* Square, R = 3, walls 20 apart: centres at heights 3 .. 17. */
	lz_walk *w = lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 3, 10, LZ_WALK_RANDOM);
	ck_assert(w && w->lo == 0 && w->hi == 63);
	ck_assert(lz_walk_set_slit(w, 20) == LZ_OK && w->lo == 3 && w->hi == 17 && w->slit);
	/* Rows 3 .. 17 of the square lattice, one lattice unit each. */
	ck_assert(fabs(lz_walk_slit_packing(2, 64, 20, 3, 10) - 90 * M_PI / 1280) < 1e-15);
	ck_assert(lz_walk_set_slit(w, 5.5) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "5.5") && strstr(lz_error_message(), "at least 6"),
	              "too narrow a slit should say the smallest width: %s", lz_error_message());
	ck_assert(lz_walk_set_slit(w, 65) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "at most"), "%s", lz_error_message());
	ck_assert(lz_walk_set_slit(w, 7) == LZ_OK && w->lo == 3 && w->hi == 4);
	/* lz_walk_set refuses a row the walls forbid. */
	ck_assert(lz_walk_set(w, 0, (lz_site){1, 2, 0}, 0) == LZ_EINVAL);
	ck_assert(lz_walk_set(w, 0, (lz_site){1, 4, 0}, 0) == LZ_OK);
	lz_walk_free(w);
	/* Triangular rows are √3/2 apart: R = 3 needs row 4 (3.46); H = 20 ends at row 19
	 * (16.45 <= 17). */
	w = lz_walk_alloc(LZ_LATTICE_TRIANGULAR, 64, 3, 10, LZ_WALK_RANDOM);
	ck_assert(lz_walk_set_slit(w, 20) == LZ_OK && w->lo == 4 && w->hi == 19);
	lz_walk_free(w);
	/* Cubic: the walls cross z. */
	w = lz_walk_alloc(LZ_LATTICE_CUBIC, 16, 1, 10, LZ_WALK_RANDOM);
	ck_assert(lz_walk_set_slit(w, 5) == LZ_OK && w->lo == 1 && w->hi == 4);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	ck_assert(lz_walk_place(w, rng, 0) == LZ_OK);
	for (size_t i = 0; i < w->n; i++)
		ck_assert_msg(w->r[3 * i + 2] >= 1 && w->r[3 * i + 2] <= 4, "placed in row %d, "
		              "outside the slit", w->r[3 * i + 2]);
	gsl_rng_free(rng);
	lz_walk_free(w);
}
END_TEST

LZ_TEST(profile_alloc_rejects_bad_input)
{
	ck_assert(lz_profile_alloc(LZ_LATTICE_SQUARE, 48, 0, 10, 5) == NULL);
	ck_assert(lz_profile_alloc(LZ_LATTICE_SQUARE, 64, 10, 9, 5) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "10 .. 9"), "%s", lz_error_message());
	ck_assert(lz_profile_alloc(LZ_LATTICE_SQUARE, 64, 0, 64, 5) == NULL);
	ck_assert(lz_profile_alloc(LZ_LATTICE_SQUARE, 64, -1, 3, 5) == NULL);
	ck_assert(lz_profile_alloc(LZ_LATTICE_SQUARE, 64, 0, 3, 0) == NULL);
	lz_profile *p = lz_profile_alloc(LZ_LATTICE_TRIANGULAR, 64, 0, 63, 5);
	ck_assert(p && fabs(p->row_volume - 32 * sqrt(3)) < 1e-12);
	lz_profile_free(p);
}
END_TEST

LZ_TEST(walk_grid_start_has_no_overlap)
{
	/* Boxes whose side is no multiple of the spacing (the periodic gap), slits, 3D. */
	static const struct { lz_lattice_kind kind; int L; double R, H; size_t n; } cases[] = {
		{LZ_LATTICE_SQUARE, 16, 2.5, 0, 9},       /* spacing 5: 3 × 3 */
		{LZ_LATTICE_TRIANGULAR, 64, 2.2, 0, 144}, /* spacing 5: 12 × 12 */
		{LZ_LATTICE_SQUARE, 256, 6, 18, 21},      /* one row in a slit 1.5 σ wide */
		{LZ_LATTICE_TRIANGULAR, 128, 3, 40, 90},
		{LZ_LATTICE_CUBIC, 32, 1.5, 20, 300},
	};
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		lz_walk *w = lz_walk_alloc(cases[k].kind, cases[k].L, cases[k].R, cases[k].n,
		                           LZ_WALK_RANDOM);
		ck_assert(w != NULL);
		if (cases[k].H > 0)
			ck_assert(lz_walk_set_slit(w, cases[k].H) == LZ_OK);
		ck_assert_msg(lz_walk_place_grid(w, rng) == LZ_OK, "case %zu: %s", k,
		              lz_error_message());
		ck_assert_msg(lz_walk_overlaps(w) == 0, "case %zu: the grid start overlaps", k);
		for (size_t i = 0; i < w->n; i++)
			ck_assert(lz_walk_row_allowed(w, w->r[i * (size_t)w->dim + (size_t)w->dim - 1]));
		lz_walk_free(w);
	}
	/* One more disk than the 3 × 3 grid holds. */
	lz_walk *w = lz_walk_alloc(LZ_LATTICE_SQUARE, 16, 2.5, 10, LZ_WALK_RANDOM);
	ck_assert(lz_walk_place_grid(w, rng) == LZ_EPHYS);
	ck_assert_msg(strstr(lz_error_message(), "holds 9"), "%s", lz_error_message());
	lz_walk_free(w);
	gsl_rng_free(rng);
}
END_TEST
