/* scaling — lesson 05, experiment: is an event O(1)? Events and collisions per CPU
 * second against N, with the particles numbered cell by cell or at random, and the
 * bytes per particle against the caches (DynamO, Bannerman, Sargant & Lue, J. Comput. Chem. 32, 3329 (2011), its scaling figure).
 *
 * An event costs a heap operation, O(log N) — a handful of levels more at each tenfold
 * N — plus a prediction over the block of cells, O(1) at fixed density. What actually
 * changes with N is where the data is: while the particles, events, heap and cell
 * lists (lz_edmd_bytes per particle) fit in the L2 or L3 cache an event reads them
 * fast; beyond, each prediction waits for memory, unless particles near in space are
 * near in memory. The engine can renumber the particles cell by cell at every re-base
 * (sort_every = 1, lz_edmd_sort, in its default cell order), as here for the sorted
 * series; without (sort_every = 0, the default), a long run ends up with its particles
 * scattered in memory — here they are shuffled at the start, which is where an
 * unsorted run drifts to. From
 * LZ_EDMD_FAR particles on the loop prefetches (lz_edmd.prefetch: the next event's
 * cells and particles, the candidates of a prediction, the heap's lower levels); the
 * sorted system is timed once more with that switched off, on the same state.
 *
 * Hard spheres (3D) and disks (2D) at η = 0.3, N = 10^3 .. 10^6 (10^5 at the demo
 * size), automatic cells, melted from the lattice, then timed in three stretches
 * (median) sorted and shuffled. The cache sizes come from
 * /sys/devices/system/cpu/cpu0/cache (or sysconf); OUTDIR/scaling_cache.gp hands them
 * to the plot.
 *
 * Checks: the work is O(1) per unit of physics — events per collision the same at every
 * N (within 5 %); and while the data fits in the L2 cache, so is the time — events per
 * CPU second at the largest N that fits within a factor 1.5 of the smallest N. Beyond
 * the cache the slowdown is measured and reported, not checked: it depends on the
 * machine and on what else runs on it.
 *
 * Usage: scaling OUTDIR [--quick]
 * Writes OUTDIR/scaling.dat, scaling_cache.gp and scaling.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include <gsl/gsl_permutation.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 5004u
#define ETA 0.3
#define NSIZES 7
#define REPEATS 3
#define MAX_CACHE_RATIO 1.5  /* events/s, smallest N over the largest in L2, at most */
#define MAX_EVCOLL_DEV 0.05   /* events per collision, relative spread over N */

static const size_t n_of[NSIZES] = {1000, 3162, 10000, 31623, 100000, 316228, 1000000};

typedef struct {
	int sizes;          /* how many of n_of */
	double melt;        /* events per particle from the lattice */
	double events_min;  /* events per timed stretch: max(events_min, per_n · N) */
	double per_n;
} sizes;

static const sizes full = {NSIZES, 2, 2e5, 0.5};
static const sizes quick = {5, 2, 6e4, 0.3};

typedef struct {
	double ev_per_s, coll_per_s, bytes;
	double ev_per_coll;  /* events per collision over all stretches */
} speed;

/* Cache size of `level` (2 or 3) in bytes, from sysfs or sysconf; 0 when unknown. */
static double cache_bytes(int level)
{
	for (int k = 0; k < 8; k++) {
		char path[128];
		int lv = 0;
		char type[32] = "", size[32] = "";
		snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/level", k);
		FILE *f = fopen(path, "r");
		if (!f)
			break;
		int got = fscanf(f, "%d", &lv);
		fclose(f);
		snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/type", k);
		if ((f = fopen(path, "r"))) {
			got += fscanf(f, "%31s", type);
			fclose(f);
		}
		snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/size", k);
		if ((f = fopen(path, "r"))) {
			got += fscanf(f, "%31s", size);
			fclose(f);
		}
		if (got == 3 && lv == level && type[0] != 'I') {
			char *end;
			double b = strtod(size, &end);
			return b * (*end == 'K' ? 1024.0 : *end == 'M' ? 1048576.0 : 1.0);
		}
	}
#if defined(_SC_LEVEL2_CACHE_SIZE) && defined(_SC_LEVEL3_CACHE_SIZE)
	long b = sysconf(level == 2 ? _SC_LEVEL2_CACHE_SIZE : _SC_LEVEL3_CACHE_SIZE);
	return b > 0 ? (double)b : 0;
#else
	return 0;
#endif
}

