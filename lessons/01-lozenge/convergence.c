/* convergence — lesson 01, experiment 1 (§4, §7): the order of every integrator.
 *
 * A harmonic oscillator (ω = 1, x(0) = 1, v(0) = 0) runs to T = 10 with each of the
 * five integrators at dt = T/n, n = 50·2^k. Two errors are recorded per run: the
 * largest relative energy error seen along the way and the position error at T
 * against the exact x(T) = cos ωT. Their slopes on a log-log plot, fitted with
 * gsl_fit_linear over the smallest steps, are the orders of the methods: 1 for
 * Euler and symplectic Euler, 2 for the Verlet family.
 *
 * Usage: convergence OUTDIR [--quick]   (the same size either way: it takes 0.1 s)
 * Writes OUTDIR/convergence.dat, convergence_fit.gp (the slopes, for the plot
 * legend) and convergence.json. Exit status 1 when a fitted order is off.
 */
#include <math.h>
#include <stdio.h>

#include <gsl/gsl_fit.h>

#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/potential.h"

#define OMEGA 1.0
#define T_END 10.0
#define N_FIRST 50        /* steps of the coarsest run: dt = 0.2 */
#define NDT 11            /* step sizes, each half the previous one */
#define NFIT 6            /* the smallest NDT-NFIT.. are in the asymptotic regime */
#define TOLERANCE 0.1     /* allowed |fitted order - theory| */

static const int theory_order[LZ_NINTEGRATORS] = {1, 1, 2, 2, 2};

typedef struct {
	double energy;    /* max over the run of |E - E0| / E0 */
	double position;  /* |x(T) - cos ωT| */
} errors;

/* One run of integrator m with nsteps steps of T_END/nsteps. */
static int run(lz_integrator m, long nsteps, errors *e)
{
	lz_harmonic p = {OMEGA};
	double dt = T_END / (double)nsteps, when;
	lz_md *s = lz_md_alloc(1, 1, lz_harmonic_force, &p);
	if (!s)
		return LZ_ENOMEM;
	s->r[0] = 1.0;
	s->v[0] = 0.0;
	int status = lz_md_start(s, m, dt);
	double e0 = lz_md_energy(s, m, &when);
	e->energy = 0.0;
	for (long i = 0; i < nsteps && status == LZ_OK; i++) {
		status = lz_md_step(s, m, dt);
		double de = fabs(lz_md_energy(s, m, &when) - e0) / e0;
		if (de > e->energy)
			e->energy = de;
	}
	e->position = fabs(s->r[0] - cos(OMEGA * (double)nsteps * dt));
	lz_md_free(s);
	return status;
}

