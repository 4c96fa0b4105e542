/* nlist.c — Verlet neighbour lists: the all-pairs build, the build from cell lists
 * and the fast refresh from the neighbours of the neighbours, with two copies
 * (graded). */
#include <stddef.h>
#include <stdint.h>

#include "lz/cells.h"
#include "lz/error.h"
#include "lz/lattice.h"
#include "lz/nlist.h"

/* LZ_HELPERS_BEGIN */
/* The minimum-image distance² of particles i and j. */
static int64_t pair_d2(const lz_nlist *nl, const int32_t *r, size_t i, size_t j)
{
	const int32_t *a = r + i * (size_t)nl->dim, *b = r + j * (size_t)nl->dim;
	return lz_lattice_min_dist2(nl->box, a[0] - b[0], a[1] - b[1],
	                            nl->dim == 3 ? a[2] - b[2] : 0);
}
/* LZ_HELPERS_END */

int lz_nlist_build_allpairs(lz_nlist *nl, const int32_t *r)
{
	/* Hint: the target is t = &nl->buf[!nl->cur]; set t->len = 0. For every i:
	 * t->start[i] = t->len, then lz_nbuf_push every j != i whose minimum-image
	 * distance² (lz_lattice_min_dist2(nl->box, dx, dy, dz), dz = 0 in 2D) is below
	 * nl->rl2 — strictly: a pair at exactly r_l is not listed. Finish with
	 * t->start[n] = t->len and flip nl->cur. A failed push returns its status at once
	 * (the list in use stays the old one). See §6 "Verlet's list" in
	 * lessons/04-neighbours/README.md. */
	/* LZ_SOLUTION_BEGIN */
	lz_nbuf *t = &nl->buf[!nl->cur];
	t->len = 0;
	for (size_t i = 0; i < nl->n; i++) {
		t->start[i] = (uint32_t)t->len;
		for (size_t j = 0; j < nl->n; j++) {
			if (j == i || pair_d2(nl, r, i, j) >= nl->rl2)
				continue;
			int st = lz_nbuf_push(t, (uint32_t)j);
			if (st)
				return st;
		}
	}
	t->start[nl->n] = (uint32_t)t->len;
	nl->cur = !nl->cur;
	return LZ_OK;
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	const lz_lattice_box *box = nl->box;
	double reach = lz_lattice_reach(box->kind, nl->rl);
	if (c->shift < 0)
		return lz_error(LZ_EINVAL, "the cells are not a lattice grid (shift = %d): make "
		                "them with lz_cells_alloc_lattice", c->shift);
	if (c->dim != nl->dim || c->side != (double)box->side)
		return lz_error(LZ_EINVAL, "the cells are a %dD grid of side %g, the box is %dD of "
		                "side %d: make the grid for this box", c->dim, c->side, nl->dim,
		                (int)box->side);
	if (c->width < reach)
		return lz_error(LZ_EINVAL, "cells of side %g are narrower than the reach %g of the "
		                "list radius r_l = %g on the %s lattice: a listed pair could sit "
		                "two cells apart; make the grid with a cutoff of at least r_l",
		                c->width, reach, nl->rl, lz_lattice_name(box->kind));
	if (c->n != nl->n)
		return lz_error(LZ_EINVAL, "the cells hold %zu particles, the list is for %zu: bin "
		                "these particles (lz_cells_bin_sites, lz_cells_link) first",
		                c->n, nl->n);
	lz_nbuf *t = &nl->buf[!nl->cur];
	t->len = 0;
	for (size_t i = 0; i < nl->n; i++) {
		t->start[i] = (uint32_t)t->len;
		const uint32_t *block = c->full + (size_t)c->of[i] * (size_t)c->nfull;
		for (int k = 0; k < c->nfull; k++)
			for (int32_t p = c->head[block[k]]; p >= 0; p = c->next[p]) {
				if ((size_t)p == i || pair_d2(nl, r, i, (size_t)p) >= nl->rl2)
					continue;
				int st = lz_nbuf_push(t, (uint32_t)p);
				if (st)
					return st;
			}
	}
	t->start[nl->n] = (uint32_t)t->len;
	nl->cur = !nl->cur;
	return LZ_OK;
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	const lz_nbuf *s = &nl->buf[nl->cur];
	lz_nbuf *t = &nl->buf[!nl->cur];
	uint8_t *mark = nl->mark;
	int st = LZ_OK;
	t->len = 0;
	for (size_t i = 0; i < nl->n; i++) {
		t->start[i] = (uint32_t)t->len;
		size_t a = s->start[i], b = s->start[i + 1];
		/* Every candidate is looked at once: marked when first seen, listed or not. */
		mark[i] = 1;
		for (size_t p = a; p < b && st == LZ_OK; p++) {
			uint32_t j = s->idx[p];
			if (!mark[j]) {
				mark[j] = 1;
				if (pair_d2(nl, r, i, j) < nl->rl2)
					st = lz_nbuf_push(t, j);
			}
		}
		for (size_t p = a; p < b && st == LZ_OK; p++) {
			uint32_t j = s->idx[p];
			for (size_t q = s->start[j]; q < s->start[j + 1] && st == LZ_OK; q++) {
				uint32_t m = s->idx[q];
				if (!mark[m]) {
					mark[m] = 1;
					if (pair_d2(nl, r, i, m) < nl->rl2)
						st = lz_nbuf_push(t, m);
				}
			}
		}
		/* The same walk again clears exactly the marks set. */
		mark[i] = 0;
		for (size_t p = a; p < b; p++) {
			uint32_t j = s->idx[p];
			mark[j] = 0;
			for (size_t q = s->start[j]; q < s->start[j + 1]; q++)
				mark[s->idx[q]] = 0;
		}
		if (st)
			return st;
	}
	t->start[nl->n] = (uint32_t)t->len;
	nl->cur = !nl->cur;
	return LZ_OK;
	/* LZ_SOLUTION_END */
}
