/* YOUR FILE — this is the file you fill in for stage 02-lattice.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/02-lattice/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=02`; see your own code at work with
 * `make lesson STAGE=02`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

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
	LZ_TODO();
}

/* Random walk: a fresh direction every step. Ballistic: the same direction until a
 * collision, then a fresh one. */
size_t lz_walk_sweep(lz_walk *w, gsl_rng *rng)
{
	/* Hint: for i = 0 .. n-1 in order. Random walk: dir[i] = gsl_rng_uniform_int(rng,
	 * ndir), then try the move. Ballistic: try dir[i]; only if it is rejected draw a
	 * new dir[i]. Return how many moves were accepted. The thesis's driver loop is in
	 * lessons/02-lattice/README.md §6. */
	LZ_TODO();
}
