/* pedmd_lesson.h — what the experiments of lesson 06 share: the machines whose costs
 * the stub's virtual time models, a melted gas, the serial reference run that every
 * parallel run must reproduce, and one parallel run on the stub with what it measured.
 *
 * Everything here is static inline, so that a driver that does not use a helper does
 * not warn about it. Not a library: the drivers are the only users.
 */
#ifndef PEDMD_LESSON_H
#define PEDMD_LESSON_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/msg.h"
#include "lz/pedmd.h"
#include "lz/rng.h"

/* ---- machines ---- */

/* The costs of the stub's virtual time (lz/msg.h, LZ_STUB_VIRTUAL). */
typedef struct {
	const char *name;
	double cost_event;    /* s per event carried out (rolled back ones included) */
	double cost_message;  /* s of CPU per send and per receive */
	double latency;       /* s from a send to the earliest arrival; a reduction too */
} machine;

/* A cluster with a fast network. An event: stage 05 runs about 1.8 million events
 * per second on one core, and a rank does more per event (ghosts, messages, saving),
 * so 1 µs. A message of ~100 bytes costs its sender and its receiver 0.5 µs each (the
 * software overhead of a small MPI message), and arrives 2 µs after it was sent, the
 * end-to-end latency of InfiniBand; a reduction is charged one latency too. */
static const machine CLUSTER = {"cluster", 1e-6, 0.5e-6, 2e-6};

/* The same CPU on a network that costs nothing: what is left is the algorithm's own
 * loss (rollbacks, waiting for the slowest rank at a cut). */
static const machine IDEAL = {"ideal network", 1e-6, 0, 0};

/* Stub parameters for P ranks on machine m, scheduled in virtual time. */
static inline lz_stub_params stub_on(const machine *m, int P, unsigned long seed)
{
	lz_stub_params sp = {P, LZ_STUB_VIRTUAL, seed, 0, 0, 1, m->cost_event, m->cost_message,
	                     m->latency};
	return sp;
}

/* ---- the serial reference ---- */

/* A growing list of events (the serial run's, in the order it carried them out). */
typedef struct {
	lz_pedmd_record *ev;
	size_t n, cap;
} event_log;

static inline int log_push(event_log *log, lz_pedmd_record q)
{
	if (log->n == log->cap) {  /* doubling: amortised O(1), a few reallocations a run */
		size_t cap = log->cap ? 2 * log->cap : 4096;
		lz_pedmd_record *ev = realloc(log->ev, cap * sizeof *ev);
		if (!ev)
			return lz_error(LZ_ENOMEM, "no memory for a log of %zu events", cap);
		log->ev = ev;
		log->cap = cap;
	}
	log->ev[log->n++] = q;
	return LZ_OK;
}

/* What the event at the top of e's heap is, before lz_edmd_step carries it out, as a
 * rank notes it (lz_pedmd_note): a collision (i < j), a stale collision, or a face —
 * a crossing, until the step shows that it was a wall. */
static inline lz_pedmd_record next_event(const lz_edmd *e)
{
	uint32_t i = lz_heap_top(e->heap);
	lz_edmd_event ev = e->ev[i];
	lz_pedmd_record q = {e->t_base + lz_heap_top_t(e->heap), i, i, LZ_PEDMD_CROSSING, 0};
	if (ev.partner >= 0 && e->p[ev.partner].count == ev.pcount) {
		uint32_t j = (uint32_t)ev.partner;
		q.kind = LZ_PEDMD_COLLISION;
		q.i = i < j ? i : j;
		q.j = i < j ? j : i;
	} else if (ev.partner >= 0) {
		q.kind = LZ_PEDMD_STALE;
	}
	return q;
}

/* The next re-base time after absolute time T: the next multiple of tau, computed as
 * the ranks compute it, so that both runs round alike. */
static inline double next_rebase(double T, double tau)
{
	return (floor(T / tau) + 1) * tau;
}

/* Run e serially to absolute time t_stop the way the ranks do: re-based at every
 * multiple of tau before t_stop (none at t_stop itself), every particle brought to
 * t_stop at the end. Each event goes into log when log is not NULL. O(events log N). */
