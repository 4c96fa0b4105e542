/* edmd_obs.c — what is measured on an event-driven run (lz/edmd_obs.h): the pressure
 * and the collision rate from the counters, block averages with the guards, and on
 * request g(r) and the mean-square displacement. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_statistics_double.h>

#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/reference.h"
#include "lz/timer.h"

/* The guards of lz_edmd_blocks (header). */
#define OVERLAP_GUARD 1e-10
#define ENERGY_GUARD 1e-8

lz_edmd_sample lz_edmd_measure(const lz_edmd *e)
{
	lz_edmd_sample s = {
		.time = lz_edmd_time(e) - e->t_reset,
		.T = lz_edmd_temperature(e),
		.events = e->events,
		.collisions = e->collisions,
		.crossings = e->crossings,
		.bounces = e->bounces,
		.stale = e->stale,
		.rebuilds = e->rebuilds,
	};
	double n = (double)e->n, d = e->dim;
	if (s.time > 0) {
		s.gamma = 2.0 * (double)e->collisions / (n * s.time);
		s.Z = s.T > 0 ? 1 + e->virial / (d * n * s.T * s.time) : NAN;
		s.Z_gamma = s.T > 0 ? 1 + sqrt(M_PI / s.T) * s.gamma / (2 * d) : NAN;
	} else {
		s.gamma = s.Z = s.Z_gamma = NAN;
	}
	s.free_time = e->collisions > 0 ? 1 / s.gamma : INFINITY;
	return s;
}

/* ---- blocks ---- */

/* The block values, kept for the standard errors. */
typedef struct {
	double *Z, *gamma, *Zg, *T;
	double E0, P0[3];
} series;

/* Mean and standard error of x[0 .. k-1] (the error NaN for one block). */
static void mean_err(const double *x, size_t k, double *mean, double *err)
{
	*mean = k > 0 ? gsl_stats_mean(x, 1, k) : NAN;
	*err = k > 1 ? gsl_stats_sd(x, 1, k) / sqrt((double)k) : NAN;
}

/* r's means and errors over the first k blocks. */
static void finish(const series *s, size_t k, lz_edmd_result *r)
{
	r->blocks = k;
	mean_err(s->Z, k, &r->Z, &r->Z_err);
	mean_err(s->gamma, k, &r->gamma, &r->gamma_err);
	mean_err(s->Zg, k, &r->Z_gamma, &r->Z_gamma_err);
	mean_err(s->T, k, &r->T, &r->T_err);
	r->free_time = r->gamma > 0 ? 1 / r->gamma : INFINITY;
}

/* The guards at a block end: overlaps, energy and momentum against the start. */
static int guard(const lz_edmd *e, const series *s, lz_edmd_result *r)
{
	uint32_t a = 0, b = 0;
	double over = lz_edmd_max_overlap(e, &a, &b);
	double E = lz_edmd_energy(e), P[3], dP = 0;
	lz_edmd_momentum(e, P);
	for (int x = 0; x < 3; x++)
		dP += (P[x] - s->P0[x]) * (P[x] - s->P0[x]);
	double drift = fabs(E / s->E0 - 1);
	r->max_overlap = fmax(r->max_overlap, over);
	r->energy_rel_drift = fmax(r->energy_rel_drift, drift);
	r->momentum_abs_drift = fmax(r->momentum_abs_drift, sqrt(dP));
	if (!isfinite(E))
		return lz_error(LZ_EPHYS, "the energy is %g at t = %.10g: a position or velocity "
		                "is no longer a number", E, lz_edmd_time(e));
	if (over > OVERLAP_GUARD)
		return lz_error(LZ_EPHYS, "particles %u and %u overlap by %.3g σ at t = %.10g "
		                "(guard %g): a collision was missed or carried out late", a, b,
		                over, lz_edmd_time(e), OVERLAP_GUARD);
	if (e->restitution == 1 && e->g == 0 && drift > ENERGY_GUARD)
		return lz_error(LZ_EPHYS, "the energy drifted by %.3g relative at t = %.10g "
		                "(guard %g): elastic collisions and free flight conserve it to "
		                "round-off", drift, lz_edmd_time(e), ENERGY_GUARD);
	return LZ_OK;
}

/* One block of the plan: run it in pieces of `every` events, or up to the fixed
 * observation times *t_obs (advanced here), with an observation after each but the
 * last; *cpu gets the CPU time of the runs. */
