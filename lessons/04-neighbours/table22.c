/* table22 — lesson 04, experiment: the four ways to find neighbours on one system
 * (thesis 2.5.1, table 2.2), from 10^3 to 10^6 particles.
 *
 * Hard disks of radius R = 12 random-walk on the square lattice at packing 0.474 in
 * boxes of side L = 1024 .. 32768 (N = 1099 .. 1 125 000: the thesis's 1100 .. 70 400
 * and two sizes beyond). Every driver of lz/nwalk.h walks the same system: the same
 * start (random sequential adsorption from one seed) and the same random numbers, so
 * with a safe refresh interval they make the same decisions, and the final
 * configurations must be identical — that is checked, with zero missed pairs and zero
 * overlaps. Each driver runs at its own best skin (skin_of below), refreshed at the
 * safe interval floor(Δr / 2) sweeps.
 *
 * What to expect. NL rebuilds its lists from all pairs, N²/2 distances every 16 sweeps
 * (skin 32): per atom-step that is N/32 distances, so its speed falls as 1/N once the
 * rebuild dominates. FNL refreshes from the neighbours of the neighbours, CL re-bins: O(1)
 * per atom-step, so their speed is flat but for the caches (the thesis: 337/397 and
 * 199/216 from 1100 to 70 400). FR does one look-up per step but repaints the
 * perimeter of the excluded disk: flat and slower. Speed: atom-steps per CPU second
 * (the machine is shared), the median of 3 repeats (one run above 10^5 particles);
 * the fitted exponent α of
 * speed ∝ N^α for each driver.
 *
 * Usage: table22 OUTDIR [--quick]
 * Writes OUTDIR/table22.dat and table22.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/nwalk.h"
#include "lz/output.h"

#define SEED 2204u        /* fixed: the lesson quotes the numbers of this run */
#define RADIUS 12.0
#define PACKING 0.474
#define NDRV 4
#define MAXSIDE 6
#define REPEATS 3

static const int64_t side_of[MAXSIDE] = {1024, 2048, 4096, 8192, 16384, 32768};
/* Each driver's skin, from skin.c at N = 4400: FNL 32, its fastest skin that misses
 * nothing (shorter lists lose pairs, lesson 04 §10: r_l = 57, refreshed every 16 sweeps);
 * NL the same lists, so that the two differ only in how they refresh (NL alone would
 * gain from a thicker skin still); CL 7, at its best (r_l = 32: cells of 32, re-binned
 * every 3 sweeps); FR has none. */
static const double skin_of[NDRV] = {32, 32, 7, 0};
/* Thesis table 2.2, 1000 atom-steps per second on a 433 MHz Alpha (rigid4), at
 * N = 1100, 4400, 17 600, 70 400 (boxes 1024 .. 8192); NL, FNL, CL, FR. */
static const double thesis[NDRV][4] = {
	{393, 210, 70, 20}, {397, 386, 344, 337}, {216, 210, 204, 199}, {48, 48, 48, 47}};

/* How far each run goes: the sides, the largest side NL runs at (its rebuild is
 * O(N²)), and the atom-steps each timed repeat aims at (NL fewer). */
typedef struct {
	int nside;
	int64_t nl_max;
	double steps, nl_steps;
} sizes;

static const sizes full = {6, 8192, 4e6, 3e5};
static const sizes quick = {4, 4096, 6e5, 1e5};

typedef struct {
	int ran;
	size_t n;
	long sweeps;
	double speed, lo, hi;       /* atom-steps per CPU second: median, slowest, fastest */
	double bytes;               /* the neighbour structure, bytes per particle */
	double neighbours;          /* list entries, distance tests or painted points per step */
	double acceptance;
	uint64_t missed, overlaps;
	int32_t *final;             /* the last configuration, n·2 */
} cell_run;

static cell_run runs[MAXSIDE][NDRV];

static lz_nwalk_params params(lz_nwalk_driver d, int64_t side)
{
	lz_nwalk_params p = lz_nwalk_params_for(d, LZ_LATTICE_SQUARE, side, RADIUS, PACKING);
	p.skin = skin_of[d];   /* particles as placed: the thesis's order */
	return p;
}

/* What a step costs the driver in look-ups: list entries per particle (NL, FNL),
 * distance tests per offered step (CL), repainted points per step (FR). */
static double neighbours(const lz_nwalk *nw)
{
	switch (nw->p.driver) {
	case LZ_NWALK_NL:
	case LZ_NWALK_FNL:
		return (double)lz_nlist_entries(nw->nl) / (double)nw->p.n;
	case LZ_NWALK_CL:
		return (double)nw->candidates / (double)nw->moves;
	default:
		return 2 * lz_shape_mean_move(nw->field->excl);
	}
}

/* One driver at one size: REPEATS timed runs of `sweeps` sweeps, each from the
 * generator seeded SEED + 1 + repeat (the same for every driver). */
