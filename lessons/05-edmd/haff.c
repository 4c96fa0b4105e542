/* haff — lesson 05, experiment: a granular gas cools. Inelastic hard disks (restitution
 * e < 1) lose kinetic energy at every collision, and as they slow down they collide
 * less often: Haff's law.
 *
 * The derivation, kinetic theory at its simplest. A collision with normal relative
 * velocity u_n loses (1 - e²) u_n²/4 (lz_edmd_bounce). Collisions select fast
 * approaches: for Maxwellian velocities at temperature T the approach speed of the
 * colliding pairs has the density ∝ u exp(-u²/4T), so <u_n²> per collision = 4T, and
 * each collision loses (1 - e²) T on average. With N Γ/2 collisions per unit time
 * and an energy N·(d/2)·T,
 *     dT/dt = -(1 - e²) Γ T / d,
 * and the collision rate goes as the speed, Γ = Γ0 √(T/T0) at fixed density. So
 *     dT/dt = -(1 - e²) Γ0 T^(3/2) / (d √T0)  ⇒  T(t) = T0 / (1 + t/t0)²,
 *     t0 = 2d / ((1 - e²) Γ0):
 * t0 is 2d/(1 - e²) mean free times at the start — 21 for e = 0.9, 7.8 for e = 0.7 in
 * 2D. No fit is needed: Γ0 is measured in the elastic run that prepares the start.
 *
 * The run: N hard disks at η = 0.25 melted elastically (and Γ0 measured), then the
 * restitution is set to e and T(t) is sampled at times geometric in t/t0. The
 * homogeneous cooling state is unstable: fluctuations of density grow (a denser
 * region collides more, cools faster, its pressure drops and it draws in more
 * particles), clusters form, and T falls away from Haff's law. At e = 0.7 the clusters
 * may collapse (infinitely many collisions in a finite time): lz_edmd_run then stops
 * with LZ_EPHYS and the run ends there, at the time reached. Also measured from the
 * early stretch: the energy lost per collision in units of T (theory: 1 - e²), and
 * the fitted t0 (1/√T is linear in t under Haff's law: gsl_fit_linear).
 *
 * Checks, for both restitutions: early on, while t <= t0/4 (T falls to 0.64 T0, in 1.6
 * (e = 0.7) to 4.4 (e = 0.9) collisions per particle), the measured T is within 3 % of
 * Haff's law with the kinetic-theory t0; and the energy lost per collision over
 * t < t0/2 is within 5 % of (1 - e²) kT. Both assume molecular chaos: uncorrelated,
 * Maxwellian velocities of the colliding pairs. Inelastic collisions build up
 * correlations (partners that just collided move alike, and meet again more gently):
 * at e = 0.7 a collision loses 2-4 % less than (1 - e²) kT after a few collisions per
 * particle, and T runs 2-5 % above Haff's law by t0/2. Later the growing clusters and
 * vortices hold kinetic energy that the collisions do not dissipate, and T falls much
 * slower.
 *
 * Usage: haff OUTDIR [--quick]
 * Writes OUTDIR/haff.dat, haff_config.dat (the e = 0.7 disks at the end) and haff.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"

#define SEED 5006u
#define DIM 2
#define ETA 0.25
#define NREST 2
#define NSAMPLE 48
#define TAU_MIN 0.01
#define CHECK_TAU 0.25  /* the early regime checked: t <= t0/4, while T falls to 0.64 T0 */
#define LOSS_TOL 0.05   /* energy lost per collision: within 5 % of (1 - e²) T */
#define HAFF_TOL 0.03
#define FIT_TAU 0.5     /* t0 fitted over t < 0.5 t0 */

static const double rest_of[NREST] = {0.9, 0.7};

typedef struct {
	size_t n;
	double melt;      /* events per particle, elastic */
	double tau_max;   /* the run ends at tau_max · t0 */
} sizes;

static const sizes full = {40000, 30, 1000};
static const sizes quick = {10000, 20, 100};

typedef struct {
	double gamma0, t0;        /* elastic collision rate at the start, Haff's t0 */
	double tau[NSAMPLE], T[NSAMPLE], coll[NSAMPLE];  /* t/t0, kT, collisions/particle */
	int samples;
	double tau_end;           /* where the run ended (collapse or tau_max) */
	int collapsed;
	char why[300];
	double loss_per_coll;     /* energy lost per collision / T, early stretch */
	double t0_fit, worst;     /* fitted t0; largest |T/T_Haff - 1| for tau <= CHECK_TAU */
} cooling;

