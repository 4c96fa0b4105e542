/* test_output.c — data files, summary.json, run directories, rmtree, gnuplot. */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include "lz/output.h"
#include "lz/progress.h"
#include "lz/timer.h"
#include "lztest.h"
#include "support.h"

/* Run the writer on a memory stream and parse what it wrote. */
static char *json_text(void (*write)(lz_json *), size_t *len)
{
	char *buf = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&buf, &n);
	ck_assert(f != NULL);
	lz_json *j = lz_json_begin(f);
	ck_assert(j != NULL);
	write(j);
	ck_assert_msg(lz_json_end(j) == LZ_OK, "lz_json_end reported a write error");
	fclose(f);
	if (len)
		*len = n;
	return buf;
}

static const char nasty[] = "quote\" back\\slash\ttab\nnew\x01one\x1f\x7f del é σ /";

static void write_strings(lz_json *j)
{
	lz_json_str(j, "plain", "hello");
	lz_json_str(j, nasty, nasty);
	lz_json_str(j, "empty", "");
}

LZ_TEST(json_strings_escaped)
{
	char *text = json_text(write_strings, NULL), err[128];
	lzt_json *j = lzt_json_parse(text, err, sizeof err);
	ck_assert_msg(j != NULL, "summary is not valid JSON (%s):\n%s", err, text);
	ck_assert_msg(j->n == 3, "expected 3 members, found %d", j->n);
	const lzt_member *m = lzt_json_get(j, nasty);
	ck_assert_msg(m && m->kind == LZT_STR && strcmp(m->text, nasty) == 0,
	              "a key and value with quotes, backslashes and control characters did not "
	              "survive the round trip:\n%s", text);
	ck_assert_msg(strstr(text, "\\u0001") && strstr(text, "\\u007f"),
	              "control characters should be written as \\uXXXX:\n%s", text);
	ck_assert_msg(strcmp(lzt_json_get(j, "empty")->text, "") == 0, "empty string changed");
	free(j);
	free(text);
}
END_TEST

static void write_special_numbers(lz_json *j)
{
	lz_json_num(j, "nan", NAN);
	lz_json_num(j, "inf", INFINITY);
	lz_json_num(j, "minus_inf", -INFINITY);
	lz_json_err(j, "energy", -1.5, NAN);
	lz_json_int(j, "big", -9223372036854775807LL - 1);
	lz_json_bool(j, "yes", 1);
	lz_json_bool(j, "no", 0);
	lz_json_num(j, "minus_zero", -0.0);
	lz_json_num(j, "tiny", 4.9406564584124654e-324);
}

LZ_TEST(json_non_finite_is_null)
{
	char *text = json_text(write_special_numbers, NULL), err[128];
	lzt_json *j = lzt_json_parse(text, err, sizeof err);
	ck_assert_msg(j != NULL, "summary with NaN/Inf is not valid JSON (%s):\n%s", err, text);
	const char *nulls[] = {"nan", "inf", "minus_inf", "energy_err"};
	for (int i = 0; i < 4; i++)
		ck_assert_msg(lzt_json_get(j, nulls[i]) && lzt_json_get(j, nulls[i])->kind == LZT_NULL,
		              "'%s' should be null (JSON has no NaN or Inf):\n%s", nulls[i], text);
	const lzt_member *e = lzt_json_get(j, "energy"), *big = lzt_json_get(j, "big");
	ck_assert_msg(e && e->kind == LZT_NUM && e->num == -1.5, "lz_json_err lost the value");
	ck_assert_msg(big && strcmp(big->text, "-9223372036854775808") == 0,
	              "lz_json_int wrote %s for LLONG_MIN", big ? big->text : "nothing");
	ck_assert_msg(lzt_json_get(j, "yes")->kind == LZT_TRUE &&
	              lzt_json_get(j, "no")->kind == LZT_FALSE, "booleans wrong:\n%s", text);
	ck_assert_msg(lzt_json_get(j, "tiny")->num == 4.9406564584124654e-324,
	              "the smallest subnormal did not round-trip");
	free(j);
	free(text);
}
END_TEST

static double doubles[200];

static void write_doubles(lz_json *j)
{
	for (int i = 0; i < 200; i++) {
		char key[16];
		snprintf(key, sizeof key, "x%d", i);
		lz_json_num(j, key, doubles[i]);
	}
}

