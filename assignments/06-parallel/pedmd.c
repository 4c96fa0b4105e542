/* YOUR FILE — this is the file you fill in for stage 06-parallel.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/06-parallel/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=06`; see your own code at work with
 * `make lesson STAGE=06`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* pedmd.c — the graded functions of the parallel engine (lz/pedmd.h): who owns what,
 * who must be told, an event on a rank, a message from a neighbour, state saving,
 * the verdict at a cut, and the cuts moved to balance the load. */
#include <math.h>
#include <string.h>

#include "lz/error.h"
#include "lz/pedmd.h"

int lz_pedmd_owner(const lz_pedmd_domains *d, uint32_t c)
{
	/* Hint: k = d->place[c] is the cell's place on the curve; find the rank r with
	 * d->cut[r] <= k < d->cut[r + 1] by bisection over r (the cuts increase). The
	 * last rank owns up to cut[P] - 1. See lessons/06-parallel/README.md §2. */
	LZ_TODO();
}

void lz_pedmd_classify(const lz_edmd *e, const lz_pedmd_domains *d, int rank, uint8_t *cls)
{
	/* Hint: first mark every cell FAR, and every cell `rank` owns INTERIOR. Then for
	 * every owned cell look at its block (lz_edmd_block_of: the cells off[0][x] +
	 * off[1][y] + off[2][z]): a block cell owned by someone else makes the owned
	 * cell BORDER and the other cell HALO. Walls cut the block short, periodic axes
	 * wrap it: lz_edmd_block_of knows. See §2. */
	LZ_TODO();
}

int lz_pedmd_listeners(const lz_edmd *e, const lz_pedmd_domains *d, int rank, uint32_t c,
                       int *out)
{
	/* Hint: the owners of the cells of c's block, without `rank` itself and without
	 * repeats (a block has at most 27 cells: a small array and a linear search is
	 * plenty), then sorted. Those ranks hold c as HALO: they need every change of a
	 * particle in c. See §3. */
	LZ_TODO();
}

int lz_pedmd_save(lz_pedmd *r, uint32_t i)
{
	/* Hint: mark[i] == epoch means i is saved already in this window: nothing to do.
	 * Else mark it and append its version to r->saved (lz_pedmd_grow makes room):
	 * role, whether it is in the heap and with which key (lz_heap_contains,
	 * lz_heap_key), its record p, its event ev, own, ghost and heard. See §6. */
	LZ_TODO();
}

void lz_pedmd_restore(lz_pedmd *r)
{
	/* Hint: each saved version back in O(log N): take the particle out of the cell
	 * list it is in now (unless ABSENT: then it is in none), write back its record,
	 * event, own, ghost, role and heard, put it into its saved cell's list (unless it
	 * was ABSENT); in the heap, update its key or push it when it was in the heap
	 * then, take it out when it was not (its key to -INFINITY, then pop). Then the
	 * system's scalars (*r->e = r->snap: the arrays are the same), the clock (clock0),
	 * the waiting messages (wait0, nwait0) and the read stamps (lz_pedmd_unread); an
	 * empty save list and window log. Nothing of O(N): only what the window touched.
	 * See §6. */
	LZ_TODO();
}


int lz_pedmd_step(lz_pedmd *r, int *did)
{
	/* Hint: as lz_edmd_step (stage 05), with the rank's twists. The top i and its
	 * time t; nothing to do (*did = 0) when the heap is empty, t is infinite or
	 * e->t_base + t > r->t_end. Else count it (e->events, r->counts.processed), set
	 * e->now and r->clock to t; an event with a ghost reads the ghost's cell at t
	 * (lz_pedmd_read_at). A stale collision (the partner's count changed):
	 * note it (LZ_PEDMD_STALE), predict i again with lz_pedmd_predict and tell i's
	 * neighbours (lz_pedmd_announce). A collision: save both, bring them to t,
	 * bounce along lz_edmd_separation, both counts + 1, note it once (if j is a
	 * ghost, only when i's number is the smaller: lz_pedmd_id(r, i) < lz_pedmd_id(r,
	 * j), as a slot need not be a particle's number), predict and announce i, and j
	 * too when it is owned (a ghost's next event comes from its owner: forget the old
	 * one). A face: a wall
	 * bounce, or a crossing — into a cell this rank owns (predict, announce with
	 * the old cell as `from`), or into another rank's: pop i from the heap, make it
	 * a GHOST here (own[i].t = t: when it left) and announce with that rank as
	 * `to_owner` (it gets MIGRATE). Save before you change anything
	 * (lz_pedmd_save). See §4. */
	LZ_TODO();
}


int lz_pedmd_apply(lz_pedmd *r, const lz_pedmd_message *m)
{
	/* Hint: a message later than r->clock waits (lz_pedmd_wait). Otherwise, by kind:
	 * STATE — the ghost's new record and event (ignore one older than the record
	 * you have: it comes from a former owner); LATE (lz_pedmd_late(r, m->t)) when a
	 * prediction after m->t read its old or its new cell (read[c] > m->t); LATE at
	 * the event's time when the event aims at a particle r no longer owns but handed
	 * over after that time (own[aim].t): r should have carried out that collision; move it
	 * to its new cell; the owned particles its old and its new event aim at get
	 * their keys again (lz_pedmd_retarget). MIGRATE — into a cell r owns: LATE when
	 * a prediction read the cell after m->t or some particle of the block is past
	 * m->t (lz_pedmd_block_at); make it OWNED and predict it AT m->t (set e->now to
	 * m->t for the prediction, then back), announce it. LEAVE — a ghost gone: LATE
	 * when its cell was read after m->t; forget it. Save before changing anything.
	 * See §5. */
	LZ_TODO();
}

int lz_pedmd_decide(double t_error, double T, double t_next, double *t_end)
{
	/* Hint: no error (t_error infinite): commit. An error after T: roll back and end
	 * the next window at the error's time (its events still run: the error cannot
	 * come again at the end of a window). An error at T or before: no window can be
	 * shortened enough — a conservative step to t_next. See §7. */
	LZ_TODO();
}

int lz_pedmd_rebalance(const lz_pedmd_domains *d, const double *load, double threshold,
                       uint32_t *new_cut)
{
	/* Hint: walk the curve adding load[curve[k]]; cut r goes where the running total
	 * first passes r/P of the whole, but never so that a rank is left without a cell
	 * (cut[r] >= cut[r-1] + 1 and <= ncells - (P - r)). Compare the busiest rank's
	 * load before and after (lz_pedmd_busiest); keep the old cuts unless the new one
	 * is at most (1 - threshold) of the old. See §8. */
	LZ_TODO();
}
