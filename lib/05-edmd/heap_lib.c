/* heap_lib.c — allocation, the changes of every key or item, and the invariant check
 * of the indexed heap (lz/heap.h); the sifts are the assignment
 * (solutions/05-edmd/heap.c). */
#include <math.h>
#include <stdlib.h>

#include "lz/bigmem.h"
#include "lz/error.h"
#include "lz/heap.h"

/* Spare nodes in front of node[0]: node[k] then starts at byte 16 (k + front) of a
 * 64-byte aligned block, so that the children of any node share one cache line (a
 * sift down reads one line per level): 1 for the binary heap (2k+1, 2k+2), 3 for the
 * 4-ary (4k+1 .. 4k+4). Behind node[cap - 1]: 1 node, or 3 kept at +INFINITY. */
static size_t front(unsigned arity) { return arity == 4 ? 3 : 1; }
static size_t behind(unsigned arity) { return arity == 4 ? 3 : 1; }

lz_heap *lz_heap_alloc(size_t cap) { return lz_heap_alloc_arity(cap, 2); }

lz_heap *lz_heap_alloc_arity(size_t cap, unsigned arity)
{
	if (cap < 1 || cap >= LZ_HEAP_NONE) {
		lz_error(LZ_EINVAL, "heap capacity %zu must be in [1, %u)", cap, LZ_HEAP_NONE);
		return NULL;
	}
	if (arity != 2 && arity != 4) {
		lz_error(LZ_EINVAL, "heap arity %u must be 2 or 4", arity);
		return NULL;
	}
	lz_heap *h = calloc(1, sizeof *h);
	if (h) {
		h->arity = arity;
		h->node = lz_bigmem_alloc((front(arity) + cap + behind(arity)) * sizeof *h->node);
		if (h->node)
			h->node += front(arity);
		h->pos = lz_bigmem_alloc(cap * sizeof *h->pos);
	}
	if (!h || !h->node || !h->pos) {
		lz_heap_free(h);
		lz_error(LZ_ENOMEM, "no memory for a heap of %zu items", cap);
		return NULL;
	}
	h->cap = cap;
	lz_heap_clear(h);
	return h;
}

void lz_heap_free(lz_heap *h)
{
	if (!h)
		return;
	lz_bigmem_free(h->node ? h->node - front(h->arity) : NULL);
	lz_bigmem_free(h->pos);
	free(h);
}

int lz_heap_resize(lz_heap *h, size_t cap)
{
	if (cap < 1 || cap >= LZ_HEAP_NONE || cap < h->n)
		return lz_error(LZ_EINVAL, "heap capacity %zu must be in [1, %u) and hold its %zu "
		                "nodes", cap, LZ_HEAP_NONE, h->n);
	for (size_t k = 0; k < h->n; k++)
		if (h->node[k].id >= cap)
			return lz_error(LZ_EINVAL, "heap capacity %zu: item %u is in the heap", cap,
			                h->node[k].id);
	size_t f = front(h->arity), b = behind(h->arity), old = h->cap;
	lz_heap_node *node = lz_bigmem_resize(h->node - f, (f + old + b) * sizeof *node,
	                                      (f + cap + b) * sizeof *node);
	if (!node)
		return lz_error(LZ_ENOMEM, "no memory for a heap of %zu items", cap);
	h->node = node + f;
	uint32_t *pos = lz_bigmem_resize(h->pos, old * sizeof *pos, cap * sizeof *pos);
	if (!pos)
		return lz_error(LZ_ENOMEM, "no memory for a heap of %zu items", cap);
	h->pos = pos;
	for (size_t i = old; i < cap; i++)
		pos[i] = LZ_HEAP_NONE;
	for (size_t k = h->n; k < cap + b; k++)  /* past the nodes in use: "never" */
		h->node[k] = (lz_heap_node){INFINITY, 0};
	h->cap = cap;
	return LZ_OK;
}

void lz_heap_clear(lz_heap *h)
{
	h->n = 0;
	for (size_t i = 0; i < h->cap; i++)
		h->pos[i] = LZ_HEAP_NONE;
	for (size_t k = 0; k < h->cap + behind(h->arity); k++)
		h->node[k] = (lz_heap_node){INFINITY, 0};
}

void lz_heap_shift(lz_heap *h, double dt)
{
	for (size_t k = 0; k < h->n; k++)
		h->node[k].t -= dt;
}

