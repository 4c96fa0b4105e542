/* test_stage06_msg.c — the library half of stage 06, which students do not write: the
 * message API over the stub back-end (lz/msg.h) — exactly once, in order between two
 * ranks, the reductions, the interleavings that a seed repeats, a deadlock reported
 * instead of a hang, the input checks — and the parallel engine's own checks
 * (lz/pedmd.h): the decompositions' invariants, the parameters refused with their
 * ranges, the audit finding hand-broken states, and balanced cuts from a pilot run
 * that spread the committed events evenly and change not one of them. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/edmd.h"
#include "lz/msg.h"
#include "lz/pedmd.h"
#include "lz/rng.h"
#include "lztest.h"

/* ---- the stub ---- */

enum { SENDS = 300 };

/* Every rank sends SENDS numbered messages to every other rank, then receives until it
 * has them all; each checks they come once each, in order per sender. */
typedef struct {
	int P;
	lz_stub *s;
	int sent[16];
	int got[16][16];       /* got[to][from]: messages received, = the next number expected */
	int reduced[16];
	double sum[16][2], min[16];
} chat;

static int chat_work(int rank, void *arg, lz_work *state)
{
	chat *c = arg;
	lz_msg *m = lz_stub_rank(c->s, rank);
	*state = LZ_WORK_BUSY;
	for (int k = 0; k < 3 && c->sent[rank] < SENDS * (c->P - 1); k++, c->sent[rank]++) {
		int to = c->sent[rank] % (c->P - 1), seq = c->sent[rank] / (c->P - 1);
		to += to >= rank;
		int msg[2] = {rank, seq};
		int st = lz_msg_send(m, to, msg, sizeof msg);
		if (st)
			return st;
	}
	int from, msg[2], got, heard = 0;
	size_t n;
	while ((got = lz_msg_poll(m, &from, msg, sizeof msg, &n)) == 1) {
		heard = 1;
		LZ_REQUIRE(n == sizeof msg && msg[0] == from, "rank %d: a message of %zu bytes from %d "
		      "says it is from %d", rank, n, from, msg[0]);
		LZ_REQUIRE(msg[1] == c->got[rank][from], "rank %d: message %d from rank %d arrived when "
		      "%d was next: two messages between the same ranks keep their order, and each "
		      "comes once", rank, msg[1], from, c->got[rank][from]);
		c->got[rank][from]++;
	}
	if (got < 0)
		return got;
	int all = c->sent[rank] == SENDS * (c->P - 1);
	for (int f = 0; f < c->P; f++)
		all &= f == rank || c->got[rank][f] == SENDS;
	if (!all) {
		if (!heard && c->sent[rank] == SENDS * (c->P - 1))
			*state = LZ_WORK_WAIT;  /* nothing to do until a message comes */
		return LZ_OK;
	}
	if (c->reduced[rank] == 0) {
		double in[2] = {rank + 1.0, 10.0 - rank};
		c->reduced[rank] = 1;
		return lz_msg_reduce_start(m, LZ_MSG_SUM, in, 2);
	}
	if (c->reduced[rank] == 1) {
		double out[2];
		got = lz_msg_reduce_test(m, out);
		if (got == 1) {
			c->sum[rank][0] = out[0];
			c->sum[rank][1] = out[1];
			c->reduced[rank] = 2;
			double in[1] = {rank == c->P - 1 ? -3.5 : rank};
			return lz_msg_reduce_start(m, LZ_MSG_MINIMUM, in, 1);
		}
		*state = LZ_WORK_WAIT;
		return got;
	}
	double out[1];
	got = lz_msg_reduce_test(m, out);
	if (got == 1) {
		c->min[rank] = out[0];
		*state = LZ_WORK_DONE;
		return LZ_OK;
	}
	*state = LZ_WORK_WAIT;
	return got;
}

/* The chat on P ranks under a policy; the stub's clock at the end. */
static double run_chat(int P, lz_stub_policy policy, unsigned long seed, int delay)
{
	lz_stub_params p = {P, policy, seed, delay, 1, 5, 1e-6, 3e-6, 2e-5};
	chat c = {P, lz_stub_alloc(&p), {0}, {{0}}, {0}, {{0}}, {0}};
	LZ_REQUIRE(c.s, "lz_stub_alloc(%d ranks): %s", P, lz_error_message());
	int st = lz_stub_run(c.s, chat_work, &c);
	LZ_REQUIRE(st == LZ_OK, "%d ranks, policy %d: the run failed: %s", P, policy,
	      lz_error_message());
	for (int r = 0; r < P; r++) {
		lz_msg_counts k = lz_msg_counters(lz_stub_rank(c.s, r));
		LZ_REQUIRE(k.sent == (uint64_t)SENDS * (P - 1) && k.received == k.sent &&
		      k.reductions == 2, "rank %d of %d: sent %llu, received %llu, %llu reductions; "
		      "expected %d, %d and 2", r, P, (unsigned long long)k.sent,
		      (unsigned long long)k.received, (unsigned long long)k.reductions, SENDS * (P - 1),
		      SENDS * (P - 1));
		double want[2] = {P * (P + 1) / 2.0, 10.0 * P - P * (P - 1) / 2.0};
		LZ_REQUIRE(c.sum[r][0] == want[0] && c.sum[r][1] == want[1], "rank %d of %d: the sums "
		      "are %g and %g, the reduction says %g and %g", r, P, want[0], want[1], c.sum[r][0],
		      c.sum[r][1]);
		LZ_REQUIRE(c.min[r] == -3.5, "rank %d: the minimum is -3.5 (the last rank's), the "
		      "reduction says %g", r, c.min[r]);
	}
	double t = lz_stub_time(c.s);
	lz_stub_free(c.s);
	return t;
}

LZ_TEST(stub_delivers_once_in_order_and_reduces)
{
	for (int P = 2; P <= 7; P += 5)
		for (int policy = LZ_STUB_ROUND_ROBIN; policy <= LZ_STUB_VIRTUAL; policy++)
			run_chat(P, (lz_stub_policy)policy, 11, 4);
	/* a seed repeats its interleaving (the clock counts the turns), another does not */
	double a = run_chat(5, LZ_STUB_RANDOM, 3, 6), b = run_chat(5, LZ_STUB_RANDOM, 3, 6);
	double c = run_chat(5, LZ_STUB_RANDOM, 4, 6);
	ck_assert_msg(a == b, "the same seed gave %g and %g turns", a, b);
	ck_assert_msg(a != c, "seeds 3 and 4 gave the same %g turns: the seed does not reach the "
	              "interleaving", a);
	/* virtual time: the latency is the floor of a message's trip */
	double v = run_chat(2, LZ_STUB_VIRTUAL, 1, 0);
	ck_assert_msg(v >= 2e-5 && v < 1, "virtual time of the chat: %g s, at least one latency", v);
}
END_TEST

