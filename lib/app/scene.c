/* scene.c — scene files: read `key = value` lines, then bind them to a method's table.
 *
 * Reading checks only the form of the file; binding checks every value against the
 * key table. Each entry remembers where it came from ("water.scene:7" or "command
 * line") so that every message points at the line to fix.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/rng.h"
#include "scene.h"

#define LZ_SCENE_LINE_MAX 4096       /* bytes in one line */
#define LZ_SCENE_FILE_MAX (1 << 20)  /* bytes in one file: a scene is a few lines */
#define LZ_SCENE_KEYS_MAX 1024       /* keeps the duplicate search cheap */

typedef struct {
	char *key, *value;
	char *where;  /* "FILE:LINE" or the override's origin, for messages */
	int line;     /* line number in the file; 0 for an override */
	int unset;    /* 1: unset (`key=`, or a file value an override of its group beat):
	                 kept only so that bind can report an unknown key */
} lz_entry;

/* A key of the bound method's table, parsed. */
typedef struct {
	const char *text;   /* the value as text (given or default); NULL: no value */
	int entry;          /* index of the entry that gave it; -1: the default */
	double real;        /* REAL and INT */
	long long integer;  /* INT; SEED: the seed used; BOOL: 0/1; ENUM: the index */
	char *path;         /* PATH: the resolved file name (owned); text points at it */
} lz_value;

struct lz_scene {
	char *name;
	char *origin;  /* the file's path (or the name): the place of whole-scene messages */
	char *dir;     /* the file's directory, the base of its relative paths; NULL: "." */
	lz_entry *e;
	size_t n, cap;
	const lz_key_table *t;  /* the table of a successful bind, else NULL */
	lz_value *v;            /* one per key of the table */
};

/* ---- reading ---- */

/* 1 when the n bytes are text: valid UTF-8 without control characters except tab. */
static int is_text(const unsigned char *p, size_t n)
{
	for (size_t i = 0; i < n;) {
		unsigned c = p[i], cp, min;
		size_t len;
		if (c < 0x80) {
			if ((c < 0x20 && c != '\t') || c == 0x7f)
				return 0;
			i++;
			continue;
		}
		if (c >= 0xc2 && c <= 0xdf)
			len = 2, cp = c & 0x1f, min = 0x80;
		else if ((c & 0xf0) == 0xe0)
			len = 3, cp = c & 0x0f, min = 0x800;
		else if (c >= 0xf0 && c <= 0xf4)
			len = 4, cp = c & 0x07, min = 0x10000;
		else
			return 0;
		if (i + len > n)
			return 0;
		for (size_t k = 1; k < len; k++) {
			if ((p[i + k] & 0xc0) != 0x80)
				return 0;
			cp = cp << 6 | (p[i + k] & 0x3f);
		}
		/* Overlong forms, UTF-16 surrogates and code points past Unicode. */
		if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff))
			return 0;
		i += len;
	}
	return 1;
}

static char *trim(char *s)
{
	while (*s == ' ' || *s == '\t')
		s++;
	size_t n = strlen(s);
	while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t'))
		s[--n] = '\0';
	return s;
}

static int is_word(const char *s)
{
	for (; *s; s++)
		if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_'))
			return 0;
	return 1;
}

/* Split one line (len bytes at raw, no newline) into key and value, copied into buf
 * (LZ_SCENE_LINE_MAX + 1 bytes). Returns 1 for an assignment, 0 for a blank or
 * comment line, or an error code; `where` starts every message. An empty value is an
 * error unless may_be_empty (an override that unsets). */
static int parse_line(const char *raw, size_t len, const char *where, int may_be_empty,
                      char *buf, char **key, char **value)
{
	if (len > 0 && raw[len - 1] == '\r')  /* a file saved with CRLF line ends */
		len--;
	if (len > LZ_SCENE_LINE_MAX)
		return lz_error(LZ_ESYNTAX, "%s: line longer than %d bytes", where,
		                LZ_SCENE_LINE_MAX);
	if (!is_text((const unsigned char *)raw, len))
		return lz_error(LZ_ESYNTAX, "%s: not a text line (binary data?)", where);
	memcpy(buf, raw, len);
	buf[len] = '\0';
	char *hash = strchr(buf, '#');
	if (hash)
		*hash = '\0';
	char *line = trim(buf);
	if (!*line)
		return 0;
	char *eq = strchr(line, '=');
	if (!eq)
		return lz_error(LZ_ESYNTAX, "%s: expected 'key = value', found '%s'", where, line);
	*eq = '\0';
	*key = trim(line);
	*value = trim(eq + 1);
	if (!**key)
		return lz_error(LZ_ESYNTAX, "%s: no key before '='", where);
	if (!is_word(*key))
		return lz_error(LZ_ESYNTAX, "%s: key '%s' must be one word of a-z, 0-9 and _",
		                where, *key);
	if (!**value && !may_be_empty)
		return lz_error(LZ_ESYNTAX, "%s: key '%s' has no value", where, *key);
	return 1;
}

/* The entry of key, unset or not, or -1. */
static int scene_entry(const lz_scene *s, const char *key)
{
	for (size_t i = 0; i < s->n; i++)
		if (strcmp(s->e[i].key, key) == 0)
			return (int)i;
	return -1;
}

/* The entry that gives key a value, or -1 (none, or unset). */
static int scene_find(const lz_scene *s, const char *key)
{
	int i = scene_entry(s, key);
	return i >= 0 && !s->e[i].unset ? i : -1;
}

void lz_scene_unbind(lz_scene *s)
{
	for (size_t i = 0; s->v && i < s->t->n; i++)
		free(s->v[i].path);
	free(s->v);
	s->v = NULL;
	s->t = NULL;
}

/* Set key = value from `where` (line 0: an override, which replaces an earlier
 * value, and unsets the key when the value is empty; otherwise a second value for a
 * key is an error). */
static int scene_put(lz_scene *s, const char *key, const char *value, const char *where,
                        int line)
{
	int i = scene_entry(s, key);
	if (i >= 0 && line > 0)
		return lz_error(LZ_ESYNTAX, "%s: key '%s' given twice (first at line %d)", where,
		                key, s->e[i].line);
	if (i < 0 && s->n == LZ_SCENE_KEYS_MAX)
		return lz_error(LZ_ESYNTAX, "%s: more than %d keys: not a scene", where,
		                LZ_SCENE_KEYS_MAX);
	if (i < 0 && s->n == s->cap) {
		size_t cap = s->cap ? 2 * s->cap : 16;
		lz_entry *e = realloc(s->e, cap * sizeof *e);
		if (!e)
			return lz_error(LZ_ENOMEM, "%s: no memory for key '%s'", where, key);
		s->e = e;
		s->cap = cap;
	}
	char *k = strdup(key), *v = strdup(value), *w = strdup(where);
	if (!k || !v || !w) {
		free(k);
		free(v);
		free(w);
		return lz_error(LZ_ENOMEM, "%s: no memory for key '%s'", where, key);
	}
	if (i < 0)
		i = (int)s->n++;
	else {
		free(s->e[i].key);
		free(s->e[i].value);
		free(s->e[i].where);
	}
	s->e[i] = (lz_entry){k, v, w, line, !*value};
	lz_scene_unbind(s);
	return LZ_OK;
}

lz_scene *lz_scene_new(const char *name)
{
	lz_scene *s = calloc(1, sizeof *s);
	if (s) {
		s->name = strdup(name && *name ? name : "scene");
		s->origin = strdup(name && *name ? name : "scene");
	}
	if (!s || !s->name || !s->origin) {
		lz_scene_free(s);
		lz_error(LZ_ENOMEM, "no memory for a scene");
		return NULL;
	}
	return s;
}

/* The base name of path without ".scene": the scene's name and its default run dir. */
static void scene_name_of(const char *path, char *buf, size_t size)
{
	const char *base = strrchr(path, '/');
	base = base ? base + 1 : path;
	size_t n = strlen(base);
	if (n > 6 && strcmp(base + n - 6, ".scene") == 0)
		n -= 6;
	snprintf(buf, size, "%.*s", (int)n, base);
}

/* The lines of a whole file (len bytes) into s. */
static int scene_parse(lz_scene *s, const char *text, size_t len)
{
	char buf[LZ_SCENE_LINE_MAX + 1], where[LZ_SCENE_LINE_MAX + 32];
	const char *end = text + len;
	if (len >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)  /* a UTF-8 byte-order mark */
		text += 3;
	for (int line = 1; text < end; line++) {
		const char *nl = memchr(text, '\n', (size_t)(end - text));
		size_t n = nl ? (size_t)(nl - text) : (size_t)(end - text);
		char *key, *value;
		snprintf(where, sizeof where, "%s:%d", s->origin, line);
		int rc = parse_line(text, n, where, 0, buf, &key, &value);
		if (rc == 1)
			rc = scene_put(s, key, value, where, line);
		if (rc != LZ_OK)
			return rc;
		text = nl ? nl + 1 : end;
	}
	if (s->n == 0)
		return lz_error(LZ_ESYNTAX, "%s: empty scene: no keys", s->origin);
	return LZ_OK;
}

/* The contents of f, at most LZ_SCENE_FILE_MAX + 1 bytes (so that a huge file or an
 * endless device costs no more), in a buffer that grows with what is there. NULL
 * when out of memory; *err is the errno of a failed read, else 0. */
static char *read_capped(FILE *f, size_t *len, int *err)
{
	size_t cap = 4096, n = 0;
	char *buf = malloc(cap);
	while (buf) {
		n += fread(buf + n, 1, cap - n, f);
		if (n < cap || cap == LZ_SCENE_FILE_MAX + 1)
			break;
		size_t bigger = 2 * cap < LZ_SCENE_FILE_MAX + 1 ? 2 * cap : LZ_SCENE_FILE_MAX + 1;
		char *grown = realloc(buf, bigger);
		if (!grown)
			free(buf);
		buf = grown;
		cap = bigger;
	}
	*err = ferror(f) ? errno : 0;
	*len = n;
	return buf;
}

lz_scene *lz_scene_read(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		lz_error(LZ_EINVAL, "cannot open scene '%s': %s", path, strerror(errno));
		return NULL;
	}
	size_t len;
	int err;
	char *text = read_capped(f, &len, &err);
	fclose(f);
	char name[256];
	scene_name_of(path, name, sizeof name);
	lz_scene *s = NULL;
	if (!text)
		lz_error(LZ_ENOMEM, "no memory to read scene '%s'", path);
	else if (err == EISDIR)
		lz_error(LZ_EINVAL, "scene '%s' is a directory, not a scene file", path);
	else if (err)
		lz_error(LZ_EIO, "cannot read scene '%s': %s", path, strerror(err));
	else if (len > LZ_SCENE_FILE_MAX)
		lz_error(LZ_ESYNTAX, "%s: larger than 1 MiB: not a scene file", path);
	else if ((s = lz_scene_new(name))) {
		free(s->origin);
		s->origin = strdup(path);
		const char *slash = strrchr(path, '/');
		if (slash)
			s->dir = strndup(path, slash == path ? 1 : (size_t)(slash - path));
		if (!s->origin || (slash && !s->dir) || scene_parse(s, text, len) != LZ_OK) {
			if (!s->origin || (slash && !s->dir))
				lz_error(LZ_ENOMEM, "no memory to read scene '%s'", path);
			lz_scene_free(s);
			s = NULL;
		}
	}
	free(text);
	return s;
}

