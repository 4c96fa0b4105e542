/* lz/edmd.h — event-driven molecular dynamics of hard spheres (3D) and hard disks
 * (2D): particles fly straight between collisions, so the simulation jumps from one
 * collision to the next, exactly (Miller & Luding, J. Comput. Phys. 193, 306 (2004); DynamO: Bannerman, Sargant & Lue, J. Comput. Chem. 32, 3329 (2011)).
 *
 * Units: the diameter σ = 1, the mass m = 1, and time in σ√(m/kT) (kT = 1 at the
 * start). Positions in [0, L) on every axis of a box of side L, periodic unless the
 * axis has walls; in 2D the third coordinate and velocity are 0 and stay 0.
 *
 * The state. Each particle carries its own clock (DynamO's "delayed states"): r is
 * where it was at its time t0, and it has flown straight since, so its position now is
 * r + v (now - t0) (with gravity, - g (now - t0)²/2 on x). Only the particles an
 * event involves are brought up to date; everyone else is left alone. Invariants
 * between events:
 *     t0(i) <= now <= t_event(i)   for every particle i;
 *     particle i is in the list of cell p[i].cell, and r(i) at any time up to its
 *     event lies in that cell (to round-off);
 *     the heap holds every particle exactly once, keyed by the time of its event.
 *
 * One event per particle (Miller & Luding). Particle i keeps only its EARLIEST event
 * ev[i]: a collision with a partner, a crossing of a face of its cell, or a bounce off
 * a wall. When i and j collide, their other predicted events become wrong — and so do
 * the events that others had predicted with i or j. Rather than search for and delete
 * those, every particle counts its collisions (count); an event with a partner stores
 * the partner's count at prediction, and when it comes up it is STALE if the partner
 * has collided since (p[j].count != ev.pcount): the particle then simply predicts
 * again. Its own count needs no check: whenever i's velocity changes, i is predicted
 * again and its heap entry replaced.
 *
 * Cells. The box is cut into m cells per side, each at least σ wide, so a particle's
 * partners are in the 3^dim block around its cell (lz/cells.h explains why). A
 * prediction looks only there and no further than the time the particle leaves its
 * cell: leaving is itself an event, after which it predicts again among its new
 * neighbours. Cost per event O(1) at fixed density; Miller & Luding find the fewest
 * events per second wasted at C/N ≈ 1.5 cells per particle (2D) and ≈ 8 (3D) in a
 * dilute gas, and as many cells as fit (side σ) in a dense one; in 3D this engine's
 * minimum is broad (C/N 1.5 to 10 within 12 % of the cheapest, lesson 05 §6) and
 * lz_edmd_auto_cells takes 3, which needs fewer bytes.
 *
 * Round-off (DynamO). A double holds 16 digits: an absolute time of 10^12 leaves a
 * resolution of 10^-4 for the events, which is an overlap. So `now` is kept small:
 * every 8N events the run brings every particle up to date and subtracts `now` from
 * every time (lz_edmd_rebase); the time already run is kept apart in t_base.
 *
 * Memory: 64 bytes of particle, 8 of event, 16 + 4 of heap, 4 of cell list, and 8 per
 * cell: about 110 bytes per particle in a dense fluid (lz_edmd_bytes).
 */
#ifndef LZ_EDMD_H
#define LZ_EDMD_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "lz/calendar.h"
#include "lz/heap.h"
#include "lz/rng.h"

/* ev.partner of a particle for which nothing will ever happen (at rest, alone). */
#define LZ_EDMD_NONE INT32_MIN
/* ev.partner of a particle that reaches the edge of its skin (neighbour lists: its
 * list is built again then). */
#define LZ_EDMD_SHELL (-7)
/* Faces of a cell: face f = 2·axis + up (up = 1 towards larger coordinates). A face
 * event is stored as partner = LZ_EDMD_FACE(f) = -1 - f, a negative number. */
#define LZ_EDMD_FACE(f) (-1 - (int32_t)(f))

/* From this many particles on (about 3 MB of particle records, beyond a core's L2
 * cache) the event loop prefetches (lz_edmd.prefetch): measured in lesson 05 §9. */