/* A rank that waits for a message nobody sends. */
static int lonely(int rank, void *arg, lz_work *state)
{
	(void)arg;
	*state = rank == 0 ? LZ_WORK_DONE : LZ_WORK_WAIT;
	return LZ_OK;
}

LZ_TEST(stub_reports_a_deadlock_and_bad_input)
{
	for (int policy = LZ_STUB_ROUND_ROBIN; policy <= LZ_STUB_VIRTUAL; policy++) {
		lz_stub_params p = {3, (lz_stub_policy)policy, 1, 2, 0, 3, 1e-6, 1e-6, 1e-6};
		lz_stub *s = lz_stub_alloc(&p);
		ck_assert_ptr_nonnull(s);
		int st = lz_stub_run(s, lonely, NULL);
		ck_assert_msg(st == LZ_EDOM && strstr(lz_error_message(), "deadlock"), "two ranks wait "
		              "for ever under policy %d: the stub must say deadlock (code %d: %s)", policy,
		              st, lz_error_message());
		lz_stub_free(s);
	}
	lz_stub_params bad[] = {
		{0, LZ_STUB_ROUND_ROBIN, 1, 0, 0, 1, 0, 0, 0},
		{LZ_STUB_RANKS_MAX + 1, LZ_STUB_ROUND_ROBIN, 1, 0, 0, 1, 0, 0, 0},
		{2, 9, 1, 0, 0, 1, 0, 0, 0},
		{2, LZ_STUB_ROUND_ROBIN, 1, -1, 0, 1, 0, 0, 0},
		{2, LZ_STUB_AHEAD, 1, 0, 5, 1, 0, 0, 0},
		{2, LZ_STUB_VIRTUAL, 1, 0, 0, 1, -1, 0, 0},
	};
	for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
		ck_assert_msg(lz_stub_alloc(&bad[k]) == NULL && lz_test_last_error() == LZ_EINVAL,
		              "bad stub parameters %zu must be refused with LZ_EINVAL", k);
	lz_stub_params p = {2, LZ_STUB_ROUND_ROBIN, 1, 0, 0, 1, 0, 0, 0};
	lz_stub *s = lz_stub_alloc(&p);
	lz_msg *m = lz_stub_rank(s, 0);
	char big[LZ_MSG_MAX + 1] = {0};
	ck_assert_int_eq(lz_msg_send(m, 0, big, 1), LZ_EINVAL);             /* to itself */
	ck_assert_int_eq(lz_msg_send(m, 2, big, 1), LZ_EINVAL);             /* no such rank */
	ck_assert_int_eq(lz_msg_send(m, 1, big, LZ_MSG_MAX + 1), LZ_EINVAL); /* too big */
	ck_assert_int_eq(lz_msg_send(m, 1, big, 64), LZ_OK);
	int from;
	size_t n;
	ck_assert_int_eq(lz_msg_poll(lz_stub_rank(s, 1), &from, big, 8, &n), LZ_EINVAL);
	ck_assert_int_eq(lz_msg_poll(lz_stub_rank(s, 1), &from, big, 64, &n), 1);
	double in[LZ_MSG_RMAX + 1] = {0};
	ck_assert_int_eq(lz_msg_reduce_start(m, LZ_MSG_SUM, in, LZ_MSG_RMAX + 1), LZ_EINVAL);
	ck_assert_int_eq(lz_msg_reduce_start(m, LZ_MSG_SUM, in, 1), LZ_OK);
	ck_assert_int_eq(lz_msg_reduce_start(m, LZ_MSG_SUM, in, 1), LZ_EINVAL);  /* one at a time */
	lz_stub_free(s);
}
END_TEST

/* ---- the engine's own checks ---- */

