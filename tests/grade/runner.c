/* runner.c — the main() of every test suite: rubric in, Check in fork mode, results out.
 *
 * The tests of a suite register themselves (LZ_TEST, lztest.h). The runner reads the
 * rubric, refuses to run when rubric and suite disagree, gives every test its own
 * Check test case (so each has its own timeout and a crash costs that test only),
 * runs them, and reports — for a student as a readable table, for the grader as
 * tab-separated lines (the protocol is documented in lztest.h).
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "lztest.h"

#define MAX_TESTS 512

typedef struct {
	char name[128];
	int points;
	char visibility[32];
	double timeout;
	const TTest *test;  /* the registered test of that name */
} rubric_line;

static struct {
	const char *name;
	const TTest *test;
} registry[MAX_TESTS];
static int nregistered;

static rubric_line rubric[MAX_TESTS];
static int nrubric;

void lz_test_register(const char *name, const TTest *test)
{
	if (nregistered == MAX_TESTS) {
		fprintf(stderr, "runner: more than %d tests in one suite\n", MAX_TESTS);
		exit(2);
	}
	registry[nregistered].name = name;
	registry[nregistered].test = test;
	nregistered++;
}

double lz_test_reldiff(double a, double b)
{
	double scale = fabs(b) > 1e-300 ? fabs(b) : 1e-300;
	return fabs(a - b) / scale;
}

/* ---- handlers that turn library events into test failures ---- */

static void gsl_to_failure(const char *reason, const char *file, int line, int gsl_errno)
{
	ck_abort_msg("GSL error %d (%s) at %s:%d: %s", gsl_errno, gsl_strerror(gsl_errno),
	             file, line, reason);
}

static void todo_to_failure(const char *function, const char *file)
{
	ck_abort_msg("not implemented: %s (%s)", function, file);
}

/* ---- the rubric ---- */

static int known_visibility(const char *v)
{
	static const char *const ok[] = {"visible", "hidden", "after_due_date", "after_published"};
	for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++)
		if (strcmp(v, ok[i]) == 0)
			return 1;
	return 0;
}

static int parse_rubric_line(const char *path, int lineno, char *text)
{
	char *hash = strchr(text, '#');
	if (hash)
		*hash = '\0';
	char name[128], vis[32], extra[2];
	int points;
	double timeout;
	int got = sscanf(text, "%127s %d %31s %lf %1s", name, &points, vis, &timeout, extra);
	if (got <= 0)
		return 0;  /* blank or comment */
	if (got != 4 || points < 0 || !known_visibility(vis) || !(timeout > 0 && timeout <= 3600)) {
		fprintf(stderr, "%s:%d: a rubric line is `test points visibility timeout_s` with "
		        "points >= 0, visibility visible|hidden|after_due_date|after_published and "
		        "timeout in (0, 3600]\n", path, lineno);
		return -1;
	}
	for (int i = 0; i < nrubric; i++)
		if (strcmp(rubric[i].name, name) == 0) {
			fprintf(stderr, "%s:%d: test '%s' is listed twice\n", path, lineno, name);
			return -1;
		}
	if (nrubric == MAX_TESTS) {
		fprintf(stderr, "%s:%d: more than %d rubric lines\n", path, lineno, MAX_TESTS);
		return -1;
	}
	rubric_line *r = &rubric[nrubric++];
	snprintf(r->name, sizeof r->name, "%s", name);
	snprintf(r->visibility, sizeof r->visibility, "%s", vis);
	r->points = points;
	r->timeout = timeout;
	return 0;
}

static int read_rubric(const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		fprintf(stderr, "runner: cannot read rubric %s: %s\n", path, strerror(errno));
		return -1;
	}
	char line[1024];
	int lineno = 0, status = 0;
	while (status == 0 && fgets(line, sizeof line, f))
		status = parse_rubric_line(path, ++lineno, line);
	fclose(f);
	return status;
}

/* Every rubric line names a registered test and every registered test has a line. */
static int match_rubric(void)
{
	int bad = 0;
	for (int i = 0; i < nrubric; i++) {
		for (int j = 0; j < nregistered && !rubric[i].test; j++)
			if (strcmp(rubric[i].name, registry[j].name) == 0)
				rubric[i].test = registry[j].test;
		if (!rubric[i].test) {
			fprintf(stderr, "runner: rubric lists '%s' but no LZ_TEST defines it\n",
			        rubric[i].name);
			bad = 1;
		}
	}
	for (int j = 0; j < nregistered; j++) {
		int listed = 0;
		for (int i = 0; i < nrubric && !listed; i++)
			listed = strcmp(rubric[i].name, registry[j].name) == 0;
		if (!listed) {
			fprintf(stderr, "runner: test '%s' is not in the rubric (it would never count)\n",
			        registry[j].name);
			bad = 1;
		}
	}
	return bad ? -1 : 0;
}

/* ---- results ---- */

static const rubric_line *find_line(const char *name)
{
	for (int i = 0; i < nrubric; i++)
		if (strcmp(rubric[i].name, name) == 0)
			return &rubric[i];
	return NULL;
}

static const char *status_word(TestResult *tr)
{
	if (tr_rtype(tr) == CK_PASS)
		return "pass";
	if (tr_rtype(tr) == CK_FAILURE)
		return "fail";
	return strstr(tr_msg(tr), "timeout") ? "timeout" : "error";
}