#define LZ_EDMD_FAR 32768

/* The most cells a box may have (2^27): cell numbers and their arithmetic stay well
 * inside 32 bits. */
#define LZ_EDMD_CELLS_MAX ((size_t)1 << 27)

/* Room for the candidates of one prediction (the particles of a block: at most about
 * 27 · 4 in a dense fluid, far fewer on average). */
#define LZ_EDMD_GATHER 512

/* The densest packings: fcc spheres π/(3√2), triangular disks π/(2√3). */
#define LZ_EDMD_CLOSE_3D 0.74048048969306104
#define LZ_EDMD_CLOSE_2D 0.90689968211710892

enum { LZ_EDMD_WALLS_NONE, LZ_EDMD_WALLS_X, LZ_EDMD_WALLS_BOX };

/* Where a prediction looks for partners (params.neighbours): the 3^dim cells around
 * the particle, or its own list of neighbours (see "Neighbour lists" below). */
enum { LZ_EDMD_CELLS, LZ_EDMD_LIST };

/* What orders the events (params.queue): automatic (the calendar with lists, the heap
 * with cells), the graded binary heap (lz/heap.h), its 4-ary variant, or a calendar
 * queue (lz/calendar.h). The last two are the library's, for lists only. */
enum { LZ_EDMD_QUEUE_AUTO, LZ_EDMD_HEAP, LZ_EDMD_HEAP4, LZ_EDMD_CALENDAR };

/* A particle: 64 bytes, one cache line. */
typedef struct {
	double r[3];     /* position at time t0, σ */
	double v[3];     /* velocity at time t0, σ per time unit */
	double t0;       /* the time r and v belong to (the particle's own clock) */
	uint32_t count;  /* collisions and wall bounces so far: changes whenever v does */
	uint32_t cell;   /* the cell whose list holds the particle */
} lz_edmd_particle;

/* The head of a cell's list, and its second particle beside it (second = next[head],
 * kept up to date): a cell's first two particles are read at once, without following
 * the list, and both with one cache line — a prediction's reads do not wait on each
 * other (lesson 05 §9). -1: no such particle. */
typedef struct {
	int32_t head;
	int32_t second;
} lz_edmd_list;

/* A particle's next event; its time is the particle's key in the heap. */
typedef struct {
	int32_t partner;  /* >= 0: collision with that particle; LZ_EDMD_FACE(f): leaving
	                     the cell through face f (or bouncing off the wall there);
	                     LZ_EDMD_NONE: never */
	uint32_t pcount;  /* the partner's count when the event was predicted */
} lz_edmd_event;

typedef struct {
	int dim;             /* 2 or 3 */
	size_t n;            /* particles, 1 <= n < 2^31 */
	double packing;      /* η = n·v1/L^dim, v1 = π/6 (3D) or π/4 (2D); sets L */
	double restitution;  /* between particles, in (0, 1]; walls are elastic */
	double gravity;      /* g >= 0 along -x (needs walls on x) */
	int walls;           /* LZ_EDMD_WALLS_NONE, _X (walls at x = 0 and L), _BOX */
	int cells;           /* cells per side, 0 = automatic (lz_edmd_auto_cells; with
	                        lists, lz_edmd_list_cells) */
	int neighbours;      /* LZ_EDMD_CELLS (0, the default) or LZ_EDMD_LIST */
	double shell;        /* lists: the shell S > 1 (σ); 0 = automatic
	                        (lz_edmd_list_shell) */
	int queue;           /* LZ_EDMD_QUEUE_AUTO (0), _HEAP, _HEAP4 or _CALENDAR */
} lz_edmd_params;

struct lz_edmd_lists;

