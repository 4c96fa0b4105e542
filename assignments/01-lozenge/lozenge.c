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

/* lozenge.c — the exact truncation order of a finite-difference formula (graded). */
#include "lz/error.h"
#include "lz/lozenge.h"


/* The order p, the exact leading coefficient c and the derivative of the local
 * truncation error Σ terms - target = c dt^p x^(k_T+p) + O(dt^(p+1)). */
int lz_formula_order(const lz_formula *f, int max_deriv, int *order,
                     lz_ratio *leading, int *deriv)
{
	/* Hint: expand each sample, q_k(t + h dt/2) = Σ_j (h dt/2)^j / j! x^(k+j)(t), times
	 * its weight's dt^(k - k_T); for D = 0, 1, ..., max_deriv add up the coefficients of
	 * x^(D) exactly (lz_ratio_*), minus the target's. The first non-zero one gives
	 * p = D - k_T. See lessons/01-lozenge/README.md §4. */
	LZ_TODO();
}
