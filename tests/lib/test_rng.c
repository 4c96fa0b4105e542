/* test_rng.c — seeds, reproducibility, generator types. */
#include <stdlib.h>
#include <string.h>

#include "lz/rng.h"
#include "lztest.h"

LZ_TEST(rng_same_seed_same_numbers)
{
	lz_rng *a = lz_rng_alloc(NULL, 12345), *b = lz_rng_alloc("mt19937", 12345);
	ck_assert_msg(a && b, "lz_rng_alloc failed for seed 12345: %s", lz_error_message());
	ck_assert_msg(strcmp(gsl_rng_name(a->gsl), "mt19937") == 0,
	              "the default generator is '%s', expected mt19937", gsl_rng_name(a->gsl));
	ck_assert_msg(a->seed == 12345, "rng->seed = %lu, expected the seed given", a->seed);
	for (int i = 0; i < 1000; i++) {
		unsigned long x = gsl_rng_get(a->gsl), y = gsl_rng_get(b->gsl);
		if (x != y)  /* not ck_assert: Check writes a pipe message per passing assert */
			ck_abort_msg("draw %d differs (%lu vs %lu) for the same seed: a run would "
			             "not be reproducible", i, x, y);
	}
	lz_rng_free(a);
	lz_rng_free(b);
}
END_TEST

LZ_TEST(rng_different_seeds_differ)
{
	lz_rng *a = lz_rng_alloc(NULL, 1), *b = lz_rng_alloc(NULL, 2);
	ck_assert(a && b);
	int same = 0;
	for (int i = 0; i < 1000; i++)
		same += gsl_rng_get(a->gsl) == gsl_rng_get(b->gsl);
	ck_assert_msg(same < 5, "seeds 1 and 2 gave %d equal draws out of 1000", same);
	double u = lz_rng_uniform(a);
	ck_assert_msg(u >= 0 && u < 1, "lz_rng_uniform gave %g, outside [0, 1)", u);
	lz_rng_free(a);
	lz_rng_free(b);
	lz_rng_free(NULL);
}
END_TEST

LZ_TEST(rng_other_gsl_types)
{
	const char *types[] = {"taus2", "ranlxd2", "gfsr4"};
	for (int i = 0; i < 3; i++) {
		lz_rng *r = lz_rng_alloc(types[i], LZ_SEED_MAX);
		ck_assert_msg(r != NULL, "type %s with seed LZ_SEED_MAX was refused: %s", types[i],
		              lz_error_message());
		ck_assert_msg(strcmp(gsl_rng_name(r->gsl), types[i]) == 0, "asked for %s, got %s",
		              types[i], gsl_rng_name(r->gsl));
		lz_rng_free(r);
	}
}
END_TEST

LZ_TEST(rng_unknown_type_is_named)
{
	lz_rng *r = lz_rng_alloc("mersenne", 5);
	ck_assert_msg(r == NULL, "an unknown generator type was accepted");
	ck_assert_msg(strstr(lz_error_message(), "'mersenne'") &&
	              strstr(lz_error_message(), "mt19937"),
	              "the message should name the bad type and a valid one: '%s'",
	              lz_error_message());
}
END_TEST

LZ_TEST(rng_seed_out_of_range_refused)
{
	ck_assert_msg(lz_rng_alloc(NULL, 0) == NULL, "seed 0 (GSL's 'default seed') was accepted");
	if (sizeof(unsigned long) > 4)
		ck_assert_msg(lz_rng_alloc(NULL, LZ_SEED_MAX + 1) == NULL,
		              "seed 2^32 was accepted, but mt19937 uses only 32 bits of the seed");
	ck_assert_msg(strstr(lz_error_message(), "[1, 4294967295]") != NULL,
	              "the message should give the range: '%s'", lz_error_message());
}
END_TEST

static int compare_seeds(const void *a, const void *b)
{
	unsigned long x = *(const unsigned long *)a, y = *(const unsigned long *)b;
	return (x > y) - (x < y);
}

LZ_TEST(rng_auto_seeds_in_range_and_distinct)
{
	enum { N = 1000 };
	unsigned long *s = malloc(N * sizeof *s);
	ck_assert(s != NULL);
	for (int i = 0; i < N; i++) {
		s[i] = lz_seed_auto();
		if (s[i] < 1 || s[i] > LZ_SEED_MAX)
			ck_abort_msg("auto seed %lu is outside [1, %lu]", s[i], LZ_SEED_MAX);
	}
	qsort(s, N, sizeof *s, compare_seeds);
	for (int i = 1; i < N; i++)
		if (s[i] == s[i - 1])
			ck_abort_msg("two of %d calls of lz_seed_auto gave the same seed %lu", N, s[i]);
	free(s);
}
END_TEST

LZ_TEST(rng_seed_parse)
{
	unsigned long seed = 0;
	int is_auto = -1;
	ck_assert(lz_seed_parse("42", &seed, &is_auto) == LZ_OK);
	ck_assert_msg(seed == 42 && is_auto == 0, "'42' parsed as %lu (auto=%d)", seed, is_auto);
	ck_assert(lz_seed_parse("4294967295", &seed, &is_auto) == LZ_OK && seed == LZ_SEED_MAX);
	ck_assert(lz_seed_parse("auto", &seed, &is_auto) == LZ_OK);
	ck_assert_msg(is_auto == 1 && seed >= 1 && seed <= LZ_SEED_MAX,
	              "'auto' gave seed %lu, auto=%d", seed, is_auto);
	const char *bad[] = {"0", "-1", "4294967296", "99999999999999999999999", "12abc", "",
	                     " 5", "+5", "1.5", "AUTO", "0x10"};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		seed = 777;
		ck_assert_msg(lz_seed_parse(bad[i], &seed, &is_auto) == LZ_EINVAL,
		              "seed text '%s' was accepted (as %lu)", bad[i], seed);
		ck_assert_msg(seed == 777, "a refused seed '%s' still changed *seed", bad[i]);
		ck_assert_msg(strstr(lz_error_message(), bad[i]) != NULL,
		              "the message should quote the bad text '%s': '%s'", bad[i],
		              lz_error_message());
	}
}
END_TEST
