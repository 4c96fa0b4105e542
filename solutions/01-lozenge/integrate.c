/* integrate.c — one time step of each integrator (graded).
 *
 * The state layout (which quantity lives at which time) is the table in
 * lib/include/lz/integrate.h. Every step calls lz_md_force(s) exactly once, at the
 * new positions. lz_md_step has already checked dt, and advances the clock s->t
 * itself afterwards.
 */
#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/vec.h"

/* Explicit Euler: r(t+dt) = r + dt v(t); v(t+dt) = v + dt a(t); then a = F(r(t+dt)).
 * Both updates use the old state. */
int lz_step_euler(lz_md *s, double dt)
{
	/* Hint: drift r with the OLD v, kick v with the old a, then lz_md_force(s).
	 * Using the new v for r turns this into symplectic Euler.
	 * lz_axpy (lz/vec.h) is y += alpha x. See lessons/01-lozenge/README.md §1, §3. */
	/* LZ_SOLUTION_BEGIN */
	size_t len = s->n * (size_t)s->dim;
	lz_axpy(s->r, dt, s->v, len);
	lz_axpy(s->v, dt, s->a, len);
	return lz_md_force(s);
	/* LZ_SOLUTION_END */
}

/* Symplectic Euler, kick then drift: v(t+dt) = v + dt a(t); r(t+dt) = r + dt v(t+dt);
 * a = F(r(t+dt)). */
int lz_step_symplectic_euler(lz_md *s, double dt)
{
	/* Hint: Euler's two updates in the other order: kick v with a(t), then drift r
	 * with the NEW v, then the force. The swap bounds the energy error (a shadow
	 * energy is conserved). See lessons/01-lozenge/README.md §1, §5. */
	/* LZ_SOLUTION_BEGIN */
	size_t len = s->n * (size_t)s->dim;
	lz_axpy(s->v, dt, s->a, len);
	lz_axpy(s->r, dt, s->v, len);
	return lz_md_force(s);
	/* LZ_SOLUTION_END */
}

/* Position (Störmer) Verlet: r(t+dt) = 2 r(t) - r(t-dt) + dt² a(t), the velocity
 * v(t) = (r(t+dt) - r(t-dt)) / (2 dt), r_prev <- r(t), then a = F(r(t+dt)). */
int lz_step_verlet(lz_md *s, double dt)
{
	/* Hint: per coordinate, next = r + ((r - r_prev) + dt² a) (small terms first),
	 * v = (next - r_prev) / (2 dt), then r_prev = r and r = next: keep the old r until
	 * v is done. A stale r_prev breaks the recursion.
	 * See lessons/01-lozenge/README.md §2, §6. */
	/* LZ_SOLUTION_BEGIN */
	size_t len = s->n * (size_t)s->dim;
	double dt2 = dt * dt, inv2dt = 0.5 / dt;
	double *r = s->r, *rp = s->r_prev, *v = s->v;
	const double *a = s->a;
	for (size_t i = 0; i < len; i++) {
		/* The small terms first, then the large r: the thesis' grouping rule. */
		double next = r[i] + ((r[i] - rp[i]) + dt2 * a[i]);
		v[i] = (next - rp[i]) * inv2dt;
		rp[i] = r[i];
		r[i] = next;
	}
	return lz_md_force(s);
	/* LZ_SOLUTION_END */
}

/* Velocity Verlet: half kick v += dt/2 a(t); drift r += dt v; a = F(r(t+dt));
 * half kick v += dt/2 a(t+dt). */
int lz_step_velocity_verlet(lz_md *s, double dt)
{
	/* Hint: half kick, drift, lz_md_force(s), half kick. The second half kick must
	 * use the NEW a, so it comes after the force (and only if that succeeded).
	 * See lessons/01-lozenge/README.md §3, §4. */
	/* LZ_SOLUTION_BEGIN */
	size_t len = s->n * (size_t)s->dim;
	lz_axpy(s->v, 0.5 * dt, s->a, len);
	lz_axpy(s->r, dt, s->v, len);
	int status = lz_md_force(s);
	if (status != LZ_OK)
		return status;
	lz_axpy(s->v, 0.5 * dt, s->a, len);
	return status;
	/* LZ_SOLUTION_END */
}

/* Leapfrog with v at half steps: v(t+dt/2) = v(t-dt/2) + dt a(t);
 * r(t+dt) = r(t) + dt v(t+dt/2); a = F(r(t+dt)). */
int lz_step_leapfrog(lz_md *s, double dt)
{
	/* Hint: s->v holds v(t - dt/2): one full kick takes it to t + dt/2 and the drift
	 * uses it. No half kicks here: the half step lives in the state layout, which
	 * lz_md_start prepared. See lessons/01-lozenge/README.md §3, §4. */
	/* LZ_SOLUTION_BEGIN */
	size_t len = s->n * (size_t)s->dim;
	lz_axpy(s->v, dt, s->a, len);
	lz_axpy(s->r, dt, s->v, len);
	return lz_md_force(s);
	/* LZ_SOLUTION_END */
}
