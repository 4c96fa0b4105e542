/* test_stage05_lists.c — the library's options of the event-driven engine (lz/edmd.h):
 * neighbour lists, the 4-ary heap and the calendar queue (lz/heap.h, lz/calendar.h).
 * The queues against a brute-force minimum under the operations of an event loop; the
 * engine with every option through the physics the graded suite asks of the cells —
 * exact two-particle times across the boundary, a ball bouncing under gravity between
 * walls in closed form, energy and momentum to round-off and no overlap in dense
 * fluids of disks and spheres with their invariants audited, the pressure of hard
 * spheres against the reference, the identity with the collision rate, a clock at
 * 10^12, the inelastic collapse reported — and the same trajectory as the cells for a
 * while, renumbering without changing it, and bad input refused with its range. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/calendar.h"
#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/heap.h"
#include "lz/rng.h"
#include "lztest.h"
#include "support.h"

/* ---- the queues ---- */

/* A queue under test: the 4-ary heap or the calendar, behind one pair of calls. */
typedef struct {
	lz_heap *h;
	lz_calendar *q;
} tested;

static void q_set(tested *x, uint32_t id, double t)
{
	if (x->q) {
		ck_assert_int_eq(lz_calendar_set(x->q, id, t), LZ_OK);
	} else if (lz_heap_contains(x->h, id)) {
		lz_heap4_update(x->h, id, t);
	} else {
		lz_heap4_push(x->h, id, t);
	}
}
static double q_top_t(const tested *x)
{
	return x->q ? lz_calendar_top_t(x->q) : lz_heap_top_t(x->h);
}
static int q_audit(const tested *x) { return x->q ? lz_calendar_audit(x->q) : lz_heap_audit(x->h); }

/* The earliest key of the brute-force copy, and how many hold it. */
static double brute_min(const double *key, size_t n, size_t *ties)
{
	double m = INFINITY;
	*ties = 0;
	for (size_t i = 0; i < n; i++)
		m = key[i] < m ? key[i] : m;
	for (size_t i = 0; i < n; i++)
		*ties += key[i] == m;
	return m;
}

/* The operations of an event loop on n items: the top gets a later key (its next
 * event), a random item of the first half one no earlier than the top (a partner
 * predicted again: the second half keeps its keys until they come due),
 * some keys +INFINITY (never), some far ahead (past the calendar's ring), some equal,
 * and now and then a jump over a long empty stretch; the top must always be the
 * brute-force minimum, and the structure audit clean. */
static void event_loop_order(tested *x, size_t n, unsigned long seed)
{
	gsl_rng *r = lz_test_rng(seed);
	double *key = malloc(n * sizeof *key), now = 0;
	for (uint32_t i = 0; i < n; i++) {
		key[i] = gsl_rng_uniform(r);
		q_set(x, i, key[i]);
	}
	for (int step = 0; step < 200000; step++) {
		size_t ties;
		double m = brute_min(key, n, &ties);
		LZ_REQUIRE(q_top_t(x) == m, "step %d: the queue's top is %.17g, the earliest key is "
		           "%.17g", step, q_top_t(x), m);
		uint32_t top = x->q ? lz_calendar_top(x->q) : lz_heap_top(x->h);
		LZ_REQUIRE(key[top] == m, "step %d: the top item %u has key %.17g, not the earliest "
		           "%.17g", step, top, key[top], m);
		if (isinf(m))
			break;
		now = m;
		double u = gsl_rng_uniform(r);
		double next = u < 0.01 ? INFINITY : u < 0.02 ? now + 50 : u < 0.03 ? now
		              : u < 0.04 ? now + 1e-3 * n : now + 2 * gsl_rng_uniform(r);
		key[top] = next;
		q_set(x, top, next);
		/* a partner from the first half only: the other half's far keys come due */
		uint32_t other = (uint32_t)gsl_rng_uniform_int(r, (n + 1) / 2);
		key[other] = now + 3 * gsl_rng_uniform(r);
		q_set(x, other, key[other]);
		if (step % 20000 == 0)
			LZ_REQUIRE(q_audit(x) == LZ_OK, "step %d: %s", step, lz_error_message());
	}
	free(key);
	gsl_rng_free(r);
}

LZ_TEST(queues_give_the_earliest_event_like_brute_force)
{
	for (int kind = 0; kind < 2; kind++)
		for (size_t n = 1; n <= 4000; n *= 15) {
			tested x = {NULL, NULL};
			if (kind == 0)
				x.h = lz_heap_alloc_arity(n, 4);
			else  /* a ring of about 4 time units: the keys 50 ahead wait in the overflow
			       * while the ring is never empty, until it turns to them */
				x.q = lz_calendar_alloc(n, 1.0 / (double)n);
			ck_assert(x.h || x.q);
			if (x.q)
				ck_assert_int_eq(lz_calendar_layout(x.q, 4.0 / x.q->days), LZ_OK);
			event_loop_order(&x, n, 40 + n);
			lz_heap_free(x.h);
			lz_calendar_free(x.q);
		}
}
END_TEST

/* n keys shifted (a re-based clock), laid out with other days, items renamed: the
 * same keys come out in the same order. */
static void shifted_keep_order(size_t n)
{
	lz_calendar *q = lz_calendar_alloc(n, 1e-3);
	gsl_rng *r = lz_test_rng(77);
	double *key = malloc(n * sizeof *key);
	uint32_t *to = malloc(n * sizeof *to);
	for (uint32_t i = 0; i < n; i++) {
		key[i] = 5 + 10 * gsl_rng_uniform(r);
		ck_assert_int_eq(lz_calendar_set(q, i, key[i]), LZ_OK);
		to[i] = (uint32_t)(n - 1 - i);
	}
	ck_assert_int_eq(lz_calendar_shift(q, 5), LZ_OK);
	ck_assert_msg(lz_calendar_audit(q) == LZ_OK, "after the shift: %s", lz_error_message());
	ck_assert_int_eq(lz_calendar_layout(q, 0.37), LZ_OK);
	ck_assert_int_eq(lz_calendar_renumber(q, to), LZ_OK);
	ck_assert_msg(lz_calendar_audit(q) == LZ_OK, "after layout and renumbering: %s",
	              lz_error_message());
	double last = -INFINITY;
	for (size_t k = 0; k < n; k++) {  /* take every item out in order: key +INFINITY */
		uint32_t id = lz_calendar_top(q);
		double t = lz_calendar_top_t(q);
		LZ_REQUIRE(t >= last && t == key[n - 1 - id] - 5, "item %zu out: %u at %.17g after "
		           "%.17g, its key was %.17g", k, id, t, last, key[n - 1 - id] - 5);
		last = t;
		ck_assert_int_eq(lz_calendar_set(q, id, INFINITY), LZ_OK);
	}
	ck_assert_msg(isinf(lz_calendar_top_t(q)) && lz_calendar_audit(q) == LZ_OK,
	              "every key at infinity: the top is %g (%s)", lz_calendar_top_t(q),
	              lz_error_message());
	free(key);
	free(to);
	gsl_rng_free(r);
	lz_calendar_free(q);
}

LZ_TEST(calendar_shift_layout_and_renumber_keep_the_order)
{
	shifted_keep_order(2000);
	shifted_keep_order(300000);  /* past 2^17 items: the most days, longer ones */
}
END_TEST

LZ_TEST(queues_refuse_bad_sizes)
{
	lz_test_clear_error();
	ck_assert_ptr_null(lz_heap_alloc_arity(10, 3));
	ck_assert_msg(strstr(lz_error_message(), "2 or 4"), "says: %s", lz_error_message());
	ck_assert_ptr_null(lz_calendar_alloc(0, 1));
	ck_assert_ptr_null(lz_calendar_alloc(10, 0));
	ck_assert_msg(strstr(lz_error_message(), "positive"), "says: %s", lz_error_message());
}
END_TEST

/* ---- the engine with lists ---- */

static const int queues[] = {LZ_EDMD_HEAP, LZ_EDMD_HEAP4, LZ_EDMD_CALENDAR};
static const char *const queue_name[] = {"heap", "heap4", "calendar"};

static lz_edmd *lists_system(int dim, size_t n, double eta, int walls, double g, double er,
                             double shell, int queue)
{
	lz_edmd_params p = {dim, n, eta, er, g, walls, 0, LZ_EDMD_LIST, shell, queue};
	lz_edmd *e = lz_edmd_alloc(&p);
	ck_assert_msg(e != NULL, "lz_edmd_alloc(dim %d, n %zu, packing %g, lists, shell %g): %s",
	              dim, n, eta, shell, lz_error_message());
	return e;
}

static lz_edmd *lists_lattice(int dim, size_t n, double eta, int walls, double g,
                              double shell, int queue, unsigned long seed)
{
	lz_edmd *e = lists_system(dim, n, eta, walls, g, 1, shell, queue);
	lz_rng *r = lz_rng_alloc(NULL, seed);
	int st = lz_edmd_place_lattice(e, r);
	lz_rng_free(r);
	ck_assert_msg(st == LZ_OK, "place_lattice: %s", lz_error_message());
	return e;
}

/* Run `chunks` pieces of `events` events, auditing after each: the invariants of the
 * lists, the cells by centre and the queue; then no overlap, the energy (elastic) and
 * momentum (periodic, no gravity) to round-off. */
static void run_audited(lz_edmd *e, int chunks, uint64_t events, const char *what)
{
	double E0 = lz_edmd_energy(e), P0[3], P[3];
	lz_edmd_momentum(e, P0);
	for (int k = 0; k < chunks; k++) {
		int st = lz_edmd_run(e, events, INFINITY);
		LZ_REQUIRE(st == LZ_OK, "%s, chunk %d: %s", what, k, lz_error_message());
		LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%s, after %llu events (%llu rebuilds): %s",
		           what, (unsigned long long)e->events, (unsigned long long)e->rebuilds,
		           lz_error_message());
		uint32_t i = 0, j = 0;
		double over = lz_edmd_max_overlap(e, &i, &j);
		LZ_REQUIRE(over < 1e-10, "%s: particles %u and %u overlap by %.3g after %llu events — "
		           "a neighbour missing from a list?", what, i, j, over,
		           (unsigned long long)e->events);
	}
	if (e->restitution == 1)
		LZ_REQUIRE(fabs(lz_edmd_energy(e) / E0 - 1) < 1e-10, "%s: the energy moved by %.2g",
		           what, lz_edmd_energy(e) / E0 - 1);
	lz_edmd_momentum(e, P);
	for (int a = 0; !e->wall[0] && e->g == 0 && a < 3; a++)
		LZ_REQUIRE(fabs(P[a] - P0[a]) < 1e-9, "%s: the momentum %c moved from %.3g to %.3g",
		           what, "xyz"[a], P0[a], P[a]);
	LZ_REQUIRE(e->rebuilds > 0 && e->collisions > 0, "%s: %llu rebuilds and %llu collisions "
	           "— the lists never moved?", what, (unsigned long long)e->rebuilds,
	           (unsigned long long)e->collisions);
}

LZ_TEST(edmd_lists_keep_every_invariant_with_every_queue)
{
	for (int k = 0; k < 3; k++) {
		char what[128];
		struct {
			int dim, walls;
			double eta, g, shell;
		} c[] = {{3, LZ_EDMD_WALLS_NONE, 0.49, 0, 1.4}, {2, LZ_EDMD_WALLS_NONE, 0.69, 0, 1.8},
		         {3, LZ_EDMD_WALLS_BOX, 0.3, 0, 1.5}, {2, LZ_EDMD_WALLS_X, 0.2, 2, 2.2},
		         {3, LZ_EDMD_WALLS_NONE, 0.1, 0, 3.0},
		         /* lists of 150 and more: the prediction's later words of pairs */
		         {3, LZ_EDMD_WALLS_NONE, 0.3, 0, 4.0}};
		for (size_t s = 0; s < sizeof c / sizeof c[0]; s++) {
			snprintf(what, sizeof what, "%dD, η = %g, walls %d, g = %g, shell %g, %s", c[s].dim,
			         c[s].eta, c[s].walls, c[s].g, c[s].shell, queue_name[k]);
			lz_edmd *e = lists_lattice(c[s].dim, 2000, c[s].eta, c[s].walls, c[s].g,
			                           c[s].shell, queues[k], 300 + s);
			run_audited(e, 8, 5000, what);
			lz_edmd_free(e);
		}
	}
}
END_TEST