static int run_block(lz_edmd *e, const lz_edmd_plan *plan, double *t_obs, double *cpu)
{
	double t_stop = lz_edmd_time(e) + plan->duration;
	uint64_t left = plan->events;
	for (;;) {
		int timed = plan->interval > 0 && *t_obs < t_stop;
		uint64_t piece = !timed && plan->every && plan->every < left ? plan->every : left;
		uint64_t before = e->events;
		double t0 = lz_cpu_now();
		int st = lz_edmd_run(e, piece, timed ? *t_obs : t_stop);
		*cpu += lz_cpu_now() - t0;
		if (st)
			return st;
		uint64_t done = e->events - before;
		if (plan->events != UINT64_MAX)
			left -= done;
		if (left == 0 || (!timed && done < piece))  /* the count, or t_stop, is reached */
			return LZ_OK;
		if (timed)
			*t_obs += plan->interval;
		if (plan->observe && (st = plan->observe(e, plan->arg)))
			return st;
	}
}

int lz_edmd_blocks_plan(lz_edmd *e, size_t blocks, const lz_edmd_plan *plan,
                        lz_edmd_result *r)
{
	*r = (lz_edmd_result){0};
	if (blocks < 2)
		return lz_error(LZ_EINVAL, "blocks = %zu: an error bar needs at least 2 blocks",
		                blocks);
	if (plan->events == 0 || !(plan->duration > 0))
		return lz_error(LZ_EINVAL, "a block of %llu events and duration %g is empty",
		                (unsigned long long)plan->events, plan->duration);
	if (plan->events == UINT64_MAX && isinf(plan->duration))
		return lz_error(LZ_EINVAL, "a block needs a number of events or a duration");
	series s = {0};
	double *mem = malloc(4 * blocks * sizeof *mem);
	if (!mem)
		return lz_error(LZ_ENOMEM, "no memory for %zu blocks", blocks);
	s.Z = mem;
	s.gamma = mem + blocks;
	s.Zg = mem + 2 * blocks;
	s.T = mem + 3 * blocks;
	s.E0 = lz_edmd_energy(e);
	lz_edmd_momentum(e, s.P0);
	int st = LZ_OK;
	double t_obs = lz_edmd_time(e) + plan->interval;
	size_t done = 0;  /* blocks measured */
	while (done < blocks && st == LZ_OK) {
		lz_edmd_reset_counts(e);
		st = run_block(e, plan, &t_obs, &r->cpu_s);
		if (st)
			break;
		lz_edmd_sample b = lz_edmd_measure(e);
		s.Z[done] = b.Z;
		s.gamma[done] = b.gamma;
		s.Zg[done] = b.Z_gamma;
		s.T[done] = b.T;
		done++;
		r->time += b.time;
		r->events += b.events;
		r->collisions += b.collisions;
		r->crossings += b.crossings;
		r->bounces += b.bounces;
		r->stale += b.stale;
		r->rebuilds += b.rebuilds;
		st = guard(e, &s, r);
		if (st == LZ_OK && plan->observe)
			st = plan->observe(e, plan->arg);
	}
	finish(&s, done, r);
	free(mem);
	return st;
}

int lz_edmd_blocks(lz_edmd *e, size_t blocks, uint64_t events, lz_edmd_result *r)
{
	lz_edmd_plan plan = {events, INFINITY, 0, NULL, NULL, 0};
	return lz_edmd_blocks_plan(e, blocks, &plan, r);
}

/* ---- the reference equation of state ---- */

/* Z_ref at the tabulated packings: datasets/reference/hard-spheres.csv (3D) and
 * hard-disks.csv (2D). */
enum { Z_ROWS = 16 };
static double z_cs(double x)
{
	return (1 + x + x * x - x * x * x) / pow(1 - x, 3);
}

static double z_henderson(double x)
{
	return (1 + x * x / 8) / ((1 - x) * (1 - x));
}

double lz_edmd_z_closed(int dim, double packing)
{
	return dim == 3 ? z_cs(packing) : z_henderson(packing);
}

double lz_edmd_z_reference(int dim, double packing, const char **source)
{
	double eta[Z_ROWS], z[Z_ROWS];
	lz_ref ref[Z_ROWS];
	size_t n = 0;
	if (lz_reference_table(dim == 3 ? "hard-spheres.csv" : "hard-disks.csv", "Z",
	                       dim == 3 ? "3" : "2", "eta", eta, ref, Z_ROWS, &n) != LZ_OK) {
		if (source)
			*source = "none: the reference table cannot be read";
		return NAN;
	}
	for (size_t k = 0; k < n; k++)
		z[k] = ref[k].value;
	double (*closed)(double) = dim == 3 ? z_cs : z_henderson;
	if (!(packing > 0) || packing > eta[n - 1]) {
		if (source)
			*source = dim == 3 ? "carnahan-starling" : "henderson";
		return packing > 0 && packing < 1 ? closed(packing) : NAN;
	}
	/* the ratio to the closed form is smooth and near 1: interpolate it linearly */
	double x0 = 0, q0 = 1;
	size_t k = 0;
	while (eta[k] < packing) {
		x0 = eta[k];
		q0 = z[k] / closed(eta[k]);
		k++;
	}
	double q1 = z[k] / closed(eta[k]);
	double q = q0 + (q1 - q0) * (packing - x0) / (eta[k] - x0);
	if (source)
		*source = "table";
	return q * closed(packing);
}

/* ---- g(r) ---- */

/* Add the pair at squared distance d2 to h when it lies in h's range. */
static void gr_count(gsl_histogram *h, double d2, double lo2, double hi2)
{
	if (d2 < hi2 && d2 >= lo2)
		gsl_histogram_increment(h, sqrt(d2));
}

/* Every pair, the nearest image on the periodic axes: for boxes too small for the
 * cell scan (its block would wrap onto itself). */
static void gr_all_pairs(const lz_edmd *e, const double *r, gsl_histogram *h, double lo2,
                         double hi2)
{
	for (size_t i = 0; i < e->n; i++)
		for (size_t j = i + 1; j < e->n; j++) {
			double d2 = 0;
			for (int a = 0; a < e->dim; a++) {
				double d = r[3 * j + a] - r[3 * i + a];
				if (!e->wall[a])
					d -= e->L * rint(d / e->L);
				d2 += d * d;
			}
			gr_count(h, d2, lo2, hi2);
		}
}

/* The pairs of particle lists i (cell c) and j (cell d), j shifted by shift; within
 * one cell (same = 1) each pair once. */
static void gr_lists(const lz_edmd *e, const double *r, uint32_t c, uint32_t d,
                     const double shift[3], int same, gsl_histogram *h, double lo2,
                     double hi2)
{
	for (int32_t i = e->list[c].head; i >= 0; i = e->next[i])
		for (int32_t j = same ? e->next[i] : e->list[d].head; j >= 0; j = e->next[j]) {
			double d2 = 0;
			for (int a = 0; a < 3; a++) {
				double x = r[3 * j + a] + shift[a] - r[3 * i + a];
				d2 += x * x;
			}
			gr_count(h, d2, lo2, hi2);
		}
}

/* The pairs of cell c with itself and with the cells within `reach` cells of it on
 * each axis in one half of the block (offsets after 0 in z, y, x order: the other half
 * sees c from its side), so each pair once. */
static void gr_cell(const lz_edmd *e, const double *r, const int reach[3], const int cc[3],
                    gsl_histogram *h, double lo2, double hi2)
{
	static const double none[3] = {0, 0, 0};
	uint32_t c = (uint32_t)cc[0] + (uint32_t)e->m[0] * ((uint32_t)cc[1] +
	             (uint32_t)e->m[1] * (uint32_t)cc[2]);
	if (e->list[c].head < 0)
		return;
	gr_lists(e, r, c, c, none, 1, h, lo2, hi2);
	int o[3];
	for (o[2] = 0; o[2] <= reach[2]; o[2]++)
		for (o[1] = o[2] ? -reach[1] : 0; o[1] <= reach[1]; o[1]++)
			for (o[0] = o[2] || o[1] ? -reach[0] : 1; o[0] <= reach[0]; o[0]++) {
				int q[3];
				double shift[3] = {0, 0, 0};
				int inside = 1;
				for (int a = 0; a < 3 && inside; a++) {
					q[a] = cc[a] + o[a];
					if (q[a] < 0 || q[a] >= e->m[a]) {
						inside = !e->wall[a];
						shift[a] = q[a] < 0 ? -e->L : e->L;
						q[a] += q[a] < 0 ? e->m[a] : -e->m[a];
					}
				}
				uint32_t d = inside ? (uint32_t)q[0] + (uint32_t)e->m[0] * ((uint32_t)q[1] +
				             (uint32_t)e->m[1] * (uint32_t)q[2]) : 0;
				if (inside && e->list[d].head >= 0)
					gr_lists(e, r, c, d, shift, 0, h, lo2, hi2);
			}
}

