/* fpsum.c — compensated and pairwise summation (graded). */
#include <stddef.h>

#include "lz/error.h"
#include "lz/fpsum.h"

/* LZ_HELPERS_BEGIN */
#include <math.h>
/* LZ_HELPERS_END */

/* Neumaier's compensated addition: after t = sum + x, the part of the smaller
 * operand that t could not hold is recovered exactly and kept in comp. */
void lz_kahan_add(lz_kahan *k, double x)
{
	/* Hint: t = sum + x rounds; (big - t) + small is exactly what was lost, big being
	 * the larger of sum and x in magnitude (Neumaier). Add it to comp, keep t in sum.
	 * Kahan's original assumes big = sum and fails on 1, 1e100, 1, -1e100.
	 * See lessons/01-lozenge/README.md §6. */
	/* LZ_SOLUTION_BEGIN */
	double t = k->sum + x;
	if (fabs(k->sum) >= fabs(x))
		k->comp += (k->sum - t) + x;
	else
		k->comp += (x - t) + k->sum;
	k->sum = t;
	/* LZ_SOLUTION_END */
}

/* Pairwise summation: the two halves summed recursively, short blocks naively. */
double lz_sum_pairwise(const double *x, size_t n)
{
	/* Hint: n <= 8: add left to right. Otherwise h = n / 2 and the sum of x[0..h) plus
	 * the sum of x[h..n), both pairwise. Try n = 0, 1, 9 and odd n: an off-by-one at
	 * the split drops or repeats a term. See lessons/01-lozenge/README.md §6. */
	/* LZ_SOLUTION_BEGIN */
	if (n <= 8) {
		double s = 0.0;
		for (size_t i = 0; i < n; i++)
			s += x[i];
		return s;
	}
	size_t h = n / 2;
	return lz_sum_pairwise(x, h) + lz_sum_pairwise(x + h, n - h);
	/* LZ_SOLUTION_END */
}
