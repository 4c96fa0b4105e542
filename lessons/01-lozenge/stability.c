/* stability — lesson 01, experiment 2 (§5): the ω·dt < 2 limit and the shadow energy.
 *
 * Part 1. The Verlet family applied to ẍ = -ω²x is the linear recurrence
 * x_{n+1} = (2 - Ω²) x_n - x_{n-1}, Ω = ω·dt, whose characteristic roots solve
 * λ² - (2 - Ω²)λ + 1 = 0. For Ω < 2 they lie on the unit circle (bounded motion);
 * for Ω > 2 one of them is real with |λ| > 1 and the solution explodes like |λ|^n.
 * We run velocity Verlet at Ω = 1.99 and Ω = 2.01 from x = 1, v = 0, write the
 * trajectories, and check that Verlet and leapfrog give the same verdict.
 *
 * Part 2. At Ω = 0.5 the energy of velocity Verlet oscillates, but the shadow
 * energy H~ = v²/2 + (ω²x²/2)(1 - Ω²/4) stays constant to round-off; symplectic
 * Euler conserves v²/2 + ω²x²/2 - (dt ω²/2) x v instead; Euler's energy grows by
 * exactly (1 + Ω²) per step.
 *
 * Usage: stability OUTDIR [--quick]   (the same size either way)
 * Writes OUTDIR/stability.dat, shadow.dat, stability.json. Exit 1 if a check fails.
 */
#include <math.h>
#include <stdio.h>

#include <gsl/gsl_fit.h>

#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/potential.h"

#define TRAJ_STEPS 200      /* steps written for the trajectory plot */
#define LONG_STEPS 100000   /* steps for the conservation and boundedness checks */
#define OMEGA_DT_SHADOW 0.5
#define SHADOW_STEPS 60     /* a little over four periods at Ω = 0.5 */

/* The larger root modulus of λ² - (2 - Ω²)λ + 1 = 0: 1 when Ω <= 2. */
static double growth_factor(double w)
{
	double half = 1.0 - 0.5 * w * w;  /* (2 - Ω²)/2 */
	return fabs(half) <= 1.0 ? 1.0 : fabs(half) + sqrt(half * half - 1.0);
}

/* A unit oscillator (ω = 1, so Ω = dt) at x = 1, v = 0, ready for integrator m. */
static lz_md *oscillator(lz_harmonic *p, lz_integrator m, double dt)
{
	p->omega = 1.0;
	lz_md *s = lz_md_alloc(1, 1, lz_harmonic_force, p);
	if (!s)
		return NULL;
	s->r[0] = 1.0;
	if (lz_md_start(s, m, dt) != LZ_OK) {
		lz_md_free(s);
		return NULL;
	}
	return s;
}

/* Run m at Ω = w for nsteps; the largest |x| seen and the slope of ln|x_n| over the
 * second half (the measured growth rate per step). */
static int probe(lz_integrator m, double w, long nsteps, double *xmax, double *rate)
{
	lz_harmonic p;
	lz_md *s = oscillator(&p, m, w);
	if (!s)
		return LZ_EINVAL;
	double ln_half = 0.0;
	int status = LZ_OK;
	*xmax = 1.0;
	for (long i = 1; i <= nsteps && status == LZ_OK; i++) {
		status = lz_md_step(s, m, w);
		*xmax = fmax(*xmax, fabs(s->r[0]));
		if (i == nsteps / 2)
			ln_half = log(fabs(s->r[0]));
	}
	*rate = (log(fabs(s->r[0])) - ln_half) / (double)(nsteps - nsteps / 2);
	lz_md_free(s);
	return status;
}

