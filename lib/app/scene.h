/* scene.h — scene files: `key = value` lines, '#' comments, one key per line.
 *
 * A scene names its engine with `method = NAME`; the engine's key table says which
 * keys exist, their types, defaults and allowed ranges. Parsing is in two
 * passes: lz_scene_read() collects the lines and lz_scene_set() adds command-line
 * overrides; lz_scene_bind() then checks everything against the key table. Every
 * error names the place ("water.scene:7:" or "command line:") and the allowed range:
 *   water.scene:7: key 'dt' = -0.1 is out of range (0, 1]
 * Errors are LZ_ESYNTAX (malformed file) or LZ_EINVAL (bad key or value).
 *
 * The command line wins over the file: an override replaces the file's value; an
 * empty one (`key=`) unsets the key, so that its default applies; and an override of
 * one key of a group of alternatives (steps or time; n or packing) unsets the other
 * keys of that group the file gives, so `time=10` works on a scene that sets steps.
 */
#ifndef LZ_SCENE_H
#define LZ_SCENE_H

#include <stddef.h>

#include "lz/output.h"

typedef enum {
	LZ_KEY_INT,   /* decimal integer, range [min, max] */
	LZ_KEY_REAL,  /* finite real, range per min/max and the open flags */
	LZ_KEY_ENUM,  /* one of the words in `choices`, "a|b|c" */
	LZ_KEY_SEED,  /* "auto" or an integer in [1, LZ_SEED_MAX] (lz/rng.h) */
	LZ_KEY_BOOL,  /* true|false|yes|no|1|0 */
	LZ_KEY_TEXT,  /* any text without control characters (a label, a type name) */
	LZ_KEY_PATH   /* a file name: relative to the scene file's directory when the file
	                 gives it, to the current directory when the command line does */
} lz_key_type;

/* One entry of an engine's key table. */
typedef struct {
	const char *name;
	lz_key_type type;
	const char *def;      /* default value as text; NULL: the key is required,
	                         "" : optional with no default (see lz_scene_has) */
	double min, max;      /* allowed range of INT and REAL keys */
	int min_open, max_open; /* 1: the bound itself is excluded, e.g. dt in (0, 1] */
	const char *choices;  /* ENUM: "euler|verlet|..." */
	const char *unit;     /* unit of a number in reduced units ("σ", "1/τ"), or NULL */
	const char *help;     /* one line for `lz help METHOD` */
	int group;            /* > 0: one of the alternative keys of that group number (give
	                         one of them): an override of one unsets the others */
} lz_key;

/* A key table: the keys a scene may hold for one engine, and that engine's name (the
 * value `method =` must have, and the name in messages: "unknown key 'x' for method
 * edmd"). The parser knows nothing else of the engines. */
typedef struct {
	const char *method;
	const lz_key *key;
	size_t n;
} lz_key_table;

typedef struct lz_scene lz_scene;

/* Read a scene file. NULL with lz_error on a missing or unreadable file, binary
 * content, a line without '=', an empty key, a key given twice, or an empty file. */
lz_scene *lz_scene_read(const char *path);
/* An empty scene named `name` (for programs that build scenes themselves). */
lz_scene *lz_scene_new(const char *name);
/* Add or replace `key=value` (a command-line override); origin names where it came
 * from in error messages, e.g. "command line". `key=` (no value) unsets the key: the
 * scene then reads as if it did not give it (an unknown key is still reported at
 * bind). */
int lz_scene_set(lz_scene *s, const char *assignment, const char *origin);
void lz_scene_free(lz_scene *s);

/* The scene's name: the file's base name without ".scene". */
const char *lz_scene_name(const lz_scene *s);
/* The raw text of `method`, or NULL when the scene has none. */
const char *lz_scene_method(const lz_scene *s);

/* Check every key against the table: unknown keys, missing required keys, wrong
 * types, values out of range; fill in defaults; resolve seed=auto (the seed actually
 * used is then what lz_scene_seed returns and what lz_scene_json writes) and the paths
 * of the file against its directory. An override of a key of a group (lz_key.group)
 * unsets, for good, the file's values of the other keys of that group. The table is
 * kept, not copied. On an error the scene is left unbound. */
int lz_scene_bind(lz_scene *s, const lz_key_table *t);
/* Forget the binding (the scene's lines stay). O(1). */
void lz_scene_unbind(lz_scene *s);

/* Typed values of a bound scene. Asking for a key the table does not declare is
 * a programming error: it returns 0 / "" and reports LZ_EINVAL. */
double lz_scene_real(const lz_scene *s, const char *key);
long long lz_scene_int(const lz_scene *s, const char *key);
int lz_scene_bool(const lz_scene *s, const char *key);
const char *lz_scene_text(const lz_scene *s, const char *key);
int lz_scene_enum(const lz_scene *s, const char *key);  /* index into choices; -1: no value */
unsigned long lz_scene_seed(const lz_scene *s, const char *key);
/* 1 when the key has a value (given, or a non-empty default). */
int lz_scene_has(const lz_scene *s, const char *key);
/* 1 when the key was given explicitly (in the file or on the command line), and not
 * unset since. */
int lz_scene_given(const lz_scene *s, const char *key);

/* Report a cross-key problem at the key's place: "file:line: " + message. Returns
 * LZ_EINVAL. For the engines' cross-key checks. */
int lz_scene_fail(const lz_scene *s, const char *key, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* Write every parameter of a bound scene (given or default) into a summary: "method"
 * first, then the table's keys in order; null for an optional key without a value. */
void lz_scene_json(const lz_scene *s, lz_json *j);

#endif
