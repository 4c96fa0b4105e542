/* lz/lgas.h — lattice gases (thesis 1.4): HPP on the square lattice, FHP on the
 * triangular one, as arrays of bit-coded sites.
 *
 * Lattice units throughout: a site is (x, y) with 0 <= x, y < L, L a power of two,
 * stored at index (y << log2 L) | x; the lattice is periodic in both directions. Time
 * is in steps; a particle moves one lattice spacing per step.
 *
 * A site is one byte. Bit k (k < 6 for FHP, k < 4 for HPP) set means a particle
 * leaves the site in direction k of lz_lattice_dirs (lz/lattice.h): on the square
 * lattice k·90°, on the triangular lattice k·60° counterclockwise from 3 o'clock,
 * stored sheared, so the FHP directions are (1,0), (0,1), (-1,1), (-1,0), (0,-1),
 * (1,-1) and rows y are the lattice rows, √3/2 apart. Bit 7 (LZ_LGAS_WALL) marks an
 * obstacle site: particles that enter it are sent back the way they came
 * (bounce-back, no slip). Bit 6 is always 0.
 *
 * One time step is lz_lgas_collide then lz_lgas_propagate. Both conserve the number
 * of particles exactly, and away from walls the momentum too: every collision rule
 * keeps the sum of the direction vectors, which in sheared integer form (lz_lgas_totals)
 * is a pair of integers — conservation is checked exactly, never to a tolerance.
 */
#ifndef LZ_LGAS_H
#define LZ_LGAS_H

#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/lattice.h"

typedef enum { LZ_LGAS_HPP, LZ_LGAS_FHP } lz_lgas_model;

#define LZ_LGAS_WALL 0x80u
/* The collision table: entry (chirality << 6) | state, chirality 0 or 1. */
#define LZ_LGAS_TABLE_SIZE 128
/* The largest side: 2^14 sites per row, 2^28 bytes per lattice. */
#define LZ_LGAS_SIDE_MAX 16384

typedef struct {
	lz_lgas_model model;
	int nbits;        /* 4 (HPP) or 6 (FHP): directions per site */
	int32_t side;     /* L, a power of two */
	int32_t mask;     /* L - 1 */
	int shift;        /* log2 L: site (x, y) is at (y << shift) | x */
	uint8_t *site;    /* L² sites */
	uint8_t *next;    /* L² bytes of scratch for the propagation */
} lz_lgas;

/* "hpp" or "fhp"; parse returns LZ_EINVAL naming the choices. */
const char *lz_lgas_model_name(lz_lgas_model model);
int lz_lgas_parse(const char *name, lz_lgas_model *model);

/* The lattice of a model: LZ_LATTICE_SQUARE (HPP) or LZ_LATTICE_TRIANGULAR (FHP). */
lz_lattice_kind lz_lgas_lattice(lz_lgas_model model);

/* An empty lattice gas (every site 0) of side L. NULL with lz_error when L is not a
 * power of two in [2, LZ_LGAS_SIDE_MAX], the model is unknown, or no memory. O(L²). */
lz_lgas *lz_lgas_alloc(lz_lgas_model model, int64_t side);
void lz_lgas_free(lz_lgas *g);

/* Index of site (x, y), any integers (wrapped periodically by mask). O(1). */
static inline uint32_t lz_lgas_index(const lz_lgas *g, int32_t x, int32_t y)
{
	return ((uint32_t)((uint32_t)y & (uint32_t)g->mask) << g->shift) |
	       ((uint32_t)x & (uint32_t)g->mask);
}

/* ---- initial states (each overwrites every site but keeps the walls) ----
 * Every link (site, direction) of a non-wall site is drawn independently with GSL;
 * density d is the mean occupation per link, in (0, 1). LZ_EINVAL with lz_error for
 * a d or an amplitude that would make a probability leave [0, 1]. O(L²). */

/* Uniform: every link occupied with probability d (the equilibrium at rest). */
int lz_lgas_init_uniform(lz_lgas *g, double d, gsl_rng *rng);

/* A shear wave u_x(y) = u0 sin(2π y / L) along the rows, from the linearised
 * equilibrium N_k = d (1 + 2 c_k·u) with c_k the unit vector of direction k (k·60° or
 * k·90°). Needs |u0| <= 1/2 (no link probability below 0) and d (1 + 2 |u0|) < 1. */
int lz_lgas_init_shear(lz_lgas *g, double d, double u0, gsl_rng *rng);

/* A density pulse: d everywhere, d (1 + a) on the disk of radius L/8 (Euclidean,
 * lattice spacings) around the centre of the box. Needs d (1 + a) < 1, a > -1. */
int lz_lgas_init_pulse(lz_lgas *g, double d, double a, gsl_rng *rng);

/* A uniform flow u = (u0, 0) along the rows (+x), from the same linearised
 * equilibrium as the shear wave, N_k = d (1 + 2 c_k·u): the mean velocity of the
 * particles is u0 (lattice spacings per step). Needs |u0| <= 1/2 (no link
 * probability below 0) and d (1 + 2 |u0|) < 1. */
int lz_lgas_init_flow(lz_lgas *g, double d, double u0, gsl_rng *rng);

