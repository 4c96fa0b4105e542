/* test_accuracy.c — stability limit, convergence order, time reversibility and the
 * extremes: tiny steps (round-off) and very long runs. */
#include <math.h>

#include <gsl/gsl_fit.h>

#include "stage01.h"

/* ---- the stability limit ω·dt = 2 (datasets/reference/harmonic.csv) ----
 *
 * One test per scheme and property, so that the points follow the function that is
 * right. Two coordinates start at x = 1 and x = -1/2 with v = 0 (ω = 1), so a step that
 * forgets some of the n*dim coordinates shows. */

enum { LIM_DIM = 2 };
static const double lim_x0[LIM_DIM] = {1.0, -0.5}, lim_v0[LIM_DIM] = {0.0, 0.0};

static lz_md *limit_new(lz_integrator m, lz_harmonic *p, double big_omega)
{
	lz_md *s = lz_md_alloc(1, LIM_DIM, lz_harmonic_force, p);
	ck_assert_msg(s != NULL, "lz_md_alloc failed: %s", lz_error_message());
	for (int i = 0; i < LIM_DIM; i++) {
		s->r[i] = lim_x0[i];
		s->v[i] = lim_v0[i];
	}
	ck_assert_msg(lz_md_start(s, m, big_omega) == LZ_OK, "lz_md_start: %s", lz_error_message());
	return s;
}

/* At Ω = 1.99 the scheme is stable: 1e5 steps stay on its exact discrete solution
 * x_k = x0 cos kθ, cos θ = 1 - Ω²/2 (stage01.h), so |x| never exceeds |x0|. Near the
 * limit a rounding error is amplified by ~1/sin θ = 5 and the phase error adds up
 * over the steps: ~1e5 · 5 · 1e-16 = 5e-11, so 1e-8 separates round-off from a wrong
 * scheme (whose error is O(1) here). */
static void check_stable(lz_integrator m)
{
	const double big_omega = 1.99;
	const char *name = lz_integrator_name(m);
	lz_harmonic p = {1.0};
	lz_md *s = limit_new(m, &p, big_omega);
	double worst_x = 0.0, worst_dev = 0.0;
	int when = 0;
	for (int k = 1; k <= 100000; k++) {
		step_ok(s, m, big_omega);
		for (int i = 0; i < LIM_DIM; i++)
			worst_x = fmax(worst_x, fabs(s->r[i]) / fabs(lim_x0[i]));
		double dev = osc_deviation(s, m, 1.0, big_omega, lim_x0, lim_v0, k);
		if (dev > worst_dev) {
			worst_dev = dev;
			when = k;
		}
	}
	lz_md_free(s);
	ck_assert_msg(worst_x <= 1.0 + 1e-9, "%s at ω·dt = 1.99: |x| reached %.6g times its start "
	              "value within 1e5 steps; the scheme is stable for ω·dt < 2 and |x| never "
	              "exceeds it — check the dt² (or dt/2 + dt/2) factors of the kicks", name,
	              worst_x);
	ck_assert_msg(worst_dev < 1e-8, "%s at ω·dt = 1.99: after %d steps the state is %.2e "
	              "from the exact discrete solution x_k = x0 cos kθ (cos θ = 1 - Ω²/2) and "
	              "its velocity; round-off stays below 1e-8 — is every coordinate updated, "
	              "and is v stored at the time the layout table gives?", name, when, worst_dev);
}

LZ_TEST(stable_just_below_the_limit_verlet)
{
	check_stable(LZ_VERLET);
}
END_TEST

LZ_TEST(stable_just_below_the_limit_velocity_verlet)
{
	check_stable(LZ_VELOCITY_VERLET);
}
END_TEST

LZ_TEST(stable_just_below_the_limit_leapfrog)
{
	check_stable(LZ_LEAPFROG);
}
END_TEST

/* At Ω = 2.01 the step has the real eigenvalues λ± = c ± √(c² - 1), c = 1 - Ω²/2,
 * λ- ≈ -1.2213 and λ+ = 1/λ- ≈ -0.8188: from v = 0 the positions are exactly
 * x_k = x0 (λ+^k + λ-^k)/2, and |x| passes 1e3 |x0| after ~35 steps. The shadow
 * energy (stage01.h) is still conserved, now indefinite; it involves v. Both are
 * held relative to the growing scale |λ-|^k (round-off ~k ε, below 1e-12). */
