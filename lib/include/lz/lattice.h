/* lz/lattice.h — lattices: their kinds, direction tables, the distance² of a
 * displacement, and the minimum image in a periodic box whose side is a power of two.
 *
 * Lattice units throughout: a site is a vector of integers, the lattice spacing (the
 * nearest-neighbour distance) is 1, and distances² are exact integers (int64_t).
 *
 * The triangular lattice is stored sheared (thesis 2.4.5): site (i, j) is the point
 * i·l1 + j·l2 with l1 = (1, 0), l2 = (1/2, √3/2), kept at (i, j) of an ordinary square
 * array. Its six neighbours are then (±1, 0), (0, ±1), (1, -1) and (-1, 1) — the four
 * square neighbours and the anti-diagonal pair — and the true squared distance of an
 * integer displacement is dx² + dx·dy + dy², with no √3 anywhere. Each site owns the
 * area √3/2 (the rhombus l1 × l2).
 *
 * Periodic boxes are cubes (squares, rhombi) of side L, the same in every direction,
 * L a power of two, so that x & (L - 1) wraps any coordinate (lz/bits.h).
 */
#ifndef LZ_LATTICE_H
#define LZ_LATTICE_H

#include <stdint.h>

/* The largest periodic side: the distance-correction table has L entries, and the
 * minimum-image distance² reaches 3 (L/2)² ≈ 3.2e9 — beyond int32_t, hence int64_t. */
#define LZ_LATTICE_SIDE_MAX 65536

typedef enum {
	LZ_LATTICE_SQUARE,      /* 2D, 4 nearest neighbours */
	LZ_LATTICE_SQUARE8,     /* 2D, 4 nearest + 4 diagonal neighbours */
	LZ_LATTICE_TRIANGULAR,  /* 2D, 6 neighbours, stored sheared (above) */
	LZ_LATTICE_CUBIC,       /* 3D simple cubic, 6 face neighbours */
	LZ_LATTICE_CUBIC18,     /* 3D, 6 faces + 12 edges (face diagonals) */
	LZ_LATTICE_CUBIC26,     /* 3D, 6 faces + 12 edges + 8 corners (body diagonals) */
	LZ_NLATTICES
} lz_lattice_kind;

/* A site or a displacement in lattice units; z is 0 in 2D. */
typedef struct {
	int32_t x, y, z;
} lz_site;

/* Names as scene files spell them: "square", "square8", "triangular", "cubic",
 * "cubic18", "cubic26". parse returns LZ_EINVAL naming the choices. */
const char *lz_lattice_name(lz_lattice_kind kind);
int lz_lattice_parse(const char *name, lz_lattice_kind *kind);

/* 2 or 3 (0 for an invalid kind). */
int lz_lattice_dim(lz_lattice_kind kind);

/* The area (volume) one site owns, in units of the lattice spacing: 1 on the square
 * and cubic lattices, √3/2 on the triangular one. An ideal gas of N points on V sites
 * has N / (V · cell) points per unit area. */
double lz_lattice_cell_volume(lz_lattice_kind kind);

/* The Cartesian coordinates c[0..2] (lattice units, c[2] = 0 in 2D) of site p (dim =
 * lz_lattice_dim(kind) int32_t, the layout of a particle array) of a periodic box of
 * side L, each coordinate of p in [0, L). The triangular site (i, j) is at
 * (i + j/2, j·√3/2) with the x wrapped into [0, L): the sheared rhombus of the box is
 * then drawn as the L × L√3/2 rectangle, an equivalent periodic cell (rows are whole
 * periods L long). O(1). */
void lz_lattice_cartesian(lz_lattice_kind kind, int32_t side, const int32_t *p, double c[3]);

/* A bound on every coordinate of a displacement shorter than r on lattice `kind`: if
 * dist2(dx, dy, dz) < r² then |dx|, |dy|, |dz| <= the bound. ceil(r) on the square and
 * cubic lattices; ceil(2r/√3) on the sheared triangular one, where x² + xy + y² >=
 * 3x²/4. The half-width of a shape's bounding box, and the smallest cell side that
 * keeps pairs closer than r in neighbouring cells (lz/cells.h). 0 for an invalid
 * kind. O(1). */
double lz_lattice_reach(lz_lattice_kind kind, double r);

