/* trade — lesson 05, experiment: THE TRADE of cost against accuracy. Event-driven hard spheres,
 * exact to round-off, against the obvious time-stepped simulation, which is wrong by
 * an amount that shrinks with the time step dt and costs more as it does.
 *
 * The time-stepped scheme, written here because it is what one writes first: move
 * every particle by v·dt; find the pairs closer than σ with the cell list of stage 04
 * (lz/cells.h: bin, link, lz_cells_pairs); for each such pair that approaches, swap the
 * normal components of the velocities (an elastic bounce along the line of centres)
 * and count the impulse in the virial; then push the two apart, half the overlap each,
 * along the line of centres. The bounce happens up to dt late, at a separation below
 * σ, and a pair can be pushed into a third particle: the pressure from the impulses
 * comes out wrong, and the particles overlap by about |Δv|·dt before anyone notices.
 *
 * Both start from the same melted configuration: N hard spheres at η = 0.3, where the
 * mean free time is about 0.1. Each runs the same simulated time, cut into BLOCKS
 * blocks for the error bars (lz_edmd_blocks_plan for the event-driven run). Error:
 * |Z - Z_ref| / Z_ref, Z_ref = 3.9840(5) (lz_edmd_z_reference); cost: CPU seconds per
 * unit of simulated time. The order of the time-stepped error in dt is fitted
 * (gsl_fit_linear on log-log, the dt whose error is below 3 error bars left out).
 *
 * Checks: the event-driven Z within 3 error bars (plus Z_ref's uncertainty) of Z_ref,
 * with overlaps at round-off (< 1e-10 σ); the time-stepped error falls as dt shrinks
 * (each smaller dt no worse than the larger one within 3 combined error bars, and the
 * smallest dt at least 5 times better than the largest).
 *
 * Usage: trade OUTDIR [--quick]
 * Writes OUTDIR/trade.dat, trade_ed.dat and trade.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/cells.h"
#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/reference.h"
#include "lz/output.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 5005u
#define DIM 3
#define ETA 0.3
#define BLOCKS 10
#define NSIGMA 3.0
#define NDT 7

static const double dt_of[NDT] = {0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001};

typedef struct {
	size_t n;
	double melt;      /* events per particle from the lattice */
	double time;      /* simulated time of every run */
	int ndt;          /* how many of dt_of */
} sizes;

static const sizes full = {4000, 40, 20, NDT};
static const sizes quick = {1000, 30, 10, NDT};

/* One time-stepped run. */
typedef struct {
	double dt, Z, Z_err, cpu_per_time;
	double overlaps;      /* overlapping pairs found per particle per step */
	double depth_mean;    /* their mean depth 1 - |r_ij|, σ */
	double depth_max;
	double T_drift;       /* |T_end/T_start - 1| (the bounces conserve it) */
} ts_result;

/* kT = 2 KE / (dim n) of the velocities v (3 per particle). */
static double temperature(const double *v, size_t n)
{
	double ke = 0;
	for (size_t i = 0; i < 3 * n; i++)
		ke += 0.5 * v[i] * v[i];
	return 2 * ke / (DIM * (double)n);
}

/* The nearest-image separation x_j - x_i in a periodic box of side L. */
static double separation(const double *x, uint32_t i, uint32_t j, double L, double dr[3])
{
	double d2 = 0;
	for (int a = 0; a < 3; a++) {
		dr[a] = x[3 * j + a] - x[3 * i + a];
		dr[a] -= L * rint(dr[a] / L);
		d2 += dr[a] * dr[a];
	}
	return sqrt(d2);
}