typedef struct {
	int dim;
	size_t n;
	double L;               /* box side, σ */
	double restitution;
	double g;               /* gravity along -x */
	int wall[3];            /* 1: hard walls at 0 and L on this axis (centres stay in
	                           [1/2, L - 1/2]); 0: periodic */
	int m[3];               /* cells per side (m[2] = 1 in 2D); >= 3 when periodic */
	double w[3];            /* cell side L / m[a] (>= σ) */
	size_t ncells;          /* m[0]·m[1]·m[2] <= LZ_EDMD_CELLS_MAX */
	lz_edmd_list *list;     /* list[c]: the head of cell c's list of particles (in
	                           pages that take memory where written, lz_bigmem_sparse:
	                           a rank of lz/pedmd.h writes only the cells it holds) */
	int32_t *next;          /* next particle in the same cell, -1 at the end; and
	                           next[-1] = -1, a sentinel: the successor of "no
	                           particle" is "no particle", so a loop may read it */
	lz_edmd_particle *p;    /* n particles */
	lz_edmd_event *ev;      /* their next events */
	lz_heap *heap;          /* particle i keyed by the time of ev[i] (NULL: cal) */
	lz_calendar *cal;       /* the same in a calendar (lists only; NULL: heap) */
	struct lz_edmd_lists *lists;  /* neighbour lists (NULL: cells, the graded loop) */
	double now;             /* the time of the last event, since the last re-base */
	double t_base;          /* the time at which now was last set to 0 */
	uint64_t since_rebase;  /* events since then */
	unsigned sort_every;    /* renumber the particles cell by cell every this many
	                           re-bases (lz_edmd_sort); 0: never. Default 0: no gain
	                           once the loop prefetches (lesson 05 §9) */
	unsigned rebases;       /* re-bases so far */
	int rebase_auto;        /* 1 (the default): lz_edmd_run re-bases every 8 max(n,
	                           1024) events; 0: only when asked (lz_edmd_rebase) — for
	                           a run that must re-base at given absolute times, as the
	                           serial reference of the parallel engine (lz/pedmd.h) does */
	int prefetch;           /* 1: the arrays outgrow the caches (n >= LZ_EDMD_FAR), so
	                           the loop asks for the memory it will read next ahead of
	                           time; 0: it would only cost instructions. Set by
	                           lz_edmd_alloc; the trajectory is the same either way */
	uint64_t coll_mark;     /* collisions at the last re-base (the collapse guard) */
	/* counters since the last lz_edmd_reset_counts (the event loop adds to them) */
	uint64_t events;        /* heap pops, stale ones included */
	uint64_t collisions;    /* pair collisions */
	uint64_t crossings;     /* cell crossings */
	uint64_t bounces;       /* wall bounces */
	uint64_t stale;         /* events found stale */
	uint64_t rebuilds;      /* neighbour lists built again (skin events) */
	double virial;          /* Σ over collisions of r_ij · Δp_i (> 0), σ·momentum */
	double t_reset;         /* the absolute time of the last reset */
} lz_edmd;

/* The particle whose event comes next, and its time, whichever the queue. O(1). */
static inline uint32_t lz_edmd_first(const lz_edmd *e)
{
	return e->cal ? lz_calendar_top(e->cal) : lz_heap_top(e->heap);
}
static inline double lz_edmd_first_t(const lz_edmd *e)
{
	return e->cal ? lz_calendar_top_t(e->cal) : lz_heap_top_t(e->heap);
}

/* How far a particle may be from the cell that holds it (σ): 0 with cells (it is in
 * it), the skin δ with lists (they hold it by its centre). O(1). */
static inline double lz_edmd_stray(const lz_edmd *e);

/* ---- flight: library, inline (the hot loop calls these) ---- */

/* Position and velocity of p at time t (>= p->t0, same time base as now). O(1). */
static inline void lz_edmd_state(const lz_edmd *e, const lz_edmd_particle *p, double t,
                                 double r[3], double v[3])
{
	double dt = t - p->t0;
	for (int a = 0; a < 3; a++) {
		r[a] = p->r[a] + p->v[a] * dt;
		v[a] = p->v[a];
	}
	r[0] -= 0.5 * e->g * dt * dt;
	v[0] -= e->g * dt;
}

/* dr = r_b - r_a at the nearest image on the periodic axes (a and b at the same
 * time): the separation a collision bounces along. Swapping a and b negates it
 * exactly. O(1). */
