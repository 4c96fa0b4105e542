/* cell_order — lesson 04, experiment: where the bytes are. Linked lists against fixed
 * arrays, particles as placed against particles numbered cell by cell in row-major or
 * Morton order, inside and outside the caches (thesis 2.4.3; DynamO: Bannerman, Sargant & Lue, J. Comput. Chem. 32, 3329 (2011)).
 *
 * The system of table22 (hard disks R = 12, packing 0.474, boxes 1024 .. 32768, so
 * N = 1099 .. 1 125 000), walked by the cell-list driver CL (skin 7, re-binned every 3
 * sweeps) in six variants: the lists linked (head/next) or in fixed arrays, and the
 * particles numbered as placed (random in space), cell by cell in row-major order, or
 * cell by cell in Morton order (the cells numbered the same way). Plus the fast
 * neighbour list FNL as placed and in Morton order: its rows are per particle, so only
 * the numbering can help it.
 *
 * What to expect. With few particles everything fits in the caches and the variants
 * run alike. With many, a step that reads the positions of its candidates misses the
 * cache when those particles are scattered in memory: numbering them cell by cell puts
 * a cell's particles side by side, and Morton order also puts the cells above and
 * below nearby. DynamO reports 10-28 % from Morton order outside the cache. The
 * particles drift between renumberings (here: only once, at the start), so the gain
 * fades over very long runs.
 *
 * Speed: atom-steps per CPU second, median of 3 repeats; every variant walks the same
 * trajectory (the numbering changes the order of the moves, so not the same one as
 * table22: the same within a numbering).
 *
 * Usage: cell_order OUTDIR [--quick]
 * Writes OUTDIR/cell_order.dat and cell_order.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/nwalk.h"
#include "lz/output.h"

#define SEED 2207u
#define RADIUS 12.0
#define PACKING 0.474
#define SKIN_CL 7.0      /* the best skins of skin.c, as in table22 */
#define SKIN_FNL 32.0
#define REPEATS 3
#define MAXSIDE 6
#define NVAR 8

static const int64_t side_of[MAXSIDE] = {1024, 2048, 4096, 8192, 16384, 32768};

/* A variant: driver, store, numbering. */
typedef struct {
	const char *name;
	lz_nwalk_driver driver;
	int linked;
	int renumber;
	lz_cells_order order;
} variant;

static const variant var[NVAR] = {
	{"CL linked, as placed", LZ_NWALK_CL, 1, 0, LZ_CELLS_ROW},
	{"CL linked, row-major", LZ_NWALK_CL, 1, 1, LZ_CELLS_ROW},
	{"CL linked, Morton", LZ_NWALK_CL, 1, 1, LZ_CELLS_MORTON},
	{"CL arrays, as placed", LZ_NWALK_CL, 0, 0, LZ_CELLS_ROW},
	{"CL arrays, row-major", LZ_NWALK_CL, 0, 1, LZ_CELLS_ROW},
	{"CL arrays, Morton", LZ_NWALK_CL, 0, 1, LZ_CELLS_MORTON},
	{"FNL, as placed", LZ_NWALK_FNL, 0, 0, LZ_CELLS_ROW},
	{"FNL, Morton", LZ_NWALK_FNL, 0, 1, LZ_CELLS_MORTON},
};

typedef struct {
	int nside;
	double steps;
} sizes;

static const sizes full = {6, 3e6};
static const sizes quick = {4, 4e5};

/* Median atom-steps per CPU second of variant v at side L; *clean = no missed pair
 * and no overlap. */
