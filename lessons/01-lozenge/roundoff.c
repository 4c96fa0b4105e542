/* roundoff — lesson 01, experiment 5 (§6): when the step is tiny, round-off wins.
 *
 * An oscillator (ω = 1) centred at X0 = 1000 σ — a particle far from the origin of
 * a big box — starts at X0 + 1 at rest and runs to T = 1 with n = 10 ... 1e7 steps;
 * the error is |x(T) - X0 - cos T|. Truncation error falls like dt². Rounding error
 * grows with the number of steps: every step adds a tiny increment to a position of
 * size 1000, whose last bit is worth 1.1e-13. Four ways to do the same arithmetic:
 *   verlet     r(t+dt) = 2r(t) - r(t-dt) + dt² a: the small dt² a meets the large
 *              positions, and the recurrence lets every rounding error grow
 *              linearly in time;
 *   leapfrog   the same trajectory, but the small terms are grouped first
 *              (v·dt is kept apart and only then added to r);
 *   velocity-verlet  r += dt v, naive accumulation;
 *   compensated      velocity Verlet with r and v kept as Kahan sums (lz_kahan_add),
 *              so the low-order bits of every increment survive.
 *
 * Usage: roundoff OUTDIR [--quick]   (the same either way: 1.5 s)
 * Writes OUTDIR/roundoff.dat and roundoff.json. Exit 1 if a check fails.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lz/error.h"
#include "lz/fpsum.h"
#include "lz/integrate.h"
#include "lz/lesson.h"
#include "lz/output.h"

#define T_END 1.0
#define X0 1000.0          /* centre of the oscillator, σ */
#define MAX_POINTS 25      /* n = 10^(1 + k/4), k = 0..24 */
#define NVARIANTS 4

static const char *const variant_name[NVARIANTS] = {"verlet", "leapfrog",
                                                    "velocity-verlet", "compensated"};

/* The force of a unit oscillator centred at X0 (lz_force_fn). */
static int centred_force(size_t n, int dim, const double *r, double *a, double *u,
                         void *params)
{
	*u = 0.0;
	for (size_t i = 0; i < n * (size_t)dim; i++) {
		a[i] = -(r[i] - X0);
		*u += 0.5 * (r[i] - X0) * (r[i] - X0);
	}
	return LZ_OK;
}

/* x - X0 is exact (Sterbenz: the two are within a factor 2), so the error measured
 * is the integrator's, not the measurement's. */
static double error_at(double x_minus_x0, long nsteps, double dt)
{
	return fabs(x_minus_x0 - cos((double)nsteps * dt));
}

/* Position error at T after nsteps with a library integrator. */
static int run_library(lz_integrator m, long nsteps, double *err)
{
	double dt = T_END / (double)nsteps;
	lz_md *s = lz_md_alloc(1, 1, centred_force, NULL);
	if (!s)
		return LZ_ENOMEM;
	s->r[0] = X0 + 1.0;
	int status = lz_md_start(s, m, dt);
	for (long i = 0; i < nsteps && status == LZ_OK; i++)
		status = lz_md_step(s, m, dt);
	*err = error_at(s->r[0] - X0, nsteps, dt);
	lz_md_free(s);
	return status;
}

/* Velocity Verlet with compensated accumulation of r and v. The force sees r
 * rounded to double, which costs nothing that accumulates. */
static int run_compensated(long nsteps, double *err)
{
	double dt = T_END / (double)nsteps, x, a, u;
	lz_kahan r = {X0 + 1.0, 0.0}, v = {0.0, 0.0};
	x = lz_kahan_value(&r);
	int status = centred_force(1, 1, &x, &a, &u, NULL);
	for (long i = 0; i < nsteps && status == LZ_OK; i++) {
		lz_kahan_add(&v, 0.5 * dt * a);
		lz_kahan_add(&r, dt * lz_kahan_value(&v));
		x = lz_kahan_value(&r);
		status = centred_force(1, 1, &x, &a, &u, NULL);
		lz_kahan_add(&v, 0.5 * dt * a);
	}
	*err = error_at((r.sum - X0) + r.comp, nsteps, dt);
	return status;
}

