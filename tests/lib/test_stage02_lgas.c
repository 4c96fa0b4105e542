/* test_stage02_lgas.c — the library half of lz/lgas.h, which students do not write:
 * allocation and its checks, initial states, totals, obstacles, and the scene checks
 * of method lattice-gas. These call no graded function and pass with the stubs as
 * well, except the last two, which run the method's scenes (the physics of the
 * pulse and of a plate in a flow) and so need a working lgas.c: with the stubs they
 * fail at "not implemented". `make check` runs this suite against the reference. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/lgas.h"
#include "method.h"
#include "lz/output.h"
#include "scene.h"
#include "lztest.h"
#include "support.h"


LZ_TEST(lgas_alloc_rejects_bad_sizes)
{
	ck_assert(lz_lgas_alloc(LZ_LGAS_FHP, 100) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "100") && strstr(lz_error_message(), "64") &&
	              strstr(lz_error_message(), "128"), "size 100: the message should name it and "
	              "the nearest powers of two 64 and 128: '%s'", lz_error_message());
	ck_assert(lz_lgas_alloc(LZ_LGAS_HPP, 0) == NULL);
	ck_assert(lz_lgas_alloc(LZ_LGAS_HPP, -8) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "-8"), "'%s'", lz_error_message());
	ck_assert(lz_lgas_alloc(LZ_LGAS_HPP, 1) == NULL);
	ck_assert(lz_lgas_alloc(LZ_LGAS_FHP, 2 * LZ_LGAS_SIDE_MAX) == NULL);
	ck_assert(lz_lgas_alloc((lz_lgas_model)7, 16) == NULL);
	lz_lgas_model m;
	ck_assert(lz_lgas_parse("fhp", &m) == LZ_OK && m == LZ_LGAS_FHP);
	ck_assert(lz_lgas_parse("hpp", &m) == LZ_OK && m == LZ_LGAS_HPP);
	ck_assert(lz_lgas_parse("fhp2", &m) == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "hpp|fhp"));
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 2);
	ck_assert(g && g->side == 2 && g->mask == 1 && g->shift == 1 && g->nbits == 6);
	ck_assert(lz_lgas_index(g, -1, -1) == 3 && lz_lgas_index(g, 2, 1) == 2);
	lz_lgas_free(g);
	lz_lgas_free(NULL);
}
END_TEST

LZ_TEST(lgas_init_rejects_bad_densities)
{
	gsl_rng *r = lz_test_rng(1);
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 8);
	static const double bad[] = {0.0, 1.0, -0.1, 1.5, NAN};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		ck_assert(lz_lgas_init_uniform(g, bad[i], r) == LZ_EINVAL);
		ck_assert_msg(strstr(lz_error_message(), "(0, 1)"), "density %g: '%s'", bad[i],
		              lz_error_message());
		ck_assert(lz_lgas_init_shear(g, bad[i], 0.1, r) == LZ_EINVAL);
		ck_assert(lz_lgas_init_pulse(g, bad[i], 0.1, r) == LZ_EINVAL);
	}
	ck_assert(lz_lgas_init_shear(g, 0.4, 0.8, r) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "u0 = 0.8"), "'%s'", lz_error_message());
	ck_assert(lz_lgas_init_pulse(g, 0.6, 1.0, r) == LZ_EINVAL);
	ck_assert(lz_lgas_init_pulse(g, 0.2, -1.0, r) == LZ_EINVAL);
	lz_lgas_free(g);
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_uniform_density_and_totals)
{
	gsl_rng *r = lz_test_rng(2);
	for (int m = 0; m < 2; m++) {
		lz_lgas *g = lz_lgas_alloc(m ? LZ_LGAS_FHP : LZ_LGAS_HPP, 128);
		LZ_REQUIRE_TRUE(lz_lgas_init_uniform(g, 0.3, r) == LZ_OK);
		int64_t mass, p[2];
		lz_lgas_totals(g, &mass, p);
		double links = 128.0 * 128.0 * g->nbits, mean = mass / links;
		LZ_REQUIRE(fabs(mean - 0.3) < 5 * sqrt(0.21 / links), "uniform d = 0.3: measured %g",
		              mean);
		for (size_t i = 0; i < 128 * 128; i++)
			LZ_REQUIRE_TRUE(g->site[i] < (1u << g->nbits));
		/* By hand: one particle in each direction of the site at the origin. */
		memset(g->site, 0, 128 * 128);
		g->site[0] = m ? 0x03 : 0x03;  /* directions 0 and 1 */
		lz_lgas_totals(g, &mass, p);
		LZ_REQUIRE_TRUE(mass == 2 && p[0] == 1 && p[1] == 1);
		LZ_REQUIRE_TRUE(lz_lgas_row_px2(g, 0) == (m ? 2 + 1 : 2));
		g->site[0] = m ? 0x3F : 0x0F;
		lz_lgas_totals(g, &mass, p);
		LZ_REQUIRE_TRUE(mass == g->nbits && p[0] == 0 && p[1] == 0);
		LZ_REQUIRE_TRUE(lz_lgas_row_px2(g, 0) == 0);
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_shear_wave_has_its_momentum_profile)
{
	gsl_rng *r = lz_test_rng(3);
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 256);
	ck_assert(lz_lgas_init_shear(g, 0.2, 0.1, r) == LZ_OK);
	/* Row-averaged x-momentum per site: 6 d u0 sin(2π y/L) on FHP (Σ c_x² = 3, times 2d). */
	double sum = 0.0;
	for (int32_t y = 0; y < 256; y++)
		sum += lz_lgas_row_px2(g, y) / 2.0 / 256.0 * sin(2.0 * M_PI * y / 256.0);
	double amp = 2.0 * sum / 256.0, want = 2.0 * 0.2 * 3.0 * 0.1;
	ck_assert_msg(fabs(amp - want) < 0.1 * want, "FHP shear wave d = 0.2, u0 = 0.1: "
	              "momentum amplitude %g per site, expected 2 d u0 Σ c_x² = %g", amp, want);
	int64_t mass, p[2];
	lz_lgas_totals(g, &mass, p);
	ck_assert(fabs(mass / (256.0 * 256.0 * 6) - 0.2) < 0.005);
	lz_lgas_free(g);
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_pulse_is_denser_in_the_middle_and_keeps_walls)
{
	gsl_rng *r = lz_test_rng(4);
	for (int m = 0; m < 2; m++) {
		lz_lgas *g = lz_lgas_alloc(m ? LZ_LGAS_FHP : LZ_LGAS_HPP, 64);
		lz_lgas_set_wall(g, 0, 0);
		lz_lgas_set_wall(g, -1, 64);  /* wraps to (63, 0) */
		ck_assert(lz_lgas_init_pulse(g, 0.2, 2.0, r) == LZ_OK);
		ck_assert(g->site[0] & LZ_LGAS_WALL && g->site[63] & LZ_LGAS_WALL);
		long centre = 0, corner = 0;
		for (int32_t y = -2; y <= 2; y++)
			for (int32_t x = -2; x <= 2; x++) {
				centre += __builtin_popcount(g->site[lz_lgas_index(g, 32 + x, 32 + y)]);
				corner += __builtin_popcount(g->site[lz_lgas_index(g, 8 + x, 8 + y)] & 0x3F);
			}
		ck_assert_msg(centre > 2 * corner, "pulse a = 2: centre %ld particles, corner %ld",
		              centre, corner);
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_flow_has_its_mean_velocity)
{
	gsl_rng *r = lz_test_rng(5);
	for (int m = 0; m < 2; m++) {
		lz_lgas *g = lz_lgas_alloc(m ? LZ_LGAS_FHP : LZ_LGAS_HPP, 256);
		ck_assert(lz_lgas_init_flow(g, 0.2, 0.3, r) == LZ_OK);
		int64_t mass, p[2];
		lz_lgas_totals(g, &mass, p);
		/* Cartesian momentum from the sheared integer one (lz_lgas_totals). */
		double px = m ? p[0] + 0.5 * p[1] : p[0], py = m ? p[1] * sqrt(3.0) / 2.0 : p[1];
		/* Each particle's c_x has variance about 1/2: the mean over ~mass particles
		 * scatters by sqrt(1/(2 mass)) ≈ 0.003. */
		ck_assert_msg(fabs(px / mass - 0.3) < 0.02 && fabs(py / mass) < 0.02, "%s flow u0 = 0.3: "
		              "mean particle velocity (%g, %g), expected (0.3, 0)", m ? "FHP" : "HPP",
		              px / mass, py / mass);
		/* Links against the flow are emptied at u0 = 1/2, never below. */
		ck_assert(lz_lgas_init_flow(g, 0.2, 0.5, r) == LZ_OK);
		ck_assert(lz_lgas_init_flow(g, 0.2, -0.6, r) == LZ_EINVAL);
		ck_assert_msg(strstr(lz_error_message(), "u0 = -0.6") && strstr(lz_error_message(), "1/2"),
		              "flow u0 = -0.6 should be refused naming it and the bound 1/2: '%s'",
		              lz_error_message());
		ck_assert(lz_lgas_init_shear(g, 0.2, 0.7, r) == LZ_EINVAL);
		ck_assert(lz_lgas_init_flow(g, 0.8, 0.2, r) == LZ_EINVAL);
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(lgas_obstacle_sizes_rejected_with_range)
{
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 64);
	static const int64_t bad[] = {0, -3, 33, 1000};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
		for (int k = LZ_LGAS_PLATE; k <= LZ_LGAS_DISK; k++) {
			char value[32];
			snprintf(value, sizeof value, "%lld", (long long)bad[i]);
			LZ_REQUIRE_TRUE(lz_lgas_add_obstacle(g, (lz_lgas_obstacle)k, bad[i]) == -1);
			LZ_REQUIRE(strstr(lz_error_message(), value) &&
			              strstr(lz_error_message(), "[1, 32]"), "obstacle size %s on L = 64: "
			              "the message should name it and the range [1, 32]: '%s'", value,
			              lz_error_message());
		}
	LZ_REQUIRE_TRUE(lz_lgas_add_obstacle(g, (lz_lgas_obstacle)7, 4) == -1);
	ck_assert(lz_lgas_add_obstacle(g, LZ_LGAS_NO_OBSTACLE, 4) == 0);
	for (size_t i = 0; i < 64 * 64; i++)
		LZ_REQUIRE(g->site[i] == 0, "a refused obstacle marked site %zu", i);
	lz_lgas_free(g);
}
END_TEST

/* A wall set crossed by no particle: every row of a plate has one site, and the rows'
 * sites step by at most one site (a particle that changes row moves by 0 or -1 in x,
 * so it meets the wall in its old or its new row). A disk holds the sites within
 * size/2, about π (size/2)² / (area per site) of them. */
LZ_TEST(lgas_obstacle_shapes)
{
	for (int m = 0; m < 2; m++) {
		int fhp = m == 1;
		double h = fhp ? sqrt(3.0) / 2.0 : 1.0;
		lz_lgas *g = lz_lgas_alloc(fhp ? LZ_LGAS_FHP : LZ_LGAS_HPP, 128);
		LZ_REQUIRE_TRUE(lz_lgas_add_obstacle(g, LZ_LGAS_PLATE, 21) == 21);
		int rows = 0;
		int32_t last = -1;
		for (int32_t y = 0; y < 128; y++) {
			int in_row = 0;
			for (int32_t x = 0; x < 128; x++)
				if (g->site[lz_lgas_index(g, x, y)] & LZ_LGAS_WALL) {
					double X, Y;
					lz_lgas_position(g, x, y, &X, &Y);
					LZ_REQUIRE(fabs(X - 32.0) <= 0.5 && fabs(Y - y * h) < 1e-12, "%s plate "
					              "site (%d, %d) is at X = %g, more than half a spacing from "
					              "L/4 = 32", fhp ? "FHP" : "HPP", x, y, X);
					LZ_REQUIRE(last < 0 || rows == 0 || x == last || x == last - 1,
					              "plate rows step from x = %d to %d: a particle could pass",
					              last, x);
					last = x;
					in_row++;
				}
			LZ_REQUIRE_TRUE(in_row <= 1);
			rows += in_row;
			LZ_REQUIRE(in_row || rows == 0 || rows == 21, "the plate has a gap at row %d", y);
		}
		LZ_REQUIRE_TRUE(rows == 21);
		memset(g->site, 0, 128 * 128);
		int64_t n = lz_lgas_add_obstacle(g, LZ_LGAS_DISK, 40);
		double want = M_PI * 20 * 20 / h;
		LZ_REQUIRE(fabs(n - want) < 0.05 * want, "%s disk of diameter 40: %lld sites, "
		              "expected about π 20² / %g = %g", fhp ? "FHP" : "HPP", (long long)n, h, want);
		for (int32_t y = 0; y < 128; y++)
			for (int32_t x = 0; x < 128; x++) {
				double X, Y;
				lz_lgas_position(g, x, y, &X, &Y);
				double r = hypot(X - 32.0, Y - 64 * h);
				int wall = (g->site[lz_lgas_index(g, x, y)] & LZ_LGAS_WALL) != 0;
				/* Sites at exactly 20 may go either way by round-off. */
				LZ_REQUIRE(wall ? r <= 20.0 + 1e-9 : r > 20.0 - 1e-9, "%s site (%d, %d) at distance %g from the "
				              "disk's centre: wall = %d", fhp ? "FHP" : "HPP", x, y, r, wall);
			}
		lz_lgas_free(g);
	}
}
END_TEST

/* Bind a lattice-gas scene from "a=1;b=2" assignments. */
static int bind_lgas(const char *assignments)
{
	return lzt_bind(&lz_method_lattice_gas, assignments);
}

LZ_TEST(lgas_scene_rejects_bad_obstacles)
{
	ck_assert_msg(lz_method_find("lattice-gas") == &lz_method_lattice_gas,
	              "method lattice-gas is not registered");
	ck_assert_msg(bind_lgas("init=flow;amplitude=0.3;obstacle=plate;obstacle_size=32") == LZ_OK,
	              "a plate in a flow: %s", lz_error_message());
	ck_assert_msg(bind_lgas("obstacle=disk") == LZ_OK, "a disk of the default size: %s",
	              lz_error_message());
	ck_assert_msg(bind_lgas("obstacle=disk;obstacle_size=128") == LZ_OK, "L/2: %s",
	              lz_error_message());
	ck_assert(bind_lgas("obstacle=plate;obstacle_size=300") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "300") && strstr(lz_error_message(), "[1, 128]"),
	              "obstacle_size = 300 on L = 256: name it and the range [1, 128]: '%s'",
	              lz_error_message());
	ck_assert(bind_lgas("obstacle=disk;obstacle_size=129") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "129"));
	ck_assert(bind_lgas("obstacle=plate;obstacle_size=0") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "obstacle_size"));
	ck_assert(bind_lgas("obstacle_size=8") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "obstacle = none"), "a size without an "
	              "obstacle: '%s'", lz_error_message());
	ck_assert(bind_lgas("obstacle=wall") == LZ_EINVAL);
	ck_assert(bind_lgas("init=flow;amplitude=0.6") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "0.6"));
	ck_assert(bind_lgas("block=6") == LZ_EINVAL);
	ck_assert(bind_lgas("size=64;block=128") == LZ_EINVAL);
	ck_assert(bind_lgas("init=flow;steps=100;average=200") == LZ_EINVAL);
	ck_assert(bind_lgas("init=pulse;amplitude=1;average=10") == LZ_EINVAL);
	ck_assert(bind_lgas("init=shear-wave;average=10") == LZ_EINVAL);
}
END_TEST

