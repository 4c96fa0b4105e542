/* cells_lib.c — allocation of cell grids with their Morton ranks and block tables,
 * binning, the cell-ordered permutation and the memory count (lz/cells.h). The
 * Morton code, the cell of a site or point, the block, the lists and the pair scan
 * are graded (solutions/04-neighbours/cells.c); this file calls them and checks what
 * they return before storing it, so a wrong answer is an error, not a stray write. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lz/bits.h"
#include "lz/cells.h"
#include "lz/error.h"

/* The most particles a grid can index: particle numbers are int32_t in next[]. */
#define CELLS_NMAX ((size_t)INT32_MAX)

/* The most cells per side that keeps m^dim <= LZ_CELLS_MAX: 2048 in 2D, 161 in 3D. */
static int32_t cells_side_max(int dim) { return dim == 2 ? 2048 : 161; }

static size_t ipow(size_t b, int e)
{
	size_t p = 1;
	while (e-- > 0)
		p *= b;
	return p;
}

/* The checks shared by both allocators; LZ_OK or LZ_EINVAL with a message. */
static int cells_check_common(lz_cells_order order, size_t nmax, size_t cap)
{
	if (order != LZ_CELLS_ROW && order != LZ_CELLS_MORTON)
		return lz_error(LZ_EINVAL, "cell order %d is neither LZ_CELLS_ROW (%d) nor "
		                "LZ_CELLS_MORTON (%d)", (int)order, LZ_CELLS_ROW, LZ_CELLS_MORTON);
	if (nmax == 0 || nmax > CELLS_NMAX)
		return lz_error(LZ_EINVAL, "nmax = %zu particles is out of range: allowed 1 <= nmax "
		                "<= %zu (particle numbers are 32-bit)", nmax, CELLS_NMAX);
	if (cap > CELLS_NMAX)
		return lz_error(LZ_EINVAL, "cap = %zu particles per cell is out of range: allowed "
		                "0 (no fixed arrays) <= cap <= %zu", cap, CELLS_NMAX);
	return LZ_OK;
}

/* Fill rank[] and unrank[]: the cells sorted by Morton code. The codes of an m^dim
 * grid lie below M^dim, M the power of two >= m (at most 2^22 codes in 2D, m <= 2048,
 * and 2^24 in 3D, m <= 161 < 256): one bit per code marks the codes in use, and a
 * cell's rank is the number of marked codes below its own — a counting sort, O(M^dim)
 * without a comparison. Each code is checked, as lz_morton is graded. */
static int cells_rank(lz_cells *c)
{
	size_t m = (size_t)c->m, M = 1;
	while (M < m)
		M *= 2;
	size_t ncodes = ipow(M, c->dim), nwords = (ncodes + 63) / 64;
	uint64_t *bits = calloc(nwords, sizeof *bits);
	uint32_t *below = malloc(nwords * sizeof *below);
	int status = LZ_OK;
	if (!bits || !below) {
		status = lz_error(LZ_ENOMEM, "no memory to rank %zu cells in Morton order", c->ncells);
		goto out;
	}
	for (size_t q = 0; q < c->ncells; q++) {
		uint32_t x = (uint32_t)(q % m), y = (uint32_t)(q / m % m);
		uint32_t z = c->dim == 3 ? (uint32_t)(q / (m * m)) : 0;
		uint64_t code = lz_morton(c->dim, x, y, z);
		if (code >= ncodes || bits[code / 64] >> (code % 64) & 1) {
			status = lz_error(LZ_EINVAL, "lz_morton(%d, %u, %u, %u) = %llu is %s: the codes "
			                  "of a %zu^%d grid must be distinct and below %zu (bit b of x "
			                  "goes to bit %d·b of the code)", c->dim, x, y, z,
			                  (unsigned long long)code, code >= ncodes ? "too large" :
			                  "the code of another cell too", m, c->dim, ncodes, c->dim);
			goto out;
		}
		bits[code / 64] |= UINT64_C(1) << (code % 64);
		c->rank[q] = (uint32_t)code;
	}
	uint32_t sum = 0;
	for (size_t w = 0; w < nwords; w++) {
		below[w] = sum;
		sum += (uint32_t)__builtin_popcountll(bits[w]);
	}
	for (size_t q = 0; q < c->ncells; q++) {
		uint32_t code = c->rank[q];
		uint64_t lower = bits[code / 64] & ((UINT64_C(1) << (code % 64)) - 1);
		c->rank[q] = below[code / 64] + (uint32_t)__builtin_popcountll(lower);
		c->unrank[c->rank[q]] = (uint32_t)q;
	}
out:
	free(bits);
	free(below);
	return status;
}

