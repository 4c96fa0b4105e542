/* workprec — lesson 01, experiment 3 (§7): what accuracy costs.
 *
 * N independent 3D harmonic oscillators (ω = 1) with random starts run to T = 10.
 * The error is the rms position error at T, relative to the rms amplitude, against
 * the exact solution r0 cos ωt + (v0/ω) sin ωt. The cost is counted two ways: force
 * evaluations (what matters when forces are expensive) and CPU seconds (what the
 * user waits for; it also charges the method's own bookkeeping). The five
 * integrators run at dt = T/n over a range of n; GSL's adaptive Runge-Kutta-Prince-
 * Dormand (8,9) integrator (gsl_odeiv2 rk8pd) runs at tolerances 1e-1 ... 1e-12 as
 * the high-order reference, its right-hand side calls counted as force evaluations.
 *
 * Usage: workprec OUTDIR [--quick]   (quick: 200 oscillators and n <= 1e4;
 *                                     full: 1000 oscillators and n <= 1e5)
 * Writes OUTDIR/workprec_<method>.dat and workprec.json. Exit 1 if a check fails.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_odeiv2.h>

#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/potential.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define T_END 10.0
#define SEED 2024
#define MAX_POINTS 24     /* n = 10^(1 + k/4): at most k = 0..16 */
#define NTOL 12           /* rk8pd tolerances 1e-1 ... 1e-12 */
#define NFIT 5            /* points of the asymptotic slope fit */
#define TARGET 1e-6       /* the accuracy the headline costs refer to */
#define MIN_CPU 0.02      /* repeat a run until it used at least this much CPU */
#define NMETHODS (LZ_NINTEGRATORS + 1)

typedef struct {
	size_t n;          /* oscillators */
	double *r0, *v0;   /* start, 3n each */
	double amplitude;  /* rms amplitude sqrt(Σ r0² + v0²/ω²) */
} problem;

typedef struct {
	int npoints;
	double param[MAX_POINTS];  /* dt, or the rk8pd tolerance */
	double evals[MAX_POINTS], cpu[MAX_POINTS], err[MAX_POINTS];
} curve;

static int problem_init(problem *p, size_t n)
{
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	p->n = n;
	p->r0 = malloc(3 * n * sizeof *p->r0);
	p->v0 = malloc(3 * n * sizeof *p->v0);
	if (!rng || !p->r0 || !p->v0) {
		lz_rng_free(rng);
		return lz_error(LZ_ENOMEM, "no memory for %zu oscillators", n);
	}
	double sum = 0.0;
	for (size_t i = 0; i < 3 * n; i++) {
		p->r0[i] = 2.0 * lz_rng_uniform(rng) - 1.0;
		p->v0[i] = 2.0 * lz_rng_uniform(rng) - 1.0;
		sum += p->r0[i] * p->r0[i] + p->v0[i] * p->v0[i];
	}
	p->amplitude = sqrt(sum);
	lz_rng_free(rng);
	return LZ_OK;
}

/* rms distance of r from the exact positions at t, relative to the amplitude. */
static double position_error(const problem *p, const double *r, double t)
{
	double c = cos(t), s = sin(t), sum = 0.0;
	for (size_t i = 0; i < 3 * p->n; i++) {
		double d = r[i] - (p->r0[i] * c + p->v0[i] * s);
		sum += d * d;
	}
	return sqrt(sum) / p->amplitude;
}

/* One integration with m in nsteps steps; adds its CPU time and returns the error. */
static int integrate_once(const problem *p, lz_integrator m, long nsteps,
                          double *cpu, double *evals, double *err)
{
	lz_harmonic h = {1.0};
	double dt = T_END / (double)nsteps, t0 = lz_cpu_now();
	lz_md *s = lz_md_alloc(p->n, 3, lz_harmonic_force, &h);
	if (!s)
		return LZ_ENOMEM;
	memcpy(s->r, p->r0, 3 * p->n * sizeof *s->r);
	memcpy(s->v, p->v0, 3 * p->n * sizeof *s->v);
	int status = lz_md_start(s, m, dt);
	for (long i = 0; i < nsteps && status == LZ_OK; i++)
		status = lz_md_step(s, m, dt);
	*cpu += lz_cpu_now() - t0;
	*evals = (double)s->force_evals;
	*err = position_error(p, s->r, (double)nsteps * dt);
	lz_md_free(s);
	return status;
}

