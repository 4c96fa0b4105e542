/* report.c — lz-report, the autograder's report writer (README.md, "How an instructor grades").
 *
 * It links no student code and no library: it reads what the grader captured and
 * writes the reports. grade.sh runs it after every process of the submission is
 * gone, so nothing the student's code wrote can stand in for a report.
 *
 *   lz-report --out DIR [--spec FILE] [--gradebook CSV --student NAME] [--quiet]
 *
 * The spec (FILE, or standard input) is a line-oriented description of the run,
 * `keyword argument`, '#' comments:
 *
 *   title TEXT            what was graded (shown on top of the report)
 *   stage NN-name         starts a stage; the lines below belong to it
 *   rubric PATH           a rubric file of the stage (repeat for hidden/rubric ...)
 *   build ok|failed|rejected|unreadable [LOG]   the build, and the compiler's output
 *                         (rejected: the objects broke the grader's rules; unreadable:
 *                         the submission could not be read at all)
 *   results PATH          what the test runner printed (stdout and stderr, captured)
 *   exit N                the runner's exit status as the shell saw it (124: timeout)
 *   budget S              the seconds the whole test program was allowed
 *   note TEXT             a line for the stage's "build" pseudo-test
 *   refused TEXT          a file of the stage the grader refused, and why (its stub
 *                         was graded instead); the stage's status says so
 *   hidden-elsewhere N    N more points of the stage are in hidden tests that this
 *                         tree does not have (a student's handout)
 *
 * Every rubric test gets a result. Only LZRESULT lines between LZBEGIN and LZEND
 * count, and the last line for a test wins (an LZBEGIN starts afresh, so only the
 * runner's own block, printed last, counts); a test the runner did not report scores
 * 0 with the reason (did not compile, crashed, timed out). A test scores its points
 * on pass and 0 otherwise. Tests from a rubric under a hidden/ directory are hidden
 * tests (not in the student handout); the report says how many points they carry.
 * Every stage gets a status: graded, did not compile, refused: why, or unreadable.
 *
 * DIR receives report.txt (also printed), results.json (Gradescope), junit.xml and
 * results.tap (TAP version 13). --gradebook appends the student's row to a CSV
 * (student, a score and a status column per stage, total, max), writing its header
 * when new.
 * Exit status: 0 when the reports were written, 2 otherwise.
 */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define LOG_LINES 60      /* compiler output kept in the build pseudo-test */
#define LOG_LINE_MAX 400  /* and the longest line of it */
#define SAID_LINES 10     /* runner lines outside the protocol worth showing */
#define MSG_COLUMNS 100   /* the table shows this much of a message */

typedef enum { R_MISSING, R_PASS, R_FAIL, R_ERROR, R_TIMEOUT } result;
typedef enum { B_NONE, B_OK, B_FAILED, B_REJECTED, B_UNREADABLE } build_state;

typedef struct {
	char **v;
	size_t n;
} strlist;

typedef struct {
	char *name;
	double points;
	char *visibility;
	result res;
	char *message;
	int hidden;          /* from a hidden/ rubric: not in the student handout */
} test;

typedef struct {
	char *name;
	test *tests;
	size_t ntests;
	build_state build;
	char *build_log;     /* first LOG_LINES lines of the compiler output */
	char *results_path;
	int exit_status;     /* -1: not given */
	double budget;       /* 0: not given */
	strlist notes;
	strlist refused;     /* files the grader refused, and why */
	strlist said;        /* runner output that is not protocol */
	double hidden_elsewhere;  /* points of hidden tests this tree does not have */
	int saw_begin, saw_end;
	long ran;
	double got, max;
} stage;

typedef struct {
	char *title;
	stage *stages;
	size_t nstages;
	double got, max;
	double hidden_got, hidden_max, hidden_elsewhere;
	size_t nhidden;
} report;

/* ---- memory and errors -------------------------------------------------- */

static _Noreturn void die(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static _Noreturn void die(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fputs("lz-report: ", stderr);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
	va_end(ap);
	exit(2);
}

static void *xrealloc(void *p, size_t n)
{
	p = realloc(p, n ? n : 1);
	if (!p)
		die("out of memory");
	return p;
}

static char *xstrdup(const char *s)
{
	size_t n = strlen(s) + 1;
	return memcpy(xrealloc(NULL, n), s, n);
}

static char *xprintf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static char *xprintf(const char *fmt, ...)
{
	char *buf = NULL;
	size_t len = 0;
	FILE *m = open_memstream(&buf, &len);
	if (!m)
		die("out of memory");
	va_list ap;
	va_start(ap, fmt);
	vfprintf(m, fmt, ap);
	va_end(ap);
	if (fclose(m) != 0)
		die("out of memory");
	return buf;
}

static void strlist_add(strlist *l, const char *s)
{
	l->v = xrealloc(l->v, (l->n + 1) * sizeof *l->v);
	l->v[l->n++] = xstrdup(s);
}

/* Drop a trailing newline (and a carriage return before it). */
static void chomp(char *s)
{
	size_t n = strlen(s);
	while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == '\r'))
		s[--n] = '\0';
}