/* Fill one block table (full or half) from lz_cells_stencil, checking each answer;
 * missing cells and the empty cell's row are the empty cell ncells. */
static int cells_table(lz_cells *c, int half)
{
	int width = half ? c->nhalf : c->nfull;
	uint32_t *table = half ? c->half : c->full, out[27];
	uint32_t empty = (uint32_t)c->ncells;
	for (size_t q = 0; q < c->ncells; q++) {
		int k = lz_cells_stencil(c, q, half, out);
		if (k < 1 || k > width || out[0] != q)
			return lz_error(LZ_EINVAL, "lz_cells_stencil(cell %zu, half = %d) returned %d "
			                "cells starting with %u: expected 1 to %d cells, the cell "
			                "itself first", q, half, k, k > 0 ? out[0] : empty, width);
		uint32_t *row = table + q * (size_t)width;
		for (int j = 0; j < width; j++) {
			row[j] = j < k ? out[j] : empty;
			if (j < k && out[j] >= empty)
				return lz_error(LZ_EINVAL, "lz_cells_stencil(cell %zu, half = %d) gave "
				                "cell %u, but the cells are numbered 0 .. %zu", q, half,
				                out[j], c->ncells - 1);
		}
	}
	for (int j = 0; j < width; j++)
		table[c->ncells * (size_t)width + (size_t)j] = empty;
	return LZ_OK;
}

/* The grid once its geometry is settled: memory, empty lists, ranks, block tables. */
static lz_cells *cells_new(int dim, double side, double rc, int periodic, int32_t m,
                           int shift, lz_cells_order order, size_t nmax, size_t cap)
{
	size_t ncells = ipow((size_t)m, dim);
	if (cap > (SIZE_MAX / sizeof(uint32_t)) / (ncells + 1))
		return lz_error(LZ_EINVAL, "cap = %zu particles per cell in %zu cells is more "
		                "memory than can be addressed", cap, ncells + 1), NULL;
	lz_cells *c = calloc(1, sizeof *c);
	if (!c)
		return lz_error(LZ_ENOMEM, "no memory for a cell grid"), NULL;
	c->dim = dim;
	c->periodic = periodic;
	c->side = side;
	c->cutoff = rc;
	c->m = m;
	c->width = side / m;
	c->inv_width = m / side;
	c->shift = shift;
	c->ncells = ncells;
	c->order = order;
	c->nfull = dim == 2 ? 9 : 27;
	c->nhalf = (c->nfull + 1) / 2;
	c->nmax = nmax;
	c->cap = cap;
	if (order == LZ_CELLS_MORTON) {
		c->rank = malloc(ncells * sizeof *c->rank);
		c->unrank = malloc(ncells * sizeof *c->unrank);
	}
	c->full = malloc((ncells + 1) * (size_t)c->nfull * sizeof *c->full);
	c->half = malloc((ncells + 1) * (size_t)c->nhalf * sizeof *c->half);
	c->of = malloc(nmax * sizeof *c->of);
	c->head = malloc((ncells + 1) * sizeof *c->head);
	c->next = malloc(nmax * sizeof *c->next);
	if (cap > 0) {
		c->count = calloc(ncells + 1, sizeof *c->count);
		c->slot = malloc((ncells + 1) * cap * sizeof *c->slot);
	}
	if ((order == LZ_CELLS_MORTON && (!c->rank || !c->unrank)) || !c->full || !c->half ||
	    !c->of || !c->head || !c->next || (cap > 0 && (!c->count || !c->slot))) {
		lz_error(LZ_ENOMEM, "no memory for a grid of %zu cells, %zu particles and %zu "
		         "per cell", ncells, nmax, cap);
		lz_cells_free(c);
		return NULL;
	}
	for (size_t q = 0; q <= ncells; q++)
		c->head[q] = -1;
	if ((order == LZ_CELLS_MORTON && cells_rank(c) != LZ_OK) || cells_table(c, 0) != LZ_OK ||
	    cells_table(c, 1) != LZ_OK) {
		lz_cells_free(c);
		return NULL;
	}
	return c;
}