static int run_integrator(const problem *p, lz_integrator m, int kmax, curve *c)
{
	c->npoints = 0;
	for (int k = 0; k <= kmax; k++) {
		long nsteps = lround(pow(10.0, 1.0 + k / 4.0));
		double cpu = 0.0, evals = 0.0, err = 0.0;
		int reps = 0, status;
		do {
			status = integrate_once(p, m, nsteps, &cpu, &evals, &err);
			reps++;
		} while (status == LZ_OK && cpu < MIN_CPU);
		if (status != LZ_OK)
			return status;
		c->param[c->npoints] = T_END / (double)nsteps;
		c->evals[c->npoints] = evals;
		c->cpu[c->npoints] = cpu / reps;
		c->err[c->npoints++] = err;
	}
	return LZ_OK;
}

/* ---- the GSL reference: y = (r, v), dy/dt = (v, a) ---- */
typedef struct {
	size_t n;
	unsigned long calls;
} rhs_params;

static int rhs(double t, const double *y, double *dydt, void *params)
{
	rhs_params *rp = params;
	lz_harmonic h = {1.0};
	size_t len = 3 * rp->n;
	double u;
	rp->calls++;
	memcpy(dydt, y + len, len * sizeof *y);
	return lz_harmonic_force(rp->n, 3, y, dydt + len, &u, &h) == LZ_OK ? GSL_SUCCESS
	                                                                  : GSL_EBADFUNC;
}

static int rk8pd_once(const problem *p, double tol, double *cpu, double *evals,
                      double *err)
{
	size_t len = 3 * p->n;
	rhs_params rp = {p->n, 0};
	gsl_odeiv2_system sys = {rhs, NULL, 2 * len, &rp};
	double *y = malloc(2 * len * sizeof *y), t = 0.0, t0 = lz_cpu_now();
	gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd,
	                                                     0.1, tol, 0.0);
	if (!y || !d) {
		free(y);
		return lz_error(LZ_ENOMEM, "no memory for the rk8pd reference");
	}
	memcpy(y, p->r0, len * sizeof *y);
	memcpy(y + len, p->v0, len * sizeof *y);
	int status = gsl_odeiv2_driver_apply(d, &t, T_END, y);
	*cpu += lz_cpu_now() - t0;
	*evals = (double)rp.calls;
	*err = position_error(p, y, T_END);
	gsl_odeiv2_driver_free(d);
	free(y);
	return status == GSL_SUCCESS ? LZ_OK
	       : lz_error(LZ_EDOM, "rk8pd at tol %g failed: %s", tol, gsl_strerror(status));
}

static int run_rk8pd(const problem *p, curve *c)
{
	c->npoints = 0;
	for (int k = 1; k <= NTOL; k++) {
		double tol = pow(10.0, -k), cpu = 0.0, evals = 0.0, err = 0.0;
		int reps = 0, status;
		do {
			status = rk8pd_once(p, tol, &cpu, &evals, &err);
			reps++;
		} while (status == LZ_OK && cpu < MIN_CPU);
		if (status != LZ_OK)
			return status;
		c->param[c->npoints] = tol;
		c->evals[c->npoints] = evals;
		c->cpu[c->npoints] = cpu / reps;
		c->err[c->npoints++] = err;
	}
	return LZ_OK;
}

/* ---- analysis and output ---- */

/* Straight-line fit of log10 err against log10 evals over the last NFIT points. */
static void cost_fit(const curve *c, double *intercept, double *slope)
{
	double x[NFIT], y[NFIT], v00, v01, v11, ss;
	for (int i = 0; i < NFIT; i++) {
		x[i] = log10(c->evals[c->npoints - NFIT + i]);
		y[i] = log10(c->err[c->npoints - NFIT + i]);
	}
	gsl_fit_linear(x, 1, y, 1, NFIT, intercept, slope, &v00, &v01, &v11, &ss);
}

/* The cost (column cost[]) at which the error first falls to TARGET, interpolated
 * in log-log between the bracketing points. When the runs never got there, the
 * fitted line is extrapolated (*extrapolated = 1), the CPU time assumed
 * proportional to the force evaluations beyond the last point. */
static double cost_at_target(const curve *c, const double *cost, int *extrapolated)
{
	*extrapolated = 0;
	for (int i = 1; i < c->npoints; i++)
		if (c->err[i - 1] > TARGET && c->err[i] <= TARGET) {
			double f = log(c->err[i - 1] / TARGET) / log(c->err[i - 1] / c->err[i]);
			return exp(log(cost[i - 1]) + f * log(cost[i] / cost[i - 1]));
		}
	if (c->err[0] <= TARGET)
		return cost[0];
	double c0, c1;
	int last = c->npoints - 1;
	cost_fit(c, &c0, &c1);
	*extrapolated = 1;
	return pow(10.0, (log10(TARGET) - c0) / c1) / c->evals[last] * cost[last];
}