/* Time e: REPEATS stretches of `events`, the median rates. */
static int timed(lz_edmd *e, uint64_t events, speed *s)
{
	double ev[REPEATS], co[REPEATS], done = 0, colls = 0;
	for (int k = 0; k < REPEATS; k++) {
		lz_edmd_reset_counts(e);
		double t0 = lz_cpu_now();
		int st = lz_edmd_run(e, events, INFINITY);
		double cpu = lz_cpu_now() - t0;
		if (st)
			return st;
		ev[k] = (double)e->events / cpu;
		co[k] = (double)e->collisions / cpu;
		done += (double)e->events;
		colls += (double)e->collisions;
	}
	s->ev_per_coll = done / colls;
	gsl_sort(ev, 1, REPEATS);
	gsl_sort(co, 1, REPEATS);
	s->ev_per_s = gsl_stats_median_from_sorted_data(ev, 1, REPEATS);
	s->coll_per_s = gsl_stats_median_from_sorted_data(co, 1, REPEATS);
	s->bytes = lz_edmd_bytes(e);
	return LZ_OK;
}

/* N particles in dim dimensions: melted, then timed numbered cell by cell (s[0]),
 * the same without prefetching (s[2]; NAN below LZ_EDMD_FAR, where it is off anyway)
 * and shuffled (s[1]). */
static int measure(int dim, size_t n, const sizes *sz, lz_rng *rng, speed s[3])
{
	lz_edmd_params p = {dim, n, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p), *u = lz_edmd_alloc(&p);
	double *r = malloc(3 * n * sizeof *r), *v = malloc(3 * n * sizeof *v);
	gsl_permutation *perm = gsl_permutation_alloc(n);
	int st = e && u ? LZ_OK : LZ_EINVAL;
	if (st == LZ_OK && (!r || !v || !perm))
		st = lz_error(LZ_ENOMEM, "no memory for %zu particles", n);
	if (st == LZ_OK) {
		e->sort_every = 1;
		st = lz_edmd_place_lattice(e, rng);
	}
	if (st == LZ_OK)
		st = lz_edmd_run(e, (uint64_t)(sz->melt * (double)n), INFINITY);
	uint64_t events = (uint64_t)fmax(sz->events_min, sz->per_n * (double)n);
	if (st == LZ_OK)
		st = timed(e, events, &s[0]);
	s[2] = (speed){NAN, NAN, NAN, NAN};
	if (st == LZ_OK && e->prefetch) {
		e->prefetch = 0;
		st = timed(e, events, &s[2]);
		e->prefetch = 1;
	}
	if (st == LZ_OK) {
		lz_edmd_sync(e);
		gsl_permutation_init(perm);
		gsl_ran_shuffle(rng->gsl, perm->data, n, sizeof(size_t));
		for (size_t i = 0; i < n; i++)
			for (int a = 0; a < 3; a++) {
				r[3 * i + a] = e->p[perm->data[i]].r[a];
				v[3 * i + a] = e->p[perm->data[i]].v[a];
			}
		u->sort_every = 0;
		st = lz_edmd_set(u, r, v);
	}
	if (st == LZ_OK)
		st = timed(u, events, &s[1]);
	lz_edmd_free(e);
	lz_edmd_free(u);
	free(r);
	free(v);
	gsl_permutation_free(perm);
	return st;
}

