/* stage01.h — set-ups shared by the stage-01 suites (static inline: a suite uses
 * what it needs). They call only library code; the graded steps run in the tests. */
#ifndef STAGE01_H
#define STAGE01_H

#include <math.h>

#include "lztest.h"
#include "lz/integrate.h"
#include "lz/potential.h"
#include "lz/rng.h"

/* Every integrator, for tests that hold for all of them. */
static const lz_integrator all_integrators[LZ_NINTEGRATORS] = {
	LZ_EULER, LZ_SYMPLECTIC_EULER, LZ_VERLET, LZ_VELOCITY_VERLET, LZ_LEAPFROG};

/* n oscillators in dim dimensions, every coordinate at x0 with velocity v0, started
 * for integrator m at step dt. */
static inline lz_md *osc_new(lz_integrator m, lz_harmonic *p, size_t n, int dim, double dt,
                             double x0, double v0)
{
	lz_md *s = lz_md_alloc(n, dim, lz_harmonic_force, p);
	ck_assert_msg(s != NULL, "lz_md_alloc failed: %s", lz_error_message());
	for (size_t i = 0; i < n * (size_t)dim; i++) {
		s->r[i] = x0;
		s->v[i] = v0;
	}
	ck_assert_msg(lz_md_start(s, m, dt) == LZ_OK, "lz_md_start: %s", lz_error_message());
	return s;
}

/* One step through lz_md_step (which calls the graded function), asserted. Check's
 * ck_assert marks every passing point through a pipe in fork mode: too slow for a
 * loop of 1e7 steps, hence the plain test. */
static inline void step_ok(lz_md *s, lz_integrator m, double dt)
{
	int status = lz_md_step(s, m, dt);
	if (status != LZ_OK)
		ck_abort_msg("%s: a step of dt = %g failed with status %d (%s)",
		             lz_integrator_name(m), dt, status, lz_error_message());
}

/* Position and velocity of coordinate i at one common time, read through the state
 * layout of lz/integrate.h: Verlet's v lags a step and pairs with r_prev; leapfrog's
 * v is half a step behind r and is synchronised with half a kick. */
static inline void sync_xv(const lz_md *s, lz_integrator m, size_t i, double *x, double *v)
{
	*x = m == LZ_VERLET && s->v_lags ? s->r_prev[i] : s->r[i];
	*v = m == LZ_LEAPFROG ? s->v[i] + 0.5 * s->dt * s->a[i] : s->v[i];
}

/* The 108-particle Lennard-Jones fluid of the lesson: fcc at density 0.8, cutoff
 * 2.5, Maxwell velocities at temperature T from a fixed seed. */
static inline lz_md *lj_fluid_new(lz_lj *p, size_t n, double rho, double T, unsigned long seed)
{
	ck_assert_msg(lz_lj_init(p, n, 3, rho, 2.5) == LZ_OK, "lz_lj_init: %s",
	              lz_error_message());
	lz_md *s = lz_md_alloc(n, 3, lz_lj_force, p);
	lz_rng *rng = lz_rng_alloc(NULL, seed);
	ck_assert_msg(s && rng, "allocation failed: %s", lz_error_message());
	ck_assert_msg(lz_lattice_start(s->r, n, 3, p->box) == LZ_OK, "lattice: %s",
	              lz_error_message());
	lz_maxwell_velocities(s->v, n, 3, T, rng);
	lz_rng_free(rng);
	return s;
}

#endif
