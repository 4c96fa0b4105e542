/* YOUR FILE — this is the file you fill in for stage 03-field.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/03-field/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=03`; see your own code at work with
 * `make lesson STAGE=03`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* field.c — painting particles into a byte field, the O(1) collision test, the
 * head/tail move and random sequential adsorption to exact jamming (graded). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/field.h"


/* Check for a byte at its limit before touching anything, so a refused placement
 * leaves the field as it was. */
int lz_field_place(lz_field *f, lz_site c)
{
	/* Hint: wrap c with & mask (as uint32_t). First pass over the excluded shape
	 * (f->excl->pts, offsets from c, wrapped with lz_field_index): if some cell is
	 * already 255, return lz_error(LZ_EPHYS, ...) and change nothing. Then make room
	 * with lz_field_reserve(f, n + 1), store the centre as particle n, and add 1 to
	 * every cell of the shape; a cell going from 0 to 1 is one free site less (nfree).
	 * See lessons/03-field/README.md. */
	LZ_TODO();
}

int lz_field_remove(lz_field *f, size_t i)
{
	/* Hint: LZ_EINVAL (lz_error naming i and n) if i >= n. Subtract 1 on every cell
	 * of particle i's excluded shape (a cell reaching 0 is a free site more), then copy
	 * the last particle's centre into slot i and decrease n. */
	LZ_TODO();
}

int lz_field_is_free(const lz_field *f, lz_site s)
{
	/* Hint: one look-up, f->cell[lz_field_index(f, s.x, s.y, s.z)] == 0. Nothing
	 * else: the field already knows every particle's excluded area. */
	LZ_TODO();
}

/* The target may hold exactly the particle's own coverage and nothing more. */
int lz_field_can_move(const lz_field *f, size_t i, int d)
{
	/* Hint: t = r[i] + dirs[d]. The particle's own shape covers t when
	 * f->excl->self[d] is 1; so the step is free iff cell[t] == self[d]. Why not
	 * cell[t] <= 1? Read the header lz/field.h: when self[d] is 0 (tiny particles), a
	 * 1 at t belongs to a neighbour. */
	LZ_TODO();
}

/* Heads before tails: a cell never dips below zero, even for a tiny shape. */
void lz_field_move(lz_field *f, size_t i, int d)
{
	/* Hint: add 1 at the head points and subtract 1 at the tail points of direction d
	 * (f->excl->head[d], tail[d], nmove[d] each, offsets from the OLD centre), keeping
	 * nfree; only then move r[i] by dirs[d], wrapped with & mask. The body of the shape
	 * is not touched: that is the point of the method (thesis fig. 2.9). */
	LZ_TODO();
}

/* Random draws while they succeed often; an exact list of the free sites once they
 * no longer do. Both pick a uniform free site, so the statistics do not change. */
int lz_field_rsa(lz_field *f, gsl_rng *rng, size_t target, int *jammed)
{
	/* Hint: loop while nfree > 0 and (target == 0 or n < target). Phase 1, while
	 * nfree >= L^dim / 16 (the box's sites, not nsites): draw x, y (and z) with
	 * gsl_rng_uniform_int(rng, L); if lz_field_is_free, lz_field_place it.
	 * Phase 2: scan the field once into an array
	 * of the free sites' coordinates (or indices); draw an entry k with
	 * gsl_rng_uniform_int(rng, m); if its site is no longer free, overwrite it with the
	 * last entry and shrink m; else place there. Count every draw in f->tries. Never
	 * stop because "many tries failed": only nfree == 0 means jammed. Set *jammed at
	 * the end. See lessons/03-field/README.md. */
	LZ_TODO();
}
