/* test_hdmc.c — the off-lattice hard-disk Monte Carlo (lz/hdmc.h), the reference of
 * stage 02's walkers. Library code, not graded: these tests check its physics against
 * exact cases (one and two disks, uniform points, the low-density limit), the hard-disk
 * equation of state, and that it never lets two disks overlap. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_histogram.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/hdmc.h"
#include "lztest.h"

static gsl_histogram *hist_uniform(size_t bins, double lo, double hi)
{
	gsl_histogram *h = gsl_histogram_alloc(bins);
	ck_assert(h != NULL);
	gsl_histogram_set_ranges_uniform(h, lo, hi);
	return h;
}

/* The nearest distance between any two disks, over all nine periodic images: a
 * different road from the library's minimum image. */
static double nearest_all_images(const lz_hdmc *h)
{
	double best = INFINITY, L = h->side;
	for (size_t i = 1; i < h->n; i++)
		for (size_t j = 0; j < i; j++)
			for (int a = -1; a <= 1; a++)
				for (int b = -1; b <= 1; b++)
					best = fmin(best, hypot(h->x[2 * i] - h->x[2 * j] + a * L,
					                        h->x[2 * i + 1] - h->x[2 * j + 1] + b * L));
	return best;
}

#define NBLK 20  /* blocks for error bars */
#define MAXBIN 32

/* NBLK blocks of `sweeps` sweeps each, g sampled after every sweep: per bin the mean of
 * the blocks' g and its standard error — block averages, honest for a correlated
 * chain. */
static void gr_blocks(lz_hdmc *h, gsl_rng *r, gsl_histogram *hist, unsigned long sweeps,
                      double *mean, double *err)
{
	static double g[NBLK][MAXBIN];
	ck_assert(hist->n <= MAXBIN);
	int bad = 0;  /* not ck_assert in the loop: each one writes to the runner's pipe */
	for (int b = 0; b < NBLK; b++) {
		gsl_histogram_reset(hist);
		for (unsigned long s = 0; s < sweeps; s++) {
			lz_hdmc_sweep(h, r);
			bad |= lz_hdmc_gr_add(h, hist) != LZ_OK;
		}
		ck_assert(!bad && lz_hdmc_gr(h, hist, sweeps, g[b]) == LZ_OK);
	}
	for (size_t k = 0; k < hist->n; k++) {
		mean[k] = gsl_stats_mean(&g[0][k], MAXBIN, NBLK);
		err[k] = gsl_stats_sd_m(&g[0][k], MAXBIN, NBLK, mean[k]) / sqrt(NBLK);
	}
}

static void assert_inside_box(const lz_hdmc *h)
{
	for (size_t k = 0; k < 2 * h->n; k++)
		ck_assert_msg(h->x[k] >= 0 && h->x[k] < h->side, "coordinate %zu = %.17g is outside "
		              "[0, L = %g): a move was not wrapped into the box", k, h->x[k], h->side);
}

LZ_TEST(hdmc_alloc_rejects_bad_input)
{
	ck_assert(lz_hdmc_alloc(0, 0.3) == NULL);
	ck_assert_msg(strstr(lz_error_message(), "n = 0"), "the message should name n: %s",
	              lz_error_message());
	static const double bad[] = {0.0, -0.2, 0.9069, 0.95, 1.0};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		char value[32];
		snprintf(value, sizeof value, "%g", bad[k]);
		ck_assert_msg(lz_hdmc_alloc(10, bad[k]) == NULL, "packing %g accepted", bad[k]);
		ck_assert_msg(strstr(lz_error_message(), value) &&
		              strstr(lz_error_message(), "(0, 0.9069)"),
		              "the message should name the packing %s and the range (0, 0.9069): %s",
		              value, lz_error_message());
	}
	ck_assert(lz_hdmc_alloc(10, NAN) == NULL);
	ck_assert(lz_hdmc_alloc(10, INFINITY) == NULL);
	lz_hdmc *h = lz_hdmc_alloc(100, 0.3);
	ck_assert_msg(h != NULL, "a valid system refused: %s", lz_error_message());
	ck_assert_msg(fabs(h->side * h->side * 0.3 - 100 * M_PI / 4) < 1e-10,
	              "L = %g does not give eta = N pi/4 / L^2 = 0.3", h->side);
	ck_assert(lz_hdmc_set(h, 100, 0, 0) == LZ_EINVAL);
	ck_assert(lz_hdmc_set(h, 0, NAN, 0) == LZ_EINVAL);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_place_refuses_what_cannot_fit)
{
	/* Two disks in a box of side 1.37: the farthest apart they can be is half the
	 * diagonal, 0.97 < σ, whatever the arrangement. */
	lz_hdmc *h = lz_hdmc_alloc(2, 0.85);
	ck_assert(h != NULL);
	ck_assert_int_eq(lz_hdmc_place(h), LZ_EPHYS);
	ck_assert_msg(strstr(lz_error_message(), "n = 2") && strstr(lz_error_message(), "0.85"),
	              "the message should name n and the packing: %s", lz_error_message());
	lz_hdmc_free(h);
	/* One disk with L < σ overlaps its own image (η > π/4); just below, it fits. */
	h = lz_hdmc_alloc(1, 0.8);
	ck_assert_int_eq(lz_hdmc_place(h), LZ_EPHYS);
	lz_hdmc_free(h);
	h = lz_hdmc_alloc(1, 0.78);
	ck_assert_int_eq(lz_hdmc_place(h), LZ_OK);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_touching_allowed_overlap_across_the_boundary)
{
	lz_hdmc *h = lz_hdmc_alloc(2, 0.05);  /* L = 5.6 */
	ck_assert(h != NULL);
	ck_assert(lz_hdmc_set(h, 0, 1.0, 1.0) == LZ_OK && lz_hdmc_set(h, 1, 2.0, 1.0) == LZ_OK);
	ck_assert_msg(lz_hdmc_overlaps(h) == 0, "two disks at distance exactly sigma touch; "
	              "they do not overlap (d^2 < 1 is an overlap, d^2 = 1 is not)");
	ck_assert_msg(lz_hdmc_try_move(h, 1, -1e-9, 0) == 0, "a move to d = 1 - 1e-9 must be "
	              "rejected");
	ck_assert(h->x[2] == 2.0 && h->moves == 1 && h->accepted == 0);
	ck_assert_msg(lz_hdmc_try_move(h, 1, 0.5, 0.0) == 1, "a move away must be accepted");
	ck_assert_msg(lz_hdmc_try_move(h, 1, -0.5, 0.0) == 1 && h->x[2] == 2.0, "a move back to "
	              "touching, d = 1 exactly, must be accepted");
	ck_assert(h->moves == 3 && h->accepted == 2);
	/* Across the periodic boundary: 0.2 and L - 0.5 are 0.7 apart. */
	ck_assert(lz_hdmc_set(h, 0, 0.2, 3.0) == LZ_OK);
	ck_assert(lz_hdmc_set(h, 1, h->side - 0.5, 3.0) == LZ_OK);
	ck_assert_msg(lz_hdmc_overlaps(h) == 1, "disks at x = 0.2 and x = L - 0.5 overlap "
	              "through the periodic boundary (minimum image)");
	ck_assert(lz_hdmc_set(h, 1, h->side - 0.5, 4.5) == LZ_OK);
	ck_assert_msg(lz_hdmc_try_move(h, 1, 0.0, -1.0) == 0, "a move onto a disk's periodic "
	              "image must be rejected");
	/* A move out of the box comes back in on the other side. */
	ck_assert(lz_hdmc_try_move(h, 1, 0.7, 0.0) == 1);
	ck_assert_msg(fabs(h->x[2] - 0.2) < 1e-12, "x = L - 0.5 + 0.7 should wrap to 0.2, got "
	              "%.17g", h->x[2]);
	assert_inside_box(h);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_no_overlaps_after_many_sweeps)
{
	gsl_rng *r = lz_test_rng(7);
	lz_hdmc *h = lz_hdmc_alloc(64, 0.7);
	ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
	ck_assert_msg(nearest_all_images(h) >= 1.0, "the lattice start overlaps: nearest "
	              "distance %g", nearest_all_images(h));
	double acc = lz_hdmc_tune(h, r, 500, 0.4);
	ck_assert_msg(acc > 0.2 && acc < 0.6, "tuning reached acceptance %g, not near 0.4", acc);
	double delta = h->delta;
	for (int s = 0; s < 40000; s++)
		lz_hdmc_sweep(h, r);
	ck_assert_msg(h->delta == delta, "a sweep changed delta: sampling must run at fixed "
	              "delta, or detailed balance is broken");
	ck_assert_msg(lz_hdmc_overlaps(h) == 0, "%zu overlapping pairs after 40000 sweeps "
	              "(2.6e6 moves) at eta = 0.7", lz_hdmc_overlaps(h));
	double d = nearest_all_images(h);
	ck_assert_msg(d >= 1.0, "nearest distance over all periodic images %.17g < sigma", d);
	ck_assert_msg(d < 1.05, "nearest distance %g at eta = 0.7: the disks should touch "
	              "nearly", d);
	assert_inside_box(h);
	gsl_rng_free(r);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_extreme_densities)
{
	gsl_rng *r = lz_test_rng(11);
	/* η = 1e-4: the tuner opens δ to its cap L/2, where a move lands anywhere. */
	lz_hdmc *h = lz_hdmc_alloc(10, 1e-4);
	ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
	double acc = lz_hdmc_tune(h, r, 200, 0.4);
	ck_assert_msg(h->delta == h->side / 2 && acc > 0.99, "at eta = 1e-4 delta should reach "
	              "L/2 = %g with acceptance ~1; got delta %g, acceptance %g", h->side / 2,
	              h->delta, acc);
	assert_inside_box(h);
	lz_hdmc_free(h);
	/* η = 0.89, 98 % of close packing: 56 disks as a 7 x 8 stretched triangular lattice
	 * (the densest such start reaches 0.8976), rattling in their cages. */
	h = lz_hdmc_alloc(56, 0.89);
	ck_assert_msg(h != NULL && lz_hdmc_place(h) == LZ_OK, "no start at eta = 0.89: %s",
	              lz_error_message());
	acc = lz_hdmc_tune(h, r, 500, 0.4);
	for (int s = 0; s < 500; s++)
		lz_hdmc_sweep(h, r);
	ck_assert_msg(acc > 0.2 && h->delta < 0.05, "near close packing delta must shrink "
	              "(delta %g, acceptance %g)", h->delta, acc);
	ck_assert_msg(nearest_all_images(h) >= 1.0, "overlap at eta = 0.89: nearest %.17g",
	              nearest_all_images(h));
	gsl_rng_free(r);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_free_disk_steps_are_symmetric_and_uniform)
{
	/* One disk alone: every move is accepted, and its steps must be the proposal, a
	 * uniform draw from [-δ, δ]²: mean 0 (a one-sided proposal drifts, and breaks
	 * detailed balance between the disks), variance δ²/3, never beyond δ. */
	gsl_rng *r = lz_test_rng(13);
	lz_hdmc *h = lz_hdmc_alloc(1, 0.01);  /* L = 8.9 */
	ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
	h->delta = 0.3;
	const int steps = 100000;
	double sum[2] = {0, 0}, sum2[2] = {0, 0}, big = 0;
	for (int s = 0; s < steps; s++) {
		double old[2] = {h->x[0], h->x[1]};
		lz_hdmc_sweep(h, r);
		for (int c = 0; c < 2; c++) {
			double d = h->x[c] - old[c];
			d -= h->side * round(d / h->side);  /* the step, through the boundary too */
			sum[c] += d;
			sum2[c] += d * d;
			big = fmax(big, fabs(d));
		}
	}
	ck_assert_msg(h->accepted == (uint64_t)steps, "a lone disk had %llu of %d moves "
	              "rejected", (unsigned long long)(steps - h->accepted), steps);
	double sd = 0.3 / sqrt(3.0) / sqrt(steps);  /* of the mean step */
	for (int c = 0; c < 2; c++) {
		double mean = sum[c] / steps, var = sum2[c] / steps;
		ck_assert_msg(fabs(mean) < 4 * sd, "coordinate %d: mean step %.5f, expected 0 +- "
		              "%.5f: the proposal is not symmetric", c, mean, sd);
		ck_assert_msg(fabs(var / 0.03 - 1) < 0.02, "coordinate %d: step variance %.5f, "
		              "expected delta^2/3 = 0.03 (uniform in [-delta, delta])", c, var);
	}
	ck_assert_msg(big <= 0.3, "a step of %g beyond delta = 0.3", big);
	gsl_rng_free(r);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_gr_of_uniform_points_is_one)
{
	/* Points set uniformly at random, overlaps and all (no Monte Carlo): g = 1 in
	 * expectation in every bin, r < σ included, at any n — with n(n-1)/2 pairs and
	 * the exact annulus area. */
	gsl_rng *r = lz_test_rng(3);
	lz_hdmc *h = lz_hdmc_alloc(3, 0.05);
	gsl_histogram *hist = hist_uniform(8, 0.0, 4.0);  /* L/2 = 3.43 */
	char half[32];
	snprintf(half, sizeof half, "%g", h->side / 2);
	ck_assert_int_eq(lz_hdmc_gr_add(h, hist), LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "4)") && strstr(lz_error_message(), half),
	              "the message should name the edge 4 and L/2 = %s: %s", half,
	              lz_error_message());
	gsl_histogram_free(hist);
	hist = hist_uniform(6, 0.0, 3.0);
	const unsigned long nconf = 200000;
	int bad = 0;
	for (unsigned long c = 0; c < nconf; c++) {
		for (size_t i = 0; i < 3; i++)
			bad |= lz_hdmc_set(h, i, h->side * gsl_rng_uniform(r),
			                   h->side * gsl_rng_uniform(r)) != LZ_OK;
		bad |= lz_hdmc_gr_add(h, hist) != LZ_OK;
	}
	ck_assert(!bad);
	double g[6];
	ck_assert_int_eq(lz_hdmc_gr(h, hist, 0, g), LZ_EINVAL);
	ck_assert_int_eq(lz_hdmc_gr(h, hist, nconf, g), LZ_OK);
	for (size_t k = 0; k < 6; k++) {
		double err = 1 / sqrt(hist->bin[k]);  /* Poisson: each pair is independent */
		ck_assert_msg(fabs(g[k] - 1) < 4 * err, "uniform points: g = %.4f in [%g, %g), "
		              "expected 1 +- %.4f; is the annulus area pi (r2^2 - r1^2) and the "
		              "pair count n(n-1)/2?", g[k], hist->range[k], hist->range[k + 1], err);
	}
	gsl_histogram_free(hist);
	gsl_rng_free(r);
	lz_hdmc_free(h);
}
END_TEST

