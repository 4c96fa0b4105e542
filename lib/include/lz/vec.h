/* lz/vec.h — small vector helpers for 1-3 D and for flat arrays of n·dim doubles.
 *
 * Particle arrays are flat and particle-major: coordinate c of particle i is
 * x[i*dim + c]. All functions are O(length) and inline; lengths in σ (reduced units).
 */
#ifndef LZ_VEC_H
#define LZ_VEC_H

#include <math.h>
#include <stddef.h>

/* y += alpha * x over n entries: the workhorse of every integrator. */
static inline void lz_axpy(double *y, double alpha, const double *x, size_t n)
{
	for (size_t i = 0; i < n; i++)
		y[i] += alpha * x[i];
}

/* Σ a_i b_i over n entries (plain left-to-right sum). */
static inline double lz_dot(const double *a, const double *b, size_t n)
{
	double s = 0.0;
	for (size_t i = 0; i < n; i++)
		s += a[i] * b[i];
	return s;
}

/* |a|² over n entries. */
static inline double lz_norm2(const double *a, size_t n) { return lz_dot(a, a, n); }

/* The periodic image of a separation dx in a box of side L closest to zero:
 * the result lies in [-L/2, L/2]. Precondition: |dx| < 1.5 L (one wrap suffices
 * for separations of particles already inside the box). */
static inline double lz_min_image(double dx, double L)
{
	if (dx > 0.5 * L)
		return dx - L;
	if (dx < -0.5 * L)
		return dx + L;
	return dx;
}

/* x wrapped into [0, L). */
static inline double lz_wrap(double x, double L)
{
	x = fmod(x, L);
	return x < 0.0 ? x + L : x;
}

#endif
