/* lesson.c — arguments, files, checks and exit status of the experiment drivers. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"

int lz_lesson_args(int argc, char **argv, const char *stage, lz_lesson *L)
{
	const char *argv0 = argc > 0 && argv[0] ? argv[0] : "driver";
	const char *slash = strrchr(argv0, '/');
	memset(L, 0, sizeof *L);
	L->name = slash ? slash + 1 : argv0;
	L->stage = stage;
	if (argc < 2 || argc > 3 || (argc == 3 && strcmp(argv[2], "--quick") != 0)) {
		fprintf(stderr, "usage: %s OUTDIR [--quick]\n", argv0);
		return LZ_EINVAL;
	}
	L->outdir = argv[1];
	L->quick = argc == 3;
	/* A driver run by hand gets its directory made, as lesson.sh would. */
	if (mkdir(L->outdir, 0777) != 0 && errno != EEXIST) {
		fprintf(stderr, "%s: cannot make the output directory %s: %s\n", L->name,
		        L->outdir, strerror(errno));
		return LZ_EIO;
	}
	lz_set_error_handler(lz_error_quiet);
	return LZ_OK;
}

const char *lz_lesson_path(lz_lesson *L, const char *file)
{
	int len = snprintf(L->path, sizeof L->path, "%s/%s", L->outdir, file);
	if (len < 0 || (size_t)len >= sizeof L->path) {
		lz_error(LZ_EINVAL, "path '%s/%s' is longer than %zu bytes", L->outdir, file,
		         sizeof L->path - 1);
		return NULL;
	}
	return L->path;
}

lz_data *lz_lesson_data(lz_lesson *L, const char *file, const char *title, int ncol,
                        const char *const *names, const char *const *units)
{
	const char *path = lz_lesson_path(L, file);
	return path ? lz_data_open(path, title, ncol, names, units) : NULL;
}

lz_json *lz_lesson_json(lz_lesson *L, const char *file)
{
	const char *path = lz_lesson_path(L, file);
	lz_json *j = path ? lz_json_open(path) : NULL;
	if (j)
		lz_json_str(j, "check", lz_lesson_verdict(L));
	return j;
}

FILE *lz_lesson_fopen(lz_lesson *L, const char *file)
{
	const char *path = lz_lesson_path(L, file);
	FILE *f = path ? fopen(path, "w") : NULL;
	if (path && !f)
		lz_error(LZ_EIO, "cannot write %s: %s", path, strerror(errno));
	return f;
}

int lz_lesson_fclose(const lz_lesson *L, FILE *f, const char *file)
{
	int bad = ferror(f);
	bad |= fclose(f) != 0;
	return bad ? lz_error(LZ_EIO, "cannot write %s/%s", L->outdir, file) : LZ_OK;
}

const char *lz_lesson_check(lz_lesson *L, int good)
{
	if (!good)
		L->failed++;
	return good ? "ok" : "CHECK FAILED";
}

const char *lz_lesson_verdict(const lz_lesson *L)
{
	return L->failed ? "FAILED" : "passed";
}

int lz_lesson_error(const lz_lesson *L)
{
	fprintf(stderr, "%s: %s\n", L->name, lz_error_message());
	return 2;
}

int lz_lesson_finish(const lz_lesson *L, const char *fmt, ...)
{
	va_list ap;
	printf("check: ");
	va_start(ap, fmt);
	vprintf(fmt, ap);
	va_end(ap);
	if (L->failed)
		printf(": FAILED (run `make test STAGE=%s`)\n", L->stage);
	else
		printf(": passed\n");
	return L->failed ? 1 : 0;
}