LZ_TEST(json_numbers_round_trip)
{
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, 2024);
	for (int i = 0; i < 200; i++) {
		/* Random bit patterns cover every exponent; skip the non-finite ones. */
		do {
			uint64_t bits = (uint64_t)gsl_rng_get(r) << 32 | gsl_rng_get(r);
			memcpy(&doubles[i], &bits, sizeof bits);
		} while (!isfinite(doubles[i]));
	}
	doubles[0] = 0.1;
	doubles[1] = 1.0 / 3.0;
	doubles[2] = 1e300;
	gsl_rng_free(r);
	char *text = json_text(write_doubles, NULL), err[128];
	lzt_json *j = lzt_json_parse(text, err, sizeof err);
	ck_assert_msg(j != NULL, "numbers are not valid JSON (%s)", err);
	for (int i = 0; i < 200; i++)
		ck_assert_msg(j->m[i].num == doubles[i] || (doubles[i] == 0 && j->m[i].num == 0),
		              "%.17g was written as %s, which reads back as %.17g: %%.17g must "
		              "round-trip exactly", doubles[i], j->m[i].text, j->m[i].num);
	free(j);
	free(text);
}
END_TEST

static void write_nothing(lz_json *j)
{
}

/* A key written twice makes the object invalid JSON: the writer must say so, also
 * when the second one comes from a value's _err companion. */
LZ_TEST(json_duplicate_key_is_an_error)
{
	char *buf = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&buf, &n);
	lz_json *j = lz_json_begin(f);
	lz_json_int(j, "steps", 10);
	lz_json_num(j, "dt", 0.1);
	lz_json_int(j, "steps", 10);
	ck_assert_msg(lz_json_end(j) == LZ_EINVAL, "a summary with 'steps' twice was accepted");
	ck_assert_msg(strstr(lz_error_message(), "'steps'") != NULL,
	              "the error should name the key written twice; it says '%s'",
	              lz_error_message());
	j = lz_json_begin(f);
	lz_json_num(j, "p_err", 1.0);
	lz_json_err(j, "p", 2.0, 0.1);
	ck_assert_msg(lz_json_end(j) == LZ_EINVAL, "'p_err' written by hand and by lz_json_err "
	              "was accepted");
	j = lz_json_begin(f);
	lz_json_err(j, "p", 2.0, 0.1);
	lz_json_num(j, "pressure", 1.0);
	ck_assert_msg(lz_json_end(j) == LZ_OK, "distinct keys were refused: %s",
	              lz_error_message());
	fclose(f);
	free(buf);
}
END_TEST

LZ_TEST(json_empty_object_and_file)
{
	char *text = json_text(write_nothing, NULL), err[128];
	lzt_json *j = lzt_json_parse(text, err, sizeof err);
	ck_assert_msg(j && j->n == 0, "an empty summary should be {}; got '%s'", text);
	free(j);
	free(text);
	const char *dir = lzt_tmpdir();
	const char *path = lzt_path(dir, "s.json");
	lz_json *w = lz_json_open(path);
	ck_assert(w != NULL);
	lz_json_int(w, "steps", 1000);
	ck_assert(lz_json_end(w) == LZ_OK);
	text = lzt_slurp(path, NULL);
	ck_assert_msg(text && (j = lzt_json_parse(text, err, sizeof err)) && j->n == 1,
	              "lz_json_open wrote '%s'", text ? text : "(nothing)");
	free(j);
	free(text);
	ck_assert_msg(lz_json_open("/nonexistent-dir/s.json") == NULL,
	              "opening a JSON file in a missing directory should fail");
	ck_assert(lz_rmtree(dir) == LZ_OK);
}
END_TEST

