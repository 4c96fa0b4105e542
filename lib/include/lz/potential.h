/* lz/potential.h — force laws for lz_md (lz/integrate.h), reduced units.
 *
 * Harmonic: U = ω²|r|²/2 per particle (independent oscillators), a = -ω² r.
 * Lennard-Jones: U(r) = 4(r⁻¹² - r⁻⁶) - U(rc) for r < rc, 0 beyond (cut and
 * shifted), all pairs with the minimum image in a periodic cubic (3D) or square
 * (2D) box of side L. O(N²) per evaluation: for the small systems of stage 01.
 */
#ifndef LZ_POTENTIAL_H
#define LZ_POTENTIAL_H

#include <stddef.h>
#include "lz/integrate.h"
#include "lz/rng.h"

typedef struct {
	double omega;  /* angular frequency ω, 1/τ */
} lz_harmonic;

/* lz_force_fn for lz_harmonic. */
int lz_harmonic_force(size_t n, int dim, const double *r, double *a, double *u,
                      void *params);

typedef struct {
	double box;     /* side L, σ */
	double rc;      /* cutoff, σ; 0 < rc <= L/2 */
	double rc2;     /* rc² */
	double ushift;  /* U_LJ(rc), subtracted so that U is continuous at rc */
	double virial;  /* Σ_pairs r·F of the last evaluation, for the pressure */
	int single;     /* 1: round forces and energy to float (precision=float) */
} lz_lj;

/* Parameters for n particles at number density rho (σ⁻ᵈ) in dim 2 or 3 with cutoff
 * rc. LZ_EINVAL when rc > L/2 (the minimum image would miss pairs), rho <= 0, n < 1. */
int lz_lj_init(lz_lj *p, size_t n, int dim, double rho, double rc);

/* lz_force_fn for lz_lj. */
int lz_lj_force(size_t n, int dim, const double *r, double *a, double *u,
                void *params);

/* Place n particles on a face-centred cubic lattice filling the box (3D, n = 4m³)
 * or a centred square lattice (2D, n = 2m²).
 * LZ_EINVAL when n is not of that form (the message lists the nearest allowed n). */
int lz_lattice_start(double *r, size_t n, int dim, double box);
/* The check lz_lattice_start makes, without positions (for a scene's check). */
int lz_lattice_check(size_t n, int dim);

/* Maxwell-Boltzmann velocities at temperature T (k_B = m = 1): Gaussian draws,
 * total momentum removed, then scaled so the kinetic temperature is exactly T
 * (with dim(n-1) degrees of freedom; n = 1 gets v = 0). */
void lz_maxwell_velocities(double *v, size_t n, int dim, double T, lz_rng *rng);

#endif
