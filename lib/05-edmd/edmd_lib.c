/* edmd_lib.c — the library half of lz/edmd.h: the box and its checks, the initial
 * states and the start, the counters and the overlap check. The cells are in
 * edmd_cells.c, the neighbour lists in edmd_list.c (both called from here, never the
 * other way round); the run, the re-base and the guards in edmd_run.c (which calls
 * this file); the graded event loop in solutions/05-edmd/edmd.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include "lz/bigmem.h"
#include "lz/edmd.h"
#include "lz/error.h"

/* Volume (area) of one particle of diameter 1. */
static double particle_volume(int dim) { return dim == 3 ? M_PI / 6 : M_PI / 4; }

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
	if (p->neighbours != LZ_EDMD_CELLS && p->neighbours != LZ_EDMD_LIST)
		return lz_error(LZ_EINVAL, "neighbours = %d must be cells (%d) or list (%d)",
		                p->neighbours, LZ_EDMD_CELLS, LZ_EDMD_LIST);
	if (p->queue < LZ_EDMD_QUEUE_AUTO || p->queue > LZ_EDMD_CALENDAR)
		return lz_error(LZ_EINVAL, "queue = %d must be automatic (%d), heap (%d), heap4 (%d) "
		                "or calendar (%d)", p->queue, LZ_EDMD_QUEUE_AUTO, LZ_EDMD_HEAP,
		                LZ_EDMD_HEAP4, LZ_EDMD_CALENDAR);
	if ((p->queue == LZ_EDMD_HEAP4 || p->queue == LZ_EDMD_CALENDAR) &&
	    p->neighbours != LZ_EDMD_LIST)
		return lz_error(LZ_EINVAL, "queue = %s (the library's) needs neighbours = list: with "
		                "cells the graded event loop drives the binary heap",
		                p->queue == LZ_EDMD_HEAP4 ? "heap4" : "calendar");
	if (p->neighbours == LZ_EDMD_LIST && p->shell != 0 && !(p->shell > 1 && p->shell <= 4))
		return lz_error(LZ_EINVAL, "shell = %g σ must be in (1, 4] (0: automatic): the "
		                "neighbours are the centres within it, and it must exceed σ",
		                p->shell);
	return LZ_OK;
}

/* The cells per side for p in a box of side L, each at least `reach` wide (σ, or the
 * shell S with lists), or 0 with lz_error. */
static int choose_cells(const lz_edmd_params *p, double L, double reach)
{
	int walled = p->walls == LZ_EDMD_WALLS_BOX;  /* every axis has walls */
	int least = walled ? 1 : 3;
	const char *what = reach > 1 ? "the shell" : "σ";
	if (p->cells == 0) {
		int m = reach > 1 ? lz_edmd_list_cells(p->dim, p->n, L, reach)
		                  : lz_edmd_auto_cells(p->dim, p->n, L);
		if (m == 0 && walled)
			m = L >= reach ? (int)floor(L / reach) : 0;
		if (m > 0)
			return (int)fmin(m, cells_cap(p->dim));
		double nmin = ceil(pow(3.0 * reach, p->dim) * p->packing / particle_volume(p->dim));
		lz_error(LZ_EINVAL,
		         "the box side L = %.4g σ (n = %zu at packing %g) is below 3 times %s "
		         "(%g σ): a periodic box needs at least 3 cells that wide per side (one "
		         "cell per side is refused, not simulated); use n >= %.0f at this packing%s",
		         L, p->n, p->packing, what, reach, nmin,
		         reach > 1 ? ", a narrower shell, or neighbours = cells" : "");
		return 0;
	}
	if (p->cells < least || L / p->cells < reach || p->cells > cells_cap(p->dim)) {
		int most = (int)fmin(floor(L / reach), cells_cap(p->dim));
		lz_error(LZ_EINVAL, "cells = %d per side must be in [%d, %d]: at least %d %s, "
		         "each at least %s (%g σ) wide in a box of side %.4g σ, and at most 2^27 "
		         "cells", p->cells, least, most, least,
		         walled ? "" : "(a periodic block needs three distinct cells)", what, reach,
		         L);
		return 0;
	}
	return p->cells;
}

static int alloc_arrays(lz_edmd *e, int queue)
{
	e->list = lz_bigmem_sparse(e->ncells * sizeof *e->list);  /* see lz_edmd's list */
	e->next = lz_bigmem_alloc((e->n + 1) * sizeof *e->next);
	if (e->next)
		*e->next++ = -1;  /* the sentinel next[-1] */
	e->p = lz_bigmem_alloc(e->n * sizeof *e->p);
	e->ev = lz_bigmem_alloc(e->n * sizeof *e->ev);
	if (!e->list || !e->next || !e->p || !e->ev)
		return lz_error(LZ_ENOMEM, "no memory for %zu particles in %zu cells", e->n,
		                e->ncells);
	/* a calendar's first days: lz_edmd_list_start sizes them from the first events */
	if (queue == LZ_EDMD_CALENDAR)
		return (e->cal = lz_calendar_alloc(e->n, 1.0 / (double)e->n)) ? LZ_OK : LZ_ENOMEM;
	e->heap = lz_heap_alloc_arity(e->n, queue == LZ_EDMD_HEAP4 ? 4 : 2);
	return e->heap ? LZ_OK : LZ_ENOMEM;
}