static inline void lz_edmd_separation(const lz_edmd *e, const lz_edmd_particle *a,
                                      const lz_edmd_particle *b, double dr[3])
{
	for (int x = 0; x < 3; x++) {
		dr[x] = b->r[x] - a->r[x];
		if (!e->wall[x] && x < e->dim)
			dr[x] -= e->L * rint(dr[x] / e->L);
	}
}

/* Bring p up to time t: r, v and t0 = t. O(1). */
static inline void lz_edmd_advance(const lz_edmd *e, lz_edmd_particle *p, double t)
{
	lz_edmd_state(e, p, t, p->r, p->v);
	p->t0 = t;
}

/* The block of cells around a cell, axis by axis: on axis a the cells at offsets
 * -1, 0, +1 (n[a] of them: 3, fewer next to a wall, 1 on z in 2D). Cell number
 *     off[0][x] + off[1][y] + off[2][z]     for x < n[0], y < n[1], z < n[2]
 * is a cell of the block (27 in 3D, 9 in 2D), and shift[a][.] is what to add on axis a
 * to a position in that cell to bring it next to the centre cell across the periodic
 * boundary (0 or ±L). */
typedef struct {
	int n[3];
	uint32_t off[3][3];  /* the cell coordinate times its stride (1, m[0], m[0]·m[1]) */
	double shift[3][3];
	int wraps;           /* 1 when some shift is not 0 (the block crosses the periodic
	                        boundary); 0: every cell sees the centre's positions */
} lz_edmd_block;

/* Fill b with the block around cell c. O(1). */
void lz_edmd_block_of(const lz_edmd *e, uint32_t c, lz_edmd_block *b);

/* Ask the memory system for the cell heads of the block around cell c (a hint: it
 * changes nothing and never faults), so that a prediction for a particle in c finds
 * them in the cache. O(1): 2 prefetches per row of the block. */
void lz_edmd_prefetch_block(const lz_edmd *e, uint32_t c);

/* Before the next event: ask the memory system for what it and the two after it will
 * read (cells, records, heap nodes), a stage of each chain of misses per event, so
 * that successive events' misses overlap (lesson 05 §9). A hint only: nothing is
 * written. O(1); worth it when the system outgrows the cache (e->prefetch). */
void lz_edmd_fetch_ahead(const lz_edmd *e);

/* The cell across face f of cell c, and in *jump what to add to r[f/2] of a particle
 * that crosses it (±L when it wraps, else 0). Precondition: f is not a wall face.
 * O(1). */
uint32_t lz_edmd_cell_across(const lz_edmd *e, uint32_t c, int f, double *jump);

/* The cell that holds position r (a position a hair outside the box, by round-off,
 * goes to the nearest cell). O(1). */
uint32_t lz_edmd_cell_of(const lz_edmd *e, const double r[3]);

/* Cell-list bookkeeping (list and next): take i out of its cell's list
 * (O(particles in the cell)), put it at the head of cell c's list and set p[i].cell =
 * c (O(1)), empty every cell (O(cells)). */
void lz_edmd_cell_remove(lz_edmd *e, uint32_t i);
void lz_edmd_cell_insert(lz_edmd *e, uint32_t i, uint32_t c);
void lz_edmd_cell_clear(lz_edmd *e);

/* The earliest t >= 0 at which x(t) = x + v t - g t²/2 (g > 0) reaches lo (going
 * down) or hi (going up), lo <= x <= hi up to round-off; *up = 1 when it is hi.
 * Numerically stable roots (no difference of nearly equal numbers). O(1). */
double lz_edmd_fall_time(double x, double v, double g, double lo, double hi, int *up);

/* ---- graded (solutions/05-edmd/edmd.c) ---- */

/* The time until two spheres of diameter 1 touch, dr = r_j - r_i and dv = v_j - v_i
 * at the same instant (3 components; 0 in z in 2D): the smallest t >= 0 with
 * |dr + dv t| = 1, or INFINITY when they never touch: receding or moving sideways
 * (dr·dv >= 0), missing each other, or only grazing (touching with no approach). A
 * pair already touching (or overlapping by round-off) and approaching collides at
 * t = 0. The root is computed without cancellation. O(1). */
double lz_edmd_pair_time(const double dr[3], const double dv[3]);

