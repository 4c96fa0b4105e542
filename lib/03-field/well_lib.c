/* well_lib.c — allocation of a square well on a field, painted for the particles
 * already there, and the total energy from the well field (lz/well.h). The
 * acceptance table, ΔN and the Metropolis move are graded (solutions/03-field/well.c). */
#include <math.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/well.h"

/* Check the arguments of lz_well_alloc before any graded code runs; LZ_OK or the
 * code of an lz_error naming the bad value and its allowed range. */
static int well_check(const lz_field *f, double lambda, double depth, double temperature)
{
	if (!f)
		return lz_error(LZ_EINVAL, "a well needs a field: f is NULL");
	if (!(lambda > 1 && lambda <= LZ_WELL_LAMBDA_MAX))
		return lz_error(LZ_EINVAL, "lambda = %g: the well's range in units of the diameter "
		                "σ must lie in (1, %g] (1 is no well at all; beyond %g a site's "
		                "count could pass a byte)", lambda, LZ_WELL_LAMBDA_MAX,
		                LZ_WELL_LAMBDA_MAX);
	double rw = lambda * 2 * f->radius, widest = (double)f->side / (4 * f->radius);
	if (2 * rw > (double)f->side)
		return lz_error(LZ_EINVAL, "lambda = %g gives a well of range rw = %g lattice units "
		                "for R = %g, too wide for the box of side %d: 2·rw must be <= L (or "
		                "the well would wrap onto itself); allowed 1 < lambda <= %g",
		                lambda, rw, f->radius, (int)f->side, widest);
	if (!(depth >= 0) || !isfinite(depth))
		return lz_error(LZ_EINVAL, "depth = %g: the well depth ε must be finite and >= 0 "
		                "(0 is hard particles alone)", depth);
	if (!(temperature > 0) || !isfinite(temperature))
		return lz_error(LZ_EINVAL, "temperature = %g: kT must be positive and finite",
		                temperature);
	return LZ_OK;
}

/* Add 1 on the well shape of every particle. A byte at 255 means an overlapping pile
 * far beyond anything a hard-core configuration reaches: refuse it rather than wrap. */
static int well_paint_all(lz_well *w, const lz_field *f)
{
	const lz_shape *s = w->shape;
	for (size_t i = 0; i < f->n; i++) {
		const int32_t *c = f->r + i * (size_t)f->dim;
		int32_t cz = f->dim == 3 ? c[2] : 0;
		for (size_t k = 0; k < s->n; k++) {
			uint8_t *v = w->cell + lz_field_index(f, c[0] + s->pts[k].x,
			                                      c[1] + s->pts[k].y, cz + s->pts[k].z);
			if (*v == UINT8_MAX)
				return lz_error(LZ_EPHYS, "particle %zu at (%d, %d, %d) would make a site "
				                "lie in the wells of more than 255 particles: do the "
				                "particles overlap?", i, (int)c[0], (int)c[1], (int)cz);
			(*v)++;
		}
	}
	return LZ_OK;
}

lz_well *lz_well_alloc(const lz_field *f, double lambda, double depth, double temperature)
{
	if (well_check(f, lambda, depth, temperature) != LZ_OK)
		return NULL;
	lz_well *w = calloc(1, sizeof *w);
	if (!w)
		return lz_error(LZ_ENOMEM, "no memory for a well"), NULL;
	w->range = lambda * 2 * f->radius;
	w->depth = depth;
	w->temperature = temperature;
	w->cell = calloc(f->nsites, 1);
	if (!w->cell) {
		lz_error(LZ_ENOMEM, "no memory for a well field of %zu sites", f->nsites);
		lz_well_free(w);
		return NULL;
	}
	w->shape = lz_shape_alloc(f->kind, w->range);
	if (!w->shape || well_paint_all(w, f) != LZ_OK) {
		lz_well_free(w);
		return NULL;
	}
	lz_well_table(w);
	return w;
}

void lz_well_free(lz_well *w)
{
	if (!w)
		return;
	lz_shape_free(w->shape);
	free(w->cell);
	free(w);
}

/* Every pair is seen from both ends: the sum of the partner counts is twice the
 * number of pairs. */
double lz_well_energy(const lz_well *w, const lz_field *f)
{
	size_t partners = 0;
	for (size_t i = 0; i < f->n; i++) {
		const int32_t *c = f->r + i * (size_t)f->dim;
		partners += (size_t)w->cell[lz_field_index(f, c[0], c[1], f->dim == 3 ? c[2] : 0)] - 1;
	}
	return -w->depth * ((double)partners / 2);
}
