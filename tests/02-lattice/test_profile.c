/* test_profile.c — density profiles across a slit: exact hand-made configurations in
 * 2D and 3D (checked as physics: the profile integrates to N over the slit, a full
 * row has the density of that row's sites), a particle outside the rows, an empty
 * accumulator, and the profile of hard disks in a slit — flat at low density, both
 * wall rows crowded at high density (the first layer of thesis 2.5.3). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/profile.h"
#include "lz/walk.h"
#include "walk_check.h"

static lz_profile *make(lz_lattice_kind kind, int64_t L, int32_t lo, int32_t hi, size_t n)
{
	lz_profile *p = lz_profile_alloc(kind, L, lo, hi, n);
	ck_assert_msg(p != NULL, "lz_profile_alloc: %s", lz_error_message());
	return p;
}

/* Σ ρ(c) · h · L^(dim-1) over the rows: the number of particles per configuration. */
static double integral(lz_lattice_kind kind, int64_t L, const double *rho, int rows)
{
	double slab = lz_walk_row_spacing(kind) * pow((double)L, lz_lattice_dim(kind) - 1);
	double sum = 0;
	for (int c = 0; c < rows; c++)
		sum += rho[c] * slab;
	return sum;
}

LZ_TEST(profile_hand_made_configurations)
{
	/* Triangular, L = 8, rows 2 .. 5. Two configurations of 3 particles: rows {2, 2, 5}
	 * and {3, 2, 5}. Counts 3, 1, 0, 2 over 2 samples. */
	lz_profile *p = make(LZ_LATTICE_TRIANGULAR, 8, 2, 5, 3);
	int32_t a[] = {0, 2, 7, 2, 4, 5}, b[] = {1, 3, 1, 2, 6, 5};
	ck_assert_int_eq(lz_profile_add_config(p, a), LZ_OK);
	ck_assert_int_eq(lz_profile_add_config(p, b), LZ_OK);
	ck_assert_msg(p->count[0] == 3 && p->count[1] == 1 && p->count[2] == 0 &&
	              p->count[3] == 2 && p->nsamples == 2, "counts per row %llu %llu %llu %llu "
	              "over %llu samples, expected 3 1 0 2 over 2: the row is the LAST coordinate",
	              (unsigned long long)p->count[0], (unsigned long long)p->count[1],
	              (unsigned long long)p->count[2], (unsigned long long)p->count[3],
	              (unsigned long long)p->nsamples);
	/* NaN in: every row must be written. */
	double rho[4] = {NAN, NAN, NAN, NAN};
	ck_assert_int_eq(lz_profile_result(p, rho), LZ_OK);
	double n = integral(LZ_LATTICE_TRIANGULAR, 8, rho, 4);
	ck_assert_msg(fabs(n - 3) < 1e-12, "the profile integrates to %.15g particles across the "
	              "slit, not 3: ρ is a number per unit area, and a row of the triangular "
	              "lattice is a strip of height √3/2", n);
	/* Row 2 holds 1.5 particles on average on 8 sites of area √3/2 each. */
	ck_assert(fabs(rho[0] - 1.5 / (8 * sqrt(3) / 2)) < 1e-12 && rho[2] == 0);
	ck_assert(fabs(rho[1] / rho[3] - 0.5) < 1e-15);
	lz_profile_free(p);

	/* Cubic, L = 4, every site of row z = 1 filled: that row has density 1 (one per
	 * unit volume), the others 0. */
	p = make(LZ_LATTICE_CUBIC, 4, 0, 3, 16);
	int32_t full[48];
	for (int i = 0; i < 16; i++) {
		full[3 * i] = i % 4;
		full[3 * i + 1] = i / 4;
		full[3 * i + 2] = 1;
	}
	ck_assert_int_eq(lz_profile_add_config(p, full), LZ_OK);
	double r3[4] = {NAN, NAN, NAN, NAN};
	ck_assert_int_eq(lz_profile_result(p, r3), LZ_OK);
	ck_assert_msg(r3[1] == 1 && r3[0] == 0 && r3[2] == 0 && r3[3] == 0, "a full plane of "
	              "the cubic lattice has density 1, got %g (rows 0..3: %g %g %g %g)", r3[1],
	              r3[0], r3[1], r3[2], r3[3]);
	lz_profile_free(p);
}
END_TEST

