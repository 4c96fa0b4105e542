/* lowbits — lesson 02, experiment 2 (§3): what is wrong with an LCG, and what is not.
 *
 * The thesis's generator x_{n+1} = (69069 x_n + 1) mod 2^32 (lz/lcg.h) against GSL's
 * mt19937, both from the same seed:
 *   - the sequence from seed 0, which the thesis prints;
 *   - the bits of the first 256 outputs as a picture (lowbits.dat), and the period of
 *     bit k, which must be exactly 2^(k+1) for the LCG;
 *   - successive pairs of the low byte (lowpairs.dat): for the LCG x_{n+1} mod 256 is
 *     a function of x_n mod 256, so only 256 of the 65536 possible pairs ever occur;
 *   - the [0,1) map at the largest integer, and how often a float map returns 1.0;
 *   - integers in [0, n): x % n against lz_lcg_below, for n = 6 (a die) and
 *     n = 3·2^30 (where x % n doubles the odds of the first third).
 *
 * Usage: lowbits OUTDIR [--quick]   (quick: 10^6 dice; full: 10^7)
 * Writes OUTDIR/lowbits.dat, lowpairs.dat and lowbits.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>

#include "lz/error.h"
#include "lz/lcg.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"

#define SEED 20000u       /* any seed: the patterns do not depend on it */
#define NPIC 256          /* outputs drawn in the bit picture */
#define KMAX 20           /* periods checked for bits 0 .. KMAX-1 */
#define NPAIR 4096        /* successive pairs of the low byte */

/* Period of bit k in b[0..n): the smallest power of two p <= n/2 with b[i+p] == b[i]
 * for all i, or 0 if there is none (the stream's period divides 2^32, so every
 * period of one of its bits is a power of two). */
static long bit_period(const uint32_t *x, long n, int k)
{
	for (long p = 1; p <= n / 2; p *= 2) {
		long i = 0;
		while (i + p < n && ((x[i] ^ x[i + p]) >> k & 1u) == 0)
			i++;
		if (i + p == n)
			return p;
	}
	return 0;
}

/* Number of distinct (x_n mod 256, x_{n+1} mod 256) among n pairs of x[0..n]. */
static int distinct_pairs(const uint32_t *x, int n)
{
	static unsigned char seen[65536];
	int count = 0;
	memset(seen, 0, sizeof seen);
	for (int i = 0; i < n; i++) {
		unsigned k = (x[i] & 255u) << 8 | (x[i + 1] & 255u);
		count += !seen[k];
		seen[k] = 1;
	}
	return count;
}

