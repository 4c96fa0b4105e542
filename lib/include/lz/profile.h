/* lz/profile.h — the density profile across a slit, collected on the lattice's own
 * rows (thesis 2.5.3).
 *
 * Lattice units: the profile runs along the last coordinate (y in 2D, z in 3D) of a
 * box of side L; row c of that coordinate is a slab of Cartesian thickness h (the row
 * spacing, lz_walk_row_spacing) and cross-section L^(dim-1), and it holds
 * L^(dim-1) sites of cell volume `cell` (lz_lattice_cell_volume), so its volume is
 *     V_row = L^(dim-1) · cell      (h = cell in 2D: 1, or √3/2 triangular).
 * The number density of row c over S configurations is
 *     ρ(c) = count(c) / (S · V_row),
 * particles per unit area (volume) in lattice units. The slit's walls are parallel to
 * the rows, so, unlike g(r) (lz/gr.h), a profile carries no lattice noise and needs no
 * correction (thesis 2.5.3).
 */
#ifndef LZ_PROFILE_H
#define LZ_PROFILE_H

#include <stddef.h>
#include <stdint.h>

#include "lz/lattice.h"

/* A profile accumulator. Invariants: count has hi - lo + 1 entries, count[c - lo]
 * the centres seen in row c; nsamples configurations of n particles were added. */
typedef struct {
	int dim;             /* 2 or 3 */
	int32_t lo, hi;      /* the rows histogrammed, 0 <= lo <= hi < L */
	size_t n;            /* particles per configuration */
	double row_volume;   /* V_row = L^(dim-1) · cell */
	uint64_t *count;     /* centres per row, hi - lo + 1 entries */
	uint64_t nsamples;   /* configurations added */
} lz_profile;

/* An empty profile of rows lo .. hi for configurations of n >= 1 particles on lattice
 * `kind` in a box of side L (power of two). NULL with an lz_error naming the bad value
 * unless 0 <= lo <= hi < L. O(hi - lo). */
lz_profile *lz_profile_alloc(lz_lattice_kind kind, int64_t side, int32_t lo, int32_t hi,
                             size_t n);
void lz_profile_free(lz_profile *p);

/* ---- graded (solutions/02-lattice/profile.c) ---- */

/* Add one configuration r (p->n sites, p->dim int32_t coordinates each, flat: the row
 * of particle i is r[i·dim + dim - 1]) and count it in p->nsamples. LZ_EINVAL, with p
 * unchanged, if some particle's row is outside lo .. hi (a particle went through a
 * wall). O(n). */
int lz_profile_add_config(lz_profile *p, const int32_t *r);

/* rho[c - lo] = ρ(c), the number density of row c (header comment), for every row.
 * LZ_EINVAL, writing nothing, if no configuration was added. O(hi - lo). */
int lz_profile_result(const lz_profile *p, double *rho);

#endif
