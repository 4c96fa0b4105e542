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
	/* LZ_SOLUTION_BEGIN */
	uint32_t k = d->place[c];
	int lo = 0, hi = d->P;  /* cut[lo] <= k < cut[hi] */
	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;
		if (d->cut[mid] <= k)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
	/* LZ_SOLUTION_END */
}

void lz_pedmd_classify(const lz_edmd *e, const lz_pedmd_domains *d, int rank, uint8_t *cls)
{
	/* Hint: first mark every cell FAR, and every cell `rank` owns INTERIOR. Then for
	 * every owned cell look at its block (lz_edmd_block_of: the cells off[0][x] +
	 * off[1][y] + off[2][z]): a block cell owned by someone else makes the owned
	 * cell BORDER and the other cell HALO. Walls cut the block short, periodic axes
	 * wrap it: lz_edmd_block_of knows. See §2. */
	/* LZ_SOLUTION_BEGIN */
	for (uint32_t c = 0; c < e->ncells; c++)
		cls[c] = lz_pedmd_owner(d, c) == rank ? LZ_PEDMD_INTERIOR : LZ_PEDMD_FAR;
	lz_edmd_block b;
	for (uint32_t c = 0; c < e->ncells; c++) {
		if (cls[c] == LZ_PEDMD_FAR || cls[c] == LZ_PEDMD_HALO)
			continue;
		lz_edmd_block_of(e, c, &b);
		for (int z = 0; z < b.n[2]; z++)
			for (int y = 0; y < b.n[1]; y++)
				for (int x = 0; x < b.n[0]; x++) {
					uint32_t q = b.off[0][x] + b.off[1][y] + b.off[2][z];
					if (cls[q] == LZ_PEDMD_FAR || cls[q] == LZ_PEDMD_HALO) {
						cls[q] = LZ_PEDMD_HALO;
						cls[c] = LZ_PEDMD_BORDER;
					}
				}
	}
	/* LZ_SOLUTION_END */
}

int lz_pedmd_listeners(const lz_edmd *e, const lz_pedmd_domains *d, int rank, uint32_t c,
                       int *out)
{
	/* Hint: the owners of the cells of c's block, without `rank` itself and without
	 * repeats (a block has at most 27 cells: a small array and a linear search is
	 * plenty), then sorted. Those ranks hold c as HALO: they need every change of a
	 * particle in c. See §3. */
	/* LZ_SOLUTION_BEGIN */
	lz_edmd_block b;
	lz_edmd_block_of(e, c, &b);
	int n = 0;
	for (int z = 0; z < b.n[2]; z++)
		for (int y = 0; y < b.n[1]; y++)
			for (int x = 0; x < b.n[0]; x++) {
				int o = lz_pedmd_owner(d, b.off[0][x] + b.off[1][y] + b.off[2][z]);
				int k = 0;
				while (k < n && out[k] != o)
					k++;
				if (o != rank && k == n)
					out[n++] = o;
			}
	for (int k = 1; k < n; k++)  /* insertion sort: at most a handful */
		for (int j = k; j > 0 && out[j - 1] > out[j]; j--) {
			int t = out[j];
			out[j] = out[j - 1];
			out[j - 1] = t;
		}
	return n;
	/* LZ_SOLUTION_END */
}

int lz_pedmd_save(lz_pedmd *r, uint32_t i)
{
	/* Hint: mark[i] == epoch means i is saved already in this window: nothing to do.
	 * Else mark it and append its version to r->saved (lz_pedmd_grow makes room):
	 * role, whether it is in the heap and with which key (lz_heap_contains,
	 * lz_heap_key), its record p, its event ev, own, ghost and heard. See §6. */
	/* LZ_SOLUTION_BEGIN */
	if (r->mark[i] == r->epoch)
		return LZ_OK;
	if (lz_pedmd_grow((void **)&r->saved, &r->capsaved, r->nsaved, sizeof *r->saved))
		return LZ_ENOMEM;
	const lz_edmd *e = r->e;
	int in = lz_heap_contains(e->heap, i);
	r->saved[r->nsaved++] = (lz_pedmd_saved){i, r->role[i], (uint8_t)in, e->p[i], e->ev[i],
	                                         r->own[i], r->ghost[i],
	                                         in ? lz_heap_key(e->heap, i) : INFINITY,
	                                         r->heard[i]};
	r->mark[i] = r->epoch;
	return LZ_OK;
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	lz_edmd *e = r->e;
	for (size_t k = 0; k < r->nsaved; k++) {
		const lz_pedmd_saved *s = &r->saved[k];
		uint32_t i = s->id;
		if (r->role[i] != LZ_PEDMD_ABSENT)
			lz_edmd_cell_remove(e, i);
		e->p[i] = s->p;
		e->ev[i] = s->ev;
		r->own[i] = s->own;
		r->ghost[i] = s->ghost;
		r->role[i] = s->role;
		r->heard[i] = s->heard;
		if (s->role != LZ_PEDMD_ABSENT)
			lz_edmd_cell_insert(e, i, s->p.cell);
		int in = lz_heap_contains(e->heap, i);
		if (s->in_heap && in) {
			lz_heap_update(e->heap, i, s->key);
		} else if (s->in_heap) {
			lz_heap_push(e->heap, i, s->key);
		} else if (in) {
			lz_heap_update(e->heap, i, -INFINITY);  /* to the top, then off */
			lz_heap_pop(e->heap);
		}
	}
	*e = r->snap;
	r->clock = r->clock0;
	if (r->nwait0 > 0)
		memcpy(r->wait, r->wait0, r->nwait0 * sizeof *r->wait);
	r->nwait = r->nwait0;
	lz_pedmd_unread(r);
	r->nsaved = 0;
	r->nwlog = 0;
	r->wcommit = 0;
	r->wvirial = 0;
	/* LZ_SOLUTION_END */
}

