/* ljnve — lesson 01, experiment 4 (§5, §7): energy conservation in a real fluid.
 *
 * A Lennard-Jones liquid (cut and shifted at rc = 2.5, density ρ = 0.8) is melted
 * from an fcc lattice and brought to T ≈ 1 by velocity rescaling with velocity
 * Verlet at dt = 0.005. From that one equilibrated state, NVE runs of the same
 * length at several dt measure the energy per particle E/N: its rms spread (the
 * shadow-energy wobble, which should scale as dt²) and its drift (the slope of a
 * straight-line fit, which a symplectic integrator keeps near zero).
 * For N = 108 every dt from 0.000125 to 0.016 runs twice: in double, and in single
 * precision (forces rounded to float, state rounded to float after every step), to
 * see where round-off rather than truncation sets the error. The larger N (full
 * size only) run dt >= 0.002 in double: the spread of E/N falls like N^-1/2.
 *
 * Usage: ljnve OUTDIR [--quick]   (quick: N = 108; full: N = 108, 256, 500, 864)
 * Writes OUTDIR/ljnve.dat, ljnve_trace.dat (E/N(t) for N = 108), ljnve.json.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/potential.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/vec.h"

#define RHO 0.8
#define TEMP 1.0
#define RC 2.5
#define SEED 4242
#define DT_EQ 0.005
#define EQ_STEPS 1000       /* equilibration: 5 τ, rescaled every RESCALE_EVERY */
#define RESCALE_EVERY 20
#define T_RUN 5.12          /* length of every NVE run, τ: a whole number of every dt */
#define WRAP_EVERY 50       /* keep positions in the box (minimum image needs it) */
#define NDT 8
#define FIRST_DT_LARGE_N 4 /* larger systems start at dts[4] = 0.002 */
#define NPREC 2             /* 0: double, 1: float */
#define SAMPLE_DT 0.016     /* trace sampling interval, a multiple of every dt */
#define NTRACE 321          /* T_RUN / SAMPLE_DT + 1 */
#define MAX_SAMPLES 40961   /* T_RUN / dts[0] + 1 */

static const double dts[NDT] = {0.000125, 0.00025, 0.0005, 0.001, 0.002, 0.004, 0.008, 0.016};
#define DT_DRIFT 5          /* dts[5] = 0.004: the usual working step */

typedef struct {
	lz_lj p;
	lz_md *s;
	double *r_eq, *v_eq;  /* the equilibrated state every NVE run starts from */
} fluid;

typedef struct {
	double sigma;      /* rms spread of E/N, ε */
	double drift;      /* d(E/N)/dt from a linear fit, ε/τ */
	double drift_err;  /* its standard error from the fit */
	double temp, upot; /* mean kinetic temperature and U/N */
} nve_stats;

static double temperature(const lz_md *s)
{
	return 2.0 * lz_md_kinetic(s, LZ_VELOCITY_VERLET) / (3.0 * (double)(s->n - 1));
}

static void wrap(lz_md *s, double box)
{
	for (size_t i = 0; i < 3 * s->n; i++)
		s->r[i] = lz_wrap(s->r[i], box);
}

/* Lattice, Maxwell velocities, then EQ_STEPS of velocity Verlet with the kinetic
 * temperature reset to TEMP every RESCALE_EVERY steps (not in the last quarter, so
 * the state handed on is an unperturbed NVE state). */
