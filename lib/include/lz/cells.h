/* lz/cells.h — cell lists: binning by bit shift and by scaling, linked lists and
 * fixed-capacity arrays, the block of neighbouring cells with periodic wrap, the half
 * block for pair loops, and the Morton (Z-order) numbering of cells (thesis 2.4.3;
 * DynamO's Morton-ordered cells: Bannerman, Sargant & Lue, J. Comput. Chem. 32, 3329 (2011)).
 *
 * Lengths are in the units of the coordinates: lattice units for lattice sites, any
 * unit (σ off the lattice) for continuous points.
 *
 * The box, of side L along each of its dim axes (2 or 3), is cut into m cells per
 * side, of side w = L / m, no narrower than the cutoff: then two particles closer than
 * the cutoff sit in the same cell or in touching ones, so the 3^dim block around a
 * particle's cell (9 cells in 2D, 27 in 3D) holds every partner it can have. In a
 * periodic box the block wraps, and m >= 3 is needed for its 3^dim cells to be
 * distinct (with m = 2 the cells left and right of a cell are the same cell).
 *
 * Binning. A particle's cell coordinates (cx, cy, cz), each in [0, m):
 *   - lattice sites (lz_cells_alloc_lattice): L = 2^k and w = 2^s, so cx = x >> s, one
 *     shift per axis (thesis 2.4.3: the high bits of a coordinate name its cell);
 *   - continuous points (lz_cells_alloc): cx = floor(x / w) after x is wrapped into
 *     [0, L) (periodic box) — a division (or a multiplication by 1/w) and a floor.
 *
 * Numbering. The cells live in memory in one of two orders; a cell's number is its
 * place in that order (its STORAGE index, 0 .. ncells-1):
 *   - row-major (LZ_CELLS_ROW): q = cx + m·(cy + m·cz), x fastest;
 *   - Morton (LZ_CELLS_MORTON): the cells sorted by the Morton code of (cx, cy, cz)
 *     (lz_morton: the bits of the coordinates interleaved). When m is a power of two
 *     the codes are exactly 0 .. m^dim - 1, so a cell's number IS its code; otherwise
 *     the codes have gaps and rank[] compacts them. Cells near in space are then near
 *     in memory in every direction, not only along x.
 * rank[q] gives the storage index of the row-major cell q, unrank[] the inverse; both
 * are NULL in row order (the identity).
 *
 * Lists. Every particle i has its cell of[i] (a storage index). Two stores:
 *   - linked list (lz_cells_link): head[c] is the first particle of cell c, next[i]
 *     the one after i in the same cell, -1 ends a list. n + ncells ints, no overflow
 *     possible; a scan hops around memory (next[] is indexed by particle).
 *   - fixed-capacity arrays (lz_cells_fill): count[c] particles, listed in
 *     slot[c·cap + 0 .. count[c]-1]. A cell's particles are contiguous, but cap is fixed
 *     at allocation: a cell that would hold more is an error, never a silent drop.
 * One extra cell, number ncells, is always empty (head = -1, count = 0): in a box that
 * is not periodic, the block tables point the cells missing beyond a wall at it, so
 * loops over a block need no test.
 *
 * Cost: binning O(1) per particle; link and fill O(n + ncells); a block scan
 * O(3^dim · particles per cell). Memory: the tables are ncells · (1 + 3^dim + half)
 * words, the lists n (linked) or ncells · cap (arrays) words.
 */
#ifndef LZ_CELLS_H
#define LZ_CELLS_H

#include <stddef.h>
#include <stdint.h>

#include "lz/lattice.h"

/* The most cells a grid may have (2^22: 2048² or 161³; the block tables then take
 * about 280 MB in 2D, 700 MB in 3D): when the cutoff would allow more, the cells
 * are made wider (still correct, a little slower). */
#define LZ_CELLS_MAX ((size_t)1 << 22)
/* The number of the always-empty cell is c->ncells; a block entry naming it is "no
 * cell". */

typedef enum { LZ_CELLS_ROW, LZ_CELLS_MORTON } lz_cells_order;

/* A pair of particle indices, i < j. */
typedef struct {
	uint32_t i, j;
} lz_pair;

/* A cell grid and its lists. Invariants (after alloc): m^dim = ncells <= LZ_CELLS_MAX;
 * width = side / m >= the cutoff given at allocation; full[c·nfull + k] for
 * k < nfull is the k-th cell of c's block (c itself first), half[c·nhalf + k] the
 * k-th cell of its half block, with ncells standing for a cell beyond a wall; after
 * binning, of[i] < ncells for i < n. */
