/* test_cli.c — the lz command, called in-process: a good scene runs and writes its
 * summary; every kind of bad input exits 2 with one line on stderr and leaves no
 * directory behind; the same seed gives the same summary. */
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "method.h"
#include "lz/output.h"
#include "scene.h"
#include "lztest.h"
#include "support.h"

#define HARMONIC "method = verlet\npotential = harmonic\nintegrator = velocity-verlet\n" \
                 "dt = 0.01\nsteps = 1000\nseed = 7\n"

static const char *dir;  /* this test's temporary directory */

/* Remove the temporary directory; the next scene() makes a new one. */
static void cleanup(void)
{
	ck_assert_msg(lz_rmtree(dir) == LZ_OK, "cannot remove %s: %s", dir, lz_error_message());
	dir = NULL;
}

static const char *scene(const char *name, const char *text)
{
	if (!dir)
		dir = lzt_tmpdir();
	const char *path = lzt_path(dir, name);
	lzt_write_str(path, text);
	return path;
}

LZ_TEST(cli_runs_harmonic_scene)
{
	const char *path = scene("harmonic.scene", HARMONIC), *out = lzt_path(dir, "out");
	int rc = lzt_cli("run", path, "--out", out, "--quiet", NULL);
	ck_assert_msg(rc == 0, "lz run on a good harmonic scene exited %d: %s", rc, lzt_err);
	lzt_json *j = lzt_summary(out);
	const lzt_member *m = lzt_json_get(j, "method");
	ck_assert_msg(m && m->kind == LZT_STR && strcmp(m->text, "verlet") == 0,
	              "summary.json should start with method = verlet");
	ck_assert_msg(strcmp(j->m[0].key, "method") == 0, "'method' is not the first key");
	ck_assert_msg(lzt_num(j, "seed") == 7, "the seed written is %g, not the seed given (7)",
	              lzt_num(j, "seed"));
	double err = lzt_num(j, "energy_rel_err_max"), wall = lzt_num(j, "wall_s");
	ck_assert_msg(err >= 0 && err < 1e-3, "energy_rel_err_max = %g for velocity Verlet at "
	              "dt = 0.01 on the harmonic oscillator", err);
	ck_assert_msg(wall >= 0 && lzt_num(j, "steps_per_s") > 0, "wall_s or steps_per_s not > 0");
	ck_assert_msg(lzt_count_matching(dir, ".partial-") == 0, "a .partial directory is left");
	ck_assert_msg(lzt_err[0] == '\0', "--quiet, yet stderr has '%s'", lzt_err);
	free(j);
	cleanup();
}
END_TEST

LZ_TEST(cli_same_seed_same_summary)
{
	const char *path = scene("h.scene", HARMONIC);
	const char *a = lzt_path(dir, "a"), *b = lzt_path(dir, "b");
	ck_assert(lzt_cli("run", path, "--out", a, "--quiet", "steps=2000", NULL) == 0);
	ck_assert(lzt_cli("run", path, "--out", b, "--quiet", "steps=2000", NULL) == 0);
	lzt_json *ja = lzt_summary(a), *jb = lzt_summary(b);
	ck_assert_msg(ja->n == jb->n, "the two runs wrote %d and %d keys", ja->n, jb->n);
	for (int i = 0; i < ja->n; i++) {
		const char *key = ja->m[i].key;
		size_t n = strlen(key);
		ck_assert_msg(strcmp(key, jb->m[i].key) == 0, "key %d: '%s' vs '%s'", i, key,
		              jb->m[i].key);
		if (strcmp(key, "wall_s") == 0 || (n > 6 && strcmp(key + n - 6, "_per_s") == 0))
			continue;  /* timings */
		ck_assert_msg(ja->m[i].kind == jb->m[i].kind && strcmp(ja->m[i].text, jb->m[i].text) == 0,
		              "'%s' differs between two runs with seed 7: %s vs %s — a run must "
		              "be reproducible bit for bit", key, ja->m[i].text, jb->m[i].text);
	}
	ck_assert_msg(lzt_num(ja, "steps") == 2000, "the override steps=2000 was not applied");
	free(ja);
	free(jb);
	cleanup();
}
END_TEST

