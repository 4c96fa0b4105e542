/* walk_check.h — what the stage-02 tests that run walkers check alike.
 *
 * A walker test judges lz_walk_try_move and lz_walk_sweep, but it runs on a box that
 * lz_lattice_dctable filled and measures distances with lz_lattice_min_dist2: when
 * those are wrong the walkers cannot be judged, so the box is checked first
 * (wc_require_box). A sweep is then replayed move by move against the header's rule
 * (wc_sweep): every move that creates no overlap and stays between the walls must be
 * accepted, every other one rejected, each particle seeing the others where the
 * sweep had left them. Distances here are the tests' own arithmetic, never the
 * functions under test.
 */
#ifndef WALK_CHECK_H
#define WALK_CHECK_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/walk.h"

/* The nearest-image distance² of sites p and q (coordinates in [0, L)) of a periodic
 * box of side L on lattice `kind`, by search over the images. */
int64_t wc_near_d2(lz_lattice_kind kind, int64_t L, const int32_t *p, const int32_t *q);

/* Precondition of a walker test: the box of w has the saw-tooth table and, when w has
 * two or more particles, its minimum image is the nearest on a grid of displacements
 * across the whole box. Fails the test naming the function to fix first. */
void wc_require_box(const lz_walk *w);

/* Scratch for replayed sweeps, and the statistics of the directions drawn. */
typedef struct {
	lz_walk *w;
	int32_t *old, *cur;  /* positions before the sweep, and as the sweep left them */
	int *odir;           /* directions before the sweep */
	long rejected;       /* ballistic moves rejected */
	long kept;           /* ... after which the new direction equals the old one */
	long tried[26];      /* random walk: the moves offered per direction */
} wc_run;

wc_run *wc_run_new(lz_walk *w);
void wc_run_free(wc_run *run);

/* One lz_walk_sweep of run->w, replayed: fails the test at the first move that breaks
 * the rule, a return value other than the number of moves, or counters that do not
 * add up. Returns the accepted moves. O(n²). */
size_t wc_sweep(wc_run *run, gsl_rng *rng);

/* After the sweeps: a ballistic particle whose move was rejected draws a direction
 * uniformly from all ndir, so it keeps the old one with probability 1/ndir. */
void wc_require_uniform_redraws(const wc_run *run, const char *what);

/* After the sweeps: the random walk offered every direction equally often
 * (chi-square, p > 1e-4). */
void wc_require_uniform_directions(const wc_run *run, const char *what);

#endif