void lz_heap_renumber(lz_heap *h, const uint32_t *to)
{
	for (size_t i = 0; i < h->cap; i++)
		h->pos[i] = LZ_HEAP_NONE;
	for (size_t k = 0; k < h->n; k++) {
		h->node[k].id = to[h->node[k].id];
		h->pos[h->node[k].id] = (uint32_t)k;
	}
}

int lz_heap_audit(const lz_heap *h)
{
	if (h->n > h->cap)
		return lz_error(LZ_EDOM, "heap holds %zu nodes, more than its %zu items", h->n, h->cap);
	for (size_t k = 0; k < h->n; k++) {
		uint32_t id = h->node[k].id;
		if (id >= h->cap)
			return lz_error(LZ_EDOM, "heap node %zu holds item %u, beyond the %zu items", k,
			                id, h->cap);
		if (h->pos[id] != k)
			return lz_error(LZ_EDOM, "heap node %zu holds item %u but pos[%u] = %u", k, id,
			                id, h->pos[id]);
		size_t up = (k - 1) / h->arity;
		if (k > 0 && h->node[k].t < h->node[up].t)
			return lz_error(LZ_EDOM,
			                "heap order broken: node %zu (t = %.17g) is earlier than its "
			                "parent %zu (t = %.17g)", k, h->node[k].t, up, h->node[up].t);
	}
	for (size_t k = h->n; h->arity == 4 && k < h->cap + behind(4); k++)
		if (h->node[k].t != INFINITY)
			return lz_error(LZ_EDOM, "4-ary heap: node %zu, past the %zu in use, holds t = "
			                "%.17g, not +INFINITY (a sift would take it for a child)", k,
			                h->n, h->node[k].t);
	size_t in = 0;
	for (size_t i = 0; i < h->cap; i++)
		if (h->pos[i] != LZ_HEAP_NONE) {
			if (h->pos[i] >= h->n || h->node[h->pos[i]].id != i)
				return lz_error(LZ_EDOM, "pos[%zu] = %u points at a node that is not item %zu",
				                i, h->pos[i], i);
			in++;
		}
	if (in != h->n)
		return lz_error(LZ_EDOM, "%zu items claim a place in a heap of %zu nodes", in, h->n);
	return LZ_OK;
}

/* ---- the 4-ary heap ---- */

static void sift_up4(lz_heap *h, size_t k)
{
	lz_heap_node x = h->node[k];
	while (k > 0) {
		size_t up = (k - 1) / 4;
		if (h->node[up].t <= x.t)
			break;
		h->node[k] = h->node[up];
		h->pos[h->node[k].id] = (uint32_t)k;
		k = up;
	}
	h->node[k] = x;
	h->pos[x.id] = (uint32_t)k;
}

static void sift_down4(lz_heap *h, size_t k)
{
	lz_heap_node *node = h->node, x = node[k];
	size_t n = h->n;
	for (;;) {
		size_t c = 4 * k + 1;
		if (c >= n)
			break;
		/* the sixteen grandchildren fill four lines: in a heap too big for the caches,
		 * asked for now so that their misses overlap this level's comparisons */
		if (n >= LZ_HEAP_FAR)
			for (size_t g = 4 * c + 1; g < 4 * c + 17 && g < n; g += 4)
				__builtin_prefetch(&node[g]);
		/* the earliest of four (those past n are at +INFINITY), without a branch */
		size_t a = c + (node[c + 1].t < node[c].t), b = c + 2 + (node[c + 3].t < node[c + 2].t);
		c = node[b].t < node[a].t ? b : a;
		if (x.t <= node[c].t)
			break;
		node[k] = node[c];
		h->pos[node[k].id] = (uint32_t)k;
		k = c;
	}
	node[k] = x;
	h->pos[x.id] = (uint32_t)k;
}

void lz_heap4_push(lz_heap *h, uint32_t id, double t)
{
	size_t k = h->n++;
	h->node[k] = (lz_heap_node){t, id};
	h->pos[id] = (uint32_t)k;
	sift_up4(h, k);
}

void lz_heap4_update(lz_heap *h, uint32_t id, double t)
{
	size_t k = h->pos[id];
	double old = h->node[k].t;
	h->node[k].t = t;
	if (t < old)
		sift_up4(h, k);
	else
		sift_down4(h, k);
}
