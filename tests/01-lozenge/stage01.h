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

/* ---- the harmonic oscillator, solved exactly for every scheme ----
 *
 * On ẍ = -ω²x every scheme is a linear map of (x, v), so its k-th step has a closed
 * form (derived by hand; Ω = ω dt):
 *   Verlet family: x_{k+1} - 2 cos θ x_k + x_{k-1} = 0 with cos θ = 1 - Ω²/2, i.e.
 *     θ = 2 asin(Ω/2), and x_1 = x0 cos θ + dt v0, so x_k = x0 cos kθ + B sin kθ,
 *     B = dt v0 / sin θ. Velocity Verlet's v_k = (x_{k+1} - cos θ x_k)/dt
 *     = v0 cos kθ - x0 (sin θ/dt) sin kθ; Verlet's central difference is the same
 *     number one step later; leapfrog's (x_k - x_{k-1})/dt is
 *     ω (B cos (k-½)θ - x0 sin (k-½)θ), because 2 sin(θ/2) = Ω.
 *   Symplectic Euler: the same recurrence (trace 2 - Ω², determinant 1) from
 *     x_1 = x0 (1 - Ω²) + dt v0, so B = (dt v0 - x0 Ω²/2) / sin θ; its v_k is
 *     (x_k - x_{k-1})/dt, the leapfrog form.
 *   Euler: ωx + iv is multiplied by 1 - iΩ = ρ e^{-iφ} per step, ρ = √(1 + Ω²),
 *     φ = atan Ω: x_k = ρ^k (x0 cos kφ + (v0/ω) sin kφ), v_k = ρ^k (v0 cos kφ -
 *     ω x0 sin kφ).
 * Needs Ω < 2 (the stability limit) for the Verlet family and symplectic Euler. */
typedef struct {
	double x, v, x_prev;  /* r, v as the layout stores them, and x_{k-1} */
} osc_exact;

static inline osc_exact osc_exact_state(lz_integrator m, double omega, double dt, double x0,
                                        double v0, double k)
{
	double big = omega * dt;
	osc_exact e;
	if (m == LZ_EULER) {
		double phi = atan(big), grow = exp(0.5 * k * log1p(big * big));
		e.x = grow * (x0 * cos(k * phi) + v0 / omega * sin(k * phi));
		e.v = grow * (v0 * cos(k * phi) - omega * x0 * sin(k * phi));
		double back = exp(0.5 * (k - 1.0) * log1p(big * big));
		e.x_prev = back * (x0 * cos((k - 1.0) * phi) + v0 / omega * sin((k - 1.0) * phi));
		return e;
	}
	double th = 2.0 * asin(0.5 * big), sn = sin(th);
	double b = m == LZ_SYMPLECTIC_EULER ? (dt * v0 - 0.5 * x0 * big * big) / sn : dt * v0 / sn;
	e.x = x0 * cos(k * th) + b * sin(k * th);
	e.x_prev = x0 * cos((k - 1.0) * th) + b * sin((k - 1.0) * th);
	double kv = m == LZ_VERLET && k >= 1.0 ? k - 1.0 : k;
	if (m == LZ_LEAPFROG || m == LZ_SYMPLECTIC_EULER)
		e.v = omega * (b * cos((k - 0.5) * th) - x0 * sin((k - 0.5) * th));
	else
		e.v = v0 * cos(kv * th) - x0 * sn / dt * sin(kv * th);
	return e;
}

/* The largest distance of r, v (and Verlet's r_prev) from the closed form after k
 * steps, over the n*dim coordinates, coordinate i started from x0[i], v0[i]. */
static inline double osc_deviation(const lz_md *s, lz_integrator m, double omega, double dt,
                                   const double *x0, const double *v0, double k)
{
	double worst = 0.0;
	for (size_t i = 0; i < s->n * (size_t)s->dim; i++) {
		osc_exact e = osc_exact_state(m, omega, dt, x0[i], v0[i], k);
		worst = fmax(worst, fmax(fabs(s->r[i] - e.x), fabs(s->v[i] - e.v)));
		if (m == LZ_VERLET)  /* lz_md_start's Taylor r_prev is x_{-1} exactly */
			worst = fmax(worst, fabs(s->r_prev[i] - e.x_prev));
	}
	return worst;
}

/* The quantity scheme m conserves exactly on ẍ = -ω²x (datasets/reference/harmonic.csv), summed over
 * the coordinates, x and v taken at one time:
 *   Verlet family     v²/2 + ω²x²/2 (1 - Ω²/4)
 *   symplectic Euler  v²/2 + ω²x²/2 - (dt ω²/2) x v
 * It is conserved for every Ω, also beyond the stability limit (where it is no longer
 * positive). */
static inline double shadow_energy(const lz_md *s, lz_integrator m, double omega, double dt)
{
	double h = 0.0, w2 = omega * omega;
	for (size_t i = 0; i < s->n * (size_t)s->dim; i++) {
		double x, v;
		sync_xv(s, m, i, &x, &v);
		if (m == LZ_SYMPLECTIC_EULER)
			h += 0.5 * v * v + 0.5 * w2 * x * x - 0.5 * dt * w2 * x * v;
		else
			h += 0.5 * v * v + 0.5 * w2 * x * x * (1.0 - 0.25 * w2 * dt * dt);
	}
	return h;
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