typedef struct {
	int dim;               /* 2 or 3 */
	int periodic;          /* 1: the block wraps at the faces; 0: walls, no wrap */
	double side;           /* L, coordinate units */
	double cutoff;         /* the cutoff the grid was made for (lattice: a distance) */
	int32_t m;             /* cells per side: >= 3 in a periodic box, >= 1 otherwise */
	double width;          /* w = L / m >= the cutoff (lattice: >= its reach) */
	double inv_width;      /* m / L */
	int shift;             /* lattice grids: log2 w, so cx = x >> shift; -1 otherwise */
	size_t ncells;         /* m^dim; cell ncells is the extra, always-empty one */
	lz_cells_order order;
	uint32_t *rank;        /* Morton: rank[row-major q] = storage index; NULL in row order */
	uint32_t *unrank;      /* Morton: unrank[storage index] = q; NULL in row order */
	int nfull;             /* 3^dim: 9 or 27 */
	int nhalf;             /* (3^dim + 1) / 2: 5 or 14 */
	uint32_t *full;        /* (ncells + 1) · nfull block entries (the empty cell's: itself) */
	uint32_t *half;        /* (ncells + 1) · nhalf half-block entries */
	size_t n;              /* particles binned */
	size_t nmax;           /* room for particles in of[] and next[] */
	uint32_t *of;          /* of[i]: the storage index of particle i's cell */
	int32_t *head;         /* linked: ncells + 1 first particles, -1 = empty */
	int32_t *next;         /* linked: nmax successors, -1 = end of the list */
	size_t cap;            /* arrays: room per cell; 0 = no arrays were allocated */
	uint32_t *count;       /* arrays: ncells + 1 counts */
	uint32_t *slot;        /* arrays: (ncells + 1) · cap particle indices */
} lz_cells;

/* A grid for continuous points in a box of side L (dim 2 or 3), periodic or not, for
 * pairs closer than rc: m = floor(L / rc) cells per side (fewer if m^dim would pass
 * LZ_CELLS_MAX; at least 1), numbered in `order`, with room for nmax particles and,
 * when cap > 0, fixed arrays of cap particles per cell. NULL with an lz_error naming
 * the bad value and the allowed range when: dim is not 2 or 3; L or rc is not positive
 * and finite; the box is periodic and rc > L/3 (fewer than 3 cells per side: the
 * block would hold a cell twice — use all pairs); nmax is 0 or above 2^31 - 1; no
 * memory. Builds the block tables with lz_cells_stencil and, in Morton order, the
 * ranks with lz_morton (graded code runs here). O(ncells · 3^dim). */
lz_cells *lz_cells_alloc(int dim, double side, double rc, int periodic, lz_cells_order order,
                         size_t nmax, size_t cap);

/* A periodic grid for the sites of lattice `kind` in a box of side L (a power of two):
 * cells of side w = the smallest power of two >= lz_lattice_reach(kind, rc) (so a
 * pair closer than rc differs by at most w in every coordinate, and sits in touching
 * cells), doubled while m^dim would pass LZ_CELLS_MAX; shift = log2 w. Errors as
 * lz_cells_alloc, and on an invalid kind, a side that lz_lattice_side_check refuses,
 * or m = L / w < 3 (the message gives the largest rc allowed). O(ncells · 3^dim). */
lz_cells *lz_cells_alloc_lattice(lz_lattice_kind kind, int64_t side, double rc,
                                 lz_cells_order order, size_t nmax, size_t cap);
void lz_cells_free(lz_cells *c);

/* The storage index of the cell with coordinates cx[0 .. dim-1], each in [0, m).
 * O(1). */
static inline size_t lz_cells_index(const lz_cells *c, const int32_t *cx)
{
	size_t m = (size_t)c->m;
	size_t q = (size_t)cx[0] + m * (size_t)cx[1];
	if (c->dim == 3)
		q += m * m * (size_t)cx[2];
	return c->rank ? c->rank[q] : q;
}

/* The coordinates cx[0 .. dim-1] of the cell with storage index `cell` (< ncells).
 * O(1). */
void lz_cells_coords(const lz_cells *c, size_t cell, int32_t *cx);