/* The direction table of a lattice (thesis 2.4.1, DIRX/DIRY): *n directions, 4, 8, 6,
 * 6, 18 or 26. Invariant for every kind: the opposite of direction i is direction
 * (i + n/2) mod n, so a reversal is one addition. In 2D the directions go
 * counterclockwise from (1, 0), so a turn by one step is i + 1 (on the triangular
 * lattice direction k points at k·60°, as the lattice gas's bit k — lz/bits.h). In 3D
 * the first half lists the nearer shells first: faces, then edges, then corners.
 * NULL (and *n = 0) for an invalid kind. O(1); the tables are static. */
const lz_site *lz_lattice_dirs(lz_lattice_kind kind, int *n);

/* LZ_OK if side is a power of two in [1, LZ_LATTICE_SIDE_MAX]; otherwise LZ_EINVAL
 * with an lz_error naming the value and the nearest allowed sizes. O(1). */
int lz_lattice_side_check(int64_t side);

/* The dimension (2 or 3) of lattice `kind` when side also passes
 * lz_lattice_side_check; otherwise 0 with an lz_error naming the bad value. The one
 * check every allocator of a box-sized object starts with. O(1). */
int lz_lattice_kind_side_check(lz_lattice_kind kind, int64_t side);

/* A periodic box with its distance-correction table. Invariant: side = mask + 1 is a
 * power of two, dc has side entries, and dc[u] is the minimum-image representative
 * of u (lz_lattice_dctable). */
typedef struct {
	lz_lattice_kind kind;
	int dim;        /* 2 or 3 */
	int32_t side;   /* L, the same in every direction */
	int32_t mask;   /* L - 1: (uint32_t)x & mask is x mod L for any int32_t x */
	int32_t *dc;    /* the distance-correction table, L entries */
} lz_lattice_box;

/* A box of side L for lattice `kind`, its table filled by lz_lattice_dctable. NULL
 * with lz_error on an invalid kind, a side lz_lattice_side_check refuses, or no
 * memory. O(L). */
lz_lattice_box *lz_lattice_box_alloc(lz_lattice_kind kind, int64_t side);
void lz_lattice_box_free(lz_lattice_box *b);

/* ---- graded (solutions/02-lattice/lattice.c) ---- */

/* The squared distance of the integer displacement (dx, dy, dz) on lattice `kind`,
 * in units of the lattice spacing: dx² + dy² (square, square8; dz is ignored),
 * dx² + dx·dy + dy² (triangular, sheared coordinates; dz ignored), dx² + dy² + dz²
 * (cubic, cubic18, cubic26). Exact for |dx|, |dy|, |dz| <= 2^30: the products are
 * formed in 64 bits. -1 for an invalid kind. O(1). */
int64_t lz_lattice_dist2(lz_lattice_kind kind, int32_t dx, int32_t dy, int32_t dz);

/* Fill the distance-correction table of a periodic side L (thesis 2.4.5, DCTBL, fig.
 * 2.16): dc[u] for every masked difference u = (x_i - x_j) & (L - 1) in [0, L) is the
 * representative of u modulo L in (-L/2, L/2]: u itself up to L/2, u - L above. So
 * the minimum-image component of any difference is dc[d & (L - 1)], one look-up and
 * no branch. At u = L/2 both images are equally far; the table keeps +L/2.
 * L must be a power of two in [1, LZ_LATTICE_SIDE_MAX]: otherwise LZ_EINVAL, with a
 * message naming L and the allowed sizes (lz_lattice_side_check), and dc untouched.
 * O(L). */
int lz_lattice_dctable(int64_t side, int32_t *dc);

/* The minimum-image squared distance of the raw displacement (dx, dy, dz) — any int32_t
 * values, e.g. x_i - x_j of wrapped or unwrapped coordinates — in box b: the smallest
 * distance² over all periodic images (dx + a L, dy + b L, dz + c L). On the square
 * and cubic lattices the component-wise correction by b->dc gives it. On the
 * triangular lattice the box is a rhombus whose nearest-image region is a hexagon
 * (the Wigner–Seitz cell), not the sheared square the table assumes: after the
 * table, when dx and dy have the same sign s, the images (dx - sL, dy) and
 * (dx, dy - sL) can be nearer (thesis fig. 2.15), and the smallest of the three is
 * the exact answer. (The thesis uses the table alone, which is right only for pairs
 * nearer than √3 L/4 ≈ 0.43 L, the inradius of the sheared square; g(r) up to L/2
 * needs the exact form.) O(1): a few look-ups, no loop. */
int64_t lz_lattice_min_dist2(const lz_lattice_box *b, int32_t dx, int32_t dy, int32_t dz);

#endif
