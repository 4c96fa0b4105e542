/* test_cli_run.c — what `lz run` does besides running: the table of results after a
 * run (rounded error bars, references, speed, seed) and --quiet; the command line over
 * the scene (an override of one stop key unsets the other, key= unsets); the config
 * file found next to the scene from any directory; an interrupted run and an --out
 * that cannot be made leave nothing behind; the warning for a crystal compared with a
 * fluid's equation of state; `lz help` in 100 columns, pasted into the scenes README. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "method.h"
#include "run_table.h"
#include "lztest.h"
#include "support.h"

#define HARMONIC "method = verlet\npotential = harmonic\nintegrator = velocity-verlet\n" \
                 "dt = 0.01\nsteps = 1000\nseed = 7\n"
/* A small fluid of hard spheres, a fraction of a second to run. */
#define SPHERES "method = edmd\nn = 200\npacking = 0.3\nequilibrate = 5\nevents = 20\n" \
                "seed = 5\n"

/* dir/name with the text, for a scene or a config file. */
static const char *put(const char *dir, const char *name, const char *text)
{
	const char *path = lzt_path(dir, name);
	lzt_write_str(path, text);
	return path;
}

/* The line of text whose first word is `word`, into line; 0 when there is none. */
static int row(const char *text, const char *word, char *line, size_t size)
{
	size_t n = strlen(word);
	for (const char *p = text; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL) {
		const char *q = p + strspn(p, " ");
		if (strncmp(q, word, n) == 0 && q[n] == ' ') {
			snprintf(line, size, "%.*s", (int)strcspn(q, "\n"), q);
			return 1;
		}
	}
	return 0;
}

static void cleanup(const char *dir)
{
	ck_assert_msg(lz_rmtree(dir) == LZ_OK, "cannot remove %s: %s", dir, lz_error_message());
}

LZ_TEST(cli_format_err_rounds_to_two_digits)
{
	static const struct {
		double v, err;
		const char *want;
	} cases[] = {
		{4.09987, 0.003612, "4.0999 ± 0.0036"}, {12.3456, 0.98, "12.35 ± 0.98"},
		{12.3456, 0.996, "12.3 ± 1.0"},          {123456, 340, "123460 ± 340"},
		{-0.00321, 0.00045, "-0.00321 ± 0.00045"}, {1.2345e-5, 3.4e-8, "(1.2345 ± 0.0034)e-5"},
		{2.5e7, 1.26e5, "(2.500 ± 0.013)e7"},    {1.0000000000000151, 8.5e-16, "1 ± 8.5e-16"},
		{2.5, 0, "2.5"},                         {NAN, 1, "null"},
	};
	char buf[64];
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		lz_format_err(cases[i].v, cases[i].err, buf, sizeof buf);
		ck_assert_msg(strcmp(buf, cases[i].want) == 0, "%.17g ± %.17g printed as '%s', not "
		              "'%s' (the error to 2 significant digits, the value to the same place)",
		              cases[i].v, cases[i].err, buf, cases[i].want);
	}
}
END_TEST

LZ_TEST(cli_run_prints_the_folder_and_a_table)
{
	const char *dir = lzt_tmpdir(), *out = lzt_path(dir, "out");
	const char *path = put(dir, "harmonic.scene", HARMONIC);
	char want[1200], line[512];
	ck_assert_msg(lzt_cli("run", path, "--out", out, NULL) == 0, "lz run failed: %s", lzt_err);
	snprintf(want, sizeof want, "lz: results in %s/\n", out);
	ck_assert_msg(strstr(lzt_err, want), "stderr should end with the folder line '%s': '%s'",
	              want, lzt_err);
	ck_assert_msg(strncmp(lzt_out, "harmonic (verlet)\n", 18) == 0 && row(lzt_out, "quantity",
	              line, sizeof line), "stdout should be the table, under 'harmonic (verlet)' "
	              "and a header row:\n%s", lzt_out);
	ck_assert_msg(row(lzt_out, "energy_rel_err_max", line, sizeof line),
	              "the table has no row for energy_rel_err_max:\n%s", lzt_out);
	ck_assert_msg(row(lzt_out, "speed", line, sizeof line) && strstr(line, " steps/s"),
	              "the speed row should give steps_per_s in steps/s:\n%s", lzt_out);
	ck_assert_msg(row(lzt_out, "seed", line, sizeof line) && strcmp(line + strlen(line) - 2,
	              " 7") == 0, "the seed row should say 7:\n%s", lzt_out);
	ck_assert_msg(lzt_cli("run", path, "--out", out, "--quiet", NULL) == 0, "%s", lzt_err);
	ck_assert_msg(!lzt_out[0] && !lzt_err[0], "--quiet prints nothing, yet stdout '%s', "
	              "stderr '%s'", lzt_out, lzt_err);
	cleanup(dir);
}
END_TEST