LZ_TEST(cli_replaces_previous_run_and_logs_auto_seed)
{
	const char *path = scene("h.scene", "method = verlet\npotential = harmonic\n"
	                         "integrator = velocity-verlet\ndt = 0.01\nsteps = 100\n");
	const char *out = lzt_path(dir, "runs/h");
	ck_assert(lzt_cli("run", path, "--out", out, NULL) == 0);
	ck_assert_msg(lzt_cli("run", path, "--out", out, NULL) == 0,
	              "a second run into the same directory failed: %s", lzt_err);
	lzt_json *j = lzt_summary(out);
	char want[128];
	snprintf(want, sizeof want, "lz: seed = %.0f (auto); pass seed=%.0f to repeat this run\n",
	         lzt_num(j, "seed"), lzt_num(j, "seed"));
	ck_assert_msg(strstr(lzt_err, want) != NULL, "stderr should log the seed used:\n"
	              "  %s\ngot\n  %s", want, lzt_err);
	ck_assert_msg(lzt_count_matching(lzt_path(dir, "runs"), "h.") == 0,
	              "a temporary directory was left next to the run");
	free(j);
	cleanup();
}
END_TEST

LZ_TEST(cli_default_output_directory)
{
	const char *path = scene("spring.scene", HARMONIC);
	ck_assert(chdir(dir) == 0);
	int rc = lzt_cli("run", path, "--quiet", NULL);
	ck_assert_msg(rc == 0, "exit %d: %s", rc, lzt_err);
	ck_assert_msg(lzt_exists(lzt_path(dir, "build/runs/spring/summary.json")),
	              "without --out the run should go to build/runs/<scene name>/");
	ck_assert(chdir("/") == 0);
	cleanup();
}
END_TEST

LZ_TEST(cli_scene_by_name)
{
	scene("spring.scene", HARMONIC);
	setenv("LZ_SCENES", dir, 1);
	ck_assert_msg(strcmp(lz_scene_dir(), dir) == 0, "lz_scene_dir() ignores $LZ_SCENES");
	int rc = lzt_cli("run", "spring", "--out", lzt_path(dir, "o"), "--quiet", NULL);
	ck_assert_msg(rc == 0, "a scene named without its path was not found in $LZ_SCENES: %s",
	              lzt_err);
	cleanup();
}
END_TEST

/* A refused run: exit 2, one line "lz: ..." on stderr (containing `expect`), and
 * nothing written. */
static void refused(const char *expect, const char *path, const char *extra)
{
	const char *out = lzt_path(dir, "out");
	lz_set_error_handler(NULL);  /* the CLI must not print a message twice */
	int rc = extra ? lzt_cli("run", path, "--out", out, extra, NULL)
	               : lzt_cli("run", path, "--out", out, NULL);
	ck_assert_msg(rc == 2, "bad input (%s) should exit 2, exited %d: %s", expect, rc, lzt_err);
	ck_assert_msg(strncmp(lzt_err, "lz: ", 4) == 0 && strstr(lzt_err, expect),
	              "stderr should be 'lz: ...%s...', got '%s'", expect, lzt_err);
	const char *nl = strchr(lzt_err, '\n');
	ck_assert_msg(nl && !strstr(lzt_err + 1, "lz: ") && (!nl[1] || strstr(nl, "usage: ")),
	              "the message should be printed once, on one line (then the usage, for "
	              "a usage error): '%s'", lzt_err);
	ck_assert_msg(!lzt_exists(out), "a refused run created its output directory");
	ck_assert_msg(lzt_count_matching(dir, ".partial-") == 0, "a refused run left a .partial");
	cleanup();
}

