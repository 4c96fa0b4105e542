/* lists — lesson 05, experiment: cells or neighbour lists, and how wide a shell? The
 * cost of simulated time (CPU µs per collision) of hard spheres from η = 10^-3 to 0.55,
 * with the cells and with lists of every shell S.
 *
 * A list holds the particles whose centres lie within S of a particle's centre, and
 * is built again when the particle strays δ = (S - 1)/2 from it (a skin event). A wide
 * shell: few rebuilds, but many candidates per prediction and 4 bytes each; a narrow
 * one: the other way round. Cells cost nothing to keep but scan the 27 cells around a
 * particle, most of whose particles are too far to matter in a dense fluid; in a gas
 * the free flights are long, and a list's skin is left again and again between two
 * collisions. (Smallenburg, Eur. Phys. J. E 45, 22 (2022), fig. 4, measures the same
 * trade for his code.)
 *
 * Each packing is melted once with cells; the same state is loaded (lz_edmd_set) into
 * cells and into lists of every shell, each warmed until its rebuilds run at their
 * steady rate, then timed in stretches taken in turn (a burst of load on the machine
 * spoils one stretch of several options, not every stretch of one); the median.
 * Recorded: collisions per CPU second, rebuilds per collision, the mean list length
 * (the candidates of a prediction) and the bytes per particle.
 *
 * Check: the automatic choice (lz_edmd_list_pays, lz_edmd_list_shell) costs at most
 * 20 % more per collision than the cheapest option measured, at every packing.
 *
 * Usage: lists OUTDIR [--quick]
 * Writes OUTDIR/lists.dat and lists.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "edmd_lesson.h"
#include "lz/lesson.h"
#include "lz/output.h"

#define SEED 5017u
#define REPEATS 3
#define AUTO_SLACK 1.20  /* the automatic choice may cost this much more than the best */
#define MAXOPT 9         /* options per packing: the cells and up to 8 shells */

static const double shells[] = {1.2, 1.3, 1.35, 1.4, 1.5, 1.8, 2.2, 3.0};
#define NSHELL ((int)(sizeof shells / sizeof shells[0]))

typedef struct {
	size_t n;
	int npack;
	const double *packing;
	double melt, warm;  /* events per particle */
	double budget;      /* CPU seconds per timed stretch */
} sizes;

static const double full_packing[] = {0.001, 0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.55};
static const double quick_packing[] = {0.01, 0.3, 0.5};
static const sizes full = {8000, 10, full_packing, 60, 20, 0.3};
static const sizes quick = {3000, 3, quick_packing, 25, 8, 0.04};

typedef struct {
	double shell;       /* 0: cells */
	double us_per_coll, coll_per_s, rebuilds_per_coll, neighbours, bytes;
	int is_auto;
} option;

/* The options at packing eta, loaded from (r, v), warmed and timed in turn. Returns
 * their number (the cells first, then the shells the box holds). */