static lz_edmd *gas(int dim, size_t n, double eta, unsigned long seed)
{
	lz_edmd_params p = {dim, n, eta, 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	lz_rng *rng = lz_rng_alloc("mt19937", seed);
	LZ_REQUIRE(e && rng && lz_edmd_place_lattice(e, rng) == LZ_OK, "a gas: %s",
	      lz_error_message());
	lz_rng_free(rng);
	e->rebase_auto = 0;
	return e;
}

LZ_TEST(pedmd_domains_are_a_curve_cut_evenly)
{
	for (int dim = 2; dim <= 3; dim++) {
		lz_edmd *e = gas(dim, dim == 2 ? 900 : 2000, 0.3, 1);
		for (int kind = LZ_PEDMD_ROWS; kind <= LZ_PEDMD_MORTON; kind++)
			for (int P = 1; P <= 16; P += 5) {
				lz_pedmd_domains *d = lz_pedmd_domains_alloc(e, P, kind);
				ck_assert_ptr_nonnull(d);
				for (uint32_t c = 0; c < e->ncells; c++)
					LZ_REQUIRE(d->place[c] < e->ncells && d->curve[d->place[c]] == c, "%dD, curve %d: "
					      "cell %u is at place %u, where the curve has cell %u", dim, kind, c,
					      d->place[c], d->curve[d->place[c]]);
				LZ_REQUIRE(d->cut[0] == 0 && d->cut[P] == e->ncells, "cuts from %u to %u", d->cut[0],
				      d->cut[P]);
				for (int r = 0; r < P; r++) {
					uint32_t w = d->cut[r + 1] - d->cut[r];
					LZ_REQUIRE(w >= e->ncells / (size_t)P && w <= e->ncells / (size_t)P + 1, "%dD, %d "
					      "ranks: rank %d has %u of the %zu cells: even cuts", dim, P, r, w, e->ncells);
				}
				lz_pedmd_domains_free(d);
			}
		ck_assert_ptr_null(lz_pedmd_domains_alloc(e, 0, LZ_PEDMD_ROWS));
		ck_assert_ptr_null(lz_pedmd_domains_alloc(e, (int)e->ncells + 1, LZ_PEDMD_ROWS));
		ck_assert_ptr_null(lz_pedmd_domains_alloc(e, 2, 7));
		ck_assert_msg(strstr(lz_error_message(), "rows") != NULL, "a bad curve names the choices: %s",
		              lz_error_message());
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(pedmd_refuses_bad_parameters_and_audits)
{
	lz_edmd *s = gas(2, 400, 0.3, 2);
	lz_stub_params sp = {3, LZ_STUB_ROUND_ROBIN, 1, 2, 0, 1, 1e-6, 1e-6, 1e-6};
	lz_pedmd_params good = {0.05, 0.5, 0, 0.1, 1, 16, 0, 1.125, 0};
	lz_pedmd_params bad[] = {
		{0, 0.5, 0, 0.1, 1, 16, 0, 1.125, 0},    {INFINITY, 0.5, 0, 0.1, 1, 16, 0, 1.125, 0},
		{0.05, -1, 0, 0.1, 1, 16, 0, 1.125, 0},  {0.05, 0.5, -1, 0.1, 1, 16, 0, 1.125, 0},
		{0.05, 0.5, 0, 1, 1, 16, 0, 1.125, 0},   {0.05, 0.5, 0, 0.1, 1, 0, 0, 1.125, 0},
		{0.05, 0.5, 0, 0.1, 1, 16, 0, 1, 0},     {0.05, 0.5, 0, 0.1, 1, 16, 0, NAN, 0},
		{0.05, 0.5, 0, 0.1, 1, 16, 0, 1.125, 2},
	};
	const char *says[] = {"window", "window", "rebase", "balance", "threshold", "work", "grow",
	                      "grow", "compact"};
	for (int k = 0; k < 9; k++) {
		ck_assert_msg(lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &bad[k]) == NULL &&
		              lz_test_last_error() == LZ_EINVAL && strstr(lz_error_message(), says[k]),
		              "bad parameters %d must be refused naming %s: %s", k, says[k],
		              lz_error_message());
	}
	uint32_t cut[4] = {0, 5, 5, (uint32_t)s->ncells};
	ck_assert_msg(lz_pedmd_sim_alloc_cut(s, LZ_PEDMD_ROWS, cut, &sp, &good) == NULL &&
	              lz_test_last_error() == LZ_EINVAL, "cuts that leave a rank without cells");

	lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &good);
	ck_assert_ptr_nonnull(x);
	ck_assert_int_eq(lz_pedmd_audit(x->rank, x->P), LZ_OK);
	/* a ghost that differs from its owner's record, and a particle owned twice */
	uint32_t g = 0;
	int holder = -1;
	for (uint32_t i = 0; i < s->n && holder < 0; i++)
		for (int k = 0; k < x->P; k++)
			if (lz_pedmd_role(x->rank[k], i) == LZ_PEDMD_GHOST) {
				g = i;
				holder = k;
				break;
			}
	ck_assert_int_ge(holder, 0);
	x->rank[holder]->e->p[g].v[0] += 1e-15;
	ck_assert_msg(lz_pedmd_audit(x->rank, x->P) == LZ_EDOM && strstr(lz_error_message(), "ghost"),
	              "a ghost off by 1e-15 in one velocity: %s", lz_error_message());
	x->rank[holder]->e->p[g].v[0] -= 1e-15;
	x->rank[holder]->role[g] = LZ_PEDMD_OWNED;
	ck_assert_msg(lz_pedmd_audit(x->rank, x->P) == LZ_EDOM, "a particle owned by two ranks");
	x->rank[holder]->role[g] = LZ_PEDMD_GHOST;
	lz_pedmd_sim_free(x);
	lz_edmd_free(s);
}
END_TEST

/* Ranks a and b (lz_pedmd_alloc and lz_pedmd_adopt of the same start, or twins of two
 * identical runs): the same roles, events, records, cell lists (in the same order:
 * predictions read them so) and heap. */
static void same_rank(const lz_pedmd *a, const lz_pedmd *b, int k)
{
	const lz_edmd *ea = a->e, *eb = b->e;
	for (uint32_t i = 0; i < ea->n; i++) {
		int present = a->role[i] != LZ_PEDMD_ABSENT;
		LZ_REQUIRE(a->role[i] == b->role[i] && a->heard[i] == b->heard[i] &&
		           memcmp(&a->own[i], &b->own[i], sizeof a->own[i]) == 0 &&
		           memcmp(&a->ghost[i], &b->ghost[i], sizeof a->ghost[i]) == 0 &&
		           (!present || memcmp(&ea->p[i], &eb->p[i], sizeof ea->p[i]) == 0),
		           "rank %d: particle %u: role %d / %d, own, ghost or record differ between "
		           "the two ranks", k, i, a->role[i], b->role[i]);
		int in = lz_heap_contains(ea->heap, i);
		LZ_REQUIRE(in == lz_heap_contains(eb->heap, i) &&
		           (!in || lz_heap_key(ea->heap, i) == lz_heap_key(eb->heap, i)),
		           "rank %d: particle %u in the heap %d / %d", k, i, in,
		           lz_heap_contains(eb->heap, i));
	}
	for (uint32_t c = 0; c < ea->ncells; c++) {
		int32_t x = ea->list[c].head, y = eb->list[c].head;
		for (; x >= 0 && x == y; x = ea->next[x], y = eb->next[y])
			;
		LZ_REQUIRE(x == y, "rank %d: cell %u lists %d where the other rank lists %d", k, c, x,
		           y);
	}
}

/* lz_pedmd_owned_part, 7 at a time (as lz-mpi gathers a picture), lists what
 * lz_pedmd_owned lists, in the same order. */
static void owned_in_parts(const lz_pedmd *r, int k)
{
	size_t n = lz_pedmd_owned(r, NULL), got = 0, m;
	lz_pedmd_message *all = malloc(n * sizeof *all), part[7];
	ck_assert_ptr_nonnull(all);
	LZ_REQUIRE_TRUE(lz_pedmd_owned(r, all) == n && n > 7);
	uint32_t from = 0;
	while ((m = lz_pedmd_owned_part(r, &from, part, 7)) > 0) {
		LZ_REQUIRE(got + m <= n && memcmp(part, all + got, m * sizeof *part) == 0,
		           "rank %d: the part from %zu differs from lz_pedmd_owned's", k, got);
		got += m;
	}
	LZ_REQUIRE(got == n && from == r->e->n, "rank %d: the parts hold %zu of %zu owned, and "
	           "stop at particle %u of %zu", k, got, n, from, r->e->n);
	free(all);
}

/* Rank a in local numbering, made from start s: a slot for each particle of its
 * cells and halo, with its record, and few others (their events' partners); its
 * frame b (lz_pedmd_release) holds its owned records at their numbers. */
static void check_share(const lz_pedmd *a, const lz_edmd *s, const lz_edmd *b, int k)
{
	size_t share = 0;
	for (uint32_t id = 0; id < s->n; id++) {
		int64_t i = lz_pedmd_slot(a, id);
		int here = a->cls[s->p[id].cell] != LZ_PEDMD_FAR;
		share += here;
		LZ_REQUIRE(!here || (i >= 0 && lz_pedmd_id(a, (uint32_t)i) == id &&
		           memcmp(&a->e->p[i], &s->p[id], sizeof s->p[id]) == 0),
		           "rank %d: particle %u of its cells or halo has no slot, or another "
		           "record", k, id);
		LZ_REQUIRE(here == (lz_pedmd_role(a, id) != LZ_PEDMD_ABSENT), "rank %d: particle "
		           "%u's role %d", k, id, lz_pedmd_role(a, id));
		LZ_REQUIRE(lz_pedmd_owner(a->d, s->p[id].cell) != k ||
		           memcmp(&b->p[id], &s->p[id], sizeof s->p[id]) == 0, "rank %d: owned "
		           "particle %u is not in the released frame at its number", k, id);
	}
	LZ_REQUIRE(share <= a->nslots && a->nslots < 2 * share && a->nslots < s->n,
	           "rank %d: %zu slots for a share of %zu of %zu particles", k, a->nslots,
	           share, s->n);
	LZ_REQUIRE(lz_pedmd_slot(a, (uint32_t)s->n) < 0, "rank %d: a number beyond N has a slot", k);
}

LZ_TEST(pedmd_adopt_takes_the_system_as_alloc_copies_it)
{
	/* lz-mpi's ranks take the start itself (one system a process): each must be the
	 * rank lz_pedmd_alloc makes from a copy, the cell lists in the same order; with a
	 * slot for every particle the start becomes the rank's system, in local numbering
	 * the rank keeps its share and frees the start */
	lz_stub_params sp = {3, LZ_STUB_ROUND_ROBIN, 1, 2, 0, 1, 1e-6, 1e-6, 1e-6};
	lz_pedmd_params pp = {0.05, 0.5, 0, 0.1, 1, 16, 0, 1.125, 0};
	lz_edmd *s = gas(3, 2000, 0.3, 5);
	lz_stub *stub = lz_stub_alloc(&sp);
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(s, 3, LZ_PEDMD_MORTON);
	LZ_REQUIRE_TRUE(stub && d && lz_edmd_run(s, 3000, INFINITY) == LZ_OK);
	for (pp.compact = 0; pp.compact <= 1; pp.compact++)
		for (int k = 0; k < 3; k++) {
			lz_edmd *t = gas(3, 2000, 0.3, 5);
			LZ_REQUIRE_TRUE(lz_edmd_run(t, 3000, INFINITY) == LZ_OK);
			lz_pedmd *a = lz_pedmd_alloc(s, d, lz_stub_rank(stub, k), &pp);
			lz_pedmd *b = lz_pedmd_adopt(t, d, lz_stub_rank(stub, k), &pp);
			LZ_REQUIRE(a && b, "rank %d: %s", k, lz_error_message());
			LZ_REQUIRE(pp.compact || lz_pedmd_system(b) == t, "rank %d: lz_pedmd_adopt made a "
			           "copy", k);
			same_rank(a, b, k);
			owned_in_parts(a, k);
			lz_edmd *back = lz_pedmd_release(b);
			LZ_REQUIRE(pp.compact || back == t, "rank %d: lz_pedmd_release gave back another "
			           "system", k);
			LZ_REQUIRE(back && back->n == s->n, "rank %d: the released frame", k);
			if (pp.compact)
				check_share(a, s, back, k);
			lz_pedmd_free(a);
			lz_edmd_free(back);
		}
	pp.compact = 0;
	/* a system with lists cannot be a rank's: refused, and freed */
	lz_edmd_params q = {3, 500, 0.3, 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_LIST, 0, 0};
	lz_edmd *l = lz_edmd_alloc(&q);
	ck_assert_ptr_nonnull(l);
	l->rebase_auto = 0;
	lz_pedmd_domains *dl = lz_pedmd_domains_alloc(l, 3, LZ_PEDMD_MORTON);
	ck_assert_ptr_nonnull(dl);
	ck_assert_msg(lz_pedmd_adopt(l, dl, lz_stub_rank(stub, 0), &pp) == NULL &&
	              lz_test_last_error() == LZ_EINVAL && strstr(lz_error_message(), "cells"),
	              "a system with lists adopted: %s", lz_error_message());
	lz_pedmd_domains_free(dl);
	lz_pedmd_domains_free(d);
	lz_stub_free(stub);
	lz_edmd_free(s);
}
END_TEST

/* n disks in a box of packing 0.15, all in its bottom third (x < L/3, on a square
 * lattice of spacing 1.2) with Maxwell velocities, gravity 1 along -x: the events
 * happen where the disks are. */
static lz_edmd *sediment(size_t n)
{
	lz_edmd_params p = {2, n, 0.15, 1, 1.0, LZ_EDMD_WALLS_BOX, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	double *r = calloc(3 * n, sizeof *r), *v = calloc(3 * n, sizeof *v);
	lz_rng *rng = lz_rng_alloc("mt19937", 5);
	LZ_REQUIRE(e && r && v && rng, "out of memory");
	int rows = (int)((e->L - 1) / 1.2);
	for (size_t i = 0; i < n; i++) {
		r[3 * i] = 0.6 + 1.2 * (double)(i / (size_t)rows);
		r[3 * i + 1] = 0.6 + 1.2 * (double)(i % (size_t)rows);
	}
	LZ_REQUIRE(r[3 * (n - 1)] < e->L / 3, "the sediment does not fit the bottom third");
	lz_edmd_maxwell(e, rng, v);
	LZ_REQUIRE(lz_edmd_set(e, r, v) == LZ_OK, "the sediment: %s", lz_error_message());
	e->rebase_auto = 0;
	free(r);
	free(v);
	lz_rng_free(rng);
	return e;
}

/* Runs a (a slot for every particle) and b (local numbering) of one start on the same
 * stub: the same run, operation by operation — every counter, every message, every
 * record at the end (gathered into pa and pb) —, and b's ranks hold fewer slots than
 * the N particles. */
static void same_run(lz_pedmd_sim *a, lz_pedmd_sim *b, lz_edmd *pa, lz_edmd *pb,
                     double t_stop, const char *what)
{
	ck_assert_msg(lz_pedmd_sim_run(a, t_stop) == LZ_OK, "%s, a slot a particle: %s", what,
	              lz_error_message());
	ck_assert_msg(lz_pedmd_sim_run(b, t_stop) == LZ_OK, "%s, local numbering: %s", what,
	              lz_error_message());
	lz_pedmd_counts ca = lz_pedmd_sim_counts(a), cb = lz_pedmd_sim_counts(b);
	LZ_REQUIRE(memcmp(&ca, &cb, sizeof ca) == 0, "%s: the counters differ with local "
	           "numbering (%llu / %llu processed, %llu / %llu rollbacks)", what,
	           (unsigned long long)ca.processed, (unsigned long long)cb.processed,
	           (unsigned long long)ca.rollbacks, (unsigned long long)cb.rollbacks);
	for (int k = 0; k < a->P; k++) {
		lz_msg_counts ma = lz_msg_counters(lz_stub_rank(a->stub, k)),
		              mb = lz_msg_counters(lz_stub_rank(b->stub, k));
		LZ_REQUIRE(ma.sent == mb.sent && ma.received == mb.received, "%s: rank %d sent %llu "
		           "messages, %llu with local numbering", what, k, (unsigned long long)ma.sent,
		           (unsigned long long)mb.sent);
		LZ_REQUIRE(b->rank[k]->nslots < pa->n, "%s: rank %d holds %zu slots for %zu "
		           "particles", what, k, b->rank[k]->nslots, pa->n);
	}
	lz_pedmd_sim_gather(a, pa);
	lz_pedmd_sim_gather(b, pb);
	for (uint32_t i = 0; i < pa->n; i++)
		LZ_REQUIRE(memcmp(&pa->p[i], &pb->p[i], sizeof pa->p[i]) == 0, "%s: particle %u ends "
		           "elsewhere with local numbering", what, i);
}

LZ_TEST(pedmd_local_numbering_is_the_same_run)
{
	/* a rank that holds only what it has heard of, in slots of its own, runs what a
	 * rank with a slot for every particle runs: 2D and 3D, slabs and Morton, P = 2 to
	 * 8, every schedule, walls with gravity and loss, moving cuts and the rollback
	 * check; and both are the serial run */
	struct {
		int dim;
		size_t n;
		int P, kind, balance, recheck;
		lz_stub_policy policy;
	} runs[] = {
		{2, 900, 2, LZ_PEDMD_ROWS, 0, 0, LZ_STUB_ROUND_ROBIN},
		{2, 900, 3, LZ_PEDMD_MORTON, 0, 0, LZ_STUB_RANDOM},
		{2, 900, 4, LZ_PEDMD_ROWS, 0, 1, LZ_STUB_AHEAD},
		{3, 1500, 8, LZ_PEDMD_MORTON, 0, 0, LZ_STUB_VIRTUAL},
		{3, 1500, 4, LZ_PEDMD_ROWS, 0, 0, LZ_STUB_RANDOM},
		{0, 800, 4, LZ_PEDMD_MORTON, 3, 0, LZ_STUB_VIRTUAL},  /* 0: the sediment */
		{0, 800, 3, LZ_PEDMD_ROWS, 2, 0, LZ_STUB_RANDOM},
	};
	for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
		char what[120];
		snprintf(what, sizeof what, "%s, N = %zu, P = %d, %s, policy %d%s%s",
		         runs[k].dim ? (runs[k].dim == 3 ? "3D gas" : "2D gas") : "sediment",
		         runs[k].n, runs[k].P, runs[k].kind == LZ_PEDMD_ROWS ? "rows" : "Morton",
		         runs[k].policy, runs[k].balance ? ", moving cuts" : "",
		         runs[k].recheck ? ", rechecked" : "");
		lz_edmd *e[4];
		for (int q = 0; q < 4; q++)
			e[q] = runs[k].dim ? gas(runs[k].dim, runs[k].n, 0.35, 13) : sediment(runs[k].n);
		lz_stub_params sp = {runs[k].P, runs[k].policy, 21, 3, 0, 4, 1e-6, 2e-6, 5e-6};
		lz_pedmd_params pp = {0.05, 0.5, runs[k].balance, 0.02, 0, 16, runs[k].recheck, 1.125, 0};
		lz_pedmd_sim *a = lz_pedmd_sim_alloc(e[0], runs[k].kind, &sp, &pp);
		pp.compact = 1;
		lz_pedmd_sim *b = lz_pedmd_sim_alloc(e[1], runs[k].kind, &sp, &pp);
		LZ_REQUIRE(a && b, "%s: %s", what, lz_error_message());
		a->audit = b->audit = 1;  /* holding the ranks at a cut changes the schedule: both */
		double t = runs[k].dim ? 0.6 : 2.0;
		same_run(a, b, e[0], e[1], t, what);
		ck_assert_int_eq(lz_pedmd_serial(e[2], t, 0.5), LZ_OK);
		for (uint32_t i = 0; i < e[2]->n; i++)
			LZ_REQUIRE(memcmp(&e[1]->p[i], &e[2]->p[i], sizeof e[2]->p[i]) == 0, "%s: particle "
			           "%u ends elsewhere than serially", what, i);
		LZ_REQUIRE(!runs[k].balance || lz_pedmd_sim_counts(b).balances > 0, "%s: the cuts never "
		           "moved", what);
		lz_pedmd_sim_free(a);
		lz_pedmd_sim_free(b);
		for (int q = 0; q < 4; q++)
			lz_edmd_free(e[q]);
	}
}
END_TEST

LZ_TEST(pedmd_opened_ranks_take_the_start_in_parts)
{
	/* what lz-mpi's ranks do at the start: each opens empty with the start's box and
	 * clock only, takes from the start's particles, sent 64 at a time, those of its
	 * cells and halo, and the run is the serial run, bit for bit; the set-up is not a
	 * move of the cuts, and a rank with a slot for every particle cannot open empty */
	for (int kind = LZ_PEDMD_ROWS; kind <= LZ_PEDMD_MORTON; kind++) {
		lz_edmd *s = kind ? sediment(800) : gas(2, 900, 0.35, 17);
		lz_edmd *ref = kind ? sediment(800) : gas(2, 900, 0.35, 17);
		lz_stub_params sp = {4, LZ_STUB_RANDOM, 5, 3, 0, 4, 1e-6, 2e-6, 5e-6};
		lz_pedmd_params pp = {0.05, 0.5, 0, 0.05, 0, 16, 0, 1.125, 1};
		lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, kind, &sp, &pp);
		LZ_REQUIRE_TRUE(x != NULL);
		x->audit = 1;
		lz_edmd shape = *s;  /* what rank 0 broadcasts: scalars, no arrays */
		shape.p = NULL;
		shape.ev = NULL;
		shape.next = NULL;
		shape.list = NULL;
		shape.heap = NULL;
		lz_pedmd_message part[64];
		for (int k = 0; k < 4; k++) {
			lz_pedmd_free(x->rank[k]);
			x->rank[k] = lz_pedmd_open(&shape, x->d, lz_stub_rank(x->stub, k), &pp);
			LZ_REQUIRE(x->rank[k] && lz_pedmd_take_begin(x->rank[k]) == LZ_OK, "rank %d: %s",
			           k, lz_error_message());
			size_t m;
			uint32_t from = 0;
			while ((m = lz_pedmd_start_part(s, &from, part, 64)) > 0)
				LZ_REQUIRE(lz_pedmd_take_part(x->rank[k], part, m) == LZ_OK, "rank %d: %s", k,
				           lz_error_message());
			ck_assert_int_eq(lz_pedmd_take_end(x->rank[k]), LZ_OK);
			LZ_REQUIRE(x->rank[k]->nslots < s->n && lz_pedmd_counters(x->rank[k]).balances == 0,
			           "rank %d: %zu slots of %zu, %llu balances", k, x->rank[k]->nslots, s->n,
			           (unsigned long long)lz_pedmd_counters(x->rank[k]).balances);
		}
		ck_assert_msg(lz_pedmd_audit(x->rank, 4) == LZ_OK, "opened: %s", lz_error_message());
		double t = kind ? 2.0 : 0.6;
		ck_assert_msg(lz_pedmd_sim_run(x, t) == LZ_OK, "the run: %s", lz_error_message());
		ck_assert_int_eq(lz_pedmd_serial(ref, t, 0.5), LZ_OK);
		ck_assert_uint_eq(lz_pedmd_sim_counts(x).committed, ref->events);
		lz_pedmd_sim_gather(x, s);
		for (uint32_t i = 0; i < s->n; i++)
			LZ_REQUIRE(memcmp(&s->p[i], &ref->p[i], sizeof ref->p[i]) == 0, "particle %u ends "
			           "elsewhere than serially after an opened start", i);
		pp.compact = 0;
		ck_assert_msg(lz_pedmd_open(&shape, x->d, lz_stub_rank(x->stub, 0), &pp) == NULL &&
		              strstr(lz_error_message(), "compact"), "an opened rank with a slot for "
		              "every particle: %s", lz_error_message());
		lz_pedmd_sim_free(x);
		lz_edmd_free(s);
		lz_edmd_free(ref);
	}
}
END_TEST