/* Bin n particles: of[i] = lz_cells_of_site(c, r + i·dim) for lattice sites (every
 * coordinate in [0, L)), or lz_cells_of_point(c, x + i·dim) for points; sets c->n.
 * LZ_EINVAL if n > nmax, or (sites) the grid is not a lattice grid. O(n). */
int lz_cells_bin_sites(lz_cells *c, size_t n, const int32_t *r);
int lz_cells_bin_points(lz_cells *c, size_t n, const double *x);

/* perm[k] = the particle listed k-th when the cells are read in storage order and the
 * particles of a cell by increasing index (a stable counting sort of of[0 .. n-1]):
 * the numbering that puts particles near in space near in memory. Needs binning, not
 * lists. LZ_ENOMEM without scratch memory. O(n + ncells). */
int lz_cells_permutation(const lz_cells *c, uint32_t *perm);

/* Bytes held by the grid: tables, of[], the linked lists and the arrays. O(1). */
size_t lz_cells_bytes(const lz_cells *c);

/* ---- graded (solutions/04-neighbours/cells.c) ---- */

/* The Morton code of the cell coordinates (x, y, z) (z ignored when dim = 2): bit b
 * of x goes to bit dim·b of the code, bit b of y to bit dim·b + 1, bit b of z to bit
 * 3b + 2. So the cells of any aligned 2^k block get consecutive codes, and (0,0),
 * (1,0), (0,1), (1,1) are 0, 1, 2, 3. A 64-bit code: in 3D each coordinate < 2^21,
 * in 2D all 32 bits of x and y count. O(1) with bit tricks (or O(bits) with a loop). */
uint64_t lz_morton(int dim, uint32_t x, uint32_t y, uint32_t z);

/* The storage index of the cell of lattice site r[0 .. dim-1] (each coordinate in
 * [0, L)) in a lattice grid: cell coordinates r >> shift (header comment), then
 * lz_cells_index. O(1). */
size_t lz_cells_of_site(const lz_cells *c, const int32_t *r);

/* The storage index of the cell of point x[0 .. dim-1]. Periodic box: each coordinate
 * is first wrapped into [0, L) (any finite value: negative ones, L itself and beyond),
 * so the cell coordinate is floor(x / w) mod m. Box with walls: points outside [0, L]
 * go to the nearest edge cell. A coordinate whose floor(x / w) comes out as m through
 * round-off (x a hair below L) is taken as m - 1. O(1). */
size_t lz_cells_of_point(const lz_cells *c, const double *x);

/* The cells around `cell` (a storage index < ncells) in out[], as storage indices,
 * and their number. half = 0: the whole block, every cell whose coordinates differ
 * from cell's by -1, 0 or +1 on each axis, wrapped in a periodic box — 9 (27) cells;
 * with walls the ones beyond a wall are left out. half = 1: the cell itself and the
 * forward half of the other offsets, (a, b, c) with c > 0, or c = 0 and b > 0, or
 * c = b = 0 and a > 0 — 5 (14) cells — so that each pair of touching cells appears in
 * the half block of exactly one of the two. In every case cell itself comes first.
 * out has room for 27. O(3^dim). */
int lz_cells_stencil(const lz_cells *c, size_t cell, int half, uint32_t *out);

/* Build the linked lists from of[0 .. n-1]: head[] of every cell (the empty one too)
 * and next[] (header comment), each list in any order. O(n + ncells). */
void lz_cells_link(lz_cells *c);

/* Build the fixed arrays from of[0 .. n-1]: count[] and slot[] (header comment),
 * the particles of a cell in increasing index. LZ_EPHYS, with an lz_error naming the
 * cell, its capacity cap and what to do, if a cell would receive more than cap
 * particles (the arrays are then incomplete: never used); LZ_EINVAL if no arrays were
 * allocated (cap = 0). O(n + ncells). */
int lz_cells_fill(lz_cells *c);

/* Every pair of points closer than rc (distance² < rc², the minimum image in a
 * periodic box), found exactly once by scanning each cell's linked list against itself
 * and against its half block (lz_cells_link must have run on the same points). The
 * first cap pairs found go to out[] as (i, j) with i < j, in any order; returns how
 * many pairs there are (more than cap when out was too small, like snprintf).
 * Precondition: rc <= c->width. O(n · particles per cell). */
size_t lz_cells_pairs(const lz_cells *c, const double *x, double rc, lz_pair *out, size_t cap);

#endif