/* Slope of log10(err) against log10(dt) over the NFIT smallest steps. */
static double fit_slope(const double *dt, const double *err)
{
	double x[NFIT], y[NFIT], c0, c1, cov00, cov01, cov11, sumsq;
	for (int i = 0; i < NFIT; i++) {
		x[i] = log10(dt[NDT - NFIT + i]);
		y[i] = log10(err[NDT - NFIT + i]);
	}
	gsl_fit_linear(x, 1, y, 1, NFIT, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
	return c1;
}

static int write_data(lz_lesson *L, const double *dt, errors e[][LZ_NINTEGRATORS])
{
	const char *names[1 + 2 * LZ_NINTEGRATORS], *units[1 + 2 * LZ_NINTEGRATORS];
	char label[2 * LZ_NINTEGRATORS][48];
	names[0] = "dt";
	units[0] = "tau";
	for (int m = 0; m < LZ_NINTEGRATORS; m++) {
		snprintf(label[m], sizeof label[m], "dE_%s", lz_integrator_name(m));
		snprintf(label[LZ_NINTEGRATORS + m], sizeof label[0], "dx_%s",
		         lz_integrator_name(m));
		names[1 + m] = label[m];
		units[1 + m] = "rel";
		names[1 + LZ_NINTEGRATORS + m] = label[LZ_NINTEGRATORS + m];
		units[1 + LZ_NINTEGRATORS + m] = "sigma";
	}
	lz_data *d = lz_lesson_data(L, "convergence.dat", "harmonic oscillator, omega=1, "
	                            "x0=1, v0=0, T=10: max relative energy error and "
	                            "|x(T)-cos T| vs dt", 1 + 2 * LZ_NINTEGRATORS, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < NDT; k++) {
		double row[1 + 2 * LZ_NINTEGRATORS] = {dt[k]};
		for (int m = 0; m < LZ_NINTEGRATORS; m++) {
			row[1 + m] = e[k][m].energy;
			row[1 + LZ_NINTEGRATORS + m] = e[k][m].position;
		}
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

/* The fitted slopes as gnuplot variables, so the plot legend shows them. */
static int write_fit_gp(lz_lesson *L, double (*slope)[2])
{
	FILE *f = lz_lesson_fopen(L, "convergence_fit.gp");
	if (!f)
		return LZ_EIO;
	fprintf(f, "# fitted orders, written by the convergence driver\n");
	for (int m = 0; m < LZ_NINTEGRATORS; m++)
		fprintf(f, "sE%d = %.3f; sX%d = %.3f\n", m, slope[m][0], m, slope[m][1]);
	return lz_lesson_fclose(L, f, "convergence_fit.gp");
}

static int write_json(lz_lesson *L, double (*slope)[2])
{
	char key[64];
	lz_json *j = lz_lesson_json(L, "convergence.json");
	if (!j)
		return LZ_EIO;
	lz_json_str(j, "system", "harmonic oscillator, omega=1, T=10");
	for (int m = 0; m < LZ_NINTEGRATORS; m++) {
		snprintf(key, sizeof key, "order_energy_%s", lz_integrator_name(m));
		lz_json_num(j, key, round(slope[m][0] * 1000.0) / 1000.0);
		snprintf(key, sizeof key, "order_position_%s", lz_integrator_name(m));
		lz_json_num(j, key, round(slope[m][1] * 1000.0) / 1000.0);
	}
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	double dt[NDT], slope[LZ_NINTEGRATORS][2];
	errors e[NDT][LZ_NINTEGRATORS];
	printf("convergence: harmonic oscillator omega = %g, x0 = 1, v0 = 0, T = %g\n",
	       OMEGA, T_END);
	printf("  dt = T/n, n = %d ... %d (%d values); orders fitted over the %d smallest dt\n",
	       N_FIRST, N_FIRST << (NDT - 1), NDT, NFIT);
	for (int k = 0; k < NDT; k++) {
		long n = (long)N_FIRST << k;
		dt[k] = T_END / (double)n;
		for (int m = 0; m < LZ_NINTEGRATORS; m++)
			if (run(m, n, &e[k][m]) != LZ_OK) {
				fprintf(stderr, "convergence: %s at dt = %g failed: %s\n",
				        lz_integrator_name(m), dt[k], lz_error_message());
				return 2;
			}
	}
	printf("  %-17s %9s %9s %7s\n", "integrator", "energy", "position", "theory");
	for (int m = 0; m < LZ_NINTEGRATORS; m++) {
		double de[NDT], dx[NDT];
		for (int k = 0; k < NDT; k++) {
			de[k] = e[k][m].energy;
			dx[k] = e[k][m].position;
		}
		slope[m][0] = fit_slope(dt, de);
		slope[m][1] = fit_slope(dt, dx);
		int good = fabs(slope[m][0] - theory_order[m]) < TOLERANCE &&
		           fabs(slope[m][1] - theory_order[m]) < TOLERANCE;
		printf("  %-17s %9.3f %9.3f %7d  %s\n", lz_integrator_name(m), slope[m][0],
		       slope[m][1], theory_order[m], lz_lesson_check(&L, good));
	}
	if (write_data(&L, dt, e) || write_fit_gp(&L, slope) || write_json(&L, slope))
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "fitted orders within %.1f of theory", TOLERANCE);
}
