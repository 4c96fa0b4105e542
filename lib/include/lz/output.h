/* lz/output.h — what a run writes: data files, summary.json, its directory, plots.
 *
 * Data files are whitespace columns under a '#' header that names every column and
 * its unit. summary.json is one flat JSON object. A run writes into a temporary
 * directory that replaces the output directory only when the run succeeded, so a
 * failed run never leaves a directory that looks finished.
 */
#ifndef LZ_OUTPUT_H
#define LZ_OUTPUT_H

#include <stddef.h>
#include <stdio.h>

/* ---- data files ---- */
typedef struct lz_data lz_data;

/* Open `path` for writing and write the header:
 *   # title
 *   # name1 [unit1]  name2 [unit2] ...
 * ncol in [1, 64]; units may be NULL or "" for dimensionless columns.
 * NULL with lz_error (LZ_EIO, LZ_EINVAL) on failure. */
lz_data *lz_data_open(const char *path, const char *title, int ncol,
                      const char *const *names, const char *const *units);
/* One row of ncol values (%.12g; non-finite values as nan/inf). */
void lz_data_row(lz_data *d, const double *values);
/* A '#' comment line in the body (e.g. a blank-line-separated block label). */
void lz_data_comment(lz_data *d, const char *text);
/* Close; LZ_EIO if any write failed. Frees d. */
int lz_data_close(lz_data *d);

/* ---- summary.json: one flat object, keys in the order written ---- */
typedef struct lz_json lz_json;

/* Start an object on an open stream (not closed by lz_json_end) or on a new file. */
lz_json *lz_json_begin(FILE *f);
lz_json *lz_json_open(const char *path);
/* Non-finite numbers are written as null; numbers use %.17g (round trip exact). */
void lz_json_num(lz_json *j, const char *key, double v);
void lz_json_int(lz_json *j, const char *key, long long v);
void lz_json_str(lz_json *j, const char *key, const char *v);  /* escaped */
void lz_json_bool(lz_json *j, const char *key, int v);
/* A value and its error bar: key and key_err. */
void lz_json_err(lz_json *j, const char *key, double v, double err);
/* Close the object; LZ_EIO if a write failed. Frees j (and closes the file
 * if lz_json_open made it). */
int lz_json_end(lz_json *j);

/* ---- a run's output directory ---- */
typedef struct {
	char final[4096];  /* where the results go when the run succeeds */
	char tmp[4096];    /* where they are written meanwhile: final + ".partial-PID" */
} lz_rundir;

/* Create the parents of `out` and the temporary directory. LZ_EINVAL, creating
 * nothing, when `out` is /, . or .., or exists and is not a run directory (a file, or
 * a non-empty directory without summary.json): lz never deletes what it did not
 * write (think of --out ~). */
int lz_rundir_begin(lz_rundir *d, const char *out);
/* tmp/name into buf (LZ_EINVAL if it does not fit). */
int lz_rundir_file(const lz_rundir *d, const char *name, char *buf, size_t size);
/* Replace `final` (removed recursively if it exists, after the same check as begin)
 * by the temporary directory. */
int lz_rundir_commit(lz_rundir *d);
/* Remove the temporary directory and everything in it; does nothing after a commit
 * or a failed begin, so a caller may call it on every failure path. */
void lz_rundir_abort(lz_rundir *d);

/* Remove a directory tree (like rm -rf); LZ_OK if it did not exist. */
int lz_rmtree(const char *path);

/* Run `gnuplot script` inside directory dir (script relative to dir). Returns LZ_OK,
 * or 1 without an error when gnuplot is not installed (the plot is then skipped),
 * or LZ_EIO when gnuplot failed. */
int lz_gnuplot(const char *dir, const char *script);

#endif
