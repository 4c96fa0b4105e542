/* test_lozenge.c — truncation orders of known stencils. Every expected value below
 * was derived by hand from the Taylor series (the derivation is in the comment), so
 * a test never trusts the code it grades. */
#include "lozenge_expect.h"

LZ_TEST(lozenge_verlet_order)
{
	/* r(t+dt) + r(t-dt) = 2r + dt² a + dt⁴/12 x⁗ + ...: so
	 * 2r - r(t-dt) + dt² a - r(t+dt) = -dt⁴/12 x⁗. */
	expect_order("Verlet r(+dt) = 2r(0) - r(-dt) + dt² a(0)",
	             (lz_formula){LZ_COL_R, 2, 3, {T(R, 0, 2, 1), T(R, -2, -1, 1), T(A, 0, 1, 1)}},
	             4, -1, 12, 4);
}
END_TEST

LZ_TEST(lozenge_central_velocity_order)
{
	/* (r(t+dt) - r(t-dt)) / (2dt) = v + dt²/6 x‴ + ... */
	expect_order("central velocity v(0) = (r(+dt) - r(-dt))/(2dt)",
	             (lz_formula){LZ_COL_V, 0, 2, {T(R, 2, 1, 2), T(R, -2, -1, 2)}}, 2, 1, 6, 3);
}
END_TEST

LZ_TEST(lozenge_euler_orders)
{
	/* r + dt v - r(t+dt) = -dt²/2 a;  v + dt a - v(t+dt) = -dt²/2 x‴. */
	expect_order("Euler position r(+dt) = r(0) + dt v(0)",
	             (lz_formula){LZ_COL_R, 2, 2, {T(R, 0, 1, 1), T(V, 0, 1, 1)}}, 2, -1, 2, 2);
	expect_order("Euler velocity v(+dt) = v(0) + dt a(0)",
	             (lz_formula){LZ_COL_V, 2, 2, {T(V, 0, 1, 1), T(A, 0, 1, 1)}}, 2, -1, 2, 3);
}
END_TEST

LZ_TEST(lozenge_leapfrog_orders)
{
	/* Half steps: v(t ± dt/2) = v ± dt/2 a + dt²/8 x‴ ± dt³/48 x⁗, so
	 * v(-dt/2) + dt a - v(+dt/2) = -dt³/24 x⁗ (order 3 in the half-step column);
	 * r + dt v(t+dt/2) - r(t+dt) = dt³ (1/8 - 1/6) x‴ = -dt³/24 x‴ (midpoint rule). */
	expect_order("leapfrog velocity v(+dt/2) = v(-dt/2) + dt a(0)",
	             (lz_formula){LZ_COL_V, 1, 2, {T(V, -1, 1, 1), T(A, 0, 1, 1)}}, 3, -1, 24, 4);
	expect_order("leapfrog position r(+dt) = r(0) + dt v(+dt/2)",
	             (lz_formula){LZ_COL_R, 2, 2, {T(R, 0, 1, 1), T(V, 1, 1, 1)}}, 3, -1, 24, 3);
}
END_TEST

LZ_TEST(lozenge_velocity_verlet_orders)
{
	/* r + dt v + dt²/2 a - r(t+dt) = -dt³/6 x‴ (the b term is missing);
	 * v + dt/2 a + dt/2 a(t+dt) - v(t+dt) = dt³ (1/4 - 1/6) x⁗ = dt³/12 x⁗ (trapezoid). */
	expect_order("velocity Verlet position r(+dt) = r + dt v + dt²/2 a",
	             (lz_formula){LZ_COL_R, 2, 3, {T(R, 0, 1, 1), T(V, 0, 1, 1), T(A, 0, 1, 2)}},
	             3, -1, 6, 3);
	expect_order("velocity Verlet velocity v(+dt) = v + dt/2 (a(0) + a(+dt))",
	             (lz_formula){LZ_COL_V, 2, 3, {T(V, 0, 1, 1), T(A, 0, 1, 2), T(A, 2, 1, 2)}},
	             3, 1, 12, 4);
}
END_TEST

