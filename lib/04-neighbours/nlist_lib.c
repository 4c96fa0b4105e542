/* nlist_lib.c — the storage of Verlet neighbour lists, the one-copy refresh kept to
 * show how it loses particles, and the brute-force audit (lz/nlist.h). The builds and
 * the two-copy refresh are graded (solutions/04-neighbours/nlist.c). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/nlist.h"

lz_nlist *lz_nlist_alloc(const lz_lattice_box *box, size_t n, double rl)
{
	if (!box)
		return lz_error(LZ_EINVAL, "a neighbour list needs a box (box = NULL)"), NULL;
	if (n == 0 || n > (size_t)INT32_MAX)
		return lz_error(LZ_EINVAL, "n = %zu particles: a neighbour list takes 1 <= n <= %ld",
		                n, (long)INT32_MAX), NULL;
	double half = box->side / 2.0;
	if (!(rl > 0) || !isfinite(rl))
		return lz_error(LZ_EINVAL, "list radius rl = %g lattice units must be positive and "
		                "finite; allowed 0 < rl <= %g (half the box)", rl, half), NULL;
	if (rl > half)
		return lz_error(LZ_EINVAL, "list radius rl = %g lattice units is a cutoff larger "
		                "than half the box (L = %d): a pair could then be within r_l "
		                "through two periodic images at once; allowed 0 < rl <= %g",
		                rl, (int)box->side, half), NULL;
	lz_nlist *nl = calloc(1, sizeof *nl);
	if (!nl)
		return lz_error(LZ_ENOMEM, "no memory for a neighbour list"), NULL;
	nl->box = box;
	nl->dim = box->dim;
	nl->n = n;
	nl->rl = rl;
	nl->rl2 = (int64_t)ceil(rl * rl);
	nl->buf[0].start = calloc(n + 1, sizeof(uint32_t));
	nl->buf[1].start = calloc(n + 1, sizeof(uint32_t));
	nl->mark = calloc(n, 1);
	if (!nl->buf[0].start || !nl->buf[1].start || !nl->mark) {
		lz_nlist_free(nl);
		return lz_error(LZ_ENOMEM, "no memory for the neighbour lists of %zu particles", n),
		       NULL;
	}
	return nl;
}

void lz_nlist_free(lz_nlist *nl)
{
	if (!nl)
		return;
	for (int k = 0; k < 2; k++) {
		free(nl->buf[k].start);
		free(nl->buf[k].idx);
	}
	free(nl->mark);
	free(nl);
}

size_t lz_nlist_entries(const lz_nlist *nl)
{
	return nl->buf[nl->cur].len;
}

size_t lz_nlist_bytes(const lz_nlist *nl)
{
	return 2 * (nl->n + 1) * sizeof(uint32_t) +
	       (nl->buf[0].cap + nl->buf[1].cap) * sizeof(uint32_t) + nl->n;
}

/* Minimum-image distance² of particles i and j. */
static int64_t pair_d2(const lz_nlist *nl, const int32_t *r, size_t i, size_t j)
{
	const int32_t *a = r + i * (size_t)nl->dim, *b = r + j * (size_t)nl->dim;
	return lz_lattice_min_dist2(nl->box, a[0] - b[0], a[1] - b[1],
	                            nl->dim == 3 ? a[2] - b[2] : 0);
}

/* Rewriting the rows in place, in index order, is the same as writing them in order
 * into the other copy while reading every row j < i there (it has been rewritten
 * already) and every row j >= i in the old copy (it still stands as it was). That is
 * what happens here: the old copy is only a picture of the rows not yet rewritten. */
int lz_nlist_refresh_single(lz_nlist *nl, const int32_t *r)
{
	const lz_nbuf *s = &nl->buf[nl->cur];
	lz_nbuf *t = &nl->buf[!nl->cur];
	uint8_t *mark = nl->mark;
	int st = LZ_OK;
	t->len = 0;
	for (size_t i = 0; i < nl->n && st == LZ_OK; i++) {
		t->start[i] = (uint32_t)t->len;
		mark[i] = 1;
		/* Row i keeps its entries still within r_l... */
		for (size_t p = s->start[i]; p < s->start[i + 1] && st == LZ_OK; p++) {
			uint32_t j = s->idx[p];
			if (!mark[j] && pair_d2(nl, r, i, j) < nl->rl2) {
				mark[j] = 1;
				st = lz_nbuf_push(t, j);
			}
		}
		/* ...then takes from the rows, as they stand now, of those it kept. The kept
		 * entries are t->idx[t->start[i] .. kept); indices, not pointers: a push may
		 * move t->idx. */
		size_t kept = t->len;
		for (size_t q = t->start[i]; q < kept && st == LZ_OK; q++) {
			uint32_t j = t->idx[q];
			const lz_nbuf *b = j < i ? t : s;
			for (size_t p = b->start[j]; p < b->start[j + 1] && st == LZ_OK; p++) {
				uint32_t m = b->idx[p];
				if (!mark[m] && pair_d2(nl, r, i, m) < nl->rl2) {
					mark[m] = 1;
					st = lz_nbuf_push(t, m);
				}
			}
		}
		mark[i] = 0;
		for (size_t q = t->start[i]; q < t->len; q++)
			mark[t->idx[q]] = 0;
	}
	if (st != LZ_OK)
		return st;
	t->start[nl->n] = (uint32_t)t->len;
	nl->cur = !nl->cur;
	return LZ_OK;
}

int lz_nlist_audit(const lz_nlist *nl, const int32_t *r, int64_t r2, lz_nlist_audit_report *rep)
{
	*rep = (lz_nlist_audit_report){0};
	size_t n = nl->n;
	uint8_t *on = calloc(n, 1);  /* on[j] = 1: j is on the row being checked */
	if (!on)
		return lz_error(LZ_ENOMEM, "no memory to audit the lists of %zu particles", n);
	const lz_nbuf *b = &nl->buf[nl->cur];
	for (size_t i = 0; i < n; i++) {
		size_t len;
		const uint32_t *row = lz_nlist_row(nl, i, &len);
		for (size_t k = 0; k < len; k++) {
			uint32_t j = row[k];
			if (j == i) {
				rep->self++;
				continue;
			}
			if (on[j]) {
				rep->duplicates++;
				continue;
			}
			on[j] = 1;
			if (pair_d2(nl, r, i, j) >= nl->rl2)
				rep->beyond++;
			int back = 0;
			for (size_t p = b->start[j]; p < b->start[j + 1] && !back; p++)
				back = b->idx[p] == i;
			rep->asymmetric += !back;
		}
		/* A pair is missing when either row lacks the other: the force on one of the
		 * two would be lost. Counted at its smaller index, so once. */
		for (size_t j = i + 1; j < n; j++) {
			if (pair_d2(nl, r, i, j) >= r2)
				continue;
			int listed = on[j];
			if (listed) {
				listed = 0;
				for (size_t p = b->start[j]; p < b->start[j + 1] && !listed; p++)
					listed = b->idx[p] == i;
			}
			rep->missing += !listed;
		}
		for (size_t k = 0; k < len; k++)
			on[row[k]] = 0;
	}
	free(on);
	return LZ_OK;
}
