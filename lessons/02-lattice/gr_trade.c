/* gr_trade — lesson 02, the trade (§8, open question 4): lattice resolution against
 * g(r) error against cost, for hard disks at packing η ≈ 0.4.
 *
 * The reference is off the lattice: N hard disks in continuous space, Metropolis
 * Monte Carlo (lz/hdmc.h), its g(r) in fine bins of σ/96 with error bars from
 * NBLOCK consecutive blocks of the chain, and its contact value g(σ+), fitted, turned
 * into the pressure Z = 1 + 2η g(σ+) and checked against the hard-disk equation of
 * state (Z_ref(0.4) = 2.8293 from the resummed virial series, read from
 * datasets/reference/hard-disks.csv; the small step from 0.4 to the η actually run is
 * taken from Henderson's Z_H, whose slope is right to well below the error here).
 *
 * The lattice runs: the same N random walkers (lz/walk.h) of radius R = 3, 6, 12, 24
 * on the triangular lattice (sheared, 6 directions). The box side is fixed by the
 * radius, L = 128 R / 3 = 128, 256, 512, 1024 — powers of two with L/R constant — and N
 * is the count nearest to η = 0.4 there, 201 for every R (η = 0.40053); the reference
 * runs at that same N and η, so finite-size effects are the same on both sides. A
 * lattice step is σ/(2R), and a random walk covers a distance in σ in a number of
 * steps ∝ (distance/step)²: the sweeps are scaled ∝ R² (R = 24 runs 64 times the
 * sweeps of R = 3), so that every run covers the same physical diffusion. Only the sweeps are timed
 * (CPU seconds: the machine may run other jobs), not the g(r) sampling.
 *
 * The error: shell k of the lattice g is [k, k+1) lattice units = [k, k+1)/(2R) σ,
 * exactly 48/R fine reference bins, so the reference averaged over the shell (area
 * weighted: total pairs over total ideal pairs) is a sum, not an interpolation. The
 * error of a run is the rms over its shells in [σ, 2.5σ) of lattice g minus that
 * average, for the corrected g (lz_gr_result, pairs over lattice points) and the raw
 * one (pairs over exact area); the statistical floor is the rms of the two error bars
 * combined, which the error cannot go below however good the lattice. Thinner shells
 * hold fewer pairs, so at the same physical run length the floor grows, roughly like
 * √R; the
 * coarse error joins each run's shells into the σ/6 shells of R = 3 first (pairs over
 * lattice points, again exact), so that the noise is alike at every R and what is
 * left is the lattice's own error. The effective packing says where that comes from:
 * a lattice disk excludes fewer sites than the area of a true disk of the same σ.
 *
 * Checks: the reference has no overlaps and its contact Z is within 3 error bars of
 * the equation of state; no walker overlaps; the coarse error at R = 24 is below that
 * at R = 3, and (full size only: at the demo size R = 24 is noise-limited) so is the
 * per-shell error.
 *
 * Usage: gr_trade OUTDIR [--quick]
 * Writes OUTDIR/gr_ref.dat, gr_lattice.dat, gr_trade.dat and gr_trade.json.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_histogram.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/gr.h"
#include "lz/hdmc.h"
#include "lz/lattice.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/reference.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/walk.h"

#define SEED 20024u           /* fixed: the lesson quotes the numbers of this run */
#define ETA 0.4               /* the packing asked for */
#define KIND LZ_LATTICE_TRIANGULAR
#define NR 4                  /* radii */
#define NBLOCK 8              /* blocks for the error bars */
#define FINE 96               /* reference bins per σ: every shell edge k/(2R) is one */
#define RMAX 3                /* g(r) up to 3 σ */
#define NFINE (RMAX * FINE)
#define ERR_HI 2.5            /* the error is measured on [1, ERR_HI) σ */
#define CONTACT_WIDTH 0.1     /* ln g fitted on [1, 1.1] σ for g(σ+) */
#define NSIGMA 3.0            /* "within its statistical error": 3 error bars */
#define MAXSH (2 * RMAX * 24) /* lattice shells up to 3σ at the largest R */