/* Two disks at η = 0.1 (L = 3.96, A = 15.7) with displacements up to δ (0: L/2), g in
 * bins of 0.1 up to 1.9 < L/2: zero below σ, A/(A - π) = 1.25 above, within 4 block
 * errors. */
static void two_disks(gsl_rng *r, double delta, unsigned long sweeps)
{
	lz_hdmc *h = lz_hdmc_alloc(2, 0.1);
	ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
	h->delta = delta > 0 ? delta : h->side / 2;
	gsl_histogram *hist = hist_uniform(19, 0.0, 1.9);
	double g[19], err[19], A = h->side * h->side, exact = A / (A - M_PI);
	gr_blocks(h, r, hist, sweeps, g, err);
	for (size_t k = 0; k < 10; k++)
		ck_assert_msg(g[k] == 0, "two disks, delta = %g: g = %g closer than sigma, in "
		              "[%g, %g)", delta, g[k], hist->range[k], hist->range[k + 1]);
	for (size_t k = 10; k < 19; k++) {
		ck_assert_msg(err[k] < 0.03 * exact, "block error %g too large for a test", err[k]);
		ck_assert_msg(fabs(g[k] - exact) < 4 * err[k], "two disks, delta = %g: g = %.4f "
		              "+- %.4f in [%g, %g), exact %.4f: the chain does not sample the "
		              "allowed configurations uniformly", delta, g[k], err[k],
		              hist->range[k], hist->range[k + 1], exact);
	}
	gsl_histogram_free(hist);
	lz_hdmc_free(h);
}

