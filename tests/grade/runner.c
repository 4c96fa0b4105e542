/* runner.c — the main() of every test suite: rubric in, Check in fork mode, results out.
 *
 * The tests of a suite register themselves (LZ_TEST, lztest.h). The runner reads the
 * rubric, refuses to run when rubric and suite disagree, and runs every test in a
 * process of its own that runs Check for that one test (Check forks again, so the
 * test's code runs in a grandchild with the rubric's timeout). Nothing a test does —
 * crash, loop, flood its output, break Check's own reporting, hit a resource limit —
 * can stop the other tests: the runner reports what happened to that one and goes on.
 * Results go out as a readable table (student view) or as tab-separated lines (the
 * grader's view; the protocol is documented in lztest.h).
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>

#include "lztest.h"

#define MAX_TESTS 512
#define MSG_MAX 4096
#define LOG_KEEP (1L << 20)  /* bytes: a log longer than this is cut before a test */
#define LIMIT_EXIT 125       /* a test process that hit the file limit exits with this */
#define UNGRADED_TIMEOUT 120 /* seconds for each test of a suite without a rubric */

typedef struct {
	char name[128];
	int points;
	char visibility[32];
	double timeout;
	const TTest *test;  /* the registered test of that name */
	int selected;       /* run it (all, or those --only names) */
} rubric_line;

typedef struct {
	int pass;
	char word[16];      /* pass | fail | error | timeout */
	char msg[MSG_MAX];  /* why it did not pass, in words */
} outcome;

static struct {
	const char *name;
	const TTest *test;
} registry[MAX_TESTS];
static int nregistered;

static rubric_line rubric[MAX_TESTS];
static int nrubric;

/* Descriptors the test's own process must not keep (it could write fake results on
 * them), and the one it reports a file-limit signal on. */
static int private_fd[2] = {-1, -1};
static int limit_fd = -1;

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

gsl_rng *lz_test_rng(unsigned long seed)
{
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	ck_assert_msg(r != NULL, "no memory for a random number generator");
	gsl_rng_set(r, seed);
	return r;
}

lz_ref lz_test_reference(const char *file, const char *quantity, const char *dim,
                         const char *state)
{
	lz_ref r = {0, 0};
	ck_assert_msg(lz_reference(file, quantity, dim, state, &r) == LZ_OK,
	              "the literature value is missing: %s", lz_error_message());
	return r;
}

static int last_error;

int lz_test_last_error(void) { return last_error; }
void lz_test_clear_error(void) { last_error = 0; }

void lz_test_refused(int failed, const char *call, const char *says, const char *also)
{
	ck_assert_msg(failed, "%s should be refused", call);
	ck_assert_msg(last_error == LZ_EINVAL, "%s: code %d, expected LZ_EINVAL (%d)", call,
	              last_error, LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), says), "%s: the message should say \"%s\": %s",
	              call, says, lz_error_message());
	if (also)
		ck_assert_msg(strstr(lz_error_message(), also), "%s: the message should say "
		              "\"%s\": %s", call, also, lz_error_message());
}

/* ---- handlers that turn library events into test failures ---- */

static void record_error(int code, const char *message)
{
	(void)message;
	last_error = code;
}

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
	r->selected = 1;
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

/* Without a rubric (a suite that is not graded: the library's own), every registered
 * test runs, worth no points, with a generous timeout. */