/* Run a and b (the same start, one thing different: `how`) `events` events each: the
 * same collisions, rebuilds, virial, clock and records, bit for bit. */
static void same_run(lz_edmd *a, lz_edmd *b, uint64_t events, const char *how)
{
	LZ_REQUIRE_TRUE(lz_edmd_run(a, events, INFINITY) == LZ_OK &&
	                lz_edmd_run(b, events, INFINITY) == LZ_OK);
	LZ_REQUIRE(a->collisions == b->collisions && a->rebuilds == b->rebuilds &&
	           a->virial == b->virial && lz_edmd_time(a) == lz_edmd_time(b),
	           "%s: %llu / %llu collisions, %llu / %llu rebuilds, virial %.17g / %.17g", how,
	           (unsigned long long)a->collisions, (unsigned long long)b->collisions,
	           (unsigned long long)a->rebuilds, (unsigned long long)b->rebuilds, a->virial,
	           b->virial);
	for (uint32_t i = 0; i < a->n; i++)
		LZ_REQUIRE(memcmp(&a->p[i], &b->p[i], sizeof a->p[i]) == 0,
		           "%s: particle %u is elsewhere", how, i);
	LZ_REQUIRE(a->rebuilds > 0, "%s: no list was rebuilt", how);
}

LZ_TEST(edmd_lists_prefetching_changes_nothing_with_every_queue)
{
	/* the look ahead of lz_edmd_list_fetch_ahead (on from LZ_EDMD_FAR particles) only
	 * asks the memory: turned on for a small fluid it must leave the same events and
	 * the same state, bit for bit, whichever queue guesses the next events */
	for (int k = 0; k < 3; k++) {
		char how[64];
		lz_edmd *a = lists_lattice(3, 2000, 0.49, LZ_EDMD_WALLS_NONE, 0, 1.4, queues[k], 17);
		lz_edmd *b = lists_lattice(3, 2000, 0.49, LZ_EDMD_WALLS_NONE, 0, 1.4, queues[k], 17);
		a->prefetch = 0;
		b->prefetch = 1;
		snprintf(how, sizeof how, "%s, without and with the look ahead", queue_name[k]);
		same_run(a, b, 40000, how);
		lz_edmd_free(a);
		lz_edmd_free(b);
	}
}
END_TEST

LZ_TEST(edmd_lists_both_builds_of_the_prediction_give_the_same_bits)
{
	/* the prediction for any processor and the one for AVX2 (four pairs a vector) do
	 * the same operations in the same order: the same trajectory, in a periodic
	 * fluid, under gravity between walls, and with lists past 64 pairs */
	struct {
		int dim, walls;
		double eta, g, shell;
	} c[] = {{3, LZ_EDMD_WALLS_NONE, 0.49, 0, 1.4}, {2, LZ_EDMD_WALLS_X, 0.2, 2, 2.2},
	         {3, LZ_EDMD_WALLS_NONE, 0.3, 0, 4.0}};
	for (size_t s = 0; s < sizeof c / sizeof c[0]; s++) {
		char how[192];
		lz_edmd *a = lists_lattice(c[s].dim, 2000, c[s].eta, c[s].walls, c[s].g, c[s].shell,
		                           LZ_EDMD_CALENDAR, 40 + s);
		lz_edmd *b = lists_lattice(c[s].dim, 2000, c[s].eta, c[s].walls, c[s].g, c[s].shell,
		                           LZ_EDMD_CALENDAR, 40 + s);
		LZ_REQUIRE_TRUE(lz_edmd_list_wide(a, 0) == 0);
		int wide = lz_edmd_list_wide(b, 1);
		snprintf(how, sizeof how, "%dD, η = %g, g = %g, shell %g: the %s build against the "
		         "one for any processor", c[s].dim, c[s].eta, c[s].g, c[s].shell,
		         wide ? "AVX2" : "default (no AVX2 here)");
		same_run(a, b, 30000, how);
		lz_edmd_free(a);
		lz_edmd_free(b);
	}
}
END_TEST