/* Collide a and b, both at the same time, dr = r_b - r_a (the nearest image, |dr| = 1
 * up to round-off) with restitution e_r: the velocity components along k = dr/|dr|
 * change so that the normal relative velocity (v_b - v_a)·k becomes -e_r times
 * itself; momentum is conserved and the kinetic energy drops by exactly
 * (1 - e_r²)/4 · ((v_b - v_a)·k)² (nothing when e_r = 1). The tangential components
 * do not change. Returns the collision's virial r_ab·Δp_a = |dr|·|Δp| (> 0). O(1). */
double lz_edmd_bounce(lz_edmd_particle *a, lz_edmd_particle *b, const double dr[3],
                      double restitution);

/* The time until a particle at r with velocity v (both at the same instant, r inside
 * cell c) leaves the cell through one of its faces, or reaches a wall: on an axis
 * with walls, the face of an edge cell on the wall side is replaced by the contact
 * r[a] = 1/2 (or L - 1/2). Axis 0 with gravity: lz_edmd_fall_time. Sets *face to the
 * face (2·axis + up). Returns a time >= 0 (round-off may put r a hair outside its
 * cell: that is time 0), or INFINITY when the particle is at rest without gravity.
 * O(dim). */
double lz_edmd_cell_time(const lz_edmd *e, const double r[3], const double v[3], uint32_t c,
                         int *face);

/* Predict particle i's next event at time now: the earliest of its cell's face time
 * and its collision times with every particle of the block around its cell (at their
 * nearest images); store it in ev[i] (with the partner's count) and give i that time
 * in the heap (push when i is not in it, else update). O(3^dim · particles per cell
 * + log N). */
void lz_edmd_predict(lz_edmd *e, uint32_t i);

/* Carry out the earliest event: pop nothing — read the heap's top i and its time t;
 * count it (events); set now = t;
 *   - collision with j, stale (j's count changed): count it (stale), predict i again;
 *   - collision: bring i and j to t, bounce them (add the virial), count the
 *     collision (both counts + 1), predict i and j again;
 *   - face of a wall: bring i to t, reverse v[axis], count the bounce (count + 1),
 *     predict i again;
 *   - face: bring i to t, move it to the cell across (wrapping r across the periodic
 *     boundary), count the crossing, predict i again.
 * Only the one or two particles involved are touched. Returns 0, or -1 (doing
 * nothing) when the next event is at infinity. O(log N) at fixed density. */
int lz_edmd_step(lz_edmd *e);

/* ---- set-up and the run (library) ---- */

/* The cells per side Miller & Luding would choose: as many as fit (side >= σ) in a
 * dense fluid, but no more than about 1.5 per particle in 2D, 3 in 3D (as fast as
 * Miller & Luding's 8 within the noise for this engine, lesson 05 §6), at most
 * 2^27 cells. 0 when even 3 per side do not fit on a periodic axis. O(1). */
int lz_edmd_auto_cells(int dim, size_t n, double L);

/* A system for p (checked: dim, n, packing below close packing, restitution in (0,1],
 * gravity >= 0 and then walls on x, cells >= 3 per periodic side and >= σ wide — a
 * box too small for three cells per side is refused with the smallest n that fits).
 * Particles are not placed yet. NULL with lz_error on failure. O(n + cells). */
lz_edmd *lz_edmd_alloc(const lz_edmd_params *p);
void lz_edmd_free(lz_edmd *e);

/* Room for n particles, more or fewer (1 <= n < 2^31; cells and a heap, not lists or
 * a calendar): e->n becomes n, the particles below both keep their records, events,
 * cells and keys; new ones are zero records in no cell and not in the heap, their
 * events NONE; those dropped must be in no cell and not in the heap (the heap is
 * checked). e->prefetch as lz_edmd_alloc sets it for n. For a system whose particles
 * change in number (a rank of lz/pedmd.h). LZ_OK, or LZ_EINVAL / LZ_ENOMEM with e
 * unchanged but for arrays already resized. O(n). */
int lz_edmd_resize(lz_edmd *e, size_t n);

