/* cooling — lesson 06, experiment: A LOAD THAT MOVES. A granular gas (restitution
 * 0.7) cools and gathers into dense clusters (Haff's law, then the clustering
 * instability of lesson 05), so the events gather where the clusters are and a rank
 * whose domain holds one does most of the work. Two runs from the same start on
 * P = 8 ranks along the Morton curve, in the virtual time of the cluster of
 * pedmd_lesson.h: the cuts fixed (even), and the cuts moved during the run
 * (params.balance: a look at the load every 64 windows, lz_pedmd_recut when the
 * busiest rank gains 25 %).
 *
 * Measured: the committed events of each rank in 16 slices of the run, each slice
 * holding the same number of committed events, and the imbalance of each slice (the
 * busiest rank's events over the mean); the virtual time of both runs; the moves.
 *
 * Checks: both runs commit the serial events and end with the serial records, bit for
 * bit; with fixed cuts the imbalance grows as the gas clusters (the last slice at
 * least 1.2 times the first).
 *
 * Usage: cooling OUTDIR [--quick]
 * Writes OUTDIR/cooling.dat and cooling.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/pedmd.h"

#include "pedmd_lesson.h"

#define SEED 6007u
#define P 8
#define NSLICE 16

typedef struct {
	size_t n;
	double time;
} sizes;

static const sizes full = {10000, 1000};
static const sizes quick = {4000, 1000};

typedef struct {
	double vtime;
	uint64_t moves, committed, rollbacks;
	double efficiency;
	int exact;
	double t[NSLICE], imbalance[NSLICE];  /* slice's last event time; busiest / mean */
} run_result;

