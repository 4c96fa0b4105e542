/* lattice.c — distances on lattices and the minimum image in a power-of-two box
 * (graded). */
#include <stdint.h>

#include "lz/error.h"
#include "lz/lattice.h"

/* LZ_HELPERS_BEGIN */
static int64_t tri2(int64_t x, int64_t y) { return x * (x + y) + y * y; }
/* LZ_HELPERS_END */

/* The squared length of an integer displacement, exact in 64 bits. */
int64_t lz_lattice_dist2(lz_lattice_kind kind, int32_t dx, int32_t dy, int32_t dz)
{
	/* Hint: widen to int64_t BEFORE multiplying: at the largest box dx·dx alone
	 * overflows 32 bits. Square: dx² + dy²; triangular (sheared): dx² + dx·dy + dy²;
	 * cubic: dx² + dy² + dz². Square8 and cubic18/26 are the same lattices with more
	 * directions, so the same distances. See lessons/02-lattice/README.md §4. */
	/* LZ_SOLUTION_BEGIN */
	int64_t x = dx, y = dy, z = dz;
	switch (kind) {
	case LZ_LATTICE_SQUARE:
	case LZ_LATTICE_SQUARE8:
		return x * x + y * y;
	case LZ_LATTICE_TRIANGULAR:
		return tri2(x, y);
	case LZ_LATTICE_CUBIC:
	case LZ_LATTICE_CUBIC18:
	case LZ_LATTICE_CUBIC26:
		return x * x + y * y + z * z;
	default:
		return -1;
	}
	/* LZ_SOLUTION_END */
}

/* The saw-tooth of thesis fig. 2.16, tabulated. */
int lz_lattice_dctable(int64_t side, int32_t *dc)
{
	/* Hint: refuse a side that is not a power of two first (lz_lattice_side_check says
	 * why in words). Then dc[u] = u for u <= L/2 and u - L above: a masked difference
	 * u stands for u and for u - L, and the nearer one wins. Check L = 2 by hand.
	 * See lessons/02-lattice/README.md §4. */
	/* LZ_SOLUTION_BEGIN */
	int status = lz_lattice_side_check(side);
	if (status != LZ_OK)
		return status;
	int32_t L = (int32_t)side;
	for (int32_t u = 0; u < L; u++)
		dc[u] = u <= L / 2 ? u : u - L;
	return LZ_OK;
	/* LZ_SOLUTION_END */
}

/* The table per component; on the triangular rhombus, the hexagon's correction. */
int64_t lz_lattice_min_dist2(const lz_lattice_box *b, int32_t dx, int32_t dy, int32_t dz)
{
	/* Hint: mask each component ((uint32_t)dx & b->mask) and look it up in b->dc; then
	 * the distance² of the lattice. On the triangular lattice dx·dy > 0 makes the
	 * displacement long (the metric adds dx·dy): try also moving the x or the y
	 * component by one box side towards zero and keep the shortest. Test yourself
	 * against all images in a small box. See lessons/02-lattice/README.md §4. */
	/* LZ_SOLUTION_BEGIN */
	int64_t x = b->dc[(uint32_t)dx & (uint32_t)b->mask];
	int64_t y = b->dc[(uint32_t)dy & (uint32_t)b->mask];
	if (b->dim == 3) {
		int64_t z = b->dc[(uint32_t)dz & (uint32_t)b->mask];
		return x * x + y * y + z * z;
	}
	if (b->kind != LZ_LATTICE_TRIANGULAR)
		return x * x + y * y;
	int64_t d2 = tri2(x, y);
	if ((x > 0 && y > 0) || (x < 0 && y < 0)) {
		int64_t s = x > 0 ? b->side : -b->side;
		int64_t a = tri2(x - s, y), c = tri2(x, y - s);
		if (a < d2)
			d2 = a;
		if (c < d2)
			d2 = c;
	}
	return d2;
	/* LZ_SOLUTION_END */
}
