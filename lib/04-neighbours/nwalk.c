/* nwalk.c — one hard-disk random walk, four ways to find the neighbours (lz/nwalk.h,
 * thesis table 2.2): Verlet lists rebuilt from all pairs (NL), the same lists refreshed
 * from the neighbours of the neighbours (FNL), cell lists (CL), the field (FR).
 *
 * Every driver draws one direction per move, in index order, with the same call, and
 * tests the step against exactly the particles it can see with the same integer rule
 * (distance² < ceil(σ²)). So while its structure sees every pair closer than r_c, a
 * driver makes the decisions of all pairs and the four trajectories are the same, bit
 * for bit. Each driver has its own sweep function: the hot loop holds nothing a scene
 * does not use. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/nwalk.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/walk.h"

static const char *const driver_names[] = {"nl", "fnl", "cl", "fr"};
enum { NDRIVERS = sizeof driver_names / sizeof driver_names[0] };

const char *lz_nwalk_driver_name(lz_nwalk_driver d)
{
	return (unsigned)d < NDRIVERS ? driver_names[d] : "unknown";
}

int lz_nwalk_driver_parse(const char *name, lz_nwalk_driver *d)
{
	for (int k = 0; name && k < NDRIVERS; k++)
		if (strcmp(name, driver_names[k]) == 0) {
			*d = (lz_nwalk_driver)k;
			return LZ_OK;
		}
	return lz_error(LZ_EINVAL, "driver '%s' is unknown: the choices are nl (Verlet list, "
	                "all-pairs rebuild), fnl (fast refresh), cl (cell lists), fr (field)",
	                name ? name : "(null)");
}

/* ---- geometry ---- */

/* The longest step of the lattice: 1, √2 or √3. */
static double longest_step(lz_lattice_kind kind)
{
	int ndir;
	const lz_site *dirs = lz_lattice_dirs(kind, &ndir);
	int64_t most = 0;
	for (int d = 0; d < ndir; d++) {
		int64_t e2 = lz_lattice_dist2(kind, dirs[d].x, dirs[d].y, dirs[d].z);
		most = e2 > most ? e2 : most;
	}
	return sqrt((double)most);
}

/* The ranges of lz/nwalk.h's header comment. FR has no lists: r_l = r_c, no refresh. */
typedef struct {
	double sigma, lmax, rc, rl;
	int refresh_safe;
} ranges;

static ranges ranges_of(const lz_nwalk_params *p)
{
	ranges g;
	g.sigma = 2 * p->radius;
	g.lmax = longest_step(p->kind);
	g.rc = g.sigma + g.lmax;
	int lists = p->driver != LZ_NWALK_FR;
	g.rl = g.rc + (lists ? p->skin : 0);
	/* The tolerance keeps Δr / (2 lmax) = 2 (Δr = 4√2 on square8) from rounding down. */
	g.refresh_safe = lists && p->skin < 1e9 ? (int)floor(p->skin / (2 * g.lmax) + 1e-9) : 0;
	return g;
}

/* The cells per side of the lattice grid lz_cells_alloc_lattice makes for cutoff r:
 * side w the smallest power of two >= the reach of r, doubled while the grid would pass
 * LZ_CELLS_MAX. Asked before allocating, so that a box too small for a grid is known
 * without an error. */
static int64_t grid_cells(lz_lattice_kind kind, int64_t side, double r, int64_t *width)
{
	int dim = lz_lattice_dim(kind);
	double reach = lz_lattice_reach(kind, r);
	int64_t w = 1;
	while ((double)w < reach && w < side)
		w *= 2;
	while (pow((double)(side / w), dim) > (double)LZ_CELLS_MAX)
		w *= 2;
	if (width)
		*width = w;
	return side / w;
}

/* ---- the checks ---- */

static int check_box(const lz_nwalk_params *p, int dim)
{
	double sites = pow((double)p->side, dim);
	if (p->side < 2 || sites > (double)LZ_FIELD_SITES_MAX)
		return lz_error(LZ_EINVAL, "side L = %lld: the placement paints a field of L^%d "
		                "bytes, so 2 <= L <= %d in %dD", (long long)p->side, dim,
		                dim == 2 ? 32768 : 1024, dim);
	if (!(p->radius > 0) || !isfinite(p->radius) || 4 * p->radius > (double)p->side)
		return lz_error(LZ_EINVAL, "radius R = %g lattice units: a disk must not reach its "
		                "own periodic image, 2σ = 4R <= L; allowed 0 < R <= %g for L = %lld",
		                p->radius, (double)p->side / 4, (long long)p->side);
	if (p->n == 0 || p->n > (size_t)INT32_MAX)
		return lz_error(LZ_EINVAL, "n = %zu particles: allowed 1 <= n <= %ld", p->n,
		                (long)INT32_MAX);
	double eta = lz_walk_packing(p->kind, p->side, p->radius, p->n);
	double close = dim == 2 ? LZ_WALK_CLOSE_2D : LZ_WALK_CLOSE_3D;
	if (eta > close)
		return lz_error(LZ_EINVAL, "n = %zu disks of radius %g in a box of side %lld pack "
		                "η = %.4f, beyond close packing %.4f: allowed η in (0, %.4f], and "
		                "random placement jams near %s", p->n, p->radius, (long long)p->side,
		                eta, close, close, dim == 2 ? "0.547" : "0.38");
	return LZ_OK;
}

/* The skin, the interval and the ranges the lists and cells need. */
static int check_lists(const lz_nwalk_params *p, const ranges *g)
{
	if (p->refresh < 0)
		return lz_error(LZ_EINVAL, "refresh = %d sweeps: allowed 0 (the safe interval) or "
		                "a positive interval", p->refresh);
	if (p->driver == LZ_NWALK_FR)
		return LZ_OK;
	if (!(p->skin > 0) || !isfinite(p->skin))
		return lz_error(LZ_EINVAL, "skin Δr = %g lattice units: the %s driver needs a "
		                "positive, finite skin (a zero skin would need a refresh before "
		                "every step); allowed Δr > 0", p->skin,
		                lz_nwalk_driver_name(p->driver));
	double half = (double)p->side / 2;
	if (p->driver != LZ_NWALK_CL && g->rl > half)
		return lz_error(LZ_EINVAL, "list radius r_l = σ + lmax + Δr = %g is a cutoff larger "
		                "than L/2 = %g: a pair could be listed through two images; allowed "
		                "Δr <= %g here (or a larger box)", g->rl, half, half - g->rc);
	int64_t w;
	if (p->driver == LZ_NWALK_CL && grid_cells(p->kind, p->side, g->rl, &w) < 3)
		return lz_error(LZ_EINVAL, "cell lists need at least 3 cells per side no narrower "
		                "than r_l = σ + lmax + Δr = %g (reach %g: cells %lld wide, a power of "
		                "two), and the box of side %lld holds fewer; take a smaller skin or "
		                "radius, or L >= %lld", g->rl, lz_lattice_reach(p->kind, g->rl),
		                (long long)w, (long long)p->side, 4 * (long long)w);
	if (p->refresh == 0 && g->refresh_safe == 0)
		return lz_error(LZ_EINVAL, "skin Δr = %g is shorter than two steps (2 lmax = %g): "
		                "no interval is safe (refresh_safe = 0); take skin >= %g, or give "
		                "refresh explicitly to measure the misses", p->skin, 2 * g->lmax,
		                2 * g->lmax);
	return LZ_OK;
}

int lz_nwalk_check(const lz_nwalk_params *p)
{
	if ((unsigned)p->driver >= NDRIVERS)
		return lz_error(LZ_EINVAL, "driver = %d: allowed nl, fnl, cl, fr", (int)p->driver);
	int dim = lz_lattice_kind_side_check(p->kind, p->side);
	if (dim == 0)
		return LZ_EINVAL;
	int status = check_box(p, dim);
	ranges g = ranges_of(p);
	if (status == LZ_OK)
		status = check_lists(p, &g);
	if (status == LZ_OK && p->renumber && grid_cells(p->kind, p->side, g.rc, NULL) < 3)
		status = lz_error(LZ_EINVAL, "renumbering the particles cell by cell needs 3 cells "
		                  "per side no narrower than r_c = %g, and the box of side %lld holds "
		                  "fewer: keep the particles as placed (cell_order = none)", g.rc,
		                  (long long)p->side);
	return status;
}

/* ---- the structures ---- */

/* Fixed arrays per CL cell: twice the most disks of radius R that fit without overlap
 * in a cell of side w — the area (volume) of the cell grown by R all round over that of
 * a disk (sphere), and at most one per site. The factor 2 leaves room for the overlaps
 * of an unsafe interval. */
static size_t cell_capacity(const lz_nwalk *nw, int64_t width)
{
	double w = (double)width, R = nw->p.radius;
	double room = nw->dim == 2
	              ? (w * w * lz_lattice_cell_volume(nw->p.kind) + 4 * w * R + M_PI * R * R) /
	                (M_PI * R * R)
	              : (w * w * w + 6 * w * w * R + 3 * M_PI * w * R * R + 4.0 / 3 * M_PI * R * R * R) /
	                (4.0 / 3 * M_PI * R * R * R);
	double sites = pow(w, nw->dim);
	return 2 * (size_t)ceil(room < sites ? room : sites);
}

/* CL: bin the particles and rebuild the store the sweeps read. */
static int cells_rebuild(lz_nwalk *nw)
{
	int status = lz_cells_bin_sites(nw->cells, nw->p.n, nw->r);
	if (status != LZ_OK)
		return status;
	if (nw->p.linked) {
		lz_cells_link(nw->cells);
		return LZ_OK;
	}
	return lz_cells_fill(nw->cells);
}

/* NL, FNL: the refresh of the driver. */
static int lists_refresh(lz_nwalk *nw)
{
	if (nw->p.driver == LZ_NWALK_NL)
		return lz_nlist_build_allpairs(nw->nl, nw->r);
	return nw->p.single ? lz_nlist_refresh_single(nw->nl, nw->r)
	                    : lz_nlist_refresh(nw->nl, nw->r);
}

/* FNL's first list, from cells of side >= r_l; in a box too small for such a grid
 * (r_l <= L/2 still), from all pairs. */
static int fnl_first_build(lz_nwalk *nw)
{
	if (grid_cells(nw->p.kind, nw->p.side, nw->rl, NULL) < 3)
		return lz_nlist_build_allpairs(nw->nl, nw->r);
	lz_cells *c = lz_cells_alloc_lattice(nw->p.kind, nw->p.side, nw->rl, nw->p.order,
	                                     nw->p.n, 0);
	if (!c)
		return LZ_ENOMEM;
	int status = lz_cells_bin_sites(c, nw->p.n, nw->r);
	if (status == LZ_OK) {
		lz_cells_link(c);
		status = lz_nlist_build_cells(nw->nl, c, nw->r);
	}
	lz_cells_free(c);
	return status;
}

static int build_driver(lz_nwalk *nw)
{
	switch (nw->p.driver) {
	case LZ_NWALK_NL:
	case LZ_NWALK_FNL:
		nw->nl = lz_nlist_alloc(nw->box, nw->p.n, nw->rl);
		if (!nw->nl)
			return LZ_ENOMEM;
		return nw->p.driver == LZ_NWALK_NL ? lz_nlist_build_allpairs(nw->nl, nw->r)
		                                   : fnl_first_build(nw);
	case LZ_NWALK_CL: {
		int64_t w;
		grid_cells(nw->p.kind, nw->p.side, nw->rl, &w);
		nw->cells = lz_cells_alloc_lattice(nw->p.kind, nw->p.side, nw->rl, nw->p.order,
		                                   nw->p.n, nw->p.linked ? 0 : cell_capacity(nw, w));
		return nw->cells ? cells_rebuild(nw) : LZ_ENOMEM;
	}
	case LZ_NWALK_FR:
		return LZ_OK;
	}
	return LZ_EINVAL;
}

