/* gr — lesson 05, experiment: the off-lattice reference of stage 02, now exact. The
 * pair distribution g(r) of hard disks at η = 0.4 — the state that stage 02 measured
 * its lattice walkers against, N = 201 disks — from event-driven MD, against the
 * Metropolis Monte Carlo (lz/hdmc.h) that stage 02 used as its reference.
 *
 * Molecular dynamics and Monte Carlo sample the same equilibrium ensemble (every
 * non-overlapping configuration equally likely), so their g(r) must agree within the
 * noise — one by dynamics, the other by a random walk in configuration space. The
 * contact value g(σ+) sets the pressure, Z = 1 + 2η g(σ+) (datasets/reference/collision-identity.csv), and it is
 * measured three ways here:
 *   - from the histogram, extrapolated to r = σ (lz_hdmc_contact: a line through ln g
 *     over [1, 1.1] σ), for both the MC and the MD run;
 *   - from the MD pressure, g(σ+) = (Z - 1)/(2η) with Z from the collision impulses
 *     (lz_edmd_blocks_plan): exact, no histogram, no extrapolation;
 * and compared with Henderson's g_H = (1 - 7η/16)/(1 - η)² and with (Z_ref - 1)/(2η)
 * from the reference equation of state.
 *
 * Error bars: NBLOCK blocks of each run (standard error of the block means). g(r) is
 * sampled every MD_DT = 0.25 time units in MD (about one mean free time; at fixed times,
 * not after a count of events: see md_block) and every 5 sweeps in MC. The MD pressure
 * is measured in a second stretch of as many events (lz_edmd_blocks).
 *
 * Checks: MD's contact value (impulses) within 3 combined error bars of MC's
 * (histogram); MD's two routes (impulses, histogram) within 3 combined error bars;
 * MD's contact within 3 error bars, the reference's uncertainty and a finite-size
 * allowance (FINITE_N) of (Z_ref-1)/2η;
 * g(r) of MD and MC agree bin by bin: χ² per bin over [1, 3) σ below 2.
 *
 * Usage: gr OUTDIR [--quick]
 * Writes OUTDIR/gr.dat, gr_contact.dat and gr.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_histogram.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/hdmc.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/reference.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 5002u
#define N 201            /* stage 02's reference: 201 disks at η = 0.4 */
#define ETA 0.4
#define NBLOCK 8
#define PER_SIGMA 50     /* bins per σ: an edge at r = 1 exactly */
#define RMAX 3
#define NBIN (RMAX * PER_SIGMA)
#define CONTACT_WIDTH 0.1
#define MC_EVERY 5       /* MC sweeps between g(r) samples */
#define MD_DT 0.25       /* MD time between g(r) samples: about one mean free time */
#define NSIGMA 3.0
#define CHI2_MAX 2.0

/* The allowance, in g(σ+), for comparing N disks with the infinite fluid of Z_ref. A
 * periodic system of N particles with its total momentum fixed differs from N = ∞ by
 * terms of order 1/N (J. L. Lebowitz and J. K. Percus, Phys. Rev. 124, 1673 (1961));
 * their size: whether kT counts N or N - 1 kinetic degrees of freedom alone moves Z
 * by Z/N, here 0.014 (0.018 in g). */
#define FINITE_N(zref) ((zref) / (N * 2 * ETA))

typedef struct {
	unsigned long mc_tune, mc_block;  /* MC sweeps: tuning, per block */
	double md_melt;                   /* MD events per particle from the lattice */
	unsigned long md_samples;         /* MD g(r) samples per block, every N events */
} sizes;

static const sizes full = {500, 5000, 200, 3000};
static const sizes quick = {200, 400, 50, 500};

/* One method's g(r): per block, and their mean and error. */
typedef struct {
	double g[NBLOCK][NBIN], gm[NBIN], ge[NBIN];
	double contact[NBLOCK], cm, ce;   /* histogram contact value per block */
	double zm, ze;                    /* MD only: Z from the impulses */
	double pm, pe;                    /* MD only: contact from the pressure, (Z-1)/2η */
	double cpu, overlap;
} gr_run;

/* Mean and standard error of the NBLOCK values a[0], a[stride], ... */
static void block_stats(const double *a, size_t stride, double *mean, double *err)
{
	*mean = gsl_stats_mean(a, stride, NBLOCK);
	*err = gsl_stats_sd_m(a, stride, NBLOCK, *mean) / sqrt(NBLOCK);
}

static gsl_histogram *new_histogram(void)
{
	gsl_histogram *h = gsl_histogram_alloc(NBIN);
	if (!h) {
		lz_error(LZ_ENOMEM, "no memory for a histogram of %d bins", NBIN);
		return NULL;
	}
	double range[NBIN + 1];
	for (int k = 0; k <= NBIN; k++)
		range[k] = (double)k / PER_SIGMA;
	gsl_histogram_set_ranges(h, range, NBIN + 1);
	return h;
}