/* The decimals of a number as printed ("3.986" has 3). */
static int decimals(const char *x)
{
	const char *dot = strchr(x, '.');
	return dot ? (int)strspn(dot + 1, "0123456789") : 0;
}

LZ_TEST(cli_table_rounds_the_observables_of_the_summary)
{
	const char *dir = lzt_tmpdir(), *out = lzt_path(dir, "out");
	ck_assert_msg(lzt_cli("run", put(dir, "spheres.scene", SPHERES), "--out", out, NULL) == 0,
	              "%s", lzt_err);
	lzt_json *j = lzt_summary(out);
	char line[512], v[64], err[64], ref[64], source[64];
	ck_assert_msg(row(lzt_out, "Z", line, sizeof line) &&
	              sscanf(line, "Z %63s ± %63s %63s (%63[^)])", v, err, ref, source) == 4,
	              "the Z row should read 'Z value ± error reference (source)':\n%s", lzt_out);
	int dec = decimals(err), digits = 0;
	for (const char *c = err + strspn(err, "0."); *c; c++)
		digits += *c >= '0' && *c <= '9';
	ck_assert_msg(digits == 2 && decimals(v) == dec && decimals(ref) == dec,
	              "'%s': the error should have 2 significant digits, the value and the "
	              "reference as many decimals", line);
	double unit = pow(10, -dec);
	ck_assert_msg(fabs(atof(v) - lzt_num(j, "Z")) <= unit / 2 + 1e-12 &&
	              fabs(atof(err) - lzt_num(j, "Z_err")) <= unit / 2 + 1e-12 &&
	              fabs(atof(ref) - lzt_num(j, "Z_ref")) <= unit / 2 + 1e-12,
	              "'%s' is not Z = %.17g ± %.17g, Z_ref = %.17g rounded", line,
	              lzt_num(j, "Z"), lzt_num(j, "Z_err"), lzt_num(j, "Z_ref"));
	ck_assert_msg(strcmp(source, lzt_json_get(j, "Z_ref_source")->text) == 0,
	              "the reference's source is '%s', the summary says '%s'", source,
	              lzt_json_get(j, "Z_ref_source")->text);
	ck_assert_msg(row(lzt_out, "speed", line, sizeof line) && strstr(line, "events/s"),
	              "no speed in events/s:\n%s", lzt_out);
	ck_assert_msg(row(lzt_out, "seed", line, sizeof line) && strstr(line, " 5"),
	              "no seed row with 5:\n%s", lzt_out);
	free(j);
	cleanup(dir);
}
END_TEST

/* The kind of a summary member: a null is a key the run had no value for. */
static int is_null(const lzt_json *j, const char *key)
{
	const lzt_member *m = lzt_json_get(j, key);
	return m && m->kind == LZT_NULL;
}