/* ---- text: decode UTF-8, replacing what is not valid ------------------- */

#define REPLACEMENT 0xFFFDu

/* The code point at *p, advancing *p; a byte that does not start a valid, shortest
 * UTF-8 sequence decodes to U+FFFD and advances by one. */
static unsigned long next_cp(const unsigned char **p)
{
	const unsigned char *s = *p;
	unsigned long cp;
	int len;
	if (s[0] < 0x80) {
		*p += 1;
		return s[0];
	} else if (s[0] >= 0xC2 && s[0] <= 0xDF) {
		cp = s[0] & 0x1Fu, len = 2;
	} else if (s[0] >= 0xE0 && s[0] <= 0xEF) {
		cp = s[0] & 0x0Fu, len = 3;
	} else if (s[0] >= 0xF0 && s[0] <= 0xF4) {
		cp = s[0] & 0x07u, len = 4;
	} else {
		*p += 1;
		return REPLACEMENT;
	}
	for (int i = 1; i < len; i++) {
		if ((s[i] & 0xC0) != 0x80) {
			*p += 1;
			return REPLACEMENT;
		}
		cp = cp << 6 | (s[i] & 0x3Fu);
	}
	static const unsigned long least[5] = {0, 0, 0x80, 0x800, 0x10000};
	if (cp < least[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
		*p += 1;
		return REPLACEMENT;
	}
	*p += len;
	return cp;
}

static void put_cp(FILE *f, unsigned long cp)
{
	if (cp < 0x80) {
		fputc((int)cp, f);
	} else if (cp < 0x800) {
		fputc((int)(0xC0 | cp >> 6), f);
		fputc((int)(0x80 | (cp & 0x3F)), f);
	} else if (cp < 0x10000) {
		fputc((int)(0xE0 | cp >> 12), f);
		fputc((int)(0x80 | (cp >> 6 & 0x3F)), f);
		fputc((int)(0x80 | (cp & 0x3F)), f);
	} else {
		fputc((int)(0xF0 | cp >> 18), f);
		fputc((int)(0x80 | (cp >> 12 & 0x3F)), f);
		fputc((int)(0x80 | (cp >> 6 & 0x3F)), f);
		fputc((int)(0x80 | (cp & 0x3F)), f);
	}
}

/* A JSON string literal. */
static void put_json(FILE *f, const char *text)
{
	const unsigned char *p = (const unsigned char *)text;
	fputc('"', f);
	while (*p) {
		unsigned long cp = next_cp(&p);
		if (cp == '"' || cp == '\\')
			fprintf(f, "\\%c", (int)cp);
		else if (cp == '\n')
			fputs("\\n", f);
		else if (cp == '\t')
			fputs("\\t", f);
		else if (cp < 0x20 || cp == 0x7F || cp == 0x2028 || cp == 0x2029)
			fprintf(f, "\\u%04lx", cp);
		else
			put_cp(f, cp);
	}
	fputc('"', f);
}

/* XML 1.0 character data; in an attribute, also the whitespace that attribute
 * normalisation would otherwise eat. Characters XML cannot carry become U+FFFD. */
static void put_xml(FILE *f, const char *text, int attribute)
{
	const unsigned char *p = (const unsigned char *)text;
	while (*p) {
		unsigned long cp = next_cp(&p);
		if (cp == '&')
			fputs("&amp;", f);
		else if (cp == '<')
			fputs("&lt;", f);
		else if (cp == '>')
			fputs("&gt;", f);
		else if (cp == '"')
			fputs("&quot;", f);
		else if (attribute && (cp == '\n' || cp == '\t' || cp == '\r'))
			fprintf(f, "&#%lu;", cp);
		else if ((cp < 0x20 && cp != '\n' && cp != '\t' && cp != '\r') ||
		         cp == 0xFFFE || cp == 0xFFFF)
			put_cp(f, REPLACEMENT);
		else
			put_cp(f, cp);
	}
}

/* Plain text for the table: valid UTF-8, no control characters, at most `columns`
 * characters of the first line (0: everything, newlines kept). */
static void put_plain(FILE *f, const char *text, size_t columns)
{
	const unsigned char *p = (const unsigned char *)text;
	for (size_t n = 0; *p && (columns == 0 || n < columns); n++) {
		unsigned long cp = next_cp(&p);
		if (cp == '\n' && columns)
			break;
		if (cp == '\t')
			cp = ' ';
		if ((cp < 0x20 && cp != '\n') || cp == 0x7F)
			cp = REPLACEMENT;
		if (columns && n + 1 == columns && *p)
			cp = 0x2026;  /* an ellipsis where the line was cut */
		put_cp(f, cp);
	}
}

/* A YAML single-quoted scalar on one line. */
static void put_yaml(FILE *f, const char *text)
{
	const unsigned char *p = (const unsigned char *)text;
	fputc('\'', f);
	while (*p) {
		unsigned long cp = next_cp(&p);
		if (cp == '\'')
			fputs("''", f);
		else if (cp < 0x20 || cp == 0x7F)
			fputc(' ', f);
		else
			put_cp(f, cp);
	}
	fputc('\'', f);
}

/* A CSV field, quoted when it has to be. */
static void put_csv(FILE *f, const char *text)
{
	if (!strpbrk(text, ",\"\n\r")) {
		put_plain(f, text, 0);
		return;
	}
	fputc('"', f);
	for (const char *s = text; *s; s++) {
		if (*s == '"')
			fputc('"', f);
		fputc(*s == '\n' || *s == '\r' ? ' ' : *s, f);
	}
	fputc('"', f);
}

/* ---- the rubric ---------------------------------------------------------- */

static test *find_test(stage *s, const char *name)
{
	for (size_t i = 0; i < s->ntests; i++)
		if (strcmp(s->tests[i].name, name) == 0)
			return &s->tests[i];
	return NULL;
}

static void add_test(stage *s, const char *name, double points, const char *vis, int hidden)
{
	s->tests = xrealloc(s->tests, (s->ntests + 1) * sizeof *s->tests);
	s->tests[s->ntests++] = (test){xstrdup(name), points, xstrdup(vis), R_MISSING, NULL, hidden};
}

/* One rubric line: `test points visibility timeout_s`, '#' comments. */
static void rubric_line(stage *s, char *line, const char *path, int lineno)
{
	char *hash = strchr(line, '#');
	if (hash)
		*hash = '\0';
	char name[256], vis[64], extra[2];
	double points, timeout;
	int got = sscanf(line, "%255s %lf %63s %lf %1s", name, &points, vis, &timeout, extra);
	if (got <= 0)
		return;
	if (got != 4 || !(points >= 0))
		die("%s:%d: a rubric line is `test points visibility timeout_s`", path, lineno);
	if (find_test(s, name))
		die("%s:%d: test '%s' is listed twice in stage %s", path, lineno, name, s->name);
	add_test(s, name, points, vis, strstr(path, "/hidden/") != NULL);
}

static void read_rubric(stage *s, const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f)
		die("cannot read the rubric %s: %s", path, strerror(errno));
	char *line = NULL;
	size_t cap = 0;
	int lineno = 0;
	while (getline(&line, &cap, f) >= 0)
		rubric_line(s, line, path, ++lineno);
	free(line);
	fclose(f);
}

