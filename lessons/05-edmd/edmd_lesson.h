/* edmd_lesson.h — what the speed experiments of lesson 05 share: a fluid melted from
 * the lattice, handed over as positions and velocities so that every option under
 * test starts from the same state, and a timed stretch of a run.
 *
 * Everything here is static inline, so that a driver that does not use a helper does
 * not warn about it. Not a library: the drivers are the only users.
 */
#ifndef EDMD_LESSON_H
#define EDMD_LESSON_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define EDMD_LESSON_CHUNK 256  /* events between looks at the clock */

/* The system p melted from the lattice (seed) by `melt` events per particle: its
 * state into *r and *v (3 per particle, malloc'd, the caller frees them), and, where
 * the pointers are not NULL, the cells per side it chose and the box side L (σ).
 * LZ_OK, or the error of the run. */
static inline int edmd_lesson_melt(const lz_edmd_params *p, unsigned seed, double melt,
                                   double **r, double **v, int *m_auto, double *L)
{
	lz_edmd *e = lz_edmd_alloc(p);
	lz_rng *rng = lz_rng_alloc(NULL, seed);
	int st = e && rng ? lz_edmd_place_lattice(e, rng) : LZ_ENOMEM;
	if (st == LZ_OK)
		st = lz_edmd_run(e, (uint64_t)(melt * (double)p->n), INFINITY);
	*r = malloc(3 * p->n * sizeof **r);
	*v = malloc(3 * p->n * sizeof **v);
	if (st == LZ_OK && (!*r || !*v))
		st = lz_error(LZ_ENOMEM, "no memory for %zu particles", p->n);
	if (st == LZ_OK) {
		lz_edmd_get(e, *r, *v);
		if (m_auto)
			*m_auto = e->m[0];
		if (L)
			*L = e->L;
	}
	lz_edmd_free(e);
	lz_rng_free(rng);
	return st;
}

/* What one timed stretch took. */
typedef struct {
	double cpu;         /* CPU seconds */
	double events, collisions, rebuilds;
} edmd_lesson_stretch;

/* Run e for at least `budget` CPU seconds from reset counters; what it took into *s. */
static inline int edmd_lesson_time(lz_edmd *e, double budget, edmd_lesson_stretch *s)
{
	lz_edmd_reset_counts(e);
	double t0 = lz_cpu_now(), t;
	do {
		int st = lz_edmd_run(e, EDMD_LESSON_CHUNK, INFINITY);
		if (st)
			return st;
		t = lz_cpu_now();
	} while (t - t0 < budget);
	*s = (edmd_lesson_stretch){t - t0, (double)e->events, (double)e->collisions,
	                           (double)e->rebuilds};
	return LZ_OK;
}

#endif