/* Run e (melted, elastic) cooling at restitution r; the e = 0.7 disks at the end go
 * to cfg. */
static int cool(lz_edmd *e, double r, const sizes *sz, cooling *c)
{
	lz_edmd_sample s0 = lz_edmd_measure(e);  /* the elastic melt's Γ at T = 1 */
	double T0 = lz_edmd_temperature(e);
	c->gamma0 = s0.gamma;
	c->t0 = 2.0 * DIM / ((1 - r * r) * c->gamma0);
	e->restitution = r;
	lz_edmd_reset_counts(e);
	double start = lz_edmd_time(e), E_prev = lz_edmd_energy(e), T_prev = 1, C_prev = 0;
	double lost = 0, weight = 0;  /* energy lost, Σ collisions × T, over t < FIT_TAU t0 */
	double fx[NSAMPLE], fy[NSAMPLE];
	size_t nfit = 0;
	c->samples = 0;
	c->collapsed = 0;
	c->worst = 0;
	snprintf(c->why, sizeof c->why, "reached t = %g t0", sz->tau_max);
	for (int k = 0; k < NSAMPLE; k++) {
		double tau = TAU_MIN * pow(sz->tau_max / TAU_MIN, (double)k / (NSAMPLE - 1));
		int st = lz_edmd_run(e, UINT64_MAX, start + tau * c->t0);
		c->tau_end = (lz_edmd_time(e) - start) / c->t0;
		if (st == LZ_EPHYS) {
			c->collapsed = 1;
			snprintf(c->why, sizeof c->why, "%s", lz_error_message());
			break;
		}
		if (st)
			return st;
		double T = lz_edmd_temperature(e) / T0;
		c->tau[k] = tau;
		c->T[k] = T;
		c->coll[k] = 2.0 * (double)e->collisions / (double)e->n;
		c->samples = k + 1;
		if (tau <= CHECK_TAU)
			c->worst = fmax(c->worst, fabs(T * (1 + tau) * (1 + tau) - 1));
		if (tau <= FIT_TAU) {
			/* each sample interval's collisions at the interval's mean T */
			double E = lz_edmd_energy(e), C = (double)e->collisions;
			lost += E_prev - E;
			weight += (C - C_prev) * 0.5 * (T_prev + T) * T0;
			E_prev = E;
			T_prev = T;
			C_prev = C;
			fx[nfit] = tau * c->t0;
			fy[nfit++] = 1 / sqrt(T);
		}
	}
	c->loss_per_coll = weight > 0 ? lost / weight : NAN;
	double b0, b1, cov00, cov01, cov11, sumsq;
	c->t0_fit = NAN;
	if (nfit >= 3 && gsl_fit_linear(fx, 1, fy, 1, nfit, &b0, &b1, &cov00, &cov01, &cov11,
	                                &sumsq) == 0)
		c->t0_fit = b0 / b1;
	return LZ_OK;
}

