/* lz/field.h — the field representation of hard disks (spheres) on a lattice, and
 * random sequential adsorption to exact jamming (thesis 2.4.4, 2.5.1).
 *
 * Lattice units throughout. Instead of asking every other particle "are you too
 * close?", each particle of radius R paints its EXCLUDED shape — the lattice points
 * within 2R = σ of its centre (lz/shape.h with r = 2R) — into a byte per site:
 *     cell[s] = the number of particles whose excluded shape covers site s.
 * By the strict rule of lz/shape.h a site s is covered by particle j exactly when a
 * centre at s would overlap j (minimum-image d2 < σ², walk.h's rule; touching is
 * allowed). So the collision test is one look-up at the centre, O(1), whatever the
 * density: a NEW centre may sit at s iff cell[s] == 0.
 *
 * Moving particle i by one step e = dirs[d]: its own shape covers the target t when
 * self[d] = 1 (e is inside the excluded shape, which holds for every step once
 * 2R > |e|), and then cell[t] counts i too. The move is allowed iff no OTHER particle
 * covers t, i.e. iff cell[t] == self[d]: the value 1 is fine only because that 1 is
 * i's own. (Asking "cell[t] <= 1" would be wrong: a 1 painted by a neighbour while i
 * does not cover t — possible for R <= 1/2 — would let i walk into the neighbour.)
 * The move itself repaints only the head points (+1) and the tail points (-1).
 *
 * The box is periodic, of side L (a power of two) in every direction, L^dim sites,
 * site (x, y, z) stored at cell[x | y << shift | z << 2·shift], shift = log2 P, where
 * P = L normally. Every painted offset is wrapped with & mask (mask = L - 1). For the
 * memory-locality experiment (thesis table 2.3) the box may sit in a corner of a
 * larger allocated lattice of side P > L (lz_field_alloc_in): rows are then P sites
 * apart in memory, the sites outside the box hold 255 and are never free. The excluded disk must fit in the box,
 * 2σ = 4R <= L (as in walk.h): then no particle covers a site twice through its
 * periodic images, and covered means "the nearest image overlaps".
 *
 * The field also keeps the number of free sites (cell == 0), so "is the box jammed?"
 * is answered exactly, by a count, not by a guess after many failed tries (thesis
 * 2.5.1: the field can be checked systematically).
 *
 * Bytes: a site can be covered at most 255 times. A non-overlapping configuration
 * stays far below (a handful of neighbours in 2D, a dozen or so in 3D); only a
 * hand-made overlapping pile could reach it, and lz_field_place refuses that.
 *
 * Cost: memory L^dim bytes; place/remove O(|S|) ~ σ^dim; move O(|head|) ~ σ^(dim-1);
 * the collision test O(1).
 */
#ifndef LZ_FIELD_H
#define LZ_FIELD_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/lattice.h"
#include "lz/shape.h"

/* The largest field: 2^30 sites (1 GiB of bytes): L <= 32768 in 2D, 1024 in 3D. */
#define LZ_FIELD_SITES_MAX ((size_t)1 << 30)

/* A field and its particles. Invariants: cell[s] is the number of the n particles
 * whose excluded shape (centre + excl->pts, wrapped) contains s; nfree is the number
 * of sites with cell == 0; r holds the n centres, dim int32_t each, flat, every
 * coordinate in [0, L); cap >= n is the room in r. */
typedef struct {
	lz_lattice_kind kind;
	int dim;              /* 2 or 3 */
	int32_t side;         /* L, a power of two */
	int32_t mask;         /* L - 1 */
	int shift;            /* log2 P, P the allocated side (P = L but in lz_field_alloc_in) */
	size_t nsites;        /* P^dim, the bytes in cell (L^dim but in lz_field_alloc_in) */
	uint8_t *cell;        /* the field, nsites bytes */
	size_t nfree;         /* sites with cell == 0 */
	double radius;        /* R, the particles' radius, lattice units */
	lz_shape *excl;       /* the excluded shape, radius 2R (owned) */
	size_t n;             /* particles */
	size_t cap;           /* room in r, in particles */
	int32_t *r;           /* centres, n·dim */
	uint64_t tries;       /* sites drawn by lz_field_rsa, for its speed figure */
} lz_field;

/* The index into cell of site (x, y, z), each coordinate wrapped into [0, L) (z is
 * ignored in 2D). O(1). */
static inline size_t lz_field_index(const lz_field *f, int32_t x, int32_t y, int32_t z)
{
	uint32_t m = (uint32_t)f->mask;
	size_t i = ((uint32_t)x & m) | (size_t)((uint32_t)y & m) << f->shift;
	if (f->dim == 3)
		i |= (size_t)((uint32_t)z & m) << (2 * f->shift);
	return i;
}