int lz_scene_set(lz_scene *s, const char *assignment, const char *origin)
{
	const char *where = origin ? origin : "command line";
	char buf[LZ_SCENE_LINE_MAX + 1], *key, *value;
	int rc = parse_line(assignment, strlen(assignment), where, 1, buf, &key, &value);
	if (rc == 0)
		return lz_error(LZ_ESYNTAX, "%s: expected 'key=value', found '%s'", where,
		                assignment);
	return rc == 1 ? scene_put(s, key, value, where, 0) : rc;
}

void lz_scene_free(lz_scene *s)
{
	if (!s)
		return;
	for (size_t i = 0; i < s->n; i++) {
		free(s->e[i].key);
		free(s->e[i].value);
		free(s->e[i].where);
	}
	free(s->e);
	lz_scene_unbind(s);
	free(s->name);
	free(s->origin);
	free(s->dir);
	free(s);
}

const char *lz_scene_name(const lz_scene *s)
{
	return s->name;
}

const char *lz_scene_method(const lz_scene *s)
{
	int i = scene_find(s, "method");
	return i >= 0 ? s->e[i].value : NULL;
}

/* ---- binding ---- */

static int key_index(const lz_key_table *t, const char *key)
{
	for (size_t i = 0; i < t->n; i++)
		if (strcmp(t->key[i].name, key) == 0)
			return (int)i;
	return -1;
}

/* Levenshtein distance, for "did you mean". b is a table key (short). */
static size_t edit_distance(const char *a, const char *b)
{
	enum { MAXB = 64 };
	size_t row[MAXB + 1], nb = strlen(b);
	if (nb > MAXB)
		return (size_t)-1;
	for (size_t j = 0; j <= nb; j++)
		row[j] = j;
	for (size_t i = 1; a[i - 1]; i++) {
		size_t diag = row[0];
		row[0] = i;
		for (size_t j = 1; j <= nb; j++) {
			size_t up = row[j];
			size_t best = diag + (a[i - 1] != b[j - 1]);
			best = up + 1 < best ? up + 1 : best;
			best = row[j - 1] + 1 < best ? row[j - 1] + 1 : best;
			row[j] = best;
			diag = up;
		}
	}
	return row[nb];
}

static int unknown_key(const lz_scene *s, const lz_entry *e)
{
	char keys[1024] = "", hint[128] = "";
	size_t len = 0, best = (size_t)-1;
	for (size_t i = 0; i < s->t->n; i++) {
		const char *name = s->t->key[i].name;
		size_t d = edit_distance(e->key, name);
		size_t longer = strlen(e->key) > strlen(name) ? strlen(e->key) : strlen(name);
		/* A suggestion sharing less than half its letters would only confuse. */
		if (d < best && 2 * d <= longer) {
			best = d;
			snprintf(hint, sizeof hint, " (did you mean '%s'?)", name);
		}
		if (len < sizeof keys)
			len += (size_t)snprintf(keys + len, sizeof keys - len, "%s%s", i ? ", " : "",
			                        name);
	}
	return lz_error(LZ_EINVAL, "%s: unknown key '%s' for method %s%s; its keys are: %s",
	                e->where, e->key, s->t->method, hint, keys);
}

/* 0: an integer in *x; 1: not an integer; 2: an integer beyond any range we keep.
 * "1e6" is accepted: physicists write step counts that way. */
static int parse_integer(const char *text, long long *x)
{
	char *end;
	errno = 0;
	*x = strtoll(text, &end, 10);
	if (end != text && *end == '\0')
		return errno == ERANGE ? 2 : 0;
	errno = 0;
	double d = strtod(text, &end);
	if (end == text || *end != '\0' || !isfinite(d) || d != floor(d))
		return 1;
	if (fabs(d) > 9007199254740992.0)  /* 2^53: beyond it not every integer is a double */
		return 2;
	*x = (long long)d;
	return 0;
}