static int run(const variant *v, int64_t side, double steps, double *speed, int *clean)
{
	lz_nwalk_params p = lz_nwalk_params_for(v->driver, LZ_LATTICE_SQUARE, side, RADIUS,
	                                        PACKING);
	p.skin = v->driver == LZ_NWALK_FNL ? SKIN_FNL : SKIN_CL;
	p.order = v->order;
	p.renumber = v->renumber;
	p.linked = v->linked;
	lz_nwalk *nw = lz_nwalk_alloc_seeded(&p, SEED);
	if (!nw)
		return LZ_EINVAL;
	uint64_t sweeps = (uint64_t)fmax(nw->refresh, ceil(steps / (double)p.n));
	double t[REPEATS];
	int status = lz_nwalk_time(nw, SEED + 1, sweeps, REPEATS, t);
	if (status == LZ_OK) {
		gsl_sort(t, 1, REPEATS);
		*speed = 1e9 / gsl_stats_median_from_sorted_data(t, 1, REPEATS);
		*clean = nw->missed == 0 && lz_nwalk_overlaps(nw) == 0;
	}
	lz_nwalk_free(nw);
	return status;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "04", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("cell_order: hard disks R = %g, packing %g, skin CL %g FNL %g, sides 1024 .. "
	       "%lld, seed %u\n", RADIUS, PACKING, SKIN_CL, SKIN_FNL, (long long)side_of[sz->nside - 1], SEED);
	static const char *names[] = {"N", "L", "variant", "atomsteps_per_s"};
	static const char *units[] = {"", "sites", "0-7 (see cell_order.c)", "1/CPU s"};
	lz_data *d = lz_lesson_data(&L, "cell_order.dat", "cell-list and fast-list drivers: "
	                            "linked lists or fixed arrays, particles as placed or "
	                            "numbered cell by cell (row-major or Morton): atom-steps "
	                            "per CPU second, median of 3", 4, names, units);
	if (!d)
		return lz_lesson_error(&L);
	static double speed[MAXSIDE][NVAR];
	int clean = 1;
	for (int s = 0; s < sz->nside; s++) {
		double n = round(PACKING * (double)side_of[s] * (double)side_of[s] /
		                 (M_PI * RADIUS * RADIUS));
		printf("  N = %.0f:\n", n);
		for (int v = 0; v < NVAR; v++) {
			int ok;
			if (run(&var[v], side_of[s], sz->steps, &speed[s][v], &ok) != LZ_OK) {
				lz_data_close(d);
				return lz_lesson_error(&L);
			}
			clean = clean && ok;
			printf("    %-22s %8.2f M atom-steps/s\n", var[v].name, 1e-6 * speed[s][v]);
			fflush(stdout);
			double row[4] = {n, (double)side_of[s], v, speed[s][v]};
			lz_data_row(d, row);
		}
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	int top = sz->nside - 1;
	double morton_gain = speed[top][5] / speed[top][3];
	double arrays_gain = speed[top][5] / speed[top][2];
	double fnl_gain = speed[top][7] / speed[top][6];
	printf("  at N = %.0f: CL arrays Morton / as placed %.2f; arrays / linked (Morton) %.2f; "
	       "FNL Morton / as placed %.2f\n", round(PACKING * (double)side_of[top] *
	       (double)side_of[top] / (M_PI * RADIUS * RADIUS)), morton_gain, arrays_gain,
	       fnl_gain);
	printf("  no missed pair and no overlap in any variant: %s\n", lz_lesson_check(&L, clean));
	printf("  numbering cell by cell pays outside the caches (CL arrays, Morton / as "
	       "placed > 1.1 at the largest N): %s\n", lz_lesson_check(&L, morton_gain > 1.1));

	lz_json *j = lz_lesson_json(&L, "cell_order.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_num(j, "largest_side", (double)side_of[top]);
	lz_json_num(j, "cl_morton_over_placed_largest", morton_gain);
	lz_json_num(j, "cl_arrays_over_linked_largest", arrays_gain);
	lz_json_num(j, "fnl_morton_over_placed_largest", fnl_gain);
	lz_json_num(j, "cl_arrays_morton_smallest", speed[0][5]);
	lz_json_num(j, "cl_arrays_morton_largest", speed[top][5]);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "every variant exact; cell-by-cell numbering pays at large N");
}
