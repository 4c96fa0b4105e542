/* lz/well.h — a square-well attraction painted on a second field, and the Metropolis
 * move with its acceptance tabulated per integer energy change (thesis 2.4.4,
 * figs. 2.11-2.12).
 *
 * Lattice units throughout; energies in units of the well depth ε, temperatures as
 * kT (k = 1). Two particles at centre distance d interact by
 *     u(d) = infinite (d < σ),   -ε (σ <= d < λσ),   0 (d >= λσ),
 * σ = 2R the hard-core diameter, λσ = rw the well's outer edge. The hard core is the
 * field of lz/field.h. The well is a second byte field of the same layout,
 *     cell[s] = the number of particles whose WELL shape (lz/shape.h, radius rw, the
 *               strict rule dist2 < rw²) covers site s,
 * painted and moved exactly like the excluded shape (head and tail points). Since a
 * particle's well shape contains its own centre, particle i at site c has
 *     N_i = cell[c] - 1
 * partners inside its well (no one is closer than σ: the hard core forbids it), and
 * the total energy is E = -ε · (1/2) Σ_i N_i: one look-up per particle.
 *
 * A move of i by direction d changes E by ΔE = -ε · ΔN with the INTEGER
 *     ΔN = (cell[t] - wself[d]) - (cell[c] - 1),      t = c + dirs[d],
 * wself[d] = shape->self[d] (i's own well covers t; true for every step once rw > 1):
 * the partners at the new site minus those at the old one, both without i itself.
 * Because ΔN is an integer in [-LZ_WELL_KMAX, LZ_WELL_KMAX], the Metropolis
 * probability min(1, exp(-ΔE / kT)) = min(1, exp(ε ΔN / kT)) takes only 2·KMAX + 1
 * values: tabulate them once per temperature and never call exp() in the run (the
 * trick of lattice spin models).
 *
 * Bytes: a site lies in the well of at most ~40 particles in 2D and ~200 in 3D for
 * λ <= 3 (the densest packing of centres, σ apart, within rw = 3σ of a point), below
 * 255.
 *
 * Cost: memory one more byte per site; a move O(|head|) per field; ΔN O(1).
 */
#ifndef LZ_WELL_H
#define LZ_WELL_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/field.h"
#include "lz/shape.h"

/* |ΔN| never exceeds the byte range of a cell. */
#define LZ_WELL_KMAX 255

/* The largest well, in units of σ: λ <= 3 keeps every count within a byte. */
#define LZ_WELL_LAMBDA_MAX 3.0

/* A square well on a field f. Invariants: cell has f->nsites bytes, laid out as
 * f->cell (lz_field_index); cell[s] is the number of f's particles whose well shape
 * covers s; accept[k + KMAX] = min(1, exp(depth · k / temperature)) for every k in
 * [-KMAX, KMAX]. */
typedef struct {
	lz_shape *shape;        /* the well, radius rw = λσ (owned) */
	uint8_t *cell;          /* the well field, f->nsites bytes */
	double range;           /* rw = λσ, lattice units */
	double depth;           /* ε >= 0 */
	double temperature;     /* kT > 0, in the units of ε */
	double accept[2 * LZ_WELL_KMAX + 1];
} lz_well;

/* A well of range rw = lambda · 2R on field f, painted for the particles already in f,
 * its table filled (lz_well_table, graded). NULL with an lz_error naming the value
 * and its allowed range on lambda outside (1, LZ_WELL_LAMBDA_MAX] or 2·rw > L (the
 * well would wrap onto itself), depth < 0 or not finite, temperature <= 0 or not
 * finite, a well shape beyond LZ_SHAPE_BOX_MAX, or no memory; NULL with LZ_EPHYS if
 * a site would lie in more than 255 wells (only an overlapping pile can: the byte
 * would wrap). After this the particles of f must move only by lz_field_try_move
 * (lz_field_place, _remove or _move alone would leave the well stale).
 * O(nsites + n · |well|). */
lz_well *lz_well_alloc(const lz_field *f, double lambda, double depth, double temperature);
void lz_well_free(lz_well *w);

/* The total energy E = -depth · (pairs with σ <= d < rw), from the well field:
 * -depth · (1/2) Σ_i (cell[r_i] - 1). O(n). */
double lz_well_energy(const lz_well *w, const lz_field *f);

/* ---- graded (solutions/03-field/well.c) ---- */

/* Fill w->accept from w->depth and w->temperature: accept[k + KMAX] =
 * min(1, exp(depth · k / temperature)), so 1 for every k >= 0. O(KMAX). */
void lz_well_table(lz_well *w);

/* ΔN, the change in the number of particle i's well partners if it stepped by
 * direction d (header comment). Preconditions: i < f->n, 0 <= d < ndir. Does not
 * look at the hard core. O(1). */
int lz_well_delta(const lz_well *w, const lz_field *f, size_t i, int d);

/* One Metropolis trial of particle i along direction d. Refused (0, nothing drawn) if
 * lz_field_can_move says the hard cores forbid it. With no well (w == NULL) or a table
 * entry of 1 (ΔN >= 0) it is accepted without a draw; otherwise one u =
 * gsl_rng_uniform(rng) is drawn and the step accepted iff u < accept[ΔN + KMAX]. An
 * accepted step repaints the well (heads +1, tails -1 of w->shape, from the OLD
 * centre) and then moves the particle in f (lz_field_move). Returns 1 if it moved,
 * else 0. O(|head|) per field. */
int lz_field_try_move(lz_field *f, lz_well *w, size_t i, int d, gsl_rng *rng);

#endif