LZ_TEST(cli_refuses_garbage_file)
{
	char junk[256];
	for (int i = 0; i < 256; i++)
		junk[i] = (char)(i * 37 + 11);
	scene("junk.scene", "");
	lzt_write(lzt_path(dir, "junk.scene"), junk, sizeof junk);
	refused("not a text line", lzt_path(dir, "junk.scene"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_truncated_file)
{
	refused("must be one of", scene("t.scene", "method = verlet\npotential = harm"), NULL);
	refused("expected 'key = value'", scene("t.scene", "method = verlet\npoten"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_nan_value)
{
	refused(":4: key 'dt' = nan must be a finite number",
	        scene("n.scene", "method = verlet\npotential = harmonic\nsteps = 10\ndt = nan\n"),
	        NULL);
}
END_TEST

LZ_TEST(cli_refuses_duplicate_key)
{
	refused(":3: key 'potential' given twice (first at line 2)",
	        scene("d.scene", "method = verlet\npotential = harmonic\npotential = lj\n"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_unknown_key)
{
	refused("unknown key 'stepz' for method verlet (did you mean 'steps'?)",
	        scene("u.scene", HARMONIC "stepz = 10\n"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_out_of_range_value)
{
	refused("key 'dt' = -0.1 is out of range (0,", scene("r.scene", HARMONIC), "dt=-0.1");
}
END_TEST

LZ_TEST(cli_refuses_unknown_method)
{
	refused(":1: unknown method 'warp'; the methods are: verlet",
	        scene("m.scene", "method = warp\ndt = 0.1\n"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_scene_without_method)
{
	refused("no 'method' key", scene("m.scene", "dt = 0.1\n"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_missing_scene)
{
	scene("x.scene", HARMONIC);
	refused("no scene", "no-such-scene", NULL);
	scene("x.scene", HARMONIC);
	refused("No such file", lzt_path(dir, "missing/x.scene"), NULL);
}
END_TEST

LZ_TEST(cli_refuses_bad_option_and_usage)
{
	refused("unknown option '--frobnicate'", scene("h.scene", HARMONIC), "--frobnicate");
	refused("command line: no key before '='", scene("h.scene", HARMONIC), "=5");
	refused("unexpected argument 'steps'", scene("h.scene", HARMONIC), "steps");
	const char *calls[][3] = {{NULL}, {"run", NULL}, {"fly", NULL}, {"list", "x", NULL},
	                          {"help", "a", "b"}};
	for (int i = 0; i < 5; i++) {
		int rc = lzt_cli(calls[i][0], calls[i][1], calls[i][2], NULL);
		ck_assert_msg(rc == 2 && strstr(lzt_err, "usage: lz run SCENE"),
		              "call %d: a usage error should exit 2 and print the usage (exit %d, "
		              "stderr '%s')", i, rc, lzt_err);
	}
	int rc = lzt_cli("run", scene("h.scene", HARMONIC), "--out", NULL);
	ck_assert_msg(rc == 2 && strstr(lzt_err, "--out needs a directory"),
	              "--out without a directory: exit %d, '%s'", rc, lzt_err);
}
END_TEST

LZ_TEST(cli_refuses_user_directory_as_out)
{
	const char *path = scene("h.scene", HARMONIC), *mine = lzt_path(dir, "mine");
	const char *file = lzt_path(mine, "thesis.tex");
	ck_assert(mkdir(mine, 0777) == 0);
	lzt_write_str(file, "precious");
	int rc = lzt_cli("run", path, "--out", mine, "--quiet", NULL);
	ck_assert_msg(rc == 2, "--out at a user's non-empty directory should exit 2, got %d", rc);
	ck_assert_msg(lzt_exists(file), "lz deleted a file in the user's directory");
	ck_assert_msg(lzt_count_matching(dir, ".partial-") == 0, "a .partial directory is left");
	cleanup();
}
END_TEST

LZ_TEST(cli_list_and_help)
{
	scene("spring.scene", "# A mass on a spring\n" HARMONIC);
	scene("broken.scene", "method = verlet\nthis is not a scene\n");
	scene("notes.txt", "not a scene");
	setenv("LZ_SCENES", dir, 1);
	ck_assert_msg(lzt_cli("list", NULL) == 0, "lz list failed: %s", lzt_err);
	ck_assert_msg(strstr(lzt_out, "spring") && strstr(lzt_out, "verlet") &&
	              strstr(lzt_out, "A mass on a spring"),
	              "lz list should show name, method and description:\n%s", lzt_out);
	ck_assert_msg(strstr(lzt_out, "broken") && strstr(lzt_out, "broken:"),
	              "a broken scene should be listed as broken:\n%s", lzt_out);
	ck_assert_msg(!strstr(lzt_out, "notes"), "lz list showed a file that is not a .scene");
	ck_assert_msg(lzt_cli("help", NULL) == 0 && strstr(lzt_out, "verlet"),
	              "lz help should list the methods:\n%s", lzt_out);
	ck_assert_msg(lzt_cli("help", "verlet", NULL) == 0, "lz help verlet failed: %s", lzt_err);
	ck_assert_msg(strstr(lzt_out, "| dt ") && strstr(lzt_out, "| potential "),
	              "lz help verlet should list the keys:\n%s", lzt_out);
	ck_assert_msg(lzt_cli("help", "warp", NULL) == 2 && strstr(lzt_err, "unknown method 'warp'"),
	              "lz help of an unknown method should exit 2: '%s'", lzt_err);
	setenv("LZ_SCENES", lzt_path(dir, "none"), 1);
	ck_assert_msg(lzt_cli("list", NULL) != 0, "lz list of a missing directory should fail");
	cleanup();
}
END_TEST

/* Every ready-made scene must bind against its method: a key renamed in a method's
 * table would otherwise break `make lesson` and the demo, not a test. */
LZ_TEST(shipped_scenes_all_bind)
{
	glob_t g;
	ck_assert_msg(glob("datasets/scenes/*.scene", 0, NULL, &g) == 0 && g.gl_pathc > 0,
	              "no scenes found in datasets/scenes (run the tests from the tree root)");
	for (size_t i = 0; i < g.gl_pathc; i++) {
		lz_scene *s = lz_scene_read(g.gl_pathv[i]);
		ck_assert_msg(s != NULL, "%s", lz_error_message());
		const lz_method *m = lz_method_find(lz_scene_method(s));
		ck_assert_msg(m != NULL, "%s names no known method", g.gl_pathv[i]);
		ck_assert_msg(lz_method_bind(m, s) == LZ_OK, "%s", lz_error_message());
		lz_scene_free(s);
	}
	globfree(&g);
}
END_TEST

/* datasets/scenes/README.md documents every key of every method (its tables are
 * `lz help METHOD`); a key missing there is a key nobody can find. */
LZ_TEST(scenes_readme_lists_every_key)
{
	char *text = lzt_slurp("datasets/scenes/README.md", NULL);
	ck_assert_msg(text != NULL, "datasets/scenes/README.md is missing");
	size_t n;
	const lz_method *const *all = lz_methods(&n);
	for (size_t i = 0; i < n; i++) {
		char row[128];
		snprintf(row, sizeof row, "### %s", all[i]->name);
		ck_assert_msg(strstr(text, row) != NULL, "datasets/scenes/README.md has no "
		              "section '%s'", row);
		for (size_t k = 0; k < all[i]->keys.n; k++) {
			snprintf(row, sizeof row, "\n| %s ", all[i]->keys.key[k].name);
			ck_assert_msg(strstr(text, row) != NULL, "datasets/scenes/README.md does not "
			              "list key '%s' of method %s: paste `lz help %s` into it",
			              all[i]->keys.key[k].name, all[i]->name, all[i]->name);
		}
	}
	free(text);
}
END_TEST
