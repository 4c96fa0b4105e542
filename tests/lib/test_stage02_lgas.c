/* test_stage02_lgas.c — the library half of lz/lgas.h, which students do not write:
 * allocation and its checks, initial states, totals. None of these tests calls a
 * graded function, so they pass with the stubs as well. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/lgas.h"
#include "lztest.h"

static gsl_rng *rng_new(unsigned long seed)
{
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, seed);
	return r;
}

LZ_TEST(lgas_alloc_rejects_bad_sizes)
{
	ck_assert(lz_lgas_alloc(LZ_LGAS_FHP, 100) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "100") && strstr(lz_error_message(), "64") &&
	              strstr(lz_error_message(), "128"), "size 100: the message should name it and "
	              "the nearest powers of two 64 and 128: '%s'", lz_error_message());
	ck_assert(lz_lgas_alloc(LZ_LGAS_HPP, 0) == NULL);
	ck_assert(lz_lgas_alloc(LZ_LGAS_HPP, -8) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "-8"), "'%s'", lz_error_message());
	ck_assert(lz_lgas_alloc(LZ_LGAS_HPP, 1) == NULL);
	ck_assert(lz_lgas_alloc(LZ_LGAS_FHP, 2 * LZ_LGAS_SIDE_MAX) == NULL);
	ck_assert(lz_lgas_alloc((lz_lgas_model)7, 16) == NULL);
	lz_lgas_model m;
	ck_assert(lz_lgas_parse("fhp", &m) == LZ_OK && m == LZ_LGAS_FHP);
	ck_assert(lz_lgas_parse("hpp", &m) == LZ_OK && m == LZ_LGAS_HPP);
	ck_assert(lz_lgas_parse("fhp2", &m) == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "hpp|fhp"));
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 2);
	ck_assert(g && g->side == 2 && g->mask == 1 && g->shift == 1 && g->nbits == 6);
	ck_assert(lz_lgas_index(g, -1, -1) == 3 && lz_lgas_index(g, 2, 1) == 2);
	lz_lgas_free(g);
	lz_lgas_free(NULL);
}
END_TEST

LZ_TEST(lgas_init_rejects_bad_densities)
{
	gsl_rng *r = rng_new(1);
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 8);
	static const double bad[] = {0.0, 1.0, -0.1, 1.5, NAN};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		ck_assert(lz_lgas_init_uniform(g, bad[i], r) == LZ_EINVAL);
		ck_assert_msg(strstr(lz_error_message(), "(0, 1)"), "density %g: '%s'", bad[i],
		              lz_error_message());
		ck_assert(lz_lgas_init_shear(g, bad[i], 0.1, r) == LZ_EINVAL);
		ck_assert(lz_lgas_init_pulse(g, bad[i], 0.1, r) == LZ_EINVAL);
	}
	ck_assert(lz_lgas_init_shear(g, 0.4, 0.8, r) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "u0 = 0.8"), "'%s'", lz_error_message());
	ck_assert(lz_lgas_init_pulse(g, 0.6, 1.0, r) == LZ_EINVAL);
	ck_assert(lz_lgas_init_pulse(g, 0.2, -1.0, r) == LZ_EINVAL);
	lz_lgas_free(g);
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_uniform_density_and_totals)
{
	gsl_rng *r = rng_new(2);
	for (int m = 0; m < 2; m++) {
		lz_lgas *g = lz_lgas_alloc(m ? LZ_LGAS_FHP : LZ_LGAS_HPP, 128);
		ck_assert(lz_lgas_init_uniform(g, 0.3, r) == LZ_OK);
		int64_t mass, p[2];
		lz_lgas_totals(g, &mass, p);
		double links = 128.0 * 128.0 * g->nbits, mean = mass / links;
		ck_assert_msg(fabs(mean - 0.3) < 5 * sqrt(0.21 / links), "uniform d = 0.3: measured %g",
		              mean);
		for (size_t i = 0; i < 128 * 128; i++)
			ck_assert(g->site[i] < (1u << g->nbits));
		/* By hand: one particle in each direction of the site at the origin. */
		memset(g->site, 0, 128 * 128);
		g->site[0] = m ? 0x03 : 0x03;  /* directions 0 and 1 */
		lz_lgas_totals(g, &mass, p);
		ck_assert(mass == 2 && p[0] == 1 && p[1] == 1);
		ck_assert(lz_lgas_row_px2(g, 0) == (m ? 2 + 1 : 2));
		g->site[0] = m ? 0x3F : 0x0F;
		lz_lgas_totals(g, &mass, p);
		ck_assert(mass == g->nbits && p[0] == 0 && p[1] == 0);
		ck_assert(lz_lgas_row_px2(g, 0) == 0);
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_shear_wave_has_its_momentum_profile)
{
	gsl_rng *r = rng_new(3);
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 256);
	ck_assert(lz_lgas_init_shear(g, 0.2, 0.1, r) == LZ_OK);
	/* Row-averaged x-momentum per site: 6 d u0 sin(2π y/L) on FHP (Σ c_x² = 3, times 2d). */
	double sum = 0.0;
	for (int32_t y = 0; y < 256; y++)
		sum += lz_lgas_row_px2(g, y) / 2.0 / 256.0 * sin(2.0 * M_PI * y / 256.0);
	double amp = 2.0 * sum / 256.0, want = 2.0 * 0.2 * 3.0 * 0.1;
	ck_assert_msg(fabs(amp - want) < 0.1 * want, "FHP shear wave d = 0.2, u0 = 0.1: "
	              "momentum amplitude %g per site, expected 2 d u0 Σ c_x² = %g", amp, want);
	int64_t mass, p[2];
	lz_lgas_totals(g, &mass, p);
	ck_assert(fabs(mass / (256.0 * 256.0 * 6) - 0.2) < 0.005);
	lz_lgas_free(g);
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_pulse_is_denser_in_the_middle_and_keeps_walls)
{
	gsl_rng *r = rng_new(4);
	for (int m = 0; m < 2; m++) {
		lz_lgas *g = lz_lgas_alloc(m ? LZ_LGAS_FHP : LZ_LGAS_HPP, 64);
		lz_lgas_set_wall(g, 0, 0);
		lz_lgas_set_wall(g, -1, 64);  /* wraps to (63, 0) */
		ck_assert(lz_lgas_init_pulse(g, 0.2, 2.0, r) == LZ_OK);
		ck_assert(g->site[0] & LZ_LGAS_WALL && g->site[63] & LZ_LGAS_WALL);
		long centre = 0, corner = 0;
		for (int32_t y = -2; y <= 2; y++)
			for (int32_t x = -2; x <= 2; x++) {
				centre += __builtin_popcount(g->site[lz_lgas_index(g, 32 + x, 32 + y)]);
				corner += __builtin_popcount(g->site[lz_lgas_index(g, 8 + x, 8 + y)] & 0x3F);
			}
		ck_assert_msg(centre > 2 * corner, "pulse a = 2: centre %ld particles, corner %ld",
		              centre, corner);
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST
