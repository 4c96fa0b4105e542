/* YOUR FILE — this is the file you fill in for stage 04-neighbours.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/04-neighbours/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=04`; see your own code at work with
 * `make lesson STAGE=04`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* cells.c — cell lists (graded): the Morton number of a cell, the cell of a lattice
 * site by shift and of a point by scaling, the block of neighbouring cells, the
 * linked lists and the fixed arrays, and every close pair once by the half block. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "lz/bits.h"
#include "lz/cells.h"
#include "lz/error.h"


uint64_t lz_morton(int dim, uint32_t x, uint32_t y, uint32_t z)
{
	/* Hint: you wrote the bit dilation in stage 02: lz_morton2_encode(x, y) and
	 * lz_morton3_encode(x, y, z) in lz/bits.h are exactly these codes. Call the one
	 * that fits dim (or write the dilation afresh: d = (d | d << s) & mask, five
	 * steps). Check (1,0), (0,1), (1,1) -> 1, 2, 3 by hand, and that z is ignored in
	 * 2D. See lessons/04-neighbours/README.md, "Morton order". */
	LZ_TODO();
}

size_t lz_cells_of_site(const lz_cells *c, const int32_t *r)
{
	/* Hint: the cell coordinates are the high bits of the site's coordinates,
	 * cx[k] = r[k] >> c->shift for k < dim (set cx[2] = 0 in 2D). Then let
	 * lz_cells_index turn them into the storage index (it knows the Morton ranks).
	 * No division. See lessons/04-neighbours/README.md, "Cells by bit shift". */
	LZ_TODO();
}

size_t lz_cells_of_point(const lz_cells *c, const double *x)
{
	/* Hint: per axis. Periodic box: bring x into [0, L) first — fmod(x, L) keeps the
	 * sign of x, so add L to a negative result — but only when x is outside (fmod is
	 * slow). Walls: x <= 0 is cell 0, x >= L is cell m - 1. Then
	 * k = (int32_t)(x * c->inv_width), and k = m - 1 if round-off made it m (x a hair
	 * below L, or -1e-20 + L == L). Finally lz_cells_index. See
	 * lessons/04-neighbours/README.md, "Cells by bit shift". */
	LZ_TODO();
}

int lz_cells_stencil(const lz_cells *c, size_t cell, int half, uint32_t *out)
{
	/* Hint: get the cell's coordinates with lz_cells_coords, put cell itself in
	 * out[0], then loop over the offsets (a, b, d) in -1..1 (d = 0 only, in 2D),
	 * skipping (0, 0, 0) and, when half, every offset that is not forward (header).
	 * Add the offset to the coordinates; a coordinate that leaves [0, m) wraps
	 * (+m or -m) in a periodic box, and drops that neighbour with walls. Store
	 * lz_cells_index of the result. Return how many you stored. See
	 * lessons/04-neighbours/README.md, "The block of neighbouring cells" and "Pairs
	 * once: the half block". */
	LZ_TODO();
}

/* Pushing the particles from the last to the first leaves each list in increasing
 * index, which makes the lists easy to read while debugging. */
void lz_cells_link(lz_cells *c)
{
	/* Hint: first head[q] = -1 for every q in 0 .. ncells (the empty cell too: stale
	 * lists of a previous call must go). Then for each particle i: it becomes the new
	 * first particle of its cell q = of[i], and the old first one comes after it:
	 * next[i] = head[q]; head[q] = i. Two lines, no search. See
	 * lessons/04-neighbours/README.md, "Linked lists and fixed arrays". */
	LZ_TODO();
}

int lz_cells_fill(lz_cells *c)
{
	/* Hint: refuse cap == 0 with lz_error(LZ_EINVAL, ...). Set every count to 0
	 * (ncells + 1 of them), then for i = 0, 1, ... in order: q = of[i]; if count[q]
	 * already equals cap, return lz_error(LZ_EPHYS, ...) naming q and cap and what to
	 * do (a larger cap, or the linked lists); else slot[q·cap + count[q]] = i and
	 * count[q]++. See lessons/04-neighbours/README.md, "Linked lists and fixed
	 * arrays" (thesis 2.4.3: the Fortran array CL). */
	LZ_TODO();
}

size_t lz_cells_pairs(const lz_cells *c, const double *x, double rc, lz_pair *out, size_t cap)
{
	/* Hint: for every cell q < ncells and every particle i of q's list: compare i
	 * with the particles AFTER it in the same list (j = next[i], next[next[i]], ...),
	 * then with every particle of the other cells of q's half block
	 * (c->half[q·nhalf + 1 .. nhalf-1]; entries ncells are empty cells). A pair
	 * counts when its distance² < rc²; in a periodic box take each difference d to
	 * its nearest image, d - L·nearbyint(d / L). Store (min, max) while fewer than
	 * cap are stored, but count them all. See lessons/04-neighbours/README.md,
	 * "Pairs once: the half block". */
	LZ_TODO();
}
