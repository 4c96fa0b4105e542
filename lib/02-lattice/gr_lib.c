/* gr_lib.c — the library half of lz/gr.h: the exact integer square root, the exact
 * shell measure, and the accumulator's set-up. The lattice counts and the
 * normalisation are graded (solutions/02-lattice/gr.c). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/gr.h"
#include "lz/lattice.h"

uint32_t lz_isqrt64(uint64_t n)
{
	/* The double's root is within one of the truth; fix it with exact products. */
	uint64_t r = (uint64_t)sqrt((double)n);
	if (r > UINT32_MAX)
		r = UINT32_MAX;
	while (r * r > n)
		r--;
	while (r < UINT32_MAX && (r + 1) * (r + 1) <= n)
		r++;
	return (uint32_t)r;
}

double lz_shell_volume(int dim, int k)
{
	double r = k;
	if (dim == 3)
		return 4.0 * M_PI / 3.0 * (3.0 * r * r + 3.0 * r + 1.0);
	return M_PI * (2.0 * r + 1.0);
}

lz_gr *lz_gr_alloc(lz_lattice_kind kind, int64_t side, int max_r, size_t n)
{
	int dim = lz_lattice_kind_side_check(kind, side);
	if (dim == 0)
		return NULL;
	int cap = dim == 3 ? LZ_GR_MAX_SHELLS_3D : LZ_GR_MAX_SHELLS_2D;
	if (max_r < 1 || max_r > side / 2 || max_r > cap)
		return lz_error(LZ_EINVAL, "g(r) up to max_r = %d lattice units in a box of side "
		                "%lld: max_r must be in [1, %lld] (half the box, where the shells "
		                "stop fitting into the nearest-image cell; at most %d on a %dD "
		                "lattice)", max_r, (long long)side,
		                (long long)(side / 2 < cap ? side / 2 : cap), cap, dim), NULL;
	if (n < 2)
		return lz_error(LZ_EINVAL, "g(r) of %zu particles: it needs at least 2", n), NULL;
	lz_gr *g = calloc(1, sizeof *g);
	size_t d2max = (size_t)max_r * (size_t)max_r;
	if (g) {
		*g = (lz_gr){.kind = kind, .dim = dim, .side = (int32_t)side, .nshells = max_r,
		             .n = n, .d2max = (int64_t)d2max};
		g->shell_of = malloc(d2max * sizeof *g->shell_of);
		g->pairs = calloc((size_t)max_r, sizeof *g->pairs);
		g->lattice = calloc((size_t)max_r, sizeof *g->lattice);
	}
	if (!g || !g->shell_of || !g->pairs || !g->lattice) {
		lz_gr_free(g);
		lz_error(LZ_ENOMEM, "no memory for g(r) up to max_r = %d", max_r);
		return NULL;
	}
	/* Shell k covers d2 in [k², (k+1)²): fill it run by run, no root needed. */
	for (int k = 0; k < max_r; k++)
		for (size_t d2 = (size_t)k * (size_t)k; d2 < (size_t)(k + 1) * (size_t)(k + 1); d2++)
			g->shell_of[d2] = (uint32_t)k;
	if (lz_shell_counts(kind, max_r, g->lattice) != LZ_OK) {
		lz_gr_free(g);
		return NULL;
	}
	return g;
}

void lz_gr_free(lz_gr *g)
{
	if (!g)
		return;
	free(g->shell_of);
	free(g->pairs);
	free(g->lattice);
	free(g);
}

int lz_gr_add_config(lz_gr *g, const lz_lattice_box *b, const int32_t *r)
{
	if (b->dim != g->dim || b->side != g->side)
		return lz_error(LZ_EINVAL, "g(r) of a %dD box of side %d added to an accumulator for "
		                "a %dD box of side %d", b->dim, (int)b->side, g->dim, (int)g->side);
	size_t dim = (size_t)g->dim;
	for (size_t i = 0; i + 1 < g->n; i++) {
		const int32_t *a = r + i * dim;
		for (size_t j = i + 1; j < g->n; j++) {
			const int32_t *c = r + j * dim;
			lz_gr_add_pair(g, lz_lattice_min_dist2(b, a[0] - c[0], a[1] - c[1],
			                                       dim == 3 ? a[2] - c[2] : 0));
		}
	}
	lz_gr_end_sample(g);
	return LZ_OK;
}
