/* lz/edmd_obs.h — what is measured on an event-driven hard-sphere run (lz/edmd.h):
 * pressure from the collisional virial, the collision rate and the exact identity
 * between them, with block-average error bars; the guards (energy, momentum,
 * overlaps); and, on request only, the pair distribution g(r) and the mean-square
 * displacement.
 *
 * Units as lz/edmd.h: σ = m = 1; kT is measured (2 KE / (dim·n)).
 *
 * Pressure. Between collisions nothing pushes; at a collision particle a receives the
 * impulse Δp_a. Over a time t, the virial theorem gives
 *     Z = βP/ρ = 1 + Σ_collisions r_ab·Δp_a / (dim · n · kT · t),
 * (lz_edmd.virial accumulates the sum). The collision rate per particle is
 *     Γ = 2 · collisions / (n · t)  (each collision counts for both partners),
 * the mean free time 1/Γ, and for any hard-particle fluid in equilibrium (reference
 * §3) the two are tied exactly:
 *     Z = 1 + σ √(π m / kT) Γ / (2·dim).
 * The two sides are measured independently (impulses on one side, a count on the
 * other), so their agreement is a test of the whole engine. In a finite run with the
 * total momentum fixed at zero, Z from the impulses exceeds Z_gamma by about
 * (Z - 1)/(2n) (0.004 at n = 500, η = 0.4: a test helper's measurement), which is
 * not corrected here: compare at n of a few thousand or allow for it.
 *
 * Error bars: the run is cut into blocks of equal numbers of events; each block gives
 * one Z, Γ, ...; the error is the standard error of the block means (GSL statistics),
 * honest when a block is much longer than the correlation time (10 or more collisions
 * per particle per block is plenty in a fluid).
 */
#ifndef LZ_EDMD_OBS_H
#define LZ_EDMD_OBS_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_histogram.h>

#include "lz/edmd.h"

/* What one stretch of run measured (since the last lz_edmd_reset_counts). */
typedef struct {
	double time;        /* simulated time elapsed */
	double T;           /* kT at the end (2 KE / (dim n)) */
	double Z;           /* 1 + virial / (dim n T time) */
	double gamma;       /* collision rate per particle, 2 collisions / (n time) */
	double Z_gamma;     /* the identity: 1 + √(π/T) Γ / (2 dim) */
	double free_time;   /* mean free time 1/Γ (INFINITY without collisions) */
	uint64_t events, collisions, crossings, bounces, stale, rebuilds;
} lz_edmd_sample;

/* The sample of the counters since the last reset, at now. O(n) (the temperature). */
lz_edmd_sample lz_edmd_measure(const lz_edmd *e);

/* Means and standard errors over blocks, with the guards. */
typedef struct {
	size_t blocks;
	double Z, Z_err, gamma, gamma_err, Z_gamma, Z_gamma_err, T, T_err;
	double free_time;          /* 1 / gamma */
	double time;               /* simulated time of all blocks */
	uint64_t events, collisions, crossings, bounces, stale, rebuilds;
	double cpu_s;              /* CPU seconds in lz_edmd_run (guards excluded) */
	double energy_rel_drift;   /* max over block ends of |E/E0 - 1| (E0 at the start) */
	double momentum_abs_drift; /* max over block ends of |P - P0| */
	double max_overlap;        /* max over block ends of lz_edmd_max_overlap */
} lz_edmd_result;

/* Run `blocks` blocks of `events` events each, measuring each block, checking the
 * energy, momentum and overlaps at each block end; fill r. Stops at the first error
 * of lz_edmd_run (LZ_EPHYS: collapse) and returns it; returns LZ_EPHYS with lz_error
 * also when an overlap exceeds 1e-10 or (restitution 1, no gravity) the energy drifts
 * by more than 1e-8 relative — the guards report rather than carry on.
 * blocks >= 2. O(blocks · (events log n + n)). */
int lz_edmd_blocks(lz_edmd *e, size_t blocks, uint64_t events, lz_edmd_result *r);

