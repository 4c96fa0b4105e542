/* YOUR FILE — this is the file you fill in for stage 01-lozenge.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/01-lozenge/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=01`; see your own code at work with
 * `make lesson STAGE=01 IMPL=assignments`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* integrate.c — one time step of each integrator (graded).
 *
 * The state layout (which quantity lives at which time) is the table in
 * lib/include/lz/integrate.h. Every step calls lz_md_force(s) exactly once, at the
 * new positions, and advances s->t by dt. lz_md_step has already checked dt.
 */
#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/vec.h"

/* Explicit Euler: r(t+dt) = r + dt v(t); v(t+dt) = v + dt a(t); then a = F(r(t+dt)).
 * Both updates use the old state. */
int lz_step_euler(lz_md *s, double dt)
{
	/* Hint: move r with the OLD velocity first, then kick v with the old a, then
	 * evaluate the force at the new positions with lz_md_force(s) and advance s->t.
	 * Using the new v for r turns this into symplectic Euler — a different scheme.
	 * lz_axpy (lz/vec.h) does y += alpha x.
	 * See lessons/01-lozenge/README.md, "Taylor expansions and Euler". */
	LZ_TODO();
}

/* Symplectic Euler, kick then drift: v(t+dt) = v + dt a(t); r(t+dt) = r + dt v(t+dt);
 * a = F(r(t+dt)). */
int lz_step_symplectic_euler(lz_md *s, double dt)
{
	/* Hint: the same two updates as Euler in the other order: kick v with a(t), then
	 * drift r with the NEW v. This one swap makes the scheme symplectic: its energy
	 * error stays bounded instead of growing.
	 * See lessons/01-lozenge/README.md, "Stability and the shadow energy". */
	LZ_TODO();
}

/* Position (Störmer) Verlet: r(t+dt) = 2 r(t) - r(t-dt) + dt² a(t), the velocity
 * v(t) = (r(t+dt) - r(t-dt)) / (2 dt), r_prev <- r(t), then a = F(r(t+dt)). */
int lz_step_verlet(lz_md *s, double dt)
{
	/* Hint: per coordinate you need r(t+dt), the central-difference v(t) and then
	 * r_prev = old r — keep the old r until v is computed. Group terms of like size:
	 * r + ((r - r_prev) + dt² a) loses fewer digits than (2r - r_prev) + dt² a.
	 * Forgetting to update r_prev breaks the recursion.
	 * See lessons/01-lozenge/README.md, "The Verlet scheme" and "Floating point". */
	LZ_TODO();
}

/* Velocity Verlet: half kick v += dt/2 a(t); drift r += dt v; a = F(r(t+dt));
 * half kick v += dt/2 a(t+dt). */
int lz_step_velocity_verlet(lz_md *s, double dt)
{
	/* Hint: kick–drift–force–kick. The second half-kick must use the NEW
	 * acceleration, so it comes after lz_md_force(s) (and only if that succeeded).
	 * Both kicks are dt/2.
	 * See lessons/01-lozenge/README.md, "The lozenge diagram" (velocity Verlet). */
	LZ_TODO();
}

/* Leapfrog with v at half steps: v(t+dt/2) = v(t-dt/2) + dt a(t);
 * r(t+dt) = r(t) + dt v(t+dt/2); a = F(r(t+dt)). */
int lz_step_leapfrog(lz_md *s, double dt)
{
	/* Hint: s->v holds v(t - dt/2) (lz_md_start shifted it), so one full kick takes
	 * it to t + dt/2, and the drift uses that mid-step velocity. Do not add half
	 * kicks: the halves live in the state layout, not in the step.
	 * See lessons/01-lozenge/README.md, "The lozenge diagram" (leapfrog). */
	LZ_TODO();
}
