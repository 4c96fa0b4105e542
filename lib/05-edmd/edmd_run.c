/* edmd_run.c — the run of lz/edmd.h around the graded event loop: re-basing the clock,
 * renumbering the particles cell by cell, the collapse and stall guards, the state
 * handed back (lz_edmd_get) and the O(n) observables and checks (energy, momentum,
 * temperature, invariants). It calls edmd_lib.c, edmd_cells.c and edmd_list.c, never
 * the other way round. */
#include <math.h>
#include <stdlib.h>

#include "lz/edmd.h"
#include "lz/error.h"

void lz_edmd_sync(lz_edmd *e)
{
	for (size_t i = 0; i < e->n; i++)
		lz_edmd_advance(e, &e->p[i], e->now);
}

void lz_edmd_get(lz_edmd *e, double *r, double *v)
{
	lz_edmd_sync(e);
	for (size_t i = 0; i < e->n; i++)
		for (int a = 0; a < 3; a++) {
			double x = e->p[i].r[a];
			if (a < e->dim && !e->wall[a]) {
				x -= e->L * floor(x / e->L);
				if (x >= e->L)  /* -1e-17 wraps to L in round-off */
					x = 0;
			}
			r[3 * i + a] = x;
			v[3 * i + a] = e->p[i].v[a];
		}
}

int lz_edmd_next(lz_edmd *e)
{
	return e->lists ? lz_edmd_list_step(e) : lz_edmd_step(e);
}

int lz_edmd_rebase(lz_edmd *e)
{
	lz_edmd_sync(e);
	double now = e->now;
	for (size_t i = 0; i < e->n; i++)
		e->p[i].t0 = 0;
	if (e->cal) {
		int st = lz_calendar_shift(e->cal, now);
		if (st != LZ_OK)
			return st;
	} else {
		lz_heap_shift(e->heap, now);
	}
	e->t_base += now;
	e->now = 0;
	e->since_rebase = 0;
	e->rebases++;
	return LZ_OK;
}

void lz_edmd_set_time(lz_edmd *e, double t)
{
	e->t_reset += t - lz_edmd_time(e);
	e->t_base = t - e->now;
}

/* Rebuild the cell lists from p[].cell, each list in increasing particle number (so
 * that sorting an already sorted system changes nothing). */
static void relink(lz_edmd *e)
{
	lz_edmd_cell_clear(e);
	for (size_t i = e->n; i-- > 0;)
		lz_edmd_cell_insert(e, (uint32_t)i, e->p[i].cell);
}

int lz_edmd_sort(lz_edmd *e)
{
	/* The new number of every particle, walking the cells in order. */
	uint32_t *to = malloc(e->n * sizeof *to), k = 0;
	if (!to)
		return lz_error(LZ_ENOMEM, "no memory to renumber %zu particles", e->n);
	for (size_t c = 0; c < e->ncells; c++)
		for (int32_t j = e->list[c].head; j >= 0; j = e->next[j])
			to[j] = k++;
	for (size_t i = 0; i < e->n; i++)
		if (e->ev[i].partner >= 0)
			e->ev[i].partner = (int32_t)to[e->ev[i].partner];
	if (e->cal ? lz_calendar_renumber(e->cal, to) != LZ_OK
	           : (lz_heap_renumber(e->heap, to), 0)) {
		free(to);
		return LZ_ENOMEM;
	}
	if (e->lists && lz_edmd_list_renumber(e, to) != LZ_OK) {
		free(to);
		return LZ_ENOMEM;
	}
	/* apply the permutation in place, cycle by cycle: each swap puts one particle
	 * where it belongs */
	for (uint32_t i = 0; i < e->n; i++)
		while (to[i] != i) {
			uint32_t j = to[i];
			lz_edmd_particle p = e->p[i];
			lz_edmd_event ev = e->ev[i];
			e->p[i] = e->p[j];
			e->ev[i] = e->ev[j];
			e->p[j] = p;
			e->ev[j] = ev;
			to[i] = to[j];
			to[j] = j;
		}
	free(to);
	relink(e);
	return LZ_OK;
}

/* The time a particle at the current rms speed takes to fly σ (INFINITY at rest). */
static double flight_time(const lz_edmd *e)
{
	double T = lz_edmd_temperature(e);
	return T > 0 ? 1 / sqrt(e->dim * T) : INFINITY;
}

/* At a re-base: the clock must have moved by more than a trillionth of a flight time
 * over the window, or the events pile up at one instant (inelastic collapse). */