static inline int serial_run(lz_edmd *e, double t_stop, double tau, event_log *log)
{
	for (double T = next_rebase(lz_edmd_time(e), tau);; T = next_rebase(T, tau)) {
		double stop = fmin(T, t_stop);
		while (e->t_base + lz_heap_top_t(e->heap) <= stop) {
			lz_pedmd_record q = next_event(e);
			uint64_t bounces = e->bounces;
			if (lz_edmd_step(e) < 0)
				return lz_error(LZ_EPHYS, "the serial run stopped: nothing left to happen");
			if (q.kind == LZ_PEDMD_CROSSING && e->bounces > bounces)
				q.kind = LZ_PEDMD_BOUNCE;
			if (log && log_push(log, q) != LZ_OK)
				return LZ_ENOMEM;
		}
		e->now = stop - e->t_base;
		lz_edmd_sync(e);
		if (stop >= t_stop)
			break;
		lz_edmd_rebase(e);
	}
	if (log)  /* events at one instant: the order the ranks' logs are sorted in */
		qsort(log->ev, log->n, sizeof *log->ev, lz_pedmd_record_order);
	return LZ_OK;
}

/* ---- a gas ---- */

typedef struct {
	int dim;
	size_t n;
	double eta;
	int walls;           /* LZ_EDMD_WALLS_* */
	double gravity, restitution;
	unsigned long seed;
	double melt;         /* serial time run from the lattice before anything is measured */
	double rebase;       /* the re-base interval of every run of this gas */
} gas;

/* Run e (just started, rebase_auto 0) serially for `melt` time units, re-based at the
 * multiples of tau and at the end, its counters zeroed: the start of the measured runs.
 * LZ_OK or an LZ_E code. */
static inline int melt_in(lz_edmd *e, double melt, double tau)
{
	int st = melt > 0 ? serial_run(e, lz_edmd_time(e) + melt, tau, NULL) : LZ_OK;
	if (st == LZ_OK && melt > 0)
		lz_edmd_rebase(e);
	lz_edmd_reset_counts(e);
	return st;
}

/* The gas g: placed on the lattice (seeded), re-based only when asked, melted for
 * g->melt time units (melt_in). The same g gives the same bits every time: a driver
 * makes one copy to start the parallel runs from and one to run on as their serial
 * reference. NULL with lz_error. */