LZ_TEST(profile_rejects_particles_outside_and_empty)
{
	lz_profile *p = make(LZ_LATTICE_SQUARE, 16, 3, 12, 2);
	double rho[10];
	ck_assert_msg(lz_profile_result(p, rho) == LZ_EINVAL, "an empty profile has no density: "
	              "lz_profile_result must return LZ_EINVAL");
	int32_t low[] = {5, 5, 1, 2}, high[] = {5, 12, 1, 13};
	ck_assert_msg(lz_profile_add_config(p, low) == LZ_EINVAL, "row 2 is below the rows "
	              "3 .. 12: LZ_EINVAL");
	ck_assert_msg(lz_profile_add_config(p, high) == LZ_EINVAL, "row 13 is above the rows "
	              "3 .. 12: LZ_EINVAL");
	uint64_t total = p->nsamples;
	for (int c = 0; c < 10; c++)
		total += p->count[c];
	ck_assert_msg(total == 0, "a rejected configuration must leave the profile as it was "
	              "(check every row before counting any)");
	int32_t edge[] = {0, 3, 15, 12};
	ck_assert_int_eq(lz_profile_add_config(p, edge), LZ_OK);
	ck_assert(p->count[0] == 1 && p->count[9] == 1 && p->nsamples == 1);
	/* Added twice, the first good configuration puts one centre per sample in each
	 * edge row of 16 unit sites: ρ = 1/16 there, 0 in the rows between. */
	ck_assert_int_eq(lz_profile_add_config(p, edge), LZ_OK);
	for (int c = 0; c < 10; c++)
		rho[c] = NAN;
	ck_assert_int_eq(lz_profile_result(p, rho), LZ_OK);
	for (int c = 0; c < 10; c++) {
		double want = c == 0 || c == 9 ? 1.0 / 16.0 : 0.0;
		ck_assert_msg(fabs(rho[c] - want) < 1e-15, "square L = 16, rows 3 .. 12, 2 samples with "
		              "one centre in row 3 and one in row 12: ρ(%d) = %g, expected %g — ρ = "
		              "count / (samples · row volume), every row written", c + 3, rho[c], want);
	}
	lz_profile_free(p);
}
END_TEST

/* Sampled hard disks in a slit. The walkers' box is checked and every sweep replayed
 * against the rule (walk_check.c), so that the profile is judged on a right ensemble. */
static void slit_profile(size_t n, int sweeps, double *rho, int *rows, lz_walk **out)
{
	lz_walk *w = lz_walk_alloc(LZ_LATTICE_SQUARE, 64, 2, n, LZ_WALK_RANDOM);
	ck_assert(w && lz_walk_set_slit(w, 24) == LZ_OK);
	wc_require_box(w);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 11);
	ck_assert_msg(lz_walk_place(w, rng, 0) == LZ_OK, "%s", lz_error_message());
	lz_profile *p = make(LZ_LATTICE_SQUARE, 64, w->lo, w->hi, n);
	wc_run *run = wc_run_new(w);
	for (int s = 0; s < sweeps; s++) {
		wc_sweep(run, rng);
		if (s >= 1000 && s % 5 == 0) {
			int status = lz_profile_add_config(p, w->r);
			LZ_REQUIRE(status == LZ_OK, "sweep %d: lz_profile_add_config refused a "
			           "configuration whose every centre is in rows %d .. %d: %s", s, w->lo,
			           w->hi, lz_error_message());
		}
	}
	*rows = w->hi - w->lo + 1;
	for (int c = 0; c < *rows; c++)
		rho[c] = NAN;
	ck_assert_int_eq(lz_profile_result(p, rho), LZ_OK);
	*out = w;
	wc_run_free(run);
	lz_profile_free(p);
	gsl_rng_free(rng);
}

LZ_TEST(profile_disks_in_slit_flat_dilute_layered_dense)
{
	/* Square lattice, L = 64, R = 2, walls 24 apart: centres in rows 2 .. 22. */
	double rho[64];
	int rows;
	lz_walk *w;
	/* A walker needs about rows² ≈ 440 sweeps to cross the slit: 3e5 sweeps give
	 * some 4000 independent positions, about 190 per row, a 7 % scatter; 30 % is
	 * four of those. */
	slit_profile(6, 300000, rho, &rows, &w);
	double mean = 6.0 / (64.0 * rows);
	ck_assert(fabs(integral(LZ_LATTICE_SQUARE, 64, rho, rows) - 6) < 1e-9);
	for (int c = 0; c < rows; c++)
		ck_assert_msg(fabs(rho[c] / mean - 1) < 0.3, "6 disks in a slit of 21 rows: row %d "
		              "has %.2f times the mean density; a dilute gas fills the slit evenly",
		              w->lo + c, rho[c] / mean);
	lz_walk_free(w);
	/* 55 disks: packing 0.45 of the slit: the walls gather a layer, denser than the middle. */
	slit_profile(55, 6000, rho, &rows, &w);
	mean = 55.0 / (64.0 * rows);
	double mid = 0;
	for (int c = rows / 2 - 2; c <= rows / 2 + 2; c++)
		mid += rho[c] / 5;
	/* Measured: the wall rows hold about 2.3 times the middle's density. */
	ck_assert_msg(rho[0] > 1.5 * mid && rho[rows - 1] > 1.5 * mid, "dense disks in a slit: "
	              "wall rows %.3g and %.3g against %.3g in the middle (mean %.3g); the walls "
	              "should gather a layer (thesis fig. 2.28)", rho[0], rho[rows - 1], mid, mean);
	lz_walk_free(w);
}
END_TEST