/* Random sequential adsorption of n particles on a field of the box (every driver
 * starts from the same configuration for the same rng state). FR keeps the field and
 * its positions; the others copy the positions and drop it. */
static int place(lz_nwalk *nw, gsl_rng *rng)
{
	const lz_nwalk_params *p = &nw->p;
	lz_field *f = lz_field_alloc(p->kind, p->side, p->radius);
	if (!f)
		return LZ_ENOMEM;
	int jammed, status = lz_field_rsa(f, rng, p->n, &jammed);
	if (status == LZ_OK && f->n < p->n)
		status = lz_error(LZ_EPHYS, "n = %zu particles (packing %.4f) cannot be placed: "
		                  "random sequential adsorption jammed at %zu (coverage %.4f), no "
		                  "free site left; it jams near the coverage %s, so ask for less",
		                  p->n, lz_walk_packing(p->kind, p->side, p->radius, p->n), f->n,
		                  lz_field_coverage(f), nw->dim == 2 ? "0.547 in 2D" : "0.38 in 3D");
	if (status == LZ_OK && p->driver == LZ_NWALK_FR) {
		nw->field = f;
		nw->r = f->r;
		return LZ_OK;
	}
	size_t bytes = p->n * (size_t)nw->dim * sizeof *nw->r;
	if (status == LZ_OK && !(nw->r = malloc(bytes)))
		status = lz_error(LZ_ENOMEM, "no memory for %zu positions", p->n);
	if (status == LZ_OK)
		memcpy(nw->r, f->r, bytes);
	lz_field_free(f);
	return status;
}

/* Number the particles cell by cell, the cells in the grid's order, so that particles
 * near in space are near in memory. The field's bytes count particles without naming
 * them, so for FR permuting its r is all there is to do. */
static int renumber(lz_nwalk *nw)
{
	size_t n = nw->p.n, dim = (size_t)nw->dim;
	int status = lz_cells_bin_sites(nw->truth, n, nw->r);
	if (status == LZ_OK)
		status = lz_cells_permutation(nw->truth, nw->scratch);
	int32_t *old = status == LZ_OK ? malloc(n * dim * sizeof *old) : NULL;
	if (status == LZ_OK && !old)
		status = lz_error(LZ_ENOMEM, "no memory to renumber %zu particles", n);
	if (status != LZ_OK)
		return status;
	memcpy(old, nw->r, n * dim * sizeof *old);
	for (size_t k = 0; k < n; k++)
		memcpy(nw->r + k * dim, old + (size_t)nw->scratch[k] * dim, dim * sizeof *old);
	free(old);
	return LZ_OK;
}

/* The box, the ranges and the interval. */
static int setup(lz_nwalk *nw)
{
	const lz_nwalk_params *p = &nw->p;
	ranges g = ranges_of(p);
	nw->dim = lz_lattice_dim(p->kind);
	nw->box = lz_lattice_box_alloc(p->kind, p->side);
	if (!nw->box)
		return LZ_ENOMEM;
	nw->dirs = lz_lattice_dirs(p->kind, &nw->ndir);
	nw->sigma2 = (int64_t)ceil(g.sigma * g.sigma);
	nw->lmax = g.lmax;
	nw->rc = g.rc;
	nw->rl = g.rl;
	nw->rc2 = (int64_t)ceil(g.rc * g.rc);
	nw->refresh_safe = g.refresh_safe;
	nw->refresh = p->driver == LZ_NWALK_FR ? 0 : p->refresh ? p->refresh : g.refresh_safe;
	nw->scratch = malloc(p->n * sizeof *nw->scratch);
	if (!nw->scratch)
		return lz_error(LZ_ENOMEM, "no memory for %zu particles", p->n);
	return LZ_OK;
}

