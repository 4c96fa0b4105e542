/* lz/hdmc.h — hard disks off the lattice: Metropolis Monte Carlo in continuous 2D
 * space, the reference the lattice walkers of stage 02 (lz/walk.h) are measured
 * against.
 *
 * Reduced units: the disk diameter σ = 1 is the unit of length. N disks live in a
 * periodic square box of side L, chosen from N and the packing fraction
 *     η = N · (π/4) / L²,   so   L = √(N π / (4 η)).
 * Two disks overlap when their minimum-image distance is below σ: d² < 1. Touching,
 * d² = 1, is allowed (as on the lattice).
 *
 * A trial move displaces one disk, picked uniformly at random, by (u, v) drawn
 * uniformly from [-δ, δ]², wrapped into the box; it is rejected when the disk would
 * overlap another. The proposal is symmetric and the acceptance is 1 or 0, so the
 * chain obeys detailed balance with every non-overlapping configuration equally
 * likely: the hard-disk ensemble at η. δ must stay fixed while sampling (tune it
 * during equilibration only: lz_hdmc_tune).
 *
 * Cost: all pairs — O(N) per trial move, O(N²) per sweep; fine for N of a few
 * hundred. The sweep allocates nothing.
 */
#ifndef LZ_HDMC_H
#define LZ_HDMC_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_histogram.h>
#include <gsl/gsl_rng.h>

/* The densest packing of disks, hexagonal: π/√12. */
#define LZ_HDMC_CLOSE_PACKING 0.90689968211710892

/* The disks. Invariants: x holds n points (x[2i], x[2i+1]), every coordinate in
 * [0, side); once placed, no two disks overlap; 0 < delta <= side/2 (a larger
 * displacement would only repeat a smaller one modulo the box). */
typedef struct {
	size_t n;          /* disks */
	double packing;    /* η */
	double side;       /* L, in σ */
	double delta;      /* the largest displacement per coordinate, in σ */
	double *x;         /* positions, 2n, flat */
	uint64_t moves, accepted;  /* trial moves offered and accepted, for the acceptance */
} lz_hdmc;

/* n disks at packing fraction η in a periodic box of side L = √(n π / (4η)), not yet
 * placed (all at the origin), δ = 0.1 σ. NULL with an lz_error naming the bad value
 * when n < 1, or η is not in (0, π/√12 ≈ 0.9069) (close packing), or no memory. O(n). */
lz_hdmc *lz_hdmc_alloc(size_t n, double packing);
void lz_hdmc_free(lz_hdmc *h);

/* Put disk i at (x, y), in σ, wrapped into the box, without any overlap check (for
 * tests and hand-made starts). LZ_EINVAL if i >= n or x, y is not finite. O(1). */
int lz_hdmc_set(lz_hdmc *h, size_t i, double x, double y);

/* A start without overlaps, deterministic: ny rows of nx sites filled in order, the
 * odd rows shifted by half a spacing when ny is even (a stretched triangular lattice),
 * or a plain rectangular grid; of all nx, ny with nx·ny >= n the arrangement whose
 * nearest distance is largest. LZ_EPHYS with a message naming n, η and the nearest
 * distance reached when even that is below σ: near close packing, where a square box
 * fits no triangular lattice of n sites, or for n = 1, 2 with η >= π/4 (a disk would
 * overlap its own image). Melt the lattice with sweeps before sampling. O(n). */
int lz_hdmc_place(lz_hdmc *h);

/* Offer disk i the displacement (u, v) in σ: accepted (returns 1, x[i] moves, wrapped
 * into the box) when the new position overlaps no other disk, rejected (returns 0,
 * nothing moves) otherwise. Counts the move in h->moves, h->accepted. Preconditions:
 * i < n, |u|, |v| <= L/2. O(n). */
int lz_hdmc_try_move(lz_hdmc *h, size_t i, double u, double v);

/* One sweep: n trial moves, each of a disk drawn uniformly from the n with a
 * displacement drawn uniformly from [-δ, δ]². Returns the number accepted. O(n²), no
 * allocation. */
size_t lz_hdmc_sweep(lz_hdmc *h, gsl_rng *rng);

/* Equilibrate while tuning δ towards the acceptance `target` in (0, 1) (0.4 is a good
 * choice): `sweeps` sweeps in rounds of 10, after each round δ is scaled by
 * acceptance/target (at most ×2, at least ×1/2) and kept within [1e-6, L/2]. Breaks
 * detailed balance while it runs: sample only afterwards, at the fixed δ. Returns
 * the acceptance of the last round, or -1 with LZ_EINVAL from lz_error when target is
 * not in (0, 1) (nothing is run). O(sweeps · n²). */
double lz_hdmc_tune(lz_hdmc *h, gsl_rng *rng, unsigned long sweeps, double target);

/* The number of overlapping pairs (d² < 1 at the minimum image), all pairs. O(n²). */
size_t lz_hdmc_overlaps(const lz_hdmc *h);

/* Add the minimum-image distance r (in σ) of every pair of the configuration to the
 * histogram (gsl_histogram_increment: one count per pair, pairs beyond its range are
 * not counted). The caller chooses the bins; the histogram's upper edge must be at
 * most L/2, where the annulus of a bin is still whole inside the box — LZ_EINVAL
 * naming both otherwise (nothing added), and also if its lower edge is negative.
 * O(n²). */
int lz_hdmc_gr_add(const lz_hdmc *h, gsl_histogram *hist);

/* The pair distribution function of nconf configurations added by lz_hdmc_gr_add:
 *     g[k] = count[k] / (nconf · n(n-1)/2 · π (r_{k+1}² - r_k²) / L²),
 * the exact area of annulus k over the box area, times the number of distinct pairs:
 * n independent uniform points give g = 1 in expectation, at any n. g has
 * hist->n entries. LZ_EINVAL (g untouched) when nconf = 0 or n < 2. O(bins). */
int lz_hdmc_gr(const lz_hdmc *h, const gsl_histogram *hist, unsigned long nconf, double *g);

/* The contact value g(σ+), extrapolated: a straight line fitted (gsl_fit_linear) to
 * ln g over the bins whose centres lie in [1, 1 + width] σ, evaluated at r = 1. A log
 * because g falls near contact roughly exponentially, so the line's curvature bias
 * is smaller than for g itself. *err is the fit's standard error of the intercept,
 * carried to g (from the scatter of the points about the line: a guide, not a
 * rigorous error bar — use independent runs or blocks for that). Put a bin edge at
 * r = 1: a bin straddling σ mixes in the empty core. LZ_EDOM when fewer than 3 such
 * bins have g > 0, LZ_EINVAL when width <= 0. The hard-disk pressure is then
 * Z = βP/ρ = 1 + 2η g(σ+). O(bins). */
int lz_hdmc_contact(const gsl_histogram *hist, const double *g, double width, double *g0,
                    double *err);

#endif