/* ---- running the method (needs a working lgas.c) ---- */

/* Run a lattice-gas scene: the file `scene` (from the tree root) with the ";"-separated
 * overrides, into a fresh directory; returns the parsed summary.json and leaves the
 * directory in *dir. Plots are skipped (PATH without gnuplot): the numbers are tested. */
static lzt_json *run_lgas(const char *scene, const char *overrides, const char **dir)
{
	*dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_lattice_gas, scene, overrides, lzt_path(*dir, "run"));
	ck_assert_msg(status == LZ_OK, "%s with %s failed: %s", scene, overrides, lz_error_message());
	return lzt_summary(lzt_path(*dir, "run"));
}

/* The sound front of a pulse on HPP and on FHP, run small: the scenes 02-hpp-pulse and
 * 02-fhp-pulse at L = 256 for 60 steps (the ring reaches r = L/8 + 60 = 92 < L√3/4).
 * front_anisotropy is the angular harmonic H_m of the excess density in that ring, m
 * the lattice's own symmetry (4, 6): 0 for a round front, 1 for excess that only
 * streams along the lattice axes. On HPP the momentum flux is not isotropic (Π_xy ≡ 0:
 * a particle never carries momentum across its own axis) and at d = 0.1 a particle
 * collides only every ~10 steps, so the excess runs ahead along the 4 axes: over 20
 * seeds H_4 = 0.15-0.23 (mean 0.20), each ± 0.024 of site noise. The triangular
 * lattice's 6 directions make every tensor up to rank 4 isotropic, which leaves FHP
 * only a kinetic remainder: H_6 = 0.00-0.07 (mean 0.03) ± 0.019. The bounds, 0.12 and
 * 0.09, lie three standard deviations of the seed scatter beyond either mean. */
