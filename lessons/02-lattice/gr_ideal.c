/* gr_ideal — lesson 02, experiment 4 (§4, §5, §8): g(r) of an ideal gas on a lattice,
 * raw and corrected.
 *
 * N points are thrown independently and uniformly on the sites of a periodic box
 * (several may share a site: an ideal gas has no structure at all), on the square,
 * triangular (sheared) and simple cubic lattices, and their g(r) is accumulated in
 * distance² space with lz/gr.h up to half the box. The true g is exactly 1 in every
 * shell. The RAW g (pairs over the exact shell area) carries the lattice measure
 * M(k) instead; the CORRECTED g (pairs over the shell's lattice-point count) must be 1
 * within its statistical error in every shell.
 *
 * Error bars: for independent uniform points on a torus every pair distance is
 * independent of every other (translation invariance), so the count of shell k over
 * P pairs is binomial with p = count(k)/V, and the relative error of the corrected g
 * is sqrt((1 - p)/(P p)), computed from the expected count, never from the noise.
 *
 * On the triangular lattice the same pairs are also binned with the thesis's
 * approximation, the square table alone on the rhombus: identical to the exact
 * minimum image for pairs nearer than √3 L/4 ≈ 0.43 L, too long beyond, so the last
 * shells before L/2 lose pairs.
 *
 * Usage: gr_ideal OUTDIR [--quick]   (quick: 400 configurations; full: 4000)
 * Writes OUTDIR/gr_ideal.dat and gr_ideal.json.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/gr.h"
#include "lz/lattice.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"

#define SEED 20020u  /* fixed: the lesson quotes the numbers of this run */
#define NPART 256    /* points per configuration */
#define NLAT 3
#define NSIGMA 4.0   /* "within a few error bars": every shell within 4 sigma */

static const lz_lattice_kind lat_kind[NLAT] = {LZ_LATTICE_SQUARE, LZ_LATTICE_TRIANGULAR,
                                               LZ_LATTICE_CUBIC};
static const char *const lat_name[NLAT] = {"square", "triangular", "cubic"};
static const int lat_side[NLAT] = {64, 64, 32};  /* g(r) up to L/2: 32, 32, 16 shells */

/* The figures of one lattice. */
typedef struct {
	int nshells;
	double raw[64], corr[64], err[64], meas[64], table[64];
	double rms_raw, rms_corr, max_dev;  /* over shells 1 .. nshells-1; max |corr-1|/err */
	double raw0;                        /* raw g of shell 0: M(0) */
	double chi2;                        /* sum over all shells of ((corr-1)/err)² */
} result;

/* The thesis's minimum image on the rhombus: the square table per component, then
 * the triangular metric — no hexagon correction. */
static int64_t table_only_d2(const lz_lattice_box *b, int32_t dx, int32_t dy)
{
	int32_t x = b->dc[(uint32_t)dx & (uint32_t)b->mask];
	int32_t y = b->dc[(uint32_t)dy & (uint32_t)b->mask];
	return lz_lattice_dist2(LZ_LATTICE_TRIANGULAR, x, y, 0);
}

