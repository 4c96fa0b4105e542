/* test_method_field.c — the `field` method (lib/app/method_field.c): its scene checks,
 * and runs through it — adsorption to exact jamming and to a target, one and two
 * particles, 3D, moves that keep the hard core, the error of a target that jams
 * first, and the square well (an energy that a brute-force pair count reproduces,
 * colder is lower). The scene checks call no graded function; the runs need working
 * shape.c, field.c and well.c (with the stubs they fail at "not implemented"). Each
 * run is small: well under a second with -O2. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "method.h"
#include "lz/walk.h"
#include "lztest.h"
#include "support.h"

static int bind_field(const char *assignments)
{
	return lzt_bind(&lz_method_field, assignments);
}

/* Run a field scene built from the assignments; the summary (fails if the run does). */
static lzt_json *run_field(const char *assignments, const char **dir)
{
	*dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_field, NULL, assignments, lzt_path(*dir, "run"));
	ck_assert_msg(status == LZ_OK, "method field with %s failed: %s", assignments,
	              lz_error_message());
	return lzt_summary(lzt_path(*dir, "run"));
}

/* The centres of config.dat (2D: x y R, 3D: x y z R), dim doubles each, into a new
 * array; *n gets their number. */
static double *read_config(const char *dir, int dim, size_t *n)
{
	char *text = lzt_slurp(lzt_path(lzt_path(dir, "run"), "config.dat"), NULL);
	ck_assert_msg(text != NULL, "the run wrote no config.dat");
	size_t cap = 1024;
	double *r = malloc(cap * (size_t)dim * sizeof *r);
	*n = 0;
	for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
		if (line[0] == '#')
			continue;
		double v[4];
		int got = sscanf(line, "%lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3]);
		ck_assert_msg(got == dim + 1, "config.dat row '%s' should have %d columns", line,
		              dim + 1);
		if (*n == cap)
			r = realloc(r, (cap *= 2) * (size_t)dim * sizeof *r);
		for (int k = 0; k < dim; k++)
			r[*n * (size_t)dim + (size_t)k] = v[k];
		(*n)++;
	}
	free(text);
	return r;
}

/* The minimum-image squared distance of two centres of a cubic (square) box of side L. */
static double min_d2(const double *a, const double *b, int dim, double L)
{
	double d2 = 0;
	for (int k = 0; k < dim; k++) {
		double d = fabs(a[k] - b[k]);
		d = fmin(d, L - d);
		d2 += d * d;
	}
	return d2;
}

/* Pairs (brute force, all pairs) with lo <= d² < hi. */
static size_t count_pairs(const double *r, size_t n, int dim, double L, double lo, double hi)
{
	size_t pairs = 0;
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++) {
			double d2 = min_d2(r + i * (size_t)dim, r + j * (size_t)dim, dim, L);
			pairs += d2 >= lo && d2 < hi;
		}
	return pairs;
}

/* No two centres of config.dat closer than σ = 2R (touching allowed). */
static void assert_no_overlap(const char *dir, int dim, double L, double R, size_t placed)
{
	size_t n;
	double *r = read_config(dir, dim, &n);
	ck_assert_msg(n == placed, "config.dat holds %zu particles, the summary says %zu", n,
	              placed);
	size_t bad = count_pairs(r, n, dim, L, 0, 4 * R * R);
	free(r);
	ck_assert_msg(bad == 0, "%zu pairs of centres closer than σ = 2R = %g: the field let "
	              "particles overlap", bad, 2 * R);
}

static int summary_true(const lzt_json *j, const char *key)
{
	const lzt_member *m = lzt_json_get(j, key);
	ck_assert_msg(m && (m->kind == LZT_TRUE || m->kind == LZT_FALSE),
	              "summary.json has no boolean '%s'", key);
	return m->kind == LZT_TRUE;
}

