/* support.c — see support.h. */
#include <dirent.h>
#include <errno.h>
#include <stdarg.h>
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

const char *lzt_tmpdir(void)
{
	static char dir[64];
	snprintf(dir, sizeof dir, "/tmp/lz-test-XXXXXX");
	ck_assert_msg(mkdtemp(dir) != NULL, "cannot make a temporary directory: %s",
	              strerror(errno));
	return dir;
}

const char *lzt_path(const char *dir, const char *name)
{
	static char pool[32][1024];
	static int next;
	char *p = pool[next++ % 32];
	int n = snprintf(p, sizeof pool[0], "%s/%s", dir, name);
	ck_assert_msg(n > 0 && (size_t)n < sizeof pool[0], "test path too long");
	return p;
}

void lzt_write(const char *path, const void *data, size_t n)
{
	FILE *f = fopen(path, "wb");
	ck_assert_msg(f != NULL, "cannot write test file %s: %s", path, strerror(errno));
	ck_assert_msg(fwrite(data, 1, n, f) == n && fclose(f) == 0,
	              "writing test file %s failed", path);
}

void lzt_write_str(const char *path, const char *text)
{
	lzt_write(path, text, strlen(text));
}

char *lzt_slurp(const char *path, size_t *n)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return NULL;
	size_t cap = 4096, len = 0;
	char *buf = malloc(cap + 1);
	for (size_t got; buf && (got = fread(buf + len, 1, cap - len, f)) > 0;) {
		len += got;
		if (len == cap) {
			char *bigger = realloc(buf, 2 * cap + 1);
			if (!bigger)
				free(buf);
			buf = bigger;
			cap *= 2;
		}
	}
	fclose(f);
	if (buf)
		buf[len] = '\0';
	if (n)
		*n = len;
	return buf;
}

int lzt_exists(const char *path)
{
	struct stat st;
	return lstat(path, &st) == 0;
}

int lzt_count_matching(const char *dir, const char *part)
{
	DIR *d = opendir(dir);
	int count = 0;
	for (struct dirent *e; d && (e = readdir(d));)
		count += strstr(e->d_name, part) != NULL;
	if (d)
		closedir(d);
	return count;
}

/* ---- JSON ---- */

typedef struct {
	const char *p;
	char *err;
	size_t errsize;
} lzt_reader;

static int lzt_fail(lzt_reader *r, const char *what)
{
	snprintf(r->err, r->errsize, "%s at '%.20s'", what, r->p);
	return -1;
}

static void lzt_ws(lzt_reader *r)
{
	while (*r->p == ' ' || *r->p == '\t' || *r->p == '\n' || *r->p == '\r')
		r->p++;
}

static int lzt_hex4(const char *p, unsigned *v)
{
	*v = 0;
	for (int i = 0; i < 4; i++) {
		char c = p[i];
		int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
		      : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
		if (d < 0)
			return -1;
		*v = *v << 4 | (unsigned)d;
	}
	return 0;
}

/* A string into out (decoded, UTF-8), at most size - 1 bytes. */
static int lzt_string(lzt_reader *r, char *out, size_t size)
{
	size_t n = 0;
	if (*r->p != '"')
		return lzt_fail(r, "expected a string");
	for (r->p++; *r->p != '"'; r->p++) {
		unsigned char c = (unsigned char)*r->p;
		unsigned u = c;
		if (c == '\0')
			return lzt_fail(r, "unterminated string");
		if (c < 0x20)
			return lzt_fail(r, "raw control character in a string");
		if (c == '\\') {
			char e = *++r->p;
			const char *from = "\"\\/bfnrt", *to = "\"\\/\b\f\n\r\t";
			const char *hit = e ? strchr(from, e) : NULL;
			if (hit)
				u = (unsigned char)to[hit - from];
			else if (e == 'u' && lzt_hex4(r->p + 1, &u) == 0)
				r->p += 4;
			else
				return lzt_fail(r, "bad escape");
		}
		if (n + 4 >= size)
			return lzt_fail(r, "string too long for the checker");
		if (u < 0x80 || c != '\\') {
			out[n++] = (char)u;
		} else if (u < 0x800) {
			out[n++] = (char)(0xc0 | u >> 6);
			out[n++] = (char)(0x80 | (u & 0x3f));
		} else {
			out[n++] = (char)(0xe0 | u >> 12);
			out[n++] = (char)(0x80 | (u >> 6 & 0x3f));
			out[n++] = (char)(0x80 | (u & 0x3f));
		}
	}
	r->p++;
	out[n] = '\0';
	return 0;
}

