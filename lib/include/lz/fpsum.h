/* lz/fpsum.h — summing floating-point numbers without losing the small ones.
 *
 * Floating-point addition is not associative: adding a small term to a large sum
 * rounds away its low bits. Naive left-to-right summation of n terms has an error
 * bound that grows like n·ε·Σ|x|; pairwise summation like log2(n)·ε·Σ|x|;
 * compensated summation keeps a second double with the lost low-order part and
 * reaches ≈ 2ε·|Σx| + O(nε²)·Σ|x| — nearly the correctly rounded sum.
 */
#ifndef LZ_FPSUM_H
#define LZ_FPSUM_H

#include <stddef.h>

/* A running compensated sum. Invariant: the exact total of everything added is
 * (sum + comp) up to O(ε²) per addition; sum alone is what naive addition would
 * hold if it had never rounded badly. Start it zeroed: lz_kahan k = {0}. */
typedef struct {
	double sum;   /* the running total */
	double comp;  /* the low-order part that `sum` could not hold */
} lz_kahan;

/* The accumulated total, sum + comp. */
static inline double lz_kahan_value(const lz_kahan *k) { return k->sum + k->comp; }

/* Left to right, one rounding per term. O(n). */
double lz_sum_naive(const double *x, size_t n);
/* Compensated, through lz_kahan_add. O(n). */
double lz_sum_kahan(const double *x, size_t n);

/* ---- graded (solutions/01-lozenge/fpsum.c) ---- */

/* Add x to k, keeping the rounding error of the addition in k->comp. Must be exact
 * also when |x| > |k->sum| (Neumaier's form of Kahan's algorithm): after adding
 * 1, 1e100, 1, -1e100 the value is exactly 2. O(1). */
void lz_kahan_add(lz_kahan *k, double x);

/* Pairwise (cascade) summation: the sum of x[0..n) as the sum of its two halves,
 * recursively, with blocks of at most 8 terms summed naively. n = 0 gives 0.
 * Error O(ε log n); O(n) time, O(log n) stack. */
double lz_sum_pairwise(const double *x, size_t n);

#endif