/* ---- the runner's output ------------------------------------------------ */

static result parse_result(const char *word)
{
	static const struct {
		const char *word;
		result res;
	} words[] = {{"pass", R_PASS}, {"fail", R_FAIL}, {"error", R_ERROR}, {"timeout", R_TIMEOUT}};
	for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
		if (strcmp(word, words[i].word) == 0)
			return words[i].res;
	return R_ERROR;
}

/* LZRESULT <tab> test <tab> status <tab> message: the last one for a test wins. */
static void result_line(stage *s, char *line)
{
	char *name = strtok(line + strlen("LZRESULT\t"), "\t");
	char *word = name ? strtok(NULL, "\t") : NULL;
	char *message = word ? strtok(NULL, "") : NULL;
	test *t = name ? find_test(s, name) : NULL;
	if (!t || !word)
		return;  /* not a test of this rubric: it cannot score */
	t->res = parse_result(word);
	free(t->message);
	if (t->res == R_ERROR && strcmp(word, "error") != 0)
		t->message = xprintf("unrecognised result '%s'", word);
	else
		t->message = xstrdup(message ? message : "");
}

/* A block starts afresh: whatever came before it (fake lines a test printed where
 * the runner's own output goes) is forgotten. A line that only ends in LZBEGIN is a
 * start too: something printed half a line just before the runner's block. */
static void begin_block(stage *s)
{
	for (size_t i = 0; i < s->ntests; i++) {
		s->tests[i].res = R_MISSING;
		free(s->tests[i].message);
		s->tests[i].message = NULL;
	}
	s->saw_begin = 1;
	s->saw_end = 0;
	s->ran = 0;
}

static int is_begin(const char *line)
{
	size_t n = strlen(line), k = strlen("LZBEGIN");
	return n >= k && strcmp(line + n - k, "LZBEGIN") == 0;
}

static void runner_line(stage *s, char *line, int *inside)
{
	chomp(line);
	if (is_begin(line)) {
		*inside = 1;
		begin_block(s);
	} else if (strncmp(line, "LZEND\tran\t", 10) == 0 && *inside) {
		*inside = 0;
		s->saw_end = 1;
		s->ran = strtol(line + 10, NULL, 10);
	} else if (strncmp(line, "LZRESULT\t", 9) == 0) {
		if (*inside)
			result_line(s, line);
	} else if (line[0] && s->said.n < SAID_LINES) {
		strlist_add(&s->said, line);
	}
}