static int run_variant(int k, long nsteps, double *err)
{
	static const lz_integrator lib[3] = {LZ_VERLET, LZ_LEAPFROG, LZ_VELOCITY_VERLET};
	return k < 3 ? run_library(lib[k], nsteps, err) : run_compensated(nsteps, err);
}

typedef struct {
	int npoints;
	double dt[MAX_POINTS];
	double err[MAX_POINTS][NVARIANTS];
} table;

/* The step below which variant k stays more than twice as wrong as the compensated
 * run: where round-off has overtaken truncation. NaN if it never does. */
static double overtake_dt(const table *t, int k)
{
	int i = t->npoints;
	while (i > 0 && t->err[i - 1][k] > 2.0 * t->err[i - 1][NVARIANTS - 1])
		i--;
	return i < t->npoints ? t->dt[i] : NAN;
}

static int write_data(lz_lesson *L, const table *t)
{
	static const char *names[] = {"dt", "err_verlet", "err_leapfrog", "err_velocity_verlet",
	                              "err_compensated"};
	static const char *units[] = {"tau", "sigma", "sigma", "sigma", "sigma"};
	lz_data *d = lz_lesson_data(L, "roundoff.dat", "oscillator centred at X0=1000, "
	                            "x0=X0+1, v0=0, T=1: |x(T)-X0-cos T| vs dt", 5, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < t->npoints; i++) {
		double row[5] = {t->dt[i]};
		memcpy(row + 1, t->err[i], sizeof t->err[i]);
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

static int write_json(lz_lesson *L, const table *t)
{
	char key[64];
	lz_json *j = lz_lesson_json(L, "roundoff.json");
	if (!j)
		return LZ_EIO;
	for (int k = 0; k < NVARIANTS - 1; k++) {
		snprintf(key, sizeof key, "roundoff_wins_below_dt_%s", variant_name[k]);
		lz_json_num(j, key, overtake_dt(t, k));
	}
	lz_json_num(j, "smallest_dt", t->dt[t->npoints - 1]);
	for (int k = 0; k < NVARIANTS; k++) {
		snprintf(key, sizeof key, "error_at_smallest_dt_%s", variant_name[k]);
		lz_json_num(j, key, t->err[t->npoints - 1][k]);
	}
	return lz_json_end(j);
}

/* At the smallest step every naive variant must be far worse than the compensated
 * one, which must still be falling and near machine precision. */
static void check(lz_lesson *L, const table *t)
{
	int last = t->npoints - 1;
	double comp = t->err[last][NVARIANTS - 1];
	printf("  %-16s %22s %14s\n", "variant", "round-off wins below", "error@min dt");
	for (int k = 0; k < NVARIANTS; k++) {
		int good = k < NVARIANTS - 1 ? t->err[last][k] > 10.0 * comp
		           : comp < 1e-14 && comp < t->err[last - 4][k];
		char below[32] = "never";
		if (!isnan(overtake_dt(t, k)))
			snprintf(below, sizeof below, "dt = %.2e", overtake_dt(t, k));
		printf("  %-16s %22s %14.2e  %s\n", variant_name[k], below, t->err[last][k],
		       lz_lesson_check(L, good));
	}
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	int kmax = MAX_POINTS - 1;
	table t = {0};
	printf("roundoff: oscillator (omega = 1) centred at X0 = %g, x0 = X0 + 1, v0 = 0; "
	       "error |x(T) - X0 - cos T| at T = %g\n", X0, T_END);
	printf("  n = 10 ... %ld steps (4 per decade); verlet, leapfrog, velocity Verlet, "
	       "velocity Verlet + Kahan\n", lround(pow(10.0, 1.0 + kmax / 4.0)));
	for (int k = 0; k <= kmax; k++) {
		long n = lround(pow(10.0, 1.0 + k / 4.0));
		t.dt[t.npoints] = T_END / (double)n;
		for (int v = 0; v < NVARIANTS; v++)
			if (run_variant(v, n, &t.err[t.npoints][v]) != LZ_OK)
				return lz_lesson_error(&L);
		t.npoints++;
	}
	check(&L, &t);
	if (write_data(&L, &t) != LZ_OK || write_json(&L, &t) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "round-off overtakes truncation unless compensated");
}
