/* field_lib.c — allocation of a byte field with its excluded shape, the particle
 * list's room, the coverage and a free-site scan (lz/field.h). Painting, moving,
 * the collision test and adsorption are graded (solutions/03-field/field.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/field.h"
#include "lz/walk.h"

lz_field *lz_field_alloc(lz_lattice_kind kind, int64_t side, double radius)
{
	int dim = lz_lattice_kind_side_check(kind, side);
	if (dim == 0)
		return NULL;
	if (side < 2)
		return lz_error(LZ_EINVAL, "side = 1: a field needs a box of side 2 or more"), NULL;
	size_t nsites = (size_t)side * (size_t)side * (dim == 3 ? (size_t)side : 1);
	if (nsites > LZ_FIELD_SITES_MAX)
		return lz_error(LZ_EINVAL, "side = %lld gives %zu sites in %dD, more than the "
		                "field's limit of %zu (one byte each): take L <= %d", (long long)side,
		                nsites, dim, LZ_FIELD_SITES_MAX, dim == 2 ? 32768 : 1024), NULL;
	if (!(radius > 0) || !isfinite(radius))
		return lz_error(LZ_EINVAL, "radius = %g lattice units must be positive and finite",
		                radius), NULL;
	if (4.0 * radius > (double)side)
		return lz_error(LZ_EINVAL, "radius = %g lattice units is too large for a box of side "
		                "%lld: the excluded disk of radius 2R = %g must fit in the box, "
		                "2·2R <= L (or it would wrap onto itself); allowed 0 < R <= %g",
		                radius, (long long)side, 2 * radius, (double)side / 4), NULL;
	lz_field *f = calloc(1, sizeof *f);
	if (!f)
		return lz_error(LZ_ENOMEM, "no memory for a field"), NULL;
	f->kind = kind;
	f->dim = dim;
	f->side = (int32_t)side;
	f->mask = (int32_t)(side - 1);
	while (((int64_t)1 << f->shift) < side)
		f->shift++;
	f->nsites = nsites;
	f->nfree = nsites;
	f->radius = radius;
	f->cell = calloc(nsites, 1);
	if (!f->cell) {
		lz_field_free(f);
		return lz_error(LZ_ENOMEM, "no memory for a field of %zu sites", nsites), NULL;
	}
	f->excl = lz_shape_alloc(kind, 2 * radius);
	if (!f->excl) {
		lz_field_free(f);
		return NULL;
	}
	return f;
}

void lz_field_free(lz_field *f)
{
	if (!f)
		return;
	lz_shape_free(f->excl);
	free(f->cell);
	free(f->r);
	free(f);
}

int lz_field_reserve(lz_field *f, size_t n)
{
	if (n <= f->cap)
		return LZ_OK;
	size_t cap = f->cap ? f->cap : 64;
	while (cap < n)
		cap *= 2;
	int32_t *r = realloc(f->r, cap * (size_t)f->dim * sizeof *r);
	if (!r)
		return lz_error(LZ_ENOMEM, "no memory for %zu particles in the field", cap);
	f->r = r;
	f->cap = cap;
	return LZ_OK;
}

double lz_field_coverage(const lz_field *f)
{
	return lz_walk_packing(f->kind, f->side, f->radius, f->n);
}

size_t lz_field_count_free(const lz_field *f)
{
	size_t free_sites = 0;
	for (size_t s = 0; s < f->nsites; s++)
		free_sites += f->cell[s] == 0;
	return free_sites;
}
