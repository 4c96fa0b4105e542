/* locality — lesson 03, experiment (§6): the speed of the field method against the
 * radius and against the memory it is spread over (thesis 2.5.1, table 2.3).
 *
 * N = 1100 hard disks at coverage θ = 0.4746 random-walk on the square lattice: radius
 * R = 12, 6, 3, 1.5 in a box of side L = 1024, 512, 256, 128 (R/L fixed: the same
 * physical system at four resolutions). A sweep offers every disk, in index order,
 * one step in a uniformly drawn direction (lz/walk.h's random walk), made with
 * lz_field_can_move and lz_field_move: one look-up to test, the head points painted
 * +1 and the tail points -1 to move.
 *
 * What to expect. A step repaints 2σ - 1 = 4R - 1 head points and as many tail points:
 * halving R halves the work of an accepted step, so the speed should double (the
 * thesis's argument). But a step of one lattice unit is a larger part of σ at small R,
 * so fewer steps are accepted (0.87 at R = 12, 0.47 at R = 1.5): the painting per
 * offered step falls by more than 2. Not all of a step's cost is painting, though:
 * the random direction, the test and the calls cost the same at every R. So the time
 * per offered step is modelled as
 *     t = c0 + c1 · (points painted per offered step = acceptance · 2 · head)
 * and c0 (fixed, ns) and c1 (ns per painted point) are fitted (gsl_fit_linear) over
 * the four radii in each allocation. Against all that, memory: the head points of a
 * step lie on 2σ - 1 rows, P bytes apart when the box sits in a lattice of side P
 * (lz_field_alloc_in), and a small box in a small allocation stays in the caches;
 * c1 grows with P.
 *
 * Each radius runs in its box alone (P = L) and in the corner of lattices of side
 * P = 1024 .. 8192 (4096 at the demo size): exactly the same walk — the same
 * configuration, placed from one equilibrated start, and the same random numbers — in
 * every allocation, so only where the bytes are differs; that is checked. (At R = 12
 * the box alone is P = 1024: it runs twice, and the two columns show the timing
 * noise.) Speed: atom-steps per CPU second (the machine is shared: CPU time, medians
 * of 5 repeats (3 at the demo size), every radius and allocation in turn within a
 * repeat, so that a busy moment hits all of them).
 *
 * Checks: every allocation walked the same trajectory; the field's free-site count
 * agrees with a full scan after the walk; and halving R from 12 to 6 makes the walk
 * more than 1.5 times faster in every allocation (the painting per offered step falls
 * 2.3-fold, and at R = 12 painting is most of the cost). Whether a smaller allocation
 * is faster is measured, not checked: it depends on the caches of the machine.
 *
 * Usage: locality OUTDIR [--quick]
 * Writes OUTDIR/locality.dat and locality.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/field.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 2330u       /* fixed: the lesson quotes the numbers of this run */
#define NDISK 1100
#define NR 4
#define PMIN 1024        /* column k >= 1 is the allocated side P = PMIN · 2^(k-1) */
#define MAXCOL 5         /* the box alone, then P = 1024 .. 8192 */
#define MAXREP 5
#define HALVING_MIN 1.5  /* R = 12 -> 6 must speed up by more than this */

static const double radius[NR] = {12, 6, 3, 1.5};
static const int64_t box_side[NR] = {1024, 512, 256, 128};

/* Timed sweeps at R = 12 (× 12/R at R: about the same CPU time at every R), the
 * columns (the box alone and P = 1024 ..; 8192² bytes take 0.6 s to allocate) and
 * the repeats. */
typedef struct {
	long sweeps12;
	int ncol, repeats;
} sizes;

static const sizes full = {1000, 5, 5};
static const sizes quick = {50, 4, 3};

/* One radius in its allocations (columns). */
typedef struct {
	double R;
	int64_t L;
	int64_t pitch[MAXCOL];     /* the allocated side of each column */
	double speed[MAXCOL];      /* median atom-steps per CPU second */
	double lo[MAXCOL], hi[MAXCOL];  /* slowest and fastest repeat */
	long sweeps;
	double acceptance;         /* accepted over offered steps in the timed sweeps */
	double head;               /* head points of a step, mean over the directions */
	int same;                  /* every allocation ended in the same configuration */
	int free_ok;               /* nfree agreed with lz_field_count_free */
} radius_run;