static const int radius[NR] = {3, 6, 12, 24};
/* The other lattices, compared at R = 6 with OTHER_N disks in a box of 256² (packing
 * 0.4004, the same as the triangular runs; the reference has 201 disks, a finite-size
 * difference of order 1/N, far below the errors measured). */
#define NOTHER 2
#define OTHER_N 232
static const lz_lattice_kind other_kind[NOTHER] = {LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE8};

/* How long everything runs: sweeps at R = 3 (× (R/3)² at R) and of the reference. */
typedef struct {
	unsigned long eq3, prod3;        /* lattice equilibration and production, R = 3 */
	unsigned long ref_tune, ref_block;  /* reference: tuning, sweeps per block */
} sizes;

static const sizes full = {200, 1200, 500, 4000};
static const sizes quick = {16, 64, 200, 250};

#define REF_EVERY 5      /* reference sweeps between g(r) samples */
#define LAT_EVERY3 2     /* lattice sweeps between samples at R = 3, × (R/3)² */

/* The off-lattice reference. */
typedef struct {
	size_t n;
	double eta;
	double g[NBLOCK][NFINE];   /* g of each block, fine bins */
	double gm[NFINE], ge[NFINE];  /* mean and its error over the blocks */
	double z[NBLOCK];          /* Z from each block's contact value */
	double zm, ze, zexp;       /* mean, error, and the equation of state at eta */
	double zexp_err;           /* the uncertainty of zexp */
	double acceptance, delta, seconds;
	size_t overlaps;
	gsl_histogram *hist;       /* the bin edges (and the last block's counts) */
} reference;

/* One lattice run at radius R. */
typedef struct {
	lz_lattice_kind kind;
	int R;
	int64_t side;
	double eta, acceptance, seconds, steps_per_s;
	double eta_eff;  /* the packing of disks as large as the lattice's excluded region */
	unsigned long sweeps;
	int nsh;                       /* shells 0 .. nsh - 1: up to 3σ */
	double corr[NBLOCK][MAXSH], raw[NBLOCK][MAXSH];
	double cm[MAXSH], ce[MAXSH], rm[MAXSH];  /* corrected mean, error; raw mean */
	double ref[MAXSH], referr[MAXSH];        /* the reference over the same shells */
	uint64_t count[MAXSH];                   /* lattice points per shell */
	double err_corr, err_raw, floor;         /* rms over shells in [1, ERR_HI) σ */
	double err_coarse;  /* the same on the shells of R = 3, [1 + j/6, 1 + (j+1)/6) σ */
	size_t overlaps;
} lattice_run;

/* Henderson's Z_H(η) = (1 + η²/8)/(1 - η)² for hard disks. */
static double z_henderson(double eta)
{
	return (1 + eta * eta / 8) / ((1 - eta) * (1 - eta));
}

/* Mean and standard error of the NBLOCK values a[0], a[stride], ... */
static void block_stats(const double *a, size_t stride, double *mean, double *err)
{
	*mean = gsl_stats_mean(a, stride, NBLOCK);
	*err = gsl_stats_sd_m(a, stride, NBLOCK, *mean) / sqrt(NBLOCK);
}

/* The area-weighted average of g over the fine bins [i0, i1) of hist. */
static double shell_avg(const gsl_histogram *hist, const double *g, size_t i0, size_t i1)
{
	double sum = 0, area = 0;
	for (size_t i = i0; i < i1; i++) {
		double a = hist->range[i + 1] * hist->range[i + 1] - hist->range[i] * hist->range[i];
		sum += g[i] * a;
		area += a;
	}
	return sum / area;
}

