/* lz/nlist.h — Verlet neighbour lists on a lattice: built by all pairs (O(N²)), built
 * from cell lists (O(N)), and refreshed from the neighbours of the neighbours with
 * two copies of the lists, source and target (thesis 2.4.2, fig. 2.7).
 *
 * Lattice units throughout. Particles sit on the sites r[i·dim + 0 .. dim-1] of a
 * periodic box (lz/lattice.h, every coordinate in [0, L)); distances are the exact
 * integer minimum-image distances² of lz_lattice_min_dist2. The list radius is
 *     r_l = r_c + Δr,
 * r_c the range at which particles act on each other and Δr > 0 the skin. Particle j
 * is LISTED on i when their distance² is below rl2 = ceil(r_l²) (the strict rule of
 * lz/shape.h: d < r_l). A valid list is
 *     symmetric (j on i's row iff i on j's), free of self entries (i is never on its
 *     own row: its distance to itself is 0 and would always count) and of duplicates
 *     (a neighbour counted twice would be felt twice).
 * While particles move, the list stays usable as long as no pair that was farther
 * than r_l at the build has come within r_c: the skin is the margin that buys sweeps
 * between refreshes.
 *
 * The fast refresh. A particle that comes within r_l of i since the last list did not
 * come from far away: in a dense fluid it was already within r_l of one of i's
 * neighbours, so i's new row is found among i's row and the rows of the particles on
 * it: O(N · k²), k the neighbours per particle, instead of O(N²). This is a bet on
 * density, not a theorem: a pair with no common neighbour when the source was built
 * (two lone particles drifting together in a dilute gas; a particle whose row is
 * empty gains nobody, ever) is missed. lz_nlist_audit counts such misses. The new rows must
 * be read from the OLD lists only: thesis fig. 2.7 — C drifts from A to B; if A's
 * row is rewritten first (C dropped, now too far from A), B's scan of A's row no
 * longer finds C and C is lost for good. So there are two copies: the source buf[cur],
 * never written during a refresh, and the target buf[!cur], written row by row; then
 * they swap roles (cur = !cur). lz_nlist_refresh_single is the one-copy version, kept
 * to show the loss.
 *
 * Storage: each copy is a compressed row table (CSR): row i is
 * idx[start[i] .. start[i+1]), the rows back to back. Every build or refresh fills the
 * target the same way —
 *     t = &nl->buf[!nl->cur]; t->len = 0;
 *     for each i in 0 .. n-1: t->start[i] = t->len; push row i with lz_nbuf_push;
 *     t->start[n] = t->len; nl->cur = !nl->cur;
 * — and idx grows by doubling when it is full (amortised O(1); after the first few
 * builds it has room and no allocation happens).
 *
 * Memory: 2 · (n + 1 + entries) · 4 bytes, entries = n · k.
 */
#ifndef LZ_NLIST_H
#define LZ_NLIST_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "lz/cells.h"
#include "lz/error.h"
#include "lz/lattice.h"

/* One copy of the lists. Invariant once written: start[0] = 0, start[i] <= start[i+1],
 * start[n] = len <= cap, every entry < n. */
typedef struct {
	uint32_t *start;  /* n + 1 offsets into idx */
	uint32_t *idx;    /* the entries, row after row */
	size_t len;       /* entries written */
	size_t cap;       /* room in idx */
} lz_nbuf;

/* The lists of n particles and their two copies. Invariant: buf[cur] is the list in
 * use (the last build or refresh); mark[] is all 0 between calls. */
typedef struct {
	const lz_lattice_box *box;  /* the periodic box (not owned) */
	int dim;                    /* 2 or 3 */
	size_t n;                   /* particles, the rows */
	double rl;                  /* the list radius r_l, lattice units */
	int64_t rl2;                /* ceil(r_l²): listed iff distance² < rl2 */
	lz_nbuf buf[2];             /* the source and target copies (header comment) */
	int cur;                    /* 0 or 1: buf[cur] is the source */
	uint8_t *mark;              /* n bytes of scratch, 0 between calls: a refresh may
	                               set mark[j] while building a row to refuse a
	                               duplicate in O(1), and must clear it afterwards */
} lz_nlist;

/* Entries a copy starts with. */
#define LZ_NBUF_FIRST 64

/* Room for one more entry in b, by doubling idx. LZ_OK or LZ_ENOMEM (b unchanged).
 * The row offsets start[] are 32-bit, so a copy never holds more than 2^32 - 1
 * entries. Amortised O(1). */
static inline int lz_nbuf_grow(lz_nbuf *b)
{
	if (b->cap >= UINT32_MAX)
		return lz_error(LZ_ENOMEM, "a neighbour list of more than %u entries: the row "
		                "offsets are 32-bit (fewer particles or a smaller r_l)",
		                (unsigned)UINT32_MAX);
	size_t cap = b->cap ? 2 * b->cap : LZ_NBUF_FIRST;
	if (cap > UINT32_MAX)
		cap = UINT32_MAX;
	uint32_t *idx = realloc(b->idx, cap * sizeof *idx);
	if (!idx)
		return lz_error(LZ_ENOMEM, "no memory for %zu neighbour-list entries", cap);
	b->idx = idx;
	b->cap = cap;
	return LZ_OK;
}

