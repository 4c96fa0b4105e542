/* test_lj.c — the integrators on the Lennard-Jones fluid: NVE energy conservation
 * and its dt² scaling, the pressure, and a bound pair, N = 2 (the lone particle,
 * N = 1, is part of the free-fall tests: zero force is the simplest constant force). */
#include <math.h>

#include <gsl/gsl_statistics_double.h>

#include "stage01.h"

/* Velocity Verlet on the lesson's fluid (N = 108, ρ = 0.8, T = 1) to t = 1: the
 * largest relative energy error and the rms spread of E about its mean over |E0|. */
static void lj_energy_error(double dt, double *max_rel, double *rms_rel)
{
	enum { MAX_STEPS = 1000 };
	lz_lj p;
	lz_md *s = lj_fluid_new(&p, 108, 0.8, 1.0, 1);
	ck_assert(lz_md_start(s, LZ_VELOCITY_VERLET, dt) == LZ_OK);
	int steps = (int)lround(1.0 / dt);
	ck_assert(steps <= MAX_STEPS);
	double e0 = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), e[MAX_STEPS];
	*max_rel = 0.0;
	for (int k = 0; k < steps; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		e[k] = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL);
		*max_rel = fmax(*max_rel, fabs(e[k] - e0) / fabs(e0));
	}
	*rms_rel = gsl_stats_sd(e, 1, (size_t)steps) / fabs(e0);
	lz_md_free(s);
}

LZ_TEST(lj_nve_energy_conserved)
{
	double max_rel, rms;
	lj_energy_error(0.002, &max_rel, &rms);
	ck_assert_msg(max_rel < 1e-4, "Lennard-Jones N = 108, ρ = 0.8, T = 1, velocity Verlet at "
	              "dt = 0.002: the total energy moved by %.2e (relative) in 500 steps; it "
	              "should stay below 1e-4 (it is ~2e-5) — is the second half-kick using the "
	              "new force?", max_rel);
}
END_TEST

LZ_TEST(lj_energy_spread_scales_as_dt_squared)
{
	double max1, rms1, max2, rms2;
	lj_energy_error(0.002, &max1, &rms1);
	lj_energy_error(0.004, &max2, &rms2);
	double ratio = rms2 / rms1;
	ck_assert_msg(ratio > 3.2 && ratio < 4.8, "Lennard-Jones NVE: doubling dt from 0.002 to "
	              "0.004 multiplied the rms energy spread by %.2f (%.2e -> %.2e); a "
	              "second-order scheme gives 4 — a ratio near 2 means a first-order error",
	              ratio, rms1, rms2);
}
END_TEST

LZ_TEST(lj_bound_pair_conserves_momentum_and_energy)
{
	/* Two particles 1.5σ apart (inside the well) moving apart slower than escape:
	 * they oscillate. The pair forces are exact opposites, so the total momentum,
	 * zero at the start, stays exactly zero. */
	const double dt = 0.001;
	lz_lj p;
	ck_assert(lz_lj_init(&p, 2, 3, 0.001, 2.5) == LZ_OK);
	lz_md *s = lz_md_alloc(2, 3, lz_lj_force, &p);
	const double r[6] = {1, 1, 1, 2.5, 1, 1}, v[6] = {0.1, 0.2, -0.3, -0.1, -0.2, 0.3};
	for (int i = 0; i < 6; i++) {
		s->r[i] = r[i];
		s->v[i] = v[i];
	}
	ck_assert(lz_md_start(s, LZ_VELOCITY_VERLET, dt) == LZ_OK);
	double e0 = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), worst_e = 0, worst_p = 0, far = 0;
	for (int k = 0; k < 20000; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		worst_e = fmax(worst_e, fabs(lz_md_energy(s, LZ_VELOCITY_VERLET, NULL) - e0));
		double d2 = 0.0;
		for (int c = 0; c < 3; c++) {
			worst_p = fmax(worst_p, fabs(s->v[c] + s->v[3 + c]));
			d2 += (s->r[c] - s->r[3 + c]) * (s->r[c] - s->r[3 + c]);
		}
		far = fmax(far, sqrt(d2));
	}
	ck_assert_msg(worst_p < 1e-15, "Lennard-Jones pair: the total momentum reached %.2e; "
	              "equal and opposite forces keep it exactly zero — are all n*dim velocity "
	              "components kicked?", worst_p);
	ck_assert_msg(worst_e < 1e-3 * fabs(e0), "Lennard-Jones pair, velocity Verlet at dt = "
	              "0.001: the energy moved by %.2e of |E0| = %.3g over 20000 steps; expected "
	              "< 1e-3", worst_e / fabs(e0), fabs(e0));
	ck_assert_msg(far < 2.5, "Lennard-Jones pair with E < 0: the particles drifted %.3g "
	              "apart, beyond the cutoff 2.5 — a bound pair cannot separate", far);
	lz_md_free(s);
}
END_TEST