static void finish(gr_run *g)
{
	for (int k = 0; k < NBIN; k++)
		block_stats(&g->g[0][k], NBIN, &g->gm[k], &g->ge[k]);
	block_stats(g->contact, 1, &g->cm, &g->ce);
}

/* ---- Monte Carlo, stage 02's reference ---- */

static int monte_carlo(const sizes *sz, lz_rng *rng, gsl_histogram *h, gr_run *mc)
{
	lz_hdmc *d = lz_hdmc_alloc(N, ETA);
	int st = d ? lz_hdmc_place(d) : LZ_ENOMEM;
	double t0 = lz_cpu_now();
	if (st == LZ_OK && lz_hdmc_tune(d, rng->gsl, sz->mc_tune, 0.4) < 0)
		st = LZ_EINVAL;
	for (int b = 0; b < NBLOCK && st == LZ_OK; b++) {
		gsl_histogram_reset(h);
		unsigned long nconf = 0;
		for (unsigned long s = 0; s + MC_EVERY <= sz->mc_block && st == LZ_OK; s += MC_EVERY) {
			for (int k = 0; k < MC_EVERY; k++)
				lz_hdmc_sweep(d, rng->gsl);
			st = lz_hdmc_gr_add(d, h);
			nconf++;
		}
		double err;
		if (st == LZ_OK)
			st = lz_hdmc_gr(d, h, nconf, mc->g[b]);
		if (st == LZ_OK)
			st = lz_hdmc_contact(h, mc->g[b], CONTACT_WIDTH, &mc->contact[b], &err);
	}
	mc->cpu = lz_cpu_now() - t0;
	mc->overlap = d ? (double)lz_hdmc_overlaps(d) : 0;
	lz_hdmc_free(d);
	if (st == LZ_OK)
		finish(mc);
	return st;
}

/* ---- event-driven MD ---- */

/* g(r) of one block: `samples` configurations DT apart in time. Samples are taken at
 * fixed times, not after a number of events: right after an event the pair that just
 * collided sits at r = σ exactly, which would add about half a pair per sample to the
 * first bin — a few per cent of the contact value at N = 201. */
static int md_block(lz_edmd *e, unsigned long samples, gsl_histogram *h, gr_run *md, int b)
{
	gsl_histogram_reset(h);
	for (unsigned long s = 0; s < samples; s++) {
		int st = lz_edmd_run(e, UINT64_MAX, lz_edmd_time(e) + MD_DT);
		if (st == LZ_OK)
			st = lz_edmd_gr_add(e, RMAX, h);
		if (st)
			return st;
	}
	for (int k = 0; k < NBIN; k++)
		md->g[b][k] = lz_edmd_gr_value(e, h, (size_t)k, samples);
	double err;
	return lz_hdmc_contact(h, md->g[b], CONTACT_WIDTH, &md->contact[b], &err);
}