static inline lz_edmd *gas_make(const gas *g)
{
	lz_edmd_params p = {g->dim, g->n, g->eta, g->restitution, g->gravity, g->walls, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	if (!e)
		return NULL;
	lz_rng *rng = lz_rng_alloc("mt19937", g->seed);
	int st = rng ? lz_edmd_place_lattice(e, rng) : LZ_ENOMEM;
	lz_rng_free(rng);
	e->rebase_auto = 0;
	if (st == LZ_OK)
		st = melt_in(e, g->melt, g->rebase);
	if (st != LZ_OK) {
		lz_edmd_free(e);
		return NULL;
	}
	return e;
}

/* A system with g's grid, particles not placed: where a run's owned particles are
 * gathered (lz_pedmd_sim_gather). */
static inline lz_edmd *gas_blank(const gas *g)
{
	lz_edmd_params p = {g->dim, g->n, g->eta, g->restitution, g->gravity, g->walls, 0, LZ_EDMD_CELLS, 0, 0};
	return lz_edmd_alloc(&p);
}

/* The start of a measured run of g for `time` units, its serial reference run to the
 * end (*t_stop, absolute) and a blank for the gathered picture. LZ_OK, or an LZ_E code
 * with the systems made so far freed and NULL. */
static inline int gas_runs(const gas *g, double time, lz_edmd **start, lz_edmd **ref,
                           lz_edmd **pic, double *t_stop)
{
	*start = gas_make(g);
	*ref = gas_make(g);
	*pic = gas_blank(g);
	int st = *start && *ref && *pic ? LZ_OK : LZ_ENOMEM;
	*t_stop = *start ? lz_edmd_time(*start) + time : 0;
	if (st == LZ_OK)
		st = serial_run(*ref, *t_stop, g->rebase, NULL);
	if (st != LZ_OK) {
		lz_edmd_free(*start);
		lz_edmd_free(*ref);
		lz_edmd_free(*pic);
		*start = *ref = *pic = NULL;
	}
	return st;
}

/* ---- scaling ---- */

/* S ∝ P^a fitted on the points P[1 .. np-1] (P >= 2; np <= 16) on log-log by least
 * squares (gsl_fit_linear): a and its standard error from the scatter about the line
 * (NAN with fewer than three points). */
static inline void fit_power(const int *P, const double *S, int np, double *a, double *a_err)
{
	double x[16], y[16], c0, c1, cov00, cov01, cov11, sumsq;
	int n = 0;
	for (int k = 1; k < np && n < 16; k++) {
		x[n] = log(P[k]);
		y[n++] = log(S[k]);
	}
	gsl_fit_linear(x, 1, y, 1, (size_t)n, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
	*a = c1;
	*a_err = n > 2 ? sqrt(cov11 * sumsq / (n - 2)) : NAN;
}

/* ---- one parallel run ---- */

typedef struct {
	int P, kind;               /* ranks; LZ_PEDMD_ROWS or LZ_PEDMD_MORTON */
	lz_stub_params sp;         /* sp.ranks is set from P */
	lz_pedmd_params pp;
	const uint32_t *cut;       /* the cuts (P + 1 of them), NULL: even */
	int audit;                 /* 1: lz_pedmd_audit at every cut */
} par_setup;

typedef struct {
	double vtime;              /* the stub's clock at the end: virtual s, or turns */
	lz_pedmd_counts c;         /* all ranks' counters summed */
	uint64_t messages;         /* point-to-point messages sent, all ranks */
	uint64_t audits;           /* cuts audited */
	double load_ratio;         /* the largest rank's committed events over the mean */
	double load_max;           /* the largest rank's committed events */
	double per_rank[LZ_PEDMD_RANKS_MAX];  /* each rank's committed events */
	int same_counts;           /* 1: committed events, by kind, as many as serially */
	int same_records;          /* 1: every final particle record equals the serial
	                              run's, all 64 bytes of it (r, v, t0, count, cell) */
	int same_log;              /* 1: the committed events equal the serial log, record
	                              by record; -1: not compared (no log asked) */
} par_result;

/* The committed events of the run against the serial log. */
static inline int same_log(const lz_pedmd_sim *x, const event_log *want)
{
	size_t n;
	lz_pedmd_record *got = lz_pedmd_sim_log(x, &n);
	int same = n == want->n;
	for (size_t k = 0; same && k < n; k++)
		same = got[k].t == want->ev[k].t && got[k].i == want->ev[k].i &&
		       got[k].j == want->ev[k].j && got[k].kind == want->ev[k].kind;
	free(got);
	return same;
}

/* Run P ranks from `start` (a gas_make system, left as it is) to t_stop, and compare
 * with `ref`, the serial run from the same start to the same t_stop (and its log when
 * q->pp.log is 1). pic: a gas_blank system for the gathered picture. load: NULL, or
 * room for the committed events of every cell (lz_pedmd_sim_load). */
static inline int par_run(const lz_edmd *start, const par_setup *q, double t_stop,
                          const lz_edmd *ref, const event_log *log, lz_edmd *pic,
                          double *load, par_result *res)
{
	lz_stub_params sp = q->sp;
	sp.ranks = q->P;
	lz_pedmd_sim *x = lz_pedmd_sim_alloc_cut(start, q->kind, q->cut, &sp, &q->pp);
	if (!x)
		return LZ_EINVAL;  /* lz_error_message() says why */
	x->audit = q->audit;
	int st = lz_pedmd_sim_run(x, t_stop);
	if (st != LZ_OK) {
		lz_pedmd_sim_free(x);
		return st;
	}
	memset(res, 0, sizeof *res);
	res->vtime = lz_stub_time(x->stub);
	res->c = lz_pedmd_sim_counts(x);
	res->audits = x->audits;
	for (int k = 0; k < q->P; k++) {
		double mine = (double)x->rank[k]->counts.committed;
		res->per_rank[k] = mine;
		res->messages += lz_msg_counters(lz_stub_rank(x->stub, k)).sent;
		res->load_max = fmax(res->load_max, mine);
	}
	res->load_ratio = res->c.committed ? res->load_max * q->P / (double)res->c.committed : 1;
	res->same_counts = res->c.committed == ref->events && res->c.collisions == ref->collisions &&
	                   res->c.crossings == ref->crossings && res->c.bounces == ref->bounces &&
	                   res->c.stale == ref->stale;
	lz_pedmd_sim_gather(x, pic);
	res->same_records = 1;
	for (size_t i = 0; i < ref->n; i++)
		res->same_records &= memcmp(&pic->p[i], &ref->p[i], sizeof ref->p[i]) == 0;
	res->same_log = q->pp.log && log ? same_log(x, log) : -1;
	if (load)
		lz_pedmd_sim_load(x, load);
	lz_pedmd_sim_free(x);
	return LZ_OK;
}

/* 1 when the run reproduced the serial run: counts, records, and the log if compared. */
static inline int exact(const par_result *r)
{
	return r->same_counts && r->same_records && r->same_log != 0;
}

/* The share of the cells (weight NULL) or of a per-cell weight (the committed events
 * of each cell, say) that lies in BORDER cells of their owner (lz_pedmd_classify):
 * where a rank's changes must be told to others, and late news can hurt. cut: NULL
 * for even cuts. NAN with lz_error on failure. O(P · cells · 3^dim). */
static inline double border_share(const lz_edmd *e, int P, int kind, const uint32_t *cut,
                                  const double *weight)
{
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(e, P, kind);
	uint8_t *cls = d ? malloc(e->ncells) : NULL;
	if (!cls) {
		lz_pedmd_domains_free(d);
		return d ? lz_error(LZ_ENOMEM, "no memory for %zu cells", e->ncells), NAN : NAN;
	}
	if (cut)
		memcpy(d->cut, cut, (size_t)(P + 1) * sizeof *cut);
	double border = 0, total = 0;
	for (int r = 0; r < P; r++) {
		lz_pedmd_classify(e, d, r, cls);
		for (size_t c = 0; c < e->ncells; c++) {
			double w = weight ? weight[c] : 1;
			border += cls[c] == LZ_PEDMD_BORDER ? w : 0;
			total += cls[c] == LZ_PEDMD_BORDER || cls[c] == LZ_PEDMD_INTERIOR ? w : 0;
		}
	}
	free(cls);
	lz_pedmd_domains_free(d);
	return total > 0 ? border / total : 0;
}

/* ---- the window ---- */

/* The first window of a run of P ranks is c·P/R, R the serial events per unit time:
 * about c events per rank. (It adapts between 1/64 and 64 times that.) */
#define NWINDOW 5
static const double window_c[NWINDOW] = {1.0 / 64, 1.0 / 16, 0.25, 1, 4};

/* The fastest (least virtual time) of the runs of q with the windows window_c, tried
 * from the shortest up while they get faster, into *best, its c into *c_best. One
 * rank never rolls back: it runs once, its window the re-base interval (c_best NAN).
 * A run that is not the serial run is returned at once (the caller reports it). The
 * runs are deterministic: the best is a property of the setup, not of luck. */
static inline int best_window(const lz_edmd *start, par_setup q, double R, double t_stop,
                              const lz_edmd *ref, lz_edmd *pic, par_result *best,
                              double *c_best)
{
	best->vtime = INFINITY;
	for (int k = 0; k < NWINDOW; k++) {
		q.pp.window = q.P == 1 ? q.pp.rebase : window_c[k] * q.P / R;
		par_result r;
		int st = par_run(start, &q, t_stop, ref, NULL, pic, NULL, &r);
		if (st != LZ_OK)
			return st;
		int faster = r.vtime < best->vtime;
		if (faster || !exact(&r)) {
			*best = r;
			*c_best = q.P == 1 ? NAN : window_c[k];
		}
		if (q.P == 1 || !exact(&r) || !faster)
			break;  /* past the best: longer windows only roll back more */
	}
	return LZ_OK;
}

#endif