static void check_unstable(lz_integrator m)
{
	const double big_omega = 2.01, c = 1.0 - 0.5 * big_omega * big_omega;
	const double lp = c + sqrt(c * c - 1.0), lm = c - sqrt(c * c - 1.0);
	const char *name = lz_integrator_name(m);
	lz_harmonic p = {1.0};
	lz_md *s = limit_new(m, &p, big_omega);
	double h0 = shadow_energy(s, m, 1.0, big_omega), worst_x = 1.0, worst_dev = 0.0, dh = 0.0;
	int k = 0;
	while (k < 500 && worst_x <= 1e3) {
		step_ok(s, m, big_omega);
		k++;
		double scale = pow(fabs(lm), k), e2 = 0.0;
		for (int i = 0; i < LIM_DIM; i++) {
			double x = lim_x0[i] * 0.5 * (pow(lp, k) + pow(lm, k));
			worst_dev = fmax(worst_dev, fabs(s->r[i] - x) / scale);
			worst_x = fmax(worst_x, fabs(s->r[i]) / fabs(lim_x0[i]));
			e2 += s->r[i] * s->r[i] + s->v[i] * s->v[i];
		}
		dh = fmax(dh, fabs(shadow_energy(s, m, 1.0, big_omega) - h0) / e2);
	}
	lz_md_free(s);
	ck_assert_msg(worst_x > 1e3, "%s at ω·dt = 2.01: |x| stayed below %.3g times its start "
	              "for 500 steps; the scheme must blow up beyond ω·dt = 2 (growth ≈ 1.22 per "
	              "step) — a scheme stable here is using a weaker force, e.g. dt²/2 instead of "
	              "dt² in Verlet, or a single dt/2 kick", name, worst_x);
	ck_assert_msg(worst_dev < 1e-9, "%s at ω·dt = 2.01: the positions left the exact "
	              "unstable solution x_k = x0 (λ+^k + λ-^k)/2 (λ- ≈ -1.2213) by %.2e of |λ-|^k; "
	              "blowing up is not enough, it must be this growth — check the order of "
	              "kick, drift and force", name, worst_dev);
	ck_assert_msg(dh < 1e-9, "%s at ω·dt = 2.01: the shadow energy v²/2 + x²/2 (1 - Ω²/4), "
	              "conserved exactly by the scheme for every Ω, changed by %.2e of x² + v² — "
	              "the stored velocity is not the scheme's (central difference for Verlet, "
	              "half-step v for leapfrog)", name, dh);
}

LZ_TEST(unstable_just_above_the_limit_verlet)
{
	check_unstable(LZ_VERLET);
}
END_TEST

LZ_TEST(unstable_just_above_the_limit_velocity_verlet)
{
	check_unstable(LZ_VELOCITY_VERLET);
}
END_TEST

LZ_TEST(unstable_just_above_the_limit_leapfrog)
{
	check_unstable(LZ_LEAPFROG);
}
END_TEST

/* ---- convergence order ---- */

/* The time the stored v belongs to after k steps (lz/integrate.h's table). */
static double v_time(lz_integrator m, int k, double dt)
{
	return m == LZ_VERLET ? (k - 1) * dt : m == LZ_LEAPFROG ? (k - 0.5) * dt : k * dt;
}

/* The largest error of x and v against the exact motion over a run to t = 10 with
 * ω = 1 for two oscillators, x = cos t and x = sin t (two coordinates, so a step that
 * skips some of them shows): the global error. Steps are compared with the exact
 * solution at k·dt, not at s->t. */
static double global_error(lz_integrator m, double dt)
{
	lz_harmonic p = {1.0};
	lz_md *s = lz_md_alloc(1, 2, lz_harmonic_force, &p);
	s->r[0] = 1.0;
	s->v[1] = 1.0;
	ck_assert(lz_md_start(s, m, dt) == LZ_OK);
	int steps = (int)lround(10.0 / dt);
	double worst = 0.0;
	for (int k = 1; k <= steps; k++) {
		step_ok(s, m, dt);
		double t = k * dt, tv = v_time(m, k, dt);
		worst = fmax(worst, fmax(fabs(s->r[0] - cos(t)), fabs(s->r[1] - sin(t))));
		worst = fmax(worst, fmax(fabs(s->v[0] + sin(tv)), fabs(s->v[1] - cos(tv))));
	}
	lz_md_free(s);
	return worst;
}