lz_nwalk *lz_nwalk_alloc(const lz_nwalk_params *p, gsl_rng *rng)
{
	if (lz_nwalk_check(p) != LZ_OK)
		return NULL;
	lz_nwalk *nw = calloc(1, sizeof *nw);
	if (!nw)
		return lz_error(LZ_ENOMEM, "no memory for a walk"), NULL;
	nw->p = *p;
	int status = setup(nw);
	if (status == LZ_OK)
		status = place(nw, rng);
	/* The audit's grid; a box too small for one is audited over all pairs (it then
	 * holds a few dozen particles at most). */
	if (status == LZ_OK && grid_cells(p->kind, p->side, nw->rc, NULL) >= 3 &&
	    !(nw->truth = lz_cells_alloc_lattice(p->kind, p->side, nw->rc, p->order, p->n, 0)))
		status = LZ_ENOMEM;
	if (status == LZ_OK && p->renumber)
		status = renumber(nw);
	if (status == LZ_OK)
		status = build_driver(nw);
	if (status != LZ_OK) {
		lz_nwalk_free(nw);
		return NULL;
	}
	return nw;
}

void lz_nwalk_free(lz_nwalk *nw)
{
	if (!nw)
		return;
	if (!nw->field)
		free(nw->r);
	lz_field_free(nw->field);
	lz_nlist_free(nw->nl);
	lz_cells_free(nw->cells);
	lz_cells_free(nw->truth);
	lz_lattice_box_free(nw->box);
	free(nw->scratch);
	free(nw);
}

/* ---- the sweeps ---- */

/* The minimum-image distance² from site (x, y, z) to the particle at rj. */
static inline int64_t dist2_to(const lz_lattice_box *b, int dim, int32_t x, int32_t y,
                               int32_t z, const int32_t *rj)
{
	return lz_lattice_min_dist2(b, x - rj[0], y - rj[1], dim == 3 ? z - rj[2] : 0);
}

/* The site one step e from ri, wrapped, in t[0 .. 2] (t[2] = 0 in 2D). */
static inline void step_target(const int32_t *ri, const lz_site *e, uint32_t mask, int dim,
                               int32_t *t)
{
	t[0] = (int32_t)((uint32_t)(ri[0] + e->x) & mask);
	t[1] = (int32_t)((uint32_t)(ri[1] + e->y) & mask);
	t[2] = dim == 3 ? (int32_t)((uint32_t)(ri[2] + e->z) & mask) : 0;
}

static inline void step_accept(int32_t *ri, const int32_t *t, int dim)
{
	ri[0] = t[0];
	ri[1] = t[1];
	if (dim == 3)
		ri[2] = t[2];
}

/* NL, FNL: a step is tested against the particle's row. */
static void sweeps_rows(lz_nwalk *nw, gsl_rng *rng, uint64_t count)
{
	const lz_nlist *nl = nw->nl;
	const lz_lattice_box *b = nw->box;
	int dim = nw->dim;
	size_t n = nw->p.n;
	uint32_t mask = (uint32_t)b->mask;
	unsigned long ndir = (unsigned long)nw->ndir;
	int64_t s2 = nw->sigma2;
	int32_t *r = nw->r;
	uint64_t accepted = 0, tests = 0;
	for (uint64_t s = 0; s < count; s++)
		for (size_t i = 0; i < n; i++) {
			int32_t t[3], *ri = r + i * (size_t)dim;
			step_target(ri, &nw->dirs[gsl_rng_uniform_int(rng, ndir)], mask, dim, t);
			size_t len, k = 0;
			const uint32_t *row = lz_nlist_row(nl, i, &len);
			while (k < len && dist2_to(b, dim, t[0], t[1], t[2], r + row[k] * (size_t)dim) >= s2)
				k++;
			tests += k + (k < len);
			if (k == len) {
				step_accept(ri, t, dim);
				accepted++;
			}
		}
	nw->accepted += accepted;
	nw->candidates += tests;
}

/* CL, linked lists: a step is tested against every other particle of the 3^dim cells
 * around the particle's cell as last binned. */
