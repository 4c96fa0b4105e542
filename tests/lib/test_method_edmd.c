/* test_method_edmd.c — what is measured on an event-driven run (lz/edmd_obs.h,
 * lib/05-edmd/edmd_obs.c) and the `edmd` method (lib/app/method_edmd.c): the blocks, their
 * error bars and guards, the exact identity between pressure and collision rate, the
 * reference equation of state; g(r) against a brute-force pair count and an ideal gas;
 * the mean-square displacement of a nearly free gas; the scene checks (close packing,
 * a config file that overlaps or leaves the box, unknown values); runs that write
 * their summary and only the files asked for; a config file read back; determinism.
 * They need the graded code of stage 05 (heap.c, edmd.c). Each run is small: the suite
 * takes a few seconds with -O2. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_histogram.h>

#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "method.h"
#include "lz/rng.h"
#include "lztest.h"
#include "support.h"

/* ---- helpers ---- */

/* A placed system (lattice start, seed), equilibrated for `equil` events per particle. */
static lz_edmd *system_of(int dim, size_t n, double packing, int walls, unsigned long seed,
                          double equil)
{
	lz_edmd_params p = {.dim = dim, .n = n, .packing = packing, .restitution = 1,
	                    .walls = walls};
	lz_edmd *e = lz_edmd_alloc(&p);
	ck_assert_msg(e != NULL, "%s", lz_error_message());
	lz_rng *rng = lz_rng_alloc(NULL, seed);
	ck_assert(rng != NULL);
	ck_assert_msg(lz_edmd_place_lattice(e, rng) == LZ_OK, "%s", lz_error_message());
	lz_rng_free(rng);
	ck_assert_msg(lz_edmd_run(e, (uint64_t)(equil * (double)n), INFINITY) == LZ_OK, "%s",
	              lz_error_message());
	return e;
}

static int bind_edmd(const char *assignments)
{
	return lzt_bind(&lz_method_edmd, assignments);
}

/* Bind must fail with a message that contains both words (w2 may be NULL). */
static void assert_refused(const char *scene, const char *w1, const char *w2)
{
	ck_assert_msg(bind_edmd(scene) != LZ_OK, "%s was accepted", scene);
	const char *msg = lz_error_message();
	ck_assert_msg(strstr(msg, w1) && (!w2 || strstr(msg, w2)), "%s: the message should "
	              "name '%s'%s%s: %s", scene, w1, w2 ? " and " : "", w2 ? w2 : "", msg);
}

/* Run an edmd scene; the summary (fails if the run does). *dir gets the directory
 * that holds the run directory "run". */
static lzt_json *run_edmd(const char *assignments, const char **dir)
{
	*dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_edmd, NULL, assignments, lzt_path(*dir, "run"));
	ck_assert_msg(status == LZ_OK, "method edmd with %s failed: %s", assignments,
	              lz_error_message());
	return lzt_summary(lzt_path(*dir, "run"));
}

/* ---- blocks, measure, guards ---- */

/* Hard spheres at η = 0.3: the virial Z and Z from the collision rate agree (the exact
 * identity of datasets/reference/collision-identity.csv) and both meet Z_ref = 3.984; the counters add up, the
 * guards stay quiet, kT stays 1. */
