/* lz/shape.h — the lattice point set of a disk (sphere) and the points that change
 * when it takes one step (thesis 2.4.4, fig. 2.9).
 *
 * Lattice units throughout. A shape of real radius r on lattice `kind` is the set S
 * of integer offsets p = (x, y, z) from its centre with
 *     lz_lattice_dist2(kind, x, y, z) < r²            (strictly below)
 * so a point at distance exactly r is OUTSIDE. This is walk.h's overlap rule read
 * from the other side: when r = 2R = σ, offset p is in S exactly when another centre
 * at p would overlap (d2 < σ²), and touching (d2 = σ²) stays allowed. Because d2 is an
 * integer, d2 < r² is the same test as d2 < ceil(r²), the integer r2 stored below
 * (walk.h's sigma2 is the same number for r = 2R).
 *
 * On the triangular lattice the offsets are the sheared ones (lz/lattice.h): the
 * circle of radius r is the ellipse x² + xy + y² < r² in storage coordinates, and its
 * bounding box is wider, |x|, |y| < 2r/√3. The square8 and cubic18/26 kinds share
 * the metric of square and cubic; only their direction tables differ.
 *
 * When the centre steps by direction e = dirs[d] the covered set moves from S to
 * S + e. Only two thin crescents change:
 *     head[d] = (S + e) \ S      the points the shape gains,
 *     tail[d] = S \ (S + e)      the points it loses,
 * both as offsets from the centre BEFORE the step. They have equally many points
 * (S and S + e are the same size), about the perimeter (surface) of the shape, not its
 * area (volume): that is why moving a painted particle is cheap.
 */
#ifndef LZ_SHAPE_H
#define LZ_SHAPE_H

#include <stddef.h>
#include <stdint.h>

#include "lz/lattice.h"

/* The largest bounding box (2·reach + 1)^dim a shape may scan: 2^24 points, radius
 * about 2047 in 2D and 127 in 3D. */
#define LZ_SHAPE_BOX_MAX ((size_t)1 << 24)

/* A shape and its step tables. Invariants (after lz_shape_alloc): pts holds the n
 * offsets of S, each with |x|, |y|, |z| <= reach (z = 0 in 2D), no repeats; for every
 * direction d, head[d] and tail[d] hold nmove[d] offsets each (the sets above);
 * self[d] is 1 when dirs[d] itself is in S (a particle's own shape covers the site it
 * steps to), else 0. */
typedef struct {
	lz_lattice_kind kind;
	int dim;               /* 2 or 3 */
	double radius;         /* r, lattice units */
	int64_t r2;            /* ceil(r²): offset p is in S iff dist2(p) < r2 */
	int32_t reach;         /* every point of S has |x|, |y|, |z| <= reach */
	size_t n;              /* points in S */
	size_t cap;            /* room in pts: (2·reach + 1)^dim */
	lz_site *pts;          /* the n offsets of S */
	const lz_site *dirs;   /* the lattice's direction table (static) */
	int ndir;
	size_t *nmove;         /* nmove[d] = |head[d]| = |tail[d]| */
	size_t *capmove;       /* room in head[d] and in tail[d] */
	lz_site **head;        /* head[d]: (S + e) \ S, offsets from the old centre */
	lz_site **tail;        /* tail[d]: S \ (S + e), offsets from the old centre */
	int *self;             /* self[d]: 1 if dirs[d] is in S */
} lz_shape;

/* The shape of radius r on lattice `kind`, with its points and step tables filled by
 * the graded lz_shape_fill_points and lz_shape_fill_moves. NULL with an lz_error naming
 * the bad value on an invalid kind, r <= 0 or not finite, a bounding box beyond
 * LZ_SHAPE_BOX_MAX (the message gives the largest radius allowed), or no memory.
 * O(reach^dim + ndir · n). */
lz_shape *lz_shape_alloc(lz_lattice_kind kind, double radius);
void lz_shape_free(lz_shape *s);

/* 1 if offset p is in S: dist2(p) < r2. O(1). */
static inline int lz_shape_contains(const lz_shape *s, int32_t x, int32_t y, int32_t z)
{
	return lz_lattice_dist2(s->kind, x, y, z) < s->r2;
}

/* The mean of nmove[d] over the directions: the points a step repaints +1 (and as
 * many -1), the cost of a move. O(ndir). */
double lz_shape_mean_move(const lz_shape *s);

/* ---- graded (solutions/03-field/shape.c) ---- */

/* Fill s->pts with every offset of S (header comment) and set s->n. Scan the
 * bounding box |x|, |y| <= reach (and |z| <= reach in 3D; z = 0 in 2D), in any order.
 * Never writes more than s->cap points. Returns LZ_OK. O(reach^dim). */
int lz_shape_fill_points(lz_shape *s);

/* For every direction d, fill head[d] and tail[d] (header comment) and set nmove[d]
 * and self[d]. Precondition: pts and n are filled. Never writes more than capmove[d]
 * points per table. Returns LZ_OK. O(ndir · n). */
int lz_shape_fill_moves(lz_shape *s);

#endif