static void sweeps_linked(lz_nwalk *nw, gsl_rng *rng, uint64_t count)
{
	const lz_cells *c = nw->cells;
	const lz_lattice_box *b = nw->box;
	int dim = nw->dim, nfull = c->nfull;
	size_t n = nw->p.n;
	uint32_t mask = (uint32_t)b->mask;
	unsigned long ndir = (unsigned long)nw->ndir;
	int64_t s2 = nw->sigma2;
	int32_t *r = nw->r;
	uint64_t accepted = 0, tests = 0;
	for (uint64_t s = 0; s < count; s++)
		for (size_t i = 0; i < n; i++) {
			int32_t t[3], *ri = r + i * (size_t)dim;
			step_target(ri, &nw->dirs[gsl_rng_uniform_int(rng, ndir)], mask, dim, t);
			const uint32_t *block = c->full + (size_t)c->of[i] * (size_t)nfull;
			int clear = 1;
			for (int q = 0; q < nfull && clear; q++)
				for (int32_t j = c->head[block[q]]; j >= 0; j = c->next[j]) {
					if ((size_t)j == i)
						continue;
					tests++;
					if (dist2_to(b, dim, t[0], t[1], t[2], r + (size_t)j * (size_t)dim) < s2) {
						clear = 0;
						break;
					}
				}
			if (clear) {
				step_accept(ri, t, dim);
				accepted++;
			}
		}
	nw->accepted += accepted;
	nw->candidates += tests;
}

/* CL, fixed arrays: the same test, the cell's particles read from its contiguous slots. */
static void sweeps_arrays(lz_nwalk *nw, gsl_rng *rng, uint64_t count)
{
	const lz_cells *c = nw->cells;
	const lz_lattice_box *b = nw->box;
	int dim = nw->dim, nfull = c->nfull;
	size_t n = nw->p.n, cap = c->cap;
	uint32_t mask = (uint32_t)b->mask;
	unsigned long ndir = (unsigned long)nw->ndir;
	int64_t s2 = nw->sigma2;
	int32_t *r = nw->r;
	uint64_t accepted = 0, tests = 0;
	for (uint64_t s = 0; s < count; s++)
		for (size_t i = 0; i < n; i++) {
			int32_t t[3], *ri = r + i * (size_t)dim;
			step_target(ri, &nw->dirs[gsl_rng_uniform_int(rng, ndir)], mask, dim, t);
			const uint32_t *block = c->full + (size_t)c->of[i] * (size_t)nfull;
			int clear = 1;
			for (int q = 0; q < nfull && clear; q++) {
				const uint32_t *slot = c->slot + (size_t)block[q] * cap;
				for (uint32_t k = 0, m = c->count[block[q]]; k < m; k++) {
					if (slot[k] == i)
						continue;
					tests++;
					if (dist2_to(b, dim, t[0], t[1], t[2], r + (size_t)slot[k] * (size_t)dim) < s2) {
						clear = 0;
						break;
					}
				}
			}
			if (clear) {
				step_accept(ri, t, dim);
				accepted++;
			}
		}
	nw->accepted += accepted;
	nw->candidates += tests;
}

/* FR: one look-up per step, a head/tail repaint per accepted one. */
static void sweeps_field(lz_nwalk *nw, gsl_rng *rng, uint64_t count)
{
	lz_field *f = nw->field;
	size_t n = nw->p.n;
	unsigned long ndir = (unsigned long)nw->ndir;
	uint64_t accepted = 0;
	for (uint64_t s = 0; s < count; s++)
		for (size_t i = 0; i < n; i++) {
			int d = (int)gsl_rng_uniform_int(rng, ndir);
			if (lz_field_can_move(f, i, d)) {
				lz_field_move(f, i, d);
				accepted++;
			}
		}
	nw->accepted += accepted;
}

static void sweeps(lz_nwalk *nw, gsl_rng *rng, uint64_t count)
{
	switch (nw->p.driver) {
	case LZ_NWALK_NL:
	case LZ_NWALK_FNL:
		sweeps_rows(nw, rng, count);
		break;
	case LZ_NWALK_CL:
		(nw->p.linked ? sweeps_linked : sweeps_arrays)(nw, rng, count);
		break;
	case LZ_NWALK_FR:
		sweeps_field(nw, rng, count);
		break;
	}
	nw->moves += count * nw->p.n;
	nw->sweeps += count;
	nw->since += count;
}

