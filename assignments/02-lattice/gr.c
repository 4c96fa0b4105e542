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
	LZ_TODO();
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
	LZ_TODO();
}
