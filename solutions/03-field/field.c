/* field.c — painting particles into a byte field, the O(1) collision test, the
 * head/tail move and random sequential adsorption to exact jamming (graded). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/field.h"

/* LZ_HELPERS_BEGIN */
/* Add delta (+1 or -1) to the cells of the offsets pts[0 .. n) from centre c, and keep
 * the free-site count: a cell leaving 0 is one free site less, a cell reaching 0 one
 * more. */
static void paint(lz_field *f, const int32_t *c, const lz_site *pts, size_t n, int delta)
{
	int32_t cz = f->dim == 3 ? c[2] : 0;
	for (size_t k = 0; k < n; k++) {
		uint8_t *v = f->cell + lz_field_index(f, c[0] + pts[k].x, c[1] + pts[k].y,
		                                     cz + pts[k].z);
		if (delta > 0) {
			f->nfree -= *v == 0;
			(*v)++;
		} else {
			(*v)--;
			f->nfree += *v == 0;
		}
	}
}
/* LZ_HELPERS_END */

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
	/* LZ_SOLUTION_BEGIN */
	uint32_t m = (uint32_t)f->mask;
	int32_t p[3] = {(int32_t)((uint32_t)c.x & m), (int32_t)((uint32_t)c.y & m),
	                f->dim == 3 ? (int32_t)((uint32_t)c.z & m) : 0};
	const lz_shape *s = f->excl;
	for (size_t k = 0; k < s->n; k++)
		if (f->cell[lz_field_index(f, p[0] + s->pts[k].x, p[1] + s->pts[k].y,
		                           p[2] + s->pts[k].z)] == UINT8_MAX)
			return lz_error(LZ_EPHYS, "a particle at (%d, %d, %d) would cover a site "
			                "already covered 255 times: the byte would wrap (is this "
			                "pile of particles meant to overlap?)", (int)p[0], (int)p[1],
			                (int)p[2]);
	int status = lz_field_reserve(f, f->n + 1);
	if (status != LZ_OK)
		return status;
	int32_t *r = f->r + f->n * (size_t)f->dim;
	for (int k = 0; k < f->dim; k++)
		r[k] = p[k];
	f->n++;
	paint(f, p, s->pts, s->n, +1);
	return LZ_OK;
	/* LZ_SOLUTION_END */
}

int lz_field_remove(lz_field *f, size_t i)
{
	/* Hint: LZ_EINVAL (lz_error naming i and n) if i >= n. Subtract 1 on every cell
	 * of particle i's excluded shape (a cell reaching 0 is a free site more), then copy
	 * the last particle's centre into slot i and decrease n. */
	/* LZ_SOLUTION_BEGIN */
	if (i >= f->n)
		return lz_error(LZ_EINVAL, "particle %zu does not exist: there are %zu", i, f->n);
	size_t dim = (size_t)f->dim;
	int32_t *r = f->r + i * dim, c[3] = {r[0], r[1], dim == 3 ? r[2] : 0};
	paint(f, c, f->excl->pts, f->excl->n, -1);
	f->n--;
	for (size_t k = 0; k < dim; k++)
		r[k] = f->r[f->n * dim + k];
	return LZ_OK;
	/* LZ_SOLUTION_END */
}

int lz_field_is_free(const lz_field *f, lz_site s)
{
	/* Hint: one look-up, f->cell[lz_field_index(f, s.x, s.y, s.z)] == 0. Nothing
	 * else: the field already knows every particle's excluded area. */
	/* LZ_SOLUTION_BEGIN */
	return f->cell[lz_field_index(f, s.x, s.y, s.z)] == 0;
	/* LZ_SOLUTION_END */
}

/* The target may hold exactly the particle's own coverage and nothing more. */
int lz_field_can_move(const lz_field *f, size_t i, int d)
{
	/* Hint: t = r[i] + dirs[d]. The particle's own shape covers t when
	 * f->excl->self[d] is 1; so the step is free iff cell[t] == self[d]. Why not
	 * cell[t] <= 1? Read the header lz/field.h: when self[d] is 0 (tiny particles), a
	 * 1 at t belongs to a neighbour. */
	/* LZ_SOLUTION_BEGIN */
	const int32_t *r = f->r + i * (size_t)f->dim;
	lz_site e = f->excl->dirs[d];
	size_t t = lz_field_index(f, r[0] + e.x, r[1] + e.y, f->dim == 3 ? r[2] + e.z : 0);
	return f->cell[t] == f->excl->self[d];
	/* LZ_SOLUTION_END */
}

/* Heads before tails: a cell never dips below zero, even for a tiny shape. */
void lz_field_move(lz_field *f, size_t i, int d)
{
	/* Hint: add 1 at the head points and subtract 1 at the tail points of direction d
	 * (f->excl->head[d], tail[d], nmove[d] each, offsets from the OLD centre), keeping
	 * nfree; only then move r[i] by dirs[d], wrapped with & mask. The body of the shape
	 * is not touched: that is the point of the method (thesis fig. 2.9). */
	/* LZ_SOLUTION_BEGIN */
	const lz_shape *s = f->excl;
	int32_t *r = f->r + i * (size_t)f->dim;
	int32_t c[3] = {r[0], r[1], f->dim == 3 ? r[2] : 0};
	paint(f, c, s->head[d], s->nmove[d], +1);
	paint(f, c, s->tail[d], s->nmove[d], -1);
	uint32_t m = (uint32_t)f->mask;
	lz_site e = s->dirs[d];
	r[0] = (int32_t)((uint32_t)(r[0] + e.x) & m);
	r[1] = (int32_t)((uint32_t)(r[1] + e.y) & m);
	if (f->dim == 3)
		r[2] = (int32_t)((uint32_t)(r[2] + e.z) & m);
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	unsigned long L = (unsigned long)f->side;
	size_t box = (size_t)L * L * (f->dim == 3 ? L : 1);
	int status = LZ_OK;
	while (f->nfree > 0 && (target == 0 || f->n < target) && f->nfree >= box / 16) {
		lz_site c = {0, 0, 0};
		c.x = (int32_t)gsl_rng_uniform_int(rng, L);
		c.y = (int32_t)gsl_rng_uniform_int(rng, L);
		if (f->dim == 3)
			c.z = (int32_t)gsl_rng_uniform_int(rng, L);
		f->tries++;
		if (lz_field_is_free(f, c) && (status = lz_field_place(f, c)) != LZ_OK)
			break;
	}
	if (status == LZ_OK && f->nfree > 0 && (target == 0 || f->n < target)) {
		size_t m = 0;
		uint32_t *list = malloc(f->nfree * sizeof *list);
		if (!list)
			status = lz_error(LZ_ENOMEM, "no memory for a list of %zu free sites", f->nfree);
		for (size_t s = 0; list && s < f->nsites; s++)
			if (f->cell[s] == 0)
				list[m++] = (uint32_t)s;
		uint32_t mask = (uint32_t)f->mask;
		while (list && f->nfree > 0 && (target == 0 || f->n < target)) {
			size_t k = (size_t)gsl_rng_uniform_int(rng, (unsigned long)m);
			uint32_t s = list[k];
			f->tries++;
			if (f->cell[s] != 0) {
				list[k] = list[--m];
				continue;
			}
			lz_site c = {(int32_t)(s & mask), (int32_t)((s >> f->shift) & mask),
			             (int32_t)(s >> (2 * f->shift))};
			if ((status = lz_field_place(f, c)) != LZ_OK)
				break;
		}
		free(list);
	}
	*jammed = f->nfree == 0;
	return status;
	/* LZ_SOLUTION_END */
}