LZ_TEST(data_file_header_and_rows)
{
	const char *dir = lzt_tmpdir();
	const char *path = lzt_path(dir, "e.dat");
	const char *names[] = {"t", "E", "count"}, *units[] = {"τ", "ε", NULL};
	lz_data *d = lz_data_open(path, "energy against time", 3, names, units);
	ck_assert_msg(d != NULL, "lz_data_open failed: %s", lz_error_message());
	lz_data_row(d, (double[]){0.5, -1.25, 3});
	lz_data_comment(d, "block 2");
	lz_data_row(d, (double[]){NAN, INFINITY, -INFINITY});
	ck_assert(lz_data_close(d) == LZ_OK);
	char *text = lzt_slurp(path, NULL);
	const char *want = "# energy against time\n# t [τ]  E [ε]  count\n0.5 -1.25 3\n"
	                   "# block 2\nnan inf -inf\n";
	ck_assert_msg(text && strcmp(text, want) == 0, "data file is\n%s\nexpected\n%s", text, want);
	free(text);
	ck_assert_msg(lz_data_open(path, "x", 0, names, NULL) == NULL, "ncol = 0 was accepted");
	ck_assert_msg(lz_data_open(path, "x", 65, names, NULL) == NULL, "ncol = 65 was accepted");
	ck_assert_msg(lz_data_open("/nonexistent-dir/x.dat", "x", 1, names, NULL) == NULL,
	              "a data file in a missing directory was 'opened'");
	ck_assert(lz_rmtree(dir) == LZ_OK);
}
END_TEST

/* ---- run directories ---- */

static void make_run(const char *dir, const char *marker)
{
	mkdir(dir, 0777);
	lzt_write_str(lzt_path(dir, "summary.json"), marker);
}

LZ_TEST(rundir_commit_replaces_old_run)
{
	const char *dir = lzt_tmpdir();
	const char *out = lzt_path(dir, "runs/water"), *sub = lzt_path(out, "old.dat");
	mkdir(lzt_path(dir, "runs"), 0777);
	make_run(out, "{\"old\": 1}");
	lzt_write_str(sub, "old data");
	lz_rundir d;
	ck_assert_msg(lz_rundir_begin(&d, out) == LZ_OK, "begin failed: %s", lz_error_message());
	char path[8192];
	ck_assert(lz_rundir_file(&d, "summary.json", path, sizeof path) == LZ_OK);
	ck_assert_msg(strstr(path, ".partial-") != NULL, "files go to %s, not to the tmp dir", path);
	lzt_write_str(path, "{\"new\": 1}");
	ck_assert_msg(lz_rundir_commit(&d) == LZ_OK, "commit failed: %s", lz_error_message());
	const char *summary = lzt_path(out, "summary.json");
	char *text = lzt_slurp(summary, NULL);
	ck_assert_msg(text && strcmp(text, "{\"new\": 1}") == 0, "after commit summary.json is '%s'",
	              text ? text : "(missing)");
	ck_assert_msg(!lzt_exists(sub), "a file of the old run survived the commit");
	const char *runs = lzt_path(dir, "runs");
	ck_assert_msg(lzt_count_matching(runs, ".partial-") == 0 &&
	              lzt_count_matching(runs, ".old-") == 0, "temporary directories left behind");
	lz_rundir_abort(&d);  /* after a commit: nothing to do, must not remove the run */
	ck_assert_msg(lzt_exists(summary), "lz_rundir_abort after commit removed the run");
	ck_assert(lz_rmtree(dir) == LZ_OK);
	free(text);
}
END_TEST

LZ_TEST(rundir_refuses_to_delete_user_directory)
{
	const char *dir = lzt_tmpdir();
	const char *home = lzt_path(dir, "home"), *thesis = lzt_path(home, "thesis.tex");
	mkdir(home, 0777);
	lzt_write_str(thesis, "precious");
	lz_rundir d;
	int rc = lz_rundir_begin(&d, home);
	ck_assert_msg(rc == LZ_EINVAL, "a non-empty directory without summary.json was accepted "
	              "as an output directory (rc %d): `--out ~` would delete a home directory", rc);
	ck_assert_msg(strstr(lz_error_message(), "summary.json") != NULL,
	              "the refusal should say why: '%s'", lz_error_message());
	ck_assert_msg(lzt_exists(thesis), "the user's file was deleted");
	ck_assert_msg(lzt_count_matching(dir, ".partial-") == 0, "a refused begin left a tmp dir");
	/* The directory may also turn into a user's between begin and commit. */
	const char *out = lzt_path(dir, "later");
	ck_assert(lz_rundir_begin(&d, out) == LZ_OK);
	mkdir(out, 0777);
	const char *file = lzt_path(out, "notes.txt");
	lzt_write_str(file, "mine");
	ck_assert_msg(lz_rundir_commit(&d) == LZ_EINVAL, "commit replaced a user's directory");
	ck_assert_msg(lzt_exists(file), "commit deleted a user's file");
	lz_rundir_abort(&d);
	ck_assert_msg(lzt_count_matching(dir, ".partial-") == 0, "abort left the tmp dir");
	const char *bad[] = {"/", "//", ".", "..", "", "x/..", "x/./"};
	for (int i = 0; i < 7; i++)
		ck_assert_msg(lz_rundir_begin(&d, bad[i]) == LZ_EINVAL,
		              "'%s' was accepted as an output directory", bad[i]);
	const char *regular = lzt_path(dir, "file");
	lzt_write_str(regular, "x");
	ck_assert_msg(lz_rundir_begin(&d, regular) == LZ_EINVAL, "a regular file was accepted");
	ck_assert(lz_rmtree(dir) == LZ_OK);
}
END_TEST

