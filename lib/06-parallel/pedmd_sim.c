/* pedmd_sim.c — a whole parallel run in one process: the P ranks of lz/pedmd.h over
 * the stub back-end of lz/msg.h, made from one serial system, run together, audited
 * at every cut when asked, and gathered back into the serial picture. The tests, the
 * lesson's experiments and the `lz` program's stub runs all go through here. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/pedmd.h"

lz_pedmd_sim *lz_pedmd_sim_alloc(const lz_edmd *s, int kind, const lz_stub_params *sp,
                                 const lz_pedmd_params *pp)
{
	return lz_pedmd_sim_alloc_cut(s, kind, NULL, sp, pp);
}

/* 0 = cut[0] < cut[1] < ... < cut[P] = ncells. */
static int check_cuts(const uint32_t *cut, int P, size_t ncells)
{
	for (int r = 0; r < P; r++)
		if (cut[r] >= cut[r + 1])
			return lz_error(LZ_EINVAL, "cut %d = %u, cut %d = %u: every rank needs a cell", r,
			                cut[r], r + 1, cut[r + 1]);
	if (cut[0] != 0 || cut[P] != ncells)
		return lz_error(LZ_EINVAL, "the cuts run from %u to %u, not from 0 to the %zu cells",
		                cut[0], cut[P], ncells);
	return LZ_OK;
}

lz_pedmd_sim *lz_pedmd_sim_alloc_cut(const lz_edmd *s, int kind, const uint32_t *cut,
                                     const lz_stub_params *sp, const lz_pedmd_params *pp)
{
	lz_pedmd_sim *x = calloc(1, sizeof *x);
	if (!x)
		return lz_error(LZ_ENOMEM, "no memory for a parallel run"), NULL;
	x->audited_T = -INFINITY;
	x->stub = lz_stub_alloc(sp);
	if (!x->stub || !(x->d = lz_pedmd_domains_alloc(s, sp->ranks, kind))) {
		lz_pedmd_sim_free(x);
		return NULL;
	}
	if (cut && check_cuts(cut, sp->ranks, s->ncells)) {
		lz_pedmd_sim_free(x);
		return NULL;
	}
	if (cut)
		memcpy(x->d->cut, cut, (size_t)(sp->ranks + 1) * sizeof *cut);
	x->rank = calloc((size_t)sp->ranks, sizeof *x->rank);
	if (!x->rank) {
		lz_pedmd_sim_free(x);
		return lz_error(LZ_ENOMEM, "no memory for %d ranks", sp->ranks), NULL;
	}
	x->P = sp->ranks;
	for (int k = 0; k < x->P; k++)
		if (!(x->rank[k] = lz_pedmd_alloc(s, x->d, lz_stub_rank(x->stub, k), pp))) {
			lz_pedmd_sim_free(x);
			return NULL;
		}
	return x;
}

void lz_pedmd_sim_free(lz_pedmd_sim *x)
{
	if (!x)
		return;
	for (int k = 0; x->rank && k < x->P; k++)
		lz_pedmd_free(x->rank[k]);
	free(x->rank);
	lz_pedmd_domains_free(x->d);
	lz_stub_free(x->stub);
	free(x);
}

/* Every rank waits to begin the window that starts at time T: the run is at a cut. */
static int all_at(const lz_pedmd_sim *x, double T)
{
	for (int k = 0; k < x->P; k++)
		if (x->rank[k]->phase != LZ_PEDMD_BEGIN || x->rank[k]->T != T)
			return 0;
	return 1;
}

/* One turn of a rank. When auditing, a rank about to begin a window that starts later
 * than the last audited cut is held (it spends a turn doing nothing, charged as one
 * event so that virtual time moves on) until every rank is there; then the cut is
 * audited once, and they go on. */
/* The events all ranks have processed. O(P). */
static uint64_t processed(const lz_pedmd_sim *x)
{
	uint64_t n = 0;
	for (int k = 0; k < x->P; k++)
		n += x->rank[k]->counts.processed;
	return n;
}

/* At a cut due for it: new cuts from the load since the last look, summed over the
 * ranks, moved when they pay (lz_pedmd_rebalance's threshold). */
static int balance(lz_pedmd_sim *x)
{
	size_t nc = x->d->ncells;
	double *load = calloc(nc, sizeof *load), *mine = malloc(nc * sizeof *mine);
	int st = load && mine ? LZ_OK
	                      : lz_error(LZ_ENOMEM, "no memory for the load of %zu cells", nc);
	for (int k = 0; k < x->P && st == LZ_OK; k++)
		if ((st = lz_pedmd_load_since(x->rank[k], mine)) == LZ_OK)
			for (size_t c = 0; c < nc; c++)
				load[c] += mine[c];
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1];
	if (st == LZ_OK && lz_pedmd_rebalance(x->d, load, x->rank[0]->p.threshold, cut) == 1)
		st = lz_pedmd_recut(x->rank, x->P, x->d, cut);
	free(load);
	free(mine);
	return st;
}

