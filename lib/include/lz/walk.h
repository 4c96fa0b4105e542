/* lz/walk.h — hard disks (spheres in 3D) that walk on a lattice (thesis 2.2, 2.4.1).
 *
 * Lattice units throughout: a particle is a disk (sphere) of radius R centred on a
 * lattice site; positions are integer sites wrapped into [0, L) of a periodic box of
 * side L (a power of two, lz/lattice.h). Two particles overlap when their
 * minimum-image distance² (lz_lattice_min_dist2) is below (2R)² = σ²: touching, d2 =
 * σ², is allowed. On the triangular lattice the coordinates are the sheared ones.
 *
 * One ensemble step (a sweep) offers every particle, in index order, one move to a
 * neighbouring site along a direction of the lattice's table (lz_lattice_dirs). A move
 * that would create an overlap is rejected: the particle stays. The direction is
 *   - random walk (LZ_WALK_RANDOM): drawn afresh, uniformly, before every move;
 *   - ballistic (LZ_WALK_BALLISTIC): kept from step to step, so a free particle flies
 *     straight; after a rejected move (a collision) a new direction is drawn
 *     uniformly from all directions, used from the next step on.
 * The random walk obeys detailed balance with every allowed configuration equally
 * likely: the hard-disk ensemble at packing fraction
 *     η = N · (area of one disk) / (area of the box) = N π R² / (L² · cell)
 * (4/3 π R³ / L³ in 3D), cell the area per site (lz_lattice_cell_volume).
 *
 * A slit (thesis 2.5.3, lz_walk_set_slit) makes the last coordinate (y in 2D, z in
 * 3D) non-periodic: two hard walls perpendicular to it stand at Cartesian heights 0
 * and H, and a centre must keep the distance R from both. The rows (values of the
 * last coordinate) a centre may take are then lo .. hi,
 *     lo = ceil(R / h),   hi = floor((H - R) / h),
 * h the Cartesian spacing of the rows: 1, or √3/2 on the triangular lattice. A move
 * to a row outside lo .. hi is rejected like an overlap (lz_walk_row_allowed).
 *
 * Cost: all pairs — O(N) per move, O(N²) per sweep (cell lists come in stage 04).
 */
#ifndef LZ_WALK_H
#define LZ_WALK_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/lattice.h"

typedef enum { LZ_WALK_RANDOM, LZ_WALK_BALLISTIC } lz_walk_motion;

/* The densest packings, no configuration beyond them exists: hexagonal disks π/√12,
 * fcc spheres π/√18. */
#define LZ_WALK_CLOSE_2D 0.90689968211710892
#define LZ_WALK_CLOSE_3D 0.74048048969306104

/* The walkers. Invariants: r holds n sites, dim int32_t each, flat (r[i·dim + c],
 * the layout of lz_gr_add_config), every coordinate in [0, L); no two particles
 * overlap once placed; dir[i] is in [0, ndir). */
typedef struct {
	lz_lattice_box *box;   /* owned: kind, dim, side, mask and the dc table */
	int dim;               /* 2 or 3 */
	size_t n;              /* particles */
	double radius;         /* R, lattice units */
	int64_t sigma2;        /* the smallest allowed distance²: ceil((2R)²) */
	lz_walk_motion motion;
	const lz_site *dirs;   /* the lattice's direction table (static) */
	int ndir;
	int32_t *r;            /* positions, n·dim */
	int *dir;              /* the current direction of each particle */
	uint64_t moves, accepted;  /* offered and accepted moves, for the acceptance */
	int slit;              /* 1 after lz_walk_set_slit: walls across the last axis */
	double slit_width;     /* H, Cartesian lattice units (0 without a slit) */
	int32_t lo, hi;        /* the rows a centre may take: 0 .. L-1 without a slit */
} lz_walk;

/* The Cartesian spacing h of the rows of the last coordinate: √3/2 on the triangular
 * lattice, 1 on the others (0 for an invalid kind). O(1). */
double lz_walk_row_spacing(lz_lattice_kind kind);

/* 1 if a centre may sit in row `row` of the last coordinate (always, without a slit),
 * 0 if a wall forbids it. O(1). */
static inline int lz_walk_row_allowed(const lz_walk *w, int32_t row)
{
	return row >= w->lo && row <= w->hi;
}