/* One block of the reference chain: sweeps, g sampled every REF_EVERY. */
static int ref_block(lz_hdmc *h, gsl_rng *rng, unsigned long sweeps, reference *ref, int b)
{
	gsl_histogram_reset(ref->hist);
	unsigned long nconf = 0;
	int status = LZ_OK;
	for (unsigned long s = 0; s + REF_EVERY <= sweeps && status == LZ_OK; s += REF_EVERY) {
		double t0 = lz_cpu_now();
		for (int k = 0; k < REF_EVERY; k++)
			lz_hdmc_sweep(h, rng);
		ref->seconds += lz_cpu_now() - t0;
		status = lz_hdmc_gr_add(h, ref->hist);
		nconf++;
	}
	double g0 = NAN, gerr;
	if (status == LZ_OK)
		status = lz_hdmc_gr(h, ref->hist, nconf, ref->g[b]);
	if (status == LZ_OK)
		status = lz_hdmc_contact(ref->hist, ref->g[b], CONTACT_WIDTH, &g0, &gerr);
	ref->z[b] = 1 + 2 * ref->eta * g0;
	return status;
}

/* The reference at n disks and packing eta, with its block statistics. */
static int run_reference(size_t n, double eta, const sizes *sz, gsl_rng *rng, reference *ref)
{
	int status = LZ_ENOMEM;
	lz_hdmc *h = lz_hdmc_alloc(n, eta);
	ref->n = n;
	ref->eta = eta;
	ref->hist = gsl_histogram_alloc(NFINE);
	if (!h || !ref->hist) {
		if (h)
			lz_error(LZ_ENOMEM, "no memory for a histogram of %d bins", NFINE);
		goto out;
	}
	gsl_histogram_set_ranges_uniform(ref->hist, 0.0, RMAX);
	if ((status = lz_hdmc_place(h)) != LZ_OK)
		goto out;
	lz_hdmc_tune(h, rng, sz->ref_tune, 0.4);
	uint64_t moves = h->moves, accepted = h->accepted;
	for (int b = 0; b < NBLOCK; b++)
		if ((status = ref_block(h, rng, sz->ref_block, ref, b)) != LZ_OK)
			goto out;
	ref->acceptance = (double)(h->accepted - accepted) / (double)(h->moves - moves);
	ref->delta = h->delta;
	ref->overlaps = lz_hdmc_overlaps(h);
	for (size_t i = 0; i < NFINE; i++)
		block_stats(&ref->g[0][i], NFINE, &ref->gm[i], &ref->ge[i]);
	block_stats(ref->z, 1, &ref->zm, &ref->ze);
	lz_ref z;  /* Z_ref at ETA (datasets/reference/hard-disks.csv), carried to eta */
	if ((status = lz_reference("hard-disks.csv", "Z", "2", "eta=0.40", &z)) != LZ_OK)
		goto out;
	ref->zexp = z.value * z_henderson(eta) / z_henderson(ETA);
	ref->zexp_err = z.err;
out:
	lz_hdmc_free(h);
	return status;
}

/* Sweeps of w, timed (CPU seconds added to *seconds). */
static void timed_sweeps(lz_walk *w, gsl_rng *rng, unsigned long sweeps, double *seconds)
{
	double t0 = lz_cpu_now();
	for (unsigned long s = 0; s < sweeps; s++)
		lz_walk_sweep(w, rng);
	*seconds += lz_cpu_now() - t0;
}

/* Production of one lattice run: NBLOCK blocks of g, each its own accumulator. */
static int lattice_blocks(lz_walk *w, gsl_rng *rng, unsigned long per_block,
                          unsigned long every, lattice_run *lr)
{
	for (int b = 0; b < NBLOCK; b++) {
		lz_gr *g = lz_gr_alloc(lr->kind, lr->side, lr->nsh, w->n);
		if (!g)
			return LZ_ENOMEM;
		int status = LZ_OK;
		for (unsigned long s = 0; s < per_block && status == LZ_OK; s += every) {
			timed_sweeps(w, rng, every, &lr->seconds);
			status = lz_gr_add_config(g, w->box, w->r);
		}
		if (status == LZ_OK)
			status = lz_gr_result(g, lr->raw[b], lr->corr[b]);
		for (int k = 0; k < lr->nsh; k++)
			lr->count[k] = g->lattice[k];
		lz_gr_free(g);
		if (status != LZ_OK)
			return status;
	}
	return LZ_OK;
}