static int lzt_digits(lzt_reader *r)
{
	if (*r->p < '0' || *r->p > '9')
		return lzt_fail(r, "expected a digit");
	while (*r->p >= '0' && *r->p <= '9')
		r->p++;
	return 0;
}

/* The number grammar of RFC 8259: no '+', no leading zeros, no hex, no nan. */
static int parse_number(lzt_reader *r, lzt_member *m)
{
	const char *start = r->p;
	if (*r->p == '-')
		r->p++;
	if (*r->p == '0')
		r->p++;
	else if (lzt_digits(r) != 0)
		return -1;
	if (*r->p == '.') {
		r->p++;
		if (lzt_digits(r) != 0)
			return -1;
	}
	if (*r->p == 'e' || *r->p == 'E') {
		r->p++;
		if (*r->p == '+' || *r->p == '-')
			r->p++;
		if (lzt_digits(r) != 0)
			return -1;
	}
	snprintf(m->text, sizeof m->text, "%.*s", (int)(r->p - start), start);
	m->num = strtod(m->text, NULL);
	m->kind = LZT_NUM;
	return 0;
}

static int lzt_value(lzt_reader *r, lzt_member *m)
{
	static const struct {
		const char *word;
		lzt_kind kind;
	} words[] = {{"true", LZT_TRUE}, {"false", LZT_FALSE}, {"null", LZT_NULL}};
	if (*r->p == '"') {
		m->kind = LZT_STR;
		return lzt_string(r, m->text, sizeof m->text);
	}
	for (int i = 0; i < 3; i++)
		if (strncmp(r->p, words[i].word, strlen(words[i].word)) == 0) {
			r->p += strlen(words[i].word);
			m->kind = words[i].kind;
			return 0;
		}
	if (*r->p == '-' || (*r->p >= '0' && *r->p <= '9'))
		return parse_number(r, m);
	return lzt_fail(r, "expected a flat value (string, number, true, false, null)");
}

static int lzt_object(lzt_reader *r, lzt_json *j)
{
	lzt_ws(r);
	if (*r->p++ != '{')
		return lzt_fail(r, "expected '{'");
	lzt_ws(r);
	if (*r->p == '}') {
		r->p++;
		return 0;
	}
	for (;;) {
		if (j->n == (int)(sizeof j->m / sizeof j->m[0]))
			return lzt_fail(r, "too many members for the checker");
		lzt_member *m = &j->m[j->n];
		lzt_ws(r);
		if (lzt_string(r, m->key, sizeof m->key) != 0)
			return -1;
		if (lzt_json_get(j, m->key)) {
			snprintf(r->err, r->errsize, "the key '%s' appears twice", m->key);
			return -1;
		}
		lzt_ws(r);
		if (*r->p++ != ':')
			return lzt_fail(r, "expected ':'");
		lzt_ws(r);
		if (lzt_value(r, m) != 0)
			return -1;
		j->n++;
		lzt_ws(r);
		if (*r->p == '}') {
			r->p++;
			return 0;
		}
		if (*r->p++ != ',')
			return lzt_fail(r, "expected ',' or '}'");
	}
}

lzt_json *lzt_json_parse(const char *text, char *err, size_t errsize)
{
	lzt_json *j = calloc(1, sizeof *j);
	lzt_reader r = {text, err, errsize};
	ck_assert_msg(j != NULL, "out of memory");
	if (lzt_object(&r, j) == 0) {
		lzt_ws(&r);
		if (*r.p == '\0')
			return j;
		lzt_fail(&r, "text after the object");
	}
	free(j);
	return NULL;
}

const lzt_member *lzt_json_get(const lzt_json *j, const char *key)
{
	for (int i = 0; i < j->n; i++)
		if (strcmp(j->m[i].key, key) == 0)
			return &j->m[i];
	return NULL;
}

