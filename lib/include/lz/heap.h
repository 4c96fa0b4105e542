/* lz/heap.h — an indexed binary min-heap: one key (an event time) per item, the
 * smallest on top, and a position index so that an item's key can be changed without
 * searching for it (Miller & Luding, J. Comput. Phys. 193, 306 (2004), §II: one event
 * per particle, in an implicit heap).
 *
 * Items are the integers 0 .. cap-1 (particle numbers). The heap is an array of nodes
 * node[0 .. n-1], each {t, id}, in which every node is no later than its two children:
 *     node[k].t <= node[2k+1].t  and  node[k].t <= node[2k+2].t      (heap order)
 * so node[0] is the earliest. pos[] is the index the other way round:
 *     node[pos[id]].id == id for every id in the heap, pos[id] == LZ_HEAP_NONE otherwise.
 * Every function below keeps both invariants; a function that moves a node writes
 * its new pos[] at once.
 *
 * The key sits in the node, next to the id, rather than in a separate event table:
 * a sift compares keys along one path of the tree, and with the key inline each
 * comparison reads the node it is about to move anyway (16 bytes, 4 to a cache
 * line) instead of jumping to a particle's record.
 *
 * Ties: two equal keys may come out in either order; the event loop does not care.
 * Keys are finite doubles or +INFINITY ("never"); NaN is not a key.
 *
 * Cost: peek O(1); push, pop and update O(log n) — at most log2(n) levels, one
 * comparison (sift up) or two (sift down) per level. Memory: 16 bytes per node and
 * 4 per item for pos.
 */
#ifndef LZ_HEAP_H
#define LZ_HEAP_H

#include <stddef.h>
#include <stdint.h>

/* From this many nodes on (512 KB, beyond what a core's L2 cache keeps of it) sift
 * down prefetches the levels below it; below, that would only cost instructions. */
#define LZ_HEAP_FAR 32768

/* pos[id] of an item that is not in the heap. */
#define LZ_HEAP_NONE UINT32_MAX

typedef struct {
	double t;     /* the key: the time of the item's event */
	uint32_t id;  /* the item (a particle number) */
} lz_heap_node;

typedef struct {
	size_t n;            /* nodes in the heap */
	size_t cap;          /* items 0 .. cap-1 may be pushed */
	lz_heap_node *node;  /* node[0 .. n-1] in heap order; the array has cap + 1 nodes,
	                        so node[n] can always be read (its value means nothing) —
	                        cap + 3 with arity 4, and node[n .. cap+2].t = +INFINITY */
	uint32_t *pos;       /* pos[id]: where id is in node[], or LZ_HEAP_NONE */
	unsigned arity;      /* children per node: 2 (the graded heap below) or 4 (the
	                        library's lz_heap4_*) */
} lz_heap;

/* An empty binary heap for the items 0 .. cap-1 (1 <= cap < 2^32 - 1), every pos[]
 * NONE. NULL with lz_error (LZ_EINVAL, LZ_ENOMEM) on failure. O(cap). */
lz_heap *lz_heap_alloc(size_t cap);

/* The same with `arity` children per node: 2, or 4 (see "The 4-ary heap" below). */
lz_heap *lz_heap_alloc_arity(size_t cap, unsigned arity);
void lz_heap_free(lz_heap *h);

/* Empty h again (every item out). O(cap). */
void lz_heap_clear(lz_heap *h);

/* The earliest item and its key: precondition h->n > 0. O(1). */
static inline uint32_t lz_heap_top(const lz_heap *h) { return h->node[0].id; }
static inline double lz_heap_top_t(const lz_heap *h) { return h->node[0].t; }

/* 1 when id is in the heap. O(1). */
static inline int lz_heap_contains(const lz_heap *h, uint32_t id)
{
	return id < h->cap && h->pos[id] != LZ_HEAP_NONE;
}

/* The key of item id: precondition lz_heap_contains(h, id). O(1). */
static inline double lz_heap_key(const lz_heap *h, uint32_t id) { return h->node[h->pos[id]].t; }

/* The items most likely to come out next after the top, for a caller that fetches
 * their data ahead: the root's earlier child (*second), and the earlier of that
 * child's sibling and its own earlier child (*third). A guess — a new key may come
 * first — that reads no more than the root's two levels below. Precondition
 * h->n >= 7 (lz_heap_nodes_next: the same on any binary heap of 7 nodes or more,
 * node[0] its root). O(1). */
static inline void lz_heap_nodes_next(const lz_heap_node *node, uint32_t *second,
                                      uint32_t *third)
{
	size_t k1 = 1 + (node[2].t < node[1].t), k2 = k1 == 1 ? 2 : 1;
	size_t kc = 2 * k1 + 1 + (node[2 * k1 + 2].t < node[2 * k1 + 1].t);
	*second = node[k1].id;
	*third = node[kc].t < node[k2].t ? node[kc].id : node[k2].id;
}
static inline void lz_heap_next_items(const lz_heap *h, uint32_t *second, uint32_t *third)
{
	lz_heap_nodes_next(h->node, second, third);
}

/* Ask the memory for item id's node (precondition: in the heap), or for its place in
 * pos[], ahead of an update. A hint: nothing is read or written. */
