/* profile_lib.c — allocation of density-profile accumulators (lz/profile.h). The
 * histogram and its normalisation are graded (solutions/02-lattice/profile.c). */
#include <math.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/profile.h"

lz_profile *lz_profile_alloc(lz_lattice_kind kind, int64_t side, int32_t lo, int32_t hi,
                             size_t n)
{
	int dim = lz_lattice_kind_side_check(kind, side);
	if (dim == 0)
		return NULL;
	if (lo < 0 || hi < lo || hi >= side)
		return lz_error(LZ_EINVAL, "profile rows %d .. %d: need 0 <= lo <= hi < L = %lld",
		                (int)lo, (int)hi, (long long)side), NULL;
	if (n == 0)
		return lz_error(LZ_EINVAL, "n = 0 particles: a profile needs at least one"), NULL;
	lz_profile *p = calloc(1, sizeof *p);
	if (p)
		p->count = calloc((size_t)(hi - lo) + 1, sizeof *p->count);
	if (!p || !p->count) {
		lz_profile_free(p);
		return lz_error(LZ_ENOMEM, "no memory for a profile of %d rows", (int)(hi - lo + 1)),
		       NULL;
	}
	p->dim = dim;
	p->lo = lo;
	p->hi = hi;
	p->n = n;
	p->row_volume = pow((double)side, dim - 1) * lz_lattice_cell_volume(kind);
	return p;
}

void lz_profile_free(lz_profile *p)
{
	if (!p)
		return;
	free(p->count);
	free(p);
}
