/* test_heap.c — stage 05, the indexed binary min-heap (lz/heap.h): sift up, sift
 * down, push, pop and update, each keeping the heap order and the pos[] index.
 *
 * The heaps of the unit tests are made by hand (every key no earlier than its
 * parent's, ids a random permutation), so that sift_up, sift_down, pop and update
 * are each tested without the others' help; the slots beyond n hold poison (a key
 * of -1e300 and a foreign id) that a read past the end would drag into the heap.
 * The reference is the test's own bookkeeping: the key of every item in a plain
 * array, the order of the pops from qsort, and a checker that walks node[] and
 * pos[] both ways. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/heap.h"
#include "lztest.h"


#define POISON_T (-1e300)


/* 0 .. n-1 in random order. */
static void shuffled(uint32_t *a, size_t n, gsl_rng *r)
{
	for (size_t i = 0; i < n; i++)
		a[i] = (uint32_t)i;
	for (size_t i = n; i-- > 1;) {
		size_t j = gsl_rng_uniform_int(r, i + 1);
		uint32_t x = a[i];
		a[i] = a[j];
		a[j] = x;
	}
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* What the test believes: the key of every item and whether it is in the heap. */
typedef struct {
	size_t cap;
	double *key;
	int *in;
} model;

static model model_new(size_t cap)
{
	model m = {cap, calloc(cap, sizeof(double)), calloc(cap, sizeof(int))};
	LZ_REQUIRE(m.key && m.in, "out of memory for the test's model of %zu items", cap);
	return m;
}

static void model_free(model *m)
{
	free(m->key);
	free(m->in);
}

/* Poison every slot from n on: a sift that reads past the last node finds a key
 * earlier than everything and an id that is not its own. */
static void poison(lz_heap *h)
{
	for (size_t k = h->n; k < h->cap; k++) {
		h->node[k].t = POISON_T;
		h->node[k].id = (uint32_t)(h->cap - 1 - k % h->cap);
	}
}

/* The whole truth about h against the model: heap order, node ids, pos[] both ways,
 * the keys, and the count. `after` says what was just done, for the message. */
static void check_heap(const lz_heap *h, const model *m, const char *after)
{
	size_t in = 0;
	for (size_t id = 0; id < m->cap; id++)
		in += m->in[id] != 0;
	LZ_REQUIRE(h->n == in, "after %s the heap holds n = %zu nodes, expected %zu items", after,
	      h->n, in);
	for (size_t k = 0; k < h->n; k++) {
		uint32_t id = h->node[k].id;
		LZ_REQUIRE(id < m->cap, "after %s node %zu holds id %u, which is not an item (cap %zu): "
		      "was a node read from beyond the end of the heap?", after, k, id, m->cap);
		LZ_REQUIRE(m->in[id], "after %s node %zu holds item %u, which should not be in the heap",
		      after, k, id);
		LZ_REQUIRE(h->pos[id] == k, "after %s node %zu holds item %u but pos[%u] = %u: every node "
		      "that moves must have its pos[] written", after, k, id, id, h->pos[id]);
		LZ_REQUIRE(h->node[k].t == m->key[id] ||
		              (isnan(h->node[k].t) && isnan(m->key[id])),
		      "after %s item %u has the key %.17g in the heap, expected %.17g: a key travelled "
		      "without its id", after, id, h->node[k].t, m->key[id]);
		if (k > 0) {
			size_t p = (k - 1) / 2;
			LZ_REQUIRE(!(h->node[k].t < h->node[p].t),
			      "after %s the heap order is broken: node %zu (item %u, t = %.17g) is "
			      "earlier than its parent node %zu (item %u, t = %.17g)", after, k, id,
			      h->node[k].t, p, h->node[p].id, h->node[p].t);
		}
	}
	for (size_t id = 0; id < m->cap; id++)
		if (!m->in[id])
			LZ_REQUIRE(h->pos[id] == LZ_HEAP_NONE, "after %s item %zu is not in the heap but "
			      "pos[%zu] = %u, expected LZ_HEAP_NONE", after, id, id, h->pos[id]);
}

static lz_heap *heap_new(size_t cap)
{
	lz_heap *h = lz_heap_alloc(cap);
	LZ_REQUIRE(h != NULL, "lz_heap_alloc(%zu): %s", cap, lz_error_message());
	poison(h);
	return h;
}

/* A random valid heap of n nodes made by hand (no graded function): keys grow down
 * the tree by random steps, a quarter of them 0 (ties); the ids are a random subset
 * of the items in random order. */
static void hand_heap(lz_heap *h, model *m, size_t n, gsl_rng *r)
{
	lz_heap_clear(h);
	memset(m->in, 0, m->cap * sizeof *m->in);
	uint32_t *ids = malloc(m->cap * sizeof *ids);
	LZ_REQUIRE(ids, "out of memory for %zu item numbers", m->cap);
	shuffled(ids, m->cap, r);
	for (size_t k = 0; k < n; k++) {
		double t = k == 0 ? gsl_rng_uniform(r) : h->node[(k - 1) / 2].t;
		if (k > 0 && gsl_rng_uniform(r) > 0.25)
			t += gsl_rng_uniform(r);
		h->node[k].t = t;
		h->node[k].id = ids[k];
		h->pos[ids[k]] = (uint32_t)k;
		m->key[ids[k]] = t;
		m->in[ids[k]] = 1;
	}
	h->n = n;
	poison(h);
	free(ids);
}

/* A heap made by hand (no graded function) with node k = {keys[k], id(k)}, id(k) = k,
 * or n - 1 - k when reversed; the keys must already be in heap order. */
static void listed_heap(lz_heap *h, model *m, const double *keys, uint32_t n, int reversed)
{
	for (uint32_t k = 0; k < n; k++) {
		uint32_t id = reversed ? n - 1 - k : k;
		h->node[k] = (lz_heap_node){keys[k], id};
		h->pos[id] = k;
		m->key[id] = keys[k];
		m->in[id] = 1;
	}
	h->n = n;
	poison(h);
}

/* ---- sift up ---- */

LZ_TEST(heap_sift_up_moves_an_earlier_key_to_its_place)
{
	/* by hand: keys 10..70 in a full tree of 7; the last leaf (6) becomes 5, earlier
	 * than everything: it must climb 6 -> 2 -> 0 and its ancestors move down */
	lz_heap *h = heap_new(8);
	model m = model_new(8);
	static const double tens[7] = {10, 20, 30, 40, 50, 60, 70};
	listed_heap(h, &m, tens, 7, 0);
	h->node[6].t = m.key[6] = 5;
	lz_heap_sift_up(h, 6);
	LZ_REQUIRE(h->node[0].id == 6 && h->node[2].id == 0 && h->node[6].id == 2,
	      "sift_up from the last leaf (key 5, ancestors 30 at node 2 and 10 at the root): "
	      "expected items (6, 0, 2) at nodes (0, 2, 6), got (%u, %u, %u) — the node must "
	      "climb while its parent is later", h->node[0].id, h->node[2].id, h->node[6].id);
	check_heap(h, &m, "sift_up of a new earliest key from the last leaf");
	/* a key between its parent and grandparent stops half way: node 4 (item 4, 50)
	 * under node 1 (item 1, 20) under the root (item 6, 5) gets 15 */
	h->node[4].t = m.key[4] = 15;
	lz_heap_sift_up(h, 4);
	LZ_REQUIRE(h->node[0].id == 6 && h->node[1].id == 4 && h->node[4].id == 1,
	      "sift_up of key 15 from node 4 (parent 20, root 5): expected items (6, 4, 1) at "
	      "nodes (0, 1, 4), got (%u, %u, %u) — it must stop below the earlier root",
	      h->node[0].id, h->node[1].id, h->node[4].id);
	check_heap(h, &m, "sift_up that stops half way");
	/* a node already in place, and the root, do not move */
	lz_heap_node before[8];
	memcpy(before, h->node, sizeof before);
	lz_heap_sift_up(h, 5);
	lz_heap_sift_up(h, 0);
	LZ_REQUIRE(memcmp(before, h->node, sizeof before) == 0,
	      "sift_up of a node no earlier than its parent (and of the root) changed the heap");
	check_heap(h, &m, "sift_up of nodes already in place");

	/* random heaps: any node given any key no later than its old one */
	gsl_rng *r = lz_test_rng(501);
	lz_heap *g = heap_new(300);
	model mg = model_new(300);
	for (int trial = 0; trial < 3000; trial++) {
		size_t n = 1 + gsl_rng_uniform_int(r, 300);
		hand_heap(g, &mg, n, r);
		size_t k = gsl_rng_uniform_int(r, n);
		uint32_t id = g->node[k].id;
		double u = gsl_rng_uniform(r), t;
		if (u < 0.2)
			t = g->node[0].t - 1;                /* a new earliest */
		else if (u < 0.4 && k > 0)
			t = g->node[(k - 1) / 2].t;          /* a tie with the parent */
		else
			t = g->node[k].t * gsl_rng_uniform(r);
		g->node[k].t = mg.key[id] = t;
		lz_heap_sift_up(g, k);
		char what[96];
		snprintf(what, sizeof what, "sift_up of node %zu of %zu to an earlier key", k, n);
		check_heap(g, &mg, what);
	}
	gsl_rng_free(r);
	model_free(&m);
	model_free(&mg);
	lz_heap_free(h);
	lz_heap_free(g);
}
END_TEST

/* ---- sift down ---- */

LZ_TEST(heap_sift_down_follows_the_earlier_child)
{
	/* by hand: the root of keys {_, 20, 30, 40, 50, 60, 70} becomes 65: it must go to
	 * the earlier child each time (20 at node 1, then 40 at node 3) */
	lz_heap *h = heap_new(8);
	model m = model_new(8);
	static const double tens[7] = {10, 20, 30, 40, 50, 60, 70};
	listed_heap(h, &m, tens, 7, 0);
	h->node[0].t = m.key[0] = 65;
	lz_heap_sift_down(h, 0);
	LZ_REQUIRE(h->node[0].id == 1 && h->node[1].id == 3 && h->node[3].id == 0,
	      "sift_down of key 65 from the root (children 20 and 30, then 40 and 50): expected "
	      "items (1, 3, 0) at nodes (0, 1, 3), got (%u, %u, %u) — the node must swap with the "
	      "EARLIER child", h->node[0].id, h->node[1].id, h->node[3].id);
	check_heap(h, &m, "sift_down of the root to a leaf");
	/* the right child earlier than the left one */
	h->node[2].t = m.key[h->node[2].id] = 100;
	uint32_t left = h->node[5].id, right = h->node[6].id;
	h->node[6].t = m.key[right] = 55;
	lz_heap_sift_down(h, 2);
	LZ_REQUIRE(h->node[2].id == right && h->node[6].t == 100,
	      "sift_down of key 100 from node 2 with children 60 (left) and 55 (right): the "
	      "right child (item %u) should move up, got item %u at node 2 (left child is item %u)",
	      right, h->node[2].id, left);
	check_heap(h, &m, "sift_down towards the right child");

	/* an even n: the last inner node has only a left child (node 2k+2 == n is
	 * poison, earlier than everything, and must not be looked at) */
	lz_heap *g = heap_new(8);
	model mg = model_new(8);
	static const double keys[6] = {1, 2, 3, 4, 5, 6};
	listed_heap(g, &mg, keys, 6, 0);
	g->node[2].t = mg.key[2] = 9;
	lz_heap_sift_down(g, 2);
	LZ_REQUIRE(g->node[2].id == 5 && g->node[5].id == 2,
	      "sift_down of key 9 from node 2 of 6 nodes (its only child is node 5, key 6): "
	      "expected items (5, 2) at nodes (2, 5), got (%u, %u) — node 6 is beyond n",
	      g->node[2].id, g->node[5].id);
	check_heap(g, &mg, "sift_down to a lone left child");
	/* a leaf, and a node no later than its children, do not move */
	lz_heap_node before[8];
	memcpy(before, g->node, sizeof before);
	lz_heap_sift_down(g, 5);
	lz_heap_sift_down(g, 4);
	lz_heap_sift_down(g, 0);
	LZ_REQUIRE(memcmp(before, g->node, sizeof before) == 0,
	      "sift_down of leaves and of a root earlier than its children changed the heap");

	/* random heaps: any node given any key no earlier than its old one */
	gsl_rng *r = lz_test_rng(502);
	lz_heap *q = heap_new(300);
	model mq = model_new(300);
	for (int trial = 0; trial < 3000; trial++) {
		size_t n = 1 + gsl_rng_uniform_int(r, 300);
		hand_heap(q, &mq, n, r);
		size_t k = gsl_rng_uniform_int(r, n);
		uint32_t id = q->node[k].id;
		double u = gsl_rng_uniform(r), t;
		if (u < 0.1)
			t = INFINITY;
		else if (u < 0.3 && 2 * k + 1 < n)
			t = q->node[2 * k + 1].t;            /* a tie with a child */
		else
			t = q->node[k].t + 3 * gsl_rng_uniform(r);
		q->node[k].t = mq.key[id] = t;
		lz_heap_sift_down(q, k);
		char what[96];
		snprintf(what, sizeof what, "sift_down of node %zu of %zu to a later key", k, n);
		check_heap(q, &mq, what);
	}
	gsl_rng_free(r);
	model_free(&m);
	model_free(&mg);
	model_free(&mq);
	lz_heap_free(h);
	lz_heap_free(g);
	lz_heap_free(q);
}
END_TEST

/* ---- push ---- */

LZ_TEST(heap_push_keeps_order_and_index)
{
	gsl_rng *r = lz_test_rng(503);
	lz_heap *h = heap_new(500);
	model m = model_new(500);
	/* decreasing keys: each push climbs to the root */
	for (uint32_t id = 0; id < 20; id++) {
		double t = 100.0 - id;
		lz_heap_push(h, id, t);
		m.key[id] = t;
		m.in[id] = 1;
		LZ_REQUIRE(lz_heap_top(h) == id && lz_heap_top_t(h) == t,
		      "pushed item %u with key %g, the earliest so far: the top is item %u (%g)", id,
		      t, lz_heap_top(h), lz_heap_top_t(h));
		check_heap(h, &m, "a push of the earliest key");
	}
	/* random items, random keys with ties, infinity and zero */
	lz_heap_clear(h);
	memset(m.in, 0, m.cap * sizeof *m.in);
	poison(h);
	uint32_t order[500];
	shuffled(order, 500, r);
	for (size_t k = 0; k < 500; k++) {
		uint32_t id = order[k];
		double u = gsl_rng_uniform(r);
		double t = u < 0.1 ? INFINITY : u < 0.3 ? floor(10 * gsl_rng_uniform(r)) : u < 0.35 ? 0
		                                                                         : gsl_rng_uniform(r);
		lz_heap_push(h, id, t);
		m.key[id] = t;
		m.in[id] = 1;
		LZ_REQUIRE(lz_heap_contains(h, id), "item %u was pushed but lz_heap_contains says it is "
		      "not in the heap (pos[%u] = %u)", id, id, h->pos[id]);
		char what[64];
		snprintf(what, sizeof what, "push %zu of item %u (t = %g)", k + 1, id, t);
		check_heap(h, &m, what);
	}
	gsl_rng_free(r);
	model_free(&m);
	lz_heap_free(h);
}
END_TEST

/* ---- pop ---- */

LZ_TEST(heap_pop_returns_keys_in_sorted_order)
{
	gsl_rng *r = lz_test_rng(504);
	lz_heap *h = heap_new(400);
	model m = model_new(400);
	double *sorted = malloc(400 * sizeof *sorted);
	LZ_REQUIRE(sorted, "out of memory for the sorted keys");
	for (int trial = 0; trial < 200; trial++) {
		size_t n = trial < 3 ? (size_t)trial + 1 : 1 + gsl_rng_uniform_int(r, 400);
		hand_heap(h, &m, n, r);
		size_t k = 0;
		for (size_t id = 0; id < m.cap; id++)
			if (m.in[id])
				sorted[k++] = m.key[id];
		qsort(sorted, n, sizeof *sorted, cmp_double);
		for (size_t q = 0; q < n; q++) {
			uint32_t top = lz_heap_top(h);
			uint32_t id = lz_heap_pop(h);
			LZ_REQUIRE(id == top, "lz_heap_pop returned item %u but the top was item %u", id, top);
			LZ_REQUIRE(id < m.cap && m.in[id], "pop %zu of %zu returned item %u, which was not in "
			      "the heap", q + 1, n, id);
			LZ_REQUIRE(m.key[id] == sorted[q], "pop %zu of a heap of %zu returned item %u with key "
			      "%.17g, but the %zu-th smallest key is %.17g: pops must come out in the "
			      "order of a sort", q + 1, n, id, m.key[id], q + 1, sorted[q]);
			m.in[id] = 0;
			LZ_REQUIRE(h->pos[id] == LZ_HEAP_NONE, "item %u was popped but pos[%u] = %u, expected "
			      "LZ_HEAP_NONE (the item is out)", id, id, h->pos[id]);
			char what[64];
			snprintf(what, sizeof what, "pop %zu of a heap of %zu", q + 1, n);
			check_heap(h, &m, what);
		}
	}
	free(sorted);
	gsl_rng_free(r);
	model_free(&m);
	lz_heap_free(h);
}
END_TEST

/* ---- update ---- */

LZ_TEST(heap_update_moves_keys_earlier_and_later)
{
	/* by hand: the root made later must sink, a leaf made earlier must rise */
	lz_heap *h = heap_new(8);
	model m = model_new(8);
	static const double keys[7] = {1, 2, 3, 4, 5, 6, 7};
	listed_heap(h, &m, keys, 7, 1);  /* item 6 at the root */
	lz_heap_update(h, 6, 10);  /* item 6 was the root (key 1) */
	m.key[6] = 10;
	LZ_REQUIRE(h->node[0].id == 5 && h->pos[6] >= 3,
	      "update of the root item 6 from key 1 to 10 (later than everything): it should sink "
	      "to a leaf and item 5 (key 2) become the top; the top is item %u, item 6 at node %u",
	      h->node[0].id, h->pos[6]);
	check_heap(h, &m, "update of the root to a later key");
	lz_heap_update(h, 0, 0.5);  /* item 0 was a leaf (key 7) */
	m.key[0] = 0.5;
	LZ_REQUIRE(h->node[0].id == 0, "update of leaf item 0 from key 7 to 0.5 (earlier than "
	      "everything): it should become the top, the top is item %u (key %g)", h->node[0].id,
	      h->node[0].t);
	check_heap(h, &m, "update of a leaf to an earlier key");
	lz_heap_update(h, 3, m.key[3]);  /* the same key: nothing to do */
	check_heap(h, &m, "update to the same key");

	gsl_rng *r = lz_test_rng(505);
	lz_heap *g = heap_new(256);
	model mg = model_new(256);
	for (int trial = 0; trial < 300; trial++) {
		size_t n = 1 + gsl_rng_uniform_int(r, 256);
		hand_heap(g, &mg, n, r);
		for (int u = 0; u < 40; u++) {
			uint32_t id = g->node[gsl_rng_uniform_int(r, n)].id;
			double old = mg.key[id], x = gsl_rng_uniform(r), t;
			const char *kind;
			if (x < 0.35) {
				t = old - 2 * gsl_rng_uniform(r);
				kind = "an earlier key";
			} else if (x < 0.7) {
				t = old + 2 * gsl_rng_uniform(r);
				kind = "a later key";
			} else if (x < 0.8) {
				t = INFINITY;
				kind = "infinity (never)";
			} else if (x < 0.9) {
				t = g->node[0].t;
				kind = "a tie with the top";
			} else {
				t = old;
				kind = "the same key";
			}
			lz_heap_update(g, id, t);
			mg.key[id] = t;
			char what[128];
			snprintf(what, sizeof what, "update of item %u (node of %zu) from %.6g to %s", id,
			         n, old, kind);
			check_heap(g, &mg, what);
		}
	}
	gsl_rng_free(r);
	model_free(&m);
	model_free(&mg);
	lz_heap_free(h);
	lz_heap_free(g);
}
END_TEST

/* ---- everything together ---- */

LZ_TEST(heap_random_operations_match_a_sorted_list)
{
	/* pushes, pops and updates at random; every pop must give an item whose key is
	 * the smallest of those in (found by a scan), and at the end the pops must come
	 * out as qsort orders the remaining keys */
	enum { CAP = 600, OPS = 200000 };
	gsl_rng *r = lz_test_rng(506);
	lz_heap *h = heap_new(CAP);
	model m = model_new(CAP);
	size_t nin = 0;
	for (long op = 0; op < OPS; op++) {
		double x = gsl_rng_uniform(r);
		if (nin == 0 || (x < 0.4 && nin < CAP)) {
			uint32_t id;
			do
				id = (uint32_t)gsl_rng_uniform_int(r, CAP);
			while (m.in[id]);
			double t = gsl_rng_uniform(r) < 0.05 ? INFINITY : floor(1e3 * gsl_rng_uniform(r)) / 8;
			lz_heap_push(h, id, t);
			m.key[id] = t;
			m.in[id] = 1;
			nin++;
		} else if (x < 0.7) {
			double least = INFINITY;
			for (size_t i = 0; i < CAP; i++)
				if (m.in[i] && m.key[i] < least)
					least = m.key[i];
			uint32_t id = lz_heap_pop(h);
			LZ_REQUIRE(id < CAP && m.in[id], "operation %ld: lz_heap_pop returned item %u, which is "
			      "not in the heap", op, id);
			LZ_REQUIRE(m.key[id] == least, "operation %ld: lz_heap_pop returned item %u with key "
			      "%.17g, but the earliest key in the heap is %.17g", op, id, m.key[id], least);
			m.in[id] = 0;
			nin--;
		} else {
			uint32_t id;
			do
				id = (uint32_t)gsl_rng_uniform_int(r, CAP);
			while (!m.in[id]);
			double t = gsl_rng_uniform(r) < 0.05 ? INFINITY : floor(1e3 * gsl_rng_uniform(r)) / 8;
			lz_heap_update(h, id, t);
			m.key[id] = t;
		}
		if (op % 97 == 0 || op < 2000)
			check_heap(h, &m, "a random push, pop or update");
	}
	check_heap(h, &m, "200000 random operations");
	double *sorted = malloc(CAP * sizeof *sorted);
	LZ_REQUIRE(sorted, "out of memory for the sorted keys");
	size_t k = 0;
	for (size_t i = 0; i < CAP; i++)
		if (m.in[i])
			sorted[k++] = m.key[i];
	qsort(sorted, k, sizeof *sorted, cmp_double);
	for (size_t q = 0; q < k; q++) {
		uint32_t id = lz_heap_pop(h);
		LZ_REQUIRE(id < CAP && m.in[id] && m.key[id] == sorted[q],
		      "emptying the heap: pop %zu of %zu gave item %u (key %.17g), expected the key "
		      "%.17g", q + 1, k, id, id < CAP ? m.key[id] : NAN, sorted[q]);
		m.in[id] = 0;
	}
	LZ_REQUIRE(h->n == 0, "after popping all %zu items the heap holds n = %zu", k, h->n);
	free(sorted);
	gsl_rng_free(r);
	model_free(&m);
	lz_heap_free(h);
}
END_TEST

LZ_TEST(heap_ties_and_infinite_keys)
{
	/* 300 items with one key, then infinity for half of them: every item must come
	 * out exactly once, the finite ones first */
	enum { CAP = 300 };
	gsl_rng *r = lz_test_rng(507);
	lz_heap *h = heap_new(CAP);
	model m = model_new(CAP);
	uint32_t order[CAP];
	shuffled(order, CAP, r);
	for (size_t k = 0; k < CAP; k++) {
		uint32_t id = order[k];
		lz_heap_push(h, id, 2.5);
		m.key[id] = 2.5;
		m.in[id] = 1;
	}
	check_heap(h, &m, "300 pushes of the same key");
	for (size_t k = 0; k < CAP; k += 2) {
		lz_heap_update(h, order[k], INFINITY);
		m.key[order[k]] = INFINITY;
	}
	check_heap(h, &m, "updates of half the items to infinity");
	int seen[CAP] = {0};
	for (size_t q = 0; q < CAP; q++) {
		double top = lz_heap_top_t(h);
		uint32_t id = lz_heap_pop(h);
		LZ_REQUIRE(id < CAP && !seen[id], "pop %zu of 300 (keys 2.5 and infinity) returned item %u "
		      "%s", q + 1, id, id < CAP ? "a second time" : "(not an item)");
		seen[id] = 1;
		double want = q < CAP / 2 ? 2.5 : INFINITY;
		LZ_REQUIRE(m.key[id] == want && top == want, "pop %zu of 300 gave item %u with key %g (top "
		      "key %g), expected %g: the 150 finite keys come out before the 150 infinite",
		      q + 1, id, m.key[id], top, want);
		m.in[id] = 0;
		if (q % 10 == 0)
			check_heap(h, &m, "a pop among ties");
	}
	/* all infinite: nothing will ever happen, the top says so */
	for (uint32_t id = 0; id < 5; id++) {
		lz_heap_push(h, id, INFINITY);
		m.key[id] = INFINITY;
		m.in[id] = 1;
	}
	lz_heap_update(h, 3, 1.0);
	m.key[3] = 1.0;
	LZ_REQUIRE(lz_heap_top(h) == 3, "four keys at infinity and item 3 updated to 1: the top is "
	      "item %u", lz_heap_top(h));
	lz_heap_update(h, 3, INFINITY);
	m.key[3] = INFINITY;
	check_heap(h, &m, "an update back to infinity");
	LZ_REQUIRE(isinf(lz_heap_top_t(h)), "every key is infinity but the top key is %g",
	      lz_heap_top_t(h));
	/* a run of ties is no barrier: behind 200 equal keys (a tree 8 levels deep) a
	 * push of an earlier key must climb all the way to the root */
	lz_heap_clear(h);
	poison(h);
	memset(m.in, 0, sizeof m.in[0] * CAP);
	for (size_t k = 0; k < 200; k++) {
		lz_heap_push(h, order[k], 2.5);
		m.key[order[k]] = 2.5;
		m.in[order[k]] = 1;
	}
	lz_heap_push(h, order[200], 1.0);
	m.key[order[200]] = 1.0;
	m.in[order[200]] = 1;
	LZ_REQUIRE(lz_heap_top(h) == order[200] && lz_heap_top_t(h) == 1.0, "item %u pushed with key 1 "
	      "behind 200 keys of 2.5: it is the earliest and must be the top, the top is item %u "
	      "(key %g) — does the push sift up all the way, past the ties?", order[200],
	      lz_heap_top(h), lz_heap_top_t(h));
	check_heap(h, &m, "a push of an earlier key behind 200 ties");
	gsl_rng_free(r);
	model_free(&m);
	lz_heap_free(h);
}
END_TEST

LZ_TEST(heap_single_item)
{
	lz_heap *h = heap_new(1);
	model m = model_new(1);
	lz_heap_push(h, 0, 3.0);
	m.key[0] = 3;
	m.in[0] = 1;
	check_heap(h, &m, "the push of the only item");
	lz_heap_update(h, 0, 7.0);
	m.key[0] = 7;
	check_heap(h, &m, "an update of the only item to a later key");
	lz_heap_update(h, 0, -1.0);
	m.key[0] = -1;
	check_heap(h, &m, "an update of the only item to an earlier key");
	LZ_REQUIRE(lz_heap_top(h) == 0 && lz_heap_top_t(h) == -1.0, "the only item 0 with key -1: top "
	      "is item %u with key %g", lz_heap_top(h), lz_heap_top_t(h));
	uint32_t id = lz_heap_pop(h);
	m.in[0] = 0;
	LZ_REQUIRE(id == 0, "pop of the only item returned %u", id);
	check_heap(h, &m, "the pop of the only item");
	LZ_REQUIRE(!lz_heap_contains(h, 0), "the only item was popped but the heap still contains it");
	lz_heap_push(h, 0, INFINITY);
	m.key[0] = INFINITY;
	m.in[0] = 1;
	check_heap(h, &m, "a push after the heap was emptied");
	/* two items: the pop moves the last node to the root, which must be indexed */
	lz_heap *g = heap_new(2);
	model mg = model_new(2);
	lz_heap_push(g, 1, 1.0);
	lz_heap_push(g, 0, 2.0);
	mg.key[1] = 1;
	mg.key[0] = 2;
	mg.in[0] = mg.in[1] = 1;
	check_heap(g, &mg, "two pushes");
	id = lz_heap_pop(g);
	mg.in[1] = 0;
	LZ_REQUIRE(id == 1, "pop of {item 1: 1.0, item 0: 2.0} returned item %u", id);
	check_heap(g, &mg, "the pop of the earlier of two items");
	model_free(&m);
	model_free(&mg);
	lz_heap_free(h);
	lz_heap_free(g);
}
END_TEST

LZ_TEST(heap_a_million_events_in_order)
{
	/* O(log n) per operation: a million pushes, a million updates and a million pops
	 * run in well under a second; a linear scan anywhere would take hours */
	enum { N = 1000000 };
	gsl_rng *r = lz_test_rng(508);
	lz_heap *h = lz_heap_alloc(N);
	LZ_REQUIRE(h, "lz_heap_alloc(10^6): %s", lz_error_message());
	double *key = malloc(N * sizeof *key);
	LZ_REQUIRE(key, "out of memory for 10^6 keys");
	for (uint32_t id = 0; id < N; id++) {
		key[id] = gsl_rng_uniform(r);
		lz_heap_push(h, id, key[id]);
	}
	for (uint32_t k = 0; k < N; k++) {
		uint32_t id = (uint32_t)gsl_rng_uniform_int(r, N);
		key[id] = gsl_rng_uniform(r);
		lz_heap_update(h, id, key[id]);
	}
	LZ_REQUIRE(lz_heap_audit(h) == LZ_OK, "after 10^6 pushes and 10^6 updates: %s",
	      lz_error_message());
	double last = -INFINITY;
	for (size_t q = 0; q < N; q++) {
		uint32_t id = lz_heap_pop(h);
		LZ_REQUIRE(id < N && key[id] >= last, "pop %zu of 10^6 gave item %u with key %.17g after a "
		      "key %.17g: out of order", q + 1, id, id < N ? key[id] : NAN, last);
		last = key[id];
		key[id] = -1;  /* a second pop of the same item would come out of order */
	}
	LZ_REQUIRE(h->n == 0, "after 10^6 pops the heap holds n = %zu", h->n);
	size_t still = 0, first = 0;
	for (uint32_t id = N; id-- > 0;)
		if (lz_heap_contains(h, id)) {
			still++;
			first = id;
		}
	LZ_REQUIRE(still == 0, "after 10^6 pops %zu items still claim to be in the heap (item %zu: pos = "
	      "%u): a pop must mark its item out, pos = LZ_HEAP_NONE", still, first, h->pos[first]);
	free(key);
	gsl_rng_free(r);
	lz_heap_free(h);
}
END_TEST