static int fluid_init(fluid *f, size_t n)
{
	memset(f, 0, sizeof *f);
	if (lz_lj_init(&f->p, n, 3, RHO, RC) != LZ_OK)
		return LZ_EINVAL;
	f->s = lz_md_alloc(n, 3, lz_lj_force, &f->p);
	f->r_eq = malloc(3 * n * sizeof *f->r_eq);
	f->v_eq = malloc(3 * n * sizeof *f->v_eq);
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	if (!f->s || !f->r_eq || !f->v_eq || !rng) {
		lz_rng_free(rng);
		return lz_error(LZ_ENOMEM, "no memory for %zu particles", n);
	}
	int status = lz_lattice_start(f->s->r, n, 3, f->p.box);
	lz_maxwell_velocities(f->s->v, n, 3, TEMP, rng);
	lz_rng_free(rng);
	if (status == LZ_OK)
		status = lz_md_start(f->s, LZ_VELOCITY_VERLET, DT_EQ);
	for (int i = 1; i <= EQ_STEPS && status == LZ_OK; i++) {
		status = lz_md_step(f->s, LZ_VELOCITY_VERLET, DT_EQ);
		if (i % RESCALE_EVERY == 0 && i <= 3 * EQ_STEPS / 4)
			for (size_t k = 0; k < 3 * n; k++)
				f->s->v[k] *= sqrt(TEMP / temperature(f->s));
		if (i % WRAP_EVERY == 0)
			wrap(f->s, f->p.box);
	}
	memcpy(f->r_eq, f->s->r, 3 * n * sizeof *f->r_eq);
	memcpy(f->v_eq, f->s->v, 3 * n * sizeof *f->v_eq);
	return status;
}

static void fluid_free(fluid *f)
{
	lz_md_free(f->s);
	free(f->r_eq);
	free(f->v_eq);
}

/* Mean, spread and drift of the samples e[0..m) taken at t[0..m). */
static void analyse(const double *t, const double *e, size_t m, nve_stats *st)
{
	double c0, cov00, cov01, cov11, ss;
	st->sigma = gsl_stats_sd(e, 1, m);
	gsl_fit_linear(t, 1, e, 1, m, &c0, &st->drift, &cov00, &cov01, &cov11, &ss);
	st->drift_err = sqrt(cov11);
}

/* One NVE run from the equilibrated state; E/N sampled every step into the
 * caller's buffers t, e, and every SAMPLE_DT into trace (when not NULL). */
static int nve(fluid *f, double dt, int single, double *t, double *e, double *trace,
               nve_stats *st)
{
	lz_md *s = f->s;
	long nsteps = lround(T_RUN / dt), stride = lround(SAMPLE_DT / dt);
	double when, n = (double)s->n;
	if (nsteps >= MAX_SAMPLES)
		return lz_error(LZ_EINVAL, "dt = %g needs %ld samples, more than %d", dt,
		                nsteps + 1, MAX_SAMPLES);
	memcpy(s->r, f->r_eq, 3 * s->n * sizeof *s->r);
	memcpy(s->v, f->v_eq, 3 * s->n * sizeof *s->v);
	f->p.single = single;
	if (single)
		lz_md_round_float(s);
	int status = lz_md_start(s, LZ_VELOCITY_VERLET, dt);
	st->temp = st->upot = 0.0;
	for (long i = 0; status == LZ_OK; i++) {
		t[i] = (double)i * dt;
		e[i] = lz_md_energy(s, LZ_VELOCITY_VERLET, &when) / n;
		st->temp += temperature(s) / (double)(nsteps + 1);
		st->upot += s->u / n / (double)(nsteps + 1);
		if (trace && i % stride == 0 && i / stride < NTRACE)
			trace[i / stride] = e[i] - e[0];
		if (i == nsteps)
			break;
		status = lz_md_step(s, LZ_VELOCITY_VERLET, dt);
		if ((i + 1) % WRAP_EVERY == 0)
			wrap(s, f->p.box);
		if (single)  /* the state lives in float between steps */
			lz_md_round_float(s);
	}
	if (status == LZ_OK)
		analyse(t, e, (size_t)nsteps + 1, st);
	return status;
}

/* Slope of log σ against log dt over the three largest steps, where truncation
 * rather than round-off sets the spread. */
static double spread_order(nve_stats st[NDT])
{
	double x[3], y[3], c0, c1, v00, v01, v11, ss;
	for (int k = 0; k < 3; k++) {
		x[k] = log10(dts[NDT - 3 + k]);
		y[k] = log10(st[NDT - 3 + k].sigma);
	}
	gsl_fit_linear(x, 1, y, 1, 3, &c0, &c1, &v00, &v01, &v11, &ss);
	return c1;
}