LZ_TEST(hdmc_two_disks_sample_the_allowed_area_uniformly)
{
	/* Detailed balance makes every allowed configuration equally likely. For two disks
	 * the separation is then uniform over the box minus the excluded disk of area π,
	 * so g = A/(A - π) exactly for σ <= r <= L/2, and 0 below σ. With δ = L/2 a move
	 * lands anywhere; with δ = 0.5 the disks creep, around each other and through the
	 * periodic boundary, and the same must come out. */
	gsl_rng *r = lz_test_rng(5);
	two_disks(r, 0, 10000);
	two_disks(r, 0.5, 50000);
	gsl_rng_free(r);
}
END_TEST

/* The overlap area of two disks of radius σ = 1 at distance r < 2. */
static double lens_area(double r)
{
	return r >= 2 ? 0 : 2 * acos(r / 2) - (r / 2) * sqrt(4 - r * r);
}

/* Its average over the annulus [r1, r2), area weighted (midpoint rule, 200 strips). */
static double lens_avg(double r1, double r2)
{
	double s = 0, w = 0, dr = (r2 - r1) / 200;
	for (int i = 0; i < 200; i++) {
		double r = r1 + (i + 0.5) * dr;
		s += lens_area(r) * r;
		w += r;
	}
	return s / w;
}

