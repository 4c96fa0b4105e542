/* bits_lib.c — the power-of-two check and Morton decoding (the library half of lz/bits.h;
 * the wrap and the encoders are graded, in solutions/02-lattice/bits.c). */
#include <inttypes.h>
#include <stdint.h>

#include "lz/bits.h"
#include "lz/error.h"

int lz_check_pow2(const char *what, uint64_t n, uint64_t max)
{
	if (lz_is_pow2(n) && n <= max)
		return LZ_OK;
	if (n > max)
		return lz_error(LZ_EINVAL, "%s = %" PRIu64 " is too large: the largest allowed is "
		                "%" PRIu64 " (a power of two up to %" PRIu64 ")", what, n,
		                UINT64_C(1) << (63 - __builtin_clzll(max)), max);
	if (n == 0)
		return lz_error(LZ_EINVAL, "%s = 0 must be a power of two: 1, 2, 4, 8, …", what);
	/* n is between two powers of two, the upper of which may exceed max. */
	uint64_t below = UINT64_C(1) << (63 - __builtin_clzll(n)), above = below << 1;
	if (above > max)
		return lz_error(LZ_EINVAL, "%s = %" PRIu64 " is not a power of two: the nearest "
		                "allowed is %" PRIu64, what, n, below);
	return lz_error(LZ_EINVAL, "%s = %" PRIu64 " is not a power of two: the nearest allowed "
	                "are %" PRIu64 " and %" PRIu64, what, n, below, above);
}

/* Undo the dilation: each step halves the gaps between the kept bits. */
static uint32_t compact2(uint64_t d)
{
	d &= UINT64_C(0x5555555555555555);
	d = (d | d >> 1) & UINT64_C(0x3333333333333333);
	d = (d | d >> 2) & UINT64_C(0x0F0F0F0F0F0F0F0F);
	d = (d | d >> 4) & UINT64_C(0x00FF00FF00FF00FF);
	d = (d | d >> 8) & UINT64_C(0x0000FFFF0000FFFF);
	d = (d | d >> 16) & UINT64_C(0x00000000FFFFFFFF);
	return (uint32_t)d;
}

static uint32_t compact3(uint64_t d)
{
	d &= UINT64_C(0x1249249249249249);
	d = (d | d >> 2) & UINT64_C(0x10C30C30C30C30C3);
	d = (d | d >> 4) & UINT64_C(0x100F00F00F00F00F);
	d = (d | d >> 8) & UINT64_C(0x001F0000FF0000FF);
	d = (d | d >> 16) & UINT64_C(0x001F00000000FFFF);
	d = (d | d >> 32) & UINT64_C(0x00000000001FFFFF);
	return (uint32_t)d;
}

void lz_morton2_decode(uint64_t key, uint32_t *x, uint32_t *y)
{
	*x = compact2(key);
	*y = compact2(key >> 1);
}

void lz_morton3_decode(uint64_t key, uint32_t *x, uint32_t *y, uint32_t *z)
{
	*x = compact3(key);
	*y = compact3(key >> 1);
	*z = compact3(key >> 2);
}