static int write_config(lz_lesson *L, const lz_edmd *e, double tau)
{
	static const char *names[] = {"x", "y", "speed"};
	static const char *units[] = {"σ", "σ", "√(kT) at that time"};
	char title[160];
	snprintf(title, sizeof title, "inelastic hard disks, restitution %g, η = %g, at t = %.3g "
	         "t0; box side %.6g", e->restitution, ETA, tau, e->L);
	lz_data *d = lz_lesson_data(L, "haff_config.dat", title, 3, names, units);
	if (!d)
		return LZ_EIO;
	double T = lz_edmd_temperature(e);
	for (size_t i = 0; i < e->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		double row[3] = {r[0], r[1], sqrt((v[0] * v[0] + v[1] * v[1]) / T)};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("haff: %zu inelastic hard disks at η = %g, restitution 0.9 and 0.7, melted "
	       "elastically for %g events per particle, cooled to t = %g t0; seed %u\n", sz->n,
	       ETA, sz->melt, sz->tau_max, SEED);
	cooling c[NREST];
	for (int k = 0; k < NREST; k++) {
		lz_edmd_params p = {DIM, sz->n, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
		lz_edmd *e = lz_edmd_alloc(&p);
		lz_rng *rng = lz_rng_alloc(NULL, SEED);
		int st = e && rng ? lz_edmd_place_lattice(e, rng) : LZ_EINVAL;
		lz_rng_free(rng);
		if (st == LZ_OK)
			st = lz_edmd_run(e, (uint64_t)(sz->melt * (double)sz->n), INFINITY);
		if (st == LZ_OK) {
			lz_edmd_reset_counts(e);
			st = lz_edmd_run(e, (uint64_t)(sz->melt * (double)sz->n), INFINITY);
		}
		if (st == LZ_OK)
			st = cool(e, rest_of[k], sz, &c[k]);
		if (st == LZ_OK && k == NREST - 1)
			st = write_config(&L, e, c[k].tau_end);
		lz_edmd_free(e);
		if (st)
			return lz_lesson_error(&L);
		cooling *q = &c[k];
		printf("  e = %g: Γ0 = %.4f per unit time, t0 = 2d/((1-e²)Γ0) = %.4g; fitted t0 "
		       "(t < %g t0) = %.4g; energy lost per collision %.4f T (theory 1-e² = %.4f)\n",
		       rest_of[k], q->gamma0, q->t0, FIT_TAU, q->t0_fit, q->loss_per_coll,
		       1 - rest_of[k] * rest_of[k]);
		printf("     t/t0     T/T0   T/T_Haff  collisions/particle\n");
		for (int s = 0; s < q->samples; s += 4)
			printf("  %9.3g %8.3g %9.4f %12.1f\n", q->tau[s], q->T[s],
			       q->T[s] * (1 + q->tau[s]) * (1 + q->tau[s]), q->coll[s]);
		printf("  e = %g: the run ended at t = %.4g t0: %s\n", rest_of[k], q->tau_end, q->why);
		int ok = q->worst <= HAFF_TOL && q->samples > 0 && q->tau[q->samples - 1] >= CHECK_TAU;
		printf("  e = %g: T within %.0f %% of Haff's law up to t = %g t0 (worst %.2f %%): %s\n",
		       rest_of[k], 100 * HAFF_TOL, CHECK_TAU, 100 * q->worst, lz_lesson_check(&L, ok));
		double loss = q->loss_per_coll / (1 - rest_of[k] * rest_of[k]) - 1;
		printf("  e = %g: energy lost per collision %.4f kT, %+.1f %% from (1 - e²) kT (at most "
		       "%.0f %%): %s\n", rest_of[k], q->loss_per_coll, 100 * loss, 100 * LOSS_TOL,
		       lz_lesson_check(&L, fabs(loss) <= LOSS_TOL));
	}

	static const char *names[] = {"restitution", "t", "tau", "T", "T_over_Haff",
	                              "collisions_per_particle"};
	static const char *units[] = {"", "time", "t/t0", "kT/kT0", "", ""};
	lz_data *d = lz_lesson_data(&L, "haff.dat", "inelastic hard disks at η = 0.25: "
	                            "temperature against time", 6, names, units);
	if (!d)
		return lz_lesson_error(&L);
	for (int k = 0; k < NREST; k++)
		for (int s = 0; s < c[k].samples; s++) {
			double row[6] = {rest_of[k], c[k].tau[s] * c[k].t0, c[k].tau[s], c[k].T[s],
			                 c[k].T[s] * (1 + c[k].tau[s]) * (1 + c[k].tau[s]), c[k].coll[s]};
			lz_data_row(d, row);
		}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	lz_json *j = lz_lesson_json(&L, "haff.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", (long long)sz->n);
	for (int k = 0; k < NREST; k++) {
		char key[64];
		int e10 = (int)lround(10 * rest_of[k]);
		snprintf(key, sizeof key, "t0_theory_e0%d", e10);
		lz_json_num(j, key, c[k].t0);
		snprintf(key, sizeof key, "t0_fitted_e0%d", e10);
		lz_json_num(j, key, c[k].t0_fit);
		snprintf(key, sizeof key, "loss_per_collision_over_T_e0%d", e10);
		lz_json_num(j, key, c[k].loss_per_coll);
		snprintf(key, sizeof key, "worst_haff_deviation_e0%d", e10);
		lz_json_num(j, key, c[k].worst);
		snprintf(key, sizeof key, "end_tau_e0%d", e10);
		lz_json_num(j, key, c[k].tau_end);
		snprintf(key, sizeof key, "collapsed_e0%d", e10);
		lz_json_bool(j, key, c[k].collapsed);
	}
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "Haff's law within %.0f %% up to t = %g t0; the loss per "
	                        "collision within %.0f %% of (1 - e²) kT", 100 * HAFF_TOL, CHECK_TAU,
	                        100 * LOSS_TOL);
}