/* Place the particles on a simple cubic (square in 2D) lattice — or fcc in 3D when
 * the simple cubic one would be closer than σ — shifted by a random vector along the
 * periodic axes (so that no row of sites sits on a cell face), on a random subset of
 * its sites,
 * with Gaussian velocities of zero total momentum scaled to kT = 1; then lz_edmd_start.
 * LZ_EINVAL when no lattice fits the packing (it says which N would). O(n + cells). */
int lz_edmd_place_lattice(lz_edmd *e, lz_rng *rng);

/* Set the particles from r[i·3 + a], v[i·3 + a] (z components 0 in 2D), then
 * lz_edmd_start. Refused with LZ_EINVAL naming the particle: a position outside
 * [0, L) on a periodic axis (beyond 1e-12, which is wrapped as round-off) or beyond a
 * wall contact, a NaN, or two particles closer than σ (less 1e-10) (checked with the
 * cells, O(n)). */
int lz_edmd_set(lz_edmd *e, const double *r, const double *v);

/* The inverse of lz_edmd_set: every particle brought to now (lz_edmd_sync), its
 * position into r[i·3 + a], wrapped into [0, L) on the periodic axes, its velocity
 * into v[i·3 + a] (z components 0 in 2D). What it writes, lz_edmd_set takes back
 * into a system of the same box. O(n). */
void lz_edmd_get(lz_edmd *e, double *r, double *v);

/* Maxwell velocities into v (3 per particle, z = 0 in 2D): Gaussian, the total
 * momentum removed (n > 1), scaled to kT = 1 exactly. O(n). */
void lz_edmd_maxwell(const lz_edmd *e, lz_rng *rng, double *v);

/* File all particles into their cells, predict every event and fill the heap; now =
 * 0, t0 = 0 for all, counters reset (with lists: lz_edmd_list_start). LZ_OK, or
 * LZ_ENOMEM (lists only). O(n log n). */
int lz_edmd_start(lz_edmd *e);

/* Run events until `events` more have been carried out or the absolute time reaches
 * t_stop (INFINITY: no limit); at t_stop every particle is brought to t_stop. Re-bases
 * every 8 max(n, 1024) events (unless rebase_auto is 0) and renumbers the particles cell
 * by cell at each re-base when sort_every asks.
 * LZ_EINVAL when t_stop is before the clock (time does not run backwards).
 * LZ_EPHYS with lz_error: inelastic collapse (the clock stalls: 8 max(n, 1024) events,
 * most of them collisions, in less than 1e-12 of the time a particle at the current
 * speed needs to fly 1 σ — crossings at one instant, as of a lattice start, are
 * finite and do not count) or nothing left to happen. O(events · log N). */
int lz_edmd_run(lz_edmd *e, uint64_t events, double t_stop);

/* Bring every particle to now (t0 = now). O(n). */
void lz_edmd_sync(lz_edmd *e);

/* lz_edmd_sync, then subtract now from every time (t0, the queue's keys) and add it
 * to t_base. The order of the events is unchanged. LZ_OK, or LZ_ENOMEM (a calendar
 * that could not be laid out again). O(n). */
int lz_edmd_rebase(lz_edmd *e);

/* Renumber the particles cell by cell (cells in row-major order), so that particles
 * near in space are near in memory; events, partners, heap and lists follow. O(n +
 * cells). */
int lz_edmd_sort(lz_edmd *e);

/* The absolute time t_base + now. */
static inline double lz_edmd_time(const lz_edmd *e) { return e->t_base + e->now; }

/* Set the absolute time to t (the clock reads t; now stays small). O(1). */
void lz_edmd_set_time(lz_edmd *e, double t);

/* Zero the counters and the virial; t_reset = the absolute time. O(1). */
void lz_edmd_reset_counts(lz_edmd *e);

/* ---- observables and guards (library) ---- */

/* Kinetic energy Σ v²/2 (with gravity, plus Σ g x: the total energy). O(n). */
double lz_edmd_energy(const lz_edmd *e);
/* Total momentum into P[3]. O(n). */
void lz_edmd_momentum(const lz_edmd *e, double P[3]);
/* kT = 2 KE / (dim · n), the kinetic energy at now. O(n). */
double lz_edmd_temperature(const lz_edmd *e);

