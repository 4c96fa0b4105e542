/* ratio.c — exact rationals for the truncation orders of lz/lozenge.h.
 *
 * Every result is reduced, with den > 0 and |num|, den <= 2^62. Products and sums
 * are formed in __int128, where two such operands cannot overflow, then reduced;
 * a result still beyond 2^62 is reported as the invalid ratio {0, 0}, which every
 * operation passes on.
 */
#include <stdio.h>

#include "lz/lozenge.h"

#define RATIO_MAX ((__int128)1 << 62)

static const lz_ratio invalid = {0, 0};

static unsigned __int128 gcd128(unsigned __int128 a, unsigned __int128 b)
{
	while (b != 0) {
		unsigned __int128 t = a % b;
		a = b;
		b = t;
	}
	return a;
}

/* num/den reduced; invalid when den == 0 or the reduced terms exceed 2^62. */
static lz_ratio reduce(__int128 num, __int128 den)
{
	if (den == 0)
		return invalid;
	if (den < 0) {
		num = -num;
		den = -den;
	}
	unsigned __int128 mag = num < 0 ? (unsigned __int128)-num : (unsigned __int128)num;
	unsigned __int128 g = gcd128(mag, (unsigned __int128)den);
	if (g > 1) {
		num /= (__int128)g;
		den /= (__int128)g;
	}
	if (num > RATIO_MAX || num < -RATIO_MAX || den > RATIO_MAX)
		return invalid;
	return (lz_ratio){(long long)num, (long long)den};
}

int lz_ratio_ok(lz_ratio a)
{
	return a.den > 0;
}

/* An operand the __int128 arithmetic below cannot overflow on (a hand-made ratio
 * may hold anything). */
static int operand(lz_ratio a)
{
	return a.den > 0 && a.den <= RATIO_MAX && a.num <= RATIO_MAX && a.num >= -RATIO_MAX;
}

int lz_ratio_is_zero(lz_ratio a)
{
	return lz_ratio_ok(a) && a.num == 0;
}

lz_ratio lz_ratio_make(long long num, long long den)
{
	return reduce(num, den);
}

lz_ratio lz_ratio_add(lz_ratio a, lz_ratio b)
{
	if (!operand(a) || !operand(b))
		return invalid;
	return reduce((__int128)a.num * b.den + (__int128)b.num * a.den, (__int128)a.den * b.den);
}

lz_ratio lz_ratio_sub(lz_ratio a, lz_ratio b)
{
	if (!operand(a) || !operand(b))
		return invalid;
	return reduce((__int128)a.num * b.den - (__int128)b.num * a.den, (__int128)a.den * b.den);
}

lz_ratio lz_ratio_mul(lz_ratio a, lz_ratio b)
{
	if (!operand(a) || !operand(b))
		return invalid;
	return reduce((__int128)a.num * b.num, (__int128)a.den * b.den);
}

const char *lz_ratio_str(lz_ratio a, char *buf, size_t size)
{
	if (!lz_ratio_ok(a))
		snprintf(buf, size, "invalid");
	else if (a.den == 1)
		snprintf(buf, size, "%lld", a.num);
	else
		snprintf(buf, size, "%lld/%lld", a.num, a.den);
	return buf;
}