static void read_results(stage *s)
{
	FILE *f = s->results_path ? fopen(s->results_path, "r") : NULL;
	if (!f)
		return;
	char *line = NULL;
	size_t cap = 0;
	int inside = 0;
	while (getline(&line, &cap, f) >= 0)
		runner_line(s, line, &inside);
	free(line);
	fclose(f);
}

/* The first LOG_LINES lines of the compiler output, each cut at LOG_LINE_MAX. */
static char *read_log(const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return xprintf("(the compiler output %s could not be read: %s)", path, strerror(errno));
	char *out = xstrdup(""), *line = NULL;
	size_t cap = 0, n = 0;
	ssize_t len;
	while ((len = getline(&line, &cap, f)) >= 0) {
		if (n++ == LOG_LINES) {
			char *more = xprintf("%s[... more compiler output cut]\n", out);
			free(out);
			out = more;
			break;
		}
		chomp(line);
		if (strlen(line) > LOG_LINE_MAX)
			strcpy(line + LOG_LINE_MAX - 4, " ...");
		char *more = xprintf("%s%s\n", out, line);
		free(out);
		out = more;
	}
	free(line);
	fclose(f);
	return out;
}

/* ---- the spec ------------------------------------------------------------ */

static stage *current(report *r, const char *keyword, const char *path, int lineno)
{
	if (r->nstages == 0)
		die("%s:%d: '%s' before any 'stage' line", path, lineno, keyword);
	return &r->stages[r->nstages - 1];
}

static void add_stage(report *r, const char *name)
{
	r->stages = xrealloc(r->stages, (r->nstages + 1) * sizeof *r->stages);
	stage *s = &r->stages[r->nstages++];
	memset(s, 0, sizeof *s);
	s->name = xstrdup(name);
	s->exit_status = -1;
}

static void spec_build(stage *s, char *arg, const char *path, int lineno)
{
	char *word = strtok(arg, " \t");
	char *log = strtok(NULL, "");
	if (word && strcmp(word, "ok") == 0)
		s->build = B_OK;
	else if (word && strcmp(word, "failed") == 0)
		s->build = B_FAILED;
	else if (word && strcmp(word, "rejected") == 0)
		s->build = B_REJECTED;
	else if (word && strcmp(word, "unreadable") == 0)
		s->build = B_UNREADABLE;
	else
		die("%s:%d: build ok|failed|rejected|unreadable [LOG]", path, lineno);
	free(s->build_log);
	s->build_log = log ? read_log(log) : NULL;
}

static void spec_line(report *r, char *line, const char *path, int lineno)
{
	chomp(line);
	char *arg = line + strcspn(line, " \t");
	if (*arg)
		*arg++ = '\0';
	arg += strspn(arg, " \t");
	if (line[0] == '\0' || line[0] == '#')
		return;
	if (strcmp(line, "title") == 0) {
		free(r->title);
		r->title = xstrdup(arg);
		return;
	}
	if (strcmp(line, "stage") == 0) {
		if (!*arg)
			die("%s:%d: stage NN-name", path, lineno);
		add_stage(r, arg);
		return;
	}
	stage *s = current(r, line, path, lineno);
	if (strcmp(line, "rubric") == 0)
		read_rubric(s, arg);
	else if (strcmp(line, "build") == 0)
		spec_build(s, arg, path, lineno);
	else if (strcmp(line, "results") == 0)
		free(s->results_path), s->results_path = xstrdup(arg);
	else if (strcmp(line, "exit") == 0)
		s->exit_status = atoi(arg);
	else if (strcmp(line, "budget") == 0)
		s->budget = atof(arg);
	else if (strcmp(line, "note") == 0)
		strlist_add(&s->notes, arg);
	else if (strcmp(line, "refused") == 0)
		strlist_add(&s->refused, arg);
	else if (strcmp(line, "hidden-elsewhere") == 0)
		s->hidden_elsewhere = atof(arg);
	else
		die("%s:%d: unknown keyword '%s'", path, lineno, line);
}

static void read_spec(report *r, const char *path)
{
	FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "r");
	if (!f)
		die("cannot read the spec %s: %s", path, strerror(errno));
	char *line = NULL;
	size_t cap = 0;
	int lineno = 0;
	while (getline(&line, &cap, f) >= 0)
		spec_line(r, line, path, ++lineno);
	free(line);
	if (f != stdin)
		fclose(f);
	if (r->nstages == 0)
		die("%s: no stage to report", path);
}

/* ---- scoring ------------------------------------------------------------- */

