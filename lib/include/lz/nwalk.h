/* lz/nwalk.h — one hard-disk (hard-sphere) random walk, four ways to find the
 * neighbours: the drivers of thesis table 2.2.
 *
 * Lattice units throughout. The system is lz/walk.h's random walk: n disks of radius
 * R (σ = 2R) on the sites of a periodic lattice box of side L; one sweep offers every
 * particle, in index order, one step along a direction drawn with
 * gsl_rng_uniform_int(rng, ndir); a step that would bring it closer than σ to another
 * particle (distance² < ceil(σ²)) is refused. The four drivers differ only in how they
 * find the particles to test a step against:
 *   - LZ_NWALK_NL  Verlet list, rebuilt from all pairs every `refresh` sweeps: O(N²);
 *   - LZ_NWALK_FNL the same list refreshed from the neighbours of the neighbours with
 *                  two copies (lz_nlist_refresh): O(N), first built from cells;
 *   - LZ_NWALK_CL  cell lists, re-binned every `refresh` sweeps; a step is tested
 *                  against every particle of the 3^dim cells around the particle's cell
 *                  as last binned;
 *   - LZ_NWALK_FR  the field of stage 03 (lz/field.h): one look-up per step, no lists.
 * All four draw the same random numbers in the same order, so while the lists are safe
 * they make the same decisions and produce the SAME trajectory, bit for bit.
 *
 * Ranges. A step moves a particle by at most lmax (1 on the square, triangular and
 * cubic lattices, √2 on square8 and cubic18, √3 on cubic26), so the pairs that can
 * decide the next step are those closer than
 *     r_c = σ + lmax                       (the interaction range),
 * and the lists hold the pairs closer than r_l = r_c + Δr (skin Δr > 0). A pair that
 * was farther than r_l at a refresh closes in by at most 2·lmax per sweep, so after k
 * sweeps it is still at least r_l - 2k·lmax apart, and the lists stay safe for
 *     refresh_safe = floor(Δr / (2 lmax))   sweeps
 * (0 when Δr < 2 lmax: then no interval is safe). Within it every step is judged
 * right, and the audit at its end finds nothing. (The steps alone would allow
 * floor((Δr + lmax) / (2 lmax)), one sweep more for some skins — a pair is at least
 * r_l - (2k - 1)·lmax apart when one of them moves in the k-th sweep — but the audit
 * would then count pairs that reached r_c in the last sweep, after every step that
 * could have misjudged them.) A longer interval is allowed — it is the trade the
 * lesson measures — and its cost is counted: before every refresh the audit (when
 * on) counts the pairs closer than r_c that the driver cannot see (missed_pairs:
 * pairs whose next steps it would judge wrongly; summed over the refreshes, so a pair
 * missed at three refreshes counts three times), and lz_nwalk_overlaps counts the
 * damage. The refresh comes as soon as an interval is over, so the schedule does not
 * depend on how a run is cut into calls of lz_nwalk_run.
 *
 * Cost per sweep: NL O(N²/refresh + N·k); FNL and CL O(N·k); FR O(N·σ^(dim-1)) (the
 * repainted perimeter). The audit is O(N) per refresh and is timed apart.
 */
#ifndef LZ_NWALK_H
#define LZ_NWALK_H

#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/cells.h"
#include "lz/field.h"
#include "lz/lattice.h"
#include "lz/nlist.h"

typedef enum { LZ_NWALK_NL, LZ_NWALK_FNL, LZ_NWALK_CL, LZ_NWALK_FR } lz_nwalk_driver;

/* Names as scene files spell them: "nl", "fnl", "cl", "fr"; parse returns LZ_EINVAL
 * naming the choices. */
const char *lz_nwalk_driver_name(lz_nwalk_driver d);
int lz_nwalk_driver_parse(const char *name, lz_nwalk_driver *d);

/* What to simulate and how. */
typedef struct {
	lz_nwalk_driver driver;
	lz_lattice_kind kind;
	int64_t side;            /* L, a power of two */
	double radius;           /* R */
	size_t n;                /* particles, >= 1 */
	double skin;             /* Δr > 0 (NL, FNL, CL; ignored by FR) */
	int refresh;             /* sweeps between refreshes, >= 1; 0: refresh_safe */
	lz_cells_order order;    /* the numbering of the cells */
	int renumber;            /* 1: after placement, number the particles cell by cell
	                            in `order` (near in space = near in memory) */
	int linked;              /* CL: 1 scan the linked lists, 0 the fixed arrays */
	int single;              /* FNL: 1 refresh with the one-copy lz_nlist_refresh_single */
	int audit;               /* 1: count missed pairs before every refresh */
} lz_nwalk_params;

/* A running walk. Invariants: r holds n sites (dim int32_t each, in [0, L)); for FR the
 * field's own r is used and field paints exactly those sites. */
typedef struct {
	lz_nwalk_params p;
	int dim;
	lz_lattice_box *box;     /* owned */
	const lz_site *dirs;     /* the lattice's direction table (static) */
	int ndir;
	int64_t sigma2;          /* ceil(σ²): a pair closer than this overlaps */
	double lmax;             /* the longest step */
	double rc, rl;           /* r_c = σ + lmax and r_l = r_c + Δr (header comment) */
	int64_t rc2;             /* ceil(r_c²) */
	int refresh;             /* the interval in use, sweeps; 0 for FR (no refresh) */
	int refresh_safe;        /* floor(Δr / (2 lmax)); 0 for FR (no lists) */
	int32_t *r;              /* positions, n·dim (FR: field->r) */
	lz_nlist *nl;            /* NL, FNL */
	lz_cells *cells;         /* CL (FNL's first build bins on a grid of its own) */
	lz_field *field;         /* FR */
	lz_cells *truth;         /* the audit's grid, cutoff r_c; also used by renumbering */
	uint32_t *scratch;       /* n entries: the renumbering's permutation */
	uint64_t sweeps;         /* sweeps done */
	uint64_t since;          /* sweeps since the last refresh */
	uint64_t moves, accepted;
	uint64_t refreshes;      /* refreshes done (not counting the first build) */
	uint64_t missed;         /* the audit's count, summed over refreshes */
	uint64_t candidates;     /* distance tests made by the coordinate drivers */
	double move_s;           /* seconds spent in sweeps and refreshes */
	double audit_s;          /* seconds spent in the audit */
} lz_nwalk;

