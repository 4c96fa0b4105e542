/* queues — lesson 05, experiment: what should order the events? The binary heap of
 * the assignment, a 4-ary heap and a calendar queue, on the same system (hard spheres
 * at η = 0.5, lists) from N = 10^3 to 10^6.
 *
 * A heap keeps every event in order: an update sifts through log2 N levels (log4 N
 * for the 4-ary heap, whose four children share a cache line). A calendar keeps in
 * order only today's events and drops every other one into the list of its day, O(1).
 * Once the heap outgrows the caches each level is a miss; the calendar's misses do
 * not chain. The cells with the binary heap, today's engine, are measured beside them.
 *
 * Each N is melted once; the same state is loaded into every option, warmed, and timed
 * in stretches taken in turn; the median CPU µs per collision.
 *
 * Check: the automatic queue (the calendar with lists) costs at most 15 % more per
 * collision than the cheapest queue at every N.
 *
 * Usage: queues OUTDIR [--quick]
 * Writes OUTDIR/queues.dat and queues.json.
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

#define SEED 5021u
#define ETA 0.5
#define REPEATS 3
#define AUTO_SLACK 1.15

/* The options: cells with the binary heap, then lists with each queue. */
#define NOPT 4
static const int neigh[NOPT] = {LZ_EDMD_CELLS, LZ_EDMD_LIST, LZ_EDMD_LIST, LZ_EDMD_LIST};
static const int queue[NOPT] = {LZ_EDMD_HEAP, LZ_EDMD_HEAP, LZ_EDMD_HEAP4, LZ_EDMD_CALENDAR};
static const char *const label[NOPT] = {"cells, heap", "lists, heap", "lists, 4-ary heap",
                                        "lists, calendar"};

typedef struct {
	int npoints;
	const size_t *n;
	double melt, warm, budget;
} sizes;

static const size_t full_n[] = {1000, 10000, 100000, 1000000};
static const size_t quick_n[] = {1000, 10000, 50000};
static const sizes full = {4, full_n, 40, 20, 1.0};
static const sizes quick = {3, quick_n, 15, 8, 0.05};

/* CPU µs per collision of every option at N = n, median of REPEATS stretches. */
static int measure(size_t n, const sizes *sz, const double *r, const double *v,
                   double *us, double *bytes)
{
	lz_edmd *e[NOPT] = {NULL};
	int st = LZ_OK;
	for (int o = 0; o < NOPT && st == LZ_OK; o++) {
		lz_edmd_params p = {3, n, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, neigh[o], 0, queue[o]};
		e[o] = lz_edmd_alloc(&p);
		st = e[o] ? lz_edmd_set(e[o], r, v) : LZ_EINVAL;
		if (st == LZ_OK)
			st = lz_edmd_run(e[o], (uint64_t)(sz->warm * (double)n), INFINITY);
		if (st == LZ_OK)
			bytes[o] = lz_edmd_bytes(e[o]);
	}
	double t[NOPT][REPEATS];
	for (int q = 0; q < REPEATS && st == LZ_OK; q++)
		for (int o = 0; o < NOPT && st == LZ_OK; o++) {
			edmd_lesson_stretch s = {0};
			st = edmd_lesson_time(e[o], sz->budget, &s);
			t[o][q] = 1e6 * s.cpu / s.collisions;
		}
	for (int o = 0; o < NOPT && st == LZ_OK; o++) {
		gsl_sort(t[o], 1, REPEATS);
		us[o] = gsl_stats_median_from_sorted_data(t[o], 1, REPEATS);
	}
	for (int o = 0; o < NOPT; o++)
		lz_edmd_free(e[o]);
	return st;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("queues: CPU time per collision of hard spheres at η = %g with cells and the "
	       "binary heap, and lists with each queue; seed %u, %d stretches of %.2f CPU s "
	       "(median)\n", ETA, SEED, REPEATS, sz->budget);
	static const char *names[] = {"n", "option", "coll_per_s", "us_per_coll", "bytes"};
	static const char *units[] = {"particles", "0 cells+heap, 1 heap, 2 heap4, 3 calendar",
	                              "per CPU s", "CPU µs", "per particle"};
	lz_data *d = lz_lesson_data(&L, "queues.dat", "the cost of a collision with each queue",
	                            5, names, units);
	if (!d)
		return lz_lesson_error(&L);
	double worst = 0, gain_small = NAN, gain_big = NAN;
	for (int k = 0; k < sz->npoints; k++) {
		size_t n = sz->n[k];
		double *r = NULL, *v = NULL, us[NOPT], bytes[NOPT];
		lz_edmd_params p = {3, n, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_LIST, 0, 0};
		int st = edmd_lesson_melt(&p, SEED, sz->melt, &r, &v, NULL, NULL);
		if (st == LZ_OK)
			st = measure(n, sz, r, v, us, bytes);
		free(r);
		free(v);
		if (st != LZ_OK) {
			lz_data_close(d);
			return lz_lesson_error(&L);
		}
		int best = 1;
		printf("  N = %zu:\n", n);
		for (int o = 0; o < NOPT; o++) {
			best = o > 0 && us[o] < us[best] ? o : best;
			printf("    %-18s %9.3g collisions/s  %6.3f µs  %6.1f bytes\n", label[o],
			       1e6 / us[o], us[o], bytes[o]);
			double row[5] = {(double)n, o, 1e6 / us[o], us[o], bytes[o]};
			lz_data_row(d, row);
		}
		double ratio = us[3] / us[best];
		worst = ratio > worst ? ratio : worst;
		if (k == 0)
			gain_small = us[0] / us[3];
		gain_big = us[0] / us[3];
		printf("  N = %zu: the calendar costs %.2f times the cheapest queue (%s); lists with "
		       "the calendar run %.2f times as fast as cells with the heap: %s\n", n, ratio,
		       label[best], us[0] / us[3], lz_lesson_check(&L, ratio <= AUTO_SLACK));
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	lz_json *j = lz_lesson_json(&L, "queues.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_num(j, "calendar_over_best_worst", worst);
	lz_json_num(j, "lists_calendar_over_cells_heap_smallest_n", gain_small);
	lz_json_num(j, "lists_calendar_over_cells_heap_largest_n", gain_big);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "the calendar within %.0f %% of the cheapest queue",
	                        100 * (AUTO_SLACK - 1));
}