LZ_TEST(lgas_pulse_front_hpp_anisotropic_fhp_round)
{
	const char *dir;
	lzt_json *hpp = run_lgas("datasets/scenes/02-hpp-pulse.scene", "size=256;steps=60;block=8",
	                         &dir);
	ck_assert_msg(lzt_num(hpp, "front_harmonic") == 4, "HPP's front harmonic should be 4");
	double h4 = lzt_num(hpp, "front_anisotropy"), e4 = lzt_num(hpp, "front_anisotropy_err");
	ck_assert_msg(lzt_num(hpp, "mass_change") == 0 && lzt_num(hpp, "momentum_change") == 0,
	              "the HPP pulse did not conserve mass and momentum exactly");
	lz_rmtree(dir);
	lzt_json *fhp = run_lgas("datasets/scenes/02-fhp-pulse.scene", "size=256;steps=60;block=8",
	                         &dir);
	ck_assert_msg(lzt_num(fhp, "front_harmonic") == 6, "FHP's front harmonic should be 6");
	double h6 = lzt_num(fhp, "front_anisotropy"), e6 = lzt_num(fhp, "front_anisotropy_err");
	lz_rmtree(dir);
	ck_assert_msg(e4 > 0.01 && e4 < 0.04 && e6 > 0.01 && e6 < 0.04, "the error bars of the "
	              "harmonics, %g (HPP) and %g (FHP), should be the site noise, about 0.02", e4,
	              e6);
	ck_assert_msg(h4 > 0.12, "HPP pulse: front harmonic H_4 = %g ± %g; the square lattice "
	              "sends the excess ahead along its axes, H_4 ≈ 0.2 at d = 0.1 after 60 "
	              "steps — is the HPP collision turning pairs by 90°?", h4, e4);
	ck_assert_msg(fabs(h6) < 0.09, "FHP pulse: front harmonic H_6 = %g ± %g; the triangular "
	              "lattice should spread the pulse as a circle (|H_6| < 0.09) — are all six "
	              "directions propagated, and the collisions turned both ways?", h6, e6);
	free(hpp);
	free(fhp);
}
END_TEST