/* S configurations of NPART uniform points on lattice l; fills res. */
static int run_lattice(int l, int nconf, lz_rng *rng, result *res)
{
	lz_lattice_kind kind = lat_kind[l];
	int side = lat_side[l], dim = lz_lattice_dim(kind), nsh = side / 2;
	int status = LZ_ENOMEM;
	lz_lattice_box *b = lz_lattice_box_alloc(kind, side);
	lz_gr *g = lz_gr_alloc(kind, side, nsh, NPART);
	lz_gr *gt = kind == LZ_LATTICE_TRIANGULAR ? lz_gr_alloc(kind, side, nsh, NPART) : NULL;
	int32_t *r = malloc((size_t)NPART * (size_t)dim * sizeof *r);
	double *rawt = malloc((size_t)nsh * sizeof *rawt);
	if (!b || !g || (kind == LZ_LATTICE_TRIANGULAR && !gt) || !r || !rawt) {
		if (!r || !rawt)
			lz_error(LZ_ENOMEM, "no memory for %d points", NPART);
		goto out;
	}
	for (int s = 0; s < nconf; s++) {
		for (int i = 0; i < NPART * dim; i++)
			r[i] = (int32_t)gsl_rng_uniform_int(rng->gsl, (unsigned long)side);
		if ((status = lz_gr_add_config(g, b, r)) != LZ_OK)
			goto out;
		if (gt) {
			for (int i = 0; i + 1 < NPART; i++)
				for (int j = i + 1; j < NPART; j++)
					lz_gr_add_pair(gt, table_only_d2(b, r[2 * i] - r[2 * j],
					                                 r[2 * i + 1] - r[2 * j + 1]));
			lz_gr_end_sample(gt);
		}
	}
	if ((status = lz_gr_result(g, res->raw, res->corr)) != LZ_OK)
		goto out;
	if (gt && (status = lz_gr_result(gt, rawt, res->table)) != LZ_OK)
		goto out;

	double volume = pow((double)side, dim), cell = lz_lattice_cell_volume(kind);
	double npairs = (double)nconf * NPART * (NPART - 1) / 2.0;
	double s2raw = 0.0, s2corr = 0.0;
	res->nshells = nsh;
	res->max_dev = 0.0;
	res->chi2 = 0.0;
	for (int k = 0; k < nsh; k++) {
		double p = (double)g->lattice[k] / volume;
		res->err[k] = sqrt((1.0 - p) / (npairs * p));
		res->meas[k] = (double)g->lattice[k] * cell / lz_shell_volume(dim, k);
		if (!gt)
			res->table[k] = NAN;
		double dev = (res->corr[k] - 1.0) / res->err[k];
		res->chi2 += dev * dev;
		if (fabs(dev) > res->max_dev)
			res->max_dev = fabs(dev);
		if (k > 0) {
			s2raw += (res->raw[k] - 1.0) * (res->raw[k] - 1.0);
			s2corr += (res->corr[k] - 1.0) * (res->corr[k] - 1.0);
		}
	}
	res->rms_raw = sqrt(s2raw / (nsh - 1));
	res->rms_corr = sqrt(s2corr / (nsh - 1));
	res->raw0 = res->raw[0];
	status = LZ_OK;
out:
	free(rawt);
	free(r);
	lz_gr_free(gt);
	lz_gr_free(g);
	lz_lattice_box_free(b);
	return status;
}

