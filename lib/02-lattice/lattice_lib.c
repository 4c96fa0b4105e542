/* lattice_lib.c — the library half of lz/lattice.h: kinds and names, direction
 * tables, the side check and the box. The distances and the correction table are
 * graded (solutions/02-lattice/lattice.c). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lz/bits.h"
#include "lz/error.h"
#include "lz/lattice.h"

static const char *const names[LZ_NLATTICES] = {
	"square", "square8", "triangular", "cubic", "cubic18", "cubic26",
};

/* 2D tables counterclockwise from (1, 0): opposite directions are n/2 apart. */
static const lz_site square4[] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
static const lz_site square8[] = {
	{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0},
	{-1, 0, 0}, {-1, -1, 0}, {0, -1, 0}, {1, -1, 0},
};
/* Sheared: (0, 1) is l2 at 60°, (-1, 1) is l2 - l1 at 120°. */
static const lz_site triangular[] = {
	{1, 0, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, -1, 0},
};
/* 3D: the first half (faces, then edges, then corners), then its negatives. */
static const lz_site cubic6[] = {
	{1, 0, 0}, {0, 1, 0}, {0, 0, 1},
	{-1, 0, 0}, {0, -1, 0}, {0, 0, -1},
};
static const lz_site cubic18[] = {
	{1, 0, 0}, {0, 1, 0}, {0, 0, 1},
	{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1},
	{-1, 0, 0}, {0, -1, 0}, {0, 0, -1},
	{-1, -1, 0}, {-1, 1, 0}, {-1, 0, -1}, {-1, 0, 1}, {0, -1, -1}, {0, -1, 1},
};
static const lz_site cubic26[] = {
	{1, 0, 0}, {0, 1, 0}, {0, 0, 1},
	{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1},
	{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {1, -1, -1},
	{-1, 0, 0}, {0, -1, 0}, {0, 0, -1},
	{-1, -1, 0}, {-1, 1, 0}, {-1, 0, -1}, {-1, 0, 1}, {0, -1, -1}, {0, -1, 1},
	{-1, -1, -1}, {-1, -1, 1}, {-1, 1, -1}, {-1, 1, 1},
};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

static int valid(lz_lattice_kind kind) { return (unsigned)kind < LZ_NLATTICES; }

const char *lz_lattice_name(lz_lattice_kind kind)
{
	return valid(kind) ? names[kind] : "(invalid lattice)";
}

int lz_lattice_parse(const char *name, lz_lattice_kind *kind)
{
	for (int k = 0; k < LZ_NLATTICES; k++)
		if (name && strcmp(name, names[k]) == 0) {
			*kind = (lz_lattice_kind)k;
			return LZ_OK;
		}
	return lz_error(LZ_EINVAL, "lattice '%s' is unknown: the lattices are square, square8, "
	                "triangular, cubic, cubic18 and cubic26", name ? name : "(null)");
}

int lz_lattice_dim(lz_lattice_kind kind)
{
	if (!valid(kind))
		return 0;
	return kind >= LZ_LATTICE_CUBIC ? 3 : 2;
}

double lz_lattice_cell_volume(lz_lattice_kind kind)
{
	return kind == LZ_LATTICE_TRIANGULAR ? sqrt(3.0) / 2.0 : 1.0;
}

void lz_lattice_cartesian(lz_lattice_kind kind, int32_t side, const int32_t *p, double c[3])
{
	int dim = lz_lattice_dim(kind);
	c[0] = p[0];
	c[1] = p[1];
	c[2] = dim == 3 ? p[2] : 0;
	if (kind == LZ_LATTICE_TRIANGULAR) {
		c[0] = p[0] + 0.5 * p[1];
		if (c[0] >= side)
			c[0] -= side;
		c[1] = sqrt(3.0) / 2.0 * p[1];
	}
}

double lz_lattice_reach(lz_lattice_kind kind, double r)
{
	if (lz_lattice_dim(kind) == 0)
		return 0;
	return ceil(kind == LZ_LATTICE_TRIANGULAR ? 2.0 * r / sqrt(3.0) : r);
}

const lz_site *lz_lattice_dirs(lz_lattice_kind kind, int *n)
{
	static const struct {
		const lz_site *dirs;
		int n;
	} tables[LZ_NLATTICES] = {
		{square4, COUNT(square4)}, {square8, COUNT(square8)},
		{triangular, COUNT(triangular)}, {cubic6, COUNT(cubic6)},
		{cubic18, COUNT(cubic18)}, {cubic26, COUNT(cubic26)},
	};
	if (!valid(kind)) {
		*n = 0;
		return NULL;
	}
	*n = tables[kind].n;
	return tables[kind].dirs;
}

int lz_lattice_side_check(int64_t side)
{
	if (side < 1)
		return lz_error(LZ_EINVAL, "side = %lld must be a positive power of two: 1, 2, 4, "
		                "…, %d", (long long)side, LZ_LATTICE_SIDE_MAX);
	return lz_check_pow2("side", (uint64_t)side, LZ_LATTICE_SIDE_MAX);
}

int lz_lattice_kind_side_check(lz_lattice_kind kind, int64_t side)
{
	if (!valid(kind))
		return lz_error(LZ_EINVAL, "lattice kind %d is not one of the %d kinds", (int)kind,
		                LZ_NLATTICES), 0;
	return lz_lattice_side_check(side) == LZ_OK ? lz_lattice_dim(kind) : 0;
}

lz_lattice_box *lz_lattice_box_alloc(lz_lattice_kind kind, int64_t side)
{
	if (lz_lattice_kind_side_check(kind, side) == 0)
		return NULL;
	lz_lattice_box *b = malloc(sizeof *b);
	int32_t *dc = malloc((size_t)side * sizeof *dc);
	if (!b || !dc) {
		free(b);
		free(dc);
		lz_error(LZ_ENOMEM, "no memory for a box of side %lld", (long long)side);
		return NULL;
	}
	*b = (lz_lattice_box){kind, lz_lattice_dim(kind), (int32_t)side, (int32_t)(side - 1), dc};
	if (lz_lattice_dctable(side, dc) != LZ_OK) {
		lz_lattice_box_free(b);
		return NULL;
	}
	return b;
}

void lz_lattice_box_free(lz_lattice_box *b)
{
	if (!b)
		return;
	free(b->dc);
	free(b);
}
