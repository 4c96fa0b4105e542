/* cells — lesson 05, experiment: how many cells? The cost of event-driven hard spheres
 * against the number of cells per particle C/N (Miller & Luding, J. Comput. Phys. 193, 306 (2004), fig. 3).
 *
 * Few cells: each cell holds many particles, and every prediction (after every event)
 * tests the 3^dim·N/C particles of the block around a particle's cell. Many cells: a
 * particle crosses many cell faces between two collisions, each crossing an event of
 * its own. The first cost falls as (C/N)^-1, the second grows as (C/N)^(1/dim): a broad
 * minimum, which Miller & Luding put at C/N ≈ 1.5 (2D) and ≈ 8 (3D) in a dilute gas.
 * In a dense fluid the cells cannot be narrower than σ, and the best is as many as fit.
 *
 * Four systems — hard disks (N = 10 000) and hard spheres (N = 8000), each dilute
 * (η = 0.05) and dense (η = 0.65 disks, 0.45 spheres) — are melted once from the
 * lattice; the same melted state is then loaded (lz_edmd_set) into systems of m = 3 ..
 * floor(L) cells per side, and each runs in timed stretches. The speed that matters
 * is physical progress, collisions per CPU second (∝ simulated time per CPU second,
 * since every m runs the same physical system): events per CPU second would reward
 * the cell crossings, which are cheap events that achieve nothing physical. Events
 * per collision are reported too (1 + crossings + stale events, per collision).
 * The automatic choice (lz_edmd_auto_cells) is marked.
 *
 * Check: the automatic choice costs at most 25 % more CPU time per collision than the
 * cheapest m measured, in each of the four systems.
 *
 * Usage: cells OUTDIR [--quick]
 * Writes OUTDIR/cells.dat and cells.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "edmd_lesson.h"
#include "lz/lesson.h"
#include "lz/output.h"

#define SEED 5003u
#define NSYS 4
#define REPEATS 5
#define MAXM 24          /* measured cell counts per system, at most */
#define AUTO_SLACK 1.25  /* the automatic choice may cost this much more than the best */

typedef struct {
	int dim;
	size_t n;
	double eta;
	const char *name;
} system_def;

static const system_def sys_of[NSYS] = {
	{2, 10000, 0.05, "2D dilute"},
	{2, 10000, 0.65, "2D dense"},
	{3, 8000, 0.05, "3D dilute"},
	{3, 8000, 0.45, "3D dense"},
};

typedef struct {
	int points;          /* cell counts per system */
	double melt;         /* events per particle to melt the lattice */
	double warm;         /* events per particle after loading, untimed */
	double budget;       /* CPU seconds per timed stretch */
	double cn_min;       /* the smallest C/N measured (m = 3 at least) */
} sizes;

static const sizes full = {14, 40, 1, 0.15, 0.0};
static const sizes quick = {6, 15, 0.2, 0.02, 0.01};

typedef struct {
	int m;
	double cn;           /* cells per particle C/N */
	double us_per_coll;  /* CPU µs per collision, median of the repeats */
	double ev_per_s;     /* events per CPU second, median */
	double ev_per_coll;  /* events per collision */
	double neighbours;   /* particles in the 3^dim block, per particle, 3^dim N/C */
	int is_auto;
} point;

/* System s loaded from (r, v) into ms[k] cells per side, k < np, timed: REPEATS
 * passes over all the cell counts, one stretch each, so that a burst of load from
 * another process on the machine spoils one stretch of several counts rather than
 * every stretch of one; the median over the passes. */
static int measure(const system_def *s, const sizes *sz, const double *r, const double *v,
                   const int *ms, int np, point *pts)
{
	lz_edmd *e[MAXM + 1] = {NULL};
	static double us[MAXM + 1][REPEATS], eps[MAXM + 1][REPEATS];
	double ev_tot[MAXM + 1] = {0}, coll_tot[MAXM + 1] = {0};
	int st = LZ_OK;
	for (int k = 0; k < np && st == LZ_OK; k++) {
		lz_edmd_params p = {s->dim, s->n, s->eta, 1.0, 0.0, LZ_EDMD_WALLS_NONE, ms[k], LZ_EDMD_CELLS, 0, 0};
		e[k] = lz_edmd_alloc(&p);
		st = e[k] ? lz_edmd_set(e[k], r, v) : LZ_EINVAL;
		if (st == LZ_OK)
			st = lz_edmd_run(e[k], (uint64_t)(sz->warm * (double)s->n), INFINITY);
	}
	for (int q = 0; q < REPEATS && st == LZ_OK; q++)
		for (int k = 0; k < np && st == LZ_OK; k++) {
			edmd_lesson_stretch t = {0};
			st = edmd_lesson_time(e[k], sz->budget, &t);
			us[k][q] = 1e6 * t.cpu / t.collisions;
			eps[k][q] = t.events / t.cpu;
			ev_tot[k] += t.events;
			coll_tot[k] += t.collisions;
		}
	for (int k = 0; k < np && st == LZ_OK; k++) {
		point *pt = &pts[k];
		gsl_sort(us[k], 1, REPEATS);
		gsl_sort(eps[k], 1, REPEATS);
		pt->m = ms[k];
		pt->cn = (double)e[k]->ncells / (double)s->n;
		pt->us_per_coll = gsl_stats_median_from_sorted_data(us[k], 1, REPEATS);
		pt->ev_per_s = gsl_stats_median_from_sorted_data(eps[k], 1, REPEATS);
		pt->ev_per_coll = ev_tot[k] / coll_tot[k];
		pt->neighbours = pow(3, s->dim) / pt->cn;
	}
	for (int k = 0; k < np; k++)
		lz_edmd_free(e[k]);
	return st;
}

