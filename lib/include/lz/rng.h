/* lz/rng.h — random numbers: a thin, reproducible wrapper around GSL's gsl_rng.
 *
 * Every stochastic run takes a seed. A seed is an integer in [1, LZ_SEED_MAX]; the
 * text "auto" takes one from the clock, and the caller logs it, so that writing it
 * back as seed=N reproduces the run bit for bit. The default generator is GSL's
 * mt19937; any gsl_rng type name is accepted ("ranlxd2", "taus2", ...).
 * Draw distributions with gsl_ran_*(rng->gsl, ...).
 */
#ifndef LZ_RNG_H
#define LZ_RNG_H

#include <gsl/gsl_rng.h>

/* GSL's mt19937 uses 32 bits of its seed, and seed 0 means "GSL default": hence
 * the range. */
#define LZ_SEED_MAX 4294967295UL

typedef struct {
	gsl_rng *gsl;        /* the generator; pass to gsl_rng_* and gsl_ran_* */
	unsigned long seed;  /* the seed it was started from */
} lz_rng;

/* A generator of GSL type `type` (NULL: "mt19937") started from `seed` in
 * [1, LZ_SEED_MAX]. NULL with lz_error on an unknown type or a seed out of range. */
lz_rng *lz_rng_alloc(const char *type, unsigned long seed);
void lz_rng_free(lz_rng *r);

/* A seed in [1, LZ_SEED_MAX] from the clock and the process id; different on
 * every call. */
unsigned long lz_seed_auto(void);

/* Parse "auto" or a decimal integer in [1, LZ_SEED_MAX] into *seed; *is_auto says
 * which. LZ_EINVAL with a message naming the text otherwise. */
int lz_seed_parse(const char *text, unsigned long *seed, int *is_auto);

/* Uniform double in [0, 1). */
static inline double lz_rng_uniform(lz_rng *r) { return gsl_rng_uniform(r->gsl); }

#endif
