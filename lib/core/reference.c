/* reference.c — the literature tables of datasets/reference/ (lz/reference.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/reference.h"

#ifndef LZ_REFERENCE_DIR
#define LZ_REFERENCE_DIR "datasets/reference"
#endif

enum { FIELDS = 6, FIELD_MAX = 512 };

const char *lz_reference_dir(void)
{
	const char *dir = getenv("LZ_REFERENCE_DIR");
	return dir && *dir ? dir : LZ_REFERENCE_DIR;
}

/* Split one CSV line into its first FIELDS fields (quotes honoured). The number of
 * fields found. */
static int split(const char *line, char f[FIELDS][FIELD_MAX])
{
	int k = 0;
	const char *p = line;
	while (k < FIELDS) {
		size_t n = 0;
		int quoted = *p == '"';
		p += quoted;
		for (; *p && *p != '\n' && *p != '\r'; p++) {
			if (quoted && *p == '"') {
				if (p[1] != '"') {
					p++;
					break;
				}
				p++;
			} else if (!quoted && *p == ',') {
				break;
			}
			if (n + 1 < FIELD_MAX)
				f[k][n++] = *p;
		}
		f[k++][n] = '\0';
		if (*p != ',')
			break;
		p++;
	}
	return k;
}

/* The whole field as a number, or -1. */
static int number(const char *text, double *x)
{
	char *end;
	errno = 0;
	*x = strtod(text, &end);
	return end != text && *end == '\0' && errno == 0 ? 0 : -1;
}

/* Call `row` for every row of the table (after the header); stop at its first non-zero
 * return, which is returned (0 when every row was seen). */
typedef int row_fn(char f[FIELDS][FIELD_MAX], void *arg);

static int each_row(const char *file, row_fn *row, void *arg)
{
	char path[4096];
	snprintf(path, sizeof path, "%s/%s", lz_reference_dir(), file);
	FILE *in = fopen(path, "r");
	if (!in)
		return lz_error(LZ_EIO, "the reference table %s cannot be read: %s (set "
		                "LZ_REFERENCE_DIR to the tree's datasets/reference)", path,
		                strerror(errno));
	static char f[FIELDS][FIELD_MAX];
	char line[2048];
	int header = 1, st = 0;
	while (st == 0 && fgets(line, sizeof line, in)) {
		if (line[0] == '#' || line[0] == '\n')
			continue;
		if (header) {
			header = 0;
			continue;
		}
		if (split(line, f) == FIELDS)
			st = row(f, arg);
	}
	fclose(in);
	return st;
}

/* A row's value and uncertainty: LZ_OK, or LZ_ESYNTAX when either is not a number. */
static int row_numbers(const char *file, char f[FIELDS][FIELD_MAX], lz_ref *r)
{
	if (number(f[3], &r->value) || number(f[4], &r->err))
		return lz_error(LZ_ESYNTAX, "%s: the row %s, %s, %s holds '%s' ± '%s', not numbers",
		                file, f[0], f[1], f[2], f[3], f[4]);
	return LZ_OK;
}

enum { FOUND = -1 };  /* a row callback's "stop: done" (the LZ_E codes are positive) */

typedef struct {
	const char *file, *quantity, *dim, *state, *var;
	lz_ref *r;
	double *xs;
	size_t max, n;
} query;

static int match_one(char f[FIELDS][FIELD_MAX], void *arg)
{
	query *q = arg;
	if (strcmp(f[0], q->quantity) || strcmp(f[1], q->dim) || strcmp(f[2], q->state))
		return 0;
	int st = row_numbers(q->file, f, q->r);
	return st == LZ_OK ? FOUND : st;
}

int lz_reference(const char *file, const char *quantity, const char *dim, const char *state,
                 lz_ref *r)
{
	query q = {file, quantity, dim, state, NULL, r, NULL, 0, 0};
	int st = each_row(file, match_one, &q);
	if (st == 0)
		return lz_error(LZ_EINVAL, "%s/%s has no row '%s' for dim %s at '%s'",
		                lz_reference_dir(), file, quantity, dim, state);
	return st == FOUND ? LZ_OK : st;
}

static int match_table(char f[FIELDS][FIELD_MAX], void *arg)
{
	query *q = arg;
	size_t len = strlen(q->var);
	double x;
	if (strcmp(f[0], q->quantity) || strcmp(f[1], q->dim) || strncmp(f[2], q->var, len) ||
	    f[2][len] != '=' || number(f[2] + len + 1, &x) || q->n == q->max)
		return 0;
	int st = row_numbers(q->file, f, &q->r[q->n]);
	if (st == LZ_OK)
		q->xs[q->n++] = x;
	return st;
}

int lz_reference_table(const char *file, const char *quantity, const char *dim,
                       const char *var, double *xs, lz_ref *ys, size_t max, size_t *n)
{
	query q = {file, quantity, dim, NULL, var, ys, xs, max, 0};
	int st = each_row(file, match_table, &q);
	*n = q.n;
	if (st == 0 && q.n == 0)
		return lz_error(LZ_EINVAL, "%s/%s has no row '%s' for dim %s at %s=...",
		                lz_reference_dir(), file, quantity, dim, var);
	return st;
}

int lz_reference_at(const char *file, const char *quantity, const char *dim, const char *var,
                    double x, lz_ref *r)
{
	enum { MAX = 256 };
	double xs[MAX];
	lz_ref ys[MAX];
	size_t n;
	int st = lz_reference_table(file, quantity, dim, var, xs, ys, MAX, &n);
	if (st != LZ_OK)
		return st;
	for (size_t k = 0; k < n; k++)
		if (fabs(xs[k] - x) <= 1e-9) {
			*r = ys[k];
			return LZ_OK;
		}
	return lz_error(LZ_EINVAL, "%s/%s has no row '%s' for dim %s at %s=%g",
	                lz_reference_dir(), file, quantity, dim, var, x);
}