static int write_cache_gp(lz_lesson *L, double l2, double l3)
{
	FILE *f = lz_lesson_fopen(L, "scaling_cache.gp");
	if (!f)
		return LZ_EIO;
	fprintf(f, "# written by scaling.c: the caches of the machine it ran on, bytes\n"
	        "L2 = %.0f\nL3 = %.0f\n", l2, l3);
	return lz_lesson_fclose(L, f, "scaling_cache.gp");
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	double l2 = cache_bytes(2), l3 = cache_bytes(3);
	printf("scaling: hard spheres and disks at η = %g, N = %zu .. %zu, seed %u; "
	       "caches: L2 %.3g MiB, L3 %.3g MiB (per core, as the system reports them)\n",
	       ETA, n_of[0], n_of[sz->sizes - 1], SEED, l2 / 1048576, l3 / 1048576);
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	if (!rng)
		return lz_lesson_error(&L);

	static const char *names[] = {"N", "dim", "sorted", "events_per_s", "coll_per_s",
	                              "bytes_per_particle", "MiB"};
	static const char *units[] = {"", "", "1 cell by cell, 0 shuffled", "per CPU s",
	                              "per CPU s", "B", "MiB"};
	lz_data *d = lz_lesson_data(&L, "scaling.dat", "event-driven hard particles at "
	                            "packing 0.3: speed against N", 7, names, units);
	if (!d)
		return lz_lesson_error(&L);
	speed res[2][NSIZES][3];
	printf("  dim         N   B/part      MiB   events/s sorted  shuffled  no prefetch   "
	       "collisions/s sorted\n");
	for (int dd = 0; dd < 2; dd++) {
		int dim = 3 - dd;
		for (int k = 0; k < sz->sizes; k++) {
			speed *s = res[dd][k];
			if (measure(dim, n_of[k], sz, rng, s) != LZ_OK) {
				lz_data_close(d);
				lz_rng_free(rng);
				return lz_lesson_error(&L);
			}
			double mib = s[0].bytes * (double)n_of[k] / 1048576;
			printf("  %dD %9zu %8.1f %8.2f %15.3g %9.3g %12.3g %14.3g\n", dim, n_of[k],
			       s[0].bytes, mib, s[0].ev_per_s, s[1].ev_per_s, s[2].ev_per_s,
			       s[0].coll_per_s);
		}
	}
	lz_rng_free(rng);
	/* one series after the other, so that the plot's lines join each */
	for (int dd = 0; dd < 2; dd++)
		for (int q = 0; q < 2; q++)
			for (int k = 0; k < sz->sizes; k++) {
				const speed *s = &res[dd][k][q];
				double row[7] = {(double)n_of[k], 3 - dd, 1 - q, s->ev_per_s,
				                 s->coll_per_s, s->bytes, s->bytes * (double)n_of[k] / 1048576};
				lz_data_row(d, row);
			}
	if (lz_data_close(d) != LZ_OK || write_cache_gp(&L, l2, l3) != LZ_OK)
		return lz_lesson_error(&L);

	int last = sz->sizes - 1, in_l2 = 0;
	for (int k = 0; k < sz->sizes; k++)
		if (l2 > 0 ? res[0][k][0].bytes * (double)n_of[k] <= l2 : n_of[k] <= 10000)
			in_l2 = k;
	double slow[2], cache_ratio[2];
	for (int dd = 0; dd < 2; dd++) {
		double spread = 0;
		for (int k = 0; k < sz->sizes; k++)
			spread = fmax(spread, fabs(res[dd][k][0].ev_per_coll / res[dd][0][0].ev_per_coll - 1));
		printf("  %dD: %.3f events per collision at N = %zu, at most %.1f %% different at any "
		       "N (at most %.0f %%): %s\n", 3 - dd, res[dd][0][0].ev_per_coll, n_of[0],
		       100 * spread, 100 * MAX_EVCOLL_DEV, lz_lesson_check(&L, spread <= MAX_EVCOLL_DEV));
		cache_ratio[dd] = res[dd][0][0].ev_per_s / res[dd][in_l2][0].ev_per_s;
		printf("  %dD: %.3g events/s at N = %zu, %.3g at N = %zu (the largest N in L2): %.2f "
		       "times slower (at most %.1f): %s\n", 3 - dd, res[dd][0][0].ev_per_s, n_of[0],
		       res[dd][in_l2][0].ev_per_s, n_of[in_l2], cache_ratio[dd], MAX_CACHE_RATIO,
		       lz_lesson_check(&L, cache_ratio[dd] <= MAX_CACHE_RATIO));
		slow[dd] = res[dd][0][0].ev_per_s / res[dd][last][0].ev_per_s;
		printf("  %dD: beyond the cache, at N = %zu: %.3g events/s, %.2f times slower than at "
		       "N = %zu; sorted %.2f times as fast as shuffled, prefetching %.2f times as "
		       "fast as not (measured, not checked)\n",
		       3 - dd, n_of[last], res[dd][last][0].ev_per_s, slow[dd], n_of[0],
		       res[dd][last][0].ev_per_s / res[dd][last][1].ev_per_s,
		       res[dd][last][0].ev_per_s / res[dd][last][2].ev_per_s);
	}

	lz_json *j = lz_lesson_json(&L, "scaling.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_num(j, "L2_MiB", l2 / 1048576);
	lz_json_num(j, "L3_MiB", l3 / 1048576);
	lz_json_num(j, "bytes_per_particle_3d", res[0][last][0].bytes);
	for (int dd = 0; dd < 2; dd++) {
		char key[64];
		snprintf(key, sizeof key, "events_per_s_%dd_N%zu", 3 - dd, n_of[0]);
		lz_json_num(j, key, res[dd][0][0].ev_per_s);
		snprintf(key, sizeof key, "events_per_s_%dd_N%zu", 3 - dd, n_of[last]);
		lz_json_num(j, key, res[dd][last][0].ev_per_s);
		snprintf(key, sizeof key, "events_per_s_%dd_N%zu_shuffled", 3 - dd, n_of[last]);
		lz_json_num(j, key, res[dd][last][1].ev_per_s);
		snprintf(key, sizeof key, "events_per_s_%dd_N%zu_no_prefetch", 3 - dd, n_of[last]);
		lz_json_num(j, key, res[dd][last][2].ev_per_s);
		snprintf(key, sizeof key, "collisions_per_s_%dd_N%zu", 3 - dd, n_of[last]);
		lz_json_num(j, key, res[dd][last][0].coll_per_s);
		snprintf(key, sizeof key, "slowdown_%dd_N%zu", 3 - dd, n_of[last]);
		lz_json_num(j, key, slow[dd]);
	}
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "O(1) events per collision at every N; the speed "
	                        "constant while the data fits in L2");
}