static int run_one(cell_run *cr, lz_nwalk_driver d, int64_t side, double steps)
{
	lz_nwalk_params p = params(d, side);
	lz_nwalk *nw = lz_nwalk_alloc_seeded(&p, SEED);
	if (!nw)
		return LZ_EINVAL;
	cr->n = p.n;
	/* The same sweeps for every driver at a size (NL at large N fewer), at least 16 so
	 * that each timed run refreshes: drivers that run as many sweeps must end in the
	 * same configuration. */
	cr->sweeps = lround(fmax(16, round(steps / (double)p.n)));
	int repeats = p.n > 100000 ? 1 : REPEATS;   /* one run is 18 million steps at 10^6 */
	double t[REPEATS];
	int status = lz_nwalk_time(nw, SEED + 1, (uint64_t)cr->sweeps, repeats, t);
	if (status == LZ_OK) {
		gsl_sort(t, 1, (size_t)repeats);
		cr->speed = 1e9 / gsl_stats_median_from_sorted_data(t, 1, (size_t)repeats);
		cr->lo = 1e9 / t[repeats - 1];
		cr->hi = 1e9 / t[0];
		cr->bytes = (double)lz_nwalk_list_bytes(nw) / (double)p.n;
		cr->neighbours = neighbours(nw);
		cr->acceptance = (double)nw->accepted / (double)nw->moves;
		cr->missed = nw->missed;
		cr->overlaps = lz_nwalk_overlaps(nw);
		size_t bytes = 2 * p.n * sizeof(int32_t);
		cr->final = malloc(bytes);
		if (cr->final)
			memcpy(cr->final, lz_nwalk_positions(nw), bytes);
		else
			status = LZ_ENOMEM;
		cr->ran = 1;
	}
	lz_nwalk_free(nw);
	return status;
}

/* The exponent α of speed ∝ N^α, fitted over the first nside sizes driver d ran at. */
static double exponent(int nside, int d)
{
	double x[MAXSIDE], y[MAXSIDE], a, b, c00, c01, c11, ss;
	size_t k = 0;
	for (int s = 0; s < nside; s++)
		if (runs[s][d].ran) {
			x[k] = log((double)runs[s][d].n);
			y[k++] = log(runs[s][d].speed);
		}
	if (k < 2)
		return NAN;
	gsl_fit_linear(x, 1, y, 1, k, &a, &b, &c00, &c01, &c11, &ss);
	return b;
}

static void print_row(int s, int d)
{
	const cell_run *cr = &runs[s][d];
	printf("  %8zu %6lld %4s %6ld %10.3f %10.3f %8.1f %8.2f %7.3f %6llu %6llu\n", cr->n,
	       (long long)side_of[s], lz_nwalk_driver_name((lz_nwalk_driver)d), cr->sweeps,
	       1e-6 * cr->speed, s < 4 ? 1e-3 * thesis[d][s] : NAN, cr->bytes, cr->neighbours,
	       cr->acceptance, (unsigned long long)cr->missed, (unsigned long long)cr->overlaps);
}

static int write_data(lz_lesson *L, int nside)
{
	static const char *names[] = {"N", "L", "driver", "atomsteps_per_s", "slowest", "fastest",
	                              "thesis", "bytes_per_particle", "neighbours", "missed",
	                              "overlaps"};
	static const char *units[] = {"", "sites", "0 NL 1 FNL 2 CL 3 FR", "1/CPU s", "1/CPU s",
	                              "1/CPU s", "1/s (433 MHz Alpha)", "B", "", "pairs", "pairs"};
	lz_data *dd = lz_lesson_data(L, "table22.dat", "random walk of hard disks, R = 12, "
	                             "packing 0.474, skins 32/32/7, safe refresh: atom-steps per CPU "
	                             "second of the four drivers (median, slowest, fastest of 3), "
	                             "the thesis's table 2.2 beside (nan: not in it)", 11, names,
	                             units);
	if (!dd)
		return LZ_EIO;
	for (int d = 0; d < NDRV; d++)
		for (int s = 0; s < nside; s++) {
			const cell_run *cr = &runs[s][d];
			if (!cr->ran)
				continue;
			double row[11] = {(double)cr->n, (double)side_of[s], d, cr->speed, cr->lo,
			                  cr->hi, s < 4 ? 1e3 * thesis[d][s] : NAN, cr->bytes,
			                  cr->neighbours, (double)cr->missed, (double)cr->overlaps};
			lz_data_row(dd, row);
		}
	return lz_data_close(dd);
}

