/* lz/lozenge.h — finite-difference schemes as stencils, their exact truncation
 * order, and the lozenge diagram that draws them.
 *
 * A scheme relates samples of the trajectory x(t) and its derivatives at times
 * t + h·dt/2 (h whole: h even is a whole step, h odd a half step). Column k of the
 * lozenge diagram holds the k-th derivative: r (k=0), v (1), a (2), b = da/dt (3).
 * A formula computes one target sample from terms:
 *
 *     q_T(t + h_T dt/2) = Σ_i  w_i · dt^(k_i - k_T) · q_i(t + h_i dt/2)
 *
 * Verlet:    r(+2) = 2 r(0) - 1 r(-2) + 1 a(0)        (a enters with dt²)
 * Velocity:  v(0)  = 1/2 r(+2) - 1/2 r(-2)            (1/dt implied)
 *
 * Weights are exact rationals, so the truncation order is computed exactly:
 * substitute the Taylor series of every sample about t and collect the powers of dt.
 */
#ifndef LZ_LOZENGE_H
#define LZ_LOZENGE_H

#include <stdio.h>

typedef enum { LZ_COL_R = 0, LZ_COL_V = 1, LZ_COL_A = 2, LZ_COL_B = 3, LZ_NCOLS = 4 } lz_column;

/* An exact rational num/den, den > 0, reduced (lowest terms). */
typedef struct {
	long long num, den;
} lz_ratio;

#define LZ_TERMS_MAX 8
typedef struct {
	lz_column col;  /* which derivative */
	int half;       /* time offset in half steps */
	lz_ratio w;     /* weight */
} lz_term;

typedef struct {
	lz_column col;  /* the target sample */
	int half;
	int nterms;     /* 1..LZ_TERMS_MAX */
	lz_term term[LZ_TERMS_MAX];
} lz_formula;

#define LZ_FORMULAS_MAX 4
typedef struct {
	const char *name;
	const char *title;  /* for the diagram, e.g. "velocity Verlet" */
	int nformulas;
	lz_formula f[LZ_FORMULAS_MAX];
} lz_scheme;

/* ---- exact rational arithmetic (lib/01-lozenge/lozenge_lib.c) ---- */
/* num/den reduced, sign on num. LZ_EINVAL-free: den == 0 gives {0, 0}, which every
 * function treats as invalid (lz_ratio_ok). Overflow beyond 2^62 is reported the same
 * way. */
lz_ratio lz_ratio_make(long long num, long long den);
lz_ratio lz_ratio_add(lz_ratio a, lz_ratio b);
lz_ratio lz_ratio_sub(lz_ratio a, lz_ratio b);
lz_ratio lz_ratio_mul(lz_ratio a, lz_ratio b);
int lz_ratio_ok(lz_ratio a);     /* den > 0 */
int lz_ratio_is_zero(lz_ratio a);
/* "3", "-1/12" into buf. */
const char *lz_ratio_str(lz_ratio a, char *buf, size_t size);

/* ---- graded (solutions/01-lozenge/lozenge.c) ---- */

/* The local truncation error of formula f. Expanding every sample about t,
 *     Σ_i terms - q_T(t + h_T dt/2) = c · dt^p · x^(k_T + p)(t) + O(dt^(p+1)),
 * the error of the target itself. Writes p to *order, c (exact, non-zero) to
 * *leading and the derivative k_T + p to *deriv. Examines derivatives up to
 * max_deriv (0..20, so that factorials stay exact); when every coefficient up to
 * there vanishes, returns LZ_EDOM — and also when a coefficient does not fit the
 * 64-bit rationals (huge weights or time offsets). LZ_EINVAL on a malformed formula
 * (nterms out of 1..LZ_TERMS_MAX, a column out of range, a weight with den <= 0) or
 * max_deriv out of 0..20.
 * p <= 0 means the formula is not even consistent. Cost O(nterms · max_deriv). */
int lz_formula_order(const lz_formula *f, int max_deriv, int *order,
                     lz_ratio *leading, int *deriv);

/* ---- known schemes and the diagram (lib/01-lozenge/lozenge_lib.c) ---- */

/* "verlet", "velocity" (the central-difference velocity), "leapfrog",
 * "velocity-verlet", "euler", "symplectic-euler"; NULL if unknown. */
const lz_scheme *lz_scheme_find(const char *name);
/* All of them; *n gets their number. */
const lz_scheme *lz_schemes(int *n);

/* Write a gnuplot script that draws the lozenge diagram of the schemes side by side
 * (the skeleton of columns r v a b with time running down and the v, b columns
 * shifted by half a step; used samples filled, the target marked, an arrow from
 * every term to its target labelled with its weight) into `png` (pngcairo).
 * nschemes in 1..6. */
int lz_lozenge_gnuplot(FILE *out, const lz_scheme *const *schemes, int nschemes,
                       const char *png);

#endif