static int molecular_dynamics(const sizes *sz, lz_rng *rng, gsl_histogram *h, gr_run *md)
{
	lz_edmd_params p = {2, N, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	int st = e ? lz_edmd_place_lattice(e, rng) : LZ_EINVAL;
	double t0 = lz_cpu_now();
	if (st == LZ_OK)
		st = lz_edmd_run(e, (uint64_t)(sz->md_melt * N), INFINITY);
	for (int b = 0; b < NBLOCK && st == LZ_OK; b++)
		st = md_block(e, sz->md_samples, h, md, b);
	/* the pressure: as many events again, in blocks, with the guards */
	lz_edmd_result r;
	if (st == LZ_OK)
		st = lz_edmd_blocks(e, NBLOCK, (uint64_t)(sz->md_samples * N), &r);
	md->cpu = lz_cpu_now() - t0;
	lz_edmd_free(e);
	if (st)
		return st;
	finish(md);
	md->zm = r.Z;
	md->ze = r.Z_err;
	md->pm = (r.Z - 1) / (2 * ETA);
	md->pe = r.Z_err / (2 * ETA);
	md->overlap = r.max_overlap;
	return LZ_OK;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("gr: %d hard disks at η = %g (stage 02's reference state), g(r) in bins of σ/%d "
	       "to %d σ, %d blocks; MC %lu sweeps per block, MD %lu samples of g(r) per block "
	       "(every %g time units); seed %u\n", N, ETA, PER_SIGMA, RMAX, NBLOCK,
	       sz->mc_block, sz->md_samples, MD_DT, SEED);
	static gr_run mc, md;
	gsl_histogram *h = new_histogram();
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	int st = h && rng ? monte_carlo(sz, rng, h, &mc) : LZ_ENOMEM;
	if (st == LZ_OK)
		st = molecular_dynamics(sz, rng, h, &md);
	lz_rng_free(rng);
	if (st) {
		gsl_histogram_free(h);
		return lz_lesson_error(&L);
	}

	lz_ref z;  /* datasets/reference/hard-disks.csv */
	if (lz_reference_at("hard-disks.csv", "Z", "2", "eta", ETA, &z) != LZ_OK) {
		gsl_histogram_free(h);
		return lz_lesson_error(&L);
	}
	double zref = z.value;
	double g_ref = (zref - 1) / (2 * ETA), g_ref_err = z.err / (2 * ETA);
	double g_hend = (1 - 7 * ETA / 16) / ((1 - ETA) * (1 - ETA));
	printf("  contact value g(σ+):\n");
	printf("    MC, histogram        %.4f ± %.4f   (%.2f CPU s, overlaps %g)\n", mc.cm, mc.ce,
	       mc.cpu, mc.overlap);
	printf("    MD, histogram        %.4f ± %.4f   (%.2f CPU s, largest overlap %.2g σ)\n",
	       md.cm, md.ce, md.cpu, md.overlap);
	printf("    MD, impulses         %.4f ± %.4f   (Z = %.5f ± %.5f)\n", md.pm, md.pe, md.zm,
	       md.ze);
	printf("    (Z_ref - 1)/2η       %.4f ± %.4f   (Z_ref = %.4f, N = ∞)\n", g_ref, g_ref_err,
	       zref);
	printf("    Henderson            %.4f\n", g_hend);

	static const char *names[] = {"r", "g_md", "g_md_err", "g_mc", "g_mc_err"};
	static const char *units[] = {"σ (bin centre)", "", "", "", ""};
	lz_data *d = lz_lesson_data(&L, "gr.dat", "hard disks N = 201, η = 0.4: g(r) from "
	                            "event-driven MD and from Metropolis MC", 5, names, units);
	if (!d) {
		gsl_histogram_free(h);
		return lz_lesson_error(&L);
	}
	double chi2 = 0;
	int nchi = 0;
	for (int k = 0; k < NBIN; k++) {
		double r = 0.5 * (h->range[k] + h->range[k + 1]);
		double row[5] = {r, md.gm[k], md.ge[k], mc.gm[k], mc.ge[k]};
		lz_data_row(d, row);
		double var = md.ge[k] * md.ge[k] + mc.ge[k] * mc.ge[k];
		if (r > 1 && var > 0) {
			chi2 += (md.gm[k] - mc.gm[k]) * (md.gm[k] - mc.gm[k]) / var;
			nchi++;
		}
	}
	gsl_histogram_free(h);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	chi2 /= nchi;
	static const char *cnames[] = {"route", "g_contact", "err"};
	static const char *cunits[] = {"0 MD impulses, 1 MD hist, 2 MC hist, 3 Z_ref, 4 Henderson",
	                               "", ""};
	d = lz_lesson_data(&L, "gr_contact.dat", "the contact value g(σ+) of hard disks at "
	                   "η = 0.4, five ways", 3, cnames, cunits);
	if (!d)
		return lz_lesson_error(&L);
	double crow[5][3] = {{0, md.pm, md.pe}, {1, md.cm, md.ce}, {2, mc.cm, mc.ce},
	                     {3, g_ref, g_ref_err}, {4, g_hend, 0}};
	for (int k = 0; k < 5; k++)
		lz_data_row(d, crow[k]);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	double dev_mc = fabs(md.pm - mc.cm) / (NSIGMA * hypot(md.pe, mc.ce));
	double dev_routes = fabs(md.pm - md.cm) / (NSIGMA * hypot(md.pe, md.ce));
	double dev_ref = fabs(md.pm - g_ref) / (NSIGMA * md.pe + g_ref_err + FINITE_N(zref));
	printf("  MD contact (impulses) against MC's (histogram): %.4f apart, %.2f of 3 "
	       "combined error bars: %s\n", md.pm - mc.cm, dev_mc, lz_lesson_check(&L, dev_mc <= 1));
	printf("  MD contact, impulses against its histogram: %.4f apart, %.2f of 3 combined "
	       "error bars: %s\n", md.pm - md.cm, dev_routes, lz_lesson_check(&L, dev_routes <= 1));
	printf("  MD contact against (Z_ref - 1)/2η: %.4f apart, %.2f of 3 error bars + the "
	       "reference's + %.4f for N = %d against N = ∞: %s\n", md.pm - g_ref, dev_ref,
	       FINITE_N(zref), N, lz_lesson_check(&L, dev_ref <= 1));
	printf("  g(r) of MD and MC bin by bin over (1, %d) σ: χ² per bin %.2f (below %.0f): %s\n",
	       RMAX, chi2, CHI2_MAX, lz_lesson_check(&L, chi2 < CHI2_MAX));

	lz_json *j = lz_lesson_json(&L, "gr.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", N);
	lz_json_num(j, "eta", ETA);
	lz_json_err(j, "contact_md_impulses", md.pm, md.pe);
	lz_json_err(j, "contact_md_histogram", md.cm, md.ce);
	lz_json_err(j, "contact_mc_histogram", mc.cm, mc.ce);
	lz_json_num(j, "contact_from_Z_ref", g_ref);
	lz_json_num(j, "contact_henderson", g_hend);
	lz_json_num(j, "chi2_per_bin_md_mc", chi2);
	lz_json_num(j, "cpu_s_md", md.cpu);
	lz_json_num(j, "cpu_s_mc", mc.cpu);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "MD and MC contact values and g(r) agree within errors");
}
