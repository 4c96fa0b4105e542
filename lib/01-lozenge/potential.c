/* potential.c — the force laws of stage 01 and the initial states that go with them:
 * harmonic oscillators, and Lennard-Jones all pairs with the minimum image. */
#include <math.h>
#include <string.h>

#include <gsl/gsl_randist.h>

#include "lz/error.h"
#include "lz/potential.h"
#include "lz/vec.h"

int lz_harmonic_force(size_t n, int dim, const double *r, double *a, double *u,
                      void *params)
{
	const lz_harmonic *p = params;
	double w2 = p->omega * p->omega;
	size_t len = n * (size_t)dim;
	for (size_t i = 0; i < len; i++)
		a[i] = -w2 * r[i];
	*u = 0.5 * w2 * lz_norm2(r, len);
	return LZ_OK;
}

/* U_LJ(r) = 4 (r^-12 - r^-6) from 1/r². */
static double lj_energy(double inv_r2)
{
	double s6 = inv_r2 * inv_r2 * inv_r2;
	return 4.0 * s6 * (s6 - 1.0);
}

int lz_lj_init(lz_lj *p, size_t n, int dim, double rho, double rc)
{
	if (n < 1 || (dim != 2 && dim != 3) || !(rho > 0.0) || !isfinite(rho) || !(rc > 0.0))
		return lz_error(LZ_EINVAL, "Lennard-Jones needs n >= 1 (got %zu), dim 2 or 3 "
		                "(got %d), density > 0 (got %g) and cutoff rc > 0 (got %g)",
		                n, dim, rho, rc);
	double box = pow((double)n / rho, 1.0 / dim);
	if (rc > 0.5 * box)
		return lz_error(LZ_EINVAL, "cutoff rc = %g σ exceeds half the box L/2 = %g σ "
		                "(n = %zu at density %g): the minimum image would miss pairs; "
		                "use more particles or a smaller rc", rc, 0.5 * box, n, rho);
	*p = (lz_lj){.box = box, .rc = rc, .rc2 = rc * rc, .ushift = lj_energy(1.0 / (rc * rc))};
	return LZ_OK;
}

/* The nearest periodic image of a separation. Positions are not wrapped into the
 * box (Verlet's r - r_prev must not jump), so dx can be many boxes long. Rounding
 * by a cast (half away from zero) is a single instruction where nearbyint() may be
 * a library call, and this is the innermost loop. */
static inline double nearest_image(double dx, double box, double inv_box)
{
	double k = dx * inv_box;
	return dx - box * (double)(long long)(k + (k >= 0.0 ? 0.5 : -0.5));
}

static void round_to_float(double *a, size_t len, double *u)
{
	for (size_t i = 0; i < len; i++)
		a[i] = (float)a[i];
	*u = (float)*u;
}

/* All pairs for a dimension known at compile time (dim is a constant at both call
 * sites, so the coordinate loops unroll). Returns the energy; adds the virial. */
static inline double lj_pairs(size_t n, const int dim, const double *r, double *a,
                              const lz_lj *p, double *virial)
{
	double box = p->box, inv_box = 1.0 / box, energy = 0.0, w = 0.0;
	for (size_t i = 0; i + 1 < n; i++) {
		const double *ri = r + i * dim;
		double *ai = a + i * dim, fi[3] = {0, 0, 0};
		for (size_t j = i + 1; j < n; j++) {
			const double *rj = r + j * dim;
			double d[3], r2 = 0.0;
			for (int c = 0; c < dim; c++) {
				d[c] = nearest_image(ri[c] - rj[c], box, inv_box);
				r2 += d[c] * d[c];
			}
			if (r2 >= p->rc2)
				continue;
			double inv_r2 = 1.0 / r2, s6 = inv_r2 * inv_r2 * inv_r2;
			/* F·r = 48 r^-12 - 24 r^-6; F = (F·r / r²) d. */
			double fr = 24.0 * s6 * (2.0 * s6 - 1.0), f = fr * inv_r2;
			double *aj = a + j * dim;
			for (int c = 0; c < dim; c++) {
				fi[c] += f * d[c];
				aj[c] -= f * d[c];
			}
			energy += lj_energy(inv_r2) - p->ushift;
			w += fr;
		}
		for (int c = 0; c < dim; c++)
			ai[c] += fi[c];
	}
	*virial = w;
	return energy;
}

