/* summation — lesson 01, experiment 7 (§6): the order of a sum matters.
 *
 * Σ_{k=1}^{n} 1/k² (→ π²/6) is summed four ways: naively from the largest term
 * (the small terms meet a large partial sum and lose their low bits), naively from
 * the smallest (terms of like magnitude meet), pairwise (lz_sum_pairwise) and
 * compensated (lz_sum_kahan, through lz_kahan_add), the last two in the bad,
 * largest-first order. The reference is the smallest-first sum in long double.
 * It also prints the classic surprises: 0.1 is not a binary fraction, addition is
 * not associative, and times the three sums per term.
 *
 * Usage: summation OUTDIR [--quick]   (quick: n <= 1e6; full: n <= 1e7)
 * Writes OUTDIR/summation.dat and summation.json. Exit 1 if a check fails.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/fpsum.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/timer.h"

#define NMETHODS 4
#define MIN_CPU 0.05

static const char *const method_name[NMETHODS] = {"largest_first", "smallest_first",
                                                  "pairwise", "kahan"};

/* The terms twice: fwd[i] = 1/(i+1)² (largest first) and rev, its mirror image, so
 * that the n smallest-first terms of a sum of n are rev + nmax - n. */
typedef struct {
	size_t nmax;
	double *fwd, *rev;
} terms;

static double sum_with(const terms *t, int m, size_t n)
{
	switch (m) {
	case 0: return lz_sum_naive(t->fwd, n);
	case 1: return lz_sum_naive(t->rev + t->nmax - n, n);
	case 2: return lz_sum_pairwise(t->fwd, n);
	default: return lz_sum_kahan(t->fwd, n);
	}
}

/* Σ 1/k² smallest first in extended precision: the reference. */
static long double reference(size_t n)
{
	long double s = 0.0L;
	for (size_t k = n; k >= 1; k--)
		s += 1.0L / ((long double)k * (long double)k);
	return s;
}

/* CPU nanoseconds per term of method m over all nmax terms. */
static double ns_per_term(const terms *t, int m)
{
	volatile double sink = 0.0;  /* keeps the sums from being optimised away */
	double t0 = lz_cpu_now(), used;
	long reps = 0;
	do {
		sink += sum_with(t, m, t->nmax);
		reps++;
		used = lz_cpu_now() - t0;
	} while (used < MIN_CPU);
	(void)sink;
	return 1e9 * used / ((double)reps * (double)t->nmax);
}

/* The surprises of §6, printed; returns the compensated value of the adversarial
 * sum 1 + 1e100 + 1 - 1e100 (exactly 2 when lz_kahan_add is right). */
static double surprises(double *naive_adv)
{
	static const double adv[4] = {1.0, 1e100, 1.0, -1e100};
	volatile float five_thousandths = 0.005f, two_one = 2.1f;  /* as the thesis did */
	printf("  0.1 is stored as %.20f\n", 0.1);
	printf("  0.1 + 0.2 = %.17g, 0.3 = %.17g: equal? %s\n", 0.1 + 0.2, 0.3,
	       0.1 + 0.2 == 0.3 ? "yes" : "no");
	printf("  (1e16 + 1) - 1e16 = %g but (1e16 - 1e16) + 1 = %g\n",
	       (1e16 + 1.0) - 1e16, (1e16 - 1e16) + 1.0);
	printf("  single precision: 0.005f prints as %.8g, 2.1f * 2.1f as %.8g\n",
	       (double)five_thousandths, (double)(two_one * two_one));
	*naive_adv = lz_sum_naive(adv, 4);
	double comp = lz_sum_kahan(adv, 4);
	printf("  1 + 1e100 + 1 - 1e100: naive %g, pairwise %g, compensated %g (exact: 2)\n",
	       *naive_adv, lz_sum_pairwise(adv, 4), comp);
	return comp;
}

static int terms_init(terms *t, size_t nmax)
{
	t->nmax = nmax;
	t->fwd = malloc(nmax * sizeof *t->fwd);
	t->rev = malloc(nmax * sizeof *t->rev);
	if (!t->fwd || !t->rev)
		return lz_error(LZ_ENOMEM, "no memory for %zu terms", nmax);
	for (size_t i = 0; i < nmax; i++) {
		double k = (double)(i + 1);
		t->fwd[i] = 1.0 / (k * k);
		t->rev[nmax - 1 - i] = t->fwd[i];
	}
	return LZ_OK;
}

/* Relative errors of the four sums at n = 10^(1 + k/4) into summation.dat; the
 * errors at nmax into last[]. */
static int write_errors(lz_lesson *L, const terms *t, double *last)
{
	static const char *names[] = {"n", "largest_first", "smallest_first", "pairwise", "kahan"};
	static const char *units[] = {"terms", "rel", "rel", "rel", "rel"};
	lz_data *d = lz_lesson_data(L, "summation.dat", "sum of 1/k^2, k = 1..n: relative "
	                            "error against a long-double reference", 5, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0;; k++) {
		size_t n = (size_t)llround(pow(10.0, 1.0 + k / 4.0));
		if (n > t->nmax)
			break;
		long double ref = reference(n);
		double row[1 + NMETHODS] = {(double)n};
		for (int m = 0; m < NMETHODS; m++)
			row[1 + m] = (double)(fabsl((long double)sum_with(t, m, n) - ref) / ref);
		lz_data_row(d, row);
		memcpy(last, row + 1, sizeof row - sizeof row[0]);
	}
	return lz_data_close(d);
}

static int write_json(lz_lesson *L, const double *last, const double *ns, double adv,
                      double naive_adv)
{
	char key[64];
	lz_json *j = lz_lesson_json(L, "summation.json");
	if (!j)
		return LZ_EIO;
	for (int m = 0; m < NMETHODS; m++) {
		snprintf(key, sizeof key, "rel_error_%s", method_name[m]);
		lz_json_num(j, key, last[m]);
	}
	for (int m = 0; m < NMETHODS; m++) {
		snprintf(key, sizeof key, "ns_per_term_%s", method_name[m]);
		lz_json_num(j, key, round(ns[m] * 100.0) / 100.0);
	}
	lz_json_num(j, "naive_1+1e100+1-1e100", naive_adv);
	lz_json_num(j, "kahan_1+1e100+1-1e100", adv);
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	terms t = {0};
	double last[NMETHODS], ns[NMETHODS], naive_adv;
	size_t nmax = L.quick ? 1000000 : 10000000;
	printf("summation: sum of 1/k^2 for n = 10 ... %zu; reference in long double "
	       "(%d-bit mantissa)\n", nmax, LDBL_MANT_DIG);
	double adv = surprises(&naive_adv);
	if (terms_init(&t, nmax) != LZ_OK || write_errors(&L, &t, last) != LZ_OK)
		return lz_lesson_error(&L);
	lz_lesson_check(&L, adv == 2.0);  /* its line is printed by surprises() */
	printf("  %-15s %12s %12s\n", "method", "rel error", "ns/term");
	for (int m = 0; m < NMETHODS; m++) {
		ns[m] = ns_per_term(&t, m);
		int good = m == 0 ? last[0] > 10.0 * last[1] : last[m] < 1e-15;
		printf("  %-15s %12.2e %12.2f  %s\n", method_name[m], last[m], ns[m],
		       lz_lesson_check(&L, good));
	}
	free(t.fwd);
	free(t.rev);
	if (write_json(&L, last, ns, adv, naive_adv) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "compensated 1+1e100+1-1e100 = 2, pairwise and Kahan "
	                        "near epsilon");
}