/* The largest overlap 1 - |r_ij| over all pairs at now (0 when none), with the
 * cells: O(n). *pi, *pj (may be NULL) get the pair. */
double lz_edmd_max_overlap(const lz_edmd *e, uint32_t *pi, uint32_t *pj);

/* LZ_OK when the invariants above hold (t0 <= now <= event time, every particle in
 * the right cell's list and inside that cell to 1e-9, heap valid); else LZ_EDOM with
 * lz_error naming the particle. O(n + cells). For tests and guards. */
int lz_edmd_audit(const lz_edmd *e);

/* Bytes of memory per particle: particles, events, heap, lists and cells. O(1). */
double lz_edmd_bytes(const lz_edmd *e);

/* ---- neighbour lists (library: params.neighbours = LZ_EDMD_LIST) ----
 *
 * In a dense fluid most of the 3^dim·(particles per cell) candidates of a cell
 * prediction are too far to matter, and the cells are read for nothing. With lists,
 * a prediction scans only the particle's NEIGHBOURS: the particles whose centres lie
 * within the shell S of its own (Smallenburg, Eur. Phys. J. E 45, 22 (2022), §2.2;
 * the neighbour lists of lesson 04, made exact for events). A particle's CENTRE is
 * where it stood when its list was built; while every particle stays within the skin
 * δ = (S - 1)/2 of its centre, two particles whose centres are S or more apart stay
 * at least 1 apart, so the list holds every possible partner. Reaching the edge of
 * the skin is an event (partner LZ_EDMD_SHELL) in place of the cell crossings: the
 * list is built again around the particle's position then, from the cells (at least
 * S wide, holding the particles by their centres). Lists are symmetric — building i's
 * list takes i off its old neighbours' lists and puts it on its new ones' — so that
 * whichever of two neighbours changes velocity predicts the pair again, and one event
 * per particle stays enough. A wall is an event of its own (a wall face, as with
 * cells) for a particle whose centre lies within δ of the contact; under gravity the
 * skin is left no later than |v| t + g t²/2 = δ says (a bound, so early at worst).
 * Positions are wrapped into the box when a list is built, and stray at most δ
 * outside between. The trade (lesson 05 §10): a wider shell means fewer rebuilds but
 * more candidates per prediction, and 4 bytes per neighbour.
 *
 * Invariants (lz_edmd_list_audit): |r(i) - centre(i)| <= δ at now; the cells hold
 * every particle by its centre; j is in i's list exactly when i is in j's, and then
 * their centres are less than S apart — and every such pair is listed. */
/* A particle's block (list mode): its centre in units of L/65536 on each axis (16 bits:
 * the particle starts its skin at most a unit off it, 0.007σ at L = 471 — only the
 * centre's own value matters to the invariants), its neighbour count, its flags (bit
 * 0: the centre lies within S of a periodic face, so a separation needs the nearest
 * image; bit 1 + a: within δ of a wall contact on axis a), and room for `cap`
 * neighbours. A longer list keeps its first cap - 1 in the block and the rest in a
 * chain of chunks whose first number takes the last slot. */
typedef struct {
	uint16_t c[3];
	uint8_t count, edge;
	uint32_t nb[];
} lz_edmd_nbl;

#define LZ_EDMD_CHUNK 7
typedef struct {
	uint32_t next;                /* the next chunk of the chain, or UINT32_MAX */
	uint32_t nb[LZ_EDMD_CHUNK];
} lz_edmd_chunk;

typedef struct lz_edmd_lists {
	double shell;        /* S > 1, σ */
	double skin;         /* δ = (S - 1)/2 */
	double unit;         /* L / 65536: the step of the centres */
	uint32_t cap;        /* neighbours a block holds (2 .. 255) */
	size_t stride;       /* bytes per block: sizeof(lz_edmd_nbl) + 4 cap */
	unsigned char *block;  /* the n blocks */
	lz_edmd_chunk *chunk;  /* the chunks of the longer lists */
	size_t nchunk, capchunk;
	uint32_t spare;      /* the first free chunk (a list through next) */
	size_t chunks;       /* chunks in use */
	int wide;            /* 1: predictions by the AVX2 build (lz_edmd_list_wide) */
} lz_edmd_lists;

