/* lz/integrate.h — time stepping of Newton's equations, a = F(r)/m with m = 1.
 *
 * Reduced units: lengths σ, energies ε, time τ = σ√(m/ε). The state is N particles
 * in dim = 1..3 dimensions, stored flat (lz/vec.h). The schemes differ in WHEN the
 * stored quantities live — this table is the contract between the step functions
 * (graded, solutions/01-lozenge/integrate.c) and everything that reads the state:
 *
 *   integrator         r       v               a         one step costs
 *   euler              t       t               F(r(t))   1 force evaluation
 *   symplectic-euler   t       t               F(r(t))   1
 *   verlet (Störmer)   t       t - dt (*)      F(r(t))   1  (+ r_prev = r(t - dt))
 *   velocity-verlet    t       t               F(r(t))   1
 *   leapfrog           t       t - dt/2        F(r(t))   1
 *
 * (*) Position Verlet does not carry a velocity; it reconstructs it with the
 * central difference v(t) = (r(t+dt) - r(t-dt)) / (2 dt), which needs the future
 * position, so after a step v is the velocity one step back. s->u_prev holds the
 * potential energy at that same time, so lz_md_energy can pair them.
 *
 * Every step calls lz_md_force() exactly once. The clock is the library's: lz_md_step
 * keeps t = t0 + k·dt from the step count k, because adding dt to t ten million
 * times would lose ~1e-4 τ to round-off (the step functions leave t alone).
 */
#ifndef LZ_INTEGRATE_H
#define LZ_INTEGRATE_H

#include <stddef.h>

/* A force law: from positions r (n*dim) write accelerations a (n*dim) and the total
 * potential energy *u. Returns LZ_OK or an lz_error code. */
typedef int lz_force_fn(size_t n, int dim, const double *r, double *a, double *u,
                        void *params);

typedef enum {
	LZ_EULER,
	LZ_SYMPLECTIC_EULER,
	LZ_VERLET,
	LZ_VELOCITY_VERLET,
	LZ_LEAPFROG,
	LZ_NINTEGRATORS
} lz_integrator;

typedef struct {
	size_t n;         /* particles */
	int dim;          /* 1, 2 or 3 */
	double t;         /* the time of r: t0 + nsteps·dt, never accumulated */
	double t0;        /* the time of the last (re)start: lz_md_start, or a change of dt */
	unsigned long long nsteps;  /* steps of dt since t0 */
	double dt;        /* the current step (fixed for verlet and leapfrog) */
	double *r;        /* positions at t, n*dim */
	double *v;        /* velocities, at the time the table above gives */
	double *a;        /* accelerations F(r(t)) */
	double *r_prev;   /* verlet: positions at t - dt */
	double *scratch;  /* n*dim doubles a step may use freely */
	double u;         /* potential energy at r(t) */
	double u_prev;    /* potential energy one force evaluation earlier */
	int v_lags;       /* verlet: 1 once stepping (v is at t - dt) */
	unsigned long force_evals;  /* force evaluations so far (the cost measure) */
	lz_force_fn *force;
	void *force_params;
} lz_md;

/* A state for n >= 1 particles in dim 1..3, zeroed, with force law f. O(n).
 * NULL with lz_error on bad sizes or no memory. */
lz_md *lz_md_alloc(size_t n, int dim, lz_force_fn *f, void *params);
void lz_md_free(lz_md *s);

/* Evaluate the force at r: u_prev <- u; a, u <- F(r); force_evals += 1.
 * Returns the force law's status; LZ_EPHYS if a or u came out non-finite. */
int lz_md_force(lz_md *s);

/* Prepare a state whose r and v hold positions and velocities at time t for
 * stepping with `m` at step dt: computes a and u, and sets r_prev = r(t - dt)
 * by Taylor expansion (verlet) or shifts v to t - dt/2 (leapfrog).
 * LZ_EINVAL unless dt is finite and > 0. */
int lz_md_start(lz_md *s, lz_integrator m, double dt);

/* One step with integrator m (the graded functions below), after checking dt:
 * finite, > 0, and for verlet and leapfrog equal to the dt of lz_md_start; then
 * t = t0 + nsteps·dt. Another dt (euler, symplectic-euler, velocity-verlet) re-bases
 * the clock: t0 = t, nsteps = 0. */
int lz_md_step(lz_md *s, lz_integrator m, double dt);

/* The kinetic energy Σ v²/2 and the total energy at one consistent time, which is
 * returned in *when (t, or t - dt for verlet once stepping). For leapfrog the
 * half-step velocities are synchronised: v(t) = v(t - dt/2) + a(t) dt/2. O(n). */
double lz_md_kinetic(const lz_md *s, lz_integrator m);
double lz_md_energy(const lz_md *s, lz_integrator m, double *when);

/* Names as scene files spell them: "euler", "symplectic-euler", "verlet",
 * "velocity-verlet", "leapfrog". parse returns LZ_EINVAL (naming the choices). */
const char *lz_integrator_name(lz_integrator m);
int lz_integrator_parse(const char *name, lz_integrator *m);

/* Round r, v, a, r_prev to single precision: precision=float keeps the state in
 * float between steps (one +, × in double then rounded equals the float result). */
void lz_md_round_float(lz_md *s);

/* ---- graded: one step of length dt (dt > 0, checked by lz_md_step, which also
 * advances s->t) -------------------------------------------------------------- */

/* Explicit Euler: r += dt v(t); v += dt a(t); then a = F(r(t+dt)). First order;
 * on the harmonic oscillator the energy grows by exactly (1 + ω²dt²) per step. */
int lz_step_euler(lz_md *s, double dt);

/* Symplectic Euler, kick then drift: v += dt a(t); r += dt v(t+dt); a = F(r).
 * First order, but conserves a shadow energy (no drift). */
int lz_step_symplectic_euler(lz_md *s, double dt);

/* Position (Störmer) Verlet: r(t+dt) = 2 r(t) - r(t-dt) + dt² a(t); v <- the central
 * difference (r(t+dt) - r(t-dt)) / (2dt), the velocity at t; r_prev <- r(t);
 * a = F(r(t+dt)). Second order, time reversible. s->scratch may hold a copy of r(t)
 * if wanted; one pass per coordinate needs none. */
int lz_step_verlet(lz_md *s, double dt);

/* Velocity Verlet: v += dt/2 a(t); r += dt v; a = F(r(t+dt)); v += dt/2 a(t+dt).
 * Second order, symplectic, time reversible. */
int lz_step_velocity_verlet(lz_md *s, double dt);

/* Leapfrog with v at half steps: v(t+dt/2) = v(t-dt/2) + dt a(t);
 * r(t+dt) = r(t) + dt v(t+dt/2); a = F(r(t+dt)). The same positions as velocity
 * Verlet. */
int lz_step_leapfrog(lz_md *s, double dt);

#endif