lz_edmd *lz_edmd_alloc(const lz_edmd_params *p)
{
	if (check_params(p))
		return NULL;
	double L = pow((double)p->n * particle_volume(p->dim) / p->packing, 1.0 / p->dim);
	double shell = p->neighbours != LZ_EDMD_LIST ? 1
	               : p->shell > 0 ? p->shell : lz_edmd_list_shell(p->dim, p->packing);
	int m = choose_cells(p, L, shell);
	if (m > 0 && shell > 1 && p->walls != LZ_EDMD_WALLS_BOX && !(L > 4 * shell - 2)) {
		lz_error(LZ_EINVAL, "the box side L = %.4g σ is too small for the shell %g: two "
		         "neighbours can be 2S - 1 = %g apart, which must stay below L/2 on a "
		         "periodic axis; use a narrower shell, more particles, or neighbours = cells",
		         L, shell, 2 * shell - 1);
		return NULL;
	}
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
	int queue = p->queue != LZ_EDMD_QUEUE_AUTO ? p->queue
	            : p->neighbours == LZ_EDMD_LIST ? LZ_EDMD_CALENDAR : LZ_EDMD_HEAP;
	if (alloc_arrays(e, queue) ||
	    (p->neighbours == LZ_EDMD_LIST && !(e->lists = lz_edmd_list_alloc(e, shell)))) {
		lz_edmd_free(e);
		return NULL;
	}
	return e;
}

int lz_edmd_resize(lz_edmd *e, size_t n)
{
	if (e->lists || e->cal || n < 1 || n >= (size_t)INT32_MAX)
		return lz_error(LZ_EINVAL, "a system of %zu particles resized to %zu: 1 .. 2^31 - 1, "
		                "with cells and a heap", e->n, n);
	int st = lz_heap_resize(e->heap, n);  /* first: it refuses a particle still in it */
	if (st != LZ_OK)
		return st;
	size_t old = e->n;
	int32_t *next = lz_bigmem_resize(e->next - 1, (old + 1) * sizeof *next,
	                                 (n + 1) * sizeof *next);
	if (next)
		e->next = next + 1;
	lz_edmd_particle *p = next ? lz_bigmem_resize(e->p, old * sizeof *p, n * sizeof *p) : NULL;
	if (p)
		e->p = p;
	lz_edmd_event *ev = p ? lz_bigmem_resize(e->ev, old * sizeof *ev, n * sizeof *ev) : NULL;
	if (ev)
		e->ev = ev;
	if (!ev)
		return lz_error(LZ_ENOMEM, "no memory for %zu particles", n);
	for (size_t i = old; i < n; i++) {
		e->p[i] = (lz_edmd_particle){0};
		e->next[i] = -1;
		e->ev[i] = (lz_edmd_event){LZ_EDMD_NONE, 0};
	}
	e->n = n;
	e->prefetch = n >= LZ_EDMD_FAR;  /* as lz_edmd_alloc would set it for n */
	return LZ_OK;
}

void lz_edmd_free(lz_edmd *e)
{
	if (!e)
		return;
	lz_bigmem_sparse_free(e->list, e->ncells * sizeof *e->list);
	lz_bigmem_free(e->next ? e->next - 1 : NULL);
	lz_bigmem_free(e->p);
	lz_bigmem_free(e->ev);
	lz_heap_free(e->heap);
	lz_calendar_free(e->cal);
	lz_edmd_list_free(e->lists);
	free(e);
}

/* ---- the initial state ---- */

/* A lattice of M cells per side with a basis of nb points (in units of the lattice
 * constant) filling the box (on walled axes, the span [1/2, L - 1/2]). */
typedef struct {
	int M, nb, dim;
	const double (*basis)[3];
	double a[3], off[3];  /* the lattice constant and the origin on each axis */
} lattice;

static lattice lattice_of(const lz_edmd *e, int M, const double (*basis)[3], int nb)
{
	lattice g = {M, nb, e->dim, basis, {0, 0, 0}, {0, 0, 0}};
	for (int x = 0; x < e->dim; x++) {
		g.a[x] = (e->wall[x] ? e->L - 1 : e->L) / M;
		g.off[x] = e->wall[x] ? 0.5 : 0;
	}
	return g;
}

/* The sites of g and the nearest distance between two of them. */
static size_t lattice_sites(const lattice *g) { return (size_t)g->nb * (size_t)pow(g->M, g->dim); }
static double lattice_near(const lattice *g)
{
	double amin = INFINITY;
	for (int x = 0; x < g->dim; x++)
		amin = fmin(amin, g->a[x]);
	return g->nb == 1 ? amin : amin / sqrt(2.0);
}