LZ_TEST(field_scene_checks)
{
	ck_assert_msg(lz_method_find("field") == &lz_method_field, "method field is not "
	              "registered");
	ck_assert_msg(bind_field("fill=jam") == LZ_OK, "a jamming scene: %s", lz_error_message());
	ck_assert_msg(bind_field("n=10;motion=walk;steps=10;well_range=1.5;temperature=0.5") ==
	              LZ_OK, "a well scene: %s", lz_error_message());
	ck_assert_msg(bind_field("lattice=cubic;size=32;radius=2;coverage=0.2") == LZ_OK,
	              "3D: %s", lz_error_message());
	ck_assert(bind_field("size=100;n=10") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "100"), "%s", lz_error_message());
	ck_assert(bind_field("radius=-1;n=1") == LZ_EINVAL);
	ck_assert(bind_field("size=64;radius=16.5;n=1") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "too large") && strstr(lz_error_message(),
	              "R <= 16"), "a radius too large for the box: %s", lz_error_message());
	/* Close packing: the 2D bound is the key's range, the 3D one the check's. */
	ck_assert(bind_field("coverage=0.95") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "0.9069"), "%s", lz_error_message());
	ck_assert(bind_field("lattice=cubic;size=32;radius=2;coverage=0.8") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "close packing"), "%s", lz_error_message());
	ck_assert(bind_field("size=64;radius=2;n=300") == LZ_EINVAL);
	ck_assert(bind_field("coverage=1e-9") == LZ_EINVAL);
	ck_assert(bind_field("radius=3") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "exactly one"), "%s", lz_error_message());
	ck_assert(bind_field("n=10;fill=jam") == LZ_EINVAL);
	ck_assert(bind_field("n=10;coverage=0.2") == LZ_EINVAL);
	/* The well: λ = 0 or (1, 3], T > 0, and its keys only with it. */
	ck_assert(bind_field("n=10;well_range=0.9") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "(1, 3]"), "%s", lz_error_message());
	ck_assert(bind_field("n=10;well_range=4") == LZ_EINVAL);
	ck_assert(bind_field("n=10;well_range=1.5;temperature=0") == LZ_EINVAL);
	ck_assert(bind_field("n=10;well_range=1.5;well_depth=-1") == LZ_EINVAL);
	ck_assert(bind_field("n=10;temperature=0.5") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "well_range"), "%s", lz_error_message());
	ck_assert(bind_field("size=64;radius=8;n=1;well_range=3") == LZ_EINVAL);
	ck_assert(bind_field("n=10;steps=100") == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "motion"), "%s", lz_error_message());
	ck_assert(bind_field("n=10;motion=levy") == LZ_EINVAL);
	ck_assert(bind_field("fill=full") == LZ_EINVAL);
}
END_TEST

/* Random sequential adsorption to exact jamming: no free site left (counted, not
 * guessed), no overlap, and a coverage near the RSA limit. Disks of R = 2 on a 64²
 * lattice jam at θ = 0.53-0.54 (the continuum 0.547, slightly less where the coarse
 * lattice misses the smallest gaps); spheres of R = 2 in 32³ near 0.36 (0.384). */
LZ_TEST(field_jam_leaves_no_free_site)
{
	static const struct { const char *scene; int dim; double lo, hi; } cases[] = {
		{"fill=jam;size=64;radius=2;seed=3", 2, 0.50, 0.56},
		{"fill=jam;size=64;radius=2;seed=4;lattice=square8", 2, 0.50, 0.56},
		{"fill=jam;size=64;radius=2.5;seed=5;lattice=triangular", 2, 0.48, 0.57},
		{"fill=jam;size=32;radius=2;seed=6;lattice=cubic", 3, 0.32, 0.40},
	};
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		const char *dir;
		lzt_json *j = run_field(cases[k].scene, &dir);
		double theta = lzt_num(j, "placed_coverage");
		ck_assert_msg(summary_true(j, "jammed") && lzt_num(j, "free_sites") == 0,
		              "%s: jammed must be true with free_sites = 0 (it is %g)",
		              cases[k].scene, lzt_num(j, "free_sites"));
		ck_assert_msg(theta > cases[k].lo && theta < cases[k].hi, "%s: jammed at θ = %g, "
		              "expected in (%g, %g) near the RSA limit", cases[k].scene, theta,
		              cases[k].lo, cases[k].hi);
		ck_assert(lzt_num(j, "insert_attempts") >= lzt_num(j, "placed"));
		if (strstr(cases[k].scene, "triangular") == NULL)
			assert_no_overlap(dir, cases[k].dim, cases[k].dim == 2 ? 64 : 32,
			                  strstr(cases[k].scene, "radius=2.5") ? 2.5 : 2,
			                  (size_t)lzt_num(j, "placed"));
		free(j);
	}
}
END_TEST

/* A coverage target gives n = round(θ L² / πR²) particles, and the box is not jammed. */
LZ_TEST(field_coverage_target_is_met)
{
	const char *dir;
	lzt_json *j = run_field("coverage=0.3;size=128;radius=3;seed=9", &dir);
	long n = lround(0.3 / lz_walk_packing(LZ_LATTICE_SQUARE, 128, 3, 1));
	ck_assert_msg(lzt_num(j, "placed") == n, "placed %g particles for coverage 0.3, "
	              "expected round(0.3·128²/(π·9)) = %ld", lzt_num(j, "placed"), n);
	ck_assert(fabs(lzt_num(j, "placed_coverage") - 0.3) < lz_walk_packing(
	          LZ_LATTICE_SQUARE, 128, 3, 1));
	ck_assert(!summary_true(j, "jammed") && lzt_num(j, "free_sites") > 0);
	free(j);
	j = run_field("n=200;size=128;radius=3;seed=9", &dir);
	ck_assert(lzt_num(j, "placed") == 200);
	free(j);
}
END_TEST

/* A target between the RSA limit and close packing: an error that says where the box
 * jammed and what to do, and no run directory. */