/* The cell counts to measure: about sz->points of them, geometric in C/N from
 * max(3, cn_min) to floor(L) per side, and the automatic choice. Returns the count. */
static int cell_counts(const system_def *s, const sizes *sz, double L, int m_auto, int *ms)
{
	int lo = (int)ceil(pow(sz->cn_min * (double)s->n, 1.0 / s->dim));
	int hi = (int)floor(L), k = 0;
	lo = lo < 3 ? 3 : lo;
	for (int q = 0; q < sz->points; q++) {
		int m = (int)lround(lo * pow((double)hi / lo, (double)q / (sz->points - 1)));
		if (k == 0 || m > ms[k - 1])
			ms[k++] = m;
	}
	int at = 0;
	while (at < k && ms[at] < m_auto)
		at++;
	if (at == k || ms[at] != m_auto) {
		for (int q = k; q > at; q--)
			ms[q] = ms[q - 1];
		ms[at] = m_auto;
		k++;
	}
	return k;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("cells: CPU time per collision against cells per particle C/N; seed %u, "
	       "%d cell counts per system, %d stretches of %.2f CPU s each (median)\n",
	       SEED, sz->points, REPEATS, sz->budget);

	static const char *names[] = {"system", "dim", "eta", "m", "C_per_N", "us_per_coll",
	                              "events_per_s", "events_per_coll", "block_neighbours",
	                              "auto"};
	static const char *units[] = {"0..3", "", "", "cells per side", "", "CPU µs",
	                              "per CPU s", "", "3^dim N/C", "1 = lz_edmd_auto_cells"};
	lz_data *d = lz_lesson_data(&L, "cells.dat", "CPU time per collision against cells "
	                            "per particle (system 0: 2D dilute, 1: 2D dense, 2: 3D "
	                            "dilute, 3: 3D dense)", 10, names, units);
	if (!d)
		return lz_lesson_error(&L);

	double ratio[NSYS], best_cn[NSYS], auto_cn[NSYS], best_us[NSYS], auto_us[NSYS];
	int good = 1;
	for (int s = 0; s < NSYS; s++) {
		const system_def *sd = &sys_of[s];
		double *r = NULL, *v = NULL, box;
		int m_auto, ms[MAXM + 1];
		point pts[MAXM + 1];
		lz_edmd_params p = {sd->dim, sd->n, sd->eta, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0,
		                    LZ_EDMD_CELLS, 0, 0};
		if (edmd_lesson_melt(&p, SEED, sz->melt, &r, &v, &m_auto, &box) != LZ_OK) {
			free(r);
			free(v);
			lz_data_close(d);
			return lz_lesson_error(&L);
		}
		int np = cell_counts(sd, sz, box, m_auto, ms);
		printf("  %s: N = %zu, η = %g, L = %.2f σ, automatic m = %d (C/N = %.3g)\n",
		       sd->name, sd->n, sd->eta, box, m_auto, pow(m_auto, sd->dim) / (double)sd->n);
		printf("     m     C/N   µs/coll   events/s  events/coll  block\n");
		int best = 0, at = 0;
		if (measure(sd, sz, r, v, ms, np, pts) != LZ_OK) {
			free(r);
			free(v);
			lz_data_close(d);
			return lz_lesson_error(&L);
		}
		for (int k = 0; k < np; k++) {
			point *pt = &pts[k];
			pt->is_auto = ms[k] == m_auto;
			if (pt->us_per_coll < pts[best].us_per_coll)
				best = k;
			if (pt->is_auto)
				at = k;
			printf("  %4d %7.4f %9.3f %10.3g %12.2f %6.1f%s\n", pt->m, pt->cn,
			       pt->us_per_coll, pt->ev_per_s, pt->ev_per_coll, pt->neighbours,
			       pt->is_auto ? "  <- auto" : "");
			double row[10] = {s, sd->dim, sd->eta, pt->m, pt->cn, pt->us_per_coll,
			                  pt->ev_per_s, pt->ev_per_coll, pt->neighbours, pt->is_auto};
			lz_data_row(d, row);
		}
		free(r);
		free(v);
		ratio[s] = pts[at].us_per_coll / pts[best].us_per_coll;
		best_cn[s] = pts[best].cn;
		best_us[s] = pts[best].us_per_coll;
		auto_cn[s] = pts[at].cn;
		auto_us[s] = pts[at].us_per_coll;
		int ok = ratio[s] <= AUTO_SLACK;
		good = good && ok;
		printf("  %s: cheapest C/N = %.3g (%.3f µs per collision); automatic C/N = %.3g "
		       "(%.3f µs), %.2f times the cheapest (at most %.2f): %s\n", sd->name,
		       best_cn[s], best_us[s], auto_cn[s], auto_us[s], ratio[s], AUTO_SLACK,
		       lz_lesson_check(&L, ok));
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	lz_json *j = lz_lesson_json(&L, "cells.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	static const char *key[NSYS] = {"2d_dilute", "2d_dense", "3d_dilute", "3d_dense"};
	for (int s = 0; s < NSYS; s++) {
		char k[64];
		snprintf(k, sizeof k, "best_C_per_N_%s", key[s]);
		lz_json_num(j, k, best_cn[s]);
		snprintf(k, sizeof k, "auto_C_per_N_%s", key[s]);
		lz_json_num(j, k, auto_cn[s]);
		snprintf(k, sizeof k, "auto_over_best_%s", key[s]);
		lz_json_num(j, k, ratio[s]);
	}
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "the automatic cell count within %.0f %% of the cheapest",
	                        100 * (AUTO_SLACK - 1));
}
