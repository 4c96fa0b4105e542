/* heap_lib.c — allocation, the changes of every key or item, and the invariant check
 * of the indexed heap (lz/heap.h); the sifts are the assignment
 * (solutions/05-edmd/heap.c). */
#include <math.h>
#include <stdlib.h>

#include "lz/bigmem.h"
#include "lz/error.h"
#include "lz/heap.h"

lz_heap *lz_heap_alloc(size_t cap)
{
	if (cap < 1 || cap >= LZ_HEAP_NONE) {
		lz_error(LZ_EINVAL, "heap capacity %zu must be in [1, %u)", cap, LZ_HEAP_NONE);
		return NULL;
	}
	lz_heap *h = calloc(1, sizeof *h);
	if (h) {
		/* One spare node in front: node[k] then starts at byte 16 (k + 1) of a
		 * 64-byte aligned block, so the two children 2k+1 and 2k+2 of any node
		 * share one cache line (a sift down reads one line per level, not 1.5). */
		h->node = lz_bigmem_alloc((cap + 2) * sizeof *h->node);
		if (h->node)
			h->node++;
		h->pos = lz_bigmem_alloc(cap * sizeof *h->pos);
	}
	if (!h || !h->node || !h->pos) {
		lz_heap_free(h);
		lz_error(LZ_ENOMEM, "no memory for a heap of %zu items", cap);
		return NULL;
	}
	h->cap = cap;
	for (size_t k = 0; k <= cap; k++)
		h->node[k] = (lz_heap_node){INFINITY, 0};
	lz_heap_clear(h);
	return h;
}

void lz_heap_free(lz_heap *h)
{
	if (!h)
		return;
	lz_bigmem_free(h->node ? h->node - 1 : NULL);
	lz_bigmem_free(h->pos);
	free(h);
}

void lz_heap_clear(lz_heap *h)
{
	h->n = 0;
	for (size_t i = 0; i < h->cap; i++)
		h->pos[i] = LZ_HEAP_NONE;
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
		if (k > 0 && h->node[k].t < h->node[(k - 1) / 2].t)
			return lz_error(LZ_EDOM,
			                "heap order broken: node %zu (t = %.17g) is earlier than its "
			                "parent %zu (t = %.17g)",
			                k, h->node[k].t, (k - 1) / 2, h->node[(k - 1) / 2].t);
	}
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
