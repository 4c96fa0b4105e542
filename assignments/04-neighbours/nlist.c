/* YOUR FILE — this is the file you fill in for stage 04-neighbours.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/04-neighbours/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=04`; see your own code at work with
 * `make lesson STAGE=04`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* nlist.c — Verlet neighbour lists: the all-pairs build, the build from cell lists
 * and the fast refresh from the neighbours of the neighbours, with two copies
 * (graded). */
#include <stddef.h>
#include <stdint.h>

#include "lz/cells.h"
#include "lz/error.h"
#include "lz/lattice.h"
#include "lz/nlist.h"


int lz_nlist_build_allpairs(lz_nlist *nl, const int32_t *r)
{
	/* Hint: the target is t = &nl->buf[!nl->cur]; set t->len = 0. For every i:
	 * t->start[i] = t->len, then lz_nbuf_push every j != i whose minimum-image
	 * distance² (lz_lattice_min_dist2(nl->box, dx, dy, dz), dz = 0 in 2D) is below
	 * nl->rl2 — strictly: a pair at exactly r_l is not listed. Finish with
	 * t->start[n] = t->len and flip nl->cur. A failed push returns its status at once
	 * (the list in use stays the old one). See §6 "Verlet's list" in
	 * lessons/04-neighbours/README.md. */
	LZ_TODO();
}

int lz_nlist_build_cells(lz_nlist *nl, const lz_cells *c, const int32_t *r)
{
	/* Hint: first refuse a grid that cannot give the right list, each with
	 * return lz_error(LZ_EINVAL, "...") saying what is wrong: not a lattice grid
	 * (c->shift < 0); another dimension (c->dim) or side (c->side) than nl->box;
	 * cells narrower than lz_lattice_reach(nl->box->kind, nl->rl) (c->width); not
	 * binned on these n particles (c->n != nl->n). Then fill the target as in the
	 * all-pairs build, but for row i look only at the cells of its block:
	 * c->full[c->of[i] · c->nfull + k] for k < c->nfull, and in each the linked list
	 * p = c->head[cell], p = c->next[p], ... until -1. Why can no partner hide farther
	 * away, and why is no one found twice? See §7 "Lists from cells" in
	 * lessons/04-neighbours/README.md. */
	LZ_TODO();
}

int lz_nlist_refresh(lz_nlist *nl, const int32_t *r)
{
	/* Hint: read only the source s = &nl->buf[nl->cur]; write the target
	 * t = &nl->buf[!nl->cur] as the builds do. Row i's candidates are the j on i's
	 * source row and the m on the source rows of those j (even a j that has moved away
	 * from i: its row may hold i's new neighbour — thesis fig. 2.7). Take a candidate
	 * when it is not i, is not on the row already, and its distance² is below rl2. For
	 * "not i, not already" use nl->mark: set mark[i] and the mark of every candidate
	 * you have looked at, test it before looking, and set every mark you used back to
	 * 0 before the next row (mark[] must be all 0 between calls, also after an
	 * error). See §8 "The fast refresh and its two copies" in
	 * lessons/04-neighbours/README.md. */
	LZ_TODO();
}