LZ_TEST(cli_command_line_wins_over_the_scene)
{
	const char *dir = lzt_tmpdir(), *out = lzt_path(dir, "out");
	const char *spheres = put(dir, "s.scene", SPHERES "blocks = 5\n");
	ck_assert_msg(lzt_cli("run", spheres, "time=0.2", "--out", out, "--quiet", NULL) == 0,
	              "time=0.2 on a scene that gives events should run for the time: %s",
	              lzt_err);
	lzt_json *j = lzt_summary(out);
	ck_assert_msg(lzt_num(j, "time") == 0.2 && is_null(j, "events") && lzt_num(j, "blocks") == 5,
	              "time=0.2 should unset the scene's events and keep its blocks");
	free(j);
	ck_assert_msg(lzt_cli("run", spheres, "blocks=", "--out", out, "--quiet", NULL) == 0, "%s",
	              lzt_err);
	j = lzt_summary(out);
	ck_assert_msg(lzt_num(j, "blocks") == 20 && lzt_num(j, "events") == 20,
	              "blocks= should unset the scene's blocks = 5 (default 20), got %g",
	              lzt_num(j, "blocks"));
	free(j);
	const char *verlet = put(dir, "h.scene", HARMONIC);
	ck_assert_msg(lzt_cli("run", verlet, "time=2", "--out", out, "--quiet", NULL) == 0, "%s",
	              lzt_err);
	j = lzt_summary(out);
	ck_assert_msg(is_null(j, "steps") && lzt_num(j, "steps_run") == 200,
	              "time=2 at dt = 0.01 on a scene with steps = 1000 should run 200 steps, ran %g",
	              lzt_num(j, "steps_run"));
	free(j);
	static const char *const bad[][2] = {
		{"steps=10", "time=1"}, {"dt=", NULL}, {"stepz=", NULL},
	};
	static const char *const why[] = {"give steps or time, not both", "missing key 'dt'",
	                                  "unknown key 'stepz'"};
	for (int k = 0; k < 3; k++) {
		int rc = lzt_cli("run", verlet, bad[k][0], "--out", out, bad[k][1], NULL);
		ck_assert_msg(rc == 2 && strstr(lzt_err, why[k]), "%s %s should be refused with "
		              "'%s', exit 2: exit %d, '%s'", bad[k][0], bad[k][1] ? bad[k][1] : "",
		              why[k], rc, lzt_err);
	}
	cleanup(dir);
}
END_TEST

LZ_TEST(cli_config_is_read_next_to_the_scene)
{
	const char *dir = lzt_tmpdir();
	char sub[1024], scene[1100];
	snprintf(sub, sizeof sub, "%s", lzt_path(dir, "scenes"));
	ck_assert(mkdir(sub, 0777) == 0);
	/* four disks at packing 0.05: a box of side 7.93 */
	put(sub, "four.dat", "# x y\n1 1\n1 5\n5 1\n5 5\n");
	snprintf(scene, sizeof scene, "%s", put(sub, "four.scene", "method = edmd\ndim = 2\n"
	         "packing = 0.05\nconfig = four.dat\nequilibrate = 0\nevents = 2\nseed = 1\n"));
	const char *out = lzt_path(dir, "out");
	ck_assert(chdir("/") == 0);
	int rc = lzt_cli("run", scene, "--out", out, "--quiet", NULL);
	ck_assert_msg(rc == 0, "config = four.dat in %s, run from /, was not found next to the "
	              "scene: %s", scene, lzt_err);
	lzt_json *j = lzt_summary(out);
	ck_assert_msg(strcmp(lzt_json_get(j, "config")->text, lzt_path(sub, "four.dat")) == 0 &&
	              lzt_num(j, "n_run") == 4, "the summary should name the file read, %s, and "
	              "its 4 disks: '%s'", lzt_path(sub, "four.dat"), lzt_json_get(j, "config")->text);
	free(j);
	ck_assert_msg(lzt_cli("run", scene, "config=four.dat", "--out", out, "--quiet", NULL) == 2 &&
	              strstr(lzt_err, "four.dat"), "config=four.dat on the command line, run from "
	              "/, names /four.dat, which does not exist: '%s'", lzt_err);
	ck_assert(chdir(sub) == 0);
	ck_assert_msg(lzt_cli("run", scene, "config=four.dat", "--out", out, "--quiet", NULL) == 0,
	              "config=four.dat on the command line is read from the current directory: "
	              "%s", lzt_err);
	ck_assert(chdir("/") == 0);
	cleanup(dir);
}
END_TEST

/* Start `lz run SCENE --out OUT --quiet` in a child, send it sig once its partial
 * directory exists; its wait status. */
