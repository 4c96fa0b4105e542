/* YOUR FILE — this is the file you fill in for stage 02-lattice.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/02-lattice/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=02`; see your own code at work with
 * `make lesson STAGE=02`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* lattice.c — distances on lattices and the minimum image in a power-of-two box
 * (graded). */
#include <stdint.h>

#include "lz/error.h"
#include "lz/lattice.h"


/* The squared length of an integer displacement, exact in 64 bits. */
int64_t lz_lattice_dist2(lz_lattice_kind kind, int32_t dx, int32_t dy, int32_t dz)
{
	/* Hint: widen to int64_t BEFORE multiplying: at the largest box dx·dx alone
	 * overflows 32 bits. Square: dx² + dy²; triangular (sheared): dx² + dx·dy + dy²;
	 * cubic: dx² + dy² + dz². Square8 and cubic18/26 are the same lattices with more
	 * directions, so the same distances. See lessons/02-lattice/README.md §4. */
	LZ_TODO();
}

/* The saw-tooth of thesis fig. 2.16, tabulated. */
int lz_lattice_dctable(int64_t side, int32_t *dc)
{
	/* Hint: refuse a side that is not a power of two first (lz_lattice_side_check says
	 * why in words). Then dc[u] = u for u <= L/2 and u - L above: a masked difference
	 * u stands for u and for u - L, and the nearer one wins. Check L = 2 by hand.
	 * See lessons/02-lattice/README.md §4. */
	LZ_TODO();
}

/* The table per component; on the triangular rhombus, the hexagon's correction. */
int64_t lz_lattice_min_dist2(const lz_lattice_box *b, int32_t dx, int32_t dy, int32_t dz)
{
	/* Hint: mask each component ((uint32_t)dx & b->mask) and look it up in b->dc; then
	 * the distance² of the lattice. On the triangular lattice dx·dy > 0 makes the
	 * displacement long (the metric adds dx·dy): try also moving the x or the y
	 * component by one box side towards zero and keep the shortest. Test yourself
	 * against all images in a small box. See lessons/02-lattice/README.md §4. */
	LZ_TODO();
}
