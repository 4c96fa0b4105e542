/* lattice_scene.c — the shared part of the lattice engines' scenes (lattice_scene.h). */
#include <math.h>

#include "lattice_scene.h"

lz_lattice_kind lz_scene_lattice(const lz_scene *s)
{
	lz_lattice_kind kind = LZ_LATTICE_SQUARE;
	lz_lattice_parse(lz_scene_text(s, "lattice"), &kind);  /* the table allows no other */
	return kind;
}

long long lz_scene_count(const lz_scene *s, const char *fraction, double one)
{
	if (lz_scene_has(s, "n"))
		return lz_scene_int(s, "n");
	if (lz_scene_has(s, fraction))
		return llround(lz_scene_real(s, fraction) / one);
	return 0;
}