/* Cells per side for a cutoff rc: floor(L / rc), then corrected so that L / m >= rc
 * holds in floating point too (L = 0.3, rc = 0.1 gives 2.9999999999999996, and
 * 0.3 / 3 < 0.1), at least 1, at most the side that keeps m^dim <= LZ_CELLS_MAX. */
static int32_t cells_per_side(int dim, double side, double rc)
{
	double q = floor(side / rc);
	int32_t mmax = cells_side_max(dim);
	int32_t m = q >= mmax ? mmax : q < 1 ? 1 : (int32_t)q;
	while (m > 1 && side / m < rc)
		m--;
	while (m < mmax && side / (m + 1) >= rc)
		m++;
	return m;
}

lz_cells *lz_cells_alloc(int dim, double side, double rc, int periodic, lz_cells_order order,
                         size_t nmax, size_t cap)
{
	if (dim != 2 && dim != 3)
		return lz_error(LZ_EINVAL, "dim = %d: cell grids are 2 or 3 dimensional", dim), NULL;
	if (!(side > 0) || !isfinite(side))
		return lz_error(LZ_EINVAL, "box side L = %g must be positive and finite", side), NULL;
	if (!(rc > 0) || !isfinite(rc))
		return lz_error(LZ_EINVAL, "cutoff rc = %g must be positive and finite", rc), NULL;
	if (cells_check_common(order, nmax, cap) != LZ_OK)
		return NULL;
	int32_t m = cells_per_side(dim, side, rc);
	if (periodic && m < 3)
		return lz_error(LZ_EINVAL, "cutoff rc = %g is more than a third of the periodic box "
		                "side L = %g: a periodic grid needs 3 or more cells per side (with 2 "
		                "the cells left and right of a cell are one cell); allowed 0 < rc "
		                "<= L/3 = %.17g, or compare all pairs", rc, side, side / 3), NULL;
	return cells_new(dim, side, rc, periodic != 0, m, -1, order, nmax, cap);
}

lz_cells *lz_cells_alloc_lattice(lz_lattice_kind kind, int64_t side, double rc,
                                 lz_cells_order order, size_t nmax, size_t cap)
{
	int dim = lz_lattice_kind_side_check(kind, side);
	if (dim == 0)
		return NULL;
	if (!(rc > 0) || !isfinite(rc))
		return lz_error(LZ_EINVAL, "cutoff rc = %g lattice units must be positive and finite",
		                rc), NULL;
	if (cells_check_common(order, nmax, cap) != LZ_OK)
		return NULL;
	double reach = lz_lattice_reach(kind, rc);
	int shift = 0;
	while (shift < 62 && (double)((int64_t)1 << shift) < reach)
		shift++;
	int64_t m = side >> shift;
	if (m < 3) {
		if (side < 4)
			return lz_error(LZ_EINVAL, "a box of side L = %lld is too small for a periodic "
			                "cell grid: it needs 3 or more cells per side, so L >= 4",
			                (long long)side), NULL;
		/* Cells of side L/4 (m = 4) are the widest allowed: reach(rc) <= L/4. */
		double largest = kind == LZ_LATTICE_TRIANGULAR ? side / 4 * sqrt(3.0) / 2
		                                               : (double)(side / 4);
		while (lz_lattice_reach(kind, largest) > (double)(side / 4))
			largest = nextafter(largest, 0);
		return lz_error(LZ_EINVAL, "cutoff rc = %g lattice units needs cells %lld sites "
		                "wide (the power of two >= its reach %g), leaving m = %lld per side "
		                "of the box L = %lld; a periodic grid needs 3 or more: allowed "
		                "0 < rc <= %g", rc, (long long)1 << shift, reach, (long long)m,
		                (long long)side, largest), NULL;
	}
	while (m > cells_side_max(dim)) {
		m /= 2;
		shift++;
	}
	return cells_new(dim, (double)side, rc, 1, (int32_t)m, shift, order, nmax, cap);
}

void lz_cells_free(lz_cells *c)
{
	if (!c)
		return;
	free(c->rank);
	free(c->unrank);
	free(c->full);
	free(c->half);
	free(c->of);
	free(c->head);
	free(c->next);
	free(c->count);
	free(c->slot);
	free(c);
}