LZ_TEST(lozenge_five_point_stencil)
{
	/* (-r(+2dt) + 16 r(+dt) - 30 r + 16 r(-dt) - r(-2dt)) / (12 dt²): the even moments
	 * Σ w j^D / D! are 0, 1, 0, -1/90 for D = 0, 2, 4, 6, so the error is
	 * -dt⁴/90 x^(6): a fourth-order second derivative. */
	expect_order("5-point a(0) = (-r(+2) + 16 r(+1) - 30 r(0) + 16 r(-1) - r(-2))/(12 dt²)",
	             (lz_formula){LZ_COL_A, 0, 5, {T(R, 4, -1, 12), T(R, 2, 16, 12),
	                                           T(R, 0, -30, 12), T(R, -2, 16, 12),
	                                           T(R, -4, -1, 12)}},
	             4, -1, 90, 6);
}
END_TEST

LZ_TEST(lozenge_inconsistent_formulas)
{
	/* r(+dt) = 2 r(0): off by r itself, order 0. v(0) = r(+dt) (no 1/dt difference):
	 * r(t+dt)/dt - v = x/dt + ..., order -1. Neither converges. */
	expect_order("r(+dt) = 2 r(0)", (lz_formula){LZ_COL_R, 2, 1, {T(R, 0, 2, 1)}}, 0, 1, 1, 0);
	expect_order("v(0) = r(+dt)/dt", (lz_formula){LZ_COL_V, 0, 1, {T(R, 2, 1, 1)}}, -1, 1, 1, 0);
	/* Forgetting the 1/2 of the central difference: (r(+dt) - r(-dt))/dt = 2v + ...:
	 * the error v appears at order 0. */
	expect_order("v(0) = (r(+dt) - r(-dt))/dt",
	             (lz_formula){LZ_COL_V, 0, 2, {T(R, 2, 1, 1), T(R, -2, -1, 1)}}, 0, 1, 1, 1);
}
END_TEST

LZ_TEST(lozenge_exact_formula_is_edom)
{
	/* The Taylor series cut after b: r + dt v + dt²/2 a + dt³/6 b - r(t+dt) = -dt⁴/24 x⁗.
	 * Examined only up to x‴ it is exact: no order can be given there. */
	lz_formula taylor = {LZ_COL_R, 2, 4, {T(R, 0, 1, 1), T(V, 0, 1, 1), T(A, 0, 1, 2),
	                                      T(B, 0, 1, 6)}};
	int p = 0, d = 0;
	lz_ratio c = {0, 0};
	int status = lz_formula_order(&taylor, 3, &p, &c, &d);
	ck_assert_msg(status == LZ_EDOM, "the 4-term Taylor formula examined up to derivative 3 "
	              "has every coefficient zero: expected LZ_EDOM (%d), got %d", LZ_EDOM, status);
	ck_assert_msg(lz_formula_order(&taylor, 4, &p, &c, &d) == LZ_OK && p == 4 && c.num == -1 &&
	              c.den == 24 && d == 4, "the 4-term Taylor formula examined up to derivative "
	              "4: expected -1/24 dt^4 x^(4), got order %d, %lld/%lld, x^(%d)", p, c.num,
	              c.den, d);
	/* The same for the velocity: v + dt a + dt²/2 b - v(t+dt) = -dt³/6 x⁗, order 3
	 * (a target in column v), invisible up to x‴. */
	lz_formula taylor_v = {LZ_COL_V, 2, 3, {T(V, 0, 1, 1), T(A, 0, 1, 1), T(B, 0, 1, 2)}};
	status = lz_formula_order(&taylor_v, 3, &p, &c, &d);
	ck_assert_msg(status == LZ_EDOM, "the 3-term Taylor formula for v examined up to "
	              "derivative 3 has every coefficient zero: expected LZ_EDOM (%d), got %d",
	              LZ_EDOM, status);
	ck_assert_msg(lz_formula_order(&taylor_v, 4, &p, &c, &d) == LZ_OK && p == 3 &&
	              c.num == -1 && c.den == 6 && d == 4, "the 3-term Taylor formula for v "
	              "examined up to derivative 4: expected -1/6 dt^3 x^(4), got order %d, "
	              "%lld/%lld, x^(%d)", p, c.num, c.den, d);
	/* An identity at a half step is exact to all orders, also at the largest max_deriv
	 * (the coefficients (1/2)^D / D! must stay exact up to D = 20). */
	lz_formula same = {LZ_COL_V, 3, 1, {T(V, 3, 1, 1)}};
	status = lz_formula_order(&same, 20, &p, &c, &d);
	ck_assert_msg(status == LZ_EDOM, "v(+3dt/2) = v(+3dt/2) is exact to every order: expected "
	              "LZ_EDOM examined up to derivative 20, got status %d", status);
}
END_TEST