/* LZ_HELPERS_BEGIN */
/* Tell the neighbours of owned i's cell what i is now (nothing if nobody sees it). */
static int tell(lz_pedmd *r, uint32_t i, double t)
{
	return lz_pedmd_announce(r, i, r->e->p[i].cell, -1, t);
}

/* A collision of owned i with j (owned, or a ghost: then it is replicated). */
static int collide(lz_pedmd *r, uint32_t i, uint32_t j, double t)
{
	lz_edmd *e = r->e;
	int st, ghost = r->role[j] == LZ_PEDMD_GHOST;
	if ((st = lz_pedmd_save(r, i)) || (st = lz_pedmd_save(r, j)))
		return st;
	lz_edmd_particle *pi = &e->p[i], *pj = &e->p[j];
	lz_edmd_advance(e, pi, t);
	lz_edmd_advance(e, pj, t);
	double dr[3];
	lz_edmd_separation(e, pi, pj, dr);
	double w = lz_edmd_bounce(pi, pj, dr, e->restitution);
	pi->count++;
	pj->count++;
	e->collisions++;
	if (!ghost || lz_pedmd_id(r, i) < lz_pedmd_id(r, j))
		lz_pedmd_note(r, t, i, j, LZ_PEDMD_COLLISION, w);
	if ((st = lz_pedmd_predict(r, i)) || (st = tell(r, i, t)))
		return st;
	if (ghost) {  /* its owner predicts it and tells; what it aimed at is free again */
		int32_t aim = r->ghost[j].ev.partner;
		r->ghost[j] = (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}};
		if (aim >= 0 && (uint32_t)aim != i && r->role[aim] == LZ_PEDMD_OWNED)
			return lz_pedmd_retarget(r, (uint32_t)aim);
		return LZ_OK;
	}
	if ((st = lz_pedmd_predict(r, j)))
		return st;
	return tell(r, j, t);
}