static int write_json(lz_lesson *L, int nside, const double *alpha,
                      const double *thesis_alpha)
{
	lz_json *j = lz_lesson_json(L, "table22.json");
	if (!j)
		return LZ_EIO;
	lz_json_int(j, "seed", SEED);
	lz_json_num(j, "radius", RADIUS);
	lz_json_num(j, "packing", PACKING);
	lz_json_num(j, "skin_nl", skin_of[0]);
	lz_json_num(j, "skin_fnl", skin_of[1]);
	lz_json_num(j, "skin_cl", skin_of[2]);
	lz_json_int(j, "largest_n", (long long)runs[nside - 1][LZ_NWALK_FNL].n);
	for (int d = 0; d < NDRV; d++) {
		char key[64];
		const char *name = lz_nwalk_driver_name((lz_nwalk_driver)d);
		snprintf(key, sizeof key, "exponent_%s", name);
		lz_json_num(j, key, alpha[d]);
		snprintf(key, sizeof key, "exponent_%s_thesis_sizes", name);
		lz_json_num(j, key, thesis_alpha[d]);
		snprintf(key, sizeof key, "atomsteps_per_s_%s_smallest", name);
		lz_json_num(j, key, runs[0][d].speed);
	}
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "04", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("table22: hard disks R = %g, packing %g, skins NL %g FNL %g CL %g, safe refresh; "
	       "sides 1024 .. %lld; NL up to %lld; seed %u\n", RADIUS, PACKING, skin_of[0],
	       skin_of[1], skin_of[2],
	       (long long)side_of[sz->nside - 1], (long long)sz->nl_max, SEED);
	printf("  %8s %6s %4s %6s %10s %10s %8s %8s %7s %6s %6s\n", "N", "L", "drv", "sweeps",
	       "Msteps/s", "thesis", "B/part", "nbrs", "accept", "missed", "overl");
	for (int s = 0; s < sz->nside; s++)
		for (int d = 0; d < NDRV; d++) {
			if (d == LZ_NWALK_NL && side_of[s] > sz->nl_max)
				continue;
			double steps = d == LZ_NWALK_NL && side_of[s] > 2048 ? sz->nl_steps : sz->steps;
			if (run_one(&runs[s][d], (lz_nwalk_driver)d, side_of[s], steps) != LZ_OK)
				return lz_lesson_error(&L);
			print_row(s, d);
			fflush(stdout);
		}
	double alpha[NDRV], thesis_alpha[NDRV];
	for (int d = 0; d < NDRV; d++) {
		alpha[d] = exponent(sz->nside, d);
		thesis_alpha[d] = exponent(4, d);
	}
	printf("  fitted speed ~ N^alpha, all sizes: NL %.2f, FNL %.2f, CL %.2f, FR %.2f\n",
	       alpha[0], alpha[1], alpha[2], alpha[3]);
	printf("  the thesis's sizes (N <= 70 400): NL %.2f, FNL %.2f, CL %.2f, FR %.2f\n",
	       thesis_alpha[0], thesis_alpha[1], thesis_alpha[2], thesis_alpha[3]);

	int clean = 1, same = 1, nl_same = 0;
	for (int s = 0; s < sz->nside; s++)
		for (int d = 0; d < NDRV; d++) {
			const cell_run *cr = &runs[s][d], *ref = &runs[s][LZ_NWALK_FR];
			if (!cr->ran)
				continue;
			clean = clean && cr->missed == 0 && cr->overlaps == 0;
			if (cr->sweeps != ref->sweeps)   /* NL runs fewer sweeps at large N */
				continue;
			int eq = memcmp(cr->final, ref->final, 2 * cr->n * sizeof(int32_t)) == 0;
			same = same && eq;
			nl_same += d == LZ_NWALK_NL && eq;
		}
	printf("  no missed pair and no overlap at the safe refresh: %s\n",
	       lz_lesson_check(&L, clean));
	printf("  FNL, CL and FR walked the same trajectory at every size, and NL where it ran "
	       "as many sweeps (%d sizes): %s\n", nl_same, lz_lesson_check(&L, same && nl_same > 0));
	printf("  NL slows as its O(N^2) rebuild takes over, alpha < -0.4 (%.2f): %s\n",
	       alpha[0], lz_lesson_check(&L, alpha[0] < -0.4));
	printf("  FNL and CL are O(N) over the thesis's sizes, |alpha| < 0.3 (%.2f, %.2f): %s\n",
	       thesis_alpha[1], thesis_alpha[2],
	       lz_lesson_check(&L, fabs(thesis_alpha[1]) < 0.3 && fabs(thesis_alpha[2]) < 0.3));
	int status = write_data(&L, sz->nside) == LZ_OK && write_json(&L, sz->nside, alpha, thesis_alpha) == LZ_OK;
	for (int s = 0; s < MAXSIDE; s++)
		for (int d = 0; d < NDRV; d++)
			free(runs[s][d].final);
	if (!status)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "four drivers, one trajectory; NL O(N^2), FNL and CL O(N)");
}