/* The mean x-velocity of the blocks of velocity.dat whose centre lies in the box
 * [x0, x1) × [y0, y1); NAN when there is none. */
static double mean_ux(const char *path, double x0, double x1, double y0, double y1)
{
	FILE *f = fopen(path, "r");
	ck_assert_msg(f != NULL, "no %s", path);
	char line[512];
	double sum = 0.0;
	int n = 0;
	while (fgets(line, sizeof line, f)) {
		double x, y, ux, uy, rho;
		if (line[0] == '#' || sscanf(line, "%lf %lf %lf %lf %lf", &x, &y, &ux, &uy, &rho) != 5)
			continue;
		if (x >= x0 && x < x1 && y >= y0 && y < y1 && isfinite(ux)) {
			sum += ux;
			n++;
		}
	}
	fclose(f);
	return n ? sum / n : NAN;
}

/* A plate of 32 rows in an FHP flow u0 = 0.3 (d = 0.2, L = 128, 200 steps). Walls only
 * reverse particles, so the mass stays exact (the run would fail otherwise); the
 * momentum the plate takes is the drag. It meets a momentum flux of about
 * 6 d u0 = 0.36 per row and step and stops a good part of it: the drag measured over
 * five seeds is 5.4-5.8 per step, against 6 d u0 · 32 = 11.5; it must be above a tenth
 * of that. In a gas at rest the plate takes only fluctuations, |drag| <= 0.35 over five
 * seeds: below a fifth of the drag in the flow. Behind the plate the flow is slowed:
 * the wake's mean u_x is below half the far field's. */
