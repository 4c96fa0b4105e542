/* skin — lesson 04, experiment: the trade. Skin Δr against refresh interval against
 * cost against missed interactions: the stage's trade of cost against accuracy.
 *
 * 4400 hard disks (R = 12, σ = 24, packing 0.474, box 2048) random-walk on the square
 * lattice. A step moves a disk by 1, so the pairs that can decide a step are those
 * closer than r_c = σ + 1 = 25, and the lists hold the pairs closer than r_l = r_c + Δr.
 *
 * (a) Cost at the safe interval, refresh = floor(Δr / 2) sweeps, for Δr = 2 .. 64:
 * CPU ns per atom-step (median of 3) of NL, FNL and CL, and the list entries per
 * particle. A thin skin refreshes often; a thick one tests more candidates at every
 * step (the lists grow as r_l²) and, for FNL, refreshes cost k² per particle. FNL
 * misses pairs below Δr = 32 even at the safe interval (fnl_loss.c: its lists are too
 * short to hold the common neighbours it relies on). Each driver's best skin — the
 * fastest that missed nothing — is printed, and in skin.json.
 *
 * (b) Beyond the safe interval: FNL at Δr = 32 (safe: 16 sweeps) and CL at Δr = 7
 * (safe: 3) refreshed from well inside to far beyond, counting before every refresh
 * the pairs closer than r_c that the driver cannot see (per refresh per 1000
 * particles) and, at the end, the overlapping pairs — the damage. Refreshing less
 * often is cheaper and, past the safe interval, wrong: a work–precision diagram.
 *
 * Usage: skin OUTDIR [--quick]
 * Writes OUTDIR/skin_cost.dat, skin_trade.dat and skin.json.
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

#define SEED 2206u
#define RADIUS 12.0
#define SIDE 2048
#define PACKING 0.474
#define REPEATS 3
#define NSKIN 11
#define NREF 8

static const double skin_of[NSKIN] = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
static const lz_nwalk_driver cost_drv[3] = {LZ_NWALK_NL, LZ_NWALK_FNL, LZ_NWALK_CL};
/* Part (b): FNL at Δr = 32 (safe: 16 sweeps) and CL at Δr = 7 (safe: 3), each refreshed
 * from well inside to far beyond its safe interval. */
static const lz_nwalk_driver trade_drv[2] = {LZ_NWALK_FNL, LZ_NWALK_CL};
static const double trade_skin[2] = {32, 7};
static const int refresh_of[2][NREF] = {{8, 16, 32, 64, 128, 256, 512, 1024},
                                        {1, 3, 6, 12, 24, 48, 96, 192}};

typedef struct {
	double steps, nl_steps;   /* atom-steps per timed repeat */
	double trade_sweeps;      /* sweeps per run in part (b) */
} sizes;

static const sizes full = {1.5e6, 2e5, 240};
static const sizes quick = {2e5, 5e4, 48};

/* One measured run. */
typedef struct {
	double ns;          /* CPU ns per atom-step, median of the repeats */
	double entries;     /* list entries per particle (NL, FNL), distance tests per step (CL) */
	double missed;      /* pairs missed per refresh per 1000 particles */
	uint64_t overlaps;
	int refresh;
} measure;

/* `repeats` runs of `sweeps` sweeps (at least one refresh each), timed apart. */
static int run(lz_nwalk_driver d, double skin, int refresh, double sweeps, int repeats,
               measure *m)
{
	lz_nwalk_params p = lz_nwalk_params_for(d, LZ_LATTICE_SQUARE, SIDE, RADIUS, PACKING);
	p.skin = skin;
	p.refresh = refresh;
	lz_nwalk *nw = lz_nwalk_alloc_seeded(&p, SEED);
	if (!nw)
		return LZ_EINVAL;
	uint64_t count = (uint64_t)fmax(nw->refresh, ceil(sweeps));
	double t[REPEATS];
	int status = lz_nwalk_time(nw, SEED + 1, count, repeats, t);
	if (status == LZ_OK) {
		gsl_sort(t, 1, (size_t)repeats);
		m->ns = gsl_stats_median_from_sorted_data(t, 1, (size_t)repeats);
		m->entries = nw->nl ? (double)lz_nlist_entries(nw->nl) / (double)nw->p.n
		                    : (double)nw->candidates / (double)nw->moves;
		m->missed = nw->refreshes ? 1000.0 * (double)nw->missed /
		                            ((double)nw->refreshes * (double)nw->p.n) : 0;
		m->overlaps = lz_nwalk_overlaps(nw);
		m->refresh = nw->refresh;
	}
	lz_nwalk_free(nw);
	return status;
}