LZ_TEST(edmd_blocks_pressure_and_identity)
{
	lz_edmd *e = system_of(3, 500, 0.3, LZ_EDMD_WALLS_NONE, 3, 20);
	lz_edmd_result r;
	ck_assert_msg(lz_edmd_blocks(e, 10, 20 * 500, &r) == LZ_OK, "%s", lz_error_message());
	ck_assert_msg(r.blocks == 10 && r.events == 10 * 20 * 500, "10 blocks of 10^4 events: "
	              "got %zu blocks, %llu events", r.blocks, (unsigned long long)r.events);
	ck_assert(r.collisions > 0 && r.collisions + r.crossings + r.stale == r.events);
	ck_assert_msg(r.Z_err > 0 && r.Z_err < 0.05, "Z_err = %g", r.Z_err);
	ck_assert_msg(fabs(r.Z - r.Z_gamma) < 4 * (r.Z_err + r.Z_gamma_err), "the virial gives "
	              "Z = %g ± %g but the collision rate Z = %g ± %g: the identity Z = 1 + "
	              "√(π/kT) Γ / 6 is exact in equilibrium", r.Z, r.Z_err, r.Z_gamma,
	              r.Z_gamma_err);
	/* the reference Z, and the collision rate it implies by the identity */
	lz_ref zref = lz_test_reference("hard-spheres.csv", "Z", "3", "eta=0.30");
	double gamma_ref = (zref.value - 1) * 6 / sqrt(M_PI);
	ck_assert_msg(fabs(r.Z - zref.value) < 5 * r.Z_err + 0.03, "Z = %g ± %g at η = 0.3; the "
	              "reference is %g", r.Z, r.Z_err, zref.value);
	ck_assert_msg(fabs(r.gamma - gamma_ref) < 5 * r.gamma_err + 0.1, "Γ = %g, the reference "
	              "%.4g (from Z_ref by the identity)", r.gamma, gamma_ref);
	ck_assert(fabs(r.free_time * r.gamma - 1) < 1e-12);
	ck_assert_msg(fabs(r.T - 1) < 1e-10 && r.energy_rel_drift < 1e-10 &&
	              r.max_overlap < 1e-10 && r.momentum_abs_drift < 1e-9, "guards: T = %.15g, "
	              "drift %g, overlap %g, momentum %g", r.T, r.energy_rel_drift, r.max_overlap,
	              r.momentum_abs_drift);
	ck_assert(r.time > 0 && r.cpu_s >= 0);
	/* just after a reset nothing has been measured */
	lz_edmd_reset_counts(e);
	lz_edmd_sample s = lz_edmd_measure(e);
	ck_assert_msg(s.time == 0 && isnan(s.Z) && isinf(s.free_time) && s.collisions == 0,
	              "no time, no collisions: Z must be NaN and the free time infinite");
	ck_assert_msg(lz_edmd_blocks(e, 1, 100, &r) == LZ_EINVAL, "one block has no error bar");
	lz_edmd_free(e);
}
END_TEST

/* Something to watch: cutting the run at the observations changes nothing (the same
 * Z to the last bit, the same positions); a block of a duration lasts that long. */
static int count_calls(const lz_edmd *e, void *arg)
{
	(void)e;
	++*(int *)arg;
	return LZ_OK;
}

LZ_TEST(edmd_plan_observes_without_changing_the_run)
{
	lz_edmd *a = system_of(2, 400, 0.4, LZ_EDMD_WALLS_NONE, 5, 10);
	lz_edmd *b = system_of(2, 400, 0.4, LZ_EDMD_WALLS_NONE, 5, 10);
	lz_edmd_result ra, rb;
	int calls = 0;
	lz_edmd_plan plan = {3000, INFINITY, 7, count_calls, &calls, 0};
	ck_assert(lz_edmd_blocks(a, 4, 3000, &ra) == LZ_OK);
	ck_assert_msg(lz_edmd_blocks_plan(b, 4, &plan, &rb) == LZ_OK, "%s", lz_error_message());
	ck_assert_msg(calls == 4 * 429, "3000 events in pieces of 7 is 428 observations and one "
	              "at the end, per block: 4 · 429 calls, got %d", calls);
	ck_assert_msg(ra.Z == rb.Z && ra.collisions == rb.collisions, "observing changed the run: "
	              "Z %.17g vs %.17g", ra.Z, rb.Z);
	lz_edmd_sync(a);
	lz_edmd_sync(b);
	for (size_t i = 0; i < a->n; i++)
		ck_assert(memcmp(a->p[i].r, b->p[i].r, sizeof a->p[i].r) == 0);
	/* blocks of 0.25 τ */
	lz_edmd_plan timed = {UINT64_MAX, 0.25, 0, NULL, NULL, 0};
	double t0 = lz_edmd_time(b);
	ck_assert(lz_edmd_blocks_plan(b, 4, &timed, &rb) == LZ_OK);
	ck_assert_msg(fabs(rb.time - 1) < 1e-9 && fabs(lz_edmd_time(b) - t0 - 1) < 1e-9,
	              "4 blocks of 0.25 τ: %g τ measured", rb.time);
	lz_edmd_free(a);
	lz_edmd_free(b);
}
END_TEST