void lz_cells_coords(const lz_cells *c, size_t cell, int32_t *cx)
{
	size_t m = (size_t)c->m, q = c->unrank ? c->unrank[cell] : cell;
	cx[0] = (int32_t)(q % m);
	cx[1] = (int32_t)(q / m % m);
	if (c->dim == 3)
		cx[2] = (int32_t)(q / (m * m));
}

/* n <= nmax, else LZ_EINVAL. */
static int cells_room(const lz_cells *c, size_t n)
{
	if (n > c->nmax)
		return lz_error(LZ_EINVAL, "n = %zu particles is more than the grid has room for "
		                "(nmax = %zu, given at allocation)", n, c->nmax);
	return LZ_OK;
}

/* Checks the graded binning's answer; on a bad one the binning is dropped (n = 0). */
static int cells_bad_cell(lz_cells *c, size_t i, const char *what)
{
	c->n = 0;
	return lz_error(LZ_EINVAL, "%s put particle %zu in cell %u, but the cells are numbered "
	                "0 .. %zu", what, i, c->of[i], c->ncells - 1);
}

int lz_cells_bin_sites(lz_cells *c, size_t n, const int32_t *r)
{
	if (c->shift < 0)
		return lz_error(LZ_EINVAL, "this grid was made for continuous points "
		                "(lz_cells_alloc): lattice sites need lz_cells_alloc_lattice");
	if (cells_room(c, n) != LZ_OK)
		return LZ_EINVAL;
	uint32_t L = (uint32_t)c->side;
	size_t dim = (size_t)c->dim;
	for (size_t i = 0; i < n; i++) {
		const int32_t *ri = r + i * dim;
		for (size_t k = 0; k < dim; k++)
			if ((uint32_t)ri[k] >= L) {
				c->n = 0;
				return lz_error(LZ_EINVAL, "site %zu has coordinate %zu = %d outside the "
				                "box [0, %u): wrap it first (lz_wrap_mask)", i, k,
				                (int)ri[k], L);
			}
		c->of[i] = (uint32_t)lz_cells_of_site(c, ri);
		if (c->of[i] >= c->ncells)
			return cells_bad_cell(c, i, "lz_cells_of_site");
	}
	c->n = n;
	return LZ_OK;
}

int lz_cells_bin_points(lz_cells *c, size_t n, const double *x)
{
	if (cells_room(c, n) != LZ_OK)
		return LZ_EINVAL;
	size_t dim = (size_t)c->dim;
	for (size_t i = 0; i < n; i++) {
		const double *xi = x + i * dim;
		for (size_t k = 0; k < dim; k++)
			if (!isfinite(xi[k])) {
				c->n = 0;
				return lz_error(LZ_EINVAL, "point %zu has coordinate %zu = %g: a point "
				                "must have finite coordinates", i, k, xi[k]);
			}
		c->of[i] = (uint32_t)lz_cells_of_point(c, xi);
		if (c->of[i] >= c->ncells)
			return cells_bad_cell(c, i, "lz_cells_of_point");
	}
	c->n = n;
	return LZ_OK;
}

int lz_cells_permutation(const lz_cells *c, uint32_t *perm)
{
	uint32_t *start = calloc(c->ncells + 1, sizeof *start);
	if (!start)
		return lz_error(LZ_ENOMEM, "no memory to count the particles of %zu cells",
		                c->ncells);
	for (size_t i = 0; i < c->n; i++)
		start[c->of[i]]++;
	uint32_t sum = 0;
	for (size_t q = 0; q <= c->ncells; q++) {
		uint32_t k = start[q];
		start[q] = sum;
		sum += k;
	}
	for (size_t i = 0; i < c->n; i++)
		perm[start[c->of[i]]++] = (uint32_t)i;
	free(start);
	return LZ_OK;
}

size_t lz_cells_bytes(const lz_cells *c)
{
	size_t cells = c->ncells + 1, words = 0;
	if (c->rank)
		words += 2 * c->ncells;
	words += cells * (size_t)(c->nfull + c->nhalf);
	words += 2 * c->nmax + cells;
	if (c->cap > 0)
		words += cells * (1 + c->cap);
	return sizeof *c + 4 * words;
}