LZ_TEST(pedmd_cuts_from_a_pilot_run_spread_the_work)
{
	lz_edmd *s = sediment(800), *t = sediment(800);
	lz_stub_params sp = {4, LZ_STUB_VIRTUAL, 1, 0, 0, 1, 1e-6, 2e-6, 5e-6};
	lz_pedmd_params pp = {0.05, 0.5, 0, 0.1, 1, 16, 0, 1.125, 0};
	lz_pedmd_sim *pilot = lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &pp);
	ck_assert_ptr_nonnull(pilot);
	ck_assert_int_eq(lz_pedmd_sim_run(pilot, 1.0), LZ_OK);
	double *load = malloc(s->ncells * sizeof *load);
	ck_assert_ptr_nonnull(load);
	lz_pedmd_sim_load(pilot, load);
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1];
	int moved = lz_pedmd_rebalance(pilot->d, load, 0.1, cut);
	double before = 0, after = 0;
	for (int r = 0; r < 4; r++) {
		double a = 0, b = 0;
		for (uint32_t k = pilot->d->cut[r]; k < pilot->d->cut[r + 1]; k++)
			a += load[pilot->d->curve[k]];
		for (uint32_t k = cut[r]; k < cut[r + 1]; k++)
			b += load[pilot->d->curve[k]];
		before = fmax(before, a);
		after = fmax(after, b);
	}
	ck_assert_msg(moved && after < 0.8 * before, "a sediment: the even cuts give the busiest "
	              "rank %g events, the balanced ones %g: expected a real gain", before, after);

	/* both runs from the same start: the same committed events (whether the balanced one
	 * is faster depends on its borders too: lesson 06 measures it) */
	lz_pedmd_sim *even = lz_pedmd_sim_alloc(t, LZ_PEDMD_MORTON, &sp, &pp);
	lz_pedmd_sim *fair = lz_pedmd_sim_alloc_cut(t, LZ_PEDMD_MORTON, cut, &sp, &pp);
	ck_assert(even && fair);
	ck_assert_int_eq(lz_pedmd_sim_run(even, 2.0), LZ_OK);
	ck_assert_int_eq(lz_pedmd_sim_run(fair, 2.0), LZ_OK);
	lz_pedmd_counts a = lz_pedmd_sim_counts(even), b = lz_pedmd_sim_counts(fair);
	ck_assert_msg(a.committed == b.committed && a.collisions == b.collisions, "balanced cuts "
	              "changed the physics: %llu against %llu committed events",
	              (unsigned long long)a.committed, (unsigned long long)b.committed);
	lz_edmd *ga = sediment(800), *gb = sediment(800);
	lz_pedmd_sim_gather(even, ga);
	lz_pedmd_sim_gather(fair, gb);
	for (uint32_t i = 0; i < s->n; i++)
		LZ_REQUIRE(memcmp(ga->p[i].r, gb->p[i].r, sizeof ga->p[i].r) == 0, "particle %u ends "
		      "elsewhere with balanced cuts", i);
	free(load);
	lz_edmd_free(ga);
	lz_edmd_free(gb);
	lz_pedmd_sim_free(even);
	lz_pedmd_sim_free(fair);
	lz_pedmd_sim_free(pilot);
	lz_edmd_free(s);
	lz_edmd_free(t);
}
END_TEST