/* The time per offered step in one column: c0 + c1 · painted points. */
typedef struct {
	double c0, c1;             /* ns, ns per point */
} cost;

/* `count` sweeps of the random walk; the accepted steps. */
static uint64_t walk(lz_field *f, gsl_rng *rng, long count)
{
	unsigned long ndir = (unsigned long)f->excl->ndir;
	uint64_t accepted = 0;
	for (long s = 0; s < count; s++)
		for (size_t i = 0; i < f->n; i++) {
			int d = (int)gsl_rng_uniform_int(rng, ndir);
			if (lz_field_can_move(f, i, d)) {
				lz_field_move(f, i, d);
				accepted++;
			}
		}
	return accepted;
}

/* The start: NDISK disks by RSA in the box alone, then 2 (2R)² sweeps, about the
 * number for a disk to wander a diameter, so that the start is a fluid, not an RSA
 * packing (the acceptance, and with it the speed, would differ). */
static lz_field *start(const radius_run *rr, gsl_rng *rng)
{
	lz_field *f = lz_field_alloc(LZ_LATTICE_SQUARE, rr->L, rr->R);
	int jammed;
	if (!f)
		return NULL;
	if (lz_field_rsa(f, rng, NDISK, &jammed) != LZ_OK || f->n != NDISK) {
		lz_error(LZ_EPHYS, "RSA stopped at %zu of %d disks", f->n, NDISK);
		lz_field_free(f);
		return NULL;
	}
	walk(f, rng, (long)(8 * rr->R * rr->R));
	return f;
}

/* The box of f0, with its disks in the same order, in a lattice of side pitch. */
static lz_field *copy_in(const lz_field *f0, int64_t pitch)
{
	lz_field *f = lz_field_alloc_in(f0->kind, f0->side, f0->radius, pitch);
	for (size_t i = 0; f && i < f0->n; i++) {
		lz_site c = {f0->r[2 * i], f0->r[2 * i + 1], 0};
		if (lz_field_place(f, c) != LZ_OK) {
			lz_field_free(f);
			return NULL;
		}
	}
	return f;
}

/* Every radius's start (from the generator seeded SEED), placed in each of its
 * allocations; the columns of radius i in f[i]. */
static int setup(radius_run *rr, const sizes *sz, lz_field *f[NR][MAXCOL])
{
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	int status = rng ? LZ_OK : LZ_ENOMEM;
	for (int i = 0; i < NR && status == LZ_OK; i++) {
		rr[i].R = radius[i];
		rr[i].L = box_side[i];
		rr[i].sweeps = (long)lround((double)sz->sweeps12 * 12 / rr[i].R);
		rr[i].pitch[0] = rr[i].L;
		for (int k = 1; k < sz->ncol; k++)
			rr[i].pitch[k] = (int64_t)PMIN << (k - 1);
		lz_field *f0 = start(&rr[i], rng->gsl);
		if (!f0) {
			status = LZ_EINVAL;
			break;
		}
		rr[i].head = lz_shape_mean_move(f0->excl);
		for (int k = 0; k < sz->ncol && status == LZ_OK; k++)
			if (!(f[i][k] = copy_in(f0, rr[i].pitch[k])))
				status = LZ_EINVAL;
		lz_field_free(f0);
	}
	lz_rng_free(rng);
	return status;
}

/* The repeats, every radius and allocation in turn within each, so that a busy
 * moment of the machine hits them all: each walks its sweeps from the same seed.
 * Then the speeds (median, slowest, fastest), the acceptance and the comparisons. */
static int time_walks(radius_run *rr, const sizes *sz, lz_field *f[NR][MAXCOL])
{
	static double t[NR][MAXCOL][MAXREP];
	uint64_t accepted[NR] = {0};
	for (int r = 0; r < sz->repeats; r++)
		for (int i = 0; i < NR; i++)
			for (int k = 0; k < sz->ncol; k++) {
				lz_rng *rng = lz_rng_alloc("mt19937", SEED + 1 + (unsigned long)r);
				if (!rng)
					return LZ_ENOMEM;
				double t0 = lz_cpu_now();
				uint64_t a = walk(f[i][k], rng->gsl, rr[i].sweeps);
				t[i][k][r] = lz_cpu_now() - t0;
				lz_rng_free(rng);
				if (k == 0)
					accepted[i] += a;
			}
	for (int i = 0; i < NR; i++) {
		double steps = (double)rr[i].sweeps * NDISK;
		size_t n = (size_t)sz->repeats;
		for (int k = 0; k < sz->ncol; k++) {
			gsl_sort(t[i][k], 1, n);
			rr[i].speed[k] = steps / gsl_stats_median_from_sorted_data(t[i][k], 1, n);
			rr[i].lo[k] = steps / t[i][k][n - 1];
			rr[i].hi[k] = steps / t[i][k][0];
		}
		rr[i].acceptance = (double)accepted[i] / ((double)n * steps);
		const lz_field *f0 = f[i][0];
		rr[i].same = 1;
		for (int k = 0; k < sz->ncol; k++)
			rr[i].same = rr[i].same && f[i][k]->n == f0->n &&
			             memcmp(f[i][k]->r, f0->r, 2 * f0->n * sizeof *f0->r) == 0;
		rr[i].free_ok = lz_field_count_free(f0) == f0->nfree;
	}
	return LZ_OK;
}