/* The rms error of the corrected g on the common grid of the R = 3 shells over
 * [1, ERR_HI) σ: R/3 shells of the run per coarse bin, joined by their lattice
 * points (pairs over expected pairs), against the reference over the same bin. The
 * noise is then about the same at every R, and what is left is the lattice's own. */
static double coarse_error(const lattice_run *lr, const reference *ref)
{
	int per = lr->R / 3, nbin = (int)((ERR_HI - 1) * 6 + 0.5);
	double s2 = 0;
	for (int j = 0; j < nbin; j++) {
		double pairs = 0, points = 0;
		for (int k = 2 * lr->R + j * per; k < 2 * lr->R + (j + 1) * per; k++) {
			pairs += lr->cm[k] * (double)lr->count[k];
			points += (double)lr->count[k];
		}
		size_t f0 = (size_t)(FINE + j * FINE / 6);
		double d = pairs / points - shell_avg(ref->hist, ref->gm, f0, f0 + FINE / 6);
		s2 += d * d;
	}
	return sqrt(s2 / nbin);
}

/* The error figures of a lattice run against the reference. */
static void lattice_errors(lattice_run *lr, const reference *ref)
{
	size_t per = FINE / (size_t)(2 * lr->R);  /* fine bins per shell */
	double s_corr = 0, s_raw = 0, s_floor = 0;
	int count = 0;
	for (int k = 0; k < lr->nsh; k++) {
		double blk[NBLOCK], raw_err;
		block_stats(&lr->corr[0][k], MAXSH, &lr->cm[k], &lr->ce[k]);
		block_stats(&lr->raw[0][k], MAXSH, &lr->rm[k], &raw_err);
		for (int b = 0; b < NBLOCK; b++)
			blk[b] = shell_avg(ref->hist, ref->g[b], (size_t)k * per, (size_t)(k + 1) * per);
		block_stats(blk, 1, &lr->ref[k], &lr->referr[k]);
		if (k >= 2 * lr->R && k < (int)(ERR_HI * 2 * lr->R)) {
			double dc = lr->cm[k] - lr->ref[k], dr = lr->rm[k] - lr->ref[k];
			s_corr += dc * dc;
			s_raw += dr * dr;
			s_floor += lr->ce[k] * lr->ce[k] + lr->referr[k] * lr->referr[k];
			count++;
		}
	}
	lr->err_coarse = coarse_error(lr, ref);
	lr->err_corr = sqrt(s_corr / count);
	lr->err_raw = sqrt(s_raw / count);
	lr->floor = sqrt(s_floor / count);
}

/* A lattice disk of radius R keeps every other centre off the sites at d² < (2R)²:
 * fewer of them than the continuum disk of radius 2R covers, so it acts like a
 * slightly smaller disk. The packing of disks with that excluded area (a quarter of
 * it each). O(R²). */
static double effective_packing(lz_lattice_kind kind, int R, int64_t side, size_t n)
{
	int64_t excluded = 0, s2 = 4 * (int64_t)R * R;
	for (int32_t x = -3 * R; x <= 3 * R; x++)
		for (int32_t y = -3 * R; y <= 3 * R; y++)
			excluded += lz_lattice_dist2(kind, x, y, 0) < s2;
	return (double)n * (double)excluded / (4.0 * (double)side * (double)side);
}