/* ---- pairs through a fresh binning: the audit and the overlaps ---- */

/* 1 if j is on row i. */
static int on_row(const lz_nlist *nl, uint32_t i, uint32_t j)
{
	size_t len;
	const uint32_t *row = lz_nlist_row(nl, i, &len);
	for (size_t k = 0; k < len; k++)
		if (row[k] == j)
			return 1;
	return 0;
}

/* 1 if the driver would test i's steps against j and j's against i: both rows hold
 * the other (a one-copy refresh can leave them lopsided), or the cells as last binned
 * touch. */
static int sees(const lz_nwalk *nw, uint32_t i, uint32_t j)
{
	switch (nw->p.driver) {
	case LZ_NWALK_NL:
	case LZ_NWALK_FNL:
		return on_row(nw->nl, i, j) && on_row(nw->nl, j, i);
	case LZ_NWALK_CL: {
		const lz_cells *c = nw->cells;
		const uint32_t *block = c->full + (size_t)c->of[i] * (size_t)c->nfull;
		for (int q = 0; q < c->nfull; q++)
			if (block[q] == c->of[j])
				return 1;
		return 0;
	}
	case LZ_NWALK_FR:
		return 1;
	}
	return 0;
}

/* A pair closer than r2 (distance² < r2) found by count_pairs: it counts when `unseen`
 * is 0, or when the driver does not see it. */
static int pair_counts(const lz_nwalk *nw, uint32_t i, uint32_t j, int64_t r2, int unseen)
{
	int dim = nw->dim;
	const int32_t *ri = nw->r + (size_t)i * (size_t)dim;
	if (dist2_to(nw->box, dim, ri[0], ri[1], dim == 3 ? ri[2] : 0,
	             nw->r + (size_t)j * (size_t)dim) >= r2)
		return 0;
	return !unseen || !sees(nw, i, j);
}

/* The pairs closer than r2 <= rc2, each once: through the truth grid binned afresh
 * (its own cell with the later entries of its list, then its half block), or over all
 * pairs in a box too small for a grid. */
static size_t count_pairs(lz_nwalk *nw, int64_t r2, int unseen)
{
	size_t n = nw->p.n, found = 0;
	const lz_cells *c = nw->truth;
	if (!c) {
		for (uint32_t i = 0; i < n; i++)
			for (uint32_t j = i + 1; j < n; j++)
				found += (size_t)pair_counts(nw, i, j, r2, unseen);
		return found;
	}
	lz_cells_bin_sites(nw->truth, n, nw->r);
	lz_cells_link(nw->truth);
	for (size_t cell = 0; cell < c->ncells; cell++) {
		const uint32_t *half = c->half + cell * (size_t)c->nhalf;
		for (int32_t i = c->head[cell]; i >= 0; i = c->next[i])
			for (int q = 0; q < c->nhalf; q++)
				for (int32_t j = q == 0 ? c->next[i] : c->head[half[q]]; j >= 0; j = c->next[j])
					found += (size_t)pair_counts(nw, (uint32_t)i, (uint32_t)j, r2, unseen);
	}
	return found;
}

size_t lz_nwalk_overlaps(lz_nwalk *nw)
{
	return count_pairs(nw, nw->sigma2, 0);
}

/* The audit, timed apart, then the driver's refresh, timed with the moves. */
static int refresh(lz_nwalk *nw)
{
	if (nw->p.audit) {
		double t0 = lz_cpu_now();
		nw->missed += count_pairs(nw, nw->rc2, 1);
		nw->audit_s += lz_cpu_now() - t0;
	}
	double t0 = lz_cpu_now();
	int status = nw->p.driver == LZ_NWALK_CL ? cells_rebuild(nw) : lists_refresh(nw);
	nw->move_s += lz_cpu_now() - t0;
	nw->refreshes++;
	nw->since = 0;
	return status;
}