/* The slope of log(error) against log(dt) over six halvings of dt from dt0, and the
 * error constant error/dt^order at the smallest dt. */
static double measured_order(lz_integrator m, double dt0, int order, double *constant)
{
	double ldt[6], lerr[6], c0, c1, cov00, cov01, cov11, sumsq;
	for (int i = 0; i < 6; i++) {
		double dt = dt0 / (1 << i);
		ldt[i] = log(dt);
		lerr[i] = log(global_error(m, dt));
	}
	gsl_fit_linear(ldt, 1, lerr, 1, 6, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
	*constant = exp(lerr[5] - order * ldt[5]);
	return c1;
}

static void check_second_order(lz_integrator m)
{
	double c, p = measured_order(m, 0.1, 2, &c);
	ck_assert_msg(fabs(p - 2.0) < 0.1, "%s: the global error of x and v at t <= 10 falls like "
	              "dt^%.2f, expected dt^2 (second order) — a first-order slip (an initial "
	              "half-step missing, a stale force, v at the wrong time) shows here",
	              lz_integrator_name(m), p);
}

LZ_TEST(convergence_order_verlet)
{
	check_second_order(LZ_VERLET);
}
END_TEST

LZ_TEST(convergence_order_velocity_verlet)
{
	check_second_order(LZ_VELOCITY_VERLET);
}
END_TEST

LZ_TEST(convergence_order_leapfrog)
{
	check_second_order(LZ_LEAPFROG);
}
END_TEST

/* The two first-order schemes differ in their error constant, which the order alone
 * cannot see:
 *   Euler multiplies the amplitude by (1 + dt²)^(k/2) ≈ e^(t dt/2): at t = 10 the
 *     error is ≈ 5 dt along the direction of motion, and the worse of its x and v
 *     components is at least 1/√2 of that, so error/dt lies in (3.5, 6) (the phase
 *     error is second order);
 *   symplectic Euler stays on an ellipse tilted by dt/2: x = cos t - (dt/2) sin t,
 *     an error of exactly dt/2 at the largest |sin t|, so error/dt -> 0.5 (the next
 *     order adds ~dt·t ≈ 3e-3 at dt = 3e-4: ±5 % is wide). */
static void check_first_order(lz_integrator m, double lo, double hi)
{
	double c, p = measured_order(m, 0.01, 1, &c);
	ck_assert_msg(fabs(p - 1.0) < 0.1, "%s: the global error of x and v at t <= 10 falls "
	              "like dt^%.2f, expected dt^1 (first order)", lz_integrator_name(m), p);
	ck_assert_msg(c > lo && c < hi, "%s: the global error at t <= 10 is %.3g dt, expected "
	              "between %.3g dt and %.3g dt — explicit Euler (both updates with the old "
	              "state) lets the amplitude grow like e^(t dt/2), symplectic Euler (kick "
	              "first, then drift with the new v) stays within dt/2: are the two swapped?",
	              lz_integrator_name(m), c, lo, hi);
}

LZ_TEST(convergence_order_euler)
{
	check_first_order(LZ_EULER, 3.5, 6.0);
}
END_TEST

LZ_TEST(convergence_order_symplectic_euler)
{
	check_first_order(LZ_SYMPLECTIC_EULER, 0.475, 0.525);
}
END_TEST

/* ---- time reversibility ---- */

/* A pendulum per coordinate: a = -sin x, so reversal is tested on a nonlinear force. */
static int pendulum(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	*u = 0.0;
	for (size_t i = 0; i < n * (size_t)dim; i++) {
		a[i] = -sin(r[i]);
		*u += 1.0 - cos(r[i]);
	}
	return LZ_OK;
}

/* Turn the motion round, each layout its own way:
 *   velocity Verlet, Euler:  v(t) -> -v(t)
 *   leapfrog:                v(t - dt/2) -> -v(t + dt/2) = -(v(t - dt/2) + dt a(t))
 *   Verlet:                  (r, r_prev) = (r(t), r(t - dt)) -> (r(t - dt), r(t)),
 *                            then the force at the new r. */
static void reverse(lz_md *s, lz_integrator m)
{
	size_t len = s->n * (size_t)s->dim;
	for (size_t i = 0; i < len; i++) {
		if (m == LZ_VERLET) {
			double r = s->r[i];
			s->r[i] = s->r_prev[i];
			s->r_prev[i] = r;
		} else if (m == LZ_LEAPFROG) {
			s->v[i] = -(s->v[i] + s->dt * s->a[i]);
		} else {
			s->v[i] = -s->v[i];
		}
	}
	if (m == LZ_VERLET)
		ck_assert(lz_md_force(s) == LZ_OK);
}

/* Forward 1000 steps of dt = 0.05, reverse, 1000 steps back: how far from the start
 * the positions end (Verlet ends one step further back, so its r_prev is compared).
 * A symmetric scheme with the wrong force (half of it, or twice) is reversible too, so
 * the forward run must also be Newton's: a second-order scheme keeps the energy within
 * O(dt²) of E0 with a constant well below 1 (the pendulum's |a|, |v| are below 2), a
 * wrong force moves it by O(E0); the bound is dt² E0. */
static void check_reversible(lz_integrator m)
{
	const double dt = 0.05;
	const int n = 1000;
	const char *name = lz_integrator_name(m);
	lz_md *s = lz_md_alloc(2, 2, pendulum, NULL);
	double start[4];
	for (size_t i = 0; i < 4; i++) {
		s->r[i] = start[i] = 0.6 * (double)i - 0.8;
		s->v[i] = 1.2 - 0.5 * (double)i;
	}
	ck_assert(lz_md_start(s, m, dt) == LZ_OK);
	double e0 = lz_md_energy(s, m, NULL), de = 0.0;
	for (int k = 0; k < n; k++) {
		step_ok(s, m, dt);
		de = fmax(de, fabs(lz_md_energy(s, m, NULL) - e0));
	}
	reverse(s, m);
	for (int k = 0; k < n; k++)
		step_ok(s, m, dt);
	const double *end = m == LZ_VERLET ? s->r_prev : s->r;
	double worst = 0.0;
	for (size_t i = 0; i < 4; i++)
		worst = fmax(worst, fabs(end[i] - start[i]));
	lz_md_free(s);
	ck_assert_msg(de < dt * dt * e0, "%s, pendulum at dt = 0.05: the energy moved by %.2e "
	              "over 1000 steps, more than dt² E0 = %.2e; a second-order scheme stays far "
	              "inside — the forward run is not Newton's (a kick with a factor missing or "
	              "doubled?)", name, de, dt * dt * e0);
	ck_assert_msg(worst < 1e-11, "%s: 1000 steps of a pendulum forward, velocities reversed, "
	              "1000 steps back end %.2e from the start; the scheme is time reversible and "
	              "must return to round-off (< 1e-11) — a kick with a stale force or an "
	              "r_prev not updated breaks the symmetry", name, worst);
}

LZ_TEST(time_reversibility_verlet)
{
	check_reversible(LZ_VERLET);
}
END_TEST

LZ_TEST(time_reversibility_velocity_verlet)
{
	check_reversible(LZ_VELOCITY_VERLET);
}
END_TEST

LZ_TEST(time_reversibility_leapfrog)
{
	check_reversible(LZ_LEAPFROG);
}
END_TEST

LZ_TEST(euler_not_time_reversible_exact)
{
	/* Explicit Euler on ẍ = -x multiplies ωx + iv by 1 - iΩ; reversing v conjugates it.
	 * So n steps, v -> -v, n steps give (1 - iΩ)^n (1 + iΩ)^n = (1 + Ω²)^n times the
	 * conjugate start: x comes back stretched by exactly (1 + Ω²)^n, v reversed and
	 * stretched as much (e^2.5 ≈ 12 for n = 1000, Ω = 0.05). Round-off: ~2000 ε. */
	const double dt = 0.05;
	const int n = 1000;
	lz_harmonic p = {1.0};
	lz_md *s = lz_md_alloc(2, 2, lz_harmonic_force, &p);
	double x0[4], v0[4];
	for (size_t i = 0; i < 4; i++) {
		s->r[i] = x0[i] = 0.6 * (double)i - 0.8;
		s->v[i] = v0[i] = 1.2 - 0.5 * (double)i;
	}
	ck_assert(lz_md_start(s, LZ_EULER, dt) == LZ_OK);
	for (int k = 0; k < n; k++)
		step_ok(s, LZ_EULER, dt);
	reverse(s, LZ_EULER);
	for (int k = 0; k < n; k++)
		step_ok(s, LZ_EULER, dt);
	double stretch = exp(n * log1p(dt * dt)), worst = 0.0;
	for (size_t i = 0; i < 4; i++)
		worst = fmax(worst, fmax(fabs(s->r[i] - stretch * x0[i]),
		                         fabs(s->v[i] + stretch * v0[i])) / stretch);
	lz_md_free(s);
	ck_assert_msg(worst < 1e-11, "explicit Euler, 1000 steps of ẍ = -x forward, v reversed, "
	              "1000 back: the state is %.2e (relative) from (1 + Ω²)^n (x0, -v0) with "
	              "(1 + Ω²)^n = %.6g; Euler is not time reversible and misses by exactly that "
	              "stretch — both updates must use the old state, in every coordinate", worst,
	              stretch);
}
END_TEST

/* ---- extremes ---- */

LZ_TEST(tiny_dt_roundoff_regime)
{
	/* dt = 1e-10: the truncation error (Ω² ~ 1e-20) is far below round-off, so all
	 * that is left is the rounding of v += (dt/2) a and r += dt v, ~1e-16 per step,
	 * ~1e-12 after 1e4 steps. A scheme that divides by dt loses ~1e-6. */
	const double dt = 1e-10;
	lz_harmonic p = {1.0};
	/* At dt = 1e-10 even a first-order step stays within round-off: so first make sure
	 * the step is velocity Verlet, by its exact discrete solution at Ω = 0.5. */
	const double x0 = 1.0, v0 = 1.0;
	lz_md *s = osc_new(LZ_VELOCITY_VERLET, &p, 1, 1, 0.5, x0, v0);
	for (int k = 0; k < 10; k++)
		step_ok(s, LZ_VELOCITY_VERLET, 0.5);
	double off = osc_deviation(s, LZ_VELOCITY_VERLET, 1.0, 0.5, &x0, &v0, 10);
	ck_assert_msg(off < 1e-12, "before the round-off regime: 10 velocity Verlet steps at "
	              "Ω = 0.5 miss the scheme's exact discrete solution by %.2e — is the second "
	              "half-kick using the new force?", off);
	lz_md_free(s);
	s = osc_new(LZ_VELOCITY_VERLET, &p, 1, 1, dt, 1.0, 1.0);
	double e0 = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), worst = 0.0;
	for (int k = 0; k < 10000; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		worst = fmax(worst, lz_test_reldiff(lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), e0));
	}
	double t = 1e4 * dt, moved = s->r[0] - 1.0, exact = cos(t) + sin(t) - 1.0;
	ck_assert_msg(worst < 1e-11, "velocity Verlet at dt = 1e-10: the energy changed by %.2e "
	              "(relative) in 1e4 steps; only round-off (~1e-12) is expected here", worst);
	ck_assert_msg(fabs(moved - exact) < 1e-11, "velocity Verlet at dt = 1e-10: the particle "
	              "moved %.15g in t = 1e-6, expected ≈ v t = %.15g (to 1e-11)", moved, exact);
	lz_md_free(s);
}
END_TEST

