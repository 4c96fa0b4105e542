/* lattice_scene.h — what the scenes of the lattice engines (walk, field, nlist) share:
 * the `lattice` key, and the number of particles asked for by n or by a fraction of
 * the box. Written once here, used by each of their key tables and checks. */
#ifndef LZ_LATTICE_SCENE_H
#define LZ_LATTICE_SCENE_H

#include "lz/lattice.h"
#include "scene.h"

/* The `lattice` key: the kinds of lz/lattice.h by their names, square by default. */
#define LZ_KEY_LATTICE                                                                   \
	{.name = "lattice", .type = LZ_KEY_ENUM, .def = "square",                        \
	 .choices = "square|square8|triangular|cubic|cubic18|cubic26",                  \
	 .help = "lattice and its moves: 4, 4+4 diagonal, 6 (stored sheared) in 2D; 6 "   \
	         "faces, +12 edges, +8 corners in 3D (the square and the cubic ones share "  \
	         "one metric each)"}

/* The kind the bound scene's `lattice` names. O(1). */
lz_lattice_kind lz_scene_lattice(const lz_scene *s);

/* The particles asked for: n when given, else the key `fraction` (a packing fraction
 * or coverage) divided by `one`, the fraction of one particle, rounded; 0 when the
 * scene gives neither. O(1). */
long long lz_scene_count(const lz_scene *s, const char *fraction, double one);

#endif