/* The guards report: a particle whose speed changes behind the engine's back (an
 * energy bug) and two particles put on top of each other (a missed collision). */
static int bump_energy(const lz_edmd *e, void *arg)
{
	(void)arg;
	((lz_edmd *)e)->p[0].v[0] *= 1.001;
	return LZ_OK;
}

static int make_overlap(const lz_edmd *ce, void *arg)
{
	(void)arg;
	lz_edmd *e = (lz_edmd *)ce;
	for (size_t c = 0; c < e->ncells; c++) {
		int32_t i = e->list[c].head, j = i >= 0 ? e->next[i] : -1;
		if (j < 0)
			continue;
		lz_edmd_sync(e);
		for (int a = 0; a < 3; a++)
			e->p[j].r[a] = e->p[i].r[a] + (a == 0 ? 0.5 : 0);
		return LZ_OK;
	}
	return LZ_OK;
}

LZ_TEST(edmd_guards_report_energy_and_overlap)
{
	lz_edmd *e = system_of(3, 500, 0.3, LZ_EDMD_WALLS_NONE, 7, 5);
	lz_edmd_result r;
	lz_edmd_plan plan = {2000, INFINITY, 1000, bump_energy, NULL, 0};
	ck_assert_msg(lz_edmd_blocks_plan(e, 3, &plan, &r) == LZ_EPHYS, "an energy drift of "
	              "1e-3 must stop the run");
	ck_assert_msg(strstr(lz_error_message(), "energy"), "%s", lz_error_message());
	lz_edmd_free(e);
	e = system_of(3, 500, 0.45, LZ_EDMD_WALLS_NONE, 7, 5);
	plan.observe = make_overlap;
	ck_assert_msg(lz_edmd_blocks_plan(e, 3, &plan, &r) == LZ_EPHYS, "two particles 0.5 σ "
	              "apart must stop the run");
	ck_assert_msg(strstr(lz_error_message(), "overlap"), "%s", lz_error_message());
	ck_assert_msg(r.max_overlap > 0.1, "max_overlap = %g: %s", r.max_overlap, lz_error_message());
	lz_edmd_free(e);
}
END_TEST

/* The reference equation of state: the tabulated points, an interpolation between
 * them, the closed forms beyond. */
LZ_TEST(edmd_z_reference)
{
	const char *src;
	double z3 = lz_test_reference("hard-spheres.csv", "Z", "3", "eta=0.30").value;
	double z4 = lz_test_reference("hard-spheres.csv", "Z", "3", "eta=0.40").value;
	double z2 = lz_test_reference("hard-disks.csv", "Z", "2", "eta=0.698").value;
	ck_assert(fabs(lz_edmd_z_reference(3, 0.3, &src) - z3) < 1e-12 && !strcmp(src, "table"));
	ck_assert(fabs(lz_edmd_z_reference(2, 0.698, &src) - z2) < 1e-12);
	double z = lz_edmd_z_reference(3, 0.35, &src);
	ck_assert_msg(z > z3 && z < z4 && fabs(z / 5.1888 - 1) < 0.01, "Z(0.35) = %g "
	              "should lie near Carnahan-Starling's 5.189", z);
	ck_assert(fabs(lz_edmd_z_reference(3, 1e-6, NULL) - 1) < 1e-5);
	z = lz_edmd_z_reference(3, 0.6, &src);
	ck_assert(!strcmp(src, "carnahan-starling") && fabs(z - 1.744 / 0.064) < 1e-9);
	z = lz_edmd_z_reference(2, 0.8, &src);
	ck_assert(!strcmp(src, "henderson") && fabs(z - 1.08 / 0.04) < 1e-9);
}
END_TEST

/* ---- g(r) ---- */

/* Brute force: every pair, the nearest image on the periodic axes. */
static void brute_gr(const lz_edmd *e, gsl_histogram *h)
{
	for (size_t i = 0; i < e->n; i++) {
		double ri[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, ri, v);
		for (size_t j = i + 1; j < e->n; j++) {
			double rj[3], d2 = 0;
			lz_edmd_state(e, &e->p[j], e->now, rj, v);
			for (int a = 0; a < e->dim; a++) {
				double d = fabs(rj[a] - ri[a]);
				if (!e->wall[a] && d > e->L / 2)
					d = e->L - d;
				d2 += d * d;
			}
			gsl_histogram_increment(h, sqrt(d2));
		}
	}
}