/* One lattice and radius in a box of side L: place, equilibrate, produce, compare. */
static int run_lattice(lz_lattice_kind kind, int R, int64_t side, size_t n, const sizes *sz,
                       gsl_rng *rng, const reference *ref, lattice_run *lr)
{
	unsigned long scale = (unsigned long)(R / 3) * (unsigned long)(R / 3);
	unsigned long every = LAT_EVERY3 * scale, per_block = sz->prod3 * scale / NBLOCK;
	lr->kind = kind;
	lr->R = R;
	lr->side = side;
	lr->nsh = 2 * RMAX * R;
	lr->eta = lz_walk_packing(kind, lr->side, R, n);
	lr->eta_eff = effective_packing(kind, R, lr->side, n);
	lz_walk *w = lz_walk_alloc(kind, lr->side, R, n, LZ_WALK_RANDOM);
	if (!w)
		return LZ_EINVAL;
	int status = lz_walk_place(w, rng, 0);
	if (status == LZ_OK) {
		timed_sweeps(w, rng, sz->eq3 * scale, &lr->seconds);
		uint64_t moves = w->moves, accepted = w->accepted;
		status = lattice_blocks(w, rng, per_block, every, lr);
		lr->acceptance = (double)(w->accepted - accepted) / (double)(w->moves - moves);
		lr->sweeps = sz->eq3 * scale + NBLOCK * ((per_block + every - 1) / every) * every;
		lr->steps_per_s = (double)n * (double)lr->sweeps / lr->seconds;
		lr->overlaps = lz_walk_overlaps(w);
	}
	lz_walk_free(w);
	if (status == LZ_OK)
		lattice_errors(lr, ref);
	return status;
}

