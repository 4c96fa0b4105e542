/* support.h — helpers shared by the tests of the library infrastructure:
 * temporary directories and files, and a strict little JSON reader to check what
 * the writers produce without trusting the writers. */
#ifndef LZ_TESTS_LIB_SUPPORT_H
#define LZ_TESTS_LIB_SUPPORT_H

#include <stddef.h>

/* A fresh directory /tmp/lz-test-XXXXXX (fails the test if it cannot be made). */
const char *lzt_tmpdir(void);
/* dir/name in one of 32 rotating static buffers: valid for the next 31 calls, and
 * nothing to free (so that tests stay leak-free under LeakSanitizer). */
const char *lzt_path(const char *dir, const char *name);
/* Write n bytes to path (fails the test on error). */
void lzt_write(const char *path, const void *data, size_t n);
void lzt_write_str(const char *path, const char *text);
/* The whole file, NUL-terminated, malloc'd; NULL if it cannot be read. */
char *lzt_slurp(const char *path, size_t *n);
/* 1 if path exists (as anything, links not followed). */
int lzt_exists(const char *path);
/* Entries of dir whose names contain `part` (e.g. ".partial-"). */
int lzt_count_matching(const char *dir, const char *part);

/* ---- scenes and runs of a method ---- */
struct lz_method;
struct lz_scene;

/* A scene: the file `path` (NULL: an empty scene named "test") with the ';'-separated
 * key=value overrides ("a=1;b=2") applied (fails the test if the file cannot be read
 * or an override is malformed). Free with lz_scene_free. */
struct lz_scene *lzt_scene(const char *path, const char *overrides);
/* The status of binding lzt_scene(NULL, overrides) to method m (the message is
 * lz_error_message()). */
int lzt_bind(const struct lz_method *m, const char *overrides);
/* Run method m on lzt_scene(path, overrides) into the run directory `out` as `lz run`
 * does — bind, summary.json with the parameters, run, commit — but without plots
 * (PATH is emptied while it runs). Returns the status of the bind or of the run (the
 * message is lz_error_message()); on success out/summary.json is there, on failure
 * nothing is left behind. */
int lzt_run(const struct lz_method *m, const char *path, const char *overrides,
            const char *out);

/* ---- the lz command, in-process ---- */

/* What the last lzt_cli call wrote on stdout and on stderr (truncated to 16 KiB). */
extern char lzt_out[16384], lzt_err[16384];
/* lz_cli_main on the NULL-terminated arguments after "lz"; stdout and stderr are
 * captured into lzt_out and lzt_err. Returns the exit status. */
int lzt_cli(const char *arg, ...);

/* ---- a flat JSON object, read strictly (RFC 8259 grammar) ---- */
typedef enum { LZT_NUM, LZT_STR, LZT_TRUE, LZT_FALSE, LZT_NULL } lzt_kind;
typedef struct {
	char key[128];
	lzt_kind kind;
	double num;       /* LZT_NUM */
	char text[1024];  /* LZT_STR decoded to UTF-8; LZT_NUM the number as written */
} lzt_member;
typedef struct {
	int n;
	lzt_member m[256];
} lzt_json;

/* Parse text as one flat object; NULL with a reason in err when it is not valid JSON
 * (or has duplicate keys, or nested values). Free with free(). */
lzt_json *lzt_json_parse(const char *text, char *err, size_t errsize);
const lzt_member *lzt_json_get(const lzt_json *j, const char *key);
/* RUN_DIR/summary.json parsed (fails the test if it is missing or not JSON). */
lzt_json *lzt_summary(const char *run_dir);
/* The number under key (fails the test if there is none). */
double lzt_num(const lzt_json *j, const char *key);

#endif