/* Part (a): every driver at every skin, at the safe interval. */
static int cost(lz_lesson *L, const sizes *sz, measure a[3][NSKIN])
{
	static const char *names[] = {"skin", "refresh", "driver", "ns_per_step", "entries",
	                              "missed", "overlaps"};
	static const char *units[] = {"lattice", "sweeps", "0 NL 1 FNL 2 CL", "CPU ns",
	                              "per particle (CL: tests per step)", "per refresh per 1000",
	                              "pairs"};
	lz_data *d = lz_lesson_data(L, "skin_cost.dat", "4400 hard disks, R = 12, packing "
	                            "0.474: cost per atom-step at the safe refresh interval "
	                            "against the skin", 7, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < 3; k++)
		for (int s = 0; s < NSKIN; s++) {
			double steps = k == 0 ? sz->nl_steps : sz->steps;
			measure *m = &a[k][s];
			if (run(cost_drv[k], skin_of[s], 0, steps / 4400.0, REPEATS, m) != LZ_OK) {
				lz_data_close(d);
				return LZ_EINVAL;
			}
			printf("  (a) %-3s skin %4.0f refresh %2d: %7.1f ns/step, %6.2f entries, "
			       "missed %g, overlaps %llu\n", lz_nwalk_driver_name(cost_drv[k]),
			       skin_of[s], m->refresh, m->ns, m->entries, m->missed,
			       (unsigned long long)m->overlaps);
			double row[7] = {skin_of[s], m->refresh, (double)cost_drv[k], m->ns, m->entries,
			                 m->missed, (double)m->overlaps};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

/* Part (b): FNL and CL refreshed every 1 .. 64 sweeps. */
static int trade(lz_lesson *L, const sizes *sz, measure b[2][NREF])
{
	static const char *names[] = {"skin", "refresh", "safe", "driver", "ns_per_step",
	                              "missed", "overlaps"};
	static const char *units[] = {"lattice", "sweeps", "sweeps", "1 FNL 2 CL", "CPU ns",
	                              "per refresh per 1000", "pairs"};
	lz_data *d = lz_lesson_data(L, "skin_trade.dat", "4400 hard disks, R = 12, packing "
	                            "0.474: cost and missed pairs against the refresh interval",
	                            7, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < 2; k++)
		for (int r = 0; r < NREF; r++) {
			measure *m = &b[k][r];
			int safe = (int)floor(trade_skin[k] / 2);
			double sweeps = fmax(sz->trade_sweeps, 3.0 * refresh_of[k][r]);
			if (run(trade_drv[k], trade_skin[k], refresh_of[k][r], sweeps, 1, m) != LZ_OK) {
				lz_data_close(d);
				return LZ_EINVAL;
			}
			printf("  (b) %-3s skin %2.0f refresh %2d (safe %2d): %7.1f ns/step, missed "
			       "%9.4f per refresh per 1000, overlaps %llu\n",
			       lz_nwalk_driver_name(trade_drv[k]), trade_skin[k], refresh_of[k][r], safe,
			       m->ns, m->missed, (unsigned long long)m->overlaps);
			double row[7] = {trade_skin[k], refresh_of[k][r], safe, (double)trade_drv[k],
			                 m->ns, m->missed, (double)m->overlaps};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "04", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("skin: 4400 hard disks, R = %g, packing %g, box %d, seed %u\n", RADIUS, PACKING,
	       SIDE, SEED);
	static measure a[3][NSKIN], b[2][NREF];
	if (cost(&L, sz, a) != LZ_OK || trade(&L, sz, b) != LZ_OK)
		return lz_lesson_error(&L);

	int best[3], clean = 1;
	for (int k = 0; k < 3; k++) {
		best[k] = -1;
		for (int s = 0; s < NSKIN; s++) {
			int ok = a[k][s].missed == 0 && a[k][s].overlaps == 0;
			if (cost_drv[k] != LZ_NWALK_FNL || skin_of[s] >= 32)
				clean = clean && ok;
			if (ok && (best[k] < 0 || a[k][s].ns < a[k][best[k]].ns))
				best[k] = s;
		}
		if (best[k] < 0)
			best[k] = 0;
		printf("  best skin for %s: %g (%.1f ns per atom-step)\n",
		       lz_nwalk_driver_name(cost_drv[k]), skin_of[best[k]], a[k][best[k]].ns);
	}
	int safe_clean = 1, unsafe_misses = 1;
	for (int k = 0; k < 2; k++) {
		int safe = (int)floor(trade_skin[k] / 2);
		for (int r = 0; r < NREF; r++)
			if (refresh_of[k][r] <= safe)
				safe_clean = safe_clean && b[k][r].missed == 0 && b[k][r].overlaps == 0;
		unsafe_misses = unsafe_misses && b[k][NREF - 1].missed > 0;
	}
	printf("  NL and CL at every skin, FNL from skin 32 on, and every run at or below its "
	       "safe interval miss nothing: %s\n", lz_lesson_check(&L, clean && safe_clean));
	printf("  refreshing 64 times too late misses pairs: %s\n",
	       lz_lesson_check(&L, unsafe_misses));

	lz_json *j = lz_lesson_json(&L, "skin.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	for (int k = 0; k < 3; k++) {
		char key[64];
		snprintf(key, sizeof key, "best_skin_%s", lz_nwalk_driver_name(cost_drv[k]));
		lz_json_num(j, key, skin_of[best[k]]);
		snprintf(key, sizeof key, "best_ns_per_step_%s", lz_nwalk_driver_name(cost_drv[k]));
		lz_json_num(j, key, a[k][best[k]].ns);
	}
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "safe intervals miss nothing; longer ones miss pairs");
}
