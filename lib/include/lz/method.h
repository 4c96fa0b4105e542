/* lz/method.h — the registry of simulation engines a scene can name.
 *
 * A method is a key table (lz/scene.h), an optional cross-key check and a run
 * function. The CLI binds the scene, opens the run directory and the summary,
 * writes the parameters, calls run(), then adds wall_s and commits the directory.
 * run() adds its observables (with _err error bars) and its speed figure
 * (steps_per_s, atomsteps_per_s, site_updates_per_s or events_per_s) to the summary.
 */
#ifndef LZ_METHOD_H
#define LZ_METHOD_H

#include <stddef.h>
#include "lz/output.h"
#include "lz/scene.h"

/* What a running method may use. */
typedef struct {
	const lz_rundir *dir;  /* write files with lz_rundir_file(dir, "x.dat", ...) */
	lz_json *summary;      /* add observables here */
	int quiet;             /* 1: no progress line, no chatter on stderr */
} lz_run;

typedef struct lz_method {
	const char *name;        /* the value of `method =` */
	const char *help;        /* one line for `lz help` */
	const lz_key *keys;      /* the key table; "method" itself need not be listed */
	size_t nkeys;
	int (*check)(const lz_scene *s);  /* cross-key check, or NULL */
	int (*run)(const lz_scene *s, lz_run *run);
} lz_method;

/* The method named `name`, or NULL. */
const lz_method *lz_method_find(const char *name);
/* All registered methods, in course order; *n gets their number. */
const lz_method *const *lz_methods(size_t *n);

/* The engines (each defined in its own lib/src/method_*.c). */
extern const lz_method lz_method_verlet;
extern const lz_method lz_method_walk;
extern const lz_method lz_method_lattice_gas;

#endif
