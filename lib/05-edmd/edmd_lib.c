/* edmd_lib.c — the library half of lz/edmd.h: cells and their faces, the box and its
 * checks, the initial states and the start, the counters and the overlap check. The
 * run, the re-base and the guards are in edmd_run.c (which calls this file, never
 * the other way round); the graded event loop in solutions/05-edmd/edmd.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include "lz/bigmem.h"
#include "lz/edmd.h"
#include "lz/error.h"

/* Volume (area) of one particle of diameter 1. */
static double particle_volume(int dim) { return dim == 3 ? M_PI / 6 : M_PI / 4; }

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

/* ---- the box ---- */

/* The most cells per side: the largest m with m^dim <= LZ_EDMD_CELLS_MAX. */
static int cells_cap(int dim)
{
	int m = (int)floor(pow((double)LZ_EDMD_CELLS_MAX, 1.0 / dim) + 0.5);
	while (pow(m, dim) > (double)LZ_EDMD_CELLS_MAX)
		m--;
	return m;
}

int lz_edmd_auto_cells(int dim, size_t n, double L)
{
	double most = floor(L);  /* cells no narrower than σ */
	double per = dim == 3 ? 3.0 : 1.5;  /* lesson 05 §6: as fast as 8 here, fewer bytes */
	double want = ceil(pow(per * (double)n, 1.0 / dim));
	double cap = cells_cap(dim);
	double m = fmin(fmin(most, fmax(want, 3)), cap);
	return m < 3 ? 0 : (int)m;
}

static int check_params(const lz_edmd_params *p)
{
	if (p->dim != 2 && p->dim != 3)
		return lz_error(LZ_EINVAL, "dim = %d must be 2 or 3", p->dim);
	if (p->n < 1 || p->n >= ((size_t)1 << 31))
		return lz_error(LZ_EINVAL, "n = %zu particles must be in [1, 2^31)", p->n);
	double close = p->dim == 3 ? LZ_EDMD_CLOSE_3D : LZ_EDMD_CLOSE_2D;
	if (!(p->packing > 0 && p->packing < close))
		return lz_error(LZ_EINVAL,
		                "packing = %g must be in (0, %.4f): %.4f is close packing of %s",
		                p->packing, close, close, p->dim == 3 ? "spheres (fcc)" : "disks");
	if (!(p->restitution > 0 && p->restitution <= 1))
		return lz_error(LZ_EINVAL, "restitution = %g must be in (0, 1]", p->restitution);
	if (!(p->gravity >= 0 && isfinite(p->gravity)))
		return lz_error(LZ_EINVAL, "gravity = %g must be finite and >= 0", p->gravity);
	if (p->walls < LZ_EDMD_WALLS_NONE || p->walls > LZ_EDMD_WALLS_BOX)
		return lz_error(LZ_EINVAL, "walls = %d must be none, x or box", p->walls);
	if (p->gravity > 0 && p->walls == LZ_EDMD_WALLS_NONE)
		return lz_error(LZ_EINVAL, "gravity = %g pulls along -x and needs walls on x "
		                "(walls = x or box): in a periodic box the particles would fall "
		                "for ever", p->gravity);
	return LZ_OK;
}

/* The cells per side for p in a box of side L, or 0 with lz_error. */
static int choose_cells(const lz_edmd_params *p, double L)
{
	int walled = p->walls == LZ_EDMD_WALLS_BOX;  /* every axis has walls */
	int least = walled ? 1 : 3;
	if (p->cells == 0) {
		int m = lz_edmd_auto_cells(p->dim, p->n, L);
		if (m == 0 && walled)
			m = L >= 1 ? (int)floor(L) : 0;
		if (m > 0)
			return m;
		double nmin = ceil(pow(3.0, p->dim) * p->packing / particle_volume(p->dim));
		lz_error(LZ_EINVAL,
		         "the box side L = %.4g σ (n = %zu at packing %g) is below 3σ: a "
		         "periodic box needs at least 3 cells of side σ per side (one cell per "
		         "side is refused, not simulated); use n >= %.0f at this packing",
		         L, p->n, p->packing, nmin);
		return 0;
	}
	if (p->cells < least || L / p->cells < 1 || p->cells > cells_cap(p->dim)) {
		int most = (int)fmin(floor(L), cells_cap(p->dim));
		lz_error(LZ_EINVAL, "cells = %d per side must be in [%d, %d]: at least %d %s, "
		         "each at least σ wide in a box of side %.4g σ, and at most 2^27 cells",
		         p->cells, least, most, least,
		         walled ? "" : "(a periodic block needs three distinct cells)", L);
		return 0;
	}
	return p->cells;
}

