/* lz/lesson.h — what every lesson's experiment driver does besides its experiment.
 *
 * A driver lessons/NN-name/X.c is run by lib/tools/lesson.sh as `X OUTDIR [--quick]`.
 * It prints what it ran with, writes data files (lz_data) and a flat JSON file of
 * headline figures (X.json: demo.sh shows it, its "check" member as a badge) into
 * OUTDIR, checks its results against known values — one line per check, ending in
 * "ok" or "CHECK FAILED" (lesson.sh looks for the latter) — and ends with one line
 *   check: <what it checked>: passed | FAILED (run `make test STAGE=NN`)
 * Exit status: 0 when every check passed, 1 when one failed, 2 on an error (bad
 * arguments, a file that cannot be written, a library error).
 *
 * A driver's main, in short:
 *   lz_lesson L;
 *   if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
 *           return 2;
 *   ... run; printf("... %s\n", ..., lz_lesson_check(&L, good)); ...
 *   if (write_data(&L) != LZ_OK || write_json(&L) != LZ_OK)
 *           return lz_lesson_error(&L);
 *   return lz_lesson_finish(&L, "orders within 0.1 of theory");
 *
 * Not part of any assignment: this is infrastructure for the lessons, like output.h.
 */
#ifndef LZ_LESSON_H
#define LZ_LESSON_H

#include <stdio.h>

#include "lz/output.h"

typedef struct {
	const char *name;    /* the driver, as messages name it: the last part of argv[0] */
	const char *outdir;  /* OUTDIR: every file the driver writes goes there */
	const char *stage;   /* "01": the stage whose tests the failure line points to */
	int quick;           /* 1 with --quick: the demo size */
	int failed;          /* checks failed so far (lz_lesson_check) */
	char path[4096];     /* the buffer of lz_lesson_path */
} lz_lesson;

/* Parse `NAME OUTDIR [--quick]` into L for stage `stage` ("01"; kept, not copied).
 * On anything else prints "usage: NAME OUTDIR [--quick]" on stderr and returns
 * LZ_EINVAL: the driver then exits with status 2. Makes OUTDIR when it is missing
 * (its parent must exist; LZ_EIO otherwise). Also installs lz_error_quiet as the
 * error handler, because the driver reports an error once (lz_lesson_error). O(1). */
int lz_lesson_args(int argc, char **argv, const char *stage, lz_lesson *L);

/* "OUTDIR/file", in L's buffer: valid until the next call with L. NULL with
 * lz_error (LZ_EINVAL) when it does not fit. */
const char *lz_lesson_path(lz_lesson *L, const char *file);

/* lz_data_open of OUTDIR/file (see lz/output.h for the header it writes). NULL with
 * lz_error on failure. */
lz_data *lz_lesson_data(lz_lesson *L, const char *file, const char *title, int ncol,
                        const char *const *names, const char *const *units);

/* Open OUTDIR/file for the headline figures and write its first member, "check":
 * lz_lesson_verdict(L) — so open it after the checks. NULL with lz_error on failure.
 * Close it with lz_json_end. */
lz_json *lz_lesson_json(lz_lesson *L, const char *file);

/* Open OUTDIR/file for writing text (a gnuplot script, say); NULL with lz_error
 * (LZ_EIO) on failure. Close it with lz_lesson_fclose. */
FILE *lz_lesson_fopen(lz_lesson *L, const char *file);

/* Close f, opened by lz_lesson_fopen(L, file): LZ_OK, or LZ_EIO with lz_error when a
 * write failed (disk full). */
int lz_lesson_fclose(const lz_lesson *L, FILE *f, const char *file);

/* Count one check: good != 0 passed, else L->failed goes up. Returns the word that
 * ends the line reporting it: "ok" or "CHECK FAILED". O(1). */
const char *lz_lesson_check(lz_lesson *L, int good);

/* "passed" when no check has failed so far, else "FAILED": the JSON "check" value. */
const char *lz_lesson_verdict(const lz_lesson *L);

/* Print "NAME: <lz_error_message()>" on stderr; returns 2, the exit status for an
 * error, so that main can `return lz_lesson_error(&L);`. */
int lz_lesson_error(const lz_lesson *L);

/* Print the last line, "check: <what>: passed" or "check: <what>: FAILED (run `make
 * test STAGE=NN`)", what formatted printf-style; returns the exit status, 0 when
 * every check passed and 1 otherwise. */
int lz_lesson_finish(const lz_lesson *L, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

#endif