int lz_lj_force(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	lz_lj *p = params;
	size_t len = n * (size_t)dim;
	memset(a, 0, len * sizeof *a);
	*u = dim == 3 ? lj_pairs(n, 3, r, a, p, &p->virial) : lj_pairs(n, 2, r, a, p, &p->virial);
	if (p->single)
		round_to_float(a, len, u);
	return LZ_OK;
}

static const double fcc[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
static const double centred[2][3] = {{0, 0, 0}, {0.5, 0.5, 0}};

/* Particles on a lattice of m^dim cells with nbasis sites each. */
static size_t lattice_n(size_t m, int dim, size_t nbasis)
{
	size_t count = nbasis;
	for (int d = 0; d < dim; d++)
		count *= m;
	return count;
}

/* Cells per side m with nbasis * m^dim == n, or 0 after reporting the nearest n. */
static size_t lattice_side(size_t n, int dim)
{
	if (dim != 2 && dim != 3) {
		lz_error(LZ_EINVAL, "lattice start: dim = %d must be 2 or 3", dim);
		return 0;
	}
	size_t nbasis = dim == 3 ? 4 : 2, m = 0;
	while (lattice_n(m + 1, dim, nbasis) <= n)
		m++;
	if (m > 0 && lattice_n(m, dim, nbasis) == n)
		return m;
	const char *kind = dim == 3 ? "face-centred cubic" : "centred square";
	if (m == 0)
		lz_error(LZ_EINVAL, "n = %zu particles cannot fill a %s lattice (n = %zu m^%d); "
		         "the smallest allowed n is %zu", n, kind, nbasis, dim,
		         lattice_n(1, dim, nbasis));
	else
		lz_error(LZ_EINVAL, "n = %zu particles do not fill a %s lattice (n = %zu m^%d); "
		         "the nearest allowed n are %zu and %zu", n, kind, nbasis, dim,
		         lattice_n(m, dim, nbasis), lattice_n(m + 1, dim, nbasis));
	return 0;
}

int lz_lattice_check(size_t n, int dim)
{
	return lattice_side(n, dim) ? LZ_OK : LZ_EINVAL;
}

int lz_lattice_start(double *r, size_t n, int dim, double box)
{
	size_t m = lattice_side(n, dim);
	if (m == 0)
		return LZ_EINVAL;
	size_t nbasis = dim == 3 ? 4 : 2;
	const double (*basis)[3] = dim == 3 ? fcc : centred;
	double cell = box / (double)m;
	size_t k = 0;
	for (size_t c = 0; c < n / nbasis; c++) {
		size_t idx[3] = {c % m, (c / m) % m, c / (m * m)};
		for (size_t b = 0; b < nbasis; b++, k++)
			for (int d = 0; d < dim; d++)
				/* A quarter cell off the walls keeps every site inside [0, L). */
				r[k * dim + d] = cell * ((double)idx[d] + basis[b][d] + 0.25);
	}
	return LZ_OK;
}

void lz_maxwell_velocities(double *v, size_t n, int dim, double T, lz_rng *rng)
{
	size_t len = n * (size_t)dim;
	if (n < 2 || !(T > 0.0)) {
		memset(v, 0, len * sizeof *v);
		return;
	}
	double sd = sqrt(T), mean[3] = {0, 0, 0};
	for (size_t i = 0; i < len; i++) {
		v[i] = gsl_ran_gaussian(rng->gsl, sd);
		mean[i % dim] += v[i];
	}
	for (int d = 0; d < dim; d++)
		mean[d] /= (double)n;
	for (size_t i = 0; i < len; i++)
		v[i] -= mean[i % dim];
	/* T_kin = Σ v² / (dim (n - 1)) once the momentum is gone. */
	double t_kin = lz_norm2(v, len) / ((double)dim * (double)(n - 1));
	double scale = sqrt(T / t_kin);
	for (size_t i = 0; i < len; i++)
		v[i] *= scale;
}