static int interrupted_run(const char *scene, const char *out, int sig)
{
	pid_t pid = fork();
	ck_assert(pid >= 0);
	if (pid == 0) {
		char *argv[] = {"lz", "run", (char *)scene, "--out", (char *)out, "--quiet", NULL};
		_exit(lz_cli_main(6, argv));
	}
	char partial[1100];
	snprintf(partial, sizeof partial, "%s.partial-%ld", out, (long)pid);
	for (int k = 0; k < 1000 && !lzt_exists(partial); k++)
		nanosleep(&(struct timespec){0, 10000000}, NULL);
	ck_assert_msg(lzt_exists(partial), "the run never made %s", partial);
	nanosleep(&(struct timespec){0, 200000000}, NULL);  /* well into the run */
	kill(pid, sig);
	int status;
	ck_assert(waitpid(pid, &status, 0) == pid);
	return status;
}

LZ_TEST(cli_interrupted_run_leaves_nothing_behind)
{
	const char *dir = lzt_tmpdir(), *out = lzt_path(dir, "run");
	const char *endless = put(dir, "endless.scene", "method = edmd\nn = 500\nevents = 1e9\n"
	                          "equilibrate = 0\nseed = 3\n");
	int status = interrupted_run(endless, out, SIGINT);
	ck_assert_msg(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT, "an interrupted run "
	              "should end by its SIGINT (status %d)", status);
	ck_assert_msg(!lzt_exists(out) && lzt_count_matching(dir, "run.") == 0,
	              "an interrupted run left %s or a partial directory", out);
	/* a finished run in its place stays as it was */
	ck_assert(lzt_cli("run", put(dir, "s.scene", SPHERES), "--out", out, "--quiet", NULL) == 0);
	char *before = lzt_slurp(lzt_path(out, "summary.json"), NULL);
	status = interrupted_run(endless, out, SIGTERM);
	char *after = lzt_slurp(lzt_path(out, "summary.json"), NULL);
	ck_assert_msg(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM, "status %d", status);
	ck_assert_msg(before && after && strcmp(before, after) == 0 &&
	              lzt_count_matching(dir, "run.") == 0, "a run interrupted by SIGTERM "
	              "changed the finished run in its place, or left a partial directory");
	free(before);
	free(after);
	cleanup(dir);
}
END_TEST

LZ_TEST(cli_out_that_cannot_be_made_is_bad_input)
{
	const char *dir = lzt_tmpdir();
	const char *file = put(dir, "file", "a regular file\n"), *scene = put(dir, "h.scene", HARMONIC);
	char out[1100];
	snprintf(out, sizeof out, "%s/sub", file);  /* fails for root too */
	int rc = lzt_cli("run", scene, "--out", out, NULL);
	ck_assert_msg(rc == 2 && strncmp(lzt_err, "lz: cannot make the run directory", 33) == 0 &&
	              strstr(lzt_err, "Not a directory") && strstr(lzt_err, "--out"),
	              "--out under a regular file should exit 2 saying why: exit %d, '%s'", rc,
	              lzt_err);
	ck_assert_msg(!lzt_out[0] && lzt_count_matching(dir, "partial") == 0,
	              "a refused --out printed a table or left a partial directory");
	cleanup(dir);
}
END_TEST

LZ_TEST(cli_warns_of_a_crystal_against_a_fluid_reference)
{
	const char *dir = lzt_tmpdir(), *out = lzt_path(dir, "out");
	const char *scene = put(dir, "c.scene", "method = edmd\nevents = 1\nequilibrate = 1\n"
	                        "seed = 2\n");
	/* full lattices, the only ones that fit at these packings: 4·5³ and 20² sites */
	static const char *const cases[][5] = {
		{"dim=3", "n=500", "packing=0.7", "0.4916", "carnahan-starling"},
		{"dim=2", "n=400", "packing=0.75", "0.700", "henderson"},
	};
	for (int k = 0; k < 2; k++) {
		ck_assert_msg(lzt_cli("run", scene, cases[k][0], cases[k][1], cases[k][2], "--out",
		              out, NULL) == 0, "%s", lzt_err);
		char packing[64];
		snprintf(packing, sizeof packing, "warning: packing = %s ", cases[k][2] + 8);
		ck_assert_msg(strstr(lzt_err, packing) && strstr(lzt_err, cases[k][3]) &&
		              strstr(lzt_err, cases[k][4]), "%s %s: the warning should name the "
		              "packing, the fluid's limit %s and the reference (%s): '%.900s'",
		              cases[k][0], cases[k][2], cases[k][3], cases[k][4], lzt_err);
	}
	ck_assert(lzt_cli("run", scene, "n=500", "packing=0.3", "--out", out, NULL) == 0);
	ck_assert_msg(!strstr(lzt_err, "warning"), "a fluid at 0.3 was warned about: %.900s",
	              lzt_err);
	cleanup(dir);
}
END_TEST

