/* YOUR FILE — this is the file you fill in for stage 01-lozenge.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/01-lozenge/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=01`; see your own code at work with
 * `make lesson STAGE=01`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* fpsum.c — compensated and pairwise summation (graded). */
#include <stddef.h>

#include "lz/error.h"
#include "lz/fpsum.h"


/* Neumaier's compensated addition: after t = sum + x, the part of the smaller
 * operand that t could not hold is recovered exactly and kept in comp. */
void lz_kahan_add(lz_kahan *k, double x)
{
	/* Hint: t = sum + x rounds; (big - t) + small is exactly what was lost, big being
	 * the larger of sum and x in magnitude (Neumaier). Add it to comp, keep t in sum.
	 * Kahan's original assumes big = sum and fails on 1, 1e100, 1, -1e100.
	 * See lessons/01-lozenge/README.md §6. */
	LZ_TODO();
}

/* Pairwise summation: the two halves summed recursively, short blocks naively. */
double lz_sum_pairwise(const double *x, size_t n)
{
	/* Hint: n <= 8: add left to right. Otherwise h = n / 2 and the sum of x[0..h) plus
	 * the sum of x[h..n), both pairwise. Try n = 0, 1, 9 and odd n: an off-by-one at
	 * the split drops or repeats a term. See lessons/01-lozenge/README.md §6. */
	LZ_TODO();
}