/* Append j to the row being written in b. LZ_OK, or LZ_ENOMEM if idx cannot grow.
 * Amortised O(1). */
static inline int lz_nbuf_push(lz_nbuf *b, uint32_t j)
{
	if (b->len == b->cap) {
		int st = lz_nbuf_grow(b);
		if (st)
			return st;
	}
	b->idx[b->len++] = j;
	return 0;
}

/* Row i of the list in use, and its length in *len. O(1). */
static inline const uint32_t *lz_nlist_row(const lz_nlist *nl, size_t i, size_t *len)
{
	const lz_nbuf *b = &nl->buf[nl->cur];
	*len = b->start[i + 1] - b->start[i];
	return b->idx + b->start[i];
}

/* Lists for n particles in box (kept, not owned) with list radius rl, both copies empty
 * (every row of length 0). NULL with an lz_error naming the bad value and the allowed
 * range when: box is NULL; n is 0 or above 2^31 - 1; rl is not positive and finite;
 * rl > L/2 (a pair could then be within r_l through two images at once and the
 * minimum image would not be the only contact); no memory. O(n). */
lz_nlist *lz_nlist_alloc(const lz_lattice_box *box, size_t n, double rl);
void lz_nlist_free(lz_nlist *nl);

/* Entries in the list in use (twice the number of listed pairs). O(1). */
size_t lz_nlist_entries(const lz_nlist *nl);
/* Bytes held by both copies and the scratch. O(1). */
size_t lz_nlist_bytes(const lz_nlist *nl);

/* The one-copy refresh, WRONG on purpose (header comment, thesis fig. 2.7): rows are
 * rewritten in place, in index order, each from the rows as they stand at that moment
 * — row i drops the entries now beyond r_l, then takes, from the rows of the particles
 * left on it, those within r_l (no self, no duplicate). A particle can leave one row
 * before the row that should gain it is scanned, and is then lost. Same result format
 * as lz_nlist_refresh (it also flips cur). LZ_ENOMEM without memory. O(n · k²). */
int lz_nlist_refresh_single(lz_nlist *nl, const int32_t *r);

/* What lz_nlist_audit finds wrong with the list in use. */
typedef struct {
	size_t missing;     /* pairs closer than r2 (distance² < r2) that are not listed
	                       on both rows, counted once per pair */
	size_t beyond;      /* entries at distance² >= rl2 (stale: allowed between
	                       refreshes, never right after one) */
	size_t self;        /* entries i on row i */
	size_t duplicates;  /* repeats of an entry already on the same row */
	size_t asymmetric;  /* entries j on row i without i on row j */
} lz_nlist_audit_report;

/* Check the list in use against brute force over all pairs: fills *rep (above), with
 * missing counted for the radius² r2 — rl2 to check that a fresh list is complete, a
 * smaller one (the pairs that can interact on the next move) to check that a stale
 * list is still safe. LZ_OK, or LZ_ENOMEM without scratch memory. O(n² + entries). */
int lz_nlist_audit(const lz_nlist *nl, const int32_t *r, int64_t r2, lz_nlist_audit_report *rep);

/* ---- graded (solutions/04-neighbours/nlist.c) ---- */

/* Verlet's build: compare every pair and list j on i and i on j when their distance²
 * is below rl2. Writes the target and flips (header comment); rows in any order.
 * LZ_OK or LZ_ENOMEM. O(n²). */
int lz_nlist_build_allpairs(lz_nlist *nl, const int32_t *r);

/* The same list in O(n): row i takes the particles j != i within rl2 found in the
 * block of 3^dim cells around i's cell (c->full), through the linked lists. Needs c
 * to be a lattice grid (c->shift >= 0) of the same box with cells no narrower than
 * lz_lattice_reach(kind, r_l), binned on the same r (lz_cells_bin_sites) and linked
 * (lz_cells_link): else LZ_EINVAL, with an lz_error saying which. Writes the target and
 * flips; LZ_OK or LZ_ENOMEM. O(n · 3^dim · particles per cell). */
int lz_nlist_build_cells(lz_nlist *nl, const lz_cells *c, const int32_t *r);

/* The fast refresh (header comment): row i of the target = every j != i within rl2
 * that is on i's source row or on the source row of a particle on i's source row,
 * each once. Reads only the source buf[cur]; writes the target and flips. It equals
 * a full rebuild (as sets) when every pair now within r_l was listed in the source or
 * had a common neighbour there (header comment: true in dense fluids when the moves
 * are small against the skin). LZ_OK or LZ_ENOMEM. O(n · k²). */
int lz_nlist_refresh(lz_nlist *nl, const int32_t *r);

#endif