LZ_TEST(pedmd_cuts_move_during_a_run)
{
	/* a sediment whose load moves as it falls and spreads: the cuts move every 4
	 * windows when that pays, and the run stays the serial run, bit for bit */
	lz_edmd *s = sediment(800), *ref = sediment(800), *pic = sediment(800);
	lz_stub_params sp = {4, LZ_STUB_VIRTUAL, 1, 0, 0, 1, 1e-6, 2e-6, 5e-6};
	lz_pedmd_params pp = {0.05, 0.5, 4, 0.05, 0, 16, 0, 1.125, 1};
	lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &pp);
	ck_assert_ptr_nonnull(x);
	x->audit = 1;
	uint32_t cut0[LZ_PEDMD_RANKS_MAX + 1];
	memcpy(cut0, x->d->cut, sizeof cut0);
	ck_assert_msg(lz_pedmd_sim_run(x, 3.0) == LZ_OK, "the run: %s", lz_error_message());
	ck_assert_int_eq(lz_pedmd_serial(ref, 3.0, 0.5), LZ_OK);
	lz_pedmd_counts c = lz_pedmd_sim_counts(x);
	ck_assert_msg(c.balances > 0 && memcmp(cut0, x->d->cut, 5 * sizeof *cut0) != 0, "the cuts "
	              "never moved (%llu balances)", (unsigned long long)c.balances);
	ck_assert_msg(c.committed == ref->events && c.collisions == ref->collisions,
	              "moving cuts changed the physics: %llu committed events, %llu serially",
	              (unsigned long long)c.committed, (unsigned long long)ref->events);
	lz_pedmd_sim_gather(x, pic);
	for (uint32_t i = 0; i < s->n; i++)
		LZ_REQUIRE(memcmp(&pic->p[i], &ref->p[i], sizeof ref->p[i]) == 0, "particle %u's record "
		      "differs from the serial run's after %llu moves of the cuts", i,
		      (unsigned long long)c.balances);
	ck_assert_msg(x->audits > 2, "only %llu cuts audited", (unsigned long long)x->audits);
	lz_pedmd_sim_free(x);
	lz_edmd_free(s);
	lz_edmd_free(ref);
	lz_edmd_free(pic);
}
END_TEST

