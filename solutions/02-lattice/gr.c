/* gr.c — lattice points per shell and the normalisation of g(r) (graded). */
#include <stdint.h>

#include "lz/error.h"
#include "lz/gr.h"
#include "lz/lattice.h"

/* Every site within the largest circle (sphere), binned by its exact d2. */
int lz_shell_counts(lz_lattice_kind kind, int nshells, uint64_t *count)
{
	/* Hint: loop over every site (dx, dy[, dz]) that can be nearer than nshells, take
	 * d2 = lz_lattice_dist2 and, if d2 < nshells², add one to shell floor(√d2) —
	 * computed exactly (lz_isqrt64), never through a rounded sqrt. On the triangular
	 * lattice the loop must reach |dx| <= 2·nshells/√3 (use 2·nshells to be safe).
	 * Check against table 2.4. See lessons/02-lattice/README.md §5. */
	/* LZ_SOLUTION_BEGIN */
	int dim = lz_lattice_dim(kind);
	if (dim == 0 || nshells < 1)
		return lz_error(LZ_EINVAL, "shell counts for lattice kind %d and %d shells: the kind "
		                "must be valid and nshells >= 1", (int)kind, nshells);
	int32_t reach = kind == LZ_LATTICE_TRIANGULAR ? 2 * nshells : nshells;
	int32_t zreach = dim == 3 ? nshells : 0;
	int64_t d2max = (int64_t)nshells * nshells;
	for (int k = 0; k < nshells; k++)
		count[k] = 0;
	for (int32_t x = -reach; x <= reach; x++)
		for (int32_t y = -reach; y <= reach; y++)
			for (int32_t z = -zreach; z <= zreach; z++) {
				int64_t d2 = lz_lattice_dist2(kind, x, y, z);
				if (d2 < d2max)
					count[lz_isqrt64((uint64_t)d2)]++;
			}
	return LZ_OK;
	/* LZ_SOLUTION_END */
}

/* Pairs per shell over what an ideal gas would put there. */
int lz_gr_result(const lz_gr *g, double *raw, double *corrected)
{
	/* Hint: the ideal gas puts S · N(N-1)/2 · count(k)/V pairs into shell k (V = L^dim
	 * sites) — divide by that for the corrected g. For the raw g replace count(k)/V by
	 * the shell's share of the box's area, lz_shell_volume(dim, k) / (V · cell), with
	 * cell = lz_lattice_cell_volume (√3/2 on the triangular lattice). Count the pairs
	 * in floating point: N(N-1) overflows nothing then. No samples: LZ_EINVAL.
	 * See lessons/02-lattice/README.md §5. */
	/* LZ_SOLUTION_BEGIN */
	if (g->nsamples == 0)
		return lz_error(LZ_EINVAL, "g(r) has no configuration to normalise: close at least "
		                "one with lz_gr_end_sample");
	double volume = 1.0;
	for (int c = 0; c < g->dim; c++)
		volume *= (double)g->side;
	double npairs = (double)g->nsamples * (double)g->n * ((double)g->n - 1.0) / 2.0;
	double cell = lz_lattice_cell_volume(g->kind);
	for (int k = 0; k < g->nshells; k++) {
		double p = (double)g->pairs[k];
		corrected[k] = p / (npairs * (double)g->lattice[k] / volume);
		raw[k] = p / (npairs * lz_shell_volume(g->dim, k) / (volume * cell));
	}
	return LZ_OK;
	/* LZ_SOLUTION_END */
}