static int measure(const sizes *sz, double eta, const double *r, const double *v,
                   option *opt, int *nopt)
{
	lz_edmd *e[MAXOPT] = {NULL};
	int k = 0, st = LZ_OK;
	for (int s = -1; s < NSHELL && st == LZ_OK; s++) {
		lz_edmd_params p = {3, sz->n, eta, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0,
		                    s < 0 ? LZ_EDMD_CELLS : LZ_EDMD_LIST, s < 0 ? 0 : shells[s], 0};
		if (!(e[k] = lz_edmd_alloc(&p)))
			continue;  /* a box too small for this shell */
		opt[k].shell = s < 0 ? 0 : shells[s];
		st = lz_edmd_set(e[k], r, v);
		if (st == LZ_OK)
			st = lz_edmd_run(e[k], (uint64_t)(sz->warm * (double)sz->n), INFINITY);
		k++;
	}
	static double us[MAXOPT][REPEATS];
	double colls[MAXOPT] = {0}, rebuilds[MAXOPT] = {0};
	for (int q = 0; q < REPEATS && st == LZ_OK; q++)
		for (int o = 0; o < k && st == LZ_OK; o++) {
			edmd_lesson_stretch t = {0};
			st = edmd_lesson_time(e[o], sz->budget, &t);
			us[o][q] = 1e6 * t.cpu / t.collisions;
			colls[o] += t.collisions;
			rebuilds[o] += t.rebuilds;
		}
	for (int o = 0; o < k && st == LZ_OK; o++) {
		gsl_sort(us[o], 1, REPEATS);
		opt[o].us_per_coll = gsl_stats_median_from_sorted_data(us[o], 1, REPEATS);
		opt[o].coll_per_s = 1e6 / opt[o].us_per_coll;
		opt[o].rebuilds_per_coll = rebuilds[o] / colls[o];
		opt[o].neighbours = e[o]->lists ? lz_edmd_list_mean(e[o]) : NAN;
		opt[o].bytes = lz_edmd_bytes(e[o]);
	}
	for (int o = 0; o < k; o++)
		lz_edmd_free(e[o]);
	*nopt = k;
	return st;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("lists: CPU time per collision with cells and with lists of %d shells, hard "
	       "spheres N = %zu at %d packings; seed %u, %d stretches of %.2f CPU s each "
	       "(median)\n", NSHELL, sz->n, sz->npack, SEED, REPEATS, sz->budget);
	static const char *names[] = {"eta", "shell", "coll_per_s", "us_per_coll",
	                              "rebuilds_per_coll", "list_length", "bytes", "auto"};
	static const char *units[] = {"", "σ (0: cells)", "per CPU s", "CPU µs", "", "neighbours",
	                              "per particle", "1 = the automatic choice"};
	static double rows[16][MAXOPT][8];  /* [packing][option][column], written by option */
	int counts[16] = {0};
	double worst = 0, worst_eta = 0;
	for (int k = 0; k < sz->npack; k++) {
		double eta = sz->packing[k], *r = NULL, *v = NULL;
		option opt[MAXOPT];
		lz_edmd_params p = {3, sz->n, eta, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
		int nopt = 0, st = edmd_lesson_melt(&p, SEED, sz->melt, &r, &v, NULL, NULL);
		if (st == LZ_OK)
			st = measure(sz, eta, r, v, opt, &nopt);
		free(r);
		free(v);
		if (st != LZ_OK)
			return lz_lesson_error(&L);
		double S_auto = lz_edmd_list_pays(3, sz->n, eta) == LZ_EDMD_LIST
		                ? lz_edmd_list_shell(3, eta) : 0;
		int best = 0, at = -1;
		printf("  η = %g:\n     shell  coll/s    µs/coll  rebuilds/coll  list  bytes\n", eta);
		for (int o = 0; o < nopt; o++) {
			opt[o].is_auto = fabs(opt[o].shell - S_auto) < 1e-9;
			best = opt[o].us_per_coll < opt[best].us_per_coll ? o : best;
			at = opt[o].is_auto ? o : at;
			char label[16] = "cells";
			if (opt[o].shell > 0)
				snprintf(label, sizeof label, "%.2f", opt[o].shell);
			printf("  %8s %9.3g %9.3f %14.3f %5.1f %6.1f%s\n", label, opt[o].coll_per_s,
			       opt[o].us_per_coll, opt[o].rebuilds_per_coll, opt[o].neighbours,
			       opt[o].bytes, opt[o].is_auto ? "  <- auto" : "");
			double row[8] = {eta, opt[o].shell, opt[o].coll_per_s, opt[o].us_per_coll,
			                 opt[o].rebuilds_per_coll, opt[o].neighbours, opt[o].bytes,
			                 opt[o].is_auto};
			memcpy(rows[k][o], row, sizeof row);
		}
		counts[k] = nopt;
		double ratio = at >= 0 ? opt[at].us_per_coll / opt[best].us_per_coll : INFINITY;
		int ok = ratio <= AUTO_SLACK;
		if (ratio > worst) {
			worst = ratio;
			worst_eta = eta;
		}
		printf("  η = %g: the automatic choice (%s) costs %.2f times the cheapest (%s): %s\n",
		       eta, S_auto > 0 ? "lists" : "cells", ratio,
		       opt[best].shell > 0 ? "lists" : "cells", lz_lesson_check(&L, ok));
	}
	/* one option after the other, each along the packings: a line per option */
	lz_data *d = lz_lesson_data(&L, "lists.dat", "cells (shell 0) and lists of every shell: "
	                            "the cost of a collision", 8, names, units);
	if (!d)
		return lz_lesson_error(&L);
	for (int s = -1; s < NSHELL; s++)
		for (int k = 0; k < sz->npack; k++)
			for (int o = 0; o < counts[k]; o++)
				if (rows[k][o][1] == (s < 0 ? 0 : shells[s]))
					lz_data_row(d, rows[k][o]);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	lz_json *j = lz_lesson_json(&L, "lists.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "n", (long long)sz->n);
	lz_json_num(j, "auto_over_best_worst", worst);
	lz_json_num(j, "auto_over_best_worst_packing", worst_eta);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "the automatic choice within %.0f %% of the cheapest option",
	                        100 * (AUTO_SLACK - 1));
}