/* lz_edmd_blocks with blocks of a duration instead, and something to watch. A block
 * ends after `events` events or `duration` of simulated time, whichever comes first
 * (a time-limited block brings every particle to its end); within a block, after
 * every `every` events — or, when interval > 0, at the fixed times t_start + k ·
 * interval — and at its end (guards done), observe(e, arg) is called at now. It may
 * read e, not change it, and its time is not in cpu_s; an error it returns stops the
 * run. Why fixed times: right after an event the colliding pair touches, so a sample
 * of the configuration taken at event times over-counts pairs at contact (g(σ) about
 * 2 % high at N = 200); the configuration at a time chosen without looking at the
 * events is a fair sample. Cutting the run at observations changes the trajectory
 * only by round-off (particles are brought to the observation time).
 * lz_edmd_blocks(e, b, k, r) is the plan {k, INFINITY, 0, NULL, NULL, 0}. */
typedef struct {
	uint64_t events;     /* per block; UINT64_MAX: no limit */
	double duration;     /* per block; INFINITY: no limit (one of the two is finite) */
	uint64_t every;      /* events between observations; 0: at block ends only */
	int (*observe)(const lz_edmd *e, void *arg);  /* NULL: nothing to watch */
	void *arg;
	double interval;     /* > 0: observe at fixed times this far apart instead */
} lz_edmd_plan;
int lz_edmd_blocks_plan(lz_edmd *e, size_t blocks, const lz_edmd_plan *plan,
                        lz_edmd_result *r);

/* The reference Z(η) of the hard-sphere (dim 3) or hard-disk (dim 2) fluid: the table
 * of datasets/reference/hard-spheres.csv (hard-disks.csv) — the Padé-resummed virial
 * series, and in 2D the simulated η = 0.698 — interpolated through Z/Z_CS
 * (Z/Z_Henderson) between the tabulated packings, 1 at η = 0; beyond the table,
 * Carnahan-Starling (Henderson), which is no longer the stable phase there. *source
 * (may be NULL) names which: "table" or "carnahan-starling" / "henderson". NAN, with
 * an lz_error, when the table cannot be read. O(rows of the table). */
double lz_edmd_z_reference(int dim, double packing, const char **source);

/* The closed forms beside it: Carnahan-Starling (dim 3), (1 + η + η² - η³)/(1 - η)³,
 * or Henderson (dim 2), (1 + η²/8)/(1 - η)². O(1). */
double lz_edmd_z_closed(int dim, double packing);

/* ---- on request ---- */

/* Add the distances of all pairs closer than rmax (<= L/2) at now to h (bins over
 * [a, b) with b <= rmax; pairs counted once), scanning the cells within rmax. Returns
 * LZ_OK, or LZ_EINVAL when rmax > L/2 or h reaches beyond rmax. O(n · (rmax/w)^dim). */
int lz_edmd_gr_add(const lz_edmd *e, double rmax, gsl_histogram *h);

/* g(r) of bin k of h after `samples` calls of lz_edmd_gr_add on a system of n
 * particles in volume L^dim: the count over the ideal-gas count of the shell. O(1). */
double lz_edmd_gr_value(const lz_edmd *e, const gsl_histogram *h, size_t k, size_t samples);

/* Unwrapped positions for the mean-square displacement. */
typedef struct {
	size_t n;
	double *start;  /* unwrapped positions at the start, 3 per particle */
	double *last;   /* unwrapped positions at the last update */
} lz_edmd_track;

/* Start tracking e's particles at now. NULL with lz_error on no memory. O(n). */
lz_edmd_track *lz_edmd_track_alloc(const lz_edmd *e);
void lz_edmd_track_free(lz_edmd_track *tr);

/* Update the unwrapped positions to now: each displacement since the last update is
 * taken as the nearest image, so call it before any particle can have moved L/2
 * (every few collisions per particle is safe). Precondition: no lz_edmd_sort since
 * the last update (numbers change; call it right after a run, sort_every = 0 while
 * tracking). O(n). */
void lz_edmd_track_update(lz_edmd_track *tr, const lz_edmd *e);

/* Mean-square displacement since the start, σ², over all particles. O(n). */
double lz_edmd_track_msd(const lz_edmd_track *tr);

#endif