lzt_json *lzt_summary(const char *run_dir)
{
	char err[128], *text = lzt_slurp(lzt_path(run_dir, "summary.json"), NULL);
	ck_assert_msg(text != NULL, "no summary.json in %s", run_dir);
	lzt_json *j = lzt_json_parse(text, err, sizeof err);
	ck_assert_msg(j != NULL, "summary.json is not valid JSON (%s):\n%s", err, text);
	free(text);
	return j;
}

double lzt_num(const lzt_json *j, const char *key)
{
	const lzt_member *m = lzt_json_get(j, key);
	ck_assert_msg(m && m->kind == LZT_NUM, "summary.json has no number '%s'", key);
	return m->num;
}

lz_scene *lzt_scene(const char *path, const char *overrides)
{
	lz_scene *s = path ? lz_scene_read(path) : lz_scene_new("test");
	ck_assert_msg(s != NULL, "%s", lz_error_message());
	char buf[1024];
	snprintf(buf, sizeof buf, "%s", overrides);
	for (char *tok = strtok(buf, ";"); tok; tok = strtok(NULL, ";"))
		ck_assert_msg(lz_scene_set(s, tok, "test") == LZ_OK, "override '%s': %s", tok,
		              lz_error_message());
	return s;
}

int lzt_bind(const lz_method *m, const char *overrides)
{
	lz_scene *s = lzt_scene(NULL, overrides);
	int status = lz_method_bind(m, s);
	lz_scene_free(s);
	return status;
}

/* The method's run with PATH emptied, so that no gnuplot is found. */
static int lzt_run_without_plots(const lz_method *m, const lz_scene *s, lz_run *run)
{
	const char *path_env = getenv("PATH");
	char *saved = path_env ? strdup(path_env) : NULL;
	setenv("PATH", "", 1);
	int status = m->run(s, run);
	if (saved)
		setenv("PATH", saved, 1);
	free(saved);
	return status;
}

int lzt_run(const lz_method *m, const char *path, const char *overrides, const char *out)
{
	lz_scene *s = lzt_scene(path, overrides);
	int status = lz_method_bind(m, s);
	lz_rundir d;
	if (status == LZ_OK)
		status = lz_rundir_begin(&d, out);
	if (status != LZ_OK) {
		lz_scene_free(s);
		return status;
	}
	char file[4200];
	ck_assert(lz_rundir_file(&d, "summary.json", file, sizeof file) == LZ_OK);
	lz_json *j = lz_json_open(file);
	ck_assert(j != NULL);
	lz_scene_json(s, j);
	lz_run run = {&d, j, 1};
	status = lzt_run_without_plots(m, s, &run);
	int written = lz_json_end(j);
	if (status == LZ_OK)
		status = written != LZ_OK ? written : lz_rundir_commit(&d);
	if (status != LZ_OK)
		lz_rundir_abort(&d);
	lz_scene_free(s);
	return status;
}

/* ---- the lz command in-process ---- */

char lzt_out[16384], lzt_err[16384];

/* Everything written to f (a tmpfile) into buf; f is closed. */
static void lzt_take(FILE *f, char *buf, size_t size)
{
	rewind(f);
	size_t n = fread(buf, 1, size - 1, f);
	buf[n] = '\0';
	fclose(f);
}

int lzt_cli(const char *arg, ...)
{
	char *argv[32] = {"lz"};
	int argc = 1;
	va_list ap;
	va_start(ap, arg);
	for (const char *a = arg; a && argc < 31; a = va_arg(ap, const char *))
		argv[argc++] = (char *)a;
	va_end(ap);
	argv[argc] = NULL;
	FILE *out = tmpfile(), *err = tmpfile();
	ck_assert_msg(out && err, "no temporary files for the output of lz");
	fflush(stdout);
	fflush(stderr);
	int keep_out = dup(STDOUT_FILENO), keep_err = dup(STDERR_FILENO);
	ck_assert(dup2(fileno(out), STDOUT_FILENO) >= 0 && dup2(fileno(err), STDERR_FILENO) >= 0);
	int rc = lz_cli_main(argc, argv);
	fflush(stdout);
	fflush(stderr);
	dup2(keep_out, STDOUT_FILENO);
	dup2(keep_err, STDERR_FILENO);
	close(keep_out);
	close(keep_err);
	lzt_take(out, lzt_out, sizeof lzt_out);
	lzt_take(err, lzt_err, sizeof lzt_err);
	return rc;
}