/* Why a test of the stage has no result. */
static char *why_missing(const stage *s)
{
	if (s->build == B_NONE)
		return xstrdup("not built: the grader did not get this far");
	if (s->build == B_FAILED)
		return xprintf("did not compile (the compiler's errors are in %s/build)", s->name);
	if (s->build == B_REJECTED)
		return xprintf("refused by the grader (the reason is in %s/build)", s->name);
	if (s->build == B_UNREADABLE)
		return xprintf("the submission could not be read (the reason is in %s/build)",
		               s->name);
	if (s->exit_status == 124 || s->exit_status == 137)
		return s->budget > 0 ? xprintf("timed out: the whole test program was stopped after "
		                               "%g s, before it reported this test", s->budget)
		                     : xstrdup("timed out: the whole test program was stopped "
		                               "before it reported this test");
	if (s->saw_end)
		return xprintf("not reported: the test program ran %ld tests and this was not "
		               "one of them", s->ran);
	if (s->saw_begin)
		return xprintf("the test program stopped in the middle of its report (exit "
		               "status %d)", s->exit_status);
	if (s->exit_status > 128)
		return xprintf("the test program crashed before reporting (killed by signal %d)",
		               s->exit_status - 128);
	if (s->exit_status >= 0)
		return xprintf("the test program stopped before reporting (exit status %d)%s%s",
		               s->exit_status, s->said.n ? ": " : "", s->said.n ? s->said.v[0] : "");
	return xstrdup("the test program crashed before reporting");
}

static void score_stage(stage *s)
{
	char *why = why_missing(s);
	for (size_t i = 0; i < s->ntests; i++) {
		test *t = &s->tests[i];
		if (t->res == R_MISSING)
			t->message = xstrdup(why);
		s->max += t->points;
		s->got += t->res == R_PASS ? t->points : 0;
	}
	free(why);
}

static void count_hidden(report *r, const stage *s)
{
	for (size_t i = 0; i < s->ntests; i++)
		if (s->tests[i].hidden) {
			r->nhidden++;
			r->hidden_max += s->tests[i].points;
			r->hidden_got += s->tests[i].res == R_PASS ? s->tests[i].points : 0;
		}
	r->hidden_elsewhere += s->hidden_elsewhere;
}

static void score(report *r)
{
	for (size_t i = 0; i < r->nstages; i++) {
		stage *s = &r->stages[i];
		read_results(s);
		score_stage(s);
		count_hidden(r, s);
		r->got += s->got;
		r->max += s->max;
	}
}

/* ---- the build pseudo-test ---------------------------------------------- */

/* The first line of TEXT (a copy). */
static char *first_line(const char *text)
{
	size_t n = strcspn(text, "\n");
	char *line = xrealloc(NULL, n + 1);
	memcpy(line, text, n);
	line[n] = '\0';
	return line;
}

/* The stage's status in a few words: graded, did not compile, refused: why,
 * unreadable (the gradebook's column, the build test's verdict). */
static char *stage_status(const stage *s)
{
	switch (s->build) {
	case B_OK:
		if (s->refused.n == 0)
			return xstrdup("graded");
		return xprintf("refused: %s%s", s->refused.v[0], s->refused.n > 1 ? " (and more)" : "");
	case B_FAILED:
		return xstrdup("did not compile");
	case B_REJECTED: {
		char *line = first_line(s->build_log ? s->build_log : "");
		char *status = xprintf("refused: %s", line);
		free(line);
		return status;
	}
	case B_UNREADABLE:
		return xstrdup("unreadable");
	default:
		return xstrdup("not built");
	}
}

/* The build pseudo-test passes when the stage was graded as handed in. */
static int build_passed(const stage *s)
{
	return s->build == B_OK && s->refused.n == 0;
}

/* Its full text: the outcome, the grader's notes, the compiler output, and what
 * the runner printed outside the protocol (e.g. why it refused to run). */
static void put_build_text(FILE *f, const stage *s)
{
	char *status = stage_status(s);
	fprintf(f, "%s: %s\n", s->name, status);
	free(status);
	for (size_t i = 0; i < s->notes.n; i++)
		fprintf(f, "note: %s\n", s->notes.v[i]);
	if (s->build_log && s->build != B_OK && s->build_log[0])
		fprintf(f, "\n%s", s->build_log);
	if (s->said.n)
		fputs("\nthe test program said:\n", f);
	for (size_t i = 0; i < s->said.n; i++)
		fprintf(f, "  %s\n", s->said.v[i]);
}

/* The same, as a string (for JSON, XML and TAP). */
static char *build_text(const stage *s)
{
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	if (!f)
		die("out of memory");
	put_build_text(f, s);
	fclose(f);
	return buf;
}

static const char *result_word(result r)
{
	static const char *const words[] = {"no result", "pass", "fail", "error", "timeout"};
	return words[r];
}

/* ---- report.txt ---------------------------------------------------------- */

static int name_width(const report *r)
{
	size_t w = strlen("build");
	for (size_t i = 0; i < r->nstages; i++)
		for (size_t j = 0; j < r->stages[i].ntests; j++) {
			size_t n = strlen(r->stages[i].tests[j].name);
			w = n > w ? n : w;
		}
	return (int)(w > 44 ? 44 : w);
}