static int alloc_arrays(lz_edmd *e)
{
	e->list = lz_bigmem_alloc(e->ncells * sizeof *e->list);
	e->next = lz_bigmem_alloc((e->n + 1) * sizeof *e->next);
	if (e->next)
		*e->next++ = -1;  /* the sentinel next[-1] */
	e->p = lz_bigmem_alloc(e->n * sizeof *e->p);
	e->ev = lz_bigmem_alloc(e->n * sizeof *e->ev);
	if (!e->list || !e->next || !e->p || !e->ev)
		return lz_error(LZ_ENOMEM, "no memory for %zu particles in %zu cells", e->n,
		                e->ncells);
	e->heap = lz_heap_alloc(e->n);
	return e->heap ? LZ_OK : LZ_ENOMEM;
}

lz_edmd *lz_edmd_alloc(const lz_edmd_params *p)
{
	if (check_params(p))
		return NULL;
	double L = pow((double)p->n * particle_volume(p->dim) / p->packing, 1.0 / p->dim);
	int m = choose_cells(p, L);
	if (m == 0)
		return NULL;
	lz_edmd *e = calloc(1, sizeof *e);
	if (!e) {
		lz_error(LZ_ENOMEM, "no memory for the system");
		return NULL;
	}
	e->dim = p->dim;
	e->n = p->n;
	e->L = L;
	e->restitution = p->restitution;
	e->g = p->gravity;
	e->sort_every = 0;  /* lesson 05 §9: no gain measured once the loop prefetches */
	e->prefetch = p->n >= LZ_EDMD_FAR;
	e->rebase_auto = 1;
	for (int a = 0; a < 3; a++) {
		e->wall[a] = a < p->dim && (p->walls == LZ_EDMD_WALLS_BOX ||
		                            (a == 0 && p->walls == LZ_EDMD_WALLS_X));
		e->m[a] = a < p->dim ? m : 1;
		e->w[a] = L / e->m[a];
	}
	if (e->wall[0] && !e->wall[1] && m < 3) {
		lz_error(LZ_EINVAL, "the box side L = %.4g σ is below 3σ: the periodic axes "
		         "need at least 3 cells", L);
		lz_edmd_free(e);
		return NULL;
	}
	e->ncells = (size_t)e->m[0] * e->m[1] * e->m[2];
	if (alloc_arrays(e)) {
		lz_edmd_free(e);
		return NULL;
	}
	return e;
}

void lz_edmd_free(lz_edmd *e)
{
	if (!e)
		return;
	lz_bigmem_free(e->list);
	lz_bigmem_free(e->next ? e->next - 1 : NULL);
	lz_bigmem_free(e->p);
	lz_bigmem_free(e->ev);
	lz_heap_free(e->heap);
	free(e);
}

/* ---- the initial state ---- */

/* The sites of a lattice of M per side (basis of nb points, in units of the lattice
 * constant) filling the box (on walled axes, the span [1/2, L - 1/2]) into r, 3 per
 * site; returns the number of sites and in *near the nearest distance between two. */
static size_t lattice_sites(const lz_edmd *e, int M, const double (*basis)[3], int nb,
                            double *r, double *near)
{
	double a[3], off[3];
	for (int x = 0; x < 3; x++) {
		double span = e->wall[x] ? e->L - 1 : e->L;
		a[x] = x < e->dim ? span / M : 0;
		off[x] = e->wall[x] ? 0.5 : 0;
	}
	size_t k = 0;
	int Mz = e->dim == 3 ? M : 1;
	for (int z = 0; z < Mz; z++)
		for (int y = 0; y < M; y++)
			for (int x = 0; x < M; x++)
				for (int b = 0; b < nb; b++, k++) {
					double u[3] = {x + basis[b][0], y + basis[b][1], z + basis[b][2]};
					for (int c = 0; c < 3; c++)
						r[3 * k + c] = c < e->dim ? off[c] + a[c] * u[c] : 0;
				}
	double amin = INFINITY;
	for (int x = 0; x < e->dim; x++)
		amin = fmin(amin, a[x]);
	*near = nb == 1 ? amin : amin / sqrt(2.0);
	return k;
}