/* Sweeps up to the next refresh, then the refresh as soon as the interval is over, so
 * the schedule is the same however a run is cut into calls. */
int lz_nwalk_run(lz_nwalk *nw, gsl_rng *rng, uint64_t sweeps_asked)
{
	while (sweeps_asked > 0) {
		uint64_t chunk = sweeps_asked;
		if (nw->refresh > 0 && chunk > (uint64_t)nw->refresh - nw->since)
			chunk = (uint64_t)nw->refresh - nw->since;
		double t0 = lz_cpu_now();
		sweeps(nw, rng, chunk);
		nw->move_s += lz_cpu_now() - t0;
		sweeps_asked -= chunk;
		if (nw->refresh > 0 && nw->since == (uint64_t)nw->refresh) {
			int status = refresh(nw);
			if (status != LZ_OK)
				return status;
		}
	}
	return LZ_OK;
}

const int32_t *lz_nwalk_positions(const lz_nwalk *nw)
{
	return nw->r;
}

size_t lz_nwalk_list_bytes(const lz_nwalk *nw)
{
	switch (nw->p.driver) {
	case LZ_NWALK_NL:
	case LZ_NWALK_FNL:
		return lz_nlist_bytes(nw->nl);
	case LZ_NWALK_CL:
		return lz_cells_bytes(nw->cells);
	case LZ_NWALK_FR:
		return nw->field->nsites;
	}
	return 0;
}

double lz_nwalk_speed(const lz_nwalk *nw)
{
	return nw->move_s > 0 ? (double)nw->moves / nw->move_s : 0;
}

lz_nwalk_params lz_nwalk_params_for(lz_nwalk_driver d, lz_lattice_kind kind, int64_t side,
                                    double radius, double packing)
{
	lz_nwalk_params p = {0};
	p.driver = d;
	p.kind = kind;
	p.side = side;
	p.radius = radius;
	double one = lz_walk_packing(kind, side, radius, 1);
	p.n = one > 0 ? (size_t)lround(packing / one) : 0;
	p.skin = 4;
	p.order = LZ_CELLS_ROW;
	p.audit = 1;
	return p;
}

double lz_nwalk_fnl_skin(lz_lattice_kind kind, int64_t side, double radius, size_t n)
{
	int dim = lz_lattice_dim(kind);
	double eta = lz_walk_packing(kind, side, radius, n), lmax = longest_step(kind);
	/* an ideal gas of density η/v1 holds η·(r/R)^dim particles within r of one */
	double rl = radius * pow(LZ_NWALK_FNL_ENTRIES / eta, 1.0 / dim);
	double rc = 2 * radius + lmax, skin = ceil(rl - rc);
	double most = floor((double)side / 2 - rc);  /* r_l <= L/2 */
	skin = skin < most ? skin : most;
	return skin > 2 * lmax ? skin : ceil(2 * lmax);
}

lz_nwalk *lz_nwalk_alloc_seeded(const lz_nwalk_params *p, unsigned long seed)
{
	lz_rng *rng = lz_rng_alloc("mt19937", seed);
	lz_nwalk *nw = rng ? lz_nwalk_alloc(p, rng->gsl) : NULL;
	lz_rng_free(rng);
	return nw;
}

int lz_nwalk_time(lz_nwalk *nw, unsigned long seed, uint64_t sweeps, int repeats, double *ns)
{
	for (int r = 0; r < repeats; r++) {
		lz_rng *g = lz_rng_alloc("mt19937", seed + (unsigned long)r);
		if (!g)
			return LZ_ENOMEM;
		double t0 = nw->move_s;
		uint64_t m0 = nw->moves;
		int status = lz_nwalk_run(nw, g->gsl, sweeps);
		lz_rng_free(g);
		if (status != LZ_OK)
			return status;
		ns[r] = 1e9 * (nw->move_s - t0) / (double)(nw->moves - m0);
	}
	return LZ_OK;
}