static int in_range(const lz_key *k, double x)
{
	return (k->min_open ? x > k->min : x >= k->min) &&
	       (k->max_open ? x < k->max : x <= k->max);
}

static int out_of_range(const lz_key *k, const char *text, const char *where)
{
	return lz_error(LZ_EINVAL, "%s: key '%s' = %s is out of range %c%g, %g%c", where,
	                k->name, text, k->min_open ? '(' : '[', k->min, k->max,
	                k->max_open ? ')' : ']');
}

/* The index of word `text` in "a|b|c", or -1. */
static int choice_index(const char *choices, const char *text)
{
	size_t n = strlen(text);
	int i = 0;
	for (const char *p = choices; p; i++) {
		const char *bar = strchr(p, '|');
		size_t len = bar ? (size_t)(bar - p) : strlen(p);
		if (len == n && strncmp(p, text, n) == 0)
			return i;
		p = bar ? bar + 1 : NULL;
	}
	return -1;
}

static int parse_bool(const char *text)
{
	static const char *const words[] = {"false", "true", "no", "yes", "0", "1"};
	for (int i = 0; i < 6; i++)
		if (strcmp(text, words[i]) == 0)
			return i % 2;
	return -1;
}

static int value_int(const lz_key *k, const char *text, const char *where, lz_value *v)
{
	int rc = parse_integer(text, &v->integer);
	if (rc == 1)
		return lz_error(LZ_EINVAL, "%s: key '%s' = %s must be an integer", where, k->name,
		                text);
	if (rc == 2 || !in_range(k, (double)v->integer))
		return out_of_range(k, text, where);
	v->real = (double)v->integer;
	return LZ_OK;
}

static int value_real(const lz_key *k, const char *text, const char *where, lz_value *v)
{
	char *end;
	v->real = strtod(text, &end);
	if (end == text || *end != '\0')
		return lz_error(LZ_EINVAL, "%s: key '%s' = %s must be a number", where, k->name,
		                text);
	if (!isfinite(v->real))  /* nan, inf, and overflow such as 1e999 */
		return lz_error(LZ_EINVAL, "%s: key '%s' = %s must be a finite number", where,
		                k->name, text);
	return in_range(k, v->real) ? LZ_OK : out_of_range(k, text, where);
}

static int value_seed(const lz_key *k, const char *text, const char *where, lz_value *v)
{
	if (strcmp(text, "auto") == 0) {
		v->integer = (long long)lz_seed_auto();
		return LZ_OK;
	}
	static const lz_key seed_range = {.min = 1, .max = (double)LZ_SEED_MAX};
	int rc = parse_integer(text, &v->integer);
	if (rc == 1)
		return lz_error(LZ_EINVAL, "%s: key '%s' = %s must be 'auto' or an integer",
		                where, k->name, text);
	if (rc == 2 || !in_range(&seed_range, (double)v->integer))
		return lz_error(LZ_EINVAL, "%s: key '%s' = %s is out of range [1, %lu]", where,
		                k->name, text, LZ_SEED_MAX);
	return LZ_OK;
}

static int value_parse(const lz_key *k, const char *text, const char *where, lz_value *v)
{
	switch (k->type) {
	case LZ_KEY_INT:
		return value_int(k, text, where, v);
	case LZ_KEY_REAL:
		return value_real(k, text, where, v);
	case LZ_KEY_SEED:
		return value_seed(k, text, where, v);
	case LZ_KEY_ENUM:
		v->integer = choice_index(k->choices ? k->choices : "", text);
		if (v->integer < 0)
			return lz_error(LZ_EINVAL, "%s: key '%s' = %s must be one of %s", where,
			                k->name, text, k->choices);
		return LZ_OK;
	case LZ_KEY_BOOL:
		v->integer = parse_bool(text);
		if (v->integer < 0)
			return lz_error(LZ_EINVAL, "%s: key '%s' = %s must be true or false (or "
			                "yes/no, 1/0)", where, k->name, text);
		return LZ_OK;
	case LZ_KEY_TEXT:
	case LZ_KEY_PATH:
		return LZ_OK;
	}
	return lz_error(LZ_EINVAL, "%s: key '%s' has an unknown type %d", where, k->name,
	                (int)k->type);
}