void lz_edmd_maxwell(const lz_edmd *e, lz_rng *rng, double *v)
{
	double P[3] = {0, 0, 0}, ke = 0;
	for (size_t i = 0; i < e->n; i++)
		for (int a = 0; a < 3; a++) {
			v[3 * i + a] = a < e->dim ? gsl_ran_gaussian(rng->gsl, 1.0) : 0;
			P[a] += v[3 * i + a];
		}
	for (size_t i = 0; i < e->n; i++)
		for (int a = 0; a < 3; a++) {
			if (e->n > 1)
				v[3 * i + a] -= P[a] / (double)e->n;
			ke += 0.5 * v[3 * i + a] * v[3 * i + a];
		}
	double scale = ke > 0 ? sqrt(0.5 * e->dim * (double)e->n / ke) : 0;
	for (size_t i = 0; i < 3 * e->n; i++)
		v[i] *= scale;
}

int lz_edmd_place_lattice(lz_edmd *e, lz_rng *rng)
{
	static const double sc[1][3] = {{0.5, 0.5, 0.5}};
	static const double fcc[4][3] = {
	    {0.25, 0.25, 0.25}, {0.75, 0.75, 0.25}, {0.75, 0.25, 0.75}, {0.25, 0.75, 0.75}};
	int M = (int)ceil(pow((double)e->n, 1.0 / e->dim) - 1e-9);
	while (pow(M, e->dim) < (double)e->n)
		M++;
	const double(*basis)[3] = sc;
	int nb = 1;
	double near = (e->wall[0] ? e->L - 1 : e->L) / M;
	if (near < 1 + 1e-9 && e->dim == 3) {
		basis = fcc;
		nb = 4;
		M = (int)ceil(cbrt((double)e->n / 4) - 1e-9);
		while (4.0 * M * M * M < (double)e->n)
			M++;
	}
	size_t sites = (size_t)nb * (size_t)pow(M, e->dim);
	double *site = malloc(3 * sites * sizeof *site);
	double *r = malloc(3 * e->n * sizeof *r), *v = malloc(3 * e->n * sizeof *v);
	int st = LZ_OK;
	if (!site || !r || !v) {
		st = lz_error(LZ_ENOMEM, "no memory for %zu lattice sites", sites);
	} else {
		lattice_sites(e, M, basis, nb, site, &near);
		if (near < 1 + 1e-9) {
			st = lz_error(LZ_EINVAL,
			              "%zu particles at packing %.4g do not fit on a lattice: its "
			              "sites would be %.4f σ apart (< σ); lower the packing or use "
			              "n = M^%d (or 4M^3 in 3D) for a full lattice",
			              e->n, e->n * particle_volume(e->dim) / pow(e->L, e->dim), near,
			              e->dim);
		} else {
			/* a random subset of the sites, kept in lattice order */
			size_t *idx = malloc(sites * sizeof *idx), *pick = malloc(e->n * sizeof *pick);
			if (!idx || !pick) {
				st = lz_error(LZ_ENOMEM, "no memory for %zu lattice sites", sites);
			} else {
				for (size_t k = 0; k < sites; k++)
					idx[k] = k;
				gsl_ran_choose(rng->gsl, pick, e->n, idx, sites, sizeof *idx);
				double shift[3];
				for (int a = 0; a < 3; a++)
					shift[a] = a < e->dim && !e->wall[a] ? e->L * lz_rng_uniform(rng) : 0;
				for (size_t i = 0; i < e->n; i++)
					for (int a = 0; a < 3; a++) {
						double x = site[3 * pick[i] + a] + shift[a];
						r[3 * i + a] = x < e->L ? x : x - e->L;
					}
				lz_edmd_maxwell(e, rng, v);
				st = lz_edmd_set(e, r, v);
			}
			free(idx);
			free(pick);
		}
	}
	free(site);
	free(r);
	free(v);
	return st;
}

/* The cell of position r (inside the box). */
static uint32_t cell_of(const lz_edmd *e, const double r[3])
{
	int cc[3];
	for (int a = 0; a < 3; a++) {
		int x = (int)floor(r[a] / e->w[a]);
		cc[a] = x < 0 ? 0 : x >= e->m[a] ? e->m[a] - 1 : x;
	}
	return cell_index(e, cc);
}

