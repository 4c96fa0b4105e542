/* field_lib.c — allocation of a byte field with its excluded shape, the particle
 * list's room, the coverage and a free-site scan (lz/field.h). Painting, moving,
 * the collision test and adsorption are graded (solutions/03-field/field.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/field.h"
#include "lz/walk.h"

/* The sites of a cube (square) of side `side` in `dim` dimensions; 0 with an lz_error
 * when beyond the field's limit. `what` names the side in the message. */
static size_t field_sites(int64_t side, int dim, const char *what)
{
	size_t n = (size_t)side * (size_t)side * (dim == 3 ? (size_t)side : 1);
	if (n > LZ_FIELD_SITES_MAX)
		return lz_error(LZ_EINVAL, "%s = %lld gives %zu sites in %dD, more than the "
		                "field's limit of %zu (one byte each, 1 GiB): take %s <= %d", what,
		                (long long)side, n, dim, LZ_FIELD_SITES_MAX, what,
		                dim == 2 ? 32768 : 1024), (size_t)0;
	return n;
}

/* Check the arguments of lz_field_alloc_in; the dimension, or 0 with an lz_error. */
static int field_check(lz_lattice_kind kind, int64_t side, double radius, int64_t pitch)
{
	int dim = lz_lattice_kind_side_check(kind, side);
	if (dim == 0)
		return 0;
	if (side < 2)
		return lz_error(LZ_EINVAL, "side = 1: a field needs a box of side 2 or more"), 0;
	if (pitch < side || (pitch & (pitch - 1)) != 0)
		return lz_error(LZ_EINVAL, "pitch = %lld: the allocated lattice must have a "
		                "power-of-two side of at least the box side L = %lld",
		                (long long)pitch, (long long)side), 0;
	if (field_sites(pitch, dim, pitch == side ? "L" : "pitch") == 0)
		return 0;
	if (!(radius > 0) || !isfinite(radius))
		return lz_error(LZ_EINVAL, "radius = %g lattice units must be positive and finite",
		                radius), 0;
	if (4.0 * radius > (double)side)
		return lz_error(LZ_EINVAL, "radius = %g lattice units is too large for a box of side "
		                "%lld: the excluded disk of radius 2R = %g must fit in the box, "
		                "2·2R <= L (or it would wrap onto itself); allowed 0 < R <= %g",
		                radius, (long long)side, 2 * radius, (double)side / 4), 0;
	return dim;
}

/* Mark the allocated sites outside the box (any coordinate >= L) as never free: all
 * 255, then the box's rows cleared, one memset per row (a divide per site would take
 * seconds at pitch 16384). */
static void field_fence(lz_field *f, int64_t pitch)
{
	size_t P = (size_t)pitch, L = (size_t)f->side;
	memset(f->cell, UINT8_MAX, f->nsites);
	for (size_t z = 0; z < (f->dim == 3 ? L : 1); z++)
		for (size_t y = 0; y < L; y++)
			memset(f->cell + (z * P + y) * P, 0, L);
}

lz_field *lz_field_alloc_in(lz_lattice_kind kind, int64_t side, double radius, int64_t pitch)
{
	int dim = field_check(kind, side, radius, pitch);
	if (dim == 0)
		return NULL;
	lz_field *f = calloc(1, sizeof *f);
	if (!f)
		return lz_error(LZ_ENOMEM, "no memory for a field"), NULL;
	f->kind = kind;
	f->dim = dim;
	f->side = (int32_t)side;
	f->mask = (int32_t)(side - 1);
	while (((int64_t)1 << f->shift) < pitch)
		f->shift++;
	f->nsites = field_sites(pitch, dim, "pitch");
	f->nfree = field_sites(side, dim, "side");
	f->radius = radius;
	f->cell = calloc(f->nsites, 1);
	if (!f->cell) {
		lz_error(LZ_ENOMEM, "no memory for a field of %zu sites", f->nsites);
		lz_field_free(f);
		return NULL;
	}
	if (pitch > side)
		field_fence(f, pitch);
	f->excl = lz_shape_alloc(kind, 2 * radius);
	if (!f->excl) {
		lz_field_free(f);
		return NULL;
	}
	return f;
}

lz_field *lz_field_alloc(lz_lattice_kind kind, int64_t side, double radius)
{
	return lz_field_alloc_in(kind, side, radius, side);
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