static int write_ref(lz_lesson *L, const reference *ref)
{
	static const char *names[] = {"r_lo", "r_hi", "r", "g", "g_err"};
	static const char *units[] = {"sigma", "sigma", "sigma", "", ""};
	lz_data *d = lz_lesson_data(L, "gr_ref.dat", "g(r) of hard disks off the lattice "
	                            "(Metropolis MC), mean and standard error over blocks", 5,
	                            names, units);
	if (!d)
		return LZ_EIO;
	for (size_t i = 0; i < NFINE; i++) {
		double lo = ref->hist->range[i], hi = ref->hist->range[i + 1];
		double row[5] = {lo, hi, (lo + hi) / 2, ref->gm[i], ref->ge[i]};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

static int write_lattice(lz_lesson *L, const lattice_run *lr)
{
	static const char *names[] = {"R", "k", "r", "g_corrected", "g_corrected_err", "g_raw",
	                              "g_ref_shell", "g_ref_shell_err"};
	static const char *units[] = {"lattice", "shell", "sigma", "", "", "", "", ""};
	lz_data *d = lz_lesson_data(L, "gr_lattice.dat", "g(r) of lattice walkers by shell "
	                            "k <= r < k+1 (r at the shell centre), and the reference "
	                            "averaged over the same shell", 8, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < NR; i++)
		for (int k = 0; k < lr[i].nsh; k++) {
			double row[8] = {lr[i].R, k, (k + 0.5) / (2 * lr[i].R), lr[i].cm[k], lr[i].ce[k],
			                 lr[i].rm[k], lr[i].ref[k], lr[i].referr[k]};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

static int write_trade(lz_lesson *L, const lattice_run *lr)
{
	static const char *names[] = {"R", "error_corrected", "error_raw", "stat_floor",
	                              "seconds", "atomsteps_per_s", "error_coarse", "sweeps",
	                              "acceptance", "g_contact_shell", "g_ref_contact_shell",
	                              "eta_effective"};
	static const char *units[] = {"lattice", "", "", "", "s", "1/s", "", "", "", "", "", ""};
	lz_data *d = lz_lesson_data(L, "gr_trade.dat", "lattice resolution R against g(r) "
	                            "error (rms over shells in [1, 2.5) sigma) against CPU "
	                            "seconds of the sweeps", 12, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < NR; i++) {
		int c = 2 * lr[i].R;  /* the contact shell [σ, σ + σ/(2R)) */
		double row[12] = {lr[i].R, lr[i].err_corr, lr[i].err_raw, lr[i].floor,
		                  lr[i].seconds, lr[i].steps_per_s, lr[i].err_coarse,
		                  (double)lr[i].sweeps, lr[i].acceptance, lr[i].cm[c], lr[i].ref[c],
		                  lr[i].eta_eff};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

static int write_json(lz_lesson *L, const reference *ref, const lattice_run *lr,
                      const lattice_run *other)
{
	lz_json *j = lz_lesson_json(L, "gr_trade.json");
	if (!j)
		return LZ_EIO;
	lz_json_int(j, "n", (long long)ref->n);
	lz_json_num(j, "packing", ref->eta);
	lz_json_str(j, "lattice", lz_lattice_name(KIND));
	lz_json_int(j, "seed", SEED);
	lz_json_err(j, "ref_z_contact", ref->zm, ref->ze);
	lz_json_num(j, "ref_z_expected", ref->zexp);
	lz_json_num(j, "ref_acceptance", ref->acceptance);
	for (int i = 0; i < NR; i++) {
		char key[64];
		snprintf(key, sizeof key, "error_corrected_R%d", lr[i].R);
		lz_json_num(j, key, lr[i].err_corr);
		snprintf(key, sizeof key, "error_raw_R%d", lr[i].R);
		lz_json_num(j, key, lr[i].err_raw);
		snprintf(key, sizeof key, "error_coarse_R%d", lr[i].R);
		lz_json_num(j, key, lr[i].err_coarse);
		snprintf(key, sizeof key, "stat_floor_R%d", lr[i].R);
		lz_json_num(j, key, lr[i].floor);
		snprintf(key, sizeof key, "seconds_R%d", lr[i].R);
		lz_json_num(j, key, lr[i].seconds);
	}
	double steps = 0, seconds = 0;  /* all pairs: the same cost per step at every R */
	for (int i = 0; i < NR; i++) {
		steps += (double)ref->n * (double)lr[i].sweeps;
		seconds += lr[i].seconds;
	}
	lz_json_num(j, "atomsteps_per_s", steps / seconds);
	for (int i = 0; i < NOTHER; i++) {
		char key[64];
		snprintf(key, sizeof key, "error_corrected_R6_%s", lz_lattice_name(other[i].kind));
		lz_json_num(j, key, other[i].err_corr);
	}
	return lz_json_end(j);
}

static void print_results(const reference *ref, const lattice_run *lr)
{
	printf("  reference: acceptance %.3f at delta = %.3f sigma, %.2f s of sweeps; contact "
	       "Z = %.4f +- %.4f (expected %.4f)\n", ref->acceptance, ref->delta, ref->seconds,
	       ref->zm, ref->ze, ref->zexp);
	printf("  %3s %5s %8s %7s %10s %10s %10s %10s %9s %12s %13s %7s\n", "R", "L", "sweeps",
	       "accept", "err corr", "err raw", "stat floor", "err coarse", "seconds",
	       "atom-steps/s", "g contact", "eta eff");
	for (int i = 0; i < NR; i++) {
		int c = 2 * lr[i].R;
		printf("  %3d %5lld %8lu %7.3f %10.4f %10.4f %10.4f %10.4f %9.2f %12.3g %6.3f/%.3f "
		       "%7.4f\n",
		       lr[i].R, (long long)lr[i].side, lr[i].sweeps, lr[i].acceptance,
		       lr[i].err_corr, lr[i].err_raw, lr[i].floor, lr[i].err_coarse, lr[i].seconds,
		       lr[i].steps_per_s,
		       lr[i].cm[c], lr[i].ref[c], lr[i].eta_eff);
	}
	printf("  (errors: rms over the shells in [1, %.1f) sigma of lattice g minus the "
	       "reference over the same shell; coarse: the same on the sigma/6 shells of R = 3; "
	       "g contact: lattice/reference in the first shell; eta eff: the packing of disks "
	       "whose area is a quarter of the lattice's excluded sites)\n", ERR_HI);
}

/* The three lattices at R = 6. */
static void print_others(const lattice_run *other, const lattice_run *tri)
{
	printf("  R = 6 on three lattices: %-11s %10s %10s %10s %9s %7s\n", "lattice",
	       "err corr", "err raw", "stat floor", "seconds", "eta eff");
	for (int i = 0; i <= NOTHER; i++) {
		const lattice_run *r = i < NOTHER ? &other[i] : tri;
		printf("  %26s %-11s %10.4f %10.4f %10.4f %9.2f %7.4f\n", "",
		       lz_lattice_name(r->kind), r->err_corr, r->err_raw, r->floor, r->seconds,
		       r->eta_eff);
	}
}

/* On every lattice the correction must help, and no move may create an overlap. */
static void checks_others(lz_lesson *L, const lattice_run *other)
{
	for (int i = 0; i < NOTHER; i++)
		printf("  %s, R = 6: no overlaps, corrected g nearer the reference than raw "
		       "(%.4f < %.4f): %s\n", lz_lattice_name(other[i].kind), other[i].err_corr,
		       other[i].err_raw, lz_lesson_check(L, other[i].overlaps == 0 &&
		                                         other[i].err_corr < other[i].err_raw));
}

static void checks(lz_lesson *L, const reference *ref, const lattice_run *lr)
{
	const lattice_run *lo = &lr[0], *hi = &lr[NR - 1];
	double dev = (ref->zm - ref->zexp) / hypot(ref->ze, ref->zexp_err);
	printf("  reference: no overlaps after %d blocks: %s\n", NBLOCK,
	       lz_lesson_check(L, ref->overlaps == 0));
	printf("  reference: contact Z = %.4f within %.0f error bars of %.4f (%+.1f): %s\n",
	       ref->zm, NSIGMA, ref->zexp, dev, lz_lesson_check(L, fabs(dev) < NSIGMA));
	size_t overlaps = 0;
	for (int i = 0; i < NR; i++)
		overlaps += lr[i].overlaps;
	printf("  lattice walkers: no overlaps at any R: %s\n", lz_lesson_check(L, overlaps == 0));
	printf("  lattice error on the sigma/6 grid at R = %d (%.4f) below R = %d (%.4f): %s\n",
	       hi->R, hi->err_coarse, lo->R, lo->err_coarse,
	       lz_lesson_check(L, hi->err_coarse < lo->err_coarse));
	/* On its own fine shells R = 24 is noise-limited: the demo size is too short. */
	if (!L->quick)
		printf("  corrected g error at R = %d (%.4f) below R = %d (%.4f): %s\n", hi->R,
		       hi->err_corr, lo->R, lo->err_corr,
		       lz_lesson_check(L, hi->err_corr < lo->err_corr));
}

int main(int argc, char **argv)
{
	static reference ref;
	static lattice_run lr[NR], other[NOTHER];
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	int64_t side3 = 128;
	size_t n = (size_t)lround(ETA * side3 * side3 * lz_lattice_cell_volume(KIND) / (9 * M_PI));
	double eta = lz_walk_packing(KIND, side3, 3, n);
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	if (!rng)
		return lz_lesson_error(&L);
	printf("gr_trade: N = %zu hard disks at packing %.5f; reference off the lattice, %d "
	       "blocks of %lu sweeps; random walkers on the %s lattice, R = 3 .. 24, %lu "
	       "sweeps x (R/3)^2; mt19937 seed %u\n", n, eta, NBLOCK, sz->ref_block,
	       lz_lattice_name(KIND), sz->eq3 + sz->prod3, SEED);
	int status = run_reference(n, eta, sz, rng->gsl, &ref);
	for (int i = 0; i < NR && status == LZ_OK; i++)
		status = run_lattice(KIND, radius[i], 128 * radius[i] / 3, n, sz, rng->gsl, &ref,
		                     &lr[i]);
	/* The square lattices at R = 6: a box of 256² holds 232 disks at the same packing. */
	for (int i = 0; i < NOTHER && status == LZ_OK; i++)
		status = run_lattice(other_kind[i], 6, 256, OTHER_N, sz, rng->gsl, &ref, &other[i]);
	lz_rng_free(rng);
	if (status != LZ_OK) {
		gsl_histogram_free(ref.hist);
		return lz_lesson_error(&L);
	}
	print_results(&ref, lr);
	print_others(other, &lr[1]);
	checks(&L, &ref, lr);
	checks_others(&L, other);
	status = write_ref(&L, &ref);
	gsl_histogram_free(ref.hist);
	if (status != LZ_OK || write_lattice(&L, lr) != LZ_OK || write_trade(&L, lr) != LZ_OK ||
	    write_json(&L, &ref, lr, other) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "off-lattice reference on the hard-disk equation of state, "
	                        "lattice g(r) error falls from R = 3 to R = 24");
}