/* Every entry must be a key of m; `method`, when given, must name m. */
static int scene_check_entries(const lz_scene *s)
{
	for (size_t i = 0; i < s->n; i++) {
		const lz_entry *e = &s->e[i];
		if (key_index(s->t, e->key) >= 0)
			continue;
		if (strcmp(e->key, "method") != 0)
			return unknown_key(s, e);
		if (!e->unset && strcmp(e->value, s->t->method) != 0)
			return lz_error(LZ_EINVAL, "%s: method = %s, but the scene is bound to "
			                "method %s", e->where, e->value, s->t->method);
	}
	return LZ_OK;
}

/* The command line wins: an override of a key of a group unsets the file's values of
 * the other keys of its group. */
static void scene_apply_groups(lz_scene *s)
{
	for (size_t i = 0; i < s->t->n; i++) {
		int e = scene_find(s, s->t->key[i].name);
		if (s->t->key[i].group <= 0 || e < 0 || s->e[e].line > 0)
			continue;
		for (size_t k = 0; k < s->t->n; k++) {
			int other = scene_find(s, s->t->key[k].name);
			if (k != i && s->t->key[k].group == s->t->key[i].group && other >= 0 &&
			    s->e[other].line > 0)
				s->e[other].unset = 1;
		}
	}
}

/* A path the file gives, relative to the file's directory: into v->path. */
static int resolve_path(const lz_scene *s, const lz_entry *e, lz_value *v)
{
	if (!e || e->line == 0 || !s->dir || e->value[0] == '/')
		return LZ_OK;
	size_t size = strlen(s->dir) + strlen(e->value) + 2;
	if (!(v->path = malloc(size)))
		return lz_error(LZ_ENOMEM, "%s: no memory for the path of key '%s'", e->where,
		                e->key);
	snprintf(v->path, size, "%s/%s", s->dir, e->value);
	v->text = v->path;
	return LZ_OK;
}

/* Parse the value of every key of the table, given or default. */
static int scene_parse_values(lz_scene *s)
{
	for (size_t i = 0; i < s->t->n; i++) {
		const lz_key *k = &s->t->key[i];
		lz_value *v = &s->v[i];
		v->entry = scene_find(s, k->name);
		v->text = v->entry >= 0 ? s->e[v->entry].value : k->def;
		if (!v->text)
			return lz_error(LZ_EINVAL, "%s: missing key '%s' (%s), which method %s "
			                "requires", s->origin, k->name, k->help ? k->help : "",
			                s->t->method);
		if (!*v->text) {  /* optional, no default: lz_scene_has says 0 */
			v->text = NULL;
			continue;
		}
		char def[256];
		snprintf(def, sizeof def, "method %s: the default", s->t->method);
		int rc = value_parse(k, v->text, v->entry >= 0 ? s->e[v->entry].where : def, v);
		if (rc == LZ_OK && k->type == LZ_KEY_PATH)
			rc = resolve_path(s, v->entry >= 0 ? &s->e[v->entry] : NULL, v);
		if (rc != LZ_OK)
			return rc;
	}
	return LZ_OK;
}

int lz_scene_bind(lz_scene *s, const lz_key_table *t)
{
	lz_scene_unbind(s);
	if (!t)
		return lz_error(LZ_EINVAL, "%s: no key table to bind the scene to", s->origin);
	s->t = t;
	s->v = calloc(t->n ? t->n : 1, sizeof *s->v);
	int rc = s->v ? LZ_OK : lz_error(LZ_ENOMEM, "%s: no memory to bind", s->origin);
	if (rc == LZ_OK)
		rc = scene_check_entries(s);
	if (rc == LZ_OK) {
		scene_apply_groups(s);
		rc = scene_parse_values(s);
	}
	if (rc != LZ_OK)
		lz_scene_unbind(s);
	return rc;
}

