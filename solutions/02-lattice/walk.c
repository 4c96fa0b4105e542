/* walk.c — one ensemble step of hard disks walking on a lattice (graded). */
#include <stddef.h>
#include <stdint.h>

#include "lz/error.h"
#include "lz/walk.h"

/* The walls first (one comparison), then all pairs: the new site against every other
 * particle's current site. */
int lz_walk_try_move(lz_walk *w, size_t i, int d)
{
	/* Hint: the new site is r[i] + dirs[d], each coordinate wrapped with & mask (as
	 * uint32_t, so that -1 becomes L - 1). A slit's walls forbid it when its last
	 * coordinate fails lz_walk_row_allowed (reject before any pair). Compare it with every particle j != i by
	 * lz_lattice_min_dist2(w->box, dx, dy, dz): below w->sigma2 is an overlap and the
	 * move is rejected. Touching (d2 == sigma2) is allowed. Count the offer in
	 * w->moves, an acceptance in w->accepted. See the walkers section of
	 * lessons/02-lattice/README.md §6. */
	/* LZ_SOLUTION_BEGIN */
	int dim = w->dim;
	uint32_t m = (uint32_t)w->box->mask;
	int32_t *p = w->r + i * (size_t)dim;
	lz_site s = w->dirs[d];
	int32_t nx = (int32_t)((uint32_t)(p[0] + s.x) & m);
	int32_t ny = (int32_t)((uint32_t)(p[1] + s.y) & m);
	int32_t nz = dim == 3 ? (int32_t)((uint32_t)(p[2] + s.z) & m) : 0;
	w->moves++;
	if (!lz_walk_row_allowed(w, dim == 3 ? nz : ny))
		return 0;
	for (size_t j = 0; j < w->n; j++) {
		if (j == i)
			continue;
		const int32_t *q = w->r + j * (size_t)dim;
		if (lz_lattice_min_dist2(w->box, nx - q[0], ny - q[1],
		                         dim == 3 ? nz - q[2] : 0) < w->sigma2)
			return 0;
	}
	p[0] = nx;
	p[1] = ny;
	if (dim == 3)
		p[2] = nz;
	w->accepted++;
	return 1;
	/* LZ_SOLUTION_END */
}

/* Random walk: a fresh direction every step. Ballistic: the same direction until a
 * collision, then a fresh one. */
size_t lz_walk_sweep(lz_walk *w, gsl_rng *rng)
{
	/* Hint: for i = 0 .. n-1 in order. Random walk: dir[i] = gsl_rng_uniform_int(rng,
	 * ndir), then try the move. Ballistic: try dir[i]; only if it is rejected draw a
	 * new dir[i]. Return how many moves were accepted. The thesis's driver loop is in
	 * lessons/02-lattice/README.md §6. */
	/* LZ_SOLUTION_BEGIN */
	size_t accepted = 0;
	unsigned long ndir = (unsigned long)w->ndir;
	for (size_t i = 0; i < w->n; i++) {
		if (w->motion == LZ_WALK_RANDOM)
			w->dir[i] = (int)gsl_rng_uniform_int(rng, ndir);
		if (lz_walk_try_move(w, i, w->dir[i]))
			accepted++;
		else if (w->motion == LZ_WALK_BALLISTIC)
			w->dir[i] = (int)gsl_rng_uniform_int(rng, ndir);
	}
	return accepted;
	/* LZ_SOLUTION_END */
}
