/* run_table.c — the table after a run (run_table.h), read back from summary.json.
 *
 * The summary is lz_json's own output (lz/output.h): one member per line, `"key":
 * value`, the value a number, null, true, false or a string. The reader relies on that
 * form and nothing more general.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "run_table.h"

#define SUMMARY_MAX (1 << 20)  /* bytes: a summary is a few hundred members */
#define MEMBERS_MAX 1024

typedef struct {
	char *key, *value;  /* both inside the summary's text, unescaped in place */
	int string;         /* 1: the value was a JSON string */
} member;

typedef struct {
	char *text;
	member m[MEMBERS_MAX];
	int n;
} summary;

/* ---- numbers ± errors ---- */

/* Decimals that show err to 2 significant digits (negative: tens, hundreds, ...). */
static int decimals_of(double err)
{
	int dec = 1 - (int)floor(log10(err));
	/* 0.0996 has 2 significant digits as 0.10, one decimal fewer */
	if (round(err * pow(10, dec)) >= 100)
		dec--;
	return dec;
}

void lz_format_err(double v, double err, char *buf, size_t size)
{
	if (!isfinite(v)) {
		snprintf(buf, size, "null");
		return;
	}
	if (!(err > 0) || !isfinite(err)) {
		snprintf(buf, size, "%.6g", v);
		return;
	}
	int dec = decimals_of(err);
	int e = (int)floor(log10(fmax(fabs(v), err)));
	if (e + dec >= 9) {  /* an error below the 9th digit is round-off: no digits to read */
		snprintf(buf, size, "%.9g ± %.2g", v, err);
	} else if (e >= 6 || e <= -5) {  /* a common power of ten keeps the digits readable */
		double scale = pow(10, -e);
		int d = dec + e > 0 ? dec + e : 0;
		snprintf(buf, size, "(%.*f ± %.*f)e%d", d, v * scale, d, err * scale, e);
	} else if (dec >= 0) {
		snprintf(buf, size, "%.*f ± %.*f", dec, v, dec, err);
	} else {
		double unit = pow(10, -dec);
		snprintf(buf, size, "%.0f ± %.0f", round(v / unit) * unit, round(err / unit) * unit);
	}
}

/* A reference to compare with v ± err: at the same decimal place when that is fixed. */
static void format_like(double ref, double v, double err, char *buf, size_t size)
{
	int e = isfinite(v) ? (int)floor(log10(fmax(fabs(v), err))) : 0;
	int dec = err > 0 && isfinite(err) ? decimals_of(err) : -1;
	if (dec >= 0 && e < 6 && e > -5 && e + dec < 9)
		snprintf(buf, size, "%.*f", dec, ref);
	else
		snprintf(buf, size, "%.6g", ref);
}

/* ---- reading summary.json ---- */

/* Unescape the JSON string starting after the quote at p, in place; the end, after
 * the closing quote, or NULL when there is none. */
static char *unescape(char *p)
{
	char *w = p;
	for (; *p && *p != '"'; p++) {
		if (*p != '\\') {
			*w++ = *p;
			continue;
		}
		p++;
		if (*p == 'u' && strlen(p) >= 5) {  /* lz_json escapes control characters */
			*w++ = (char)strtol((char[]){p[1], p[2], p[3], p[4], 0}, NULL, 16);
			p += 4;
		} else if (*p) {
			*w++ = *p == 'n' ? '\n' : *p == 't' ? '\t' : *p;
		} else {
			return NULL;
		}
	}
	if (*p != '"')
		return NULL;
	*w = '\0';
	return p + 1;
}

/* One line `"key": value[,]` into *m; 0 when the line is not a member. */
static int parse_member(char *line, member *m)
{
	line += strspn(line, " \t");
	if (*line != '"')
		return 0;
	m->key = line + 1;
	char *p = unescape(m->key);
	if (!p || strncmp(p, ": ", 2) != 0)
		return 0;
	p += 2;
	m->string = *p == '"';
	if (m->string)
		return (m->value = p + 1, unescape(p + 1) != NULL);
	m->value = p;
	p[strcspn(p, ",\r")] = '\0';
	return 1;
}

static int summary_read(const char *path, summary *s)
{
	FILE *f = fopen(path, "rb");
	s->n = 0;
	s->text = f ? malloc(SUMMARY_MAX + 1) : NULL;
	size_t len = s->text ? fread(s->text, 1, SUMMARY_MAX, f) : 0;
	if (f)
		fclose(f);
	if (!s->text)
		return lz_error(LZ_EIO, "cannot read the summary '%s'", path);
	s->text[len] = '\0';
	for (char *line = strtok(s->text, "\n"); line && s->n < MEMBERS_MAX;
	     line = strtok(NULL, "\n"))
		s->n += parse_member(line, &s->m[s->n]);
	return LZ_OK;
}

