/* YOUR FILE — this is the file you fill in for stage 02-lattice.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/02-lattice/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=02`; see your own code at work with
 * `make lesson STAGE=02`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* profile.c — the density profile across a slit (graded). */
#include <stddef.h>
#include <stdint.h>

#include "lz/error.h"
#include "lz/profile.h"

/* Check every row first, so that a bad configuration leaves the histogram as it was. */
int lz_profile_add_config(lz_profile *p, const int32_t *r)
{
	/* Hint: the row of particle i is r[i * dim + dim - 1]. Two passes: first make sure
	 * every row is within lo .. hi (else return lz_error(LZ_EINVAL, ...) naming the
	 * particle and its row), then count each one in p->count[row - lo] and the
	 * configuration in p->nsamples. See lessons/02-lattice/README.md §6. */
	LZ_TODO();
}

/* Counts per configuration per unit volume of the row. */
int lz_profile_result(const lz_profile *p, double *rho)
{
	/* Hint: ρ(c) = count / (nsamples · row_volume): the header's formula. With no
	 * configuration there is nothing to divide by: return an LZ_EINVAL error. */
	LZ_TODO();
}