LZ_TEST(rundir_abort_leaves_nothing)
{
	const char *dir = lzt_tmpdir();
	const char *out = lzt_path(dir, "a/b/c/");  /* parents are made; the slash is not a level */
	lz_rundir d;
	ck_assert_msg(lz_rundir_begin(&d, out) == LZ_OK, "begin failed: %s", lz_error_message());
	char path[8192];
	ck_assert(lz_rundir_file(&d, "x.dat", path, sizeof path) == LZ_OK);
	lzt_write_str(path, "1 2 3\n");
	const char *parent = lzt_path(dir, "a/b");
	ck_assert_msg(lzt_count_matching(parent, "c.partial-") == 1,
	              "the tmp directory should be a sibling c.partial-PID of the output");
	lz_rundir_abort(&d);
	ck_assert_msg(lzt_count_matching(parent, "c") == 0, "abort left something in %s", parent);
	lz_rundir_abort(&d);  /* twice is harmless */
	char tiny[8];
	ck_assert(lz_rundir_begin(&d, out) == LZ_OK);
	ck_assert_msg(lz_rundir_file(&d, "x.dat", tiny, sizeof tiny) == LZ_EINVAL,
	              "a path that does not fit the buffer was accepted");
	ck_assert(lz_rundir_commit(&d) == LZ_OK);
	ck_assert_msg(lz_rundir_commit(&d) == LZ_EINVAL, "a second commit should be refused");
	ck_assert_msg(lzt_exists(lzt_path(dir, "a/b/c")), "the committed (empty) run is missing");
	ck_assert(lz_rmtree(dir) == LZ_OK);
}
END_TEST

LZ_TEST(rmtree_removes_tree_but_never_follows_links)
{
	const char *dir = lzt_tmpdir();
	const char *tree = lzt_path(dir, "tree"), *outside = lzt_path(dir, "outside");
	mkdir(tree, 0777);
	mkdir(outside, 0777);
	const char *keep = lzt_path(outside, "keep.txt");
	lzt_write_str(keep, "keep me");
	mkdir(lzt_path(tree, "sub"), 0777);
	mkdir(lzt_path(tree, "sub/deeper"), 0777);
	lzt_write_str(lzt_path(tree, "sub/deeper/f"), "x");
	ck_assert(symlink(outside, lzt_path(tree, "sub/link")) == 0);
	ck_assert(symlink("/nonexistent", lzt_path(tree, "dangling")) == 0);
	ck_assert_msg(lz_rmtree(tree) == LZ_OK, "lz_rmtree failed: %s", lz_error_message());
	ck_assert_msg(!lzt_exists(tree), "the tree is still there");
	ck_assert_msg(lzt_exists(keep), "lz_rmtree followed a symbolic link out of the tree");
	ck_assert_msg(lz_rmtree(tree) == LZ_OK, "removing a missing path should be LZ_OK");
	ck_assert(lz_rmtree(dir) == LZ_OK);
}
END_TEST