int lz_edmd_gr_add(const lz_edmd *e, double rmax, gsl_histogram *h)
{
	if (!(rmax > 0 && rmax <= e->L / 2))
		return lz_error(LZ_EINVAL, "rmax = %g must be in (0, L/2 = %g]: beyond half the "
		                "box a pair would be met at two images", rmax, e->L / 2);
	double lo = h->range[0], hi = h->range[h->n];
	if (hi > rmax)
		return lz_error(LZ_EINVAL, "the g(r) histogram reaches r = %g, beyond rmax = %g",
		                hi, rmax);
	double *r = malloc(3 * e->n * sizeof *r);
	if (!r)
		return lz_error(LZ_ENOMEM, "no memory for %zu positions", e->n);
	for (size_t i = 0; i < e->n; i++) {
		double v[3];
		lz_edmd_state(e, &e->p[i], e->now, r + 3 * i, v);
	}
	double lo2 = lo > 0 ? lo * lo : 0, hi2 = hi * hi;
	/* a pair closer than rmax is at most ceil((rmax + 2 stray) / w) cells apart on
	 * every axis (a particle strays from its cell by at most lz_edmd_stray); on a
	 * periodic axis the 2·reach + 1 cells must be distinct, or a pair would be met
	 * twice */
	int reach[3] = {0, 0, 0}, wraps = 0;
	for (int a = 0; a < e->dim; a++) {
		reach[a] = (int)ceil((rmax + 2 * lz_edmd_stray(e)) / e->w[a]);
		if (2 * reach[a] + 1 > e->m[a]) {
			if (!e->wall[a])
				wraps = 1;
			reach[a] = e->m[a] - 1;
		}
	}
	if (wraps) {
		gr_all_pairs(e, r, h, lo2, hi2);
	} else {
		int cc[3];
		for (cc[2] = 0; cc[2] < e->m[2]; cc[2]++)
			for (cc[1] = 0; cc[1] < e->m[1]; cc[1]++)
				for (cc[0] = 0; cc[0] < e->m[0]; cc[0]++)
					gr_cell(e, r, reach, cc, h, lo2, hi2);
	}
	free(r);
	return LZ_OK;
}

double lz_edmd_gr_value(const lz_edmd *e, const gsl_histogram *h, size_t k, size_t samples)
{
	double lo, hi;
	if (k >= h->n || gsl_histogram_get_range(h, k, &lo, &hi))
		return NAN;
	double shell = e->dim == 3 ? 4 * M_PI / 3 * (hi * hi * hi - lo * lo * lo)
	                           : M_PI * (hi * hi - lo * lo);
	double n = (double)e->n, volume = pow(e->L, e->dim);
	/* the pairs an ideal gas puts in the shell: n(n-1)/2 of them, each uniform */
	double ideal = (double)samples * 0.5 * n * (n - 1) * shell / volume;
	return ideal > 0 ? gsl_histogram_get(h, k) / ideal : NAN;
}

/* ---- the mean-square displacement ---- */

lz_edmd_track *lz_edmd_track_alloc(const lz_edmd *e)
{
	lz_edmd_track *tr = malloc(sizeof *tr);
	double *mem = malloc(6 * e->n * sizeof *mem);
	if (!tr || !mem) {
		free(tr);
		free(mem);
		lz_error(LZ_ENOMEM, "no memory to track %zu particles", e->n);
		return NULL;
	}
	tr->n = e->n;
	tr->start = mem;
	tr->last = mem + 3 * e->n;
	for (size_t i = 0; i < e->n; i++) {
		double v[3];
		lz_edmd_state(e, &e->p[i], e->now, tr->start + 3 * i, v);
		for (int a = 0; a < 3; a++)
			tr->last[3 * i + a] = tr->start[3 * i + a];
	}
	return tr;
}

void lz_edmd_track_free(lz_edmd_track *tr)
{
	if (!tr)
		return;
	free(tr->start);
	free(tr);
}

void lz_edmd_track_update(lz_edmd_track *tr, const lz_edmd *e)
{
	/* last is congruent to the wrapped position of the last update, so the nearest
	 * image of (now - last) is the displacement since */
	for (size_t i = 0; i < tr->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		for (int a = 0; a < e->dim; a++) {
			double d = r[a] - tr->last[3 * i + a];
			if (!e->wall[a])
				d -= e->L * rint(d / e->L);
			tr->last[3 * i + a] += d;
		}
	}
}

double lz_edmd_track_msd(const lz_edmd_track *tr)
{
	double sum = 0;
	for (size_t i = 0; i < 3 * tr->n; i++) {
		double d = tr->last[i] - tr->start[i];
		sum += d * d;
	}
	return tr->n ? sum / (double)tr->n : NAN;
}
