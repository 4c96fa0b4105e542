/* lozenge.c — the exact truncation order of a finite-difference formula (graded). */
#include "lz/error.h"
#include "lz/lozenge.h"

/* LZ_HELPERS_BEGIN */
/* The samples of a formula as one list: the terms, then the target with weight -1,
 * so that the error Σ terms - target is a plain sum over samples. */
typedef struct {
	int col, half;
	lz_ratio w;    /* weight times 2^(col - target col): dt^k = (2u)^k, u = dt/2 */
	lz_ratio cur;  /* half^j / j! for j = D - col, the Taylor coefficient in u */
} sample;

static int formula_ok(const lz_formula *f, int max_deriv)
{
	if (!f || f->nterms < 1 || f->nterms > LZ_TERMS_MAX)
		return lz_error(LZ_EINVAL, "a formula needs 1..%d terms, not %d", LZ_TERMS_MAX,
		                f ? f->nterms : 0);
	if (max_deriv < 0 || max_deriv > 20)
		return lz_error(LZ_EINVAL, "max_deriv = %d must be in 0..20 (exact factorials)",
		                max_deriv);
	if ((unsigned)f->col >= LZ_NCOLS)
		return lz_error(LZ_EINVAL, "the target's column %d is not r, v, a or b (0..3)",
		                (int)f->col);
	for (int i = 0; i < f->nterms; i++) {
		if ((unsigned)f->term[i].col >= LZ_NCOLS)
			return lz_error(LZ_EINVAL, "term %d: column %d is not r, v, a or b (0..3)", i,
			                (int)f->term[i].col);
		if (f->term[i].w.den <= 0)
			return lz_error(LZ_EINVAL, "term %d: weight %lld/%lld needs a denominator > 0",
			                i, f->term[i].w.num, f->term[i].w.den);
	}
	return LZ_OK;
}

/* r · 2^e for |e| <= 20. */
static lz_ratio times_pow2(lz_ratio r, int e)
{
	long long p = 1LL << (e < 0 ? -e : e);
	return lz_ratio_mul(r, e < 0 ? lz_ratio_make(1, p) : lz_ratio_make(p, 1));
}

static int load_samples(const lz_formula *f, sample *s)
{
	int kt = (int)f->col;
	for (int i = 0; i < f->nterms; i++)
		s[i] = (sample){(int)f->term[i].col, f->term[i].half,
		                times_pow2(f->term[i].w, (int)f->term[i].col - kt), {0, 1}};
	s[f->nterms] = (sample){kt, f->half, lz_ratio_make(-1, 1), {0, 1}};
	return f->nterms + 1;
}

/* The coefficient of u^(D - kt) x^(D) in Σ terms - target; every sample's cur is
 * advanced from j - 1 to j = D - col on the way (cur = h^j / j!, built by one
 * multiplication per derivative). */
static lz_ratio coefficient(sample *s, int ns, int d)
{
	lz_ratio c = lz_ratio_make(0, 1);
	for (int i = 0; i < ns; i++) {
		int j = d - s[i].col;
		if (j < 0)
			continue;
		s[i].cur = j == 0 ? lz_ratio_make(1, 1)
		                  : lz_ratio_mul(s[i].cur, lz_ratio_make(s[i].half, j));
		c = lz_ratio_add(c, lz_ratio_mul(s[i].w, s[i].cur));
	}
	return c;
}
/* LZ_HELPERS_END */

/* The order p, the exact leading coefficient c and the derivative of the local
 * truncation error Σ terms - target = c dt^p x^(k_T+p) + O(dt^(p+1)). */
int lz_formula_order(const lz_formula *f, int max_deriv, int *order,
                     lz_ratio *leading, int *deriv)
{
	/* Hint: expand each sample, q_k(t + h dt/2) = Σ_j (h dt/2)^j / j! x^(k+j)(t), times
	 * its weight's dt^(k - k_T); for D = 0, 1, ..., max_deriv add up the coefficients of
	 * x^(D) exactly (lz_ratio_*), minus the target's. The first non-zero one gives
	 * p = D - k_T. See lessons/01-lozenge/README.md §4. */
	/* LZ_SOLUTION_BEGIN */
	int status = formula_ok(f, max_deriv);
	if (status != LZ_OK)
		return status;
	sample s[LZ_TERMS_MAX + 1];
	int ns = load_samples(f, s);
	int kt = (int)f->col;
	for (int d = 0; d <= max_deriv; d++) {
		lz_ratio c = coefficient(s, ns, d);
		if (!lz_ratio_ok(c))
			return lz_error(LZ_EDOM, "the Taylor coefficient of derivative %d overflows "
			                "64-bit rationals (weights or time offsets too large); lower "
			                "max_deriv", d);
		if (lz_ratio_is_zero(c))
			continue;
		/* Back from powers of u = dt/2 to powers of dt. */
		lz_ratio lead = times_pow2(c, kt - d);
		if (!lz_ratio_ok(lead))
			return lz_error(LZ_EDOM, "the leading coefficient at derivative %d overflows "
			                "64-bit rationals", d);
		*order = d - kt;
		*leading = lead;
		*deriv = d;
		return LZ_OK;
	}
	return lz_error(LZ_EDOM, "the formula is exact up to derivative %d: every Taylor "
	                "coefficient vanishes, so its order is above what was examined",
	                max_deriv);
	/* LZ_SOLUTION_END */
}