LZ_TEST(gnuplot_runs_or_is_skipped)
{
	const char *dir = lzt_tmpdir();
	/* Without gnuplot on PATH the plot is skipped quietly. */
	char path[4096];
	snprintf(path, sizeof path, "%s", getenv("PATH") ? getenv("PATH") : "/usr/bin:/bin");
	setenv("PATH", dir, 1);
	ck_assert_msg(lz_gnuplot(dir, "x.gp") == 1, "without gnuplot lz_gnuplot must return 1");
	setenv("PATH", path, 1);
	lzt_write_str(lzt_path(dir, "ok.gp"), "set print 'out.txt'\nprint 1+1\n");
	int rc = lz_gnuplot(dir, "ok.gp");
	if (rc == 1)
		return;  /* gnuplot is not installed here: nothing more to test */
	ck_assert_msg(rc == LZ_OK, "gnuplot failed on a good script: %s", lz_error_message());
	char *out = lzt_slurp(lzt_path(dir, "out.txt"), NULL);
	ck_assert_msg(out && strcmp(out, "2\n") == 0, "the script did not run in dir: out.txt is '%s'",
	              out ? out : "(missing)");
	free(out);
	lzt_write_str(lzt_path(dir, "bad.gp"), "plot sin(x\n");
	ck_assert_msg(lz_gnuplot(dir, "bad.gp") == LZ_EIO, "a broken script should give LZ_EIO");
	ck_assert_msg(strstr(lz_error_message(), "bad.gp") && !strchr(lz_error_message(), '\n'),
	              "the message should name the script, on one line: '%s'", lz_error_message());
	ck_assert(lz_rmtree(dir) == LZ_OK);
}
END_TEST

/* ---- progress and timers ---- */

LZ_TEST(timers_advance)
{
	/* A busy loop until 0.02 s of CPU time are used (or 5 s pass on a crowded machine):
	 * one thread's CPU time can never run ahead of the wall clock. */
	double w0 = lz_wall_now(), c0 = lz_cpu_now(), w1, c1;
	do {
		w1 = lz_wall_now();
		c1 = lz_cpu_now();
	} while (c1 - c0 < 0.02 && w1 - w0 < 5);
	ck_assert_msg(c1 - c0 >= 0.02, "the CPU clock advanced by only %g s in %g s of busy loop",
	              c1 - c0, w1 - w0);
	ck_assert_msg(w1 - w0 >= c1 - c0 - 1e-3, "the wall clock advanced by %g s, less than the "
	              "CPU time %g s", w1 - w0, c1 - c0);
}
END_TEST

/* Spin for `seconds`, updating p as often as a hot loop would. */
static void spin_progress(lz_progress *p, double seconds)
{
	double t0 = lz_wall_now();
	for (double done = 0; lz_wall_now() - t0 < seconds; done++)
		lz_progress_update(p, done);
}

LZ_TEST(progress_only_on_a_terminal)
{
	/* Not a terminal (a file): nothing at all. */
	FILE *f = tmpfile();
	ck_assert(f != NULL);
	int keep = dup(STDERR_FILENO);
	dup2(fileno(f), STDERR_FILENO);
	lz_progress p;
	lz_progress_begin(&p, "quiet", 1e9);
	spin_progress(&p, 0.3);
	lz_progress_end(&p);
	fflush(stderr);
	ck_assert_msg(ftell(f) == 0 && lseek(STDERR_FILENO, 0, SEEK_END) == 0,
	              "progress printed to a file; it should only print on a terminal");
	/* A pseudo-terminal: a '\r' line with the label and a percentage, <= 5 per second. */
	int master = posix_openpt(O_RDWR | O_NOCTTY);
	ck_assert_msg(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0,
	              "no pseudo-terminal available");
	int slave = open(ptsname(master), O_RDWR | O_NOCTTY);
	ck_assert(slave >= 0);
	dup2(slave, STDERR_FILENO);
	lz_progress_begin(&p, "verlet", 1e12);
	spin_progress(&p, 0.7);
	lz_progress_end(&p);
	fflush(stderr);
	dup2(keep, STDERR_FILENO);
	char buf[4096] = "";
	fcntl(master, F_SETFL, O_NONBLOCK);
	ssize_t n = read(master, buf, sizeof buf - 1);
	buf[n > 0 ? n : 0] = '\0';
	int lines = 0;
	for (const char *s = buf; (s = strstr(s, "verlet ")); s++)
		lines++;
	ck_assert_msg(lines >= 2 && lines <= 4, "in 0.7 s the progress line was printed %d times; "
	              "expected about 3 (every 0.2 s):\n%s", lines, buf);
	ck_assert_msg(strstr(buf, "\r") && strstr(buf, "%") && strstr(buf, "ETA"),
	              "the progress line should be '\\r' label percent elapsed ETA: '%s'", buf);
	close(slave);
	close(master);
	fclose(f);
}
END_TEST
