/* edmd_scene.h — what the scenes of the event-driven engines (edmd, pedmd) share: the
 * keys of the system (its size, box, walls, start and equilibration) and the system
 * they describe, placed and equilibrated. Written once here, used by both key tables
 * and runs. */
#ifndef LZ_EDMD_SCENE_H
#define LZ_EDMD_SCENE_H

#include <stddef.h>

#include "lz/edmd.h"
#include "lz/rng.h"
#include "config.h"
#include "scene.h"

/* The system's keys: dim, n, packing, restitution, gravity, walls, cells, equilibrate,
 * config, seed. */
#define LZ_EDMD_SYSTEM_KEYS \
	{.name = "dim", .type = LZ_KEY_INT, .def = "3", .min = 2, .max = 3, \
	 .help = "3: hard spheres; 2: hard disks"}, \
	{.name = "n", .type = LZ_KEY_INT, .def = "1000", .min = 1, .max = 1e9, \
	 .help = "particles, any number (a lattice start fills a random subset of its " \
	         "sites); with " "config, the file's rows"}, \
	{.name = "packing", .type = LZ_KEY_REAL, .def = "0.3", .min = 0, \
	 .max = LZ_EDMD_CLOSE_2D, .min_open = 1, .max_open = 1, \
	 .help = "packing fraction η = n·v1/L^dim (v1 = π/6, π/4), which sets the box side " \
	         "L; below " "close packing, 0.7405 (spheres) and 0.9069 (disks)"}, \
	{.name = "restitution", .type = LZ_KEY_REAL, .def = "1", .min = 0, .max = 1, \
	 .min_open = 1, \
	 .help = "normal restitution between particles (walls are elastic); below 1 the " \
	         "gas cools " "(Haff's law), clusters, and may collapse"}, \
	{.name = "gravity", .type = LZ_KEY_REAL, .def = "0", .max = 1e6, .unit = "σ/τ²", \
	 .help = "acceleration g along -x (needs walls = x or box)"}, \
	{.name = "walls", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|x|box", \
	 .help = "hard elastic walls at x = 0 and L (x) or on every axis (box); none: " \
	         "periodic"}, \
	{.name = "cells", .type = LZ_KEY_INT, .def = "0", .max = 1e5, .unit = "per side", \
	 .help = "cells per side, each at least σ wide, >= 3 on a periodic axis; 0: " \
	         "automatic: about 1.5 cells per particle in 2D, 3 in 3D (the side rounded " \
	         "up, at least 3), or as many as fit when that is fewer (dense)"}, \
	{.name = "equilibrate", .type = LZ_KEY_REAL, .def = "50", .max = 1e9, \
	 .unit = "per particle", \
	 .help = "events per particle run first and discarded, elastic whatever the " \
	         "restitution"}, \
	{.name = "config", .type = LZ_KEY_PATH, .def = "", \
	 .help = "file of rows x y [z] [vx vy [vz]] (σ, σ/τ; '#' comments; a relative " \
	         "name in the scene is read from the scene's directory): the initial state " \
	         "instead of a lattice, n = its rows, positions in [0, L); no velocities: " \
	         "Maxwell, kT = 1"}, \
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto", \
	 .help = "random seed of the lattice sites and the velocities"}

/* The particles of the bound scene: n, or the rows of its config file c (read by the
 * caller; then a given n must agree). LZ_OK or LZ_EINVAL at the key to blame. */
int lz_edmd_scene_particles(const lz_scene *s, const lz_config *c, size_t *n);

/* Place config file c's particles into e (velocities from the file or Maxwell's from
 * rng); lz_edmd_set checks the box, the walls, the numbers and the overlaps. LZ_OK or
 * LZ_EINVAL at the key `config`. */
int lz_edmd_scene_place_config(const lz_scene *s, lz_edmd *e, const lz_config *c, lz_rng *rng);

/* The system of the scene for n particles (not yet placed), its neighbours, shell and
 * queue from `engine` (NULL: cells and the binary heap), or NULL with the library's
 * message at the key to blame. O(n + cells). */
lz_edmd *lz_edmd_scene_system(const lz_scene *s, size_t n, const lz_edmd_params *engine);

/* Place e's particles: from the config file (velocities from it or Maxwell's), or on a
 * lattice. LZ_OK or an error at the key to blame. O(n log n). */
int lz_edmd_scene_start(const lz_scene *s, lz_edmd *e, lz_rng *rng);

/* Unless quiet, a warning on stderr when e is compared with the fluid's equation of
 * state (periodic, elastic, no gravity: Z_ref) at a packing where the fluid is not the
 * stable phase: above the hard-sphere freezing packing, or the hard-disk liquid's
 * stability limit (datasets/reference/). O(1). */
void lz_edmd_scene_warn_phase(const lz_edmd *e, double packing, int quiet);

/* Run `equilibrate` events per particle, elastic whatever the restitution (a progress
 * line unless quiet), then set the clock to 0. */
int lz_edmd_scene_equilibrate(const lz_scene *s, lz_edmd *e, int quiet);

#endif