LZ_TEST(pedmd_take_hands_over_the_picture_and_refuses_a_broken_one)
{
	/* what lz-mpi does at a cut, one rank at a time: the owned particles of all ranks
	 * are every particle once; each rank takes its share under new cuts, and the run
	 * goes on as the serial run. A picture that misses a particle or holds one twice,
	 * or a rank in the middle of a window, is refused with a message, and the rank
	 * taking it in place is left as its twin in a second, identical run (y) */
	lz_edmd *s = gas(2, 600, 0.35, 5), *ref = gas(2, 600, 0.35, 5), *t = gas(2, 600, 0.35, 5);
	lz_stub_params sp = {3, LZ_STUB_ROUND_ROBIN, 2, 2, 0, 4, 1e-6, 2e-6, 5e-6};
	lz_pedmd_params pp = {0.05, 0.5, 0, 0.1, 0, 16, 0, 1.125, 0};
	lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, LZ_PEDMD_ROWS, &sp, &pp);
	lz_pedmd_sim *y = lz_pedmd_sim_alloc(t, LZ_PEDMD_ROWS, &sp, &pp);
	LZ_REQUIRE_TRUE(x && y);
	ck_assert_int_eq(lz_pedmd_sim_run(x, 0.4), LZ_OK);
	ck_assert_int_eq(lz_pedmd_sim_run(y, 0.4), LZ_OK);
	for (int k = 0; k < 3; k++)  /* a run that ended at 0.4 waits at a cut there */
		x->rank[k]->phase = y->rank[k]->phase = LZ_PEDMD_BEGIN;
	lz_pedmd_message *all = malloc(s->n * sizeof *all);
	size_t n = 0;
	for (int k = 0; k < 3; k++)
		n += lz_pedmd_owned(x->rank[k], all + n);
	ck_assert_msg(n == s->n, "the ranks own %zu of the %zu particles", n, s->n);
	/* broken pictures: one short, one particle twice */
	ck_assert_int_eq(lz_pedmd_take(x->rank[0], all, n - 1), LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "picture") != NULL, "says: %s", lz_error_message());
	lz_pedmd_message keep = all[1];
	all[1] = all[0];
	ck_assert_int_eq(lz_pedmd_take(x->rank[0], all, n), LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "twice") != NULL, "says: %s", lz_error_message());
	same_rank(x->rank[0], y->rank[0], 0);  /* refused without a trace */
	all[1] = keep;
	/* new cuts: the middle rank takes a third of the cells more */
	x->d->cut[1] = (uint32_t)(x->d->ncells / 6);
	for (int k = 0; k < 3; k++) {
		ck_assert_msg(lz_pedmd_take(x->rank[k], all, n) == LZ_OK, "rank %d: %s", k,
		              lz_error_message());
		const lz_edmd *e = x->rank[k]->e;  /* each cell's list by number, as documented */
		for (uint32_t c = 0; c < e->ncells; c++)
			for (int32_t i = e->list[c].head; i >= 0 && e->next[i] >= 0; i = e->next[i])
				LZ_REQUIRE(i < e->next[i], "rank %d: cell %u lists particle %d before %d, "
				           "not by number", k, c, i, e->next[i]);
	}
	ck_assert_msg(lz_pedmd_audit(x->rank, 3) == LZ_OK, "after the hand-over: %s",
	              lz_error_message());
	ck_assert_int_eq(lz_pedmd_sim_run(x, 1.0), LZ_OK);
	ck_assert_int_eq(lz_pedmd_serial(ref, 0.4, 0.5), LZ_OK);  /* stopped there too */
	ck_assert_int_eq(lz_pedmd_serial(ref, 1.0, 0.5), LZ_OK);
	lz_pedmd_sim_gather(x, s);
	for (uint32_t i = 0; i < s->n; i++)
		LZ_REQUIRE(memcmp(&s->p[i], &ref->p[i], sizeof ref->p[i]) == 0, "particle %u differs "
		      "from the serial run after the hand-over", i);
	/* a rank in the middle of a window cannot take a picture */
	x->rank[1]->phase = LZ_PEDMD_RUN;
	ck_assert_int_eq(lz_pedmd_take(x->rank[1], all, n), LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "only at a cut") != NULL, "says: %s",
	              lz_error_message());
	x->rank[1]->phase = LZ_PEDMD_DONE;
	free(all);
	lz_pedmd_sim_free(x);
	lz_pedmd_sim_free(y);
	lz_edmd_free(s);
	lz_edmd_free(ref);
	lz_edmd_free(t);
}
END_TEST

