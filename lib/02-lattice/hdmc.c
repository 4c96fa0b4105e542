/* hdmc.c — off-lattice hard-disk Metropolis Monte Carlo, the continuum reference of
 * stage 02 (lz/hdmc.h). */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_fit.h>

#include "lz/error.h"
#include "lz/hdmc.h"

#define TUNE_ROUND 10  /* sweeps between two adjustments of δ */
#define DELTA_MIN 1e-6

lz_hdmc *lz_hdmc_alloc(size_t n, double packing)
{
	if (n < 1)
		return lz_error(LZ_EINVAL, "n = %zu disks: give at least one", n), NULL;
	if (!(packing > 0 && packing < LZ_HDMC_CLOSE_PACKING))
		return lz_error(LZ_EINVAL, "packing fraction = %g is not in (0, %.4f): it must be "
		                "positive and below hexagonal close packing pi/sqrt(12)", packing,
		                LZ_HDMC_CLOSE_PACKING), NULL;
	lz_hdmc *h = calloc(1, sizeof *h);
	double *x = calloc(2 * n, sizeof *x);
	if (!h || !x) {
		free(h);
		free(x);
		return lz_error(LZ_ENOMEM, "no memory for %zu disks", n), NULL;
	}
	h->n = n;
	h->packing = packing;
	h->side = sqrt((double)n * M_PI / (4.0 * packing));
	h->delta = 0.1;  /* <= L/2: L >= 0.93 for n >= 1 below close packing */
	h->x = x;
	return h;
}

void lz_hdmc_free(lz_hdmc *h)
{
	if (!h)
		return;
	free(h->x);
	free(h);
}

/* x mod L for x in [-L, 2L), into [0, L): the order of the two tests matters, since
 * a tiny negative x + L may round to L itself. */
static double wrap(double x, double L)
{
	if (x < 0)
		x += L;
	if (x >= L)
		x -= L;
	return x;
}

int lz_hdmc_set(lz_hdmc *h, size_t i, double x, double y)
{
	if (i >= h->n)
		return lz_error(LZ_EINVAL, "disk %zu does not exist: there are %zu", i, h->n);
	if (!isfinite(x) || !isfinite(y))
		return lz_error(LZ_EINVAL, "position (%g, %g) of disk %zu is not finite", x, y, i);
	h->x[2 * i] = wrap(fmod(x, h->side), h->side);
	h->x[2 * i + 1] = wrap(fmod(y, h->side), h->side);
	return LZ_OK;
}

/* The nearest distance of nx·ny sites on rows of nx in a box of side L, the odd rows
 * shifted by half a spacing when `shift` (ny even: the shift is then periodic); rows
 * two apart are then aligned, at 2b. */
static double grid_nearest(double L, size_t nx, size_t ny, int shift)
{
	double a = L / (double)nx, b = L / (double)ny;
	return shift ? fmin(a, fmin(hypot(a / 2, b), 2 * b)) : fmin(a, b);
}

int lz_hdmc_place(lz_hdmc *h)
{
	size_t bx = 1, by = h->n;
	int bshift = 0;
	double best = -1;
	for (size_t nx = 1; nx <= h->n; nx++) {
		size_t ny = (h->n + nx - 1) / nx;
		for (int shift = 0; shift <= (ny % 2 == 0); shift++) {
			double d = grid_nearest(h->side, nx, ny, shift);
			if (d > best) {
				best = d;
				bx = nx;
				by = ny;
				bshift = shift;
			}
		}
	}
	if (best < 1)
		return lz_error(LZ_EPHYS, "cannot place n = %zu disks at packing fraction %g in a "
		                "box of side %g: the best lattice start (%zu x %zu) has nearest "
		                "distance %g < sigma = 1; a square box fits no triangular lattice "
		                "near close packing, so lower the packing or change n", h->n,
		                h->packing, h->side, bx, by, best);
	double a = h->side / (double)bx, b = h->side / (double)by;
	for (size_t i = 0; i < h->n; i++) {
		size_t row = i / bx, col = i % bx;
		double off = bshift && row % 2 ? a / 2 : 0.0;
		h->x[2 * i] = wrap((double)col * a + off + a / 4, h->side);
		h->x[2 * i + 1] = (double)row * b + b / 4;
	}
	return LZ_OK;
}

/* The minimum-image distance² of the displacement (dx, dy), each in (-L, L): per
 * component the shorter of |d| and L - |d|, without a branch. */
static inline double min_image_d2(double dx, double dy, double L)
{
	double ax = fabs(dx), ay = fabs(dy);
	ax = ax < L - ax ? ax : L - ax;  /* not fmin: gcc calls libm for it at -O2 */
	ay = ay < L - ay ? ay : L - ay;
	return ax * ax + ay * ay;
}

/* 1 when a disk at (px, py) would overlap any disk but `skip`. */
static int overlaps_any(const lz_hdmc *h, double px, double py, size_t skip)
{
	const double *x = h->x;
	for (size_t j = 0; j < h->n; j++)
		if (min_image_d2(px - x[2 * j], py - x[2 * j + 1], h->side) < 1.0 && j != skip)
			return 1;
	return 0;
}