LZ_TEST(lgas_plate_keeps_mass_and_takes_momentum)
{
	const char *dir;
	const char *common = "size=128;obstacle_size=32;steps=200;average=100;block=8";
	lzt_json *flow = run_lgas("datasets/scenes/02-fhp-plate.scene", common, &dir);
	double drag = lzt_num(flow, "obstacle_drag"), flux = 6 * 0.2 * 0.3 * 32;
	ck_assert_msg(lzt_num(flow, "density") == 0.2 && lzt_num(flow, "amplitude") == 0.3,
	              "02-fhp-plate.scene should be d = 0.2, u0 = 0.3 (this test's numbers)");
	ck_assert_msg(lzt_num(flow, "mass_change") == 0, "mass changed with a plate");
	ck_assert_msg(lzt_num(flow, "obstacle_sites") == 32, "the plate has %g sites, not 32",
	              lzt_num(flow, "obstacle_sites"));
	ck_assert_msg(lzt_num(flow, "momentum_change") != 0 &&
	              lzt_num(flow, "momentum_change_x") == -200 * drag, "the walls took no momentum, "
	              "or obstacle_drag is not -momentum_change_x / steps");
	ck_assert_msg(drag > 0.1 * flux, "plate of 32 rows in a flow u0 = 0.3: drag %g per step, "
	              "expected well above a tenth of the flux 6 d u0 · 32 = %g — do wall sites "
	              "reverse their particles?", drag, flux);
	ck_assert_msg(lzt_num(flow, "mean_velocity_x_end") < lzt_num(flow, "mean_velocity_x_start"),
	              "the flow did not slow down although the plate took momentum");
	double h = sqrt(3.0) / 2.0, mid = 64 * h;
	const char *vel = lzt_path(dir, "run/velocity.dat");
	double wake = mean_ux(vel, 32, 64, mid - 10, mid + 10);
	double far = mean_ux(vel, 0, 128, mid + 32, mid + 56);
	ck_assert_msg(wake < 0.5 * far, "behind the plate u_x = %g, far from it %g: no wake", wake,
	              far);
	ck_assert(lzt_exists(lzt_path(dir, "run/obstacle.dat")));
	lz_rmtree(dir);
	lzt_json *rest = run_lgas("datasets/scenes/02-fhp-plate.scene", "size=128;obstacle_size=32;"
	                          "steps=200;average=100;block=8;init=uniform", &dir);
	ck_assert_msg(lzt_num(rest, "mass_change") == 0, "mass changed with a plate at rest");
	double still = lzt_num(rest, "obstacle_drag");
	ck_assert_msg(fabs(still) < 0.2 * drag, "a plate in a gas at rest took %g per step, the one "
	              "in the flow %g: a gas at rest should push it both ways alike", still, drag);
	lz_rmtree(dir);
	free(flow);
	free(rest);
}
END_TEST