LZ_TEST(lozenge_malformed_is_einval)
{
	int p, d;
	lz_ratio c;
	/* Euler's velocity v(t+dt) = v + dt a: -dt²/2 x‴ (a target in column v, so the
	 * order is the derivative minus one). */
	lz_formula good = {LZ_COL_V, 2, 2, {T(V, 0, 1, 1), T(A, 0, 1, 1)}};
	lz_formula bad[6] = {good, good, good, good, good, good};
	bad[0].nterms = 0;
	bad[1].nterms = LZ_TERMS_MAX + 1;
	bad[2].term[1].col = (lz_column)4;
	bad[3].col = (lz_column)-1;
	bad[4].term[0].w = (lz_ratio){1, 0};
	bad[5].term[1].w = (lz_ratio){1, -2};
	static const char *const what[6] = {"no terms", "9 terms", "a term in column 4",
	                                    "the target in column -1", "a weight 1/0",
	                                    "a weight 1/-2"};
	for (int i = 0; i < 6; i++) {
		int status = lz_formula_order(&bad[i], 10, &p, &c, &d);
		ck_assert_msg(status == LZ_EINVAL, "a formula with %s must be rejected with "
		              "LZ_EINVAL (%d), got %d", what[i], LZ_EINVAL, status);
	}
	/* max_deriv is allowed in 0..20: one past either end is refused. */
	static const int bad_deriv[2] = {-1, 21};
	for (int i = 0; i < 2; i++) {
		int status = lz_formula_order(&good, bad_deriv[i], &p, &c, &d);
		ck_assert_msg(status == LZ_EINVAL, "max_deriv = %d is outside 0..20 and must be "
		              "rejected with LZ_EINVAL (%d), got %d", bad_deriv[i], LZ_EINVAL, status);
	}
	/* The refusals must not cost the valid formula its answer, examined exactly up to
	 * the derivative of its error. */
	p = d = -99;
	c = (lz_ratio){0, 0};
	ck_assert_msg(lz_formula_order(&good, 3, &p, &c, &d) == LZ_OK,
	              "the valid Euler formula was rejected, examined up to x^(3) where its error "
	              "is: %s", lz_error_message());
	ck_assert_msg(p == 2 && c.num == -1 && c.den == 2 && d == 3, "the valid Euler velocity "
	              "formula v(+dt) = v + dt a: expected -1/2 dt^2 x^(3), got %lld/%lld dt^%d "
	              "x^(%d)", c.num, c.den, p, d);
}
END_TEST

LZ_TEST(lozenge_eight_terms_accepted)
{
	/* LZ_TERMS_MAX = 8 terms is allowed: the 5-point second derivative of
	 * lozenge_five_point_stencil (error -dt⁴/90 x^(6)) with its three inner terms
	 * each split into two halves. */
	lz_formula a8 = {LZ_COL_A, 0, LZ_TERMS_MAX,
	                 {T(R, 4, -1, 12), T(R, 2, 8, 12), T(R, 2, 8, 12), T(R, 0, -15, 12),
	                  T(R, 0, -15, 12), T(R, -2, 8, 12), T(R, -2, 8, 12), T(R, -4, -1, 12)}};
	expect_order("the 5-point a(0) in 8 = LZ_TERMS_MAX terms", a8, 4, -1, 90, 6);
}
END_TEST
