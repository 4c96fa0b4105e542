/* msg.c — the message API (lz/msg.h) and its stub back-end: P ranks in one process.
 *
 * Each rank's inbox is a min-heap of messages keyed by the turn (or virtual time) at
 * which they may arrive, then by a global sequence number. A message from s to r may
 * arrive no earlier than the one s sent r before it, so the heap's order keeps every
 * pair in order (non-overtaking), whatever the random delays. Reductions go through
 * two slots, by the parity of the round: a fast rank may start round k+1 while a slow
 * one still has to collect round k.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/error.h"
#include "lz/msg.h"

/* ---- the API: checks, counters, then the back-end ---- */

int lz_msg_send(lz_msg *m, int to, const void *data, size_t n)
{
	if (to < 0 || to >= m->size || to == m->rank)
		return lz_error(LZ_EINVAL, "rank %d cannot send to rank %d: ranks are 0 .. %d and "
		                "not itself", m->rank, to, m->size - 1);
	if (n > LZ_MSG_MAX)
		return lz_error(LZ_EINVAL, "a message of %zu bytes: at most LZ_MSG_MAX = %d", n,
		                LZ_MSG_MAX);
	int st = m->b->send(m, to, data, n);
	if (st == LZ_OK) {
		m->counts.sent++;
		m->counts.bytes_sent += n;
	}
	return st;
}

int lz_msg_poll(lz_msg *m, int *from, void *buf, size_t cap, size_t *n)
{
	int got = m->b->poll(m, from, buf, cap, n);
	if (got == 1) {
		m->counts.received++;
		m->counts.bytes_received += *n;
	}
	return got;
}

int lz_msg_reduce_start(lz_msg *m, lz_msg_op op, const double *in, size_t n)
{
	if (n < 1 || n > LZ_MSG_RMAX || (op != LZ_MSG_MINIMUM && op != LZ_MSG_MAXIMUM &&
	                                 op != LZ_MSG_SUM))
		return lz_error(LZ_EINVAL, "a reduction of %zu values with operation %d: 1 .. %d "
		                "values, minimum, maximum or sum", n, (int)op, LZ_MSG_RMAX);
	return m->b->reduce_start(m, op, in, n);
}

int lz_msg_reduce_test(lz_msg *m, double *out)
{
	int done = m->b->reduce_test(m, out);
	if (done == 1)
		m->counts.reductions++;
	return done;
}

double lz_msg_clock(const lz_msg *m) { return m->b->clock(m); }

void lz_msg_charge(lz_msg *m, double events) { m->b->charge(m, events); }

/* ---- the stub ---- */

typedef struct {
	double ready;    /* turn or virtual time from which it may arrive */
	uint64_t seq;    /* order of sending, for ties */
	int from;
	size_t n;
	unsigned char *data;
} letter;

typedef struct {
	letter *h;       /* a min-heap by (ready, seq) */
	size_t n, cap;
} inbox;

typedef struct {
	double value[LZ_MSG_RMAX];
	size_t n;
	lz_msg_op op;
	int joined;      /* ranks that have started this round */
	int collected;   /* ranks that have read its result */
	double ready;    /* virtual time at which the result is known */
} round_slot;

typedef struct {
	lz_msg m;
	lz_stub *stub;
	inbox in;
	double clock;        /* virtual seconds (LZ_STUB_VIRTUAL) */
	double *last_ready;  /* per receiver: the ready time of the last message sent to it */
	uint64_t round;      /* rounds this rank has started */
	int in_round;        /* 1 between its start and its successful test */
	lz_work state;
	int waits;           /* consecutive WAIT turns */
	int blocked;         /* virtual time: waits with nothing that could wake it */
} stub_rank;

struct lz_stub {
	lz_stub_params p;
	stub_rank *r;
	round_slot slot[2];
	gsl_rng *rng;
	double turn;        /* scheduler turns so far */
	uint64_t seq;
};

static stub_rank *rank_of(const lz_msg *m) { return m->impl; }

static int earlier(const letter *a, const letter *b)
{
	return a->ready < b->ready || (a->ready == b->ready && a->seq < b->seq);
}