/* Owned i reaches face f of its cell at t: a wall, or the cell across. */
static int face(lz_pedmd *r, uint32_t i, int f, double t)
{
	lz_edmd *e = r->e;
	int st = lz_pedmd_save(r, i), a = f / 2, up = f % 2;
	if (st)
		return st;
	lz_edmd_particle *pi = &e->p[i];
	lz_edmd_advance(e, pi, t);
	uint32_t c = pi->cell, ca = a == 0 ? c % (uint32_t)e->m[0]
	                       : a == 1 ? (c / (uint32_t)e->m[0]) % (uint32_t)e->m[1]
	                                : c / ((uint32_t)e->m[0] * (uint32_t)e->m[1]);
	if (e->wall[a] && (int)ca == (up ? e->m[a] - 1 : 0)) {
		pi->r[a] = up ? e->L - 0.5 : 0.5;
		pi->v[a] = -pi->v[a];
		pi->count++;
		e->bounces++;
		lz_pedmd_note(r, t, i, i, LZ_PEDMD_BOUNCE, 0);
		if ((st = lz_pedmd_predict(r, i)))
			return st;
		return tell(r, i, t);
	}
	double jump;
	uint32_t to = lz_edmd_cell_across(e, c, f, &jump);
	pi->r[a] += jump;
	lz_edmd_cell_remove(e, i);
	lz_edmd_cell_insert(e, i, to);
	e->crossings++;
	lz_pedmd_note(r, t, i, i, LZ_PEDMD_CROSSING, 0);
	/* owned or not: the cell's class says (a byte a cell, mostly in cache, where the
	 * curve's places are a miss at 10^6 cells) */
	if (r->cls[to] == LZ_PEDMD_INTERIOR || r->cls[to] == LZ_PEDMD_BORDER) {
		if ((st = lz_pedmd_predict(r, i)))
			return st;
		return lz_pedmd_announce(r, i, c, -1, t);
	}
	lz_heap_pop(e->heap);  /* i was the top: it leaves this rank's heap */
	r->role[i] = LZ_PEDMD_GHOST;
	r->ghost[i] = (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}};  /* its owner predicts */
	r->own[i] = (lz_pedmd_event){t, {LZ_EDMD_NONE, 0}};  /* when it left: see apply_state */
	return lz_pedmd_announce(r, i, c, lz_pedmd_owner(r->d, to), t);
}
/* LZ_HELPERS_END */

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
	/* LZ_SOLUTION_BEGIN */
	lz_edmd *e = r->e;
	*did = 0;
	if (e->heap->n == 0)
		return LZ_OK;
	uint32_t i = lz_heap_top(e->heap);
	double t = lz_heap_top_t(e->heap);
	if (isinf(t) || e->t_base + t > r->t_end)
		return LZ_OK;
	*did = 1;
	e->events++;
	r->counts.processed++;
	e->now = t;
	r->clock = t;
	lz_edmd_event ev = e->ev[i];
	if (ev.partner >= 0 && r->role[ev.partner] == LZ_PEDMD_GHOST)
		lz_pedmd_read_at(r, e->p[ev.partner].cell, t);  /* the ghost's record is used at t */
	if (ev.partner >= 0) {
		uint32_t j = (uint32_t)ev.partner;
		if (e->p[j].count == ev.pcount)
			return collide(r, i, j, t);
		e->stale++;
		lz_pedmd_note(r, t, i, i, LZ_PEDMD_STALE, 0);
		int st = lz_pedmd_predict(r, i);
		return st ? st : tell(r, i, t);
	}
	return face(r, i, -1 - ev.partner, t);
	/* LZ_SOLUTION_END */
}

/* LZ_HELPERS_BEGIN */
/* After ghost g's aim changed from old_aim: the owned particles it aimed at, or aims
 * at now, get their keys again. */
static int reaim(lz_pedmd *r, int32_t old_aim, int32_t new_aim)
{
	int st = LZ_OK;
	if (old_aim >= 0 && r->role[old_aim] == LZ_PEDMD_OWNED)
		st = lz_pedmd_retarget(r, (uint32_t)old_aim);
	if (st == LZ_OK && new_aim >= 0 && new_aim != old_aim && r->role[new_aim] == LZ_PEDMD_OWNED)
		st = lz_pedmd_retarget(r, (uint32_t)new_aim);
	return st;
}

static int apply_state(lz_pedmd *r, const lz_pedmd_message *m)
{
	lz_edmd *e = r->e;
	uint32_t g = m->id, to = m->p.cell;
	int had = r->role[g] == LZ_PEDMD_GHOST;
	if (m->t < r->heard[g])
		return LZ_OK;  /* older than what it knows: a former owner's news */
	if (r->role[g] == LZ_PEDMD_OWNED || r->cls[to] != LZ_PEDMD_HALO)
		return lz_error(LZ_EDOM, "rank %d: news of particle %u in cell %u, which is not in "
		                "its halo, or of a particle it owns", r->rank, g, to);
	if ((had && r->read[e->p[g].cell] > m->t) || r->read[to] > m->t)
		return lz_pedmd_late(r, m->t);
	int32_t aim = m->event.ev.partner;
	if (aim >= 0 && r->role[aim] != LZ_PEDMD_OWNED && r->own[aim].t > m->event.t)
		return lz_pedmd_late(r, m->event.t);  /* it aims at one this rank still had then */
	int st = lz_pedmd_save(r, g);
	if (st)
		return st;
	r->heard[g] = m->t;
	int32_t old_aim = had ? r->ghost[g].ev.partner : -1;
	if (had && e->p[g].cell == to) {
		e->p[g] = m->p;
	} else {
		if (had)
			lz_edmd_cell_remove(e, g);
		e->p[g] = m->p;
		lz_edmd_cell_insert(e, g, to);
	}
	r->role[g] = LZ_PEDMD_GHOST;
	r->ghost[g] = m->event;
	return reaim(r, old_aim, m->event.ev.partner);
}