LZ_TEST(edmd_lists_longer_than_their_block_chain_and_renumber)
{
	/* a shell far wider than the block was sized for: chunks, audited, renumbered */
	lz_edmd *e = lists_lattice(3, 3000, 0.45, LZ_EDMD_WALLS_NONE, 0, 1.4, LZ_EDMD_CALENDAR, 9);
	run_audited(e, 2, 20000, "η = 0.45 (lists sized for fewer)");
	size_t used = e->lists->chunks;
	ck_assert_msg(used > 0, "no list grew beyond its block (cap %u) at η = 0.45",
	              e->lists->cap);
	ck_assert_msg(lz_edmd_sort(e) == LZ_OK && lz_edmd_audit(e) == LZ_OK, "renumbered: %s",
	              lz_error_message());
	e->sort_every = 1;
	run_audited(e, 4, 10000, "renumbered at every re-base");
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(edmd_lists_two_particles_meet_on_time_across_the_boundary)
{
	/* a box of side 10: a at x = 0.7 moving +0.7, b at x = 4.7 moving -0.3, the gap of
	 * 3 closes at 1 per time unit: contact at t = 3; the velocities swap, and the gap
	 * the other way round, 10 - 2 = 8, closes at t = 11 through the boundary */
	for (int k = 0; k < 3; k++) {
		double L = 10, eta = 2 * M_PI / 6 / (L * L * L);
		lz_edmd *e = lists_system(3, 2, eta, LZ_EDMD_WALLS_NONE, 0, 1, 1.5, queues[k]);
		double r[6] = {0.7, 5, 5, 4.7, 5, 5}, v[6] = {0.7, 0, 0, -0.3, 0, 0};
		ck_assert_int_eq(lz_edmd_set(e, r, v), LZ_OK);
		double want[2] = {3, 11};
		for (int c = 0; c < 2; c++) {
			while (e->collisions == (uint64_t)c)
				ck_assert_int_eq(lz_edmd_next(e), 0);
			LZ_REQUIRE(fabs(lz_edmd_time(e) - want[c]) < 1e-12, "%s: collision %d at t = %.15g, "
			           "closed form %g", queue_name[k], c + 1, lz_edmd_time(e), want[c]);
		}
		ck_assert_msg(e->rebuilds > 0, "%s: 11 time units of flight without a rebuild",
		              queue_name[k]);
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(edmd_lists_ball_bounces_under_gravity_between_walls)
{
	/* one particle on x in [1/2, L - 1/2] under g = 2, from the floor at speed 3: up to
	 * height 9/4 above the contact and back after 2·3/2 = 3 time units, for ever */
	lz_edmd *e = lists_system(3, 1, 1e-4, LZ_EDMD_WALLS_X, 2, 1, 1.5, LZ_EDMD_CALENDAR);
	double r[3] = {0.5, 3, 3}, v[3] = {3, 0, 0};
	ck_assert_int_eq(lz_edmd_set(e, r, v), LZ_OK);
	double E0 = lz_edmd_energy(e);
	for (uint64_t b = 1; b <= 20; b++) {
		while (e->bounces < b)
			ck_assert_int_eq(lz_edmd_next(e), 0);
		LZ_REQUIRE(fabs(lz_edmd_time(e) - 3.0 * b) < 1e-9, "bounce %llu at t = %.12g, closed "
		           "form %g", (unsigned long long)b, lz_edmd_time(e), 3.0 * b);
	}
	ck_assert_msg(fabs(lz_edmd_energy(e) / E0 - 1) < 1e-12, "the energy moved by %.2g",
	              lz_edmd_energy(e) / E0 - 1);
	ck_assert_msg(e->rebuilds > 20, "a ball rising 2.25 σ in a skin of 0.25 σ rebuilt only "
	              "%llu times in 20 bounces", (unsigned long long)e->rebuilds);
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(edmd_lists_pressure_of_hard_spheres_and_the_identity)
{
	/* η = 0.3, N = 4000: Z against the reference within 3 block errors and its own;
	 * and Z against the collision rate's 1 + √(π/T) Γ/6, which must agree exactly */
	lz_edmd *e = lists_lattice(3, 4000, 0.3, LZ_EDMD_WALLS_NONE, 0, 0, LZ_EDMD_CALENDAR, 551);
	ck_assert_int_eq(lz_edmd_run(e, 150000, INFINITY), LZ_OK);
	lz_edmd_result r;
	ck_assert_msg(lz_edmd_blocks(e, 20, 200000, &r) == LZ_OK, "%s", lz_error_message());
	lz_ref z = lz_test_reference("hard-spheres.csv", "Z", "3", "eta=0.30");
	ck_assert_msg(fabs(r.Z - z.value) <= 3 * r.Z_err + z.err, "lists at η = 0.3: Z = %.4f ± "
	              "%.4f, the reference %.4f ± %.4f", r.Z, r.Z_err, z.value, z.err);
	ck_assert_msg(fabs(r.Z - r.Z_gamma) <= 3 * (r.Z_err + r.Z_gamma_err), "lists: the virial "
	              "gives %.5f, the collision rate %.5f", r.Z, r.Z_gamma);
	ck_assert_msg(r.rebuilds > 0 && r.crossings == 0, "lists: %llu rebuilds, %llu crossings",
	              (unsigned long long)r.rebuilds, (unsigned long long)r.crossings);
	lz_edmd_free(e);
}
END_TEST

/* Positions at now, wrapped into the box. */
static void wrapped(const lz_edmd *e, uint32_t i, double r[3])
{
	double v[3];
	lz_edmd_state(e, &e->p[i], e->now, r, v);
	for (int a = 0; a < e->dim; a++)
		r[a] -= e->L * floor(r[a] / e->L);
}

LZ_TEST(edmd_lists_follow_the_trajectory_of_the_cells)
{
	/* the same start with cells and with lists: the same collisions and the same
	 * places for a while (predictions made at other moments round otherwise, so the
	 * bits part, and slowly the chaos takes over) */
	lz_edmd_params pc = {3, 1000, 0.3, 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *c = lz_edmd_alloc(&pc);
	lz_edmd *l = lists_system(3, 1000, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, 1.5, LZ_EDMD_CALENDAR);
	lz_rng *r1 = lz_rng_alloc(NULL, 5), *r2 = lz_rng_alloc(NULL, 5);
	ck_assert(lz_edmd_place_lattice(c, r1) == LZ_OK && lz_edmd_place_lattice(l, r2) == LZ_OK);
	ck_assert(lz_edmd_run(c, UINT64_MAX, 0.2) == LZ_OK && lz_edmd_run(l, UINT64_MAX, 0.2) == LZ_OK);
	ck_assert_msg(c->collisions == l->collisions && c->collisions > 300, "to t = 0.2: %llu "
	              "collisions with cells, %llu with lists", (unsigned long long)c->collisions,
	              (unsigned long long)l->collisions);
	for (uint32_t i = 0; i < c->n; i++) {
		double a[3], b[3];
		wrapped(c, i, a);
		wrapped(l, i, b);
		for (int x = 0; x < 3; x++)
			LZ_REQUIRE(fabs(a[x] - b[x]) < 1e-9 || fabs(fabs(a[x] - b[x]) - c->L) < 1e-9,
			           "particle %u, %c: %.15g with cells, %.15g with lists", i, "xyz"[x], a[x],
			           b[x]);
	}
	lz_rng_free(r1);
	lz_rng_free(r2);
	lz_edmd_free(c);
	lz_edmd_free(l);
}
END_TEST

LZ_TEST(edmd_get_hands_a_listed_state_back_to_set)
{
	/* a list keeps a sphere's centre where its flight took it, outside the box after a
	 * while; lz_edmd_get wraps it back, and lz_edmd_set takes the state into cells with
	 * the same energy and momentum */
	lz_edmd *l = lists_lattice(3, 2000, 0.4, LZ_EDMD_WALLS_NONE, 0, 1.8, LZ_EDMD_CALENDAR, 9);
	l->rebase_auto = 0;
	ck_assert_int_eq(lz_edmd_run(l, 40000, INFINITY), LZ_OK);
	size_t n = l->n;
	double *r = malloc(3 * n * sizeof *r), *v = malloc(3 * n * sizeof *v), P0[3], P1[3];
	ck_assert(r && v);
	lz_edmd_get(l, r, v);
	for (size_t k = 0; k < 3 * n; k++)
		LZ_REQUIRE(r[k] >= 0 && r[k] < l->L, "coordinate %zu: %.17g outside [0, %.17g)", k,
		           r[k], l->L);
	lz_edmd_params pc = {3, n, 0.4, 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *c = lz_edmd_alloc(&pc);
	ck_assert_msg(lz_edmd_set(c, r, v) == LZ_OK, "set: %s", lz_error_message());
	lz_edmd_momentum(l, P0);
	lz_edmd_momentum(c, P1);
	ck_assert_msg(fabs(lz_edmd_energy(c) / lz_edmd_energy(l) - 1) < 1e-14, "energy %.17g, "
	              "was %.17g", lz_edmd_energy(c), lz_edmd_energy(l));
	for (int a = 0; a < 3; a++)
		ck_assert_msg(fabs(P1[a] - P0[a]) < 1e-12, "momentum %c: %.3g, was %.3g", "xyz"[a],
		              P1[a], P0[a]);
	free(r);
	free(v);
	lz_edmd_free(c);
	lz_edmd_free(l);
}
END_TEST

LZ_TEST(edmd_lists_at_a_clock_of_1e12_and_in_collapse)
{
	/* a clock far from 0 (re-based: small times inside) runs as well as one at 0;
	 * an inelastic cluster collapses into a message, not a hang */
	lz_edmd *e = lists_lattice(3, 1000, 0.45, LZ_EDMD_WALLS_NONE, 0, 0, LZ_EDMD_CALENDAR, 12);
	lz_edmd_set_time(e, 1e12);
	run_audited(e, 4, 5000, "the clock at 1e12");
	ck_assert_msg(lz_edmd_time(e) > 1e12, "the clock reads %.17g", lz_edmd_time(e));
	lz_edmd_free(e);
	lz_edmd *f = lists_system(2, 1000, 0.4, LZ_EDMD_WALLS_NONE, 0, 0.1, 0, LZ_EDMD_CALENDAR);
	lz_rng *r = lz_rng_alloc(NULL, 3);
	ck_assert_int_eq(lz_edmd_place_lattice(f, r), LZ_OK);
	int st = lz_edmd_run(f, 5000000, INFINITY);
	ck_assert_msg(st == LZ_EPHYS && strstr(lz_error_message(), "collapse"), "restitution 0.1: "
	              "status %d, %s", st, lz_error_message());
	lz_rng_free(r);
	lz_edmd_free(f);
}
END_TEST

LZ_TEST(edmd_lists_refuse_what_they_cannot_hold)
{
	lz_edmd_params p = {3, 1000, 0.3, 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_LIST, 0.9, 0};
	lz_test_clear_error();
	ck_assert_ptr_null(lz_edmd_alloc(&p));
	ck_assert_msg(strstr(lz_error_message(), "(1, 4]"), "shell 0.9: %s", lz_error_message());
	p.shell = 0;
	p.n = 20;
	ck_assert_ptr_null(lz_edmd_alloc(&p));
	ck_assert_msg(strstr(lz_error_message(), "neighbours = cells"), "20 particles: %s",
	              lz_error_message());
	p.n = 1000;
	p.neighbours = LZ_EDMD_CELLS;
	p.queue = LZ_EDMD_CALENDAR;
	ck_assert_ptr_null(lz_edmd_alloc(&p));
	ck_assert_msg(strstr(lz_error_message(), "needs neighbours = list"), "calendar with "
	              "cells: %s", lz_error_message());
	p.queue = 7;
	ck_assert_ptr_null(lz_edmd_alloc(&p));
	p.queue = 0;
	p.neighbours = 5;
	ck_assert_ptr_null(lz_edmd_alloc(&p));
	ck_assert_msg(lz_edmd_list_pays(3, 100000, 0.5) == LZ_EDMD_LIST &&
	              lz_edmd_list_pays(3, 100000, 0.1) == LZ_EDMD_CELLS &&
	              lz_edmd_list_pays(3, 20, 0.5) == LZ_EDMD_CELLS &&
	              lz_edmd_list_pays(3, 10000, 0.3) == LZ_EDMD_LIST &&
	              lz_edmd_list_pays(3, 100000, 0.3) == LZ_EDMD_CELLS,
	              "the automatic choice: lists for a dense fluid that fits them (from "
	              "0.28 in a system that fits the caches, else from 0.35), else cells");
}
END_TEST