/* The literature check of the whole chain — lattice start, force, integrator: the
 * truncated Lennard-Jones fluid at ρ = 0.8, T = 1, rc = 2.5 without tail correction
 * has P = 1.72 ± 0.04 (datasets/reference/lennard-jones.csv). The velocities are
 * rescaled to T after every step (isokinetic), so P = ρT + W/(3V) averages the
 * configurations of T = 1; ten block means give the statistical error. */
LZ_TEST(lj_pressure_matches_literature)
{
	enum { N = 108, MELT = 1000, RUN = 4000, BLOCKS = 10 };
	const double dt = 0.005, T = 1.0, rho = 0.8;
	lz_ref lit = lz_test_reference("lennard-jones.csv", "p truncated", "3", "T=1 rho=0.8 rc=2.5");
	const double p_ref = lit.value, p_ref_err = lit.err;
	lz_lj p;
	lz_md *s = lj_fluid_new(&p, N, rho, T, 3);
	ck_assert(lz_md_start(s, LZ_VELOCITY_VERLET, dt) == LZ_OK);
	/* First the precondition: the dynamics sampled must be Newton's. Without the
	 * thermostat velocity Verlet keeps E within ~1e-4 |E0| at dt = 0.005 (the 2e-5 of
	 * lj_nve_energy_conserved at dt = 0.002, times (5/2)²); a kick with a stale force
	 * drifts far beyond 1e-3 in these 200 steps. Then the thermostatted run. */
	double e0 = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), de = 0.0;
	for (int k = 0; k < 200; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		de = fmax(de, fabs(lz_md_energy(s, LZ_VELOCITY_VERLET, NULL) - e0) / fabs(e0));
	}
	ck_assert_msg(de < 1e-3, "Lennard-Jones fluid at ρ = 0.8 (N = 108), velocity Verlet at "
	              "dt = 0.005 without thermostat: the energy moved by %.2e of |E0| in 200 steps, "
	              "above 1e-3 (it stays near 1e-4) — the pressure would be sampled from a "
	              "trajectory that is not Newton's: does the second half-kick use the new "
	              "force, and does r move with the half-kicked v?", de);
	const double dof = 3.0 * (N - 1), volume = pow(p.box, 3);
	double block[BLOCKS] = {0};
	for (int k = 0; k < MELT + RUN; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		double scale = sqrt(T * dof / (2.0 * lz_md_kinetic(s, LZ_VELOCITY_VERLET)));
		for (size_t i = 0; i < 3 * N; i++)
			s->v[i] *= scale;
		if (k >= MELT)
			block[(k - MELT) / (RUN / BLOCKS)] +=
				(rho * T + p.virial / (3.0 * volume)) / (RUN / BLOCKS);
	}
	double mean = gsl_stats_mean(block, 1, BLOCKS);
	double err = gsl_stats_sd(block, 1, BLOCKS) / sqrt(BLOCKS);
	ck_assert_msg(isfinite(mean) && fabs(mean - p_ref) < p_ref_err + 3.0 * err,
	              "Lennard-Jones fluid at ρ = 0.8, T = 1 (rc = 2.5, N = 108, velocity Verlet "
	              "with the velocities held at T): virial pressure P = %.3f ± %.3f, but the "
	              "literature gives %.2f ± %.2f — a trajectory that is not Newton's (a kick "
	              "with the wrong force, or a lost factor of dt) samples the wrong states",
	              mean, err, p_ref, p_ref_err);
	lz_md_free(s);
}
END_TEST
