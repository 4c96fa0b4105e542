/* shells — lesson 02, experiment 3 (§5, §8): lattice points per shell and the lattice
 * measure correction.
 *
 * For the square, triangular (sheared, d² = dx² + dx·dy + dy²) and simple cubic
 * lattices, the number of lattice points in each unit shell k <= r < k+1 (a point on a
 * boundary goes outward) over the exact shell area π(2k+1) (triangular: times the
 * area √3/2 of one site) or volume 4π/3 (3k² + 3k + 1). That ratio, the lattice
 * measure M(k), is what divides the raw lattice g(r). The counts are checked against
 * thesis table 2.4.
 *
 * The trade: a particle of radius R lattice units has σ = 2R, so g(r) on 1 < r/σ < 3
 * is sampled by the shells 2R .. 6R. The rms of M - 1 over those shells is the size
 * of the lattice "noise" a raw g(r) carries at that resolution; the d² histogram
 * needs (6R)² bins to reach 3σ. Both for R = 3, 6, 12, 24.
 *
 * Usage: shells OUTDIR [--quick]   (the same size either way)
 * Writes OUTDIR/shells.dat, shells_res.dat and shells.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "lz/error.h"
#include "lz/lattice.h"
#include "lz/lesson.h"
#include "lz/output.h"

#define NSHELL 150  /* shells 0 .. NSHELL-1: up to 6R for R = 24 */
#define NLAT 3

static const char *const lat_name[NLAT] = {"square", "triangular", "cubic"};

/* thesis table 2.4: points in shells [0,1) .. [9,10) */
static const long table24[NLAT][10] = {
	{1, 8, 16, 20, 24, 40, 36, 48, 56, 56},
	{1, 12, 18, 24, 30, 36, 48, 66, 60, 66},
	{1, 26, 66, 158, 234, 410, 470, 738, 866, 1170},
};

/* The shell of a point at integer distance² d2: the k with k² <= d2 < (k+1)². */
static int shell_of(int64_t d2)
{
	int64_t k = (int64_t)sqrt((double)d2);
	while (k * k > d2)
		k--;
	while ((k + 1) * (k + 1) <= d2)
		k++;
	return (int)k;
}

/* Brute force: every lattice point with r < NSHELL, counted into its shell. The
 * sheared triangular lattice reaches r = n at |x| up to 2n/√3: hence the wider loop. */
static void count_shells(long count[NLAT][NSHELL])
{
	const int64_t n = NSHELL;
	for (int64_t x = -2 * n; x <= 2 * n; x++)
		for (int64_t y = -2 * n; y <= 2 * n; y++) {
			int64_t tri = lz_lattice_dist2(LZ_LATTICE_TRIANGULAR, (int32_t)x, (int32_t)y, 0);
			if (tri < n * n)
				count[1][shell_of(tri)]++;
		}
	for (int64_t x = -n; x <= n; x++)
		for (int64_t y = -n; y <= n; y++) {
			int64_t sq = lz_lattice_dist2(LZ_LATTICE_SQUARE, (int32_t)x, (int32_t)y, 0);
			if (sq < n * n)
				count[0][shell_of(sq)]++;
			for (int64_t z = -n; z <= n; z++) {
				int64_t cub = lz_lattice_dist2(LZ_LATTICE_CUBIC, (int32_t)x, (int32_t)y,
				                               (int32_t)z);
				if (cub < n * n)
					count[2][shell_of(cub)]++;
			}
		}
}

/* The exact measure of shell k on lattice l, in lattice sites (area over the area
 * of one site). */
static double exact_measure(int l, int k)
{
	double kk = k;
	if (l == 2)
		return 4.0 * M_PI / 3.0 * (3.0 * kk * kk + 3.0 * kk + 1.0);
	double area = M_PI * (2.0 * kk + 1.0);
	return l == 1 ? area / lz_lattice_cell_volume(LZ_LATTICE_TRIANGULAR) : area;
}