LZ_TEST(field_target_beyond_jamming_is_an_error)
{
	const char *dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_field, NULL, "coverage=0.62;size=64;radius=2;seed=1",
	                     lzt_path(dir, "run"));
	ck_assert_msg(status == LZ_EINVAL, "coverage 0.62 cannot be reached by adsorption; "
	              "the run returned %d", status);
	const char *msg = lz_error_message();
	ck_assert_msg(strstr(msg, "jammed") && strstr(msg, "fill = jam") && strstr(msg, "θ ="),
	              "the message should say where it jammed and suggest fill = jam: %s", msg);
	ck_assert_msg(!lzt_exists(lzt_path(dir, "run")), "a failed run left a directory");
	status = lzt_run(&lz_method_field, NULL, "n=500;size=32;radius=2;lattice=cubic",
	                 lzt_path(dir, "run"));
	ck_assert_msg(status == LZ_EINVAL && strstr(lz_error_message(), "0.384"),
	              "3D: %s", lz_error_message());
}
END_TEST

/* One particle moves freely (every trial accepted); two never overlap. */
LZ_TEST(field_one_and_two_particles)
{
	const char *dir;
	lzt_json *j = run_field("n=1;size=16;radius=1;motion=walk;steps=500;seed=2", &dir);
	ck_assert(lzt_num(j, "placed") == 1);
	ck_assert_msg(lzt_num(j, "acceptance") == 1, "a lone particle must accept every move, "
	              "acceptance = %g", lzt_num(j, "acceptance"));
	ck_assert(lzt_num(j, "steps_run") == 500 && lzt_num(j, "atomsteps_per_s") > 0);
	free(j);
	j = run_field("n=2;size=8;radius=2;motion=walk;steps=2000;seed=2", &dir);
	ck_assert(lzt_num(j, "placed") == 2);
	double acc = lzt_num(j, "acceptance");
	ck_assert_msg(acc > 0 && acc < 1, "two disks of σ = 4 in an 8² box must collide "
	              "sometimes: acceptance = %g", acc);
	assert_no_overlap(dir, 2, 8, 2, 2);
	free(j);
}
END_TEST

/* Walk and ballistic moves at a dense coverage keep the hard core (brute force over
 * config.dat), in 2D and 3D. */
LZ_TEST(field_moves_keep_the_hard_core)
{
	static const struct { const char *scene; int dim; double L; } cases[] = {
		{"coverage=0.45;size=64;radius=2;motion=walk;steps=300;seed=4", 2, 64},
		{"coverage=0.45;size=64;radius=2;motion=ballistic;steps=300;seed=4;"
		 "lattice=square8", 2, 64},
		{"coverage=0.3;size=32;radius=2;motion=ballistic;steps=100;seed=4;"
		 "lattice=cubic26", 3, 32},
	};
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		const char *dir;
		lzt_json *j = run_field(cases[k].scene, &dir);
		double acc = lzt_num(j, "acceptance");
		ck_assert_msg(acc > 0.05 && acc < 0.95, "%s: acceptance %g", cases[k].scene, acc);
		assert_no_overlap(dir, cases[k].dim, cases[k].L, 2, (size_t)lzt_num(j, "placed"));
		free(j);
	}
}
END_TEST

/* The square well: E/N from the well field equals -(pairs with σ <= d < λσ)/N counted
 * over config.dat, and the cold fluid (kT = 0.4 ε, clustering) sits far below the
 * hot one (kT = 2 ε): at coverage 0.2 and λ = 1.5, E/N ≈ -2.5 against -0.8. */
LZ_TEST(field_well_energy_cold_below_hot)
{
	static const char *const base = "coverage=0.2;size=128;radius=2;motion=walk;"
	                                "well_range=1.5;equilibrate=1000;steps=1000;sample=10;"
	                                "seed=8;temperature=";
	double e[2];
	for (int k = 0; k < 2; k++) {
		char scene[256];
		snprintf(scene, sizeof scene, "%s%s", base, k == 0 ? "0.4" : "2");
		const char *dir;
		lzt_json *j = run_field(scene, &dir);
		e[k] = lzt_num(j, "energy_per_particle");
		size_t n;
		double *r = read_config(dir, 2, &n);
		/* σ = 4, λσ = 6: partners at 16 <= d² < 36. */
		double pairs = (double)count_pairs(r, n, 2, 128, 16, 36);
		free(r);
		ck_assert_msg(fabs(e[k] + pairs / (double)n) < 1e-12, "kT = %s: E/N = %g, but "
		              "config.dat has %g pairs within the well, -pairs/N = %g", k ? "2" : "0.4",
		              e[k], pairs, -pairs / (double)n);
		ck_assert(lzt_json_get(j, "energy_per_particle_mean_err") != NULL);
		ck_assert(lzt_num(j, "energy_samples") == 100);
		ck_assert(lzt_num(j, "well_bytes") == lzt_num(j, "field_bytes"));
		free(j);
	}
	ck_assert_msg(e[0] < e[1] - 0.5, "E/N = %g at kT = 0.4 should lie well below %g at "
	              "kT = 2: a cold square-well fluid clusters", e[0], e[1]);
}
END_TEST
