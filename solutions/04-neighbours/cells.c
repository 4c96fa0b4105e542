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

/* LZ_HELPERS_BEGIN */
/* The cell coordinate of coordinate x along one axis: wrapped into [0, L) in a
 * periodic box (the test keeps the common case, inside the box, free of fmod),
 * clamped to the edge cells with walls; round-off that reaches m is taken as m - 1. */
static inline int32_t axis_cell(const lz_cells *c, double x)
{
	double L = c->side;
	if (c->periodic) {
		if (!(x >= 0 && x < L)) {
			x = fmod(x, L);
			if (x < 0)
				x += L;
		}
	} else if (!(x > 0)) {
		return 0;
	} else if (x >= L) {
		return c->m - 1;
	}
	int32_t k = (int32_t)(x * c->inv_width);
	return k < c->m ? k : c->m - 1;
}

/* 1 if the offset (a, b, d) is in the forward half: read as the number d·9 + b·3 + a,
 * it is positive. Of the two offsets ±e exactly one is forward. */
static inline int forward(int a, int b, int d)
{
	return d > 0 || (d == 0 && (b > 0 || (b == 0 && a > 0)));
}

/* The squared distance of points a and b, the nearest image in a periodic box. The
 * correction is needed only when a coordinate differs by more than L/2. */
static inline double pair_d2(const lz_cells *c, const double *a, const double *b)
{
	double s = 0, L = c->side;
	for (int k = 0; k < c->dim; k++) {
		double d = a[k] - b[k];
		if (c->periodic && fabs(d) > 0.5 * L)
			d -= L * nearbyint(d / L);
		s += d * d;
	}
	return s;
}

/* Count the pair (i, j) if closer than rc (rc2 = rc²); the first cap go to out. */
static inline size_t pair_add(const lz_cells *c, const double *x, int32_t i, int32_t j,
                              double rc2, lz_pair *out, size_t cap, size_t np)
{
	size_t dim = (size_t)c->dim;
	if (pair_d2(c, x + (size_t)i * dim, x + (size_t)j * dim) >= rc2)
		return np;
	if (np < cap)
		out[np] = i < j ? (lz_pair){(uint32_t)i, (uint32_t)j} : (lz_pair){(uint32_t)j, (uint32_t)i};
	return np + 1;
}
/* LZ_HELPERS_END */

uint64_t lz_morton(int dim, uint32_t x, uint32_t y, uint32_t z)
{
	/* Hint: you wrote the bit dilation in stage 02: lz_morton2_encode(x, y) and
	 * lz_morton3_encode(x, y, z) in lz/bits.h are exactly these codes. Call the one
	 * that fits dim (or write the dilation afresh: d = (d | d << s) & mask, five
	 * steps). Check (1,0), (0,1), (1,1) -> 1, 2, 3 by hand, and that z is ignored in
	 * 2D. See lessons/04-neighbours/README.md, "Morton order". */
	/* LZ_SOLUTION_BEGIN */
	return dim == 3 ? lz_morton3_encode(x, y, z) : lz_morton2_encode(x, y);
	/* LZ_SOLUTION_END */
}

size_t lz_cells_of_site(const lz_cells *c, const int32_t *r)
{
	/* Hint: the cell coordinates are the high bits of the site's coordinates,
	 * cx[k] = r[k] >> c->shift for k < dim (set cx[2] = 0 in 2D). Then let
	 * lz_cells_index turn them into the storage index (it knows the Morton ranks).
	 * No division. See lessons/04-neighbours/README.md, "Cells by bit shift". */
	/* LZ_SOLUTION_BEGIN */
	int32_t cx[3] = {0, 0, 0};
	for (int k = 0; k < c->dim; k++)
		cx[k] = r[k] >> c->shift;
	return lz_cells_index(c, cx);
	/* LZ_SOLUTION_END */
}

