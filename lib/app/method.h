/* method.h — the registry of simulation engines a scene can name.
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
#include <stdint.h>
#include <stdio.h>

#include "lz/lattice.h"
#include "lz/output.h"
#include "scene.h"

/* What a running method may use. */
typedef struct {
	const lz_rundir *dir;  /* write files with lz_rundir_file(dir, "x.dat", ...) */
	lz_json *summary;      /* add observables here */
	int quiet;             /* 1: no progress line, no chatter on stderr */
} lz_run;

/* A row of the table `lz run` prints after a run (run_table.h): a summary key, shown
 * with its error bar key_err when the summary has one, and its reference. */
typedef struct {
	const char *key;
	const char *ref;     /* the summary key of its reference value, or NULL */
	const char *source;  /* the summary key naming the reference's source, or NULL */
} lz_headline;

/* A speed figure: a summary key and its unit as the table prints it. */
typedef struct {
	const char *key, *unit;
} lz_speed;

typedef struct lz_method {
	const char *name;        /* the value of `method =` */
	const char *help;        /* one line for `lz help` */
	lz_key_table keys;       /* its keys ("method" itself need not be listed), under name */
	int (*check)(const lz_scene *s);  /* cross-key check, or NULL */
	int (*run)(const lz_scene *s, lz_run *run);
	const lz_headline *headline;  /* the rows of the table after a run, ended by {NULL};
	                                 a key the summary lacks is left out */
	const lz_speed *speed;        /* the speed: the first the summary holds, {NULL} ended */
} lz_method;

/* A method's table entry: its name given once, for the method and its key table. */
#define LZ_METHOD_KEYS(name_, table_) \
	.name = name_, .keys = {name_, table_, sizeof table_ / sizeof table_[0]}

/* Bind scene s to m's keys (lz_scene_bind), then run m's cross-key check. On an error
 * the scene is left unbound. */
int lz_method_bind(const lz_method *m, lz_scene *s);

/* ---- files the methods share (run_files.c; configurations: config.h) ---- */

/* The gnuplot script NAME.gp opened for writing in the run directory and begun: a
 * comment line "# lz run, method METHOD: WHAT.", the pngcairo terminal of width ×
 * height pixels and the output NAME.png. NULL with an lz_error. */
FILE *lz_run_script(const lz_run *run, const char *name, const char *method,
                    const char *what, int width, int height);
/* Close script f (from lz_run_script, always closed here) and run gnuplot on NAME.gp
 * in the run directory. LZ_OK also when gnuplot is not installed (the plot is
 * skipped); LZ_EIO when the script could not be written or gnuplot failed. */
int lz_run_plot(const lz_run *run, FILE *f, const char *name);

/* config.gp + config.png in the run directory: the particles of config.dat (as
 * lz_config_write_lattice writes it) as circles — disks in 2D, in 3D the circles in which
 * the plane z = L/2 cuts the spheres — in the window [0, window] × [0, window · h] of a
 * box of side L (h the row spacing, lz_walk_row_spacing), under `title`. LZ_OK also
 * without gnuplot; LZ_EIO as lz_run_plot. */
int lz_run_plot_config(const lz_run *run, const char *method, lz_lattice_kind kind,
                       int32_t side, double window, const char *title);

/* config.gp + config.png for particles off the lattice: the disks of diameter σ = 1
 * centred on columns 1, 2 of config.dat (σ units) — in 3D the circles in which the
 * plane z = L/2 cuts the spheres of column 3 — in the window [0, window]² of a box of
 * side L, under `title`. upright = 1 draws x upwards (so that gravity along -x points
 * down). LZ_OK also without gnuplot; LZ_EIO as lz_run_plot. */
int lz_run_plot_disks(const lz_run *run, const char *method, int dim, double L,
                      double window, int upright, const char *title);

/* The method named `name`, or NULL. */
const lz_method *lz_method_find(const char *name);
/* All registered methods, in course order; *n gets their number. */
const lz_method *const *lz_methods(size_t *n);

/* The engines (each defined in its own lib/app/method_*.c). */
extern const lz_method lz_method_verlet;
extern const lz_method lz_method_walk;
extern const lz_method lz_method_lattice_gas;
extern const lz_method lz_method_field;
extern const lz_method lz_method_nlist;
extern const lz_method lz_method_edmd;
extern const lz_method lz_method_pedmd;

#endif