int main(int argc, char **argv)
{
	static result res[NLAT];
	static const char *names[] = {"lattice", "k", "r", "r_over_L", "g_raw", "g_corrected",
	                              "g_err", "M", "g_table_only"};
	static const char *units[] = {"0 sq 1 tri 2 cub", "shell", "lattice", "", "", "", "",
	                              "", ""};
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	int nconf = L.quick ? 400 : 4000;
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	if (!rng)
		return lz_lesson_error(&L);
	printf("gr_ideal: %d configurations of %d uniform random points (an ideal gas), "
	       "g(r) up to L/2, mt19937 seed %u\n", nconf, NPART, SEED);
	for (int l = 0; l < NLAT; l++)
		if (run_lattice(l, nconf, rng, &res[l]) != LZ_OK) {
			lz_rng_free(rng);
			return lz_lesson_error(&L);
		}
	lz_rng_free(rng);

	printf("  %-11s %4s %7s %11s %12s %10s %12s %9s\n", "lattice", "L", "shells",
	       "raw g(0)", "rms raw-1", "rms corr-1", "max dev/err", "chi2/dof");
	for (int l = 0; l < NLAT; l++)
		printf("  %-11s %4d %7d %11.4f %12.4f %10.4f %12.2f %9.2f\n", lat_name[l],
		       lat_side[l], res[l].nshells, res[l].raw0, res[l].rms_raw, res[l].rms_corr,
		       res[l].max_dev, res[l].chi2 / res[l].nshells);
	printf("  (rms over shells 1 .. L/2 - 1; max dev = the largest |g_corr - 1| in error "
	       "bars, over all shells)\n");

	/* checks: the corrected g is 1 within its error everywhere, the raw g is not */
	for (int l = 0; l < NLAT; l++) {
		printf("  %s: corrected g within %.0f error bars of 1 in all %d shells: %s\n",
		       lat_name[l], NSIGMA, res[l].nshells,
		       lz_lesson_check(&L, res[l].max_dev < NSIGMA));
		double first = fabs(res[l].raw[1] - 1.0) / (res[l].meas[1] * res[l].err[1]);
		printf("  %s: raw g visibly off at small r (g_raw(0) = %.3f, g_raw(1) - 1 = %+.3f "
		       "= %.0f error bars; rms raw-1 %.1fx rms corr-1): %s\n", lat_name[l],
		       res[l].raw0, res[l].raw[1] - 1.0, first, res[l].rms_raw / res[l].rms_corr,
		       lz_lesson_check(&L, res[l].raw0 < 0.5 && first > 10.0 &&
		                       res[l].rms_raw > 2.0 * res[l].rms_corr));
	}
	/* the thesis's table-only image on the rhombus: exact below √3 L/4, short of pairs
	 * above */
	const result *t = &res[1];
	double inr = sqrt(3.0) / 4.0 * lat_side[1];
	int same = 1, kfirst = -1;
	double tail = 0.0;
	for (int k = 0; k < t->nshells; k++) {
		if (k + 1 <= inr)
			same = same && t->table[k] == t->corr[k];
		else if (kfirst < 0)
			kfirst = k;
	}
	double last = t->table[t->nshells - 1];
	for (int k = kfirst; k < t->nshells; k++)
		tail += t->table[k];
	tail /= t->nshells - kfirst;
	printf("  triangular, table alone (thesis): identical to the exact image in shells "
	       "0 .. %d (r < sqrt(3) L/4 = %.1f): %s\n", kfirst - 1, inr,
	       lz_lesson_check(&L, same));
	printf("  triangular, table alone: g of shells %d .. %d averages %.3f, last shell "
	       "%.3f (pairs given a too-long image): %s\n", kfirst, t->nshells - 1, tail, last,
	       lz_lesson_check(&L, last < 0.6 && tail < 0.9));

	lz_data *d = lz_lesson_data(&L, "gr_ideal.dat", "g(r) of an ideal gas on three "
	                            "lattices: raw (exact-area) and corrected (lattice-count) "
	                            "normalisation", 9, names, units);
	if (!d)
		return lz_lesson_error(&L);
	for (int l = 0; l < NLAT; l++)
		for (int k = 0; k < res[l].nshells; k++) {
			double row[9] = {l, k, k + 0.5, (k + 0.5) / lat_side[l], res[l].raw[k],
			                 res[l].corr[k], res[l].err[k], res[l].meas[k],
			                 res[l].table[k]};
			lz_data_row(d, row);
		}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	lz_json *j = lz_lesson_json(&L, "gr_ideal.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "configurations", nconf);
	lz_json_int(j, "points", NPART);
	for (int l = 0; l < NLAT; l++) {
		char key[64];
		snprintf(key, sizeof key, "rms_raw_minus_1_%s", lat_name[l]);
		lz_json_num(j, key, res[l].rms_raw);
		snprintf(key, sizeof key, "rms_corrected_minus_1_%s", lat_name[l]);
		lz_json_num(j, key, res[l].rms_corr);
		snprintf(key, sizeof key, "max_dev_sigma_%s", lat_name[l]);
		lz_json_num(j, key, res[l].max_dev);
	}
	lz_json_num(j, "table_only_last_shell_triangular", last);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "ideal-gas g(r): corrected within %.0f sigma of 1, raw "
	                        "off by the lattice measure", NSIGMA);
}