/* The default shell: the S that the measurements of lesson 05 §10 found fastest at
 * this packing, 1.5 or narrower in a dense fluid (1.3 near jamming), wider in a dilute
 * one; narrowed where the fastest would need more than 160 bytes per particle. O(1). */
double lz_edmd_list_shell(int dim, double packing);

/* The cells per side for lists of shell S in a box of side L: as many as fit at least
 * S wide, but no more than about 3 per particle (0 when fewer than 3 fit on a periodic
 * axis). O(1). */
int lz_edmd_list_cells(int dim, size_t n, double L, double shell);

/* Lists of shell S for system e (its n and L set): room for the neighbours of a random
 * gas at its density and some more. NULL with lz_error when out of memory. Called by
 * lz_edmd_alloc. O(n). */
lz_edmd_lists *lz_edmd_list_alloc(const lz_edmd *e, double shell);
void lz_edmd_list_free(lz_edmd_lists *l);

/* lz_edmd_start with lists (which then resets the counters): every centre where its
 * particle is, the cells by centre, every list built, every particle predicted (the
 * queue filled). LZ_OK, or LZ_ENOMEM when the lists cannot grow. O(n · neighbours). */
int lz_edmd_list_start(lz_edmd *e);

/* Predict particle i at now from its list, its skin and, when near one, the walls:
 * ev[i] and its key in the queue. Four pairs to a vector; built for any processor
 * and, on x86-64 with gcc or clang, for AVX2: the same bits either way. LZ_OK, or
 * LZ_ENOMEM (a calendar day that cannot grow). O(neighbours + log n). */
int lz_edmd_list_predict(lz_edmd *e, uint32_t i);

/* Which build of lz_edmd_list_predict e's lists use: wide = 1 the AVX2 one when the
 * processor has AVX2 (the default), 0 the one for any processor. Returns the build
 * now in use (1: AVX2). For the test that both give the same bits. O(1). */
int lz_edmd_list_wide(lz_edmd *e, int wide);

/* lz_edmd_step with lists: a collision (or a stale one) as with cells; a skin event
 * builds the particle's list again (rebuilds + 1); a wall face bounces. 0, -1 when
 * nothing will ever happen, or LZ_ENOMEM (> 0, with lz_error) when a list cannot grow.
 * O(neighbours + log n); a rebuild O(3^dim · particles per cell + neighbours²). */
int lz_edmd_list_step(lz_edmd *e);

static inline double lz_edmd_stray(const lz_edmd *e)
{
	return e->lists ? e->lists->skin : 0;
}

/* Whether lists beat cells for n particles at this packing, as lesson 05 §10 measured
 * (3D from η = 0.35, or 0.28 below LZ_EDMD_FAR particles; 2D from 0.5), and the box
 * holds lists of the automatic shell:
 * LZ_EDMD_LIST or LZ_EDMD_CELLS. O(1). */
int lz_edmd_list_pays(int dim, size_t n, double packing);

/* One event, whichever the neighbours: lz_edmd_step or lz_edmd_list_step (0, -1, or
 * an LZ_E code). O(1) on average. */
int lz_edmd_next(lz_edmd *e);

/* lz_edmd_fetch_ahead with lists: the next events' records, lists and neighbours. */
void lz_edmd_list_fetch_ahead(const lz_edmd *e);

/* The invariants above, and every particle in the cell of its centre. LZ_OK or LZ_EDOM
 * naming the particle. O(n · neighbours). */
int lz_edmd_list_audit(const lz_edmd *e);

/* Renumber the lists after the particles: particle i becomes to[i]. O(n · cap). */
int lz_edmd_list_renumber(lz_edmd *e, const uint32_t *to);

/* The mean number of neighbours in a list: the candidates of a prediction. O(n). */
double lz_edmd_list_mean(const lz_edmd *e);

/* Bytes per particle of the lists: the blocks and the chunks. O(1). */
double lz_edmd_list_bytes(const lz_edmd *e);

#endif