/* Site k of g (x fastest, then y, z; the basis within each cell) into r. */
static void lattice_site(const lattice *g, size_t k, double r[3])
{
	size_t c = k / (size_t)g->nb, M = (size_t)g->M;
	const double *b = g->basis[k % (size_t)g->nb];
	double u[3] = {(double)(c % M) + b[0], (double)(c / M % M) + b[1], (double)(c / (M * M)) + b[2]};
	for (int x = 0; x < 3; x++)
		r[x] = x < g->dim ? g->off[x] + g->a[x] * u[x] : 0;
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

static int settle(lz_edmd *e);

int lz_edmd_place_lattice(lz_edmd *e, lz_rng *rng)
{
	static const double sc[1][3] = {{0.5, 0.5, 0.5}};
	static const double fcc[4][3] = {
	    {0.25, 0.25, 0.25}, {0.75, 0.75, 0.25}, {0.75, 0.25, 0.75}, {0.25, 0.75, 0.75}};
	int M = (int)ceil(pow((double)e->n, 1.0 / e->dim) - 1e-9);
	while (pow(M, e->dim) < (double)e->n)
		M++;
	lattice g = lattice_of(e, M, sc, 1);
	if (lattice_near(&g) < 1 + 1e-9 && e->dim == 3) {
		M = (int)ceil(cbrt((double)e->n / 4) - 1e-9);
		while (4.0 * M * M * M < (double)e->n)
			M++;
		g = lattice_of(e, M, fcc, 4);
	}
	if (lattice_near(&g) < 1 + 1e-9)
		return lz_error(LZ_EINVAL, "%zu particles at packing %.4g do not fit on a lattice: "
		                "its sites would be %.4f σ apart (< σ); lower the packing or use n = "
		                "M^%d (or 4M^3 in 3D) for a full lattice", e->n,
		                e->n * particle_volume(e->dim) / pow(e->L, e->dim), lattice_near(&g),
		                e->dim);
	/* a random subset of the sites, in lattice order, straight into the records: the
	 * selection sampling of gsl_ran_choose (each site taken with the chance of the
	 * places left over the sites left), with its draws, so no array of sites is made
	 * (10^8 particles fit) */
	size_t sites = lattice_sites(&g), j = 0;
	for (size_t k = 0; k < sites && j < e->n; k++)
		if ((double)(sites - k) * gsl_rng_uniform(rng->gsl) < (double)(e->n - j))
			lattice_site(&g, k, e->p[j++].r);
	double shift[3];
	for (int a = 0; a < 3; a++)
		shift[a] = a < e->dim && !e->wall[a] ? e->L * lz_rng_uniform(rng) : 0;
	for (size_t i = 0; i < e->n; i++)
		for (int a = 0; a < 3; a++) {
			double x = e->p[i].r[a] + shift[a];
			e->p[i].r[a] = x < e->L ? x : x - e->L;
		}
	double *v = malloc(3 * e->n * sizeof *v);
	if (!v)
		return lz_error(LZ_ENOMEM, "no memory for the velocities of %zu particles", e->n);
	lz_edmd_maxwell(e, rng, v);
	for (size_t i = 0; i < e->n; i++) {
		memcpy(e->p[i].v, v + 3 * i, sizeof e->p[i].v);
		e->p[i].t0 = 0;
		e->p[i].count = 0;
	}
	free(v);
	return settle(e);
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
	return settle(e);
}

/* The records set: into the cells, checked for overlaps, started. */
static int settle(lz_edmd *e)
{
	lz_edmd_cell_clear(e);
	for (size_t i = e->n; i-- > 0;)
		lz_edmd_cell_insert(e, (uint32_t)i, lz_edmd_cell_of(e, e->p[i].r));
	e->now = 0;
	uint32_t a, b;
	double over = lz_edmd_max_overlap(e, &a, &b);
	if (over > 1e-10)
		return lz_error(LZ_EINVAL, "particles %u and %u overlap: their centres are "
		                "%.10g σ apart, less than σ = 1 (overlap %.3g)", a, b, 1 - over, over);
	return lz_edmd_start(e);
}

int lz_edmd_start(lz_edmd *e)
{
	if (e->lists) {
		int st = lz_edmd_list_start(e);
		lz_edmd_reset_counts(e);
		return st;
	}
	lz_edmd_cell_clear(e);
	for (size_t i = e->n; i-- > 0;) {
		e->p[i].t0 = 0;
		lz_edmd_cell_insert(e, (uint32_t)i, lz_edmd_cell_of(e, e->p[i].r));
	}
	e->now = 0;
	e->since_rebase = 0;
	lz_heap_clear(e->heap);
	lz_edmd_reset_counts(e);
	for (size_t i = 0; i < e->n; i++)
		lz_edmd_predict(e, (uint32_t)i);
	return LZ_OK;
}

void lz_edmd_reset_counts(lz_edmd *e)
{
	e->events = e->collisions = e->crossings = e->bounces = e->stale = e->rebuilds = 0;
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