/* The cell scan counts exactly the pairs a brute-force count finds, in a periodic box
 * (cells within rmax), a box too small for it (every pair, nearest image), 2D, and a
 * box with walls. */
LZ_TEST(edmd_gr_matches_brute_force)
{
	static const struct {
		int dim;
		size_t n;
		double packing, rmax;
		int walls;
	} cases[] = {
		{3, 1500, 0.3, 3, LZ_EDMD_WALLS_NONE},
		{3, 64, 0.3, 2.4, LZ_EDMD_WALLS_NONE},
		{2, 1500, 0.4, 5, LZ_EDMD_WALLS_NONE},
		{3, 1000, 0.2, 4, LZ_EDMD_WALLS_BOX},
		{2, 800, 0.3, 6, LZ_EDMD_WALLS_X},
	};
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
		lz_edmd *e = system_of(cases[c].dim, cases[c].n, cases[c].packing, cases[c].walls, 9, 5);
		gsl_histogram *h = gsl_histogram_alloc(97), *b = gsl_histogram_alloc(97);
		gsl_histogram_set_ranges_uniform(h, 0, cases[c].rmax);
		gsl_histogram_set_ranges_uniform(b, 0, cases[c].rmax);
		ck_assert_msg(lz_edmd_gr_add(e, cases[c].rmax, h) == LZ_OK, "case %zu: %s", c,
		              lz_error_message());
		brute_gr(e, b);
		for (size_t k = 0; k < h->n; k++)
			ck_assert_msg(gsl_histogram_get(h, k) == gsl_histogram_get(b, k), "case %zu "
			              "(%dD, %zu particles, rmax %g): bin %zu has %g pairs, brute force "
			              "%g", c, cases[c].dim, cases[c].n, cases[c].rmax, k,
			              gsl_histogram_get(h, k), gsl_histogram_get(b, k));
		ck_assert(gsl_histogram_sum(h) > 0);
		ck_assert_msg(lz_edmd_gr_add(e, e->L / 2 * 1.01, h) == LZ_EINVAL, "rmax beyond L/2 "
		              "meets pairs at two images and must be refused");
		gsl_histogram_free(h);
		gsl_histogram_free(b);
		lz_edmd_free(e);
	}
}
END_TEST

/* A nearly ideal gas (η = 10^-3): g(r) = 1 beyond contact, within the noise of the
 * pair counts, and 0 inside σ. (N = 1900: the lattice sites do not lie on cell faces.) */
LZ_TEST(edmd_gr_ideal_gas_is_one)
{
	lz_edmd *e = system_of(3, 1900, 1e-3, LZ_EDMD_WALLS_NONE, 11, 5);
	gsl_histogram *h = gsl_histogram_alloc(30);
	gsl_histogram_set_ranges_uniform(h, 0, 30);
	size_t samples = 0;
	for (int k = 0; k < 10; k++, samples++) {
		ck_assert(lz_edmd_run(e, 10 * e->n, INFINITY) == LZ_OK);
		ck_assert(lz_edmd_gr_add(e, 30, h) == LZ_OK);
	}
	ck_assert_msg(lz_edmd_gr_value(e, h, 0, samples) == 0, "no pair is closer than σ");
	for (size_t k = 2; k < h->n; k++) {
		double g = lz_edmd_gr_value(e, h, k, samples);
		double expected = (double)samples * 0.5 * 1900 * 1899 *
		                  (4 * M_PI / 3 * (pow(k + 1.0, 3) - pow(k, 3))) /
		                  pow(e->L, 3);
		double sigma = 1 / sqrt(expected);  /* relative noise of the count */
		ck_assert_msg(fabs(g - 1) < 5 * sigma + 0.01, "ideal gas: g(%g) = %g, expected 1 "
		              "± %.3g", k + 0.5, g, sigma);
	}
	gsl_histogram_free(h);
	lz_edmd_free(e);
}
END_TEST

/* ---- the mean-square displacement ---- */

/* At η = 10^-3 a sphere flies about 70 τ between collisions: over 2 τ the displacement
 * is v t, msd = <v²> t² = 3 kT t² (kT = 1 exactly at the start) — also for the
 * particles that cross the periodic boundary meanwhile, which an unwrapping error
 * would give a displacement of order L. */
