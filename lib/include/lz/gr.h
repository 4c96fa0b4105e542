/* lz/gr.h — the pair distribution function g(r) on a lattice, accumulated in integer
 * distance² space and freed of the lattice's own noise (thesis 2.5.2).
 *
 * Lattice units throughout: r in lattice spacings, d2 = r² an exact integer
 * (lz_lattice_dist2). Shell k holds the pairs with k <= r < k + 1, that is
 * k² <= d2 < (k + 1)²: a pair exactly on a boundary belongs to the OUTER shell.
 *
 * Why two g's. A shell holds a whole number of lattice points, only roughly
 * proportional to its area (thesis table 2.4: 40 points in [5, 6) but 36 in [6, 7) on
 * the square lattice). Dividing the pair count by the exact shell area gives the
 * RAW g, jagged with this fixed pattern; dividing by the shell's lattice-point count
 * gives the CORRECTED g, smooth. Their ratio is the lattice measure
 *     M(k) = count(k) · cell / exact(k),
 * count(k) the lattice points in the shell, cell the area per site
 * (lz_lattice_cell_volume) and exact(k) the shell's area π(2k + 1) or volume
 * 4π/3 (3k² + 3k + 1) (lz_shell_volume): raw g = M · corrected g.
 *
 * Normalisation, for S configurations of N particles on a box of V = L^dim sites:
 *     corrected(k) = pairs(k) / (S · N(N-1)/2 · count(k) / V),
 *     raw(k)       = pairs(k) / (S · N(N-1)/2 · exact(k) / (V · cell)).
 * N(N-1)/2 is the number of distinct pairs, so N independent uniform points give
 * corrected g = 1 in expectation exactly, at every N.
 */
#ifndef LZ_GR_H
#define LZ_GR_H

#include <stddef.h>
#include <stdint.h>

#include "lz/lattice.h"

/* The most shells an accumulator may have: its d2 → shell table holds max_r²
 * entries (64 MB at 4096), and counting the lattice points costs O(max_r^dim). */
#define LZ_GR_MAX_SHELLS_2D 4096
#define LZ_GR_MAX_SHELLS_3D 512

/* floor(√n), exact for every n (no rounding of a double can put a d2 in the wrong
 * shell). O(1). */
uint32_t lz_isqrt64(uint64_t n);

/* The exact area (dim 2) or volume (dim 3) of the continuum shell k <= r < k + 1:
 * π(2k + 1) or 4π/3 (3k² + 3k + 1) — not 2πr dr, since dr = 1 is not small next to
 * the first radii. O(1). */
double lz_shell_volume(int dim, int k);

/* A g(r) accumulator. Invariants: pairs[k] counts the pairs added with shell_of[d2]
 * = k; every d2 >= d2max went to `beyond` instead; nsamples configurations were
 * closed by lz_gr_end_sample, each of n particles. */
typedef struct {
	lz_lattice_kind kind;
	int dim;
	int32_t side;        /* L: the periodic box holds V = L^dim sites */
	int nshells;         /* shells k = 0 .. nshells - 1; max_r = nshells */
	size_t n;            /* particles per configuration */
	int64_t d2max;       /* nshells² */
	uint32_t *shell_of;  /* shell_of[d2] = floor(√d2), d2 in [0, d2max) */
	uint64_t *pairs;     /* pairs counted per shell, nshells entries */
	uint64_t *lattice;   /* lattice points per shell (lz_shell_counts), nshells entries */
	uint64_t beyond;     /* pairs at r >= max_r, not histogrammed */
	uint64_t nsamples;   /* configurations closed */
} lz_gr;

/* An empty accumulator for configurations of n >= 2 particles on lattice `kind` in a
 * periodic box of side L (power of two), for r < max_r lattice units. max_r may be at
 * most L/2, where the shells stop fitting into the box's nearest-image cell, and at
 * most LZ_GR_MAX_SHELLS_2D (3D). NULL with an lz_error naming the bad value
 * otherwise. Fills shell_of (O(max_r²)) and lattice (lz_shell_counts, O(max_r^dim)). */
lz_gr *lz_gr_alloc(lz_lattice_kind kind, int64_t side, int max_r, size_t n);
void lz_gr_free(lz_gr *g);

/* Count one pair at squared distance d2 >= 0 (lz_lattice_min_dist2). O(1), one
 * look-up, no square root: this is the inner loop. */
static inline void lz_gr_add_pair(lz_gr *g, int64_t d2)
{
	if (d2 < g->d2max)
		g->pairs[g->shell_of[d2]]++;
	else
		g->beyond++;
}

/* Close one configuration (all its N(N-1)/2 pairs added). O(1). */
static inline void lz_gr_end_sample(lz_gr *g) { g->nsamples++; }

/* Add every pair of the configuration r (g->n sites, dim int32_t coordinates each,
 * flat: r[i·dim + c]) with its minimum-image distance in box b, then close it.
 * LZ_EINVAL if b's lattice dimension or side differ from g's. O(N²). */
int lz_gr_add_config(lz_gr *g, const lz_lattice_box *b, const int32_t *r);

/* ---- graded (solutions/02-lattice/gr.c) ---- */

/* count[k] = the number of lattice points (sites of the infinite lattice, origin
 * included) with k <= r < k + 1, for k = 0 .. nshells - 1, counted exactly in integer
 * d2 space; a point exactly on a boundary (d2 = k²) goes to the outer shell, k. Must
 * reproduce thesis table 2.4. The triangular lattice's circles are ellipses in
 * sheared coordinates, reaching |dx| = 2r/√3 > r: a loop over |dx|, |dy| <= nshells
 * misses points. LZ_EINVAL for an invalid kind or nshells < 1 (count untouched).
 * O(nshells^dim). */
int lz_shell_counts(lz_lattice_kind kind, int nshells, uint64_t *count);

/* The raw and the corrected g of every shell (arrays of g->nshells), normalised as
 * in the comment at the top: raw by the exact shell area (volume), corrected by the
 * lattice count g->lattice[k]. LZ_EINVAL, writing nothing, if no configuration was
 * closed (g->nsamples = 0). O(nshells). */
int lz_gr_result(const lz_gr *g, double *raw, double *corrected);

#endif