static int write_table(lz_lesson *L, const size_t *ns, int nn, nve_stats st[][NPREC][NDT])
{
	static const char *names[] = {"N", "float", "dt", "sigma_E", "drift", "drift_err",
	                              "T", "U"};
	static const char *units[] = {"", "0/1", "tau", "eps/particle", "eps/(particle*tau)",
	                              "eps/(particle*tau)", "eps/k_B", "eps/particle"};
	lz_data *d = lz_lesson_data(L, "ljnve.dat", "LJ rho=0.8 rc=2.5 (cut and shifted), "
	                            "velocity Verlet, NVE runs of 5.12 tau: spread and drift "
	                            "of E/N", 8, names, units);
	if (!d)
		return LZ_EIO;
	for (int a = 0; a < nn; a++)
		for (int p = 0; p < NPREC; p++)
			for (int k = 0; k < NDT; k++) {
				const nve_stats *x = &st[a][p][k];
				if (!isnan(x->sigma))
					lz_data_row(d, (double[]){(double)ns[a], p, dts[k], x->sigma,
					        x->drift, x->drift_err, x->temp, x->upot});
			}
	return lz_data_close(d);
}

static int write_trace(lz_lesson *L, size_t n, double trace[NPREC][NDT][NTRACE])
{
	const char *names[1 + NPREC * NDT], *units[1 + NPREC * NDT];
	char label[NPREC * NDT][32], title[128];
	names[0] = "t";
	units[0] = "tau";
	for (int c = 0; c < NPREC * NDT; c++) {
		snprintf(label[c], sizeof label[c], "%s_dt%g", c < NDT ? "double" : "float",
		         dts[c % NDT]);
		names[1 + c] = label[c];
		units[1 + c] = "eps/particle";
	}
	snprintf(title, sizeof title, "LJ N=%zu: E/N(t) - E/N(0) for each dt and precision", n);
	lz_data *d = lz_lesson_data(L, "ljnve_trace.dat", title, 1 + NPREC * NDT, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < NTRACE; i++) {
		double row[1 + NPREC * NDT] = {i * SAMPLE_DT};
		for (int c = 0; c < NPREC * NDT; c++)
			row[1 + c] = trace[c / NDT][c % NDT][i];
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

/* The NVE runs for one N: with full_range every dt in both precisions (and the
 * trace), otherwise dt >= dts[FIRST_DT_LARGE_N] in double. Runs not made keep
 * sigma = NaN. */
static int run_size(size_t n, int full_range, nve_stats st[NPREC][NDT], double *t,
                    double *e, double trace[NPREC][NDT][NTRACE], double *atomsteps_per_s)
{
	fluid f;
	int status = fluid_init(&f, n);
	double steps = 0.0, w0 = lz_wall_now();
	for (int p = 0; p < NPREC; p++)
		for (int k = 0; k < NDT; k++)
			st[p][k].sigma = NAN;
	for (int p = 0; p < (full_range ? NPREC : 1) && status == LZ_OK; p++)
		for (int k = full_range ? 0 : FIRST_DT_LARGE_N; k < NDT && status == LZ_OK; k++) {
			status = nve(&f, dts[k], p, t, e, full_range ? trace[p][k] : NULL, &st[p][k]);
			steps += T_RUN / dts[k];
		}
	*atomsteps_per_s = steps * (double)n / (lz_wall_now() - w0);
	fluid_free(&f);
	return status;
}

/* Print one N's table and check that the spread scales as dt^2, the drift is small
 * and the potential energy is that of the LJ liquid. */
static void report(lz_lesson *L, size_t n, nve_stats st[NPREC][NDT], double rate)
{
	double order = spread_order(st[0]);
	const nve_stats *ref = &st[0][DT_DRIFT];
	int ok_order = fabs(order - 2.0) < 0.3;
	int ok_drift = fabs(ref->drift) < 1e-4;
	int ok_u = ref->upot > -4.9 && ref->upot < -4.45;
	printf("  N = %zu  (%.3g atom-steps/s)\n", n, rate);
	printf("    %-8s %14s %14s %14s %14s\n", "dt", "sigma(double)", "sigma(float)",
	       "drift(double)", "drift(float)");
	for (int k = 0; k < NDT; k++) {
		char fs[32] = "-", fd[32] = "-";  /* float runs: N = 108 only */
		if (isnan(st[0][k].sigma))
			continue;
		if (!isnan(st[1][k].sigma)) {
			snprintf(fs, sizeof fs, "%.3e", st[1][k].sigma);
			snprintf(fd, sizeof fd, "%.3e", st[1][k].drift);
		}
		printf("    %-8g %14.3e %14s %14.3e %14s\n", dts[k], st[0][k].sigma, fs,
		       st[0][k].drift, fd);
	}
	printf("    spread order (3 largest dt, double) %.2f, theory 2  %s\n", order,
	       lz_lesson_check(L, ok_order));
	printf("    drift at dt = %g (double) %.2e eps/tau per particle, limit 1e-4  %s\n",
	       dts[DT_DRIFT], ref->drift, lz_lesson_check(L, ok_drift));
	printf("    <T> = %.3f, <U>/N = %.3f (reference -4.67 +- 0.05 at T = 1: rc = 2.5, shifted; "
	       "datasets/reference/lennard-jones.csv)  %s\n", ref->temp, ref->upot,
	       lz_lesson_check(L, ok_u));
}

static void json_size(lz_json *j, size_t n, nve_stats st[NPREC][NDT], double rate)
{
	char key[64];
	snprintf(key, sizeof key, "N%zu_spread_order", n);
	lz_json_num(j, key, round(spread_order(st[0]) * 100.0) / 100.0);
	snprintf(key, sizeof key, "N%zu_sigma_E_dt0.004", n);
	lz_json_num(j, key, st[0][DT_DRIFT].sigma);
	snprintf(key, sizeof key, "N%zu_mean_U_per_N", n);
	lz_json_num(j, key, st[0][DT_DRIFT].upot);
	snprintf(key, sizeof key, "N%zu_atomsteps_per_s", n);
	lz_json_num(j, key, rate);
}

static int write_json(lz_lesson *L, const size_t *ns, int nn, nve_stats st[][NPREC][NDT],
                      const double *rate)
{
	lz_json *j = lz_lesson_json(L, "ljnve.json");
	if (!j)
		return LZ_EIO;
	lz_json_num(j, "density", RHO);
	lz_json_num(j, "run_length_tau", T_RUN);
	lz_json_num(j, "N108_sigma_E_dt0.000125_double", st[0][0][0].sigma);
	lz_json_num(j, "N108_sigma_E_dt0.000125_float", st[0][1][0].sigma);
	for (int a = 0; a < nn; a++)
		json_size(j, ns[a], st[a], rate[a]);
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	static const size_t sizes[] = {108, 256, 500, 864};
	static nve_stats st[4][NPREC][NDT];
	static double trace[NPREC][NDT][NTRACE];
	static double t[MAX_SAMPLES], e[MAX_SAMPLES];
	double rate[4];
	int nn = L.quick ? 1 : 4, status = LZ_OK;
	printf("ljnve: Lennard-Jones rho = %g, rc = %g (cut and shifted), T = %g after "
	       "%d steps of rescaled equilibration at dt = %g; seed %d\n", RHO, RC, TEMP,
	       EQ_STEPS, DT_EQ, SEED);
	printf("  velocity Verlet NVE runs of %g tau: N = 108 at dt = %g ... %g in double "
	       "and float", T_RUN, dts[0], dts[NDT - 1]);
	if (nn > 1)
		printf("; N = 256, 500, 864 at dt >= %g in double", dts[FIRST_DT_LARGE_N]);
	printf("\n");
	for (int a = 0; a < nn && status == LZ_OK; a++) {
		status = run_size(sizes[a], a == 0, st[a], t, e, trace, &rate[a]);
		if (status == LZ_OK)
			report(&L, sizes[a], st[a], rate[a]);
	}
	if (status == LZ_OK)
		status = write_table(&L, sizes, nn, st);
	if (status == LZ_OK)
		status = write_trace(&L, sizes[0], trace);
	if (status == LZ_OK)
		status = write_json(&L, sizes, nn, st, rate);
	if (status != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "energy spread ~ dt^2, small drift, liquid U/N");
}
