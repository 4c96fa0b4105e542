/* edmd_cells.c — the cells of lz/edmd.h: a cell's block and its periodic shifts, the
 * cell across a face, the cell lists, and the time a falling particle meets a face.
 * Everything else of the engine calls this file; it calls nothing of the engine. */
#include <math.h>
#include <stdint.h>

#include "lz/edmd.h"

/* The cell's coordinates on its three axes. */
static void cell_coords(const lz_edmd *e, uint32_t c, int cc[3])
{
	cc[0] = (int)(c % (uint32_t)e->m[0]);
	cc[1] = (int)(c / (uint32_t)e->m[0] % (uint32_t)e->m[1]);
	cc[2] = (int)(c / ((uint32_t)e->m[0] * (uint32_t)e->m[1]));
}

static uint32_t cell_index(const lz_edmd *e, const int cc[3])
{
	return (uint32_t)cc[0] + (uint32_t)e->m[0] * ((uint32_t)cc[1] + (uint32_t)e->m[1] * (uint32_t)cc[2]);
}

/* The block of a cell at least one cell away from every face of the box: three cells
 * on each axis (one on z in 2D), no shift. Most blocks; the general loop below costs
 * several times as much. */
static void block_inside(const lz_edmd *e, const int cc[3], lz_edmd_block *b)
{
	uint32_t s1 = (uint32_t)e->m[0], s2 = s1 * (uint32_t)e->m[1];
	for (int k = 0; k < 3; k++) {
		b->off[0][k] = (uint32_t)(cc[0] - 1 + k);
		b->off[1][k] = (uint32_t)(cc[1] - 1 + k) * s1;
		b->off[2][k] = (uint32_t)(cc[2] - 1 + k) * s2;
		b->shift[0][k] = b->shift[1][k] = b->shift[2][k] = 0;
	}
	b->n[0] = b->n[1] = 3;
	b->n[2] = e->dim == 3 ? 3 : 1;
	if (e->dim == 2)
		b->off[2][0] = 0;
	b->wraps = 0;
}

void lz_edmd_block_of(const lz_edmd *e, uint32_t c, lz_edmd_block *b)
{
	int cc[3];
	cell_coords(e, c, cc);
	if (cc[0] > 0 && cc[0] < e->m[0] - 1 && cc[1] > 0 && cc[1] < e->m[1] - 1 &&
	    (e->dim == 2 || (cc[2] > 0 && cc[2] < e->m[2] - 1))) {
		block_inside(e, cc, b);
		return;
	}
	uint32_t stride = 1;
	b->wraps = 0;
	for (int a = 0; a < 3; a++) {
		int k = 0, reach = a < e->dim ? 1 : 0;
		for (int d = -reach; d <= reach; d++) {
			int x = cc[a] + d;
			double sh = 0;
			if (x < 0 || x >= e->m[a]) {
				if (e->wall[a])
					continue;
				sh = x < 0 ? -e->L : e->L;
				x += x < 0 ? e->m[a] : -e->m[a];
			}
			b->off[a][k] = (uint32_t)x * stride;
			b->shift[a][k++] = sh;
			b->wraps |= sh != 0;
		}
		b->n[a] = k;
		stride *= (uint32_t)e->m[a];
	}
}

void lz_edmd_prefetch_block(const lz_edmd *e, uint32_t c)
{
	lz_edmd_block b;
	lz_edmd_block_of(e, c, &b);
	/* a row's cells span at most two cache lines: its first and last cells */
	for (int z = 0; z < b.n[2]; z++)
		for (int y = 0; y < b.n[1]; y++) {
			uint32_t row = b.off[1][y] + b.off[2][z];
			uint32_t first = row + b.off[0][0], last = row + b.off[0][b.n[0] - 1];
			__builtin_prefetch(&e->list[first]);
			__builtin_prefetch(&e->list[last]);
		}
}

uint32_t lz_edmd_cell_across(const lz_edmd *e, uint32_t c, int f, double *jump)
{
	int cc[3], a = f / 2;
	cell_coords(e, c, cc);
	cc[a] += f % 2 ? 1 : -1;
	*jump = 0;
	if (cc[a] < 0) {
		cc[a] += e->m[a];
		*jump = e->L;
	} else if (cc[a] >= e->m[a]) {
		cc[a] -= e->m[a];
		*jump = -e->L;
	}
	return cell_index(e, cc);
}

void lz_edmd_cell_remove(lz_edmd *e, uint32_t i)
{
	uint32_t c = e->p[i].cell;
	int32_t *link = &e->list[c].head;
	while (*link != (int32_t)i)
		link = &e->next[*link];
	*link = e->next[i];
	e->list[c].second = e->next[e->list[c].head];
}

void lz_edmd_cell_insert(lz_edmd *e, uint32_t i, uint32_t c)
{
	e->p[i].cell = c;
	e->next[i] = e->list[c].second = e->list[c].head;
	e->list[c].head = (int32_t)i;
}

void lz_edmd_cell_clear(lz_edmd *e)
{
	for (size_t c = 0; c < e->ncells; c++)
		e->list[c].head = e->list[c].second = -1;
}

double lz_edmd_fall_time(double x, double v, double g, double lo, double hi, int *up)
{
	double rise = hi - x, drop = x - lo > 0 ? x - lo : 0;
	if (v > 0) {
		double disc = v * v - 2 * g * rise;
		if (disc >= 0) {
			*up = 1;
			double t = 2 * rise / (v + sqrt(disc));
			return t > 0 ? t : 0;
		}
	}
	*up = 0;
	double root = sqrt(v * v + 2 * g * drop);
	return v >= 0 ? (v + root) / g : 2 * drop / (root - v);
}

uint32_t lz_edmd_cell_of(const lz_edmd *e, const double r[3])
{
	int cc[3];
	for (int a = 0; a < 3; a++) {
		int x = (int)floor(r[a] / e->w[a]);
		cc[a] = x < 0 ? 0 : x >= e->m[a] ? e->m[a] - 1 : x;
	}
	return cell_index(e, cc);
}