LZ_TEST(edmd_msd_ballistic_in_a_dilute_gas)
{
	lz_edmd *e = system_of(3, 1100, 1e-3, LZ_EDMD_WALLS_NONE, 13, 0);
	e->sort_every = 0;
	double v2 = 2 * lz_edmd_energy(e) / (double)e->n;
	lz_edmd_track *tr = lz_edmd_track_alloc(e);
	ck_assert(tr != NULL);
	ck_assert(lz_edmd_track_msd(tr) == 0);
	double t0 = lz_edmd_time(e), t = 2;
	while (lz_edmd_time(e) < t0 + t - 1e-12) {
		ck_assert(lz_edmd_run(e, e->n / 8, t0 + t) == LZ_OK);
		lz_edmd_track_update(tr, e);
	}
	double msd = lz_edmd_track_msd(tr);
	ck_assert_msg(fabs(msd / (v2 * t * t) - 1) < 0.02, "msd = %g after %g τ; a nearly free "
	              "gas flies ballistically, <v²> t² = %g", msd, t, v2 * t * t);
	ck_assert_msg(fabs(v2 - 3) < 1e-9, "kT = 1 in 3D: <v²> = 3, got %g", v2);
	lz_edmd_track_free(tr);
	lz_edmd_free(e);
}
END_TEST

/* ---- the method ---- */

LZ_TEST(edmd_scene_checks)
{
	ck_assert_msg(lz_method_find("edmd") == &lz_method_edmd, "method edmd is not registered");
	ck_assert_msg(bind_edmd("") == LZ_OK, "the defaults: %s", lz_error_message());
	ck_assert_msg(bind_edmd("dim=2;packing=0.85;n=400") == LZ_OK, "%s", lz_error_message());
	assert_refused("dim=3;packing=0.75", "close packing", "0.7405");
	assert_refused("dim=2;packing=0.95", "0.9069", NULL);
	assert_refused("walls=y", "none|x|box", NULL);
	assert_refused("dim=4", "[2, 3]", NULL);
	assert_refused("n=10", "3 cells", "n >= 16");
	assert_refused("gravity=1", "walls", NULL);
	assert_refused("restitution=0", "restitution", "(0, 1]");
	assert_refused("events=10;time=5", "not both", NULL);
	assert_refused("observe=gr,density", "density", "gr, msd");
	assert_refused("gr_range=2", "observe = gr", NULL);
	assert_refused("observe=gr;gr_range=20", "L/2", NULL);
	assert_refused("observe=msd;sort=yes", "sort = no", NULL);
	assert_refused("sample=3", "nothing is sampled", NULL);
	assert_refused("cells=2", "cells", "[3,");
	assert_refused("blocks=1", "blocks", "[2,");
	ck_assert(bind_edmd("observe=gr,msd;sort=no;gr_range=4") == LZ_OK);
	ck_assert(bind_edmd("walls=box;gravity=2;restitution=0.9;n=300") == LZ_OK);
}
END_TEST

/* A config file: overlapping particles, a particle outside the box, rows of the wrong
 * length, no such file, n against its rows — each an error that names the file and
 * the particle or line. A good file sets n. */
