/* lozenge_expect.h — a formula held to its hand-derived truncation error, shared by
 * the visible and the hidden stencil tests (static inline: each uses what it needs). */
#ifndef LOZENGE_EXPECT_H
#define LOZENGE_EXPECT_H

#include "lztest.h"
#include "lz/lozenge.h"

#define T(c, h, n, d) {LZ_COL_##c, (h), {(n), (d)}}

/* f with every sample moved by `by` half steps. */
static inline lz_formula shifted(lz_formula f, int by)
{
	f.half += by;
	for (int i = 0; i < f.nterms; i++)
		f.term[i].half += by;
	return f;
}

/* One call of lz_formula_order, held to the hand-derived result. */
static inline void expect_once(const char *what, const char *how, const lz_formula *f, int max_deriv,
                        int order, long long num, long long den, int deriv)
{
	int p = -99, d = -99;
	lz_ratio c = {0, 0};
	int status = lz_formula_order(f, max_deriv, &p, &c, &d);
	char got[64];
	ck_assert_msg(status == LZ_OK, "%s%s, examined up to derivative %d: lz_formula_order "
	              "returned status %d (%s); the formula is valid and its error appears at "
	              "x^(%d)", what, how, max_deriv, status, lz_error_message(), deriv);
	ck_assert_msg(p == order && c.num == num && c.den == den && d == deriv,
	              "%s%s: got error %s dt^%d x^(%d), expected %lld/%lld dt^%d x^(%d) — "
	              "expand each sample q(t + h dt/2) in powers of dt (note the /2 per half "
	              "step and the dt^(k_i - k_T) of each weight) and subtract the target",
	              what, how, lz_ratio_str(c, got, sizeof got), p, d, num, den, order, deriv);
}

/* Checks one formula against a hand-derived order, leading coefficient and
 * derivative; `what` names it in the message. Examined exactly up to that derivative
 * the error is found there, and one derivative less every coefficient vanishes
 * (LZ_EDOM): the edges of max_deriv. The leading term of the error cannot depend on
 * where t is, so the same formula moved by a half step back and a whole step on
 * must give the same answer. */
static inline void expect_order(const char *what, lz_formula f, int order, long long num,
                         long long den, int deriv)
{
	expect_once(what, "", &f, 12, order, num, den, deriv);
	expect_once(what, " (examined exactly up to its error's derivative)", &f, deriv, order,
	            num, den, deriv);
	if (deriv > 0) {
		int p, d;
		lz_ratio c;
		int status = lz_formula_order(&f, deriv - 1, &p, &c, &d);
		ck_assert_msg(status == LZ_EDOM, "%s, examined up to derivative %d: every coefficient "
		              "there vanishes (the error sits at x^(%d)), so LZ_EDOM (%d) is due, got "
		              "%d (order %d) — does the loop stop at max_deriv?", what, deriv - 1, deriv,
		              LZ_EDOM, status, status == LZ_OK ? p : 0);
	}
	lz_formula back = shifted(f, -1), on = shifted(f, 2);
	expect_once(what, " moved back by dt/2 (every offset h - 1)", &back, 12, order, num, den,
	            deriv);
	expect_once(what, " moved on by dt (every offset h + 2)", &on, 12, order, num, den, deriv);
}

#endif