static int work(int rank, void *arg, lz_work *state)
{
	lz_pedmd_sim *x = arg;
	lz_pedmd *r = x->rank[rank];
	if (x->most && processed(x) > x->most)
		return lz_error(LZ_EDOM, "no progress: the ranks processed %llu events and reached "
		                "time %.17g of %.17g (%llu windows, %llu rollbacks, %llu conservative "
		                "steps) — a rollback or a verdict that never lets a window commit?",
		                (unsigned long long)processed(x), r->T, x->t_stop,
		                (unsigned long long)r->counts.windows,
		                (unsigned long long)r->counts.rollbacks,
		                (unsigned long long)r->counts.conservative);
	if (x->audit && r->phase == LZ_PEDMD_BEGIN && r->T > x->audited_T) {
		if (!all_at(x, r->T)) {
			*state = LZ_WORK_BUSY;
			lz_msg_charge(r->msg, 1);
			return LZ_OK;
		}
		x->audited_T = r->T;
		x->audits++;
		if (lz_pedmd_audit(x->rank, x->P) != LZ_OK)
			return lz_error(LZ_EDOM, "at the cut of time %.17g: %s", r->T, lz_error_message());
	}
	if (lz_pedmd_balance_due(r, x->t_stop)) {
		if (!all_at(x, r->T)) {  /* held until every rank is at the cut */
			*state = LZ_WORK_BUSY;
			lz_msg_charge(r->msg, 1);
			return LZ_OK;
		}
		int st = balance(x);
		if (st != LZ_OK)
			return st;
	}
	return lz_pedmd_work(r, x->t_stop, state);
}

int lz_pedmd_sim_run(lz_pedmd_sim *x, double t_stop)
{
	x->t_stop = t_stop;
	return lz_stub_run(x->stub, work, x);
}

void lz_pedmd_sim_gather(const lz_pedmd_sim *x, lz_edmd *out)
{
	for (int k = 0; k < x->P; k++) {
		const lz_pedmd *r = x->rank[k];
		for (uint32_t i = 0; i < r->nslots; i++)
			if (r->role[i] == LZ_PEDMD_OWNED)
				out->p[lz_pedmd_id(r, i)] = r->e->p[i];
	}
}

void lz_pedmd_sim_load(const lz_pedmd_sim *x, double *load)
{
	memset(load, 0, x->d->ncells * sizeof *load);
	for (int k = 0; k < x->P; k++)
		for (size_t c = 0; c < x->d->ncells; c++)
			load[c] += x->rank[k]->load[c];
}

void lz_pedmd_counts_add(lz_pedmd_counts *s, const lz_pedmd_counts *c)
{
	s->processed += c->processed;
	s->committed += c->committed;
	s->windows = c->windows;  /* the same on every rank */
	s->rollbacks = c->rollbacks;
	s->conservative = c->conservative;
	s->balances = c->balances;
	s->late_harmless += c->late_harmless;
	s->saved_bytes = c->saved_bytes > s->saved_bytes ? c->saved_bytes : s->saved_bytes;
	s->rechecks = c->rechecks;
	s->collisions += c->collisions;
	s->crossings += c->crossings;
	s->bounces += c->bounces;
	s->stale += c->stale;
	s->virial += c->virial;
}

lz_pedmd_counts lz_pedmd_sim_counts(const lz_pedmd_sim *x)
{
	lz_pedmd_counts s = {0};
	for (int k = 0; k < x->P; k++)
		lz_pedmd_counts_add(&s, &x->rank[k]->counts);
	return s;
}

int lz_pedmd_record_order(const void *a, const void *b)
{
	const lz_pedmd_record *p = a, *q = b;
	if (p->t != q->t)
		return p->t < q->t ? -1 : 1;
	if (p->i != q->i)
		return p->i < q->i ? -1 : 1;
	if (p->j != q->j)
		return p->j < q->j ? -1 : 1;
	return (p->kind > q->kind) - (p->kind < q->kind);
}

lz_pedmd_record *lz_pedmd_sim_log(const lz_pedmd_sim *x, size_t *n)
{
	size_t total = 0, m;
	for (int k = 0; k < x->P; k++) {
		lz_pedmd_log(x->rank[k], &m);
		total += m;
	}
	*n = 0;
	lz_pedmd_record *all = total ? malloc(total * sizeof *all) : NULL;
	if (!all)
		return NULL;
	for (int k = 0; k < x->P; k++) {
		const lz_pedmd_record *l = lz_pedmd_log(x->rank[k], &m);
		memcpy(all + *n, l, m * sizeof *all);
		*n += m;
	}
	qsort(all, total, sizeof *all, lz_pedmd_record_order);
	return all;
}

int lz_pedmd_serial(lz_edmd *e, double t_stop, double rebase)
{
	for (double T = (floor(lz_edmd_time(e) / rebase) + 1) * rebase;; T += rebase) {
		double stop = fmin(T, t_stop);
		int st = lz_edmd_run(e, UINT64_MAX, stop);
		if (st != LZ_OK || stop >= t_stop)
			return st;
		lz_edmd_rebase(e);
	}
}