static int check_stall(const lz_edmd *e, uint64_t window)
{
	double tau = flight_time(e);
	if (e->now > 1e-12 * tau || 2 * (e->collisions - e->coll_mark) < window)
		return LZ_OK;
	return lz_error(LZ_EPHYS,
	                "inelastic collapse at t = %.10g: %llu events in %.3g time units, "
	                "less than 1e-12 of the %.3g a particle needs to fly σ (restitution "
	                "%g); the particles of a cluster collide infinitely often in finite "
	                "time — raise the restitution",
	                lz_edmd_time(e), (unsigned long long)window, e->now, tau, e->restitution);
}

/* Each event jumps to random places in memory, and every prediction waits on a chain
 * of misses (cell heads, particle records); fetched an event or two ahead, the chains
 * of successive events overlap; the heap says which events are likely next
 * (lz_heap_next_items). A wrong guess costs a few wasted fetches. */
void lz_edmd_fetch_ahead(const lz_edmd *e)
{
	const lz_heap *h = e->heap;
	if (h->n < 16)
		return;
	/* this event: its own cells and records were asked for an event ago; now the
	 * partner's cells (its record was asked for then too) and heap node */
	int32_t j = e->ev[lz_heap_top(h)].partner;
	if (j >= 0) {
		lz_edmd_prefetch_block(e, e->p[j].cell);
		lz_heap_prefetch_node(h, (uint32_t)j);
	}
	/* the next event: its record and event were asked for an event ago; now its
	 * cells, its partner's record and heap position */
	uint32_t c1, c2;
	lz_heap_next_items(h, &c1, &c2);
	int32_t j1 = e->ev[c1].partner;
	lz_edmd_prefetch_block(e, e->p[c1].cell);
	if (j1 >= 0) {
		__builtin_prefetch(&e->p[j1]);
		lz_heap_prefetch_pos(h, (uint32_t)j1);
	}
	/* the event after: its record and event */
	__builtin_prefetch(&e->p[c2]);
	__builtin_prefetch(&e->ev[c2]);
}

/* Events between two re-bases: 8 a particle, at least 8192. A re-base is O(N) —
 * every particle brought to now, every key shifted, the calendar laid out again — and
 * took 3 % of the loop at N = 10^4 done every event a particle (lesson 05 §7). Over 8
 * events a particle the clock runs about ten mean free times in a dense fluid: an
 * event time keeps all but 3 or 4 of its 53 bits against a flight. */
#define REBASE_EVENTS 8

int lz_edmd_run(lz_edmd *e, uint64_t events, double t_stop)
{
	uint64_t window = REBASE_EVENTS * (e->n > 1024 ? e->n : 1024);
	if (t_stop < lz_edmd_time(e))
		return lz_error(LZ_EINVAL, "t_stop = %.17g is before the clock, %.17g: a run "
		                "cannot go back in time", t_stop, lz_edmd_time(e));
	for (uint64_t k = 0; k < events; k++) {
		if (e->since_rebase >= window) {
			int st = check_stall(e, window);
			if (st)
				return st;
			if (e->rebase_auto && (st = lz_edmd_rebase(e)) != LZ_OK)
				return st;
			e->since_rebase = 0;
			e->coll_mark = e->collisions;
			if (e->sort_every && e->rebases % e->sort_every == 0 && (st = lz_edmd_sort(e)))
				return st;
		}
		if (e->t_base + lz_edmd_first_t(e) > t_stop) {
			e->now = t_stop - e->t_base;
			lz_edmd_sync(e);
			return LZ_OK;
		}
		if (e->prefetch) {
			if (e->lists)
				lz_edmd_list_fetch_ahead(e);
			else
				lz_edmd_fetch_ahead(e);
		}
		int st = lz_edmd_next(e);
		if (st < 0)
			return lz_error(LZ_EPHYS, "nothing left to happen at t = %.10g: every "
			                "particle is at rest or alone on its path", lz_edmd_time(e));
		if (st > 0)
			return st;
		e->since_rebase++;
	}
	return LZ_OK;
}

/* ---- observables and guards ---- */

double lz_edmd_energy(const lz_edmd *e)
{
	double E = 0;
	for (size_t i = 0; i < e->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		E += 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + e->g * r[0];
	}
	return E;
}

void lz_edmd_momentum(const lz_edmd *e, double P[3])
{
	P[0] = P[1] = P[2] = 0;
	for (size_t i = 0; i < e->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		for (int a = 0; a < 3; a++)
			P[a] += v[a];
	}
}

double lz_edmd_temperature(const lz_edmd *e)
{
	double ke = 0;
	for (size_t i = 0; i < e->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		ke += 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	}
	return 2 * ke / (e->dim * (double)e->n);
}

