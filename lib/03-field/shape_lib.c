/* shape_lib.c — allocation of a lattice disk (sphere) and its step tables
 * (lz/shape.h). The point sets themselves are graded (solutions/03-field/shape.c). */
#include <math.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/shape.h"

static size_t ipow(size_t b, int e)
{
	size_t p = 1;
	while (e-- > 0)
		p *= b;
	return p;
}

lz_shape *lz_shape_alloc(lz_lattice_kind kind, double radius)
{
	int dim = lz_lattice_dim(kind);
	if (dim == 0)
		return lz_error(LZ_EINVAL, "lattice kind %d is not one of the %d kinds", (int)kind,
		                LZ_NLATTICES), NULL;
	if (!(radius > 0) || !isfinite(radius))
		return lz_error(LZ_EINVAL, "shape radius r = %g lattice units must be positive and "
		                "finite", radius), NULL;
	/* The widest reach whose bounding box stays within LZ_SHAPE_BOX_MAX. */
	double widest = dim == 2 ? floor((sqrt((double)LZ_SHAPE_BOX_MAX) - 1) / 2)
	                         : floor((cbrt((double)LZ_SHAPE_BOX_MAX) - 1) / 2);
	double reach = lz_lattice_reach(kind, radius);
	if (reach > widest)
		return lz_error(LZ_EINVAL, "shape radius r = %g lattice units is too large for the "
		                "%s lattice: its bounding box would pass %zu points; take r <= %g",
		                radius, lz_lattice_name(kind), LZ_SHAPE_BOX_MAX,
		                kind == LZ_LATTICE_TRIANGULAR ? widest * sqrt(3.0) / 2 : widest),
		       NULL;
	lz_shape *s = calloc(1, sizeof *s);
	if (!s)
		return lz_error(LZ_ENOMEM, "no memory for a shape"), NULL;
	s->kind = kind;
	s->dim = dim;
	s->radius = radius;
	s->r2 = (int64_t)ceil(radius * radius);
	s->reach = (int32_t)reach;
	size_t side = 2 * (size_t)s->reach + 1;
	s->cap = ipow(side, dim);
	s->dirs = lz_lattice_dirs(kind, &s->ndir);
	s->pts = malloc(s->cap * sizeof *s->pts);
	s->nmove = calloc((size_t)s->ndir, sizeof *s->nmove);
	s->capmove = calloc((size_t)s->ndir, sizeof *s->capmove);
	s->head = calloc((size_t)s->ndir, sizeof *s->head);
	s->tail = calloc((size_t)s->ndir, sizeof *s->tail);
	s->self = calloc((size_t)s->ndir, sizeof *s->self);
	if (!s->pts || !s->nmove || !s->capmove || !s->head || !s->tail || !s->self)
		goto nomem;
	if (lz_shape_fill_points(s) != LZ_OK)
		goto fail;
	/* A step e = e1 + e2 + ... (unit steps along axes, |e|_1 of them) gains at most
	 * one point per lattice line along each unit step's axis, since a disk meets every
	 * line in one run of points: |head| <= |e|_1 · side^(dim-1), and <= n. */
	for (int d = 0; d < s->ndir; d++) {
		lz_site e = s->dirs[d];
		size_t l1 = (size_t)(abs(e.x) + abs(e.y) + abs(e.z));
		size_t bound = l1 * ipow(side, dim - 1);
		s->capmove[d] = bound < s->n ? bound : s->n;
		s->head[d] = malloc((s->capmove[d] ? s->capmove[d] : 1) * sizeof **s->head);
		s->tail[d] = malloc((s->capmove[d] ? s->capmove[d] : 1) * sizeof **s->tail);
		if (!s->head[d] || !s->tail[d])
			goto nomem;
	}
	if (lz_shape_fill_moves(s) != LZ_OK)
		goto fail;
	return s;
nomem:
	lz_error(LZ_ENOMEM, "no memory for a shape of radius %g (%zu points)", radius, s->cap);
fail:
	lz_shape_free(s);
	return NULL;
}

void lz_shape_free(lz_shape *s)
{
	if (!s)
		return;
	for (int d = 0; s->head && d < s->ndir; d++)
		free(s->head[d]);
	for (int d = 0; s->tail && d < s->ndir; d++)
		free(s->tail[d]);
	free(s->head);
	free(s->tail);
	free(s->nmove);
	free(s->capmove);
	free(s->self);
	free(s->pts);
	free(s);
}

double lz_shape_mean_move(const lz_shape *s)
{
	double sum = 0;
	for (int d = 0; d < s->ndir; d++)
		sum += (double)s->nmove[d];
	return sum / s->ndir;
}