/* Check and copy particle i's state: NaN, outside the box, beyond a wall contact. */
static int set_one(lz_edmd *e, size_t i, const double *r, const double *v)
{
	lz_edmd_particle *p = &e->p[i];
	for (int a = 0; a < 3; a++) {
		double x = a < e->dim ? r[3 * i + a] : 0, u = a < e->dim ? v[3 * i + a] : 0;
		if (!isfinite(x) || !isfinite(u))
			return lz_error(LZ_EINVAL, "particle %zu: position or velocity is not a "
			                "finite number", i);
		if (e->wall[a] && (x < 0.5 - 1e-12 || x > e->L - 0.5 + 1e-12))
			return lz_error(LZ_EINVAL, "particle %zu: %c = %.10g is beyond the wall "
			                "contacts [0.5, %.10g]", i, "xyz"[a], x, e->L - 0.5);
		if (!e->wall[a] && a < e->dim) {
			if (!(x >= -1e-12 && x <= e->L + 1e-12))
				return lz_error(LZ_EINVAL, "particle %zu: %c = %.10g is outside the box "
				                "[0, L = %.10g)", i, "xyz"[a], x, e->L);
			x -= e->L * floor(x / e->L);  /* a hair outside: round-off, wrapped */
			if (x >= e->L)
				x = 0;
		}
		p->r[a] = x;
		p->v[a] = u;
	}
	p->t0 = 0;
	p->count = 0;
	return LZ_OK;
}

int lz_edmd_set(lz_edmd *e, const double *r, const double *v)
{
	for (size_t i = 0; i < e->n; i++) {
		int st = set_one(e, i, r, v);
		if (st)
			return st;
	}
	lz_edmd_cell_clear(e);
	for (size_t i = e->n; i-- > 0;)
		lz_edmd_cell_insert(e, (uint32_t)i, cell_of(e, e->p[i].r));
	e->now = 0;
	uint32_t a, b;
	double over = lz_edmd_max_overlap(e, &a, &b);
	if (over > 1e-10)
		return lz_error(LZ_EINVAL, "particles %u and %u overlap: their centres are "
		                "%.10g σ apart, less than σ = 1 (overlap %.3g)", a, b, 1 - over, over);
	lz_edmd_start(e);
	return LZ_OK;
}

void lz_edmd_start(lz_edmd *e)
{
	lz_edmd_cell_clear(e);
	for (size_t i = e->n; i-- > 0;) {
		e->p[i].t0 = 0;
		lz_edmd_cell_insert(e, (uint32_t)i, cell_of(e, e->p[i].r));
	}
	e->now = 0;
	e->since_rebase = 0;
	lz_heap_clear(e->heap);
	lz_edmd_reset_counts(e);
	for (size_t i = 0; i < e->n; i++)
		lz_edmd_predict(e, (uint32_t)i);
}

void lz_edmd_reset_counts(lz_edmd *e)
{
	e->events = e->collisions = e->crossings = e->bounces = e->stale = 0;
	e->virial = 0;
	e->coll_mark = 0;
	e->t_reset = lz_edmd_time(e);
}

double lz_edmd_max_overlap(const lz_edmd *e, uint32_t *pi, uint32_t *pj)
{
	double worst = 0;
	lz_edmd_block b;
	for (uint32_t i = 0; i < e->n; i++) {
		double ri[3], vi[3];
		lz_edmd_state(e, &e->p[i], e->now, ri, vi);
		lz_edmd_block_of(e, e->p[i].cell, &b);
		for (int z = 0; z < b.n[2]; z++)
			for (int y = 0; y < b.n[1]; y++)
				for (int x = 0; x < b.n[0]; x++) {
					uint32_t c = b.off[0][x] + b.off[1][y] + b.off[2][z];
					double sh[3] = {b.shift[0][x], b.shift[1][y], b.shift[2][z]};
					for (int32_t j = e->list[c].head; j >= 0; j = e->next[j]) {
						if ((uint32_t)j <= i)
							continue;
						double rj[3], vj[3], d2 = 0;
						lz_edmd_state(e, &e->p[j], e->now, rj, vj);
						for (int a = 0; a < 3; a++) {
							double d = rj[a] + sh[a] - ri[a];
							d2 += d * d;
						}
						if (d2 < 1 && 1 - sqrt(d2) > worst) {
							worst = 1 - sqrt(d2);
							if (pi)
								*pi = i;
							if (pj)
								*pj = (uint32_t)j;
						}
					}
				}
	}
	return worst;
}