static void text_test(FILE *f, const stage *s, const test *t, int width)
{
	char pts[64];
	snprintf(pts, sizeof pts, "%g/%g", t->res == R_PASS ? t->points : 0, t->points);
	fprintf(f, "%-12s %-*s %8s  %s", s->name, width, t->name, pts, result_word(t->res));
	if (strcmp(t->visibility, "visible") != 0)
		fprintf(f, " (%s)", t->visibility);
	if (t->res != R_PASS && t->message && t->message[0]) {
		fputs(": ", f);
		put_plain(f, t->message, MSG_COLUMNS);
	}
	fputc('\n', f);
}

static void text_stage(FILE *f, const stage *s, int width)
{
	char *status = stage_status(s);
	fprintf(f, "%-12s %-*s %8s  ", s->name, width, "build", "-");
	put_plain(f, status, MSG_COLUMNS);
	fputc('\n', f);
	free(status);
	for (size_t i = 0; i < s->ntests; i++)
		text_test(f, s, &s->tests[i], width);
	char pts[64];
	snprintf(pts, sizeof pts, "%g/%g", s->got, s->max);
	fprintf(f, "%-12s %-*s %8s\n", "", width, "", pts);
}

/* Notes and compiler errors of the stages that have them, after the table. */
static void text_details(FILE *f, const report *r)
{
	for (size_t i = 0; i < r->nstages; i++) {
		const stage *s = &r->stages[i];
		if (build_passed(s) && s->notes.n == 0 && s->said.n == 0)
			continue;
		char *text = build_text(s);
		fputc('\n', f);
		put_plain(f, text, 0);
		free(text);
	}
}

/* What the hidden tests weigh: in the instructor's grade, how many of the points
 * they carry; in a student's, how many more the instructor's grade adds. */
static void put_hidden(FILE *f, const report *r)
{
	if (r->nhidden)
		fprintf(f, "\nHidden tests: %g of these %g points are in %zu tests the student "
		        "handout does not have (%g of them earned here).\n", r->hidden_max, r->max,
		        r->nhidden, r->hidden_got);
	if (r->hidden_elsewhere > 0)
		fprintf(f, "\nThese are the public tests. The instructor's grade adds hidden tests "
		        "worth %g more points.\n", r->hidden_elsewhere);
}

static void write_text(FILE *f, const report *r)
{
	int width = name_width(r);
	if (r->title)
		fprintf(f, "grading %s\n\n", r->title);
	fprintf(f, "%-12s %-*s %8s  %s\n", "stage", width, "test", "points", "result");
	for (size_t i = 0; i < r->nstages; i++)
		text_stage(f, &r->stages[i], width);
	text_details(f, r);
	put_hidden(f, r);
	fprintf(f, "\nScore: %g/%g\n", r->got, r->max);
}

/* ---- results.json (Gradescope) ------------------------------------------- */

static void json_entry(FILE *f, const char *stage_name, const char *name, double got,
                       double max, int passed, const char *output, const char *visibility)
{
	char *full = xprintf("%s/%s", stage_name, name);
	fputs("    {\"name\": ", f);
	put_json(f, full);
	fprintf(f, ", \"score\": %g, \"max_score\": %g, \"status\": \"%s\", \"output\": ", got,
	        max, passed ? "passed" : "failed");
	put_json(f, output);
	fputs(", \"visibility\": ", f);
	put_json(f, visibility);
	fputc('}', f);
	free(full);
}

static void json_stage(FILE *f, const stage *s, int *first)
{
	char *text = build_text(s);
	fputs(*first ? "" : ",\n", f);
	*first = 0;
	json_entry(f, s->name, "build", 0, 0, build_passed(s), text, "visible");
	free(text);
	for (size_t i = 0; i < s->ntests; i++) {
		const test *t = &s->tests[i];
		char *out = t->res == R_PASS ? xstrdup("pass")
		                             : xprintf("%s: %s", result_word(t->res), t->message);
		fputs(",\n", f);
		json_entry(f, s->name, t->name, t->res == R_PASS ? t->points : 0, t->points,
		           t->res == R_PASS, out, t->visibility);
		free(out);
	}
}

static void write_json(FILE *f, const report *r)
{
	char *summary = NULL;
	size_t len = 0;
	FILE *m = open_memstream(&summary, &len);
	if (!m)
		die("out of memory");
	for (size_t i = 0; i < r->nstages; i++) {
		char *status = stage_status(&r->stages[i]);
		fprintf(m, "%s: %g/%g (%s)\n", r->stages[i].name, r->stages[i].got,
		        r->stages[i].max, status);
		free(status);
	}
	put_hidden(m, r);
	fprintf(m, "Score: %g/%g\n", r->got, r->max);
	fclose(m);
	fprintf(f, "{\n  \"score\": %g,\n  \"output\": ", r->got);
	put_json(f, summary);
	fputs(",\n  \"visibility\": \"visible\",\n  \"stdout_visibility\": \"hidden\",\n"
	      "  \"tests\": [\n", f);
	int first = 1;
	for (size_t i = 0; i < r->nstages; i++)
		json_stage(f, &r->stages[i], &first);
	fputs("\n  ]\n}\n", f);
	free(summary);
}

