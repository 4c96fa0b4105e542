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
 * `make lesson STAGE=01`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

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
	LZ_TODO();
}

/* Symplectic Euler, kick then drift: v(t+dt) = v + dt a(t); r(t+dt) = r + dt v(t+dt);
 * a = F(r(t+dt)). */
int lz_step_symplectic_euler(lz_md *s, double dt)
{
	/* Hint: Euler's two updates in the other order: kick v with a(t), then drift r
	 * with the NEW v, then the force. The swap bounds the energy error (a shadow
	 * energy is conserved). See lessons/01-lozenge/README.md §1, §5. */
	LZ_TODO();
}

/* Position (Störmer) Verlet: r(t+dt) = 2 r(t) - r(t-dt) + dt² a(t), the velocity
 * v(t) = (r(t+dt) - r(t-dt)) / (2 dt), r_prev <- r(t), then a = F(r(t+dt)). */
int lz_step_verlet(lz_md *s, double dt)
{
	/* Hint: per coordinate, next = r + ((r - r_prev) + dt² a) (small terms first),
	 * v = (next - r_prev) / (2 dt), then r_prev = r and r = next: keep the old r until
	 * v is done. A stale r_prev breaks the recursion.
	 * See lessons/01-lozenge/README.md §2, §6. */
	LZ_TODO();
}

/* Velocity Verlet: half kick v += dt/2 a(t); drift r += dt v; a = F(r(t+dt));
 * half kick v += dt/2 a(t+dt). */
int lz_step_velocity_verlet(lz_md *s, double dt)
{
	/* Hint: half kick, drift, lz_md_force(s), half kick. The second half kick must
	 * use the NEW a, so it comes after the force (and only if that succeeded).
	 * See lessons/01-lozenge/README.md §3, §4. */
	LZ_TODO();
}

/* Leapfrog with v at half steps: v(t+dt/2) = v(t-dt/2) + dt a(t);
 * r(t+dt) = r(t) + dt v(t+dt/2); a = F(r(t+dt)). */
int lz_step_leapfrog(lz_md *s, double dt)
{
	/* Hint: s->v holds v(t - dt/2): one full kick takes it to t + dt/2 and the drift
	 * uses it. No half kicks here: the half step lives in the state layout, which
	 * lz_md_start prepared. See lessons/01-lozenge/README.md §3, §4. */
	LZ_TODO();
}