/* lz help edmd says what lz_edmd_auto_cells does: 3 cells per particle in 3D. */
LZ_TEST(cli_edmd_help_states_the_automatic_cells)
{
	const char *dir = lzt_tmpdir(), *out = lzt_path(dir, "out");
	const lz_key *cells = NULL;
	for (size_t k = 0; k < lz_method_edmd.keys.n; k++)
		if (strcmp(lz_method_edmd.keys.key[k].name, "cells") == 0)
			cells = &lz_method_edmd.keys.key[k];
	ck_assert_msg(cells && strstr(cells->help, "1.5 cells per particle in 2D, 3 in 3D"),
	              "lz help edmd should say 1.5 cells per particle in 2D, 3 in 3D: '%s'",
	              cells ? cells->help : "(no key cells)");
	const char *scene = put(dir, "d.scene", "method = edmd\nn = 4000\npacking = 0.1\n"
	                        "equilibrate = 0\nevents = 0.1\nseed = 1\nwrite_config = no\n");
	ck_assert(lzt_cli("run", scene, "--out", out, "--quiet", NULL) == 0);
	lzt_json *j = lzt_summary(out);
	double c = lzt_num(j, "cells_per_particle");
	ck_assert_msg(c >= 3 && c < 3.3, "4000 dilute spheres got %g cells per particle, not "
	              "about 3 as the help says", c);
	free(j);
	cleanup(dir);
}
END_TEST

/* The longest line of text, in characters (UTF-8). */
static int longest_line(const char *text, char *line, size_t size)
{
	int most = 0;
	for (const char *p = text; *p;) {
		size_t n = strcspn(p, "\n");
		int w = 0;
		for (size_t i = 0; i < n; i++)
			w += ((unsigned char)p[i] & 0xc0) != 0x80;
		if (w > most)
			snprintf(line, size, "%.*s", (int)n, p), most = w;
		p += n + (p[n] == '\n');
	}
	return most;
}

LZ_TEST(cli_help_fits_100_columns)
{
	size_t n;
	const lz_method *const *m = lz_methods(&n);
	char line[1024];
	for (size_t i = 0; i <= n; i++) {
		const char *name = i < n ? m[i]->name : NULL;
		ck_assert(lzt_cli("help", name, NULL) == 0);
		int w = longest_line(lzt_out, line, sizeof line);
		ck_assert_msg(w <= 100, "lz help %s has a line of %d characters (at most 100):\n%s",
		              name ? name : "", w, line);
	}
}
END_TEST

/* datasets/scenes/README.md holds every key table of `lz help METHOD` as it prints it. */
LZ_TEST(scenes_readme_has_every_help_table)
{
	char *text = lzt_slurp("datasets/scenes/README.md", NULL);
	ck_assert_msg(text != NULL, "datasets/scenes/README.md is missing (run the tests from "
	              "the tree root)");
	size_t n;
	const lz_method *const *m = lz_methods(&n);
	for (size_t i = 0; i < n; i++) {
		ck_assert(lzt_cli("help", m[i]->name, NULL) == 0);
		const char *table = strstr(lzt_out, "\n|");
		ck_assert_msg(table && strstr(text, table + 1), "datasets/scenes/README.md does not "
		              "hold the key table of `lz help %s` as it is now: paste it in",
		              m[i]->name);
	}
	free(text);
}
END_TEST
