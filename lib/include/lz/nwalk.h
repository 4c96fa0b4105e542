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
 * was farther than r_l at a refresh closes in by at most 2·lmax per sweep, so the
 * lists stay safe for
 *     refresh_safe = floor((Δr + lmax) / (2 lmax))   sweeps
 * (at the k-th sweep after the refresh the pair is still at least r_l - (2k - 1)·lmax
 * apart when one of them moves). A longer interval is allowed — it is the trade the
 * lesson measures — and its cost is counted: before every refresh the audit (when
 * on) counts the pairs closer than r_c that the driver cannot see (missed_pairs:
 * pairs whose steps it would judge wrongly), and lz_nwalk_overlaps counts the damage.
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
	int refresh;             /* the interval in use, sweeps */
	int refresh_safe;        /* floor((Δr + lmax) / (2 lmax)) */
	int32_t *r;              /* positions, n·dim (FR: field->r) */
	lz_nlist *nl;            /* NL, FNL */
	lz_cells *cells;         /* CL; FNL's first build */
	lz_field *field;         /* FR */
	lz_cells *truth;         /* the audit's grid, cutoff r_c; also used by renumbering */
	uint32_t *scratch;       /* n entries (renumbering, the audit) */
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
 * (CL); RSA jams before n particles (the message gives the packing and the jamming
 * coverage ≈ 0.547 in 2D, 0.38 in 3D); a cell overflows its arrays; no memory.
 * O(L^dim + N). */
lz_nwalk *lz_nwalk_alloc(const lz_nwalk_params *p, gsl_rng *rng);
void lz_nwalk_free(lz_nwalk *nw);

/* Run `sweeps` sweeps (header comment), refreshing (NL, FNL, CL) every `refresh`
 * sweeps, auditing before each refresh when asked. Adds to the counters and to move_s
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

#endif