static int inbox_push(inbox *q, letter l)
{
	if (q->n == q->cap) {
		size_t cap = q->cap ? 2 * q->cap : 64;
		letter *h = realloc(q->h, cap * sizeof *h);
		if (!h)
			return lz_error(LZ_ENOMEM, "no memory for %zu queued messages", cap);
		q->h = h;
		q->cap = cap;
	}
	size_t k = q->n++;
	while (k > 0 && earlier(&l, &q->h[(k - 1) / 2])) {
		q->h[k] = q->h[(k - 1) / 2];
		k = (k - 1) / 2;
	}
	q->h[k] = l;
	return LZ_OK;
}

static letter inbox_pop(inbox *q)
{
	letter top = q->h[0], last = q->h[--q->n];
	size_t k = 0;
	for (;;) {
		size_t c = 2 * k + 1;
		if (c >= q->n)
			break;
		if (c + 1 < q->n && earlier(&q->h[c + 1], &q->h[c]))
			c++;
		if (!earlier(&q->h[c], &last))
			break;
		q->h[k] = q->h[c];
		k = c;
	}
	if (q->n > 0)
		q->h[k] = last;
	return top;
}

/* The time a rank reads messages by: its virtual clock, or the scheduler's turn. */
static double now_of(const stub_rank *r)
{
	return r->stub->p.policy == LZ_STUB_VIRTUAL ? r->clock : r->stub->turn;
}

static int stub_send(lz_msg *m, int to, const void *data, size_t n)
{
	stub_rank *r = rank_of(m);
	lz_stub *s = r->stub;
	double ready;
	if (s->p.policy == LZ_STUB_VIRTUAL) {
		r->clock += s->p.cost_message;
		ready = r->clock + s->p.latency;
	} else {
		ready = s->turn + (s->p.delay > 0 ? (double)gsl_rng_uniform_int(s->rng,
		                                       (unsigned long)s->p.delay + 1) : 0);
	}
	if (ready < r->last_ready[to])  /* never overtake the previous message */
		ready = r->last_ready[to];
	r->last_ready[to] = ready;
	letter l = {ready, s->seq++, m->rank, n, malloc(n ? n : 1)};
	if (!l.data)
		return lz_error(LZ_ENOMEM, "no memory for a message of %zu bytes", n);
	memcpy(l.data, data, n);
	int st = inbox_push(&s->r[to].in, l);
	if (st != LZ_OK)
		free(l.data);
	s->r[to].blocked = 0;
	return st;
}

static int stub_poll(lz_msg *m, int *from, void *buf, size_t cap, size_t *n)
{
	stub_rank *r = rank_of(m);
	if (r->in.n == 0 || r->in.h[0].ready > now_of(r))
		return 0;
	if (r->in.h[0].n > cap)
		return lz_error(LZ_EINVAL, "rank %d: a message of %zu bytes from rank %d does not "
		                "fit the %zu bytes given", m->rank, r->in.h[0].n, r->in.h[0].from,
		                cap);
	letter l = inbox_pop(&r->in);
	memcpy(buf, l.data, l.n);
	*from = l.from;
	*n = l.n;
	free(l.data);
	if (r->stub->p.policy == LZ_STUB_VIRTUAL)
		r->clock += r->stub->p.cost_message;
	return 1;
}

static int stub_reduce_start(lz_msg *m, lz_msg_op op, const double *in, size_t n)
{
	stub_rank *r = rank_of(m);
	if (r->in_round)
		return lz_error(LZ_EINVAL, "rank %d started a reduction before the last one "
		                "completed", m->rank);
	round_slot *sl = &r->stub->slot[r->round % 2];
	if (sl->joined == 0) {
		sl->op = op;
		sl->n = n;
		sl->ready = 0;
		for (size_t k = 0; k < n; k++)
			sl->value[k] = in[k];
	} else {
		if (sl->op != op || sl->n != n)
			return lz_error(LZ_EINVAL, "rank %d joined a reduction of %zu values (operation "
			                "%d) that others started with %zu (operation %d)", m->rank, n,
			                (int)op, sl->n, (int)sl->op);
		for (size_t k = 0; k < n; k++)
			sl->value[k] = op == LZ_MSG_SUM       ? sl->value[k] + in[k]
			               : op == LZ_MSG_MINIMUM ? fmin(sl->value[k], in[k])
			                                      : fmax(sl->value[k], in[k]);
	}
	sl->joined++;
	sl->ready = fmax(sl->ready, now_of(r) + r->stub->p.latency);
	r->in_round = 1;
	if (sl->joined == r->stub->p.ranks)  /* complete: wake whoever waits for it */
		for (int k = 0; k < r->stub->p.ranks; k++)
			r->stub->r[k].blocked = 0;
	return LZ_OK;
}