/* Painted points per offered step: heads and tails of the accepted ones. */
static double painted(const radius_run *rr)
{
	return 2 * rr->head * rr->acceptance;
}

/* ns per offered step against painted points, over the radii, in column k. */
static void fit_cost(const radius_run *rr, int k, cost *c)
{
	double x[NR], y[NR], c00, c01, c11, ss;
	for (int i = 0; i < NR; i++) {
		x[i] = painted(&rr[i]);
		y[i] = 1e9 / rr[i].speed[k];
	}
	gsl_fit_linear(x, 1, y, 1, NR, &c->c0, &c->c1, &c00, &c01, &c11, &ss);
}

static const char *column_name(int k, char *buf, size_t size)
{
	if (k == 0)
		snprintf(buf, size, "box alone");
	else
		snprintf(buf, size, "P = %d", PMIN << (k - 1));
	return buf;
}

static void print_table(const radius_run *rr, const cost *c, int ncol)
{
	char name[32];
	printf("  speed, 1e6 atom-steps per CPU second (median), by allocation:\n");
	printf("  %5s %5s %7s %6s %7s %8s", "R", "L", "sweeps", "head", "accept", "painted");
	for (int k = 0; k < ncol; k++)
		printf(" %10s", column_name(k, name, sizeof name));
	printf("\n");
	for (int i = 0; i < NR; i++) {
		printf("  %5.1f %5lld %7ld %6.1f %7.3f %8.1f", rr[i].R, (long long)rr[i].L,
		       rr[i].sweeps, rr[i].head, rr[i].acceptance, painted(&rr[i]));
		for (int k = 0; k < ncol; k++)
			printf(" %10.2f", 1e-6 * rr[i].speed[k]);
		printf("\n");
	}
	printf("  %44s", "ns per offered step = c0 + c1 x painted: c0");
	for (int k = 0; k < ncol; k++)
		printf(" %10.1f", c[k].c0);
	printf("\n  %44s", "c1");
	for (int k = 0; k < ncol; k++)
		printf(" %10.2f", c[k].c1);
	printf("\n  halving R: expected factor (head points alone; with the acceptance) and "
	       "measured (box alone; P = %d):\n", PMIN << (ncol - 2));
	for (int i = 1; i < NR; i++)
		printf("  R = %4.1f -> %4.1f: expected %.2f; %.2f; measured %.2f; %.2f\n",
		       rr[i - 1].R, rr[i].R, rr[i - 1].head / rr[i].head,
		       painted(&rr[i - 1]) / painted(&rr[i]), rr[i].speed[0] / rr[i - 1].speed[0],
		       rr[i].speed[ncol - 1] / rr[i - 1].speed[ncol - 1]);
}