static int write_trajectories(lz_lesson *L, const double *w)
{
	static const char *names[] = {"n", "t_low", "x_low", "t_high", "x_high", "growth_high"};
	static const char *units[] = {"steps", "tau", "sigma", "tau", "sigma", "sigma"};
	lz_harmonic p[2];
	lz_md *s[2] = {oscillator(&p[0], LZ_VELOCITY_VERLET, w[0]),
	               oscillator(&p[1], LZ_VELOCITY_VERLET, w[1])};
	lz_data *d = s[0] && s[1] ? lz_lesson_data(L, "stability.dat", "velocity Verlet at "
	             "omega*dt = 1.99 (low) and 2.01 (high); growth_high = |lambda|^n", 6,
	             names, units) : NULL;
	int status = d ? LZ_OK : LZ_EIO;
	for (int i = 0; i <= TRAJ_STEPS && status == LZ_OK; i++) {
		double row[6] = {i, s[0]->t, s[0]->r[0], s[1]->t, s[1]->r[0],
		                 pow(growth_factor(w[1]), i)};
		lz_data_row(d, row);
		for (int k = 0; k < 2 && status == LZ_OK; k++)
			status = lz_md_step(s[k], LZ_VELOCITY_VERLET, w[k]);
	}
	if (d && lz_data_close(d) != LZ_OK)
		status = LZ_EIO;
	lz_md_free(s[0]);
	lz_md_free(s[1]);
	return status;
}

/* The three energies of part 2 for the state of integrator m (ω = 1, Ω = dt). */
static double shadow_of(const lz_md *s, lz_integrator m, double dt)
{
	double x = s->r[0], v = s->v[0];
	if (m == LZ_VELOCITY_VERLET)
		return 0.5 * v * v + 0.5 * x * x * (1.0 - 0.25 * dt * dt);
	return 0.5 * v * v + 0.5 * x * x - 0.5 * dt * x * v;  /* symplectic Euler */
}

typedef struct {
	double shadow_drift[2];  /* max relative change of the shadow energy: VV, SE */
	double euler_growth;     /* max relative deviation of E_n / E_0 from (1+Ω²)^n */
} shadow_result;

/* Energies of Euler, symplectic Euler and velocity Verlet side by side; the
 * conservation figures come from LONG_STEPS steps, the file from the first few. */
static int write_shadow(lz_lesson *L, shadow_result *res)
{
	static const char *names[] = {"t", "E_euler", "E_sympl", "H_sympl", "E_vv", "H_vv"};
	static const char *units[] = {"tau", "rel", "rel", "rel", "rel", "rel"};
	static const lz_integrator ms[3] = {LZ_EULER, LZ_SYMPLECTIC_EULER, LZ_VELOCITY_VERLET};
	const double dt = OMEGA_DT_SHADOW;
	lz_harmonic p[3];
	lz_md *s[3];
	double e0[3], h0[3], when;
	for (int k = 0; k < 3; k++) {
		s[k] = oscillator(&p[k], ms[k], dt);
		if (!s[k])
			return LZ_EINVAL;
		e0[k] = lz_md_energy(s[k], ms[k], &when);
		h0[k] = shadow_of(s[k], ms[k], dt);
	}
	lz_data *d = lz_lesson_data(L, "shadow.dat", "omega*dt = 0.5: energy E and shadow "
	                            "energy H, each relative to its start value, minus 1", 6,
	                            names, units);
	int status = d ? LZ_OK : LZ_EIO;
	*res = (shadow_result){{0, 0}, 0};
	for (long i = 0; i <= LONG_STEPS && status == LZ_OK; i++) {
		int euler = i <= SHADOW_STEPS;  /* (1.25)^60 is fine; (1.25)^4000 overflows */
		double e[3], h[3];
		for (int k = !euler; k < 3; k++) {
			e[k] = lz_md_energy(s[k], ms[k], &when) / e0[k] - 1.0;
			h[k] = shadow_of(s[k], ms[k], dt) / h0[k] - 1.0;
		}
		if (euler) {
			double row[6] = {s[1]->t, e[0], e[1], h[1], e[2], h[2]};
			lz_data_row(d, row);
			res->euler_growth = fmax(res->euler_growth,
			        fabs((1.0 + e[0]) / pow(1.0 + dt * dt, (double)i) - 1.0));
		}
		res->shadow_drift[0] = fmax(res->shadow_drift[0], fabs(h[2]));
		res->shadow_drift[1] = fmax(res->shadow_drift[1], fabs(h[1]));
		for (int k = !euler; k < 3 && status == LZ_OK; k++)
			status = lz_md_step(s[k], ms[k], dt);
	}
	if (d && lz_data_close(d) != LZ_OK)
		status = LZ_EIO;
	for (int k = 0; k < 3; k++)
		lz_md_free(s[k]);
	return status;
}