static const member *summary_get(const summary *s, const char *key)
{
	for (int i = 0; key && i < s->n; i++)
		if (strcmp(s->m[i].key, key) == 0)
			return &s->m[i];
	return NULL;
}

/* A member's number; NaN for null, a string or a missing key. */
static double summary_num(const summary *s, const char *key)
{
	const member *m = summary_get(s, key);
	return m && !m->string && strcmp(m->value, "null") != 0 ? strtod(m->value, NULL) : NAN;
}

/* ---- the table ---- */

enum { COLS = 3, CELL = 160, ROWS_MAX = 64 };

/* One headline row: its value (± error) and its reference (source). */
static void headline_row(const summary *s, const lz_headline *h, char cell[COLS][CELL])
{
	const member *m = summary_get(s, h->key);
	char err_key[128];
	snprintf(err_key, sizeof err_key, "%s_err", h->key);
	double v = summary_num(s, h->key), err = summary_num(s, err_key);
	snprintf(cell[0], CELL, "%s", h->key);
	if (m->string || strcmp(m->value, "true") == 0 || strcmp(m->value, "false") == 0)
		snprintf(cell[1], CELL, "%s", m->value);
	else
		lz_format_err(v, err, cell[1], CELL);
	double ref = summary_num(s, h->ref);
	const member *source = summary_get(s, h->source);
	cell[2][0] = '\0';
	if (isfinite(ref))
		format_like(ref, v, err, cell[2], CELL);
	if (isfinite(ref) && source && source->string)
		snprintf(cell[2] + strlen(cell[2]), CELL - strlen(cell[2]), " (%s)", source->value);
}

int lz_text_width(const char *t)
{
	int w = 0;
	for (; *t; t++)
		w += ((unsigned char)*t & 0xc0) != 0x80;
	return w;
}

static void print_rows(FILE *f, char (*cell)[COLS][CELL], int rows)
{
	int width[COLS] = {0};
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < COLS; c++)
			if (lz_text_width(cell[r][c]) > width[c])
				width[c] = lz_text_width(cell[r][c]);
	for (int r = 0; r < rows; r++) {
		fprintf(f, " ");
		for (int c = 0; c < COLS; c++) {
			int last = c == COLS - 1 || !cell[r][c + 1][0];
			fprintf(f, " %s%*s", cell[r][c], last ? 0 : width[c] - lz_text_width(cell[r][c]), "");
			if (last)
				break;
			fputc(' ', f);
		}
		fputc('\n', f);
	}
}

int lz_run_table(FILE *f, const lz_method *m, const char *name, const char *path)
{
	summary *s = malloc(sizeof *s);
	char (*cell)[COLS][CELL] = calloc(ROWS_MAX, sizeof *cell);
	if (!s || !cell) {
		free(s);
		free(cell);
		return lz_error(LZ_ENOMEM, "no memory for the table of results");
	}
	int rc = summary_read(path, s), rows = 1;
	snprintf(cell[0][0], CELL, "quantity");
	snprintf(cell[0][1], CELL, "value");
	snprintf(cell[0][2], CELL, "reference");
	for (const lz_headline *h = m->headline; rc == LZ_OK && h && h->key && rows < ROWS_MAX - 2;
	     h++)
		if (summary_get(s, h->key))
			headline_row(s, h, cell[rows++]);
	for (const lz_speed *v = m->speed; rc == LZ_OK && v && v->key; v++) {
		double x = summary_num(s, v->key);
		if (isfinite(x)) {
			snprintf(cell[rows][0], CELL, "speed");
			snprintf(cell[rows++][1], CELL, "%.3g %s", x, v->unit);
			break;
		}
	}
	const member *seed = summary_get(s, "seed");
	if (rc == LZ_OK && seed) {
		snprintf(cell[rows][0], CELL, "seed");
		snprintf(cell[rows++][1], CELL, "%s", seed->value);
	}
	int refs = 0;
	for (int r = 1; r < rows; r++)
		refs |= cell[r][2][0] != '\0';
	if (!refs)  /* no reference column */
		cell[0][2][0] = '\0';
	if (rc == LZ_OK) {
		fprintf(f, "%s (%s)\n", name, m->name);
		print_rows(f, cell, rows);
	}
	free(s->text);
	free(s);
	free(cell);
	return rc;
}