/* The packing fraction of n disks (spheres) of radius R in a box of side L on
 * lattice `kind`, in lattice units with the cell area (header comment). O(1). */
double lz_walk_packing(lz_lattice_kind kind, int64_t side, double radius, size_t n);

/* n walkers of radius R on lattice `kind` in a periodic box of side L, not yet placed
 * (all at the origin, direction 0). NULL with an lz_error naming the bad value on an
 * invalid kind, a side that is not a power of two in [2, LZ_LATTICE_SIDE_MAX], R <= 0
 * or 2R > L/2 (a disk would overlap its own periodic image, and the nearest image
 * would no longer be the only one in contact), n = 0, a packing fraction beyond the
 * densest packing of the lattice's dimension (π/√12 ≈ 0.9069 in 2D, π/√18 ≈ 0.7405
 * in 3D), or no memory. O(n + L). */
lz_walk *lz_walk_alloc(lz_lattice_kind kind, int64_t side, double radius, size_t n,
                       lz_walk_motion motion);
void lz_walk_free(lz_walk *w);

/* Put walls at Cartesian heights 0 and H = width across the last axis (header
 * comment); call it before lz_walk_place. LZ_EINVAL with a message giving the allowed
 * range when no row is left for a centre (H < 2R + h, roughly) or when H > L·h: the
 * box must hold the slit, and then no periodic image across the walls comes within
 * σ of a particle. O(1). */
int lz_walk_set_slit(lz_walk *w, double width);

/* The packing fraction of n disks (spheres) of radius R in a slit of width H across a
 * box of side L: n · (area of one disk) / (L · H), or n · (volume) / (L² · H). O(1). */
double lz_walk_slit_packing(int dim, int64_t side, double width, double radius, size_t n);

/* Put particle i at site s (wrapped into the box) with direction d, without any
 * overlap check (for tests and hand-made starts). LZ_EINVAL if i >= n, d is not a
 * direction, or the wrapped site is in a row the slit forbids. O(1). */
int lz_walk_set(lz_walk *w, size_t i, lz_site s, int d);

/* Place all n particles at random sites (inside the slit, if any), one after the other, each drawn again until
 * it overlaps none of those already placed (random sequential placement), and give
 * each a random direction. LZ_EPHYS with a message naming n, R and the packing if
 * some particle found no room in max_tries draws (0: 10000): random placement jams
 * near η ≈ 0.547 in 2D (0.38 in 3D), below close packing. O(n² · tries). */
int lz_walk_place(lz_walk *w, gsl_rng *rng, unsigned long max_tries);

/* Place all n particles on a random choice of the points of a grid of spacing
 * s = ceil(2R) lattice units along every axis (starting at row lo in a slit), which
 * no two disks can overlap on, with random directions: a start for densities where
 * random placement jams (narrow slits, η > 0.5); melt it by equilibration sweeps.
 * LZ_EPHYS with a message giving the grid's capacity when n exceeds it. O(grid). */
int lz_walk_place_grid(lz_walk *w, gsl_rng *rng);

/* The number of overlapping pairs (0 for a valid configuration). O(n²). */
size_t lz_walk_overlaps(const lz_walk *w);

/* ---- graded (solutions/02-lattice/walk.c) ---- */

/* Offer particle i the move by direction d (an index into w->dirs): the new site,
 * wrapped by the mask, is accepted when its last coordinate is a row the walls allow
 * (lz_walk_row_allowed) and its minimum-image distance² to every OTHER particle is at
 * least w->sigma2; then r[i] moves there. Returns 1 (moved) or 0
 * (rejected, r unchanged). Counts the move in w->moves and w->accepted. Does not
 * touch w->dir. Preconditions: i < n, 0 <= d < ndir. O(n). */
int lz_walk_try_move(lz_walk *w, size_t i, int d);

/* One ensemble step: particles 0 .. n-1 in order, each offered one move by
 * lz_walk_try_move. Random walk: dir[i] = a uniform draw in [0, ndir) before every
 * move. Ballistic: the move goes along dir[i]; when it is rejected, dir[i] becomes a
 * uniform draw in [0, ndir) (it may repeat the old one). Draw with
 * gsl_rng_uniform_int(rng, ndir). Returns the number of accepted moves. O(n²). */
size_t lz_walk_sweep(lz_walk *w, gsl_rng *rng);

#endif