LZ_TEST(ten_million_steps_bounded)
{
	/* 1e7 steps at Ω = 0.1: E stays within Ω²/4 below its start (x0 = 1, v0 = 0) and the
	 * shadow energy moves only by accumulated round-off. */
	const double dt = 0.1, big_omega2 = dt * dt;
	lz_harmonic p = {1.0};
	lz_md *s = osc_new(LZ_VELOCITY_VERLET, &p, 1, 1, dt, 1.0, 0.0);
	double worst = 0.0;
	for (long k = 0; k < 10000000; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		if (k % 1000 == 0) {
			double e = 0.5 * s->v[0] * s->v[0] + 0.5 * s->r[0] * s->r[0];
			worst = fmax(worst, fabs(e - 0.5) / 0.5);
		}
	}
	double shadow = 0.5 * s->v[0] * s->v[0] + 0.5 * s->r[0] * s->r[0] * (1 - big_omega2 / 4);
	double h0 = 0.5 * (1 - big_omega2 / 4);
	ck_assert_msg(worst <= big_omega2 / 4 * (1 + 1e-6), "velocity Verlet, 1e7 steps at "
	              "ω·dt = 0.1: the energy strayed %.3g from its start; it must stay within "
	              "Ω²/4 = %.3g forever", worst, big_omega2 / 4);
	ck_assert_msg(lz_test_reldiff(shadow, h0) < 1e-10, "velocity Verlet, 1e7 steps: the "
	              "shadow energy drifted by %.2e (relative); round-off alone gives ~1e-12",
	              lz_test_reldiff(shadow, h0));
	lz_md_free(s);
}
END_TEST