/* The time-stepped simulation from (r0, v0) for `time` with step dt. */
static int time_stepped(const double *r0, const double *v0, size_t n, double L, double dt,
                        double time, ts_result *res)
{
	double *x = malloc(3 * n * sizeof *x), *v = malloc(3 * n * sizeof *v);
	size_t cap = 4 * n;
	lz_pair *pairs = malloc(cap * sizeof *pairs);
	lz_cells *c = lz_cells_alloc(DIM, L, 1.0, 1, LZ_CELLS_ROW, n, 0);
	if (!x || !v || !pairs || !c) {
		free(x);
		free(v);
		free(pairs);
		lz_cells_free(c);
		return c ? lz_error(LZ_ENOMEM, "no memory for %zu particles", n) : LZ_EINVAL;
	}
	for (size_t i = 0; i < 3 * n; i++) {
		x[i] = r0[i];
		v[i] = v0[i];
	}
	double T = temperature(v, n);
	long steps = lround(time / dt), per_block = steps / BLOCKS;
	double Zb[BLOCKS], found = 0, depth_sum = 0, depth_max = 0, cpu = 0;
	int st = LZ_OK;
	for (int b = 0; b < BLOCKS && st == LZ_OK; b++) {
		double virial = 0, t0 = lz_cpu_now();
		for (long s = 0; s < per_block && st == LZ_OK; s++) {
			for (size_t k = 0; k < 3 * n; k++) {
				x[k] += v[k] * dt;
				x[k] -= L * floor(x[k] / L);
			}
			if ((st = lz_cells_bin_points(c, n, x)))
				break;
			lz_cells_link(c);
			size_t np;
			while ((np = lz_cells_pairs(c, x, 1.0, pairs, cap)) > cap) {
				lz_pair *more = realloc(pairs, 2 * np * sizeof *pairs);
				if (!more) {
					st = lz_error(LZ_ENOMEM, "no memory for %zu pairs", np);
					break;
				}
				pairs = more;
				cap = 2 * np;
			}
			for (size_t q = 0; q < np && st == LZ_OK; q++) {
				uint32_t i = pairs[q].i, j = pairs[q].j;
				double dr[3], d = separation(x, i, j, L, dr);
				if (d >= 1)  /* pushed apart by an earlier pair of this step */
					continue;
				found++;
				depth_sum += 1 - d;
				depth_max = fmax(depth_max, 1 - d);
				double k[3] = {dr[0] / d, dr[1] / d, dr[2] / d}, u = 0;
				for (int a = 0; a < 3; a++)
					u += (v[3 * j + a] - v[3 * i + a]) * k[a];
				if (u < 0) {  /* approaching: bounce, impulse u along k */
					for (int a = 0; a < 3; a++) {
						v[3 * i + a] += u * k[a];
						v[3 * j + a] -= u * k[a];
					}
					virial += d * -u;
				}
				for (int a = 0; a < 3; a++) {
					x[3 * i + a] -= 0.5 * (1 - d) * k[a];
					x[3 * j + a] += 0.5 * (1 - d) * k[a];
				}
			}
		}
		cpu += lz_cpu_now() - t0;
		Zb[b] = 1 + virial / (DIM * (double)n * T * (double)per_block * dt);
	}
	if (st == LZ_OK) {
		res->dt = dt;
		res->Z = gsl_stats_mean(Zb, 1, BLOCKS);
		res->Z_err = gsl_stats_sd(Zb, 1, BLOCKS) / sqrt(BLOCKS);
		res->cpu_per_time = cpu / ((double)per_block * BLOCKS * dt);
		res->overlaps = found / ((double)n * (double)per_block * BLOCKS);
		res->depth_mean = found > 0 ? depth_sum / found : 0;
		res->depth_max = depth_max;
		res->T_drift = fabs(temperature(v, n) / T - 1);
	}
	free(x);
	free(v);
	free(pairs);
	lz_cells_free(c);
	return st;
}