/* ---- typed access ---- */

static const char *type_name(lz_key_type t)
{
	static const char *const names[] = {"integer", "real", "enum", "seed", "bool", "text",
	                                    "path"};
	return (unsigned)t < sizeof names / sizeof names[0] ? names[t] : "?";
}

/* The value of `key` if it is declared with one of the types in mask (bit 1 << type). */
static const lz_value *scene_value(const lz_scene *s, const char *key, unsigned mask)
{
	if (!s->t) {
		lz_error(LZ_EINVAL, "%s: scene asked for key '%s' before lz_scene_bind", s->origin,
		         key);
		return NULL;
	}
	int i = key_index(s->t, key);
	if (i < 0) {
		lz_error(LZ_EINVAL, "method %s has no key '%s'", s->t->method, key);
		return NULL;
	}
	if (!(mask >> s->t->key[i].type & 1)) {
		lz_error(LZ_EINVAL, "key '%s' of method %s is of type %s, asked for another type",
		         key, s->t->method, type_name(s->t->key[i].type));
		return NULL;
	}
	return &s->v[i];
}

#define LZ_T(t) (1u << (t))

double lz_scene_real(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, LZ_T(LZ_KEY_REAL) | LZ_T(LZ_KEY_INT));
	return v && v->text ? v->real : 0.0;
}

long long lz_scene_int(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, LZ_T(LZ_KEY_INT) | LZ_T(LZ_KEY_SEED));
	return v && v->text ? v->integer : 0;
}

int lz_scene_bool(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, LZ_T(LZ_KEY_BOOL));
	return v && v->text ? (int)v->integer : 0;
}

const char *lz_scene_text(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, ~0u);
	return v && v->text ? v->text : "";
}

int lz_scene_enum(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, LZ_T(LZ_KEY_ENUM));
	return !v ? 0 : v->text ? (int)v->integer : -1;
}

unsigned long lz_scene_seed(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, LZ_T(LZ_KEY_SEED));
	return v && v->text ? (unsigned long)v->integer : 0;
}

int lz_scene_has(const lz_scene *s, const char *key)
{
	const lz_value *v = scene_value(s, key, ~0u);
	return v && v->text;
}

int lz_scene_given(const lz_scene *s, const char *key)
{
	return scene_find(s, key) >= 0;
}

int lz_scene_fail(const lz_scene *s, const char *key, const char *fmt, ...)
{
	char msg[1536];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	int i = scene_find(s, key);
	return lz_error(LZ_EINVAL, "%s: %s", i >= 0 ? s->e[i].where : s->origin, msg);
}

void lz_scene_json(const lz_scene *s, lz_json *j)
{
	if (!s->t) {
		lz_error(LZ_EINVAL, "%s: lz_scene_json before lz_scene_bind", s->origin);
		return;
	}
	lz_json_str(j, "method", s->t->method);
	for (size_t i = 0; i < s->t->n; i++) {
		const lz_key *k = &s->t->key[i];
		const lz_value *v = &s->v[i];
		if (strcmp(k->name, "method") == 0)
			continue;
		if (!v->text) {
			lz_json_num(j, k->name, NAN);  /* null: the key has no value */
			continue;
		}
		switch (k->type) {
		case LZ_KEY_INT:
		case LZ_KEY_SEED:
			lz_json_int(j, k->name, v->integer);
			break;
		case LZ_KEY_REAL:
			lz_json_num(j, k->name, v->real);
			break;
		case LZ_KEY_BOOL:
			lz_json_bool(j, k->name, (int)v->integer);
			break;
		case LZ_KEY_ENUM:
		case LZ_KEY_TEXT:
		case LZ_KEY_PATH:
			lz_json_str(j, k->name, v->text);
			break;
		}
	}
}