/* A walk as p asks: the box, n particles placed by random sequential adsorption on a
 * field of the same box (lz_field_rsa, so every driver starts from the same
 * configuration for the same rng state), renumbered if asked, and the driver's
 * structure built. NULL with an lz_error naming the bad value and the allowed range
 * when: the kind or side is invalid; R <= 0 or 4R > L; n = 0; the skin is not positive
 * and finite (NL, FNL, CL: a zero skin would need a refresh before every step);
 * refresh < 0; r_l > L/2 (NL, FNL) or the box holds fewer than 3 cells of side r_l
 * (CL); refresh = 0 while refresh_safe = 0 (Δr < 2 lmax: give the interval); renumber
 * in a box of fewer than 3 cells of side r_c; the placement field would pass
 * LZ_FIELD_SITES_MAX; RSA jams before n particles (LZ_EPHYS; the message gives the
 * packing and the jamming coverage ≈ 0.547 in 2D, 0.38 in 3D); a cell overflows its
 * arrays; no memory. The audit grid (cutoff r_c) is left NULL in a box of fewer than
 * 3 cells of side r_c: the audit and the overlaps then go over all pairs (a few dozen
 * particles at most fit such a box). O(L^dim + N). */
lz_nwalk *lz_nwalk_alloc(const lz_nwalk_params *p, gsl_rng *rng);
/* The checks of lz_nwalk_alloc that need neither memory nor random numbers (all but
 * jamming, overflow and memory), for a scene's check before anything runs. LZ_OK or
 * LZ_EINVAL with the lz_error. O(1). */
int lz_nwalk_check(const lz_nwalk_params *p);
void lz_nwalk_free(lz_nwalk *nw);

/* Run `sweeps` sweeps (header comment), refreshing (NL, FNL, CL) as soon as `refresh`
 * sweeps have passed since the last one, auditing before each refresh when asked. Adds to the counters and to move_s
 * and audit_s. LZ_OK, or the status of a failing refresh (LZ_ENOMEM; LZ_EPHYS when a
 * cell overflows its arrays). O(sweeps · cost per sweep). */
int lz_nwalk_run(lz_nwalk *nw, gsl_rng *rng, uint64_t sweeps);

/* The positions, n·dim. O(1). */
const int32_t *lz_nwalk_positions(const lz_nwalk *nw);

/* Pairs closer than σ (0 for a valid configuration), counted through a fresh binning.
 * O(N). */
size_t lz_nwalk_overlaps(lz_nwalk *nw);

/* Bytes of the driver's neighbour structure: both list copies (NL, FNL), the cell grid
 * and its lists (CL), the field (FR); the positions and the audit not counted. O(1). */
size_t lz_nwalk_list_bytes(const lz_nwalk *nw);

/* Atom-steps per second: moves / move_s (0 before any). O(1). */
double lz_nwalk_speed(const lz_nwalk *nw);

/* ---- for experiments (the lesson's drivers) ---- */

/* Parameters for driver d: n from the packing fraction (rounded; lz_walk_packing),
 * skin 4, the safe refresh, cells in row order, particles as placed, fixed arrays,
 * two copies, the audit on. O(1). */
lz_nwalk_params lz_nwalk_params_for(lz_nwalk_driver d, lz_lattice_kind kind, int64_t side,
                                    double radius, double packing);

/* The particles the FNL lists hold by default (lz_nwalk_fnl_skin). */
#define LZ_NWALK_FNL_ENTRIES 24.0

/* A skin at which FNL's lists hold about LZ_NWALK_FNL_ENTRIES particles each, n
 * particles of radius R in the box: Δr = R·(24/η)^(1/dim) - σ - lmax (an ideal gas at
 * packing η holds η·(r/R)^dim particles within r of one), rounded up; at most
 * L/2 - σ - lmax (r_l <= L/2), at least 2 lmax (a safe interval). The fast refresh
 * finds a newcomer only through a common neighbour; the thinnest lists that missed no
 * pair held 3 to 19 entries, more for small R (datasets/scenes/README.md, `nlist`,
 * has the measurement and its command). The default skin of `lz run` for fnl. O(1). */
double lz_nwalk_fnl_skin(lz_lattice_kind kind, int64_t side, double radius, size_t n);

/* lz_nwalk_alloc with an mt19937 generator seeded `seed` for the placement. NULL with
 * the lz_error of the allocation. */
lz_nwalk *lz_nwalk_alloc_seeded(const lz_nwalk_params *p, unsigned long seed);

/* `repeats` timed runs of `sweeps` sweeps each, run r from an mt19937 generator seeded
 * seed + r: ns[r] = CPU ns per atom-step of run r (move_s, the audit excluded). LZ_OK
 * or the status of lz_nwalk_run. O(repeats · sweeps · cost per sweep). */
int lz_nwalk_time(lz_nwalk *nw, unsigned long seed, uint64_t sweeps, int repeats, double *ns);

#endif
