/* heap.c — the indexed binary min-heap of the event loop: sift up, sift down, push,
 * pop and update, each keeping the position index pos[] in step (graded). */
#include <stddef.h>
#include <stdint.h>

#include "lz/heap.h"

void lz_heap_sift_up(lz_heap *h, size_t k)
{
	/* Hint: hold the node at k aside; while k > 0 and its parent (k - 1) / 2 is
	 * later, move the parent down into k (and write its new pos[]), k = parent. Put
	 * the held node at the final k and write its pos[]. Moving parents down instead
	 * of swapping halves the writes. See §4 "The heap" in lessons/05-edmd/README.md. */
	/* LZ_SOLUTION_BEGIN */
	lz_heap_node x = h->node[k];
	while (k > 0) {
		size_t up = (k - 1) / 2;
		if (h->node[up].t <= x.t)
			break;
		h->node[k] = h->node[up];
		h->pos[h->node[k].id] = (uint32_t)k;
		k = up;
	}
	h->node[k] = x;
	h->pos[x.id] = (uint32_t)k;
	/* LZ_SOLUTION_END */
}

void lz_heap_sift_down(lz_heap *h, size_t k)
{
	/* Hint: hold the node at k aside; while k has a child (2k + 1 < n), take the
	 * earlier child c (2k + 2 may not exist); stop if the held node is no later than
	 * c, else move c up into k (and write its pos[]), k = c. Put the held node at
	 * the final k. See §4 "The heap". */
	/* LZ_SOLUTION_BEGIN */
	lz_heap_node x = h->node[k];
	size_t n = h->n;
	for (;;) {
		size_t c = 2 * k + 1;
		if (c >= n)
			break;
		/* the four grandchildren 4k+3 .. 4k+6 fill one cache line, the eight
		 * great-grandchildren two, the sixteen below them four (lz_heap_alloc): in
		 * a heap too big for the caches, ask for them now, so that the misses of
		 * the next three levels overlap the work of this one */
		if (n >= LZ_HEAP_FAR)
			for (size_t g = 4 * k + 3, w = 4; w <= 16; g = 2 * g + 1, w *= 2)
				for (size_t l = 0; l < w; l += 4)
					__builtin_prefetch(&h->node[g + l < n ? g + l : k]);
		/* the earlier child, chosen without a branch (a coin toss the predictor
		 * would miss half the time): node[c + 1] may be read even when c + 1 = n,
		 * because the array has a spare node (lz_heap_alloc), and is then ignored */
		c += (h->node[c + 1].t < h->node[c].t) & (c + 1 < n);
		if (x.t <= h->node[c].t)
			break;
		h->node[k] = h->node[c];
		h->pos[h->node[k].id] = (uint32_t)k;
		k = c;
	}
	h->node[k] = x;
	h->pos[x.id] = (uint32_t)k;
	/* LZ_SOLUTION_END */
}

void lz_heap_push(lz_heap *h, uint32_t id, double t)
{
	/* Hint: the new node goes at the end, node[n] (write pos[id] too), n grows by
	 * one, and the node sifts up from there. */
	/* LZ_SOLUTION_BEGIN */
	size_t k = h->n++;
	h->node[k].t = t;
	h->node[k].id = id;
	h->pos[id] = (uint32_t)k;
	lz_heap_sift_up(h, k);
	/* LZ_SOLUTION_END */
}

uint32_t lz_heap_pop(lz_heap *h)
{
	/* Hint: remember node[0].id and mark it out (pos = LZ_HEAP_NONE); n shrinks by
	 * one; if nodes remain, the last one moves to the root and sifts down. */
	/* LZ_SOLUTION_BEGIN */
	uint32_t id = h->node[0].id;
	h->pos[id] = LZ_HEAP_NONE;
	if (--h->n > 0) {
		h->node[0] = h->node[h->n];
		h->pos[h->node[0].id] = 0;
		lz_heap_sift_down(h, 0);
	}
	return id;
	/* LZ_SOLUTION_END */
}

void lz_heap_update(lz_heap *h, uint32_t id, double t)
{
	/* Hint: k = pos[id]; write the new key; an earlier key can only break the order
	 * with the parents (sift up), a later one only with the children (sift down).
	 * See §4 "The heap" and §5 "One event per particle; counters, not deletion". */
	/* LZ_SOLUTION_BEGIN */
	size_t k = h->pos[id];
	double old = h->node[k].t;
	h->node[k].t = t;
	if (t < old)
		lz_heap_sift_up(h, k);
	else
		lz_heap_sift_down(h, k);
	/* LZ_SOLUTION_END */
}