int main(int argc, char **argv)
{
	static long count[NLAT][NSHELL];
	static const char *names[] = {"k", "n_square", "n_triangular", "n_cubic", "M_square",
	                              "M_triangular", "M_cubic"};
	static const char *units[] = {"lattice", "points", "points", "points", "", "", ""};
	static const int radii[4] = {3, 6, 12, 24};
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	printf("shells: lattice points in unit shells k <= r < k+1, k < %d, square, "
	       "triangular (sheared), cubic\n", NSHELL);
	count_shells(count);

	int table_ok = 1;
	printf("  %-8s %-10s %-10s %-10s\n", "shell", lat_name[0], lat_name[1], lat_name[2]);
	for (int k = 0; k < 10; k++) {
		printf("  [%d,%d)%*s", k, k + 1, k < 9 ? 3 : 2, "");
		for (int l = 0; l < NLAT; l++) {
			printf(" %-10ld", count[l][k]);
			table_ok = table_ok && count[l][k] == table24[l][k];
		}
		printf("\n");
	}
	printf("  the first ten shells equal thesis table 2.4: %s\n",
	       lz_lesson_check(&L, table_ok));

	lz_data *d = lz_lesson_data(&L, "shells.dat", "lattice points per unit shell and "
	                            "their ratio M to the exact shell measure", 7, names, units);
	if (!d)
		return lz_lesson_error(&L);
	for (int k = 0; k < NSHELL; k++) {
		double row[7] = {k, count[0][k], count[1][k], count[2][k], 0, 0, 0};
		for (int l = 0; l < NLAT; l++)
			row[4 + l] = (double)count[l][k] / exact_measure(l, k);
		lz_data_row(d, row);
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	/* the trade: lattice noise of a raw g(r) on 1 < r/σ < 3 against R */
	static const char *rnames[] = {"R", "rms_square", "rms_triangular", "rms_cubic",
	                               "max_square", "d2_bins"};
	static const char *runits[] = {"lattice", "", "", "", "", "bins"};
	lz_data *dr = lz_lesson_data(&L, "shells_res.dat", "rms and max |M - 1| over the "
	                             "shells 2R <= k < 6R (1 < r/sigma < 3)", 6, rnames, runits);
	if (!dr)
		return lz_lesson_error(&L);
	double rms[4][NLAT], maxsq[4];
	printf("  lattice noise of a raw g(r) on 1 < r/sigma < 3, rms |M - 1|:\n");
	printf("  %4s %10s %10s %10s %12s %10s\n", "R", "square", "triangular", "cubic",
	       "max square", "d2 bins");
	for (int i = 0; i < 4; i++) {
		int R = radii[i];
		maxsq[i] = 0.0;
		for (int l = 0; l < NLAT; l++) {
			double s = 0.0;
			for (int k = 2 * R; k < 6 * R; k++) {
				double m = (double)count[l][k] / exact_measure(l, k) - 1.0;
				s += m * m;
				if (l == 0 && fabs(m) > maxsq[i])
					maxsq[i] = fabs(m);
			}
			rms[i][l] = sqrt(s / (4.0 * R));
		}
		double bins = 36.0 * R * R;
		double row[6] = {R, rms[i][0], rms[i][1], rms[i][2], maxsq[i], bins};
		lz_data_row(dr, row);
		printf("  %4d %10.4f %10.4f %10.4f %12.4f %10.0f\n", R, rms[i][0], rms[i][1],
		       rms[i][2], maxsq[i], bins);
	}
	if (lz_data_close(dr) != LZ_OK)
		return lz_lesson_error(&L);
	int falls = rms[3][0] < rms[0][0] && rms[3][1] < rms[0][1] && rms[3][2] < rms[0][2];
	printf("  the noise falls as the particles grow in lattice units (R = 24 below R = 3 "
	       "on all three lattices): %s\n", lz_lesson_check(&L, falls));

	lz_json *j = lz_lesson_json(&L, "shells.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "square_shell_5", count[0][5]);
	lz_json_int(j, "square_shell_6", count[0][6]);
	for (int i = 0; i < 4; i++) {
		char key[64];
		snprintf(key, sizeof key, "rms_M_minus_1_square_R%d", radii[i]);
		lz_json_num(j, key, rms[i][0]);
	}
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "table 2.4 shell counts; lattice noise falls with R");
}
