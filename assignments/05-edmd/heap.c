/* YOUR FILE — this is the file you fill in for stage 05-edmd.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/05-edmd/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=05`; see your own code at work with
 * `make lesson STAGE=05`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

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
	LZ_TODO();
}

void lz_heap_sift_down(lz_heap *h, size_t k)
{
	/* Hint: hold the node at k aside; while k has a child (2k + 1 < n), take the
	 * earlier child c (2k + 2 may not exist); stop if the held node is no later than
	 * c, else move c up into k (and write its pos[]), k = c. Put the held node at
	 * the final k. See §4 "The heap". */
	LZ_TODO();
}

void lz_heap_push(lz_heap *h, uint32_t id, double t)
{
	/* Hint: the new node goes at the end, node[n] (write pos[id] too), n grows by
	 * one, and the node sifts up from there. */
	LZ_TODO();
}

uint32_t lz_heap_pop(lz_heap *h)
{
	/* Hint: remember node[0].id and mark it out (pos = LZ_HEAP_NONE); n shrinks by
	 * one; if nodes remain, the last one moves to the root and sifts down. */
	LZ_TODO();
}

void lz_heap_update(lz_heap *h, uint32_t id, double t)
{
	/* Hint: k = pos[id]; write the new key; an earlier key can only break the order
	 * with the parents (sift up), a later one only with the children (sift down).
	 * See §4 "The heap" and §5 "One event per particle; counters, not deletion". */
	LZ_TODO();
}