/* ---- junit.xml ------------------------------------------------------------- */

static void count_bad(const stage *s, int *failures, int *errors)
{
	*failures = 0;
	*errors = build_passed(s) ? 0 : 1;
	for (size_t i = 0; i < s->ntests; i++) {
		*failures += s->tests[i].res == R_FAIL;
		*errors += s->tests[i].res != R_FAIL && s->tests[i].res != R_PASS;
	}
}

static void junit_case(FILE *f, const stage *s, const char *name, const char *kind,
                       const char *message, const char *body)
{
	fputs("    <testcase classname=\"", f);
	put_xml(f, s->name, 1);
	fputs("\" name=\"", f);
	put_xml(f, name, 1);
	fputs("\" time=\"0\"", f);
	if (!kind) {
		fputs("/>\n", f);
		return;
	}
	fprintf(f, ">\n      <%s type=\"%s\" message=\"", kind,
	        strcmp(kind, "failure") == 0 ? "fail" : "error");
	put_xml(f, message, 1);
	fputs("\">", f);
	put_xml(f, body, 0);
	fprintf(f, "</%s>\n    </testcase>\n", kind);
}

static void junit_stage(FILE *f, const stage *s)
{
	int failures, errors;
	count_bad(s, &failures, &errors);
	fputs("  <testsuite name=\"", f);
	put_xml(f, s->name, 1);
	fprintf(f, "\" tests=\"%zu\" failures=\"%d\" errors=\"%d\" skipped=\"0\">\n",
	        s->ntests + 1, failures, errors);
	char *text = build_text(s), *status = stage_status(s);
	junit_case(f, s, "build", build_passed(s) ? NULL : "error", status, text);
	free(text);
	free(status);
	for (size_t i = 0; i < s->ntests; i++) {
		const test *t = &s->tests[i];
		char *body = xprintf("%s (0/%g points)\n%s", result_word(t->res), t->points,
		                     t->message ? t->message : "");
		junit_case(f, s, t->name, t->res == R_PASS ? NULL
		                          : t->res == R_FAIL ? "failure" : "error",
		           t->message ? t->message : "", body);
		free(body);
	}
	fputs("  </testsuite>\n", f);
}

static void write_junit(FILE *f, const report *r)
{
	size_t tests = 0;
	int failures = 0, errors = 0;
	for (size_t i = 0; i < r->nstages; i++) {
		int sf, se;
		count_bad(&r->stages[i], &sf, &se);
		tests += r->stages[i].ntests + 1;
		failures += sf;
		errors += se;
	}
	fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", f);
	fprintf(f, "<testsuites name=\"lozenge\" tests=\"%zu\" failures=\"%d\" errors=\"%d\">\n",
	        tests, failures, errors);
	for (size_t i = 0; i < r->nstages; i++)
		junit_stage(f, &r->stages[i]);
	fputs("</testsuites>\n", f);
}

/* ---- results.tap ---------------------------------------------------------- */

static void tap_point(FILE *f, int n, const stage *s, const test *t)
{
	int ok = t->res == R_PASS;
	fprintf(f, "%s %d - %s/%s (%g/%g points)\n", ok ? "ok" : "not ok", n, s->name, t->name,
	        ok ? t->points : 0, t->points);
	if (ok)
		return;
	fprintf(f, "  ---\n  result: %s\n  points: 0\n  max_points: %g\n  message: ",
	        result_word(t->res), t->points);
	put_yaml(f, t->message ? t->message : "");
	fputs("\n  ...\n", f);
}

static void tap_build(FILE *f, int n, const stage *s)
{
	char *status = stage_status(s);
	fprintf(f, "%s %d - %s/build (", build_passed(s) ? "ok" : "not ok", n, s->name);
	put_plain(f, status, 0);
	fputs(")\n", f);
	free(status);
	if (build_passed(s))
		return;
	char *text = build_text(s);
	fputs("  ---\n  message: ", f);
	put_yaml(f, text);
	fputs("\n  ...\n", f);
	free(text);
}

static void write_tap(FILE *f, const report *r)
{
	size_t total = 0;
	for (size_t i = 0; i < r->nstages; i++)
		total += r->stages[i].ntests + 1;
	fprintf(f, "TAP version 13\n1..%zu\n", total);
	int n = 0;
	for (size_t i = 0; i < r->nstages; i++) {
		const stage *s = &r->stages[i];
		tap_build(f, ++n, s);
		for (size_t j = 0; j < s->ntests; j++)
			tap_point(f, ++n, s, &s->tests[j]);
	}
	fprintf(f, "# Score: %g/%g\n", r->got, r->max);
}