/* Particle i's position now lies in its cell (to tol) and inside the walls. */
static int audit_place(const lz_edmd *e, uint32_t i, double tol)
{
	double r[3], v[3];
	const lz_edmd_particle *p = &e->p[i];
	lz_edmd_state(e, p, e->now, r, v);
	uint32_t c = p->cell, cc[3] = {c % (uint32_t)e->m[0], c / (uint32_t)e->m[0] % (uint32_t)e->m[1],
	                               c / ((uint32_t)e->m[0] * (uint32_t)e->m[1])};
	for (int a = 0; a < e->dim; a++) {
		double lo = cc[a] * e->w[a], hi = (cc[a] + 1) * e->w[a];
		if (e->wall[a]) {
			lo = fmax(lo, 0.5);
			hi = fmin(hi, e->L - 0.5);
		}
		if (r[a] < lo - tol || r[a] > hi + tol)
			return lz_error(LZ_EDOM, "particle %u: %c = %.12g at t = %.12g is outside its "
			                "cell %u, which spans [%.12g, %.12g]", i, "xyz"[a], r[a],
			                lz_edmd_time(e), c, lo, hi);
	}
	return LZ_OK;
}

static int audit_clocks(const lz_edmd *e, uint32_t i)
{
	const lz_edmd_particle *p = &e->p[i];
	double slack = 1e-12 * fmax(1, fabs(e->now));
	if (p->t0 > e->now + slack)
		return lz_error(LZ_EDOM, "particle %u: its clock t0 = %.17g is ahead of now = %.17g",
		                i, p->t0, e->now);
	if (e->cal ? !lz_calendar_contains(e->cal, i) : !lz_heap_contains(e->heap, i))
		return lz_error(LZ_EDOM, "particle %u has no event in the queue", i);
	double t = e->cal ? lz_calendar_key(e->cal, i) : lz_heap_key(e->heap, i);
	if (t < e->now - slack)
		return lz_error(LZ_EDOM, "particle %u: its event at %.17g is before now = %.17g", i,
		                t, e->now);
	int32_t q = e->ev[i].partner;
	if (q >= 0 && (size_t)q >= e->n)
		return lz_error(LZ_EDOM, "particle %u: event partner %d is not a particle", i, q);
	return LZ_OK;
}

int lz_edmd_audit(const lz_edmd *e)
{
	int st = e->cal ? lz_calendar_audit(e->cal) : lz_heap_audit(e->heap);
	if (st)
		return st;
	size_t queued = e->cal ? e->cal->n : e->heap->n;
	if (queued != e->n)
		return lz_error(LZ_EDOM, "the queue holds %zu events for %zu particles", queued, e->n);
	size_t listed = 0;
	for (size_t c = 0; c < e->ncells; c++) {
		int32_t second = e->list[c].head >= 0 ? e->next[e->list[c].head] : -1;
		if (e->list[c].second != second)
			return lz_error(LZ_EDOM, "cell %zu: second = %d, but its list's second "
			                "particle is %d", c, e->list[c].second, second);
	}
	for (size_t c = 0; c < e->ncells; c++)
		for (int32_t j = e->list[c].head; j >= 0; j = e->next[j]) {
			if ((size_t)j >= e->n || listed++ > e->n)
				return lz_error(LZ_EDOM, "cell %zu: its list is broken (entry %d)", c, j);
			if (e->p[j].cell != c)
				return lz_error(LZ_EDOM, "particle %d is in the list of cell %zu but says "
				                "it is in cell %u", j, c, e->p[j].cell);
		}
	if (listed != e->n)
		return lz_error(LZ_EDOM, "the cell lists hold %zu particles, not %zu", listed, e->n);
	for (uint32_t i = 0; i < e->n; i++)
		if ((st = audit_clocks(e, i)) || (!e->lists && (st = audit_place(e, i, 1e-9))))
			return st;
	return e->lists ? lz_edmd_list_audit(e) : LZ_OK;
}

double lz_edmd_bytes(const lz_edmd *e)
{
	double queue = e->cal ? sizeof(double) + 2 * sizeof(uint32_t) /* key, links */
	                        + (e->cal->days + 1) * sizeof(uint32_t) / (double)e->n
	                      : sizeof(lz_heap_node) + sizeof(uint32_t) /* node, pos */;
	double per = sizeof(lz_edmd_particle) + sizeof(lz_edmd_event) + queue +
	             sizeof(int32_t) /* next */;
	per += e->lists ? lz_edmd_list_bytes(e) : 0;
	return per + (double)e->ncells * sizeof(lz_edmd_list) / (double)e->n;
}