LZ_TEST(pedmd_take_in_shares_hands_over_what_each_rank_holds)
{
	/* what lz-mpi does when the cuts move: each rank sends the particles it owned to
	 * the ranks that hold their cells under the new cuts (owner and halo), a few at a
	 * time, and never sees the whole picture. A falling sediment (curved paths) on
	 * three ranks: every record a rank does not hold then has an unknown count, the
	 * invariants hold, a particle sent twice is refused, and the run goes on as the
	 * serial run, bit for bit */
	lz_edmd *s = sediment(800), *ref = sediment(800);
	lz_stub_params sp = {3, LZ_STUB_VIRTUAL, 1, 0, 0, 1, 1e-6, 2e-6, 5e-6};
	lz_pedmd_params pp = {0.05, 0.5, 0, 0.05, 0, 16, 0, 1.125, 1};
	lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &pp);
	ck_assert_ptr_nonnull(x);
	ck_assert_int_eq(lz_pedmd_sim_run(x, 1.0), LZ_OK);
	for (int k = 0; k < 3; k++)  /* a run that ended at 1.0 waits at a cut there */
		x->rank[k]->phase = LZ_PEDMD_BEGIN;
	x->d->cut[1] = (uint32_t)(x->d->ncells / 2);  /* the floor's cells: rank 0 had a third */
	x->d->cut[2] = (uint32_t)(x->d->ncells * 3 / 4);
	for (int k = 0; k < 3; k++)
		ck_assert_int_eq(lz_pedmd_take_begin(x->rank[k]), LZ_OK);
	lz_pedmd_message part[7];
	int to[27];
	for (int k = 0; k < 3; k++) {
		size_t from = 0, n;
		while ((n = lz_pedmd_take_share(x->rank[k], &from, part, 7)) > 0)
			for (size_t m = 0; m < n; m++) {
				to[0] = lz_pedmd_owner(x->d, part[m].p.cell);
				int h = 1 + lz_pedmd_listeners(s, x->d, to[0], part[m].p.cell, to + 1);
				while (h-- > 0)
					LZ_REQUIRE(lz_pedmd_take_part(x->rank[to[h]], &part[m], 1) == LZ_OK,
					           "rank %d: %s", to[h], lz_error_message());
			}
	}
	to[0] = lz_pedmd_owner(x->d, part[0].p.cell);  /* the last one sent, again */
	ck_assert_int_eq(lz_pedmd_take_part(x->rank[to[0]], &part[0], 1), LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "twice") != NULL, "says: %s", lz_error_message());
	for (int k = 0; k < 3; k++) {
		ck_assert_int_eq(lz_pedmd_take_end(x->rank[k]), LZ_OK);
		const lz_edmd *e = x->rank[k]->e;
		for (uint32_t i = 0; i < e->n; i++)
			LZ_REQUIRE(x->rank[k]->role[i] != LZ_PEDMD_ABSENT ||
			           e->p[i].count == LZ_PEDMD_UNKNOWN, "rank %d keeps particle %u's old "
			           "record (count %u): an event aimed at it could pass for a live one",
			           k, i, e->p[i].count);
		const lz_pedmd *r = x->rank[k];  /* each held cell's list by number, not by slot */
		for (uint32_t c = 0; c < e->ncells; c++)
			for (int32_t i = r->cls[c] == LZ_PEDMD_FAR ? -1 : e->list[c].head;
			     i >= 0 && e->next[i] >= 0; i = e->next[i])
				LZ_REQUIRE(lz_pedmd_id(r, (uint32_t)i) < lz_pedmd_id(r, (uint32_t)e->next[i]),
				           "rank %d: cell %u lists particle %u before %u, not by number", k, c,
				           lz_pedmd_id(r, (uint32_t)i), lz_pedmd_id(r, (uint32_t)e->next[i]));
	}
	ck_assert_msg(lz_pedmd_audit(x->rank, 3) == LZ_OK, "after the hand-over: %s",
	              lz_error_message());
	ck_assert_msg(lz_pedmd_sim_run(x, 3.0) == LZ_OK, "the run: %s", lz_error_message());
	ck_assert_int_eq(lz_pedmd_serial(ref, 1.0, 0.5), LZ_OK);  /* stopped there too */
	ck_assert_int_eq(lz_pedmd_serial(ref, 3.0, 0.5), LZ_OK);
	lz_pedmd_counts c = lz_pedmd_sim_counts(x);
	ck_assert_msg(c.committed == ref->events, "%llu events committed, %llu serially",
	              (unsigned long long)c.committed, (unsigned long long)ref->events);
	lz_pedmd_sim_gather(x, s);
	for (uint32_t i = 0; i < s->n; i++)
		LZ_REQUIRE(memcmp(&s->p[i], &ref->p[i], sizeof ref->p[i]) == 0, "particle %u differs "
		      "from the serial run after the hand-over in shares", i);
	lz_pedmd_sim_free(x);
	lz_edmd_free(s);
	lz_edmd_free(ref);
}
END_TEST