static int write_picture(lz_lesson *L, const uint32_t *lcg, const uint32_t *mt)
{
	static const char *names[] = {"n", "bit", "lcg", "mt19937"};
	static const char *units[] = {"draw", "", "", ""};
	lz_data *d = lz_lesson_data(L, "lowbits.dat", "bit k of the n-th output, 69069 LCG "
	                            "and mt19937", 4, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < 32; k++)
		for (int n = 0; n < NPIC; n++) {
			double row[4] = {n, k, (double)(lcg[n] >> k & 1u), (double)(mt[n] >> k & 1u)};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

static int write_pairs(lz_lesson *L, const uint32_t *lcg, const uint32_t *mt)
{
	static const char *names[] = {"lcg_x", "lcg_next", "mt_x", "mt_next"};
	lz_data *d = lz_lesson_data(L, "lowpairs.dat", "successive low bytes (x_n mod 256, "
	                            "x_n+1 mod 256)", 4, names, NULL);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < NPAIR; i++) {
		double row[4] = {lcg[i] & 255u, lcg[i + 1] & 255u, mt[i] & 255u, mt[i + 1] & 255u};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

/* The inverse of the odd number a modulo 2^32 (Newton: each step doubles the bits). */
static uint32_t inverse_mod_2_32(uint32_t a)
{
	uint32_t y = a;  /* right to 3 bits for odd a */
	for (int i = 0; i < 5; i++)
		y *= 2u - a * y;
	return y;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	long ndice = L.quick ? 1000000 : 10000000;
	long nstream = 1L << (KMAX + 1);
	printf("lowbits: LCG a = %u, c = %u, m = 2^32 against GSL mt19937, seed %u; bit "
	       "periods from %ld draws; %ld dice\n", (unsigned)LZ_LCG_A, (unsigned)LZ_LCG_C,
	       SEED, nstream, ndice);

	/* the thesis's table: seed 0 */
	static const uint32_t thesis[6] = {1u, 69070u, 475628535u, 3277404108u, 772999773u,
	                                   3877832058u};
	lz_lcg g;
	lz_lcg_seed(&g, 0);
	int same = 1;
	printf("  from seed 0:");
	for (int i = 0; i < 6; i++) {
		uint32_t x = lz_lcg_next(&g);
		printf(" %u", (unsigned)x);
		same = same && x == thesis[i];
	}
	printf("  (thesis 2.3.3): %s\n", lz_lesson_check(&L, same));

	uint32_t *lcg = malloc((size_t)nstream * sizeof *lcg);
	uint32_t *mt = malloc((size_t)nstream * sizeof *mt);
	lz_rng *r = lz_rng_alloc("mt19937", SEED);
	if (!lcg || !mt || !r) {
		lz_error(LZ_ENOMEM, "no memory for %ld draws", nstream);
		return lz_lesson_error(&L);
	}
	lz_lcg_seed(&g, SEED);
	for (long i = 0; i < nstream; i++) {
		lcg[i] = lz_lcg_next(&g);
		mt[i] = (uint32_t)gsl_rng_get(r->gsl);
	}

	/* periods of the low bits */
	int periods_ok = 1, mt_periodic = 0;
	printf("  period of bit k:");
	for (int k = 0; k < KMAX; k++) {
		long p = bit_period(lcg, nstream, k);
		periods_ok = periods_ok && p == 1L << (k + 1);
		mt_periodic += bit_period(mt, nstream, k) != 0;
		if (k < 8)
			printf(" %ld", p);
	}
	printf(" ... (2^(k+1) for k = 0..%d): %s\n", KMAX - 1, lz_lesson_check(&L, periods_ok));
	printf("  mt19937 bits with a period below %ld: %d of %d: %s\n", nstream / 2,
	       mt_periodic, KMAX, lz_lesson_check(&L, mt_periodic == 0));

	/* pairs of the low byte */
	int pl = distinct_pairs(lcg, NPAIR), pm = distinct_pairs(mt, NPAIR);
	double expect = 65536.0 * (1.0 - exp(-(double)NPAIR / 65536.0));
	printf("  distinct low-byte pairs in %d: LCG %d (exactly 256), mt19937 %d (random: "
	       "%.0f): %s\n", NPAIR, pl, pm, expect,
	       lz_lesson_check(&L, pl == 256 && fabs(pm - expect) < 5.0 * sqrt(expect)));

	/* the [0,1) map at its top end */
	uint32_t top = UINT32_MAX;
	lz_lcg_seed(&g, (top - LZ_LCG_C) * inverse_mod_2_32(LZ_LCG_A));  /* next is 2^32-1 */
	double u = lz_lcg_uniform(&g);
	long ones = 0;
	for (uint64_t x = (UINT64_C(1) << 32) - 4096; x < UINT64_C(1) << 32; x++) {
		volatile float f = (float)(uint32_t)x * 0x1p-32f;
		ones += f == 1.0f;
	}
	printf("  lz_lcg_uniform at x = 2^32 - 1: 1 - %.3g (< 1): %s\n", 1.0 - u,
	       lz_lesson_check(&L, u < 1.0 && u == 1.0 - 0x1p-32));
	printf("  a float map x * 2^-32f gives 1.0f for %ld of the 2^32 integers: once in "
	       "%.0f draws: %s\n", ones, 4294967296.0 / (double)ones,
	       lz_lesson_check(&L, ones == 128));

	/* integers in [0, n) */
	long hist_mod[6] = {0}, hist_below[6] = {0}, same_parity_mod = 0, same_parity_below = 0;
	uint32_t prev_mod = 0, prev_below = 0;
	lz_lcg gm, gb;
	lz_lcg_seed(&gm, SEED);
	lz_lcg_seed(&gb, SEED);
	for (long i = 0; i < ndice; i++) {
		uint32_t a = lz_lcg_next(&gm) % 6u, b = lz_lcg_below(&gb, 6);
		hist_mod[a]++;
		hist_below[b]++;
		if (i > 0) {
			same_parity_mod += (a & 1u) == (prev_mod & 1u);
			same_parity_below += (b & 1u) == (prev_below & 1u);
		}
		prev_mod = a;
		prev_below = b;
	}
	double chi2 = 0.0, e = (double)ndice / 6.0;
	for (int k = 0; k < 6; k++)
		chi2 += (hist_below[k] - e) * (hist_below[k] - e) / e;
	double pval = gsl_cdf_chisq_Q(chi2, 5.0);
	double fmod = (double)same_parity_mod / (double)(ndice - 1);
	double fbelow = (double)same_parity_below / (double)(ndice - 1);
	printf("  dice: two successive rolls of equal parity: x %% 6 %.4f, lz_lcg_below "
	       "%.4f (random: 0.5): %s\n", fmod, fbelow,
	       lz_lesson_check(&L, fmod == 0.0 && fabs(fbelow - 0.5) < 0.005));
	printf("  lz_lcg_below(6) faces:");
	for (int k = 0; k < 6; k++)
		printf(" %ld", hist_below[k]);
	printf(", chi2 = %.2f (5 dof), p = %.3f: %s\n", chi2, pval,
	       lz_lesson_check(&L, pval > 1e-4));
	uint32_t big = 3u << 30;
	long first_mod = 0, first_below = 0, nbig = ndice;
	lz_lcg_seed(&gm, SEED);
	lz_lcg_seed(&gb, SEED);
	for (long i = 0; i < nbig; i++) {
		first_mod += lz_lcg_next(&gm) % big < (1u << 30);
		first_below += lz_lcg_below(&gb, big) < (1u << 30);
	}
	double tmod = (double)first_mod / (double)nbig, tbelow = (double)first_below / (double)nbig;
	printf("  n = 3*2^30: fraction in the first third: x %% n %.4f (biased: 1/2), "
	       "lz_lcg_below %.4f (1/3): %s\n", tmod, tbelow,
	       lz_lesson_check(&L, fabs(tmod - 0.5) < 0.005 && fabs(tbelow - 1.0 / 3.0) < 0.005));

	int status = write_picture(&L, lcg, mt);
	if (status == LZ_OK)
		status = write_pairs(&L, lcg, mt);
	free(lcg);
	free(mt);
	lz_rng_free(r);
	if (status != LZ_OK)
		return lz_lesson_error(&L);
	lz_json *j = lz_lesson_json(&L, "lowbits.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "lcg_distinct_lowbyte_pairs", pl);
	lz_json_int(j, "mt_distinct_lowbyte_pairs", pm);
	lz_json_int(j, "float_map_ones_per_2_32", ones);
	lz_json_num(j, "dice_same_parity_mod", fmod);
	lz_json_num(j, "dice_same_parity_below", fbelow);
	lz_json_num(j, "first_third_mod", tmod);
	lz_json_num(j, "first_third_below", tbelow);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "LCG sequence and bit periods 2^(k+1), 256 low-byte pairs, "
	                        "float map hits 1.0 once in 2^25, unbiased integers");
}