static int write_curve(lz_lesson *L, const char *name, const curve *c, int is_rk)
{
	const char *names[] = {is_rk ? "tol" : "dt", "force_evals", "cpu", "error"};
	const char *units[] = {is_rk ? "" : "tau", "", "s", "rel"};
	char file[64], title[128];
	snprintf(file, sizeof file, "workprec_%s.dat", name);
	snprintf(title, sizeof title, "%s: rms position error at T=%g vs cost", name, T_END);
	lz_data *d = lz_lesson_data(L, file, title, 4, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < c->npoints; i++)
		lz_data_row(d, (double[]){c->param[i], c->evals[i], c->cpu[i], c->err[i]});
	return lz_data_close(d);
}

static const char *method_name(int m)
{
	return m < LZ_NINTEGRATORS ? lz_integrator_name(m) : "rk8pd";
}

static int write_json(lz_lesson *L, const curve *c, size_t n)
{
	char key[96];
	lz_json *j = lz_lesson_json(L, "workprec.json");
	if (!j)
		return LZ_EIO;
	lz_json_int(j, "oscillators", (long long)n);
	lz_json_num(j, "target_error", TARGET);
	for (int m = 0; m < NMETHODS; m++) {
		int ex;
		double evals = cost_at_target(&c[m], c[m].evals, &ex);
		snprintf(key, sizeof key, "force_evals_for_1e-6_%s%s", method_name(m),
		         ex ? "_extrapolated" : "");
		lz_json_num(j, key, round(evals));
		snprintf(key, sizeof key, "cpu_s_for_1e-6_%s%s", method_name(m),
		        ex ? "_extrapolated" : "");
		lz_json_num(j, key, cost_at_target(&c[m], c[m].cpu, &ex));
	}
	return lz_json_end(j);
}

/* Report and check the orders seen on the cost axis and the reference's reach. */
static void check(lz_lesson *L, const curve *c)
{
	static const double order[LZ_NINTEGRATORS] = {1, 1, 2, 2, 2};
	printf("  %-17s %10s %8s %14s %12s\n", "method", "slope", "theory",
	       "evals@1e-6", "cpu_s@1e-6");
	for (int m = 0; m < NMETHODS; m++) {
		double c0, slope;
		int ex;
		cost_fit(&c[m], &c0, &slope);
		int good = m == LZ_NINTEGRATORS || fabs(slope + order[m]) < 0.15;
		double evals = cost_at_target(&c[m], c[m].evals, &ex);
		printf("  %-17s %10.3f %8s %14.4g %12.3g%s  %s\n", method_name(m), slope,
		       m < LZ_NINTEGRATORS ? (order[m] == 1 ? "-1" : "-2") : "-", evals,
		       cost_at_target(&c[m], c[m].cpu, &ex), ex ? " (extrapolated)" : "",
		       lz_lesson_check(L, good));
	}
	const curve *rk = &c[LZ_NINTEGRATORS];
	int rk_ok = rk->err[rk->npoints - 1] < 1e-9;
	printf("  rk8pd at tol %.0e: error %.2e (must be < 1e-9)  %s\n",
	       rk->param[rk->npoints - 1], rk->err[rk->npoints - 1], lz_lesson_check(L, rk_ok));
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	int kmax = L.quick ? 12 : 16;
	problem p;
	curve c[NMETHODS];
	gsl_set_error_handler_off();  /* rk8pd failures come back as a status */
	if (problem_init(&p, L.quick ? 200 : 1000) != LZ_OK)
		return lz_lesson_error(&L);
	printf("workprec: %zu 3D oscillators (omega = 1, random start, seed %d) to T = %g\n",
	       p.n, SEED, T_END);
	printf("  integrators at n = 10 ... %ld steps; rk8pd at tol 1e-1 ... 1e-%d; "
	       "runs repeated to >= %g s CPU\n", lround(pow(10.0, 1.0 + kmax / 4.0)),
	       NTOL, MIN_CPU);
	int status = LZ_OK;
	for (int m = 0; m < LZ_NINTEGRATORS && status == LZ_OK; m++)
		status = run_integrator(&p, m, kmax, &c[m]);
	if (status == LZ_OK)
		status = run_rk8pd(&p, &c[LZ_NINTEGRATORS]);
	for (int m = 0; m < NMETHODS && status == LZ_OK; m++)
		status = write_curve(&L, method_name(m), &c[m], m == LZ_NINTEGRATORS);
	if (status == LZ_OK) {
		check(&L, c);
		status = write_json(&L, c, p.n);
	}
	free(p.r0);
	free(p.v0);
	if (status != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "work-precision orders and reference");
}