size_t lz_cells_of_point(const lz_cells *c, const double *x)
{
	/* Hint: per axis. Periodic box: bring x into [0, L) first — fmod(x, L) keeps the
	 * sign of x, so add L to a negative result — but only when x is outside (fmod is
	 * slow). Walls: x <= 0 is cell 0, x >= L is cell m - 1. Then
	 * k = (int32_t)(x * c->inv_width), and k = m - 1 if round-off made it m (x a hair
	 * below L, or -1e-20 + L == L). Finally lz_cells_index. See
	 * lessons/04-neighbours/README.md, "Cells by bit shift". */
	/* LZ_SOLUTION_BEGIN */
	int32_t cx[3] = {0, 0, 0};
	for (int k = 0; k < c->dim; k++)
		cx[k] = axis_cell(c, x[k]);
	return lz_cells_index(c, cx);
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	int32_t cx[3] = {0, 0, 0}, m = c->m;
	lz_cells_coords(c, cell, cx);
	int n = 0, dz = c->dim == 3;
	out[n++] = (uint32_t)cell;
	for (int d = -dz; d <= dz; d++)
		for (int b = -1; b <= 1; b++)
			for (int a = -1; a <= 1; a++) {
				if ((a == 0 && b == 0 && d == 0) || (half && !forward(a, b, d)))
					continue;
				int32_t off[3] = {a, b, d}, nb[3] = {0, 0, 0};
				int inside = 1;
				for (int k = 0; k < c->dim; k++) {
					nb[k] = cx[k] + off[k];
					if (nb[k] < 0 || nb[k] >= m) {
						inside = c->periodic;
						nb[k] = (nb[k] + m) % m;
					}
				}
				if (inside)
					out[n++] = (uint32_t)lz_cells_index(c, nb);
			}
	return n;
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	for (size_t q = 0; q <= c->ncells; q++)
		c->head[q] = -1;
	for (size_t i = c->n; i-- > 0;) {
		uint32_t q = c->of[i];
		c->next[i] = c->head[q];
		c->head[q] = (int32_t)i;
	}
	/* LZ_SOLUTION_END */
}

int lz_cells_fill(lz_cells *c)
{
	/* Hint: refuse cap == 0 with lz_error(LZ_EINVAL, ...). Set every count to 0
	 * (ncells + 1 of them), then for i = 0, 1, ... in order: q = of[i]; if count[q]
	 * already equals cap, return lz_error(LZ_EPHYS, ...) naming q and cap and what to
	 * do (a larger cap, or the linked lists); else slot[q·cap + count[q]] = i and
	 * count[q]++. See lessons/04-neighbours/README.md, "Linked lists and fixed
	 * arrays" (thesis 2.4.3: the Fortran array CL). */
	/* LZ_SOLUTION_BEGIN */
	if (c->cap == 0)
		return lz_error(LZ_EINVAL, "this grid has no fixed arrays (it was allocated with "
		                "cap = 0): give lz_cells_alloc a cap > 0, or use lz_cells_link");
	memset(c->count, 0, (c->ncells + 1) * sizeof *c->count);
	for (size_t i = 0; i < c->n; i++) {
		uint32_t q = c->of[i];
		if (c->count[q] == c->cap)
			return lz_error(LZ_EPHYS, "cell %u is full: it holds cap = %zu particles "
			                "when particle %zu arrives, and a fixed array cannot drop it; "
			                "allocate with a larger cap (the mean is %.3g per cell) or use "
			                "the linked lists", q, c->cap, i, (double)c->n / (double)c->ncells);
		c->slot[q * c->cap + c->count[q]++] = (uint32_t)i;
	}
	return LZ_OK;
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	double rc2 = rc * rc;
	size_t np = 0, nhalf = (size_t)c->nhalf;
	for (size_t q = 0; q < c->ncells; q++) {
		const uint32_t *block = c->half + q * nhalf;
		for (int32_t i = c->head[q]; i >= 0; i = c->next[i]) {
			for (int32_t j = c->next[i]; j >= 0; j = c->next[j])
				np = pair_add(c, x, i, j, rc2, out, cap, np);
			for (size_t k = 1; k < nhalf; k++)
				for (int32_t j = c->head[block[k]]; j >= 0; j = c->next[j])
					np = pair_add(c, x, i, j, rc2, out, cap, np);
		}
	}
	return np;
	/* LZ_SOLUTION_END */
}
