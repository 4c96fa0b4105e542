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
	/* LZ_SOLUTION_BEGIN */
	size_t dim = (size_t)p->dim;
	for (size_t i = 0; i < p->n; i++) {
		int32_t row = r[i * dim + dim - 1];
		if (row < p->lo || row > p->hi)
			return lz_error(LZ_EINVAL, "particle %zu is in row %d, outside the profile's "
			                "rows %d .. %d", i, (int)row, (int)p->lo, (int)p->hi);
	}
	for (size_t i = 0; i < p->n; i++)
		p->count[r[i * dim + dim - 1] - p->lo]++;
	p->nsamples++;
	return LZ_OK;
	/* LZ_SOLUTION_END */
}

/* Counts per configuration per unit volume of the row. */
int lz_profile_result(const lz_profile *p, double *rho)
{
	/* Hint: ρ(c) = count / (nsamples · row_volume): the header's formula. With no
	 * configuration there is nothing to divide by: return an LZ_EINVAL error. */
	/* LZ_SOLUTION_BEGIN */
	if (p->nsamples == 0)
		return lz_error(LZ_EINVAL, "no configuration was added to the profile");
	double norm = (double)p->nsamples * p->row_volume;
	for (int32_t c = p->lo; c <= p->hi; c++)
		rho[c - p->lo] = (double)p->count[c - p->lo] / norm;
	return LZ_OK;
	/* LZ_SOLUTION_END */
}