LZ_TEST(pedmd_rollback_check_reruns_every_window_alike)
{
	/* every window rolled back and run again, as the schedule then goes: the same end;
	 * and one rank alone never rolls back and commits all it processes */
	for (int policy = LZ_STUB_ROUND_ROBIN; policy <= LZ_STUB_VIRTUAL; policy++)
		for (int P = 1; P <= 4; P += 3) {
			lz_edmd *s = gas(2, 600, 0.35, 7), *ref = gas(2, 600, 0.35, 7);
			ck_assert_int_eq(lz_pedmd_serial(ref, 1.0, 0.5), LZ_OK);
			lz_stub_params sp = {P, (lz_stub_policy)policy, 9, 3, 0, 4, 1e-6, 2e-6, 5e-6};
			lz_pedmd_params pp = {0.05, 0.5, 0, 0.1, 0, 16, 1, 1.125, 1};
			lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &pp);
			ck_assert_ptr_nonnull(x);
			int st = lz_pedmd_sim_run(x, 1.0);
			ck_assert_msg(st == LZ_OK, "P = %d, policy %d: %s", P, policy, lz_error_message());
			lz_pedmd_counts c = lz_pedmd_sim_counts(x);
			ck_assert_msg(c.rechecks > 0 && c.committed == ref->events, "P = %d, policy %d: %llu "
			              "windows rechecked, %llu committed against %llu serial events", P,
			              policy, (unsigned long long)c.rechecks, (unsigned long long)c.committed,
			              (unsigned long long)ref->events);
			if (P == 1)
				ck_assert_msg(c.rollbacks == 0 && c.conservative == 0 &&
				              c.processed == 2 * c.committed, "one rank: %llu rollbacks, %llu "
				              "processed (twice, rechecked) for %llu committed",
				              (unsigned long long)c.rollbacks, (unsigned long long)c.processed,
				              (unsigned long long)c.committed);
			lz_pedmd_sim_gather(x, s);
			for (uint32_t i = 0; i < s->n; i++)
				LZ_REQUIRE(memcmp(&s->p[i].r, &ref->p[i].r, sizeof s->p[i].r) == 0, "P = %d, "
				      "policy %d, rechecked: particle %u ends elsewhere than serially", P, policy, i);
			lz_pedmd_sim_free(x);
			lz_edmd_free(s);
			lz_edmd_free(ref);
		}
}
END_TEST

LZ_TEST(pedmd_slow_growth_rolls_back_fewer_windows_and_keeps_the_serial_run)
{
	/* the window's growth after a commit sets how often a window is rolled back, near
	 * ln grow / (ln grow + ln 2): about one in seven at 1.125, one in 36 at 1.02; the
	 * committed run is the serial one either way */
	lz_edmd *ref = gas(2, 3000, 0.35, 11);
	ck_assert_int_eq(lz_pedmd_serial(ref, 2.0, 0.5), LZ_OK);
	double fraction[2];
	const double grow[2] = {1.125, 1.02};
	for (int k = 0; k < 2; k++) {
		lz_edmd *s = gas(2, 3000, 0.35, 11);
		lz_stub_params sp = {4, LZ_STUB_RANDOM, 3, 3, 0, 4, 1e-6, 2e-6, 5e-6};
		lz_pedmd_params pp = {0.05, 0.5, 0, 0.1, 0, 16, 0, grow[k], 0};
		lz_pedmd_sim *x = lz_pedmd_sim_alloc(s, LZ_PEDMD_MORTON, &sp, &pp);
		ck_assert_ptr_nonnull(x);
		ck_assert_msg(lz_pedmd_sim_run(x, 2.0) == LZ_OK, "grow %g: %s", grow[k],
		              lz_error_message());
		lz_pedmd_counts c = lz_pedmd_sim_counts(x);
		ck_assert_msg(c.committed == ref->events, "grow %g: %llu committed against %llu "
		              "serial events", grow[k], (unsigned long long)c.committed,
		              (unsigned long long)ref->events);
		fraction[k] = (double)c.rollbacks / (double)c.windows;
		lz_pedmd_sim_gather(x, s);
		for (uint32_t i = 0; i < s->n; i++)
			LZ_REQUIRE(memcmp(&s->p[i], &ref->p[i], sizeof s->p[i]) == 0, "grow %g: particle "
			      "%u ends elsewhere than serially", grow[k], i);
		lz_pedmd_sim_free(x);
		lz_edmd_free(s);
	}
	ck_assert_msg(fraction[1] < fraction[0] / 2, "windows rolled back: %.3f at grow 1.125, "
	              "%.3f at 1.02 (slower growth should roll back far fewer)", fraction[0],
	              fraction[1]);
	lz_edmd_free(ref);
}
END_TEST
