/* rng.c — GSL generators by name, seeds in [1, LZ_SEED_MAX], automatic seeds. */
#include <errno.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "lz/error.h"
#include "lz/rng.h"

/* The gsl_rng type called `name`, or NULL. */
static const gsl_rng_type *rng_type_find(const char *name)
{
	for (const gsl_rng_type **t = gsl_rng_types_setup(); *t; t++)
		if (strcmp((*t)->name, name) == 0)
			return *t;
	return NULL;
}

lz_rng *lz_rng_alloc(const char *type, unsigned long seed)
{
	const char *name = type ? type : "mt19937";
	const gsl_rng_type *t = rng_type_find(name);
	if (!t) {
		lz_error(LZ_EINVAL, "unknown random number generator '%s' (GSL has e.g. mt19937, "
		         "ranlxd2, taus2, ranlux389, gfsr4)", name);
		return NULL;
	}
	if (seed < 1 || seed > LZ_SEED_MAX) {
		lz_error(LZ_EINVAL, "seed %lu is out of range [1, %lu]", seed, LZ_SEED_MAX);
		return NULL;
	}
	lz_rng *r = malloc(sizeof *r);
	gsl_rng *g = r ? gsl_rng_alloc(t) : NULL;
	if (!g) {
		free(r);
		lz_error(LZ_ENOMEM, "no memory for a %s generator", name);
		return NULL;
	}
	gsl_rng_set(g, seed);
	r->gsl = g;
	r->seed = seed;
	return r;
}

void lz_rng_free(lz_rng *r)
{
	if (!r)
		return;
	gsl_rng_free(r->gsl);
	free(r);
}

/* splitmix64's finaliser: every input bit changes about half the output bits, so
 * nearby clock readings and pids give unrelated seeds. */
static uint64_t mix64(uint64_t x)
{
	x ^= x >> 30;
	x *= 0xbf58476d1ce4e5b9ULL;
	x ^= x >> 27;
	x *= 0x94d049bb133111ebULL;
	return x ^ (x >> 31);
}

unsigned long lz_seed_auto(void)
{
	/* The counter keeps two calls within one clock tick apart. */
	static atomic_ulong calls;
	struct timespec ts;
	clock_gettime(CLOCK_REALTIME, &ts);
	uint64_t x = (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
	x = mix64(x ^ mix64((uint64_t)getpid() << 20 ^ atomic_fetch_add(&calls, 1)));
	return 1 + (unsigned long)(x % LZ_SEED_MAX);
}

int lz_seed_parse(const char *text, unsigned long *seed, int *is_auto)
{
	if (strcmp(text, "auto") == 0) {
		*seed = lz_seed_auto();
		*is_auto = 1;
		return LZ_OK;
	}
	/* strtoull alone would accept spaces, a sign and wrap "-1" around. */
	if (text[0] < '0' || text[0] > '9')
		return lz_error(LZ_EINVAL, "seed '%s' must be 'auto' or an integer in [1, %lu]",
		                text, LZ_SEED_MAX);
	char *end;
	errno = 0;
	unsigned long long v = strtoull(text, &end, 10);
	if (*end != '\0')
		return lz_error(LZ_EINVAL, "seed '%s' must be 'auto' or an integer in [1, %lu]",
		                text, LZ_SEED_MAX);
	if (errno == ERANGE || v < 1 || v > LZ_SEED_MAX)
		return lz_error(LZ_EINVAL, "seed %s is out of range [1, %lu]", text, LZ_SEED_MAX);
	*seed = (unsigned long)v;
	*is_auto = 0;
	return LZ_OK;
}