/* ---- files ---------------------------------------------------------------- */

typedef void writer(FILE *f, const report *r);

/* Write DIR/NAME through a temporary file, so a reader never sees half a report. */
static void write_file(const char *dir, const char *name, writer *w, const report *r)
{
	char *path = xprintf("%s/%s", dir, name), *tmp = xprintf("%s.tmp", path);
	FILE *f = fopen(tmp, "w");
	if (!f)
		die("cannot write %s: %s", tmp, strerror(errno));
	w(f, r);
	if (fclose(f) != 0)
		die("cannot write %s: %s", tmp, strerror(errno));
	if (rename(tmp, path) != 0)
		die("cannot rename %s to %s: %s", tmp, path, strerror(errno));
	free(path);
	free(tmp);
}

static void gradebook_header(FILE *f, const report *r)
{
	fputs("student", f);
	for (size_t i = 0; i < r->nstages; i++) {
		char *status = xprintf("%s status", r->stages[i].name);
		fputc(',', f);
		put_csv(f, r->stages[i].name);
		fputc(',', f);
		put_csv(f, status);
		free(status);
	}
	fputs(",total,max\n", f);
}

/* Append the student's row; a new or empty file gets the header first, an existing
 * one must have the same header (the same stages, in the same order). */
static void write_gradebook(const char *path, const char *student, const report *r)
{
	char *want = NULL, *have = NULL;
	size_t len = 0, cap = 0;
	FILE *m = open_memstream(&want, &len);
	if (!m)
		die("out of memory");
	gradebook_header(m, r);
	fclose(m);
	FILE *f = fopen(path, "a+");
	if (!f)
		die("cannot write the gradebook %s: %s", path, strerror(errno));
	rewind(f);
	if (getline(&have, &cap, f) < 0)
		fputs(want, f);
	else if (strcmp(have, want) != 0)
		die("%s has other stages than this grade (%s): start a new gradebook", path, want);
	put_csv(f, student);
	for (size_t i = 0; i < r->nstages; i++) {
		char *status = stage_status(&r->stages[i]);
		fprintf(f, ",%g,", r->stages[i].got);
		put_csv(f, status);
		free(status);
	}
	fprintf(f, ",%g,%g\n", r->got, r->max);
	if (fclose(f) != 0)
		die("cannot write the gradebook %s: %s", path, strerror(errno));
	free(want);
	free(have);
}

/* ---- main ------------------------------------------------------------------- */

static void strlist_free(strlist *l)
{
	for (size_t i = 0; i < l->n; i++)
		free(l->v[i]);
	free(l->v);
}

static void report_free(report *r)
{
	for (size_t i = 0; i < r->nstages; i++) {
		stage *s = &r->stages[i];
		for (size_t j = 0; j < s->ntests; j++) {
			free(s->tests[j].name);
			free(s->tests[j].visibility);
			free(s->tests[j].message);
		}
		free(s->tests);
		free(s->name);
		free(s->build_log);
		free(s->results_path);
		strlist_free(&s->notes);
		strlist_free(&s->refused);
		strlist_free(&s->said);
	}
	free(r->stages);
	free(r->title);
}

typedef struct {
	const char *out, *spec, *gradebook, *student;
	int quiet;
} options;

static _Noreturn void usage(void)
{
	fputs("usage: lz-report --out DIR [--spec FILE] [--gradebook CSV --student NAME] "
	      "[--quiet]\n(the spec format is described at the top of tests/grade/report.c)\n",
	      stderr);
	exit(2);
}

static options parse_args(int argc, char **argv)
{
	options o = {NULL, "-", NULL, NULL, 0};
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		int more = i + 1 < argc;
		if (strcmp(a, "--out") == 0 && more)
			o.out = argv[++i];
		else if (strcmp(a, "--spec") == 0 && more)
			o.spec = argv[++i];
		else if (strcmp(a, "--gradebook") == 0 && more)
			o.gradebook = argv[++i];
		else if (strcmp(a, "--student") == 0 && more)
			o.student = argv[++i];
		else if (strcmp(a, "--quiet") == 0)
			o.quiet = 1;
		else
			usage();
	}
	if (!o.out || (!o.gradebook != !o.student))
		usage();
	return o;
}

int main(int argc, char **argv)
{
	options o = parse_args(argc, argv);
	report r = {0};
	read_spec(&r, o.spec);
	score(&r);
	if (mkdir(o.out, 0755) != 0 && errno != EEXIST)
		die("cannot create %s: %s", o.out, strerror(errno));
	write_file(o.out, "report.txt", write_text, &r);
	write_file(o.out, "results.json", write_json, &r);
	write_file(o.out, "junit.xml", write_junit, &r);
	write_file(o.out, "results.tap", write_tap, &r);
	if (o.gradebook)
		write_gradebook(o.gradebook, o.student, &r);
	if (!o.quiet)
		write_text(stdout, &r);
	report_free(&r);
	return 0;
}