/* Check's wording for crashes, with what it usually means in student code. */
static void explain(const char *msg, char *out, size_t size)
{
	if (strstr(msg, "signal 11"))
		snprintf(out, size, "crashed with a segmentation fault (a bad pointer, or an index "
		         "outside an array) [%s]", msg);
	else if (strstr(msg, "signal 8"))
		snprintf(out, size, "crashed with an arithmetic exception (integer division by "
		         "zero?) [%s]", msg);
	else if (strstr(msg, "signal 25"))
		snprintf(out, size, "stopped for writing far too much output (printing in a loop?) "
		         "[%s]", msg);
	else if (strstr(msg, "signal 24"))
		snprintf(out, size, "stopped for using too much CPU time [%s]", msg);
	else if (strstr(msg, "signal 6"))
		snprintf(out, size, "aborted (an assert, a failed allocation, or LZ_TODO) [%s]", msg);
	else if (strstr(msg, "timeout"))
		snprintf(out, size, "did not finish within its time limit (an endless loop, or far "
		         "too slow) [%s]", msg);
	else
		snprintf(out, size, "%s", msg);
}

/* One line: tabs and newlines would break the grader's protocol. */
static void flatten(char *s)
{
	for (; *s; s++)
		if (*s == '\t' || *s == '\n' || *s == '\r')
			*s = ' ';
}

static void print_student(TestResult **res, int nrun, int *earned, int *npass)
{
	for (int i = 0; i < nrun; i++) {
		const rubric_line *r = find_line(tr_tcname(res[i]));
		int pts = r ? r->points : 0;
		int pass = tr_rtype(res[i]) == CK_PASS;
		*earned += pass ? pts : 0;
		*npass += pass;
		printf("  %s  %3d/%-3d  %s\n", pass ? "PASS" : "FAIL", pass ? pts : 0, pts,
		       tr_tcname(res[i]));
		if (!pass) {
			char msg[4096];
			explain(tr_msg(res[i]), msg, sizeof msg);
			printf("               %s\n", msg);
		}
	}
}

static void print_machine(FILE *out, TestResult **res, int nrun)
{
	fprintf(out, "LZBEGIN\n");
	for (int i = 0; i < nrun; i++) {
		char msg[4096];
		explain(tr_msg(res[i]), msg, sizeof msg);
		flatten(msg);
		fprintf(out, "LZRESULT\t%s\t%s\t%s\n", tr_tcname(res[i]), status_word(res[i]),
		        tr_rtype(res[i]) == CK_PASS ? "" : msg);
	}
	fprintf(out, "LZEND\tran\t%d\n", nrun);
	fflush(out);
}

/* ---- main ---- */

static void usage(void)
{
	fprintf(stderr, "usage: SUITE --rubric FILE [--rubric FILE ...] [--only TEST] "
	        "[--machine [--log FILE]]\n");
	exit(2);
}

/* In machine mode the tests' own output goes to the log and the results to the
 * original stdout, so nothing a test prints can pass for a result line. */
static FILE *divert_output(const char *log)
{
	int keep = dup(STDOUT_FILENO);
	int fd = open(log ? log : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0644);
	if (keep < 0 || fd < 0) {
		fprintf(stderr, "runner: cannot open the log %s: %s\n", log ? log : "/dev/null",
		        strerror(errno));
		exit(2);
	}
	fflush(stdout);
	dup2(fd, STDOUT_FILENO);
	dup2(fd, STDERR_FILENO);
	close(fd);
	return fdopen(keep, "w");
}

static Suite *make_suite(const char *only)
{
	Suite *s = suite_create("lozenge");
	for (int i = 0; i < nrubric; i++) {
		if (only && strcmp(only, rubric[i].name) != 0)
			continue;
		TCase *tc = tcase_create(rubric[i].name);
		tcase_set_timeout(tc, rubric[i].timeout);
		tcase_add_test(tc, rubric[i].test);
		suite_add_tcase(s, tc);
	}
	return s;
}

int main(int argc, char **argv)
{
	const char *only = NULL, *log = NULL;
	int machine = 0, nrubrics = 0;
	for (int i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--rubric") == 0 && i + 1 < argc) {
			if (read_rubric(argv[++i]) != 0)
				return 2;
			nrubrics++;
		} else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
			only = argv[++i];
		} else if (strcmp(argv[i], "--log") == 0 && i + 1 < argc) {
			log = argv[++i];
		} else if (strcmp(argv[i], "--machine") == 0) {
			machine = 1;
		} else {
			usage();
		}
	}
	if (nrubrics == 0)
		usage();
	if (match_rubric() != 0)
		return 2;
	if (only && !find_line(only)) {
		fprintf(stderr, "runner: no test named '%s' in the rubric\n", only);
		return 2;
	}

	gsl_set_error_handler(gsl_to_failure);
	lz_set_todo_handler(todo_to_failure);
	lz_set_error_handler(lz_error_quiet);

	FILE *results = machine ? divert_output(log) : stdout;
	SRunner *sr = srunner_create(make_suite(only));
	srunner_run_all(sr, CK_SILENT);
	int nrun = srunner_ntests_run(sr);
	TestResult **res = srunner_results(sr);
	int expected = only ? 1 : nrubric;

	int earned = 0, total = 0, npass = 0;
	if (machine) {
		print_machine(results, res, nrun);
		for (int i = 0; i < nrun; i++)
			npass += tr_rtype(res[i]) == CK_PASS;
	} else {
		print_student(res, nrun, &earned, &npass);
		for (int i = 0; i < nrubric; i++)
			total += !only || strcmp(only, rubric[i].name) == 0 ? rubric[i].points : 0;
		if (nrun < expected)
			printf("  %d of the %d tests in the rubric did not run: that counts as failing\n",
			       expected - nrun, expected);
		printf("Score: %d/%d\n%d passed, %d failed\n", earned, total, npass,
		       expected - npass);
	}
	free(res);
	srunner_free(sr);
	return npass == expected && nrun == expected ? 0 : 1;
}