int lz_hdmc_try_move(lz_hdmc *h, size_t i, double u, double v)
{
	double px = wrap(h->x[2 * i] + u, h->side), py = wrap(h->x[2 * i + 1] + v, h->side);
	h->moves++;
	if (overlaps_any(h, px, py, i))
		return 0;
	h->x[2 * i] = px;
	h->x[2 * i + 1] = py;
	h->accepted++;
	return 1;
}

size_t lz_hdmc_sweep(lz_hdmc *h, gsl_rng *rng)
{
	size_t accepted = 0;
	for (size_t k = 0; k < h->n; k++) {
		size_t i = (size_t)gsl_rng_uniform_int(rng, (unsigned long)h->n);
		double u = h->delta * (2 * gsl_rng_uniform(rng) - 1);
		double v = h->delta * (2 * gsl_rng_uniform(rng) - 1);
		accepted += (size_t)lz_hdmc_try_move(h, i, u, v);
	}
	return accepted;
}

double lz_hdmc_tune(lz_hdmc *h, gsl_rng *rng, unsigned long sweeps, double target)
{
	if (!(target > 0 && target < 1))
		return lz_error(LZ_EINVAL, "target acceptance = %g is not in (0, 1)", target), -1;
	double acc = 0;
	for (unsigned long s = 0; s < sweeps; s += TUNE_ROUND) {
		size_t got = 0, tried = 0;
		for (unsigned long t = s; t < sweeps && t < s + TUNE_ROUND; t++, tried += h->n)
			got += lz_hdmc_sweep(h, rng);
		acc = (double)got / (double)tried;
		double scale = fmin(2.0, fmax(0.5, acc / target));
		h->delta = fmin(h->side / 2, fmax(DELTA_MIN, h->delta * scale));
	}
	return acc;
}

size_t lz_hdmc_overlaps(const lz_hdmc *h)
{
	size_t count = 0;
	const double *x = h->x;
	for (size_t i = 1; i < h->n; i++)
		for (size_t j = 0; j < i; j++)
			count += min_image_d2(x[2 * i] - x[2 * j], x[2 * i + 1] - x[2 * j + 1],
			                      h->side) < 1.0;
	return count;
}

int lz_hdmc_gr_add(const lz_hdmc *h, gsl_histogram *hist)
{
	double lo = hist->range[0], hi = hist->range[hist->n];
	if (hi > h->side / 2 || lo < 0)
		return lz_error(LZ_EINVAL, "g(r) histogram on [%g, %g) sigma: it must lie within "
		                "[0, L/2 = %g], where every annulus is whole inside the box", lo, hi,
		                h->side / 2);
	const double *x = h->x, hi2 = hi * hi;
	for (size_t i = 1; i < h->n; i++)
		for (size_t j = 0; j < i; j++) {
			double d2 = min_image_d2(x[2 * i] - x[2 * j], x[2 * i + 1] - x[2 * j + 1],
			                         h->side);
			if (d2 < hi2)
				gsl_histogram_increment(hist, sqrt(d2));
		}
	return LZ_OK;
}

int lz_hdmc_gr(const lz_hdmc *h, const gsl_histogram *hist, unsigned long nconf, double *g)
{
	if (nconf == 0 || h->n < 2)
		return lz_error(LZ_EINVAL, "g(r) needs at least one configuration of 2 or more "
		                "disks (nconf = %lu, n = %zu)", nconf, h->n);
	double pairs = (double)nconf * (double)h->n * (double)(h->n - 1) / 2;
	double area = h->side * h->side;
	for (size_t k = 0; k < hist->n; k++) {
		double r1 = hist->range[k], r2 = hist->range[k + 1];
		g[k] = hist->bin[k] / (pairs * M_PI * (r2 * r2 - r1 * r1) / area);
	}
	return LZ_OK;
}

int lz_hdmc_contact(const gsl_histogram *hist, const double *g, double width, double *g0,
                    double *err)
{
	if (!(width > 0))
		return lz_error(LZ_EINVAL, "contact fit width = %g sigma must be positive", width);
	size_t first = 0, m = 0;  /* bins first .. first + m - 1 have centres in the window */
	for (size_t k = 0; k < hist->n; k++) {
		double r = (hist->range[k] + hist->range[k + 1]) / 2;
		if (r >= 1 && r <= 1 + width && m++ == 0)
			first = k;
	}
	if (m < 3)
		return lz_error(LZ_EDOM, "contact value: only %zu bins have centres in [1, %g] "
		                "sigma; a line through ln g needs 3 or more", m, 1 + width);
	for (size_t k = first; k < first + m; k++)
		if (!(g[k] > 0))
			return lz_error(LZ_EDOM, "contact value: g = %g at r = %g sigma, inside the "
			                "fit window [1, %g]: ln g is undefined", g[k],
			                hist->range[k], 1 + width);
	double *x = malloc(2 * m * sizeof *x);
	if (!x)
		return lz_error(LZ_ENOMEM, "no memory for a fit of %zu points", m);
	double *y = x + m;
	for (size_t k = 0; k < m; k++) {
		x[k] = (hist->range[first + k] + hist->range[first + k + 1]) / 2 - 1;
		y[k] = log(g[first + k]);
	}
	double c0, c1, c00, c01, c11, sumsq;
	gsl_fit_linear(x, 1, y, 1, m, &c0, &c1, &c00, &c01, &c11, &sumsq);
	free(x);
	*g0 = exp(c0);
	*err = *g0 * sqrt(c00);
	return LZ_OK;
}