static int stub_reduce_test(lz_msg *m, double *out)
{
	stub_rank *r = rank_of(m);
	lz_stub *s = r->stub;
	round_slot *sl = &s->slot[r->round % 2];
	if (!r->in_round)
		return lz_error(LZ_EINVAL, "rank %d tested a reduction it did not start", m->rank);
	if (sl->joined < s->p.ranks || (s->p.policy == LZ_STUB_VIRTUAL && r->clock < sl->ready))
		return 0;
	for (size_t k = 0; k < sl->n; k++)
		out[k] = sl->value[k];
	r->in_round = 0;
	r->round++;
	if (++sl->collected == s->p.ranks)
		sl->joined = sl->collected = 0;
	return 1;
}

static double stub_clock(const lz_msg *m) { return now_of(rank_of(m)); }

static void stub_charge(lz_msg *m, double events)
{
	stub_rank *r = rank_of(m);
	if (r->stub->p.policy == LZ_STUB_VIRTUAL)
		r->clock += events * r->stub->p.cost_event;
}

static const lz_msg_backend stub_backend = {
	stub_send, stub_poll, stub_reduce_start, stub_reduce_test, stub_clock, stub_charge,
};

lz_stub *lz_stub_alloc(const lz_stub_params *p)
{
	if (p->ranks < 1 || p->ranks > LZ_STUB_RANKS_MAX)
		return lz_error(LZ_EINVAL, "ranks = %d: 1 <= ranks <= %d", p->ranks,
		                LZ_STUB_RANKS_MAX), NULL;
	if ((unsigned)p->policy > LZ_STUB_VIRTUAL)
		return lz_error(LZ_EINVAL, "scheduling policy %d: round robin, random, ahead or "
		                "virtual", (int)p->policy), NULL;
	if (p->delay < 0 || p->delay > 1000000)
		return lz_error(LZ_EINVAL, "delay = %d turns: 0 <= delay <= 10^6", p->delay), NULL;
	if (p->policy == LZ_STUB_AHEAD && (p->ahead < 0 || p->ahead >= p->ranks ||
	                                   p->ahead_turns < 1))
		return lz_error(LZ_EINVAL, "the rank ahead is %d (0 .. %d) with %d turns in a row "
		                "(>= 1)", p->ahead, p->ranks - 1, p->ahead_turns), NULL;
	if (p->policy == LZ_STUB_VIRTUAL && !(p->cost_event >= 0 && p->cost_message >= 0 &&
	                                      p->latency >= 0 && isfinite(p->cost_event +
	                                      p->cost_message + p->latency)))
		return lz_error(LZ_EINVAL, "virtual time needs costs and a latency >= 0 and "
		                "finite"), NULL;
	lz_stub *s = calloc(1, sizeof *s);
	if (!s)
		return lz_error(LZ_ENOMEM, "no memory for the stub"), NULL;
	s->p = *p;
	s->r = calloc((size_t)p->ranks, sizeof *s->r);
	s->rng = gsl_rng_alloc(gsl_rng_mt19937);
	int ok = s->r && s->rng;
	for (int k = 0; ok && k < p->ranks; k++) {
		stub_rank *r = &s->r[k];
		r->stub = s;
		r->m = (lz_msg){&stub_backend, k, p->ranks, {0}, r};
		ok = (r->last_ready = calloc((size_t)p->ranks, sizeof *r->last_ready)) != NULL;
	}
	if (!ok) {
		lz_stub_free(s);
		return lz_error(LZ_ENOMEM, "no memory for %d ranks", p->ranks), NULL;
	}
	gsl_rng_set(s->rng, p->seed);
	return s;
}

void lz_stub_free(lz_stub *s)
{
	if (!s)
		return;
	for (int k = 0; s->r && k < s->p.ranks; k++) {
		for (size_t q = 0; q < s->r[k].in.n; q++)
			free(s->r[k].in.h[q].data);
		free(s->r[k].in.h);
		free(s->r[k].last_ready);
	}
	free(s->r);
	if (s->rng)
		gsl_rng_free(s->rng);
	free(s);
}