/* Mark site (x, y) as a wall (wrapped periodically); its particles stay and are
 * reflected at the next collision. */
void lz_lgas_set_wall(lz_lgas *g, int32_t x, int32_t y);

/* ---- Cartesian view and obstacles ----
 * The Cartesian position (X, Y) of site (x, y) in lattice spacings, in the rectangle
 * [0, L) x [0, L h) with h = √3/2 (FHP) or 1 (HPP): HPP (x, y); FHP
 * X = (x + (y - L/2)/2) mod L, Y = y √3/2, i.e. each row is shifted by half a
 * spacing against the one below, counted from the middle row y = L/2 (which is not
 * shifted), and wrapped along the row, which is periodic. The rectangle is a whole
 * period of the lattice, so a picture of it shows every site once; the flow along x
 * continues across its left and right edges, and across its top and bottom edges
 * with a shift of L/2 along x (the period (L/2, L√3/2) of the sheared storage). O(1). */
void lz_lgas_position(const lz_lgas *g, int32_t x, int32_t y, double *X, double *Y);

typedef enum { LZ_LGAS_NO_OBSTACLE, LZ_LGAS_PLATE, LZ_LGAS_DISK } lz_lgas_obstacle;

/* The largest obstacle_size on a lattice of side L: L/2, so the flow can pass. */
static inline int64_t lz_lgas_obstacle_max(int64_t side) { return side / 2; }

/* Mark an obstacle as walls (bounce-back), centred on the middle row y = L/2 at
 * X = L/4 (a quarter of the way along the flow, leaving three quarters of the box
 * for the wake; positions as lz_lgas_position):
 *   plate: a straight line across the flow (along y) of `size` sites, one per row,
 *          rows L/2 - size/2 ... ; on FHP each row takes the site nearest X = L/4, so
 *          the line zig-zags by half a spacing and is size·√3/2 spacings long, and
 *          consecutive rows step by at most one site, so that no particle crosses it;
 *   disk:  every site within Euclidean distance size/2 of the centre (a filled
 *          circle of diameter `size` lattice spacings).
 * Set walls before the initial state: the initial states leave wall sites as they
 * are, empty on a fresh lattice.
 * Returns the number of sites marked, or -1 with LZ_EINVAL (lz_error naming the size
 * and the range [1, lz_lgas_obstacle_max(L)]) for a size out of range or an unknown
 * kind. LZ_LGAS_NO_OBSTACLE marks nothing and returns 0. O(size) for a plate,
 * O(size²) for a disk. */
int64_t lz_lgas_add_obstacle(lz_lgas *g, lz_lgas_obstacle kind, int64_t size);

/* The number of particles, and the momentum Σ c_k in integer lattice units: the sum
 * of the integer direction vectors of lz_lattice_dirs (sheared for FHP, so p[0] is
 * along l1 and p[1] along l2; the Cartesian momentum is (p0 + p1/2, p1 √3/2)). Exact.
 * O(L²). */
void lz_lgas_totals(const lz_lgas *g, int64_t *mass, int64_t p[2]);

/* Σ over the sites of row y of the Cartesian x-momentum, doubled so it is an integer
 * (2 p_x = 2 dx + dy for FHP, 2 dx for HPP). O(L). */
int64_t lz_lgas_row_px2(const lz_lgas *g, int32_t y);

/* ---- graded (solutions/02-lattice/lgas.c) ---- */

/* Fill the collision table of a model: table[(c << 6) | s] is the state after the
 * collision of state s (its low nbits bits) with chirality c in {0, 1}.
 * FHP (thesis 1.4): a two-body head-on pair turns by +60° (c = 0) or -60° (c = 1);
 * a four-body state with two head-on holes turns the same way (so that the model is
 * particle-hole symmetric: table[c][~s] = ~table[c][s]); the symmetric three-body
 * states {0,2,4} and {1,3,5} swap (a turn by 60°); every other state is unchanged.
 * HPP: the head-on pair {0,2} becomes {1,3} and back, for both chiralities; the
 * other 14 states (and every s >= 16) are unchanged. Each entry keeps the number of
 * particles and the sum of their direction vectors. O(1): 128 entries. */
void lz_lgas_table(lz_lgas_model model, uint8_t table[LZ_LGAS_TABLE_SIZE]);

/* Move every particle one site in its direction: bit k of site r goes to bit k of site
 * r + e_k (lz_lattice_dirs of the model's lattice), wrapped periodically by the mask.
 * The wall bit stays where it is. Uses g->next and swaps it with g->site. O(L²). */
void lz_lgas_propagate(lz_lgas *g);

/* Collide every site in place: a wall site reverses every particle (d -> d + nbits/2,
 * lz_site_reverse for FHP); any other site s becomes table[(c << 6) | s] with a fresh
 * chirality bit c per site drawn from rng (32 bits per gsl_rng_get when the
 * generator gives 32 random bits, else one uniform bit per site). O(L²). */
void lz_lgas_collide(lz_lgas *g, const uint8_t table[LZ_LGAS_TABLE_SIZE], gsl_rng *rng);

#endif