/* An empty field (every cell 0, no particle) for particles of radius R on lattice
 * `kind` in a periodic box of side L. NULL with an lz_error naming the bad value and
 * the allowed range on an invalid kind; a side that is not a power of two, below 2,
 * or with L^dim beyond LZ_FIELD_SITES_MAX; R <= 0 or not finite; 4R > L (the excluded
 * disk of radius 2R would wrap onto itself); an excluded shape beyond
 * LZ_SHAPE_BOX_MAX; or no memory. Builds the excluded shape with lz_shape_alloc
 * (graded code runs here). O(L^dim + shape). */
lz_field *lz_field_alloc(lz_lattice_kind kind, int64_t side, double radius);

/* As lz_field_alloc, but the box of side L sits in the corner of an allocated lattice
 * of side `pitch` (a power of two, L <= pitch, pitch^dim <= LZ_FIELD_SITES_MAX): the
 * same simulation spread over more memory. Cells outside the box hold 255 (never
 * free, never painted); nsites = pitch^dim, nfree counts the box only. Errors as
 * lz_field_alloc, and on a pitch that is not a power of two or below L.
 * O(pitch^dim + shape). */
lz_field *lz_field_alloc_in(lz_lattice_kind kind, int64_t side, double radius, int64_t pitch);
void lz_field_free(lz_field *f);

/* Room for at least n particles in r (grows by doubling). LZ_ENOMEM on failure, with
 * f unchanged. Amortised O(1) per particle. */
int lz_field_reserve(lz_field *f, size_t n);

/* The coverage (packing fraction) θ = n · (continuum area of a disk of radius R) /
 * (area of the box): n π R² / (L² · cell), or n (4/3) π R³ / L³ in 3D, cell the area
 * per site (lz_lattice_cell_volume) — the same number as lz_walk_packing. O(1). */
double lz_field_coverage(const lz_field *f);

/* The number of sites with cell == 0, counted by a full scan (a check on nfree).
 * O(L^dim). */
size_t lz_field_count_free(const lz_field *f);

/* ---- graded (solutions/03-field/field.c) ---- */

/* Add a particle at site c (wrapped into the box), as particle number n, and paint +1
 * on every site of its excluded shape, keeping nfree. No overlap check: hand-made
 * overlapping piles are allowed (tests build them). LZ_EPHYS, with f unchanged, if
 * some covered site already holds 255 (a byte would wrap); LZ_ENOMEM if r cannot
 * grow (lz_field_reserve). O(|S|). */
int lz_field_place(lz_field *f, lz_site c);

/* Take particle i away: paint -1 on its excluded shape, keep nfree, and move the
 * last particle into slot i (indices above i are not kept: particle n-1 becomes i).
 * LZ_EINVAL if i >= n. O(|S|). */
int lz_field_remove(lz_field *f, size_t i);

/* 1 if a NEW centre may sit at site s (wrapped): cell[s] == 0, else 0. O(1). */
int lz_field_is_free(const lz_field *f, lz_site s);

/* 1 if particle i may step by direction d without overlapping another particle:
 * cell[t] == excl->self[d], t = r[i] + dirs[d] wrapped (header comment), else 0.
 * Preconditions: i < n, 0 <= d < excl->ndir. O(1). */
int lz_field_can_move(const lz_field *f, size_t i, int d);

/* Step particle i by direction d unconditionally (check lz_field_can_move first):
 * +1 on the head points, -1 on the tail points of excl (offsets from the old centre),
 * keep nfree, and r[i] += dirs[d] wrapped. Preconditions: i < n, 0 <= d < ndir.
 * O(|head|). */
void lz_field_move(lz_field *f, size_t i, int d);

/* Random sequential adsorption: add particles at uniformly random free sites, one
 * after the other, until n == target (target 0: no limit) or no free site is left
 * (nfree == 0: jammed, established exactly, never guessed from failed tries). Each
 * new centre is a uniform draw among the sites free at that moment. Two phases with
 * the same law: while nfree >= L^dim / 16 (the box's sites, not nsites: a box in a
 * larger lattice, lz_field_alloc_in, draws the same sites), draw a site (x, then y,
 * then z, each gsl_rng_uniform_int(rng, L)) and keep it if it is free; after that,
 * list the free sites once by a scan and draw entries of the list
 * (gsl_rng_uniform_int(rng, m), m the entries left), dropping an entry whose site has
 * become covered. Every draw counts in f->tries. *jammed = 1 if nfree == 0 at the end, else 0. LZ_OK, or
 * LZ_ENOMEM if the list or r cannot grow (the particles placed so far stay).
 * O(N · |S| + L^dim). */
int lz_field_rsa(lz_field *f, gsl_rng *rng, size_t target, int *jammed);

#endif
