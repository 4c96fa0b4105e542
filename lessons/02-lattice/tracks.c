/* tracks — lesson 02, experiment (§6): the path of one hard disk among others on the
 * square and triangular lattices, random walk against ballistic motion (thesis fig.
 * 2.3).
 *
 * 40 disks of radius R = 2 (packing 0.03) in a periodic box of side 128 move for
 * 2e5 sweeps; the path of disk 0 is unwrapped (each accepted step added to a
 * running Cartesian position) so that it does not jump at the box's edges. A random
 * walker picks a new direction every step and so turns almost every step; a
 * ballistic one flies straight until it meets another disk. The run length — the
 * number of successive steps taken in one direction — measures the difference: for a
 * free random walker it is ndir/(ndir - 1) on average (the same direction comes
 * again with probability 1/ndir), 1.33 on the square lattice and 1.2 on the
 * triangular one; for a ballistic disk it is about the mean free path in lattice
 * units, ≈ 1/(2 n σ) for disks of diameter σ at number density n — longer on the
 * square lattice, where disks flying along the same axis never meet.
 *
 * Usage: tracks OUTDIR [--quick]   (quick: 1000 sweeps for the tracks, 2e4 for the
 * run lengths; full: 2000 and 2e5). Writes OUTDIR/tracks.dat and tracks.json.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"
#include "lz/walk.h"

#define SEED 23u
#define SIDE 128
#define RADIUS 2.0
#define NDISK 40   /* packing 40·4π/128² = 0.031: a dilute gas, long free paths */

enum { NCASE = 4 };
static const lz_lattice_kind kinds[NCASE] = {LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE,
                                             LZ_LATTICE_TRIANGULAR, LZ_LATTICE_TRIANGULAR};
static const lz_walk_motion motions[NCASE] = {LZ_WALK_RANDOM, LZ_WALK_BALLISTIC,
                                              LZ_WALK_RANDOM, LZ_WALK_BALLISTIC};

typedef struct {
	double mean_run;  /* steps per straight run of disk 0 */
	double expect;    /* ndir/(ndir-1) for a walker, the free path for a ballistic disk */
	double acceptance;
} result;

/* The step disk 0 took, as a direction index, or -1 if it stayed. */
static int step_taken(const lz_walk *w, const int32_t *before)
{
	for (int d = 0; d < w->ndir; d++) {
		uint32_t m = (uint32_t)w->box->mask;
		if ((int32_t)((uint32_t)(before[0] + w->dirs[d].x) & m) == w->r[0] &&
		    (int32_t)((uint32_t)(before[1] + w->dirs[d].y) & m) == w->r[1])
			return d;
	}
	return -1;
}

/* One case: the track of disk 0 for `show` sweeps into d (columns case, x, y), and
 * its mean run length over `sweeps` sweeps. */
static int run_case(int c, long show, long sweeps, lz_rng *rng, lz_data *d, result *res)
{
	lz_walk *w = lz_walk_alloc(kinds[c], SIDE, RADIUS, NDISK, motions[c]);
	if (!w || lz_walk_place(w, rng->gsl, 0) != LZ_OK) {
		lz_walk_free(w);
		return LZ_EINVAL;
	}
	double x = 0, y = 0, shear = kinds[c] == LZ_LATTICE_TRIANGULAR ? 0.5 : 0;
	double rise = kinds[c] == LZ_LATTICE_TRIANGULAR ? sqrt(3) / 2 : 1;
	long runs = 0, steps = 0;
	int last = -1;
	for (long s = 0; s < sweeps; s++) {
		int32_t before[2] = {w->r[0], w->r[1]};
		lz_walk_sweep(w, rng->gsl);
		int k = step_taken(w, before);
		if (k >= 0) {
			x += w->dirs[k].x + shear * w->dirs[k].y;
			y += rise * w->dirs[k].y;
			steps++;
			runs += k != last;
		}
		last = k;
		if (s < show) {
			double row[3] = {c, x, y};
			lz_data_row(d, row);
		}
	}
	double n_density = NDISK / ((double)SIDE * SIDE * lz_lattice_cell_volume(kinds[c]));
	res->mean_run = runs ? (double)steps / (double)runs : NAN;
	res->expect = motions[c] == LZ_WALK_RANDOM ? w->ndir / (w->ndir - 1.0)
	                                           : 1 / (2 * n_density * 2 * RADIUS);
	res->acceptance = (double)w->accepted / (double)w->moves;
	lz_walk_free(w);
	return LZ_OK;
}

int main(int argc, char **argv)
{
	static const char *names[] = {"case", "x", "y"};
	static const char *units[] = {"0 sq walk, 1 sq ballistic, 2 tri walk, 3 tri ballistic",
	                              "lattice units", "lattice units"};
	static const char *label[NCASE] = {"square, random walk", "square, ballistic",
	                                   "triangular, random walk", "triangular, ballistic"};
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	long show = L.quick ? 1000 : 2000, sweeps = L.quick ? 20000 : 200000;
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	lz_data *d = rng ? lz_lesson_data(&L, "tracks.dat", "the unwrapped path of one disk "
	                                  "among 40 (R = 2, L = 128), Cartesian", 3, names, units)
	                 : NULL;
	if (!d) {
		lz_rng_free(rng);
		return lz_lesson_error(&L);
	}
	printf("tracks: %d disks R = %g, L = %d (packing %.3f square), %ld sweeps, mt19937 "
	       "seed %u\n", NDISK, RADIUS, SIDE, lz_walk_packing(LZ_LATTICE_SQUARE, SIDE, RADIUS,
	       NDISK), sweeps, SEED);
	result res[NCASE];
	for (int c = 0; c < NCASE; c++) {
		if (run_case(c, show, sweeps, rng, d, &res[c]) != LZ_OK) {
			lz_rng_free(rng);
			return lz_lesson_error(&L);
		}
		printf("  %-24s mean run %6.2f steps (expected %6.2f), acceptance %.3f\n", label[c],
		       res[c].mean_run, res[c].expect, res[c].acceptance);
	}
	lz_rng_free(rng);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	for (int c = 0; c < NCASE; c += 2) {
		printf("  %s: run length within 5 %% of ndir/(ndir-1): %s\n", label[c],
		       lz_lesson_check(&L, fabs(res[c].mean_run / res[c].expect - 1) < 0.05));
		printf("  %s: runs within a factor 2 of the free path 1/(2nσ) = %.1f: %s\n",
		       label[c + 1], res[c + 1].expect, lz_lesson_check(&L,
		       res[c + 1].mean_run > res[c + 1].expect / 2 &&
		       res[c + 1].mean_run < 2 * res[c + 1].expect));
	}
	lz_json *j = lz_lesson_json(&L, "tracks.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_num(j, "run_walk_square", res[0].mean_run);
	lz_json_num(j, "run_ballistic_square", res[1].mean_run);
	lz_json_num(j, "run_walk_triangular", res[2].mean_run);
	lz_json_num(j, "run_ballistic_triangular", res[3].mean_run);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "random walkers turn, ballistic disks fly a free path");
}