lz_msg *lz_stub_rank(lz_stub *s, int r) { return &s->r[r].m; }

double lz_stub_time(const lz_stub *s)
{
	if (s->p.policy != LZ_STUB_VIRTUAL)
		return s->turn;
	double t = 0;
	for (int k = 0; k < s->p.ranks; k++)
		t = fmax(t, s->r[k].clock);
	return t;
}

/* The rank to run next; -1 when all are done. */
static int pick(lz_stub *s, int *burst)
{
	int P = s->p.ranks, live = 0, best = -1;
	for (int k = 0; k < P; k++)
		live += s->r[k].state != LZ_WORK_DONE;
	if (live == 0)
		return -1;
	if (s->p.policy == LZ_STUB_VIRTUAL) {
		for (int k = 0; k < P; k++)
			if (s->r[k].state != LZ_WORK_DONE && !s->r[k].blocked &&
			    (best < 0 || s->r[k].clock < s->r[best].clock))
				best = k;
		return best < 0 ? -2 : best;  /* -2: every live rank blocked */
	}
	if (s->p.policy == LZ_STUB_ROUND_ROBIN) {
		int k = (int)fmod(s->turn, P);
		while (s->r[k].state == LZ_WORK_DONE)
			k = (k + 1) % P;
		return k;
	}
	if (*burst > 0 && s->r[s->p.ahead].state != LZ_WORK_DONE) {  /* a burst ends with its rank */
		(*burst)--;
		return s->p.ahead;
	}
	int k = (int)gsl_rng_uniform_int(s->rng, (unsigned long)live);
	for (best = 0;; best++)
		if (s->r[best].state != LZ_WORK_DONE && k-- == 0)
			break;
	if (s->p.policy == LZ_STUB_AHEAD && best == s->p.ahead)
		*burst = s->p.ahead_turns - 1;
	return best;
}

/* Every rank that is not done has waited twice in a row and nothing is on its way. */
static int deadlocked(const lz_stub *s)
{
	for (int k = 0; k < s->p.ranks; k++) {
		const stub_rank *r = &s->r[k];
		if (r->state == LZ_WORK_DONE)
			continue;
		if (r->waits < 2 || r->in.n > 0)
			return 0;
		if (r->in_round && s->slot[r->round % 2].joined == s->p.ranks)
			return 0;  /* its reduction can complete */
	}
	return 1;
}

static int deadlock(const lz_stub *s)
{
	return lz_error(LZ_EDOM, "deadlock after %.0f turns: every rank still running waits, "
	                "and no message is on its way to any of them (a reduction one rank "
	                "never joined, or a message never sent)", s->turn);
}

/* In virtual time a waiting rank's clock moves on to its next message, or to the
 * time its reduction completes. */
static void wait_on(lz_stub *s, stub_rank *r)
{
	double next = INFINITY;
	if (r->in.n > 0)
		next = r->in.h[0].ready;
	round_slot *sl = &s->slot[r->round % 2];
	if (r->in_round && sl->joined == s->p.ranks)
		next = fmin(next, sl->ready);
	if (isfinite(next))
		r->clock = fmax(r->clock, next);
	else
		r->blocked = 1;
}

int lz_stub_run(lz_stub *s, lz_work_fn *work, void *arg)
{
	int burst = 0;
	for (int k = 0; k < s->p.ranks; k++)
		s->r[k].state = LZ_WORK_BUSY;
	for (;;) {
		int k = pick(s, &burst);
		if (k == -1)
			return LZ_OK;
		if (k == -2)
			return deadlock(s);
		stub_rank *r = &s->r[k];
		int st = work(k, arg, &r->state);
		if (st != LZ_OK)
			return st;
		r->waits = r->state == LZ_WORK_WAIT ? r->waits + 1 : 0;
		if (r->state == LZ_WORK_WAIT && s->p.policy == LZ_STUB_VIRTUAL)
			wait_on(s, r);
		s->turn++;
		if (r->state == LZ_WORK_WAIT && s->p.policy != LZ_STUB_VIRTUAL && deadlocked(s))
			return deadlock(s);
	}
}