LZ_TEST(edmd_config_file_errors)
{
	const char *dir = lzt_tmpdir();
	char scene[1024];
	const char *over = lzt_path(dir, "over.dat"), *out = lzt_path(dir, "out.dat");
	const char *cols = lzt_path(dir, "cols.dat"), *good = lzt_path(dir, "good.dat");
	lzt_write_str(over, "# two spheres 0.6 σ apart\n1 1 1\n5 5 5\n1.6 1 1\n");
	lzt_write_str(out, "1 1 1\n5 5 5\n500 2 2\n");
	lzt_write_str(cols, "1 1 1\n5 5\n");
	lzt_write_str(good, "1 5 5 0.5 0 0\n5 5 5 -0.5 0 0\n");
	snprintf(scene, sizeof scene, "packing=0.001;config=%s", over);
	assert_refused(scene, over, "particles 0 and 2 overlap");
	snprintf(scene, sizeof scene, "packing=0.001;config=%s", out);
	assert_refused(scene, "particle 2", "outside the box");
	snprintf(scene, sizeof scene, "packing=0.001;config=%s", cols);
	assert_refused(scene, cols, "line 2");
	snprintf(scene, sizeof scene, "packing=0.001;config=%s", lzt_path(dir, "none.dat"));
	assert_refused(scene, "none.dat", "cannot be read");
	snprintf(scene, sizeof scene, "packing=0.001;n=3;config=%s", good);
	assert_refused(scene, "2 rows", NULL);
	snprintf(scene, sizeof scene, "packing=0.001;dim=2;config=%s", good);
	assert_refused(scene, "a row in 2D", NULL);
	/* two spheres heading for each other along x collide once */
	snprintf(scene, sizeof scene, "packing=0.001;config=%s;equilibrate=0;time=5;blocks=2;"
	         "seed=1", good);
	const char *rdir;
	lzt_json *j = run_edmd(scene, &rdir);
	ck_assert_msg(lzt_num(j, "n_run") == 2, "the file's two rows set n");
	ck_assert_msg(lzt_num(j, "collisions") == 1, "two spheres 4 σ apart approaching at "
	              "speed 1 meet once within 5 τ; got %g collisions", lzt_num(j, "collisions"));
	free(j);
}
END_TEST

/* A run writes the summary keys (with error bars), meets the reference within its
 * error, and writes config.dat only — no gr.dat, msd.dat or temperature.dat unless
 * asked for. Its config.dat reads back as a config file. */
LZ_TEST(edmd_run_writes_summary_and_only_the_files_asked)
{
	static const char *const keys[] = {
		"Z", "Z_err", "Z_ref", "Z_ref_source", "Z_gamma", "Z_gamma_err", "collision_rate",
		"collision_rate_err", "mean_free_time", "collisions", "cell_crossings",
		"stale_events", "events_run", "events_per_s", "collisions_per_s",
		"energy_rel_drift", "momentum_abs_drift", "max_overlap", "bytes_per_particle",
		"state_bytes_per_particle", "temperature", "cells_per_side", "cells_per_particle",
		"time_run", "wall_bounces", "contact_value", "contact_value_ref",
	};
	const char *dir;
	lzt_json *j = run_edmd("n=500;packing=0.3;events=40;equilibrate=10;seed=4", &dir);
	for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
		ck_assert_msg(lzt_json_get(j, keys[k]) != NULL, "summary.json has no '%s'", keys[k]);
	double Z = lzt_num(j, "Z"), err = lzt_num(j, "Z_err");
	ck_assert_msg(fabs(Z - lzt_num(j, "Z_ref")) < 5 * err + 0.03, "Z = %g ± %g against "
	              "Z_ref %g", Z, err, lzt_num(j, "Z_ref"));
	ck_assert(!strcmp(lzt_json_get(j, "Z_ref_source")->text, "table"));
	ck_assert(lzt_num(j, "events_run") == 40 * 500 && lzt_num(j, "max_overlap") < 1e-10);
	ck_assert(lzt_num(j, "events_per_s") > 0 && lzt_num(j, "state_bytes_per_particle") > 64);
	const char *run = lzt_path(dir, "run");
	ck_assert(lzt_exists(lzt_path(run, "config.dat")));
	static const char *const extra[] = {"gr.dat", "msd.dat", "temperature.dat"};
	for (int k = 0; k < 3; k++)
		ck_assert_msg(!lzt_exists(lzt_path(run, extra[k])), "%s was not asked for", extra[k]);
	free(j);
	char scene[1024];
	snprintf(scene, sizeof scene, "packing=0.3;config=%s;events=10;equilibrate=0;seed=4",
	         lzt_path(run, "config.dat"));
	lzt_json *back = run_edmd(scene, &dir);
	ck_assert_msg(lzt_num(back, "n_run") == 500 && lzt_num(back, "temperature") > 0.99,
	              "config.dat read back: n = %g, kT = %g", lzt_num(back, "n_run"),
	              lzt_num(back, "temperature"));
	free(back);
}
END_TEST

/* observe = gr writes gr.dat (g = 0 inside σ, a contact peak near the reference) and
 * msd.dat; restitution < 1 writes temperature.dat, and the gas cools. */