static inline void lz_heap_prefetch_node(const lz_heap *h, uint32_t id)
{
	__builtin_prefetch(&h->node[h->pos[id]]);
}
static inline void lz_heap_prefetch_pos(const lz_heap *h, uint32_t id)
{
	__builtin_prefetch(&h->pos[id]);
}

/* ---- graded (solutions/05-edmd/heap.c) ---- */

/* Move the node at index k up (towards the root) while it is earlier than its parent
 * (k - 1) / 2, swapping the two and updating pos[] of both. Precondition: heap order
 * holds everywhere except, possibly, between k and its ancestors. O(log n). */
void lz_heap_sift_up(lz_heap *h, size_t k);

/* Move the node at index k down while it is later than the earlier of its children
 * 2k+1, 2k+2 (those < n), swapping it with that child and updating pos[] of both.
 * Precondition: heap order holds everywhere except, possibly, between k and its
 * descendants. O(log n). */
void lz_heap_sift_down(lz_heap *h, size_t k);

/* Insert item id (< cap, not in the heap) with key t: a new last node, sifted up.
 * O(log n). */
void lz_heap_push(lz_heap *h, uint32_t id, double t);

/* Remove the earliest node and return its id (its pos[] becomes NONE): the last node
 * moves to the root and sifts down. Precondition: h->n > 0. O(log n). */
uint32_t lz_heap_pop(lz_heap *h);

/* Give item id (in the heap) the key t: the node sifts up if t is earlier than
 * before, down if later. This is how an event is replaced — no deletion, no search:
 * pos[id] says where the node is. O(log n). */
void lz_heap_update(lz_heap *h, uint32_t id, double t);

/* ---- changes of every key or item (library) ---- */

/* Subtract dt from every key: the order is unchanged (up to ties that round together,
 * which the heap allows). For re-basing a clock. O(n). */
void lz_heap_shift(lz_heap *h, double dt);

/* Rename every item: the item id becomes to[id] (to: a permutation of 0 .. cap-1),
 * keys and order unchanged, pos[] rebuilt. O(cap). */
void lz_heap_renumber(lz_heap *h, const uint32_t *to);

/* Room for the items 0 .. cap-1 (1 <= cap < 2^32 - 1), more or fewer than before, the
 * nodes and their order as they were: every item in the heap must be below cap. The
 * new items are not in the heap. For a system whose particles change in number (a
 * rank of lz/pedmd.h that meets particles, or hands them over). LZ_OK, or LZ_EINVAL /
 * LZ_ENOMEM with h unchanged. O(cap + n). */
int lz_heap_resize(lz_heap *h, size_t cap);

/* ---- checks (library) ---- */

/* LZ_OK when heap order and the pos[] index hold (every node no earlier than its
 * parent (k - 1) / arity, node ids distinct and < cap, pos[] consistent both ways,
 * n <= cap; with arity 4 the nodes past n at +INFINITY); else LZ_EDOM with lz_error
 * naming the first broken node. O(cap). For tests and guards. */
int lz_heap_audit(const lz_heap *h);

/* ---- the 4-ary heap (library) ----
 *
 * The same indexed heap with four children per node: node k's are 4k+1 .. 4k+4, its
 * parent (k - 1) / 4. Half as many levels as the binary heap, and the four children
 * of a node fill one cache line (the array starts three nodes early, so that node 1
 * begins a line): a sift down reads one line per level and picks the earliest of four
 * in three comparisons; a sift up compares with half as many parents. In a heap that
 * outgrows the caches the levels are the misses, so halving them pays (lesson 05
 * §10); in a small one the extra comparisons cost about what they save. The nodes
 * past n are kept at +INFINITY, so that a sift reads four children without asking
 * which exist. Only these functions and the library ones above (top, contains, key,
 * clear, shift, renumber, audit) may touch a heap of arity 4. */

/* Insert item id (< cap, not in the heap) with key t. O(log4 n). */
void lz_heap4_push(lz_heap *h, uint32_t id, double t);

/* Give item id (in the heap) the key t: up or down as for lz_heap_update. O(log4 n). */
void lz_heap4_update(lz_heap *h, uint32_t id, double t);

/* As lz_heap_next_items for the 4-ary heap: the earliest child of the root, and the
 * earlier of its siblings' earliest and its own earliest child. Precondition
 * h->n >= 21. O(1). */
static inline void lz_heap4_next_items(const lz_heap *h, uint32_t *second, uint32_t *third)
{
	const lz_heap_node *node = h->node;
	size_t a = 1 + (node[2].t < node[1].t), b = 3 + (node[4].t < node[3].t);
	size_t k1 = node[b].t < node[a].t ? b : a;  /* the earliest child of the root */
	size_t s = k1 == a ? b : a;                 /* the earlier of the other pair */
	size_t c = 4 * k1 + 1, ca = c + (node[c + 1].t < node[c].t),
	       cb = c + 2 + (node[c + 3].t < node[c + 2].t);
	size_t kc = node[cb].t < node[ca].t ? cb : ca;
	size_t sib = ((k1 - 1) ^ 1) + 1;  /* k1's partner in its pair: 1-2, 3-4 */
	if (node[sib].t < node[s].t)
		s = sib;
	*second = node[k1].id;
	*third = node[kc].t < node[s].t ? node[kc].id : node[s].id;
}

#endif
