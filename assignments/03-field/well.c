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

/* well.c — the square-well attraction: the Metropolis acceptance tabulated per
 * integer change of the partner count, that change read off the well field in O(1),
 * and the Metropolis move that keeps both fields painted (graded). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lz/error.h"
#include "lz/well.h"


/* Gaining partners lowers the energy: always accepted. exp() only for losses, so a
 * huge depth / temperature underflows to 0 instead of overflowing. */
void lz_well_table(lz_well *w)
{
	/* Hint: for every k from -LZ_WELL_KMAX to LZ_WELL_KMAX, accept[k + LZ_WELL_KMAX]
	 * is the Metropolis probability of a step that changes the number of partners by
	 * k: the energy changes by ΔE = -depth · k, so it is min(1, exp(-ΔE / kT)). Set the
	 * entries for k >= 0 to exactly 1 (no exp() needed: the table is then read as
	 * "accept without a draw"). See the square-well section of
	 * lessons/03-field/README.md. */
	LZ_TODO();
}

/* Two look-ups: the partners at the target minus those at the centre, each count
 * corrected for i's own well. */
int lz_well_delta(const lz_well *w, const lz_field *f, size_t i, int d)
{
	/* Hint: c = r[i], t = c + dirs[d] (w->shape->dirs; lz_field_index wraps). The
	 * well cell at c counts i itself, so i has cell[c] - 1 partners now; at t it
	 * would have cell[t] - w->shape->self[d] (i's own well covers t only when
	 * self[d] is 1). Return the difference, new minus old. The hard core is not
	 * looked at. See the square-well section of lessons/03-field/README.md. */
	LZ_TODO();
}

/* The O(1) hard-core test first, and a random number only where the outcome is
 * uncertain (accept < 1): a step the hard core refuses, or one that is accepted for
 * sure, costs no draw. */
int lz_field_try_move(lz_field *f, lz_well *w, size_t i, int d, gsl_rng *rng)
{
	/* Hint: return 0 at once if lz_field_can_move(f, i, d) says no. With a well, look
	 * up a = w->accept[lz_well_delta(w, f, i, d) + LZ_WELL_KMAX]; only when a < 1
	 * draw u = gsl_rng_uniform(rng), and refuse (return 0) unless u < a. Then repaint
	 * the well from the OLD centre (+1 on w->shape->head[d], -1 on tail[d], nmove[d]
	 * points each, wrapped with lz_field_index) and only then lz_field_move(f, i, d),
	 * which moves the centre. Return 1. See the square-well section of
	 * lessons/03-field/README.md. */
	LZ_TODO();
}