LZ_TEST(edmd_observations_write_their_files)
{
	const char *dir;
	lzt_json *j = run_edmd("dim=2;n=600;packing=0.4;events=40;equilibrate=10;observe=gr,msd;"
	                       "sort=no;sample=4;gr_range=3;seed=5", &dir);
	const char *run = lzt_path(dir, "run");
	char *gr = lzt_slurp(lzt_path(run, "gr.dat"), NULL), *msd = lzt_slurp(lzt_path(run, "msd.dat"), NULL);
	ck_assert_msg(gr && msd, "observe = gr,msd must write gr.dat and msd.dat");
	/* g(r) is sampled at fixed times, about 4 events per particle apart at the event
	 * rate of the equilibration: 10 samples, give or take the rate's fluctuation */
	double ns = lzt_num(j, "gr_samples");
	ck_assert_msg(ns >= 8 && ns <= 12, "40 events per particle sampled about every 4: "
	              "about 10 samples, got %g", ns);
	double contact = lzt_num(j, "gr_contact"), ref = lzt_num(j, "contact_value_ref");
	ck_assert_msg(fabs(contact / ref - 1) < 0.1, "g(σ) from the histogram %g, from the "
	              "reference EoS %g", contact, ref);
	ck_assert(lzt_num(j, "msd_final") > 0);
	free(gr);
	free(msd);
	free(j);
	j = run_edmd("dim=2;n=600;packing=0.3;events=40;equilibrate=5;restitution=0.8;seed=5",
	             &dir);
	ck_assert(lzt_exists(lzt_path(lzt_path(dir, "run"), "temperature.dat")));
	ck_assert_msg(lzt_num(j, "temperature_final") < 0.5, "restitution 0.8 over 40 events per "
	              "particle must cool the gas: kT = %g", lzt_num(j, "temperature_final"));
	free(j);
}
END_TEST

/* Same scene, same seed: the same summary.json but for the timings (*_s, *_per_s). */
LZ_TEST(edmd_summary_is_deterministic)
{
	static const char *const scenes[] = {
		"n=300;packing=0.35;events=20;equilibrate=5;seed=9",
		"dim=2;n=300;packing=0.3;walls=x;gravity=0.5;restitution=0.95;events=20;seed=9;"
		"observe=gr;sample=5",
	};
	for (int k = 0; k < 2; k++) {
		const char *d1, *d2;
		lzt_json *a = run_edmd(scenes[k], &d1), *b = run_edmd(scenes[k], &d2);
		ck_assert(a->n == b->n);
		for (int i = 0; i < a->n; i++) {
			const char *key = a->m[i].key;
			size_t len = strlen(key);
			if (len > 2 && strcmp(key + len - 2, "_s") == 0)
				continue;
			const lzt_member *m = lzt_json_get(b, key);
			ck_assert_msg(m && m->kind == a->m[i].kind && strcmp(m->text, a->m[i].text) == 0,
			              "%s: '%s' differs between two runs with the same seed (%s vs %s)",
			              scenes[k], key, a->m[i].text, m ? m->text : "missing");
		}
		char *c1 = lzt_slurp(lzt_path(lzt_path(d1, "run"), "config.dat"), NULL);
		char *c2 = lzt_slurp(lzt_path(lzt_path(d2, "run"), "config.dat"), NULL);
		ck_assert_msg(c1 && c2 && strcmp(c1, c2) == 0, "%s: config.dat differs", scenes[k]);
		free(c1);
		free(c2);
		free(a);
		free(b);
	}
}
END_TEST

/* Inelastic collapse ends the run with a message, not a hang: restitution 0.1 in a
 * dense 2D gas. */
LZ_TEST(edmd_collapse_is_an_error)
{
	const char *dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_edmd, NULL, "dim=2;n=400;packing=0.6;restitution=0.1;"
	                     "equilibrate=2;events=5000;seed=2", lzt_path(dir, "run"));
	ck_assert_msg(status == LZ_EPHYS, "restitution 0.1 at η = 0.6 collapses: status %d (%s)",
	              status, lz_error_message());
	ck_assert_msg(strstr(lz_error_message(), "collapse"), "%s", lz_error_message());
	ck_assert_msg(!lzt_exists(lzt_path(dir, "run")), "a failed run left a directory");
}
END_TEST