static int apply_migrate(lz_pedmd *r, const lz_pedmd_message *m)
{
	lz_edmd *e = r->e;
	uint32_t i = m->id, to = m->p.cell;
	if (lz_pedmd_owner(r->d, to) != r->rank || r->role[i] == LZ_PEDMD_OWNED)
		return lz_error(LZ_EDOM, "rank %d: particle %u handed over into cell %u, which it "
		                "does not own, or which it owns already", r->rank, i, to);
	if (r->read[to] > m->t || !lz_pedmd_block_at(r, to, m->t))
		return lz_pedmd_late(r, m->t);
	int st = lz_pedmd_save(r, i);
	if (st)
		return st;
	r->heard[i] = m->t;
	int32_t old_aim = r->role[i] == LZ_PEDMD_GHOST ? r->ghost[i].ev.partner : -1;
	if (r->role[i] == LZ_PEDMD_GHOST)
		lz_edmd_cell_remove(e, i);
	e->p[i] = m->p;
	lz_edmd_cell_insert(e, i, to);
	r->role[i] = LZ_PEDMD_OWNED;
	r->ghost[i] = (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}};
	double keep = e->now;
	e->now = m->t;  /* predicted at the crossing, as the serial run does */
	st = lz_pedmd_predict(r, i);
	if (st == LZ_OK)
		st = lz_pedmd_announce(r, i, to, -1, m->t);
	e->now = keep;
	return st ? st : reaim(r, old_aim, -1);
}

static int apply_leave(lz_pedmd *r, const lz_pedmd_message *m)
{
	lz_edmd *e = r->e;
	uint32_t g = m->id;
	if (r->role[g] != LZ_PEDMD_GHOST || m->t < r->heard[g])
		return LZ_OK;  /* not here, or older news than it has */
	if (r->read[e->p[g].cell] > m->t)
		return lz_pedmd_late(r, m->t);
	int st = lz_pedmd_save(r, g);
	if (st)
		return st;
	r->heard[g] = m->t;
	int32_t old_aim = r->ghost[g].ev.partner;
	lz_edmd_cell_remove(e, g);
	r->role[g] = LZ_PEDMD_ABSENT;
	r->ghost[g] = (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}};
	return reaim(r, old_aim, -1);
}
/* LZ_HELPERS_END */

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
	/* LZ_SOLUTION_BEGIN */
	if (m->t > r->clock)
		return lz_pedmd_wait(r, m);
	switch (m->kind) {
	case LZ_PEDMD_STATE:
		return apply_state(r, m);
	case LZ_PEDMD_MIGRATE:
		return apply_migrate(r, m);
	case LZ_PEDMD_LEAVE:
		return apply_leave(r, m);
	}
	return lz_error(LZ_EDOM, "rank %d: a message of unknown kind %u", r->rank, m->kind);
	/* LZ_SOLUTION_END */
}

int lz_pedmd_decide(double t_error, double T, double t_next, double *t_end)
{
	/* Hint: no error (t_error infinite): commit. An error after T: roll back and end
	 * the next window at the error's time (its events still run: the error cannot
	 * come again at the end of a window). An error at T or before: no window can be
	 * shortened enough — a conservative step to t_next. See §7. */
	/* LZ_SOLUTION_BEGIN */
	if (t_error == INFINITY)
		return LZ_PEDMD_COMMIT;
	if (t_error > T) {
		*t_end = t_error;
		return LZ_PEDMD_ROLLBACK;
	}
	*t_end = t_next;
	return LZ_PEDMD_CONSERVATIVE;
	/* LZ_SOLUTION_END */
}

int lz_pedmd_rebalance(const lz_pedmd_domains *d, const double *load, double threshold,
                       uint32_t *new_cut)
{
	/* Hint: walk the curve adding load[curve[k]]; cut r goes where the running total
	 * first passes r/P of the whole, but never so that a rank is left without a cell
	 * (cut[r] >= cut[r-1] + 1 and <= ncells - (P - r)). Compare the busiest rank's
	 * load before and after (lz_pedmd_busiest); keep the old cuts unless the new one
	 * is at most (1 - threshold) of the old. See §8. */
	/* LZ_SOLUTION_BEGIN */
	int P = d->P;
	double total = 0;
	for (size_t k = 0; k < d->ncells; k++)
		total += load[d->curve[k]];
	new_cut[0] = 0;
	new_cut[P] = (uint32_t)d->ncells;
	size_t k = 0;
	double run = 0;
	for (int r = 1; r < P; r++) {
		double target = total * r / P;
		while (k < d->ncells && run + load[d->curve[k]] <= target)
			run += load[d->curve[k++]];
		uint32_t c = (uint32_t)k;
		if (c < new_cut[r - 1] + 1)
			c = new_cut[r - 1] + 1;
		if (c > d->ncells - (size_t)(P - r))
			c = (uint32_t)(d->ncells - (size_t)(P - r));
		new_cut[r] = c;
		while (k < c)
			run += load[d->curve[k++]];
	}
	double before = lz_pedmd_busiest(d, load, d->cut);
	if (total > 0 && lz_pedmd_busiest(d, load, new_cut) <= (1 - threshold) * before)
		return 1;
	memcpy(new_cut, d->cut, (size_t)(P + 1) * sizeof *new_cut);
	return 0;
	/* LZ_SOLUTION_END */
}