static void rubric_of_registry(void)
{
	for (int j = 0; j < nregistered; j++) {
		rubric_line *r = &rubric[nrubric++];
		snprintf(r->name, sizeof r->name, "%s", registry[j].name);
		snprintf(r->visibility, sizeof r->visibility, "visible");
		r->points = 0;
		r->timeout = UNGRADED_TIMEOUT;
		r->selected = 1;
	}
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

/* --only NAME[,NAME...] (repeatable): run only those. */
static int select_only(char **names, int n)
{
	if (n == 0)
		return 0;
	for (int i = 0; i < nrubric; i++)
		rubric[i].selected = 0;
	for (int k = 0; k < n; k++)
		for (char *name = strtok(names[k], ","); name; name = strtok(NULL, ",")) {
			int found = 0;
			for (int i = 0; i < nrubric; i++)
				if (strcmp(rubric[i].name, name) == 0)
					rubric[i].selected = found = 1;
			if (!found) {
				fprintf(stderr, "runner: no test named '%s' in the rubric\n", name);
				return -1;
			}
		}
	return 0;
}

/* ---- words for what happened ---- */

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

/* The file-size limit of this process (ulimit -f) in words, e.g. "20 MiB". */
static void file_limit_words(char *out, size_t size)
{
	struct rlimit rl;
	if (getrlimit(RLIMIT_FSIZE, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY)
		snprintf(out, size, "file-size limit");
	else
		snprintf(out, size, "%g MiB file limit", (double)rl.rlim_cur / (1 << 20));
}

/* One line: tabs and newlines would break the grader's protocol. */
static void flatten(char *s)
{
	for (; *s; s++)
		if (*s == '\t' || *s == '\n' || *s == '\r')
			*s = ' ';
}

/* ---- running one test ---- */

static void on_file_limit(int sig)
{
	(void)sig;
	if (limit_fd >= 0) {
		ssize_t w = write(limit_fd, "F", 1);
		(void)w;
	}
	_exit(LIMIT_EXIT);
}

/* Check's checked fixture: runs first in the test's own process (fork mode only). */
static void enter_test_process(void)
{
	for (int i = 0; i < 2; i++)
		if (private_fd[i] >= 0)
			close(private_fd[i]);
}

/* Write all of BUF to FD (a pipe). */
static void write_all(int fd, const char *buf, size_t n)
{
	while (n > 0) {
		ssize_t w = write(fd, buf, n);
		if (w < 0 && errno == EINTR)
			continue;
		if (w <= 0)
			return;
		buf += w;
		n -= (size_t)w;
	}
}

/* The runner's child: Check runs the one test (in a grandchild unless CK_FORK=no)
 * and the child sends "word<TAB>message" on RESULT_FD. It never returns. */
static _Noreturn void run_in_child(const rubric_line *r, int result_fd)
{
	signal(SIGXFSZ, on_file_limit);
	Suite *s = suite_create("lozenge");
	TCase *tc = tcase_create(r->name);
	tcase_set_timeout(tc, r->timeout);
	tcase_add_test(tc, r->test);
	suite_add_tcase(s, tc);
	SRunner *sr = srunner_create(s);
	if (srunner_fork_status(sr) == CK_FORK)
		tcase_add_checked_fixture(tc, enter_test_process, NULL);
	srunner_run_all(sr, CK_SILENT);
	if (srunner_ntests_run(sr) == 1) {
		TestResult **res = srunner_results(sr);
		const char *word = tr_rtype(res[0]) == CK_PASS      ? "pass"
		                   : tr_rtype(res[0]) == CK_FAILURE ? "fail"
		                   : strstr(tr_msg(res[0]), "timeout") ? "timeout" : "error";
		char msg[MSG_MAX], line[MSG_MAX + 32];
		explain(tr_msg(res[0]), msg, sizeof msg);
		flatten(msg);
		int n = snprintf(line, sizeof line, "%s\t%s", word, tr_rtype(res[0]) == CK_PASS ? "" : msg);
		write_all(result_fd, line, n < 0 ? 0 : (size_t)n < sizeof line ? (size_t)n : sizeof line - 1);
	}
	_exit(0);
}

/* Read FD until end of file into BUF (at most SIZE - 1 bytes kept). */
static void read_all(int fd, char *buf, size_t size)
{
	size_t n = 0;
	char sink[512];
	for (;;) {
		char *to = n + 1 < size ? buf + n : sink;
		size_t room = n + 1 < size ? size - 1 - n : sizeof sink;
		ssize_t r = read(fd, to, room);
		if (r < 0 && errno == EINTR)
			continue;
		if (r <= 0)
			break;
		if (to == buf + n)
			n += (size_t)r;
	}
	buf[n] = '\0';
}

/* In machine mode the tests' output goes to the log; one test's flood must not
 * leave the next test without room under the file limit. */
static void trim_log(void)
{
	struct stat st;
	if (fstat(STDOUT_FILENO, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > LOG_KEEP &&
	    ftruncate(STDOUT_FILENO, 0) == 0)
		printf("[runner: the output of earlier tests was cut: it passed %ld bytes]\n",
		       LOG_KEEP);
}

/* What the child's end tells when it sent no result. */
static void no_result(outcome *o, int status, int limited, double backstop)
{
	char limit[64];
	o->pass = 0;
	snprintf(o->word, sizeof o->word, "error");
	if (limited) {
		file_limit_words(limit, sizeof limit);
		snprintf(o->msg, sizeof o->msg, "exceeded the %s: the test wrote more than that "
		         "(printing in a loop? every passing ck_assert also writes about 40 bytes)",
		         limit);
	} else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM) {
		snprintf(o->word, sizeof o->word, "timeout");
		snprintf(o->msg, sizeof o->msg, "did not finish within %g s (an endless loop, or "
		         "far too slow)", backstop);
	} else if (WIFSIGNALED(status)) {
		snprintf(o->msg, sizeof o->msg, "the test program was killed by signal %d (%s) "
		         "before it reported this test", WTERMSIG(status), strsignal(WTERMSIG(status)));
	} else {
		snprintf(o->msg, sizeof o->msg, "the test program stopped before it reported this "
		         "test (exit status %d)", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
	}
}

static outcome run_one(const rubric_line *r, FILE *results)
{
	outcome o = {0};
	int res[2], lim[2];
	if (pipe(res) != 0 || pipe(lim) != 0) {
		fprintf(stderr, "runner: pipe: %s\n", strerror(errno));
		exit(2);
	}
	const char *mult_env = getenv("CK_TIMEOUT_MULTIPLIER");
	double mult = mult_env && atof(mult_env) > 0 ? atof(mult_env) : 1;
	double backstop = 2 * r->timeout * mult + 10;  /* Check's timeout comes first */
	fflush(stdout);
	fflush(stderr);
	fflush(results);
	trim_log();
	fflush(stdout);
	pid_t pid = fork();
	if (pid < 0) {
		fprintf(stderr, "runner: fork: %s\n", strerror(errno));
		exit(2);
	}
	if (pid == 0) {
		close(res[0]);
		close(lim[0]);
		private_fd[0] = res[1];
		private_fd[1] = fileno(results) == STDOUT_FILENO ? -1 : fileno(results);
		limit_fd = lim[1];
		alarm((unsigned)ceil(backstop));
		run_in_child(r, res[1]);
	}
	close(res[1]);
	close(lim[1]);
	char line[MSG_MAX + 32];
	read_all(res[0], line, sizeof line);
	close(res[0]);
	int status = 0;
	while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
		;
	fcntl(lim[0], F_SETFL, O_NONBLOCK);
	char mark[8];
	int limited = read(lim[0], mark, sizeof mark) > 0;
	close(lim[0]);
	char *tab = strchr(line, '\t');
	if (limited || !tab) {
		no_result(&o, status, limited, backstop);
		return o;
	}
	*tab = '\0';
	snprintf(o.word, sizeof o.word, "%.15s", line);
	snprintf(o.msg, sizeof o.msg, "%s", tab + 1);
	o.pass = strcmp(o.word, "pass") == 0;
	return o;
}

/* ---- results ---- */

static void print_student(const outcome *out, int graded, int *earned, int *npass)
{
	for (int i = 0; i < nrubric; i++) {
		if (!rubric[i].selected)
			continue;
		int pts = rubric[i].points;
		*earned += out[i].pass ? pts : 0;
		*npass += out[i].pass;
		if (graded)
			printf("  %s  %3d/%-3d  %s\n", out[i].pass ? "PASS" : "FAIL",
			       out[i].pass ? pts : 0, pts, rubric[i].name);
		else
			printf("  %s  %s\n", out[i].pass ? "PASS" : "FAIL", rubric[i].name);
		if (!out[i].pass)
			printf("               %s\n", out[i].msg);
	}
}

static void print_machine(FILE *f, const outcome *out, int nrun)
{
	fprintf(f, "LZBEGIN\n");
	for (int i = 0; i < nrubric; i++)
		if (rubric[i].selected)
			fprintf(f, "LZRESULT\t%s\t%s\t%s\n", rubric[i].name, out[i].word,
			        out[i].pass ? "" : out[i].msg);
	fprintf(f, "LZEND\tran\t%d\n", nrun);
	fflush(f);
}

/* ---- main ---- */

static void usage(void)
{
	fprintf(stderr, "usage: SUITE [--rubric FILE ...] [--only TEST[,TEST...]] "
	        "[--machine [--log FILE]]\n");
	exit(2);
}

/* In machine mode the tests' own output goes to the log and the results to the
 * original stdout, so nothing a test prints can pass for a result line. The log is
 * opened for appending, so cutting it (trim_log) leaves no hole to fill. */
static FILE *divert_output(const char *log)
{
	int keep = dup(STDOUT_FILENO);
	int fd = open(log ? log : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
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

int main(int argc, char **argv)
{
	const char *log = NULL;
	char *only[MAX_TESTS];
	int machine = 0, nrubrics = 0, nonly = 0;
	for (int i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--rubric") == 0 && i + 1 < argc) {
			if (read_rubric(argv[++i]) != 0)
				return 2;
			nrubrics++;
		} else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc && nonly < MAX_TESTS) {
			only[nonly++] = argv[++i];
		} else if (strcmp(argv[i], "--log") == 0 && i + 1 < argc) {
			log = argv[++i];
		} else if (strcmp(argv[i], "--machine") == 0) {
			machine = 1;
		} else {
			usage();
		}
	}
	if (nrubrics == 0)
		rubric_of_registry();
	if (match_rubric() != 0 || select_only(only, nonly) != 0)
		return 2;

	gsl_set_error_handler(gsl_to_failure);
	lz_set_todo_handler(todo_to_failure);
	lz_set_error_handler(record_error);

	FILE *results = machine ? divert_output(log) : stdout;
	static outcome out[MAX_TESTS];
	int nrun = 0, expected = 0, earned = 0, total = 0, npass = 0;
	for (int i = 0; i < nrubric; i++) {
		if (!rubric[i].selected)
			continue;
		expected++;
		total += rubric[i].points;
		out[i] = run_one(&rubric[i], results);
		nrun++;
		npass += out[i].pass;
	}
	if (machine) {
		print_machine(results, out, nrun);
	} else {
		npass = 0;
		print_student(out, nrubrics > 0, &earned, &npass);
		if (nrubrics > 0)
			printf("Score: %d/%d\n", earned, total);
		printf("%d passed, %d failed\n", npass, expected - npass);
	}
	return npass == expected ? 0 : 1;
}