LZ_TEST(hdmc_low_density_gr)
{
	/* η = 0.02: g = 0 inside σ and 1 + ρ·(lens area of the two exclusion disks) + O(ρ²)
	 * outside, the second-virial term — 3 % at contact, 0 beyond 2σ. */
	gsl_rng *r = lz_test_rng(9);
	lz_hdmc *h = lz_hdmc_alloc(50, 0.02);
	ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
	lz_hdmc_tune(h, r, 500, 0.4);
	static const double edges[] = {0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0};
	gsl_histogram *hist = gsl_histogram_alloc(6);
	ck_assert(hist != NULL && gsl_histogram_set_ranges(hist, edges, 7) == 0);
	double g[6], err[6], rho = (double)h->n / (h->side * h->side);
	gr_blocks(h, r, hist, 1000, g, err);
	ck_assert_msg(g[0] == 0 && g[1] == 0, "g inside sigma must be 0: %g, %g", g[0], g[1]);
	for (size_t k = 2; k < 6; k++) {
		double expect = 1 + rho * lens_avg(hist->range[k], hist->range[k + 1]);
		ck_assert_msg(err[k] < 0.01, "block error %g too large for a test", err[k]);
		ck_assert_msg(fabs(g[k] - expect) < 4 * err[k], "eta = 0.02: g = %.4f +- %.4f in "
		              "[%g, %g), expected %.4f (1 + second-virial term)", g[k], err[k],
		              hist->range[k], hist->range[k + 1], expect);
	}
	gsl_histogram_free(hist);
	gsl_rng_free(r);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_contact_pressure_at_eta_0_3)
{
	/* Z = 1 + 2η g(σ+) against Z_ref(0.3) = 2.06326 ± 1e-4 (resummed virial series,
	 * datasets/reference/hard-disks.csv). This run (N = 100, 20000 sweeps, g every 5, bins
	 * of 0.01σ, ln g fitted on [1, 1.1]) was repeated with 24 seeds: Z = 2.0644 ±
	 * 0.0018 (mean), run-to-run standard deviation 0.0087 — so the fit and N = 100 add
	 * no visible bias. The tolerance 0.035 is 4 of those standard deviations: purely
	 * statistical. */
	gsl_rng *r = lz_test_rng(2024);
	lz_hdmc *h = lz_hdmc_alloc(100, 0.3);
	ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
	lz_hdmc_tune(h, r, 1000, 0.4);
	gsl_histogram *hist = hist_uniform(150, 0.0, 1.5);
	unsigned long nconf = 0;
	for (int s = 1; s <= 20000; s++) {
		lz_hdmc_sweep(h, r);
		if (s % 5 == 0 && lz_hdmc_gr_add(h, hist) == LZ_OK)
			nconf++;
	}
	double g[150], g0, err;
	ck_assert(lz_hdmc_gr(h, hist, nconf, g) == LZ_OK);
	ck_assert_msg(lz_hdmc_contact(hist, g, 0.1, &g0, &err) == LZ_OK, "%s",
	              lz_error_message());
	double z = 1 + 2 * 0.3 * g0;
	lz_ref ref = lz_test_reference("hard-disks.csv", "Z", "2", "eta=0.30");
	ck_assert_msg(fabs(z - ref.value) < 0.035 + ref.err, "eta = 0.3: Z = 1 + 2 eta g(sigma+) "
	              "= %.4f (g(sigma+) = %.4f +- %.4f), the hard-disk equation of state gives "
	              "%.5f; tolerance 0.035 (4 standard deviations)", z, g0, err, ref.value);
	ck_assert_int_eq(lz_hdmc_contact(hist, g, 0.01, &g0, &err), LZ_EDOM);
	ck_assert_int_eq(lz_hdmc_contact(hist, g, -1, &g0, &err), LZ_EINVAL);
	ck_assert(lz_hdmc_tune(h, r, 10, 1.5) == -1);
	ck_assert_msg(strstr(lz_error_message(), "1.5"), "%s", lz_error_message());
	gsl_histogram_free(hist);
	gsl_rng_free(r);
	lz_hdmc_free(h);
}
END_TEST

LZ_TEST(hdmc_same_seed_same_chain)
{
	double x[2][40];
	for (int run = 0; run < 2; run++) {
		gsl_rng *r = lz_test_rng(42);
		lz_hdmc *h = lz_hdmc_alloc(20, 0.4);
		ck_assert(h != NULL && lz_hdmc_place(h) == LZ_OK);
		lz_hdmc_tune(h, r, 50, 0.4);
		for (int s = 0; s < 100; s++)
			lz_hdmc_sweep(h, r);
		ck_assert_msg(h->moves == 150 * 20, "%llu moves offered in 150 sweeps of 20 disks, "
		              "expected 3000", (unsigned long long)h->moves);
		memcpy(x[run], h->x, sizeof x[run]);
		gsl_rng_free(r);
		lz_hdmc_free(h);
	}
	ck_assert_msg(memcmp(x[0], x[1], sizeof x[0]) == 0, "the same seed gave two different "
	              "chains");
}
END_TEST