static int by_time(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* The imbalance of each slice of equal committed events: every rank's committed
 * events (its log) counted by the slice their time falls in. */
static int slices(const lz_pedmd_sim *x, run_result *out)
{
	size_t total = 0, n;
	for (int k = 0; k < P; k++) {
		lz_pedmd_log(x->rank[k], &n);
		total += n;
	}
	double *all = malloc(total * sizeof *all);
	if (!all)
		return lz_error(LZ_ENOMEM, "no memory for %zu event times", total);
	size_t m = 0;
	for (int k = 0; k < P; k++) {
		const lz_pedmd_record *q = lz_pedmd_log(x->rank[k], &n);
		for (size_t e = 0; e < n; e++)
			all[m++] = q[e].t;
	}
	qsort(all, total, sizeof *all, by_time);
	for (int s = 0; s < NSLICE; s++)  /* slice s ends at the time of its last event */
		out->t[s] = all[(size_t)((double)total * (s + 1) / NSLICE) - 1];
	free(all);
	double count[NSLICE][P];
	memset(count, 0, sizeof count);
	for (int k = 0; k < P; k++) {
		const lz_pedmd_record *q = lz_pedmd_log(x->rank[k], &n);
		for (size_t e = 0; e < n; e++) {
			int s = 0;
			while (s < NSLICE - 1 && q[e].t > out->t[s])
				s++;
			count[s][k]++;
		}
	}
	for (int s = 0; s < NSLICE; s++) {
		double most = 0, sum = 0;
		for (int k = 0; k < P; k++) {
			most = fmax(most, count[s][k]);
			sum += count[s][k];
		}
		out->imbalance[s] = sum > 0 ? most * P / sum : 1;
	}
	return LZ_OK;
}

static int one_run(const lz_edmd *start, const lz_edmd *ref, lz_edmd *pic, double t_stop,
                   int balance, double R, run_result *out)
{
	lz_stub_params sp = stub_on(&CLUSTER, P, SEED);
	lz_pedmd_params pp = {1.0 * P / R, 0.5, balance, 0.25, 1, 1, 0, 1.125, 1};
	lz_pedmd_sim *x = lz_pedmd_sim_alloc(start, LZ_PEDMD_MORTON, &sp, &pp);
	if (!x)
		return LZ_EINVAL;
	int st = lz_pedmd_sim_run(x, t_stop);
	if (st == LZ_OK)
		st = slices(x, out);
	if (st == LZ_OK) {
		lz_pedmd_counts c = lz_pedmd_sim_counts(x);
		out->vtime = lz_stub_time(x->stub);
		out->moves = c.balances;
		out->committed = c.committed;
		out->rollbacks = c.rollbacks;
		out->efficiency = (double)c.committed / (double)c.processed;
		lz_pedmd_sim_gather(x, pic);
		out->exact = c.committed == ref->events && c.collisions == ref->collisions;
		for (size_t i = 0; i < ref->n; i++)
			out->exact &= memcmp(&pic->p[i], &ref->p[i], sizeof ref->p[i]) == 0;
	}
	lz_pedmd_sim_free(x);
	return st;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "06", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	gas g = {2, sz->n, 0.3, LZ_EDMD_WALLS_NONE, 0, 0.7, SEED, 0, 0.5};
	lz_edmd *start, *ref, *pic;
	double t_stop;
	if (gas_runs(&g, sz->time, &start, &ref, &pic, &t_stop) != LZ_OK)
		return lz_lesson_error(&L);
	double R = (double)ref->events / sz->time;
	printf("cooling: 2D, N = %zu, η = 0.3, restitution 0.7, periodic, from the lattice, %g "
	       "time units (%llu serial events); P = %d Morton, cluster; seed %u\n", sz->n,
	       sz->time, (unsigned long long)ref->events, P, SEED);
	run_result fixed, moved;
	if (one_run(start, ref, pic, t_stop, 0, R, &fixed) != LZ_OK ||
	    one_run(start, ref, pic, t_stop, 64, R, &moved) != LZ_OK)
		return lz_lesson_error(&L);

	static const char *names[] = {"slice", "t_fixed", "imbalance_fixed", "t_moved",
	                              "imbalance_moved"};
	static const char *units[] = {"", "τ (end of the slice)", "busiest / mean", "τ",
	                              "busiest / mean"};
	lz_data *d = lz_lesson_data(&L, "cooling.dat", "the load of 8 ranks over a cooling run, "
	                            "in slices of equal committed events", 5, names, units);
	if (!d)
		return lz_lesson_error(&L);
	printf("  slice   t end   imbalance, fixed cuts   imbalance, moved cuts\n");
	for (int s = 0; s < NSLICE; s++) {
		printf("  %5d %7.2f %14.3f %23.3f\n", s + 1, fixed.t[s], fixed.imbalance[s],
		       moved.imbalance[s]);
		lz_data_row(d, (double[]){s + 1, fixed.t[s], fixed.imbalance[s], moved.t[s],
		                          moved.imbalance[s]});
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	printf("  virtual time: fixed cuts %.5g s (%llu rollbacks, committed/processed %.3f), "
	       "moved cuts %.5g s (%llu moves, %llu rollbacks, %.3f)\n", fixed.vtime,
	       (unsigned long long)fixed.rollbacks, fixed.efficiency, moved.vtime,
	       (unsigned long long)moved.moves, (unsigned long long)moved.rollbacks,
	       moved.efficiency);
	printf("  both runs committed the serial events and ended with the serial records: %s\n",
	       lz_lesson_check(&L, fixed.exact && moved.exact));
	printf("  fixed cuts: the imbalance grows as the gas clusters (%.3f to %.3f, at least "
	       "1.2 times): %s\n", fixed.imbalance[0], fixed.imbalance[NSLICE - 1],
	       lz_lesson_check(&L, fixed.imbalance[NSLICE - 1] >= 1.2 * fixed.imbalance[0]));

	lz_json *j = lz_lesson_json(&L, "cooling.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", (long long)sz->n);
	lz_json_num(j, "vtime_fixed_s", fixed.vtime);
	lz_json_num(j, "vtime_moved_s", moved.vtime);
	lz_json_int(j, "moves", (long long)moved.moves);
	lz_json_int(j, "rollbacks_fixed", (long long)fixed.rollbacks);
	lz_json_int(j, "rollbacks_moved", (long long)moved.rollbacks);
	lz_json_num(j, "imbalance_fixed_last", fixed.imbalance[NSLICE - 1]);
	lz_json_num(j, "imbalance_moved_last", moved.imbalance[NSLICE - 1]);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	lz_edmd_free(start);
	lz_edmd_free(ref);
	lz_edmd_free(pic);
	return lz_lesson_finish(&L, "both runs the serial run; the fixed cuts' imbalance grows");
}