/* The melted start: e runs from the lattice; its state (synced) into r0, v0. */
static int start(lz_edmd *e, const sizes *sz, double *r0, double *v0)
{
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	int st = rng ? lz_edmd_place_lattice(e, rng) : LZ_ENOMEM;
	lz_rng_free(rng);
	if (st == LZ_OK)
		st = lz_edmd_run(e, (uint64_t)(sz->melt * (double)e->n), INFINITY);
	if (st)
		return st;
	lz_edmd_get(e, r0, v0);
	return LZ_OK;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	lz_ref z;  /* datasets/reference/hard-spheres.csv */
	if (lz_reference_at("hard-spheres.csv", "Z", "3", "eta", ETA, &z) != LZ_OK)
		return lz_lesson_error(&L);
	double zref = z.value, zref_err = z.err;
	printf("trade: %zu hard spheres at η = %g, %g time units per run in %d blocks, seed "
	       "%u; Z_ref = %.4f ± %g\n", sz->n, ETA, sz->time, BLOCKS, SEED, zref, zref_err);

	lz_edmd_params p = {DIM, sz->n, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	double *r0 = malloc(3 * sz->n * sizeof *r0), *v0 = malloc(3 * sz->n * sizeof *v0);
	lz_edmd_result ed;
	lz_edmd_plan plan = {UINT64_MAX, sz->time / BLOCKS, 0, NULL, NULL, 0};
	int st = e && r0 && v0 ? start(e, sz, r0, v0) : LZ_ENOMEM;
	if (st == LZ_OK)
		st = lz_edmd_blocks_plan(e, BLOCKS, &plan, &ed);
	double box = e ? e->L : 0;
	lz_edmd_free(e);
	if (st) {
		free(r0);
		free(v0);
		return lz_lesson_error(&L);
	}
	double ed_err = fabs(ed.Z - zref) / zref, ed_cost = ed.cpu_s / ed.time;
	printf("  event-driven: Z = %.4f ± %.4f, error %.2e, %.3g CPU s per time unit, %llu "
	       "collisions, max overlap %.2g σ, energy drift %.2g\n", ed.Z, ed.Z_err, ed_err,
	       ed_cost, (unsigned long long)ed.collisions, ed.max_overlap, ed.energy_rel_drift);

	ts_result ts[NDT];
	printf("  time-stepped:\n      dt        Z       ±    error   CPU s/time  overlaps/"
	       "particle/step  mean depth  max depth\n");
	for (int k = 0; k < sz->ndt; k++) {
		if (time_stepped(r0, v0, sz->n, box, dt_of[k], sz->time, &ts[k]) != LZ_OK) {
			free(r0);
			free(v0);
			return lz_lesson_error(&L);
		}
		printf("  %6g %8.4f %7.4f %8.2e %12.3g %22.3g %11.3g %10.3g\n", ts[k].dt, ts[k].Z,
		       ts[k].Z_err, fabs(ts[k].Z - zref) / zref, ts[k].cpu_per_time, ts[k].overlaps,
		       ts[k].depth_mean, ts[k].depth_max);
	}
	free(r0);
	free(v0);

	/* the order: log error against log dt, over the dt whose error is resolved */
	double lx[NDT], ly[NDT];
	size_t nfit = 0;
	for (int k = 0; k < sz->ndt; k++) {
		double err = fabs(ts[k].Z - zref);
		if (err > NSIGMA * hypot(ts[k].Z_err, zref_err)) {
			lx[nfit] = log(ts[k].dt);
			ly[nfit++] = log(err / zref);
		}
	}
	double c0 = NAN, c1 = NAN, cov00, cov01, cov11, sumsq;
	if (nfit >= 2)
		gsl_fit_linear(lx, 1, ly, 1, nfit, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
	printf("  time-stepped error ∝ dt^%.2f (fitted on %zu step sizes)\n", c1, nfit);

	static const char *names[] = {"dt", "Z", "Z_err", "rel_error", "rel_error_err",
	                              "cpu_per_time", "overlaps_per_particle_step",
	                              "depth_mean", "depth_max", "T_drift"};
	static const char *units[] = {"time", "", "", "|Z - Z_ref| / Z_ref", "",
	                              "CPU s per time unit", "", "σ", "σ", "relative"};
	lz_data *d = lz_lesson_data(&L, "trade.dat", "time-stepped hard spheres, η = 0.3: "
	                            "pressure error and overlaps against the step", 10, names,
	                            units);
	if (!d)
		return lz_lesson_error(&L);
	for (int k = 0; k < sz->ndt; k++) {
		double row[10] = {ts[k].dt, ts[k].Z, ts[k].Z_err, fabs(ts[k].Z - zref) / zref,
		                  ts[k].Z_err / zref, ts[k].cpu_per_time, ts[k].overlaps,
		                  ts[k].depth_mean, ts[k].depth_max, ts[k].T_drift};
		lz_data_row(d, row);
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	static const char *enames[] = {"Z", "Z_err", "rel_error", "rel_error_err",
	                               "cpu_per_time", "max_overlap", "energy_drift", "Z_ref"};
	static const char *eunits[] = {"", "", "|Z - Z_ref| / Z_ref", "", "CPU s per time unit",
	                               "σ", "relative", ""};
	d = lz_lesson_data(&L, "trade_ed.dat", "event-driven hard spheres, η = 0.3, the same "
	                   "start and run length", 8, enames, eunits);
	if (!d)
		return lz_lesson_error(&L);
	double erow[8] = {ed.Z, ed.Z_err, ed_err, ed.Z_err / zref, ed_cost, ed.max_overlap,
	                  ed.energy_rel_drift, zref};
	lz_data_row(d, erow);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	double ed_tol = NSIGMA * ed.Z_err + zref_err;
	printf("  event-driven |Z - Z_ref| = %.4f within %.4f (3 error bars + the reference's) "
	       "and max overlap %.2g < 1e-10 σ: %s\n", fabs(ed.Z - zref), ed_tol, ed.max_overlap,
	       lz_lesson_check(&L, fabs(ed.Z - zref) <= ed_tol && ed.max_overlap < 1e-10));
	int falls = 1, last = sz->ndt - 1;
	for (int k = 1; k < sz->ndt; k++)
		falls = falls && fabs(ts[k].Z - zref) <=
		        fabs(ts[k - 1].Z - zref) + NSIGMA * hypot(ts[k].Z_err, ts[k - 1].Z_err);
	double gain = fabs(ts[0].Z - zref) / fabs(ts[last].Z - zref);
	printf("  time-stepped error falls as dt shrinks (within 3 error bars), %.3g times "
	       "smaller at dt = %g than at dt = %g (at least 5): %s\n", gain, dt_of[last],
	       dt_of[0], lz_lesson_check(&L, falls && gain >= 5));

	lz_json *j = lz_lesson_json(&L, "trade.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", (long long)sz->n);
	lz_json_num(j, "Z_ref", zref);
	lz_json_err(j, "Z_event_driven", ed.Z, ed.Z_err);
	lz_json_num(j, "cpu_s_per_time_event_driven", ed_cost);
	lz_json_num(j, "max_overlap_event_driven", ed.max_overlap);
	lz_json_err(j, "Z_time_stepped_smallest_dt", ts[last].Z, ts[last].Z_err);
	lz_json_num(j, "smallest_dt", dt_of[last]);
	lz_json_num(j, "cpu_s_per_time_smallest_dt", ts[last].cpu_per_time);
	lz_json_num(j, "error_order_in_dt", c1);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "event-driven Z within its error bars; the time-stepped "
	                        "error falls with dt");
}