/* Stable at w[0] and unstable at w[1], with the predicted growth, for the three
 * members of the Verlet family: a checked line each. */
static int check_family(lz_lesson *L, const double *w, double *rate_measured)
{
	static const lz_integrator fam[3] = {LZ_VERLET, LZ_VELOCITY_VERLET, LZ_LEAPFROG};
	double expect = log(growth_factor(w[1])), xmax, rate;
	for (int k = 0; k < 3; k++) {
		int status = probe(fam[k], w[0], LONG_STEPS, &xmax, &rate);
		if (status != LZ_OK)
			return status;
		int stable = xmax < 1.0 + 1e-9;
		lz_lesson_check(L, stable);
		printf("  %-16s Omega = %.2f: max|x| over %d steps = %.12f  %s\n",
		       lz_integrator_name(fam[k]), w[0], LONG_STEPS, xmax,
		       stable ? "bounded (ok)" : "CHECK FAILED: should stay <= 1");
		if ((status = probe(fam[k], w[1], TRAJ_STEPS, &xmax, &rate)) != LZ_OK)
			return status;
		int grows = fabs(rate - expect) < 1e-3 * expect;
		printf("  %-16s Omega = %.2f: ln|x| grows by %.5f per step (theory %.5f)  %s\n",
		       lz_integrator_name(fam[k]), w[1], rate, expect, lz_lesson_check(L, grows));
		if (fam[k] == LZ_VELOCITY_VERLET)
			*rate_measured = rate;
	}
	return LZ_OK;
}

static int write_json(lz_lesson *L, const double *w, double rate, const shadow_result *r)
{
	lz_json *j = lz_lesson_json(L, "stability.json");
	if (!j)
		return LZ_EIO;
	lz_json_num(j, "growth_per_step_at_2.01", exp(rate));
	lz_json_num(j, "growth_per_step_theory", growth_factor(w[1]));
	lz_json_num(j, "shadow_rel_change_velocity_verlet", r->shadow_drift[0]);
	lz_json_num(j, "shadow_rel_change_symplectic_euler", r->shadow_drift[1]);
	lz_json_num(j, "euler_growth_rel_dev_from_1+W2", r->euler_growth);
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	const double w[2] = {1.99, 2.01};
	double rate = 0.0;
	shadow_result sr;
	printf("stability: unit oscillator (omega = 1), x0 = 1, v0 = 0, Omega = omega*dt\n");
	printf("  part 1: Omega = %.2f and %.2f, %d steps plotted; part 2: Omega = %.1f\n",
	       w[0], w[1], TRAJ_STEPS, OMEGA_DT_SHADOW);
	if (check_family(&L, w, &rate) != LZ_OK || write_trajectories(&L, w) != LZ_OK ||
	    write_shadow(&L, &sr) != LZ_OK)
		return lz_lesson_error(&L);
	int shadow_ok = sr.shadow_drift[0] < 1e-12 && sr.shadow_drift[1] < 1e-12;
	int euler_ok = sr.euler_growth < 1e-12;
	printf("  shadow energy over %d steps at Omega = %.1f: velocity Verlet %.2e, "
	       "symplectic Euler %.2e (limit 1e-12)  %s\n", LONG_STEPS, OMEGA_DT_SHADOW,
	       sr.shadow_drift[0], sr.shadow_drift[1], lz_lesson_check(&L, shadow_ok));
	printf("  Euler: E_n/E_0 = (1 + Omega^2)^n to %.1e relative (limit 1e-12)  %s\n",
	       sr.euler_growth, lz_lesson_check(&L, euler_ok));
	if (write_json(&L, w, rate, &sr) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "stability limit, shadow energies, Euler growth");
}