static int write_data(lz_lesson *L, const radius_run *rr, const cost *c, int ncol)
{
	static const char *names[] = {"R", "L", "P", "column", "atomsteps_per_s", "slowest",
	                              "fastest", "acceptance", "head_points", "painted_per_step",
	                              "ns_per_step", "ns_model", "allocated_MB"};
	static const char *units[] = {"lattice", "sites", "sites", "0 box alone", "1/s", "1/s",
	                              "1/s", "", "", "", "ns", "ns", "MB"};
	lz_data *d = lz_lesson_data(L, "locality.dat", "random walk of 1100 hard disks at "
	                            "coverage 0.4746 in a box of side L in the corner of an "
	                            "allocated lattice of side P: atom-steps per CPU second "
	                            "(median, slowest and fastest of the repeats), and the cost model "
	                            "c0 + c1 painted of the column", 13, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < NR; i++)
		for (int k = 0; k < ncol; k++) {
			double P = (double)rr[i].pitch[k], x = painted(&rr[i]);
			double row[13] = {rr[i].R, (double)rr[i].L, P, k, rr[i].speed[k], rr[i].lo[k],
			                  rr[i].hi[k], rr[i].acceptance, rr[i].head, x,
			                  1e9 / rr[i].speed[k], c[k].c0 + c[k].c1 * x, P * P / 1048576};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

static int write_json(lz_lesson *L, const radius_run *rr, const cost *c, int ncol)
{
	lz_json *j = lz_lesson_json(L, "locality.json");
	if (!j)
		return LZ_EIO;
	lz_json_int(j, "n", NDISK);
	lz_json_num(j, "coverage", NDISK * M_PI * 144 / (1024.0 * 1024.0));
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "largest_allocation", PMIN << (ncol - 2));
	for (int i = 0; i < NR; i++) {
		char key[64];
		snprintf(key, sizeof key, "atomsteps_per_s_R%g_alone", rr[i].R);
		lz_json_num(j, key, rr[i].speed[0]);
		snprintf(key, sizeof key, "atomsteps_per_s_R%g_largest", rr[i].R);
		lz_json_num(j, key, rr[i].speed[ncol - 1]);
		snprintf(key, sizeof key, "acceptance_R%g", rr[i].R);
		lz_json_num(j, key, rr[i].acceptance);
	}
	for (int i = 1; i < NR; i++) {
		char key[64];
		snprintf(key, sizeof key, "halving_R%g_alone", rr[i - 1].R);
		lz_json_num(j, key, rr[i].speed[0] / rr[i - 1].speed[0]);
	}
	lz_json_num(j, "ns_fixed_alone", c[0].c0);
	lz_json_num(j, "ns_per_point_alone", c[0].c1);
	lz_json_num(j, "ns_fixed_largest", c[ncol - 1].c0);
	lz_json_num(j, "ns_per_point_largest", c[ncol - 1].c1);
	return lz_json_end(j);
}

static void checks(lz_lesson *L, const radius_run *rr, int ncol)
{
	int same = 1, free_ok = 1;
	for (int i = 0; i < NR; i++) {
		same = same && rr[i].same;
		free_ok = free_ok && rr[i].free_ok;
	}
	double least = INFINITY;
	for (int k = 0; k < ncol; k++)
		least = fmin(least, rr[1].speed[k] / rr[0].speed[k]);
	printf("  every allocation walked the same trajectory (same final configuration): %s\n",
	       lz_lesson_check(L, same));
	printf("  the free-site count agrees with a full scan after the walk: %s\n",
	       lz_lesson_check(L, free_ok));
	printf("  R = 12 -> 6 speeds up by more than %.1f in every allocation (least %.2f): %s\n",
	       HALVING_MIN, least, lz_lesson_check(L, least > HALVING_MIN));
}

int main(int argc, char **argv)
{
	static radius_run rr[NR];
	cost c[MAXCOL];
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "03", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("locality: %d hard disks at coverage %.4f on the square lattice, R = 12 .. 1.5 "
	       "in boxes of 1024 .. 128, each alone and in the corner of lattices of side %d .. "
	       "%d; %ld sweeps x 12/R timed, CPU time, median of %d; mt19937 seed %u\n", NDISK,
	       NDISK * M_PI * 144 / (1024.0 * 1024.0), PMIN, PMIN << (sz->ncol - 2),
	       sz->sweeps12, sz->repeats, SEED);
	static lz_field *f[NR][MAXCOL];
	int status = setup(rr, sz, f);
	if (status == LZ_OK)
		status = time_walks(rr, sz, f);
	for (int i = 0; i < NR; i++)
		for (int k = 0; k < sz->ncol; k++)
			lz_field_free(f[i][k]);
	if (status != LZ_OK)
		return lz_lesson_error(&L);
	for (int k = 0; k < sz->ncol; k++)
		fit_cost(rr, k, &c[k]);
	print_table(rr, c, sz->ncol);
	checks(&L, rr, sz->ncol);
	if (write_data(&L, rr, c, sz->ncol) != LZ_OK || write_json(&L, rr, c, sz->ncol) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "the same walk in every allocation; halving R at least "
	                        "%.1f times faster", HALVING_MIN);
}
