/* insert_time — lesson 03, experiment (§5): how long it takes to drop N disks into a
 * box at random, by the field and by coordinates (thesis 2.5.1, table 2.1 and fig.
 * 2.21).
 *
 * Random sequential addition of disks of radius R = 4 (σ = 8) on the square lattice up
 * to coverage θ = 0.3, N = θ L² / (π R²) disks, the box side L growing from 256 to
 * 8192 at fixed θ (128 to 2048 at the demo size), so N from a few hundred to 400 000.
 * Three methods:
 *   field      lz_field_rsa with target N: one look-up per try, O(σ²) to paint;
 *   all pairs  coordinates (double, minimum image), each try tested against every
 *              disk already placed: O(N) per try, O(N²) in all — the thesis's
 *              "neighbour-list" generator, whose new particle has no list yet;
 *   grid       the same coordinates in a cell grid of side >= σ (here exactly σ:
 *              L/σ cells a side), each try tested against the 9 cells around it:
 *              O(1) per try — the cell-list method the thesis expected "somewhere
 *              between".
 * The coordinate methods draw their tries exactly as the field's first phase does (x,
 * then y, each gsl_rng_uniform_int(rng, L), from the same seed) and test d² < σ²
 * exactly (integers held in doubles): while the field stays in that phase — it does
 * while a sixteenth of its sites are free, and at θ = 0.3 about 16 % are — all three
 * build the very same configuration, disk by disk, as the thesis's two methods did.
 * So the comparison is of the same work, and that is checked.
 *
 * Cost: CPU seconds (the machine is shared; medians of REPEATS repeats, the methods
 * interleaved so that a busy moment hits all of them), allocation included — the field
 * must clear L² bytes. All pairs runs only while the next box is predicted (N²) to
 * take less than 10 CPU seconds (1 at the demo size). Fits log t = a + b log N (gsl_fit_linear) over all
 * but the smallest box give the exponents b. Memory: the field holds L² bytes, the
 * coordinate methods 16 bytes a disk (and the grid 4 more and 4 a cell).
 *
 * Checks: the three methods build identical configurations; all pairs grows faster
 * than N^1.7, the field and the grid slower than N^1.3.
 *
 * Usage: insert_time OUTDIR [--quick]
 * Writes OUTDIR/insert_time.dat and insert_time.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/field.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 2150u       /* fixed: the lesson quotes the numbers of this run */
#define RADIUS 4.0
#define SIGMA (2 * RADIUS)
#define THETA 0.3
#define REPEATS 3
#define MAXL 8           /* box sizes, at most */
#define AP_EXPONENT_MIN 1.7
#define LINEAR_EXPONENT_MAX 1.3

enum { FIELD, ALLPAIRS, GRID, NMETHOD };
static const char *method_name[NMETHOD] = {"field", "all_pairs", "grid"};

/* The centres placed by one method, in the order of placement. */
typedef struct {
	int64_t L;
	size_t n;            /* placed so far */
	double *x, *y;       /* room for the target N */
	uint64_t tries;      /* sites drawn */
} placement;

/* One box size: the medians, the memory and what the runs had in common. */
typedef struct {
	int64_t L;
	size_t n;
	double t[NMETHOD];       /* median CPU seconds (NaN: not run) */
	double t_fit[NMETHOD];   /* the fitted power law at this N (NaN outside the fit) */
	double bytes[NMETHOD];   /* memory of the method's data */
	double tries;            /* draws per disk (the same for every method) */
	double free_frac;        /* the field's free sites over its sites at the end */
	int same;                /* the coordinate methods built the field's configuration */
} box;

typedef struct {
	int npts;
	double a, b, b_err;      /* log t = a + b log N */
} powerlaw;

/* The size of the run: box sides lmin .. lmax (powers of two); all pairs stops before
 * a box predicted to take more than ap_max CPU seconds. */
typedef struct {
	int64_t lmin, lmax;
	double ap_max;
} sizes;

static const sizes full = {256, 8192, 10};
static const sizes quick = {128, 2048, 1};

/* The next try, drawn as lz_field_rsa's first phase draws it. */
static void draw(placement *p, gsl_rng *rng, double *x, double *y)
{
	*x = (double)gsl_rng_uniform_int(rng, (unsigned long)p->L);
	*y = (double)gsl_rng_uniform_int(rng, (unsigned long)p->L);
	p->tries++;
}

/* The minimum-image component of a difference of two coordinates in [0, L). */
static inline double wrap(double d, double L)
{
	return d > L / 2 ? d - L : d < -L / 2 ? d + L : d;
}

static inline int overlap(double x1, double y1, double x2, double y2, double L)
{
	double dx = wrap(x1 - x2, L), dy = wrap(y1 - y2, L);
	return dx * dx + dy * dy < SIGMA * SIGMA;
}

/* The field: lz_field_rsa with the target. CPU seconds of allocation and insertion. */
static int place_field(placement *p, size_t target, gsl_rng *rng, double *seconds,
                       double *free_frac)
{
	double t0 = lz_cpu_now();
	lz_field *f = lz_field_alloc(LZ_LATTICE_SQUARE, p->L, RADIUS);
	if (!f)
		return LZ_EINVAL;
	int jammed, status = lz_field_rsa(f, rng, target, &jammed);
	*seconds = lz_cpu_now() - t0;
	if (status == LZ_OK && f->n != target)
		status = lz_error(LZ_EPHYS, "the field jammed at %zu disks before %zu", f->n, target);
	for (size_t i = 0; i < f->n; i++) {
		p->x[i] = f->r[2 * i];
		p->y[i] = f->r[2 * i + 1];
	}
	p->n = f->n;
	p->tries = f->tries;
	*free_frac = (double)f->nfree / (double)f->nsites;
	lz_field_free(f);
	return status;
}

/* All pairs: every try against every disk placed. O(N²). */
static double place_allpairs(placement *p, size_t target, gsl_rng *rng)
{
	double t0 = lz_cpu_now(), L = (double)p->L;
	while (p->n < target) {
		double x, y;
		draw(p, rng, &x, &y);
		size_t j = 0;
		while (j < p->n && !overlap(x, y, p->x[j], p->y[j], L))
			j++;
		if (j == p->n) {
			p->x[p->n] = x;
			p->y[p->n] = y;
			p->n++;
		}
	}
	return lz_cpu_now() - t0;
}

/* The cell of coordinate x among nc cells of side L/nc. */
static inline int32_t cell_of(double x, int32_t nc, double L)
{
	return (int32_t)(x * nc / L);
}

/* 1 if (x, y) overlaps a disk in the 3×3 cells around its own (linked lists: head of
 * each cell, next of each disk, -1 ending a list). */
static int grid_overlap(const placement *p, const int32_t *head, const int32_t *next,
                        int32_t nc, double x, double y)
{
	double L = (double)p->L;
	int32_t cx = cell_of(x, nc, L), cy = cell_of(y, nc, L);
	for (int32_t dy = -1; dy <= 1; dy++)
		for (int32_t dx = -1; dx <= 1; dx++) {
			int32_t c = (cx + dx + nc) % nc + (cy + dy + nc) % nc * nc;
			for (int32_t j = head[c]; j >= 0; j = next[j])
				if (overlap(x, y, p->x[j], p->y[j], L))
					return 1;
		}
	return 0;
}

/* The grid: cells of side L / floor(L/σ) >= σ, so every disk that can overlap a try
 * sits in the 9 cells around it. O(N). */
static int place_grid(placement *p, size_t target, gsl_rng *rng, double *seconds,
                      double *bytes)
{
	double t0 = lz_cpu_now(), L = (double)p->L;
	int32_t nc = (int32_t)floor(L / SIGMA);
	int32_t *head = malloc((size_t)nc * (size_t)nc * sizeof *head);
	int32_t *next = malloc(target * sizeof *next);
	if (!head || !next) {
		free(head);
		free(next);
		return lz_error(LZ_ENOMEM, "no memory for a grid of %d² cells", (int)nc);
	}
	memset(head, 0xff, (size_t)nc * (size_t)nc * sizeof *head);  /* every list empty */
	while (p->n < target) {
		double x, y;
		draw(p, rng, &x, &y);
		if (grid_overlap(p, head, next, nc, x, y))
			continue;
		int32_t c = cell_of(x, nc, L) + cell_of(y, nc, L) * nc;
		p->x[p->n] = x;
		p->y[p->n] = y;
		next[p->n] = head[c];
		head[c] = (int32_t)p->n;
		p->n++;
	}
	*seconds = lz_cpu_now() - t0;
	*bytes = (double)target * (2 * sizeof(double) + sizeof *next) +
	         (double)nc * nc * sizeof *head;
	free(head);
	free(next);
	return LZ_OK;
}

/* One method once, from the seed: its CPU seconds; the placement is left in p. */
static int run_method(int m, box *b, placement *p, double *seconds)
{
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	if (!rng)
		return LZ_ENOMEM;
	p->n = 0;
	p->tries = 0;
	int status = LZ_OK;
	if (m == FIELD)
		status = place_field(p, b->n, rng->gsl, seconds, &b->free_frac);
	else if (m == ALLPAIRS)
		*seconds = place_allpairs(p, b->n, rng->gsl);
	else
		status = place_grid(p, b->n, rng->gsl, seconds, &b->bytes[GRID]);
	lz_rng_free(rng);
	return status;
}

static int same_placement(const placement *a, const placement *b)
{
	return a->n == b->n && memcmp(a->x, b->x, a->n * sizeof *a->x) == 0 &&
	       memcmp(a->y, b->y, a->n * sizeof *a->y) == 0;
}

/* One box: every method REPEATS times, interleaved; medians; the configurations
 * compared. run[m] says whether method m runs at this size. */
static int run_box(box *b, const int *run)
{
	placement p[NMETHOD];
	double t[NMETHOD][REPEATS];
	int status = LZ_OK;
	for (int m = 0; m < NMETHOD; m++) {
		p[m].L = b->L;
		p[m].x = malloc(b->n * sizeof(double));
		p[m].y = malloc(b->n * sizeof(double));
		if (!p[m].x || !p[m].y)
			status = lz_error(LZ_ENOMEM, "no memory for %zu centres", b->n);
	}
	for (int r = 0; r < REPEATS && status == LZ_OK; r++)
		for (int m = 0; m < NMETHOD && status == LZ_OK; m++)
			if (run[m])
				status = run_method(m, b, &p[m], &t[m][r]);
	b->same = 1;
	for (int m = 0; m < NMETHOD; m++) {
		b->t[m] = NAN;
		if (status == LZ_OK && run[m]) {
			gsl_sort(t[m], 1, REPEATS);
			b->t[m] = gsl_stats_median_from_sorted_data(t[m], 1, REPEATS);
			b->same = b->same && same_placement(&p[FIELD], &p[m]);
		}
	}
	b->tries = (double)p[FIELD].tries / (double)b->n;
	b->bytes[FIELD] = (double)b->L * (double)b->L + (double)b->n * 2 * sizeof(int32_t);
	b->bytes[ALLPAIRS] = (double)b->n * 2 * sizeof(double);
	for (int m = 0; m < NMETHOD; m++) {
		free(p[m].x);
		free(p[m].y);
	}
	return status;
}

/* log t = a + b log N over the boxes but the smallest where method m ran. */
static void fit_method(box *bx, int nb, int m, powerlaw *P)
{
	double x[MAXL], y[MAXL], c00, c01, c11, ss;
	int k = 0;
	for (int i = 1; i < nb; i++)
		if (isfinite(bx[i].t[m])) {
			x[k] = log((double)bx[i].n);
			y[k] = log(bx[i].t[m]);
			k++;
		}
	P->npts = k;
	gsl_fit_linear(x, 1, y, 1, (size_t)k, &P->a, &P->b, &c00, &c01, &c11, &ss);
	P->b_err = k > 2 ? sqrt(c11) : NAN;
	for (int i = 0; i < nb; i++)
		bx[i].t_fit[m] = i > 0 && isfinite(bx[i].t[m]) ?
		                 exp(P->a + P->b * log((double)bx[i].n)) : NAN;
}

static void print_boxes(const box *bx, int nb)
{
	printf("  %6s %8s %10s %10s %10s %9s %7s %9s %12s %10s %10s\n", "L", "N", "field s",
	       "allpairs s", "grid s", "ap/field", "tries/N", "free frac", "field bytes",
	       "ap bytes", "grid bytes");
	for (int i = 0; i < nb; i++) {
		const box *b = &bx[i];
		printf("  %6lld %8zu %10.4f %10.4f %10.4f %9.1f %7.2f %9.3f %12.0f %10.0f %10.0f\n",
		       (long long)b->L, b->n, b->t[FIELD], b->t[ALLPAIRS], b->t[GRID],
		       b->t[ALLPAIRS] / b->t[FIELD], b->tries, b->free_frac, b->bytes[FIELD],
		       b->bytes[ALLPAIRS], b->bytes[GRID]);
	}
}

static void print_fits(const box *bx, int nb, const powerlaw *P)
{
	printf("  fits log t = a + b log N over all but the smallest box:\n");
	printf("  %-10s %6s %7s %7s %12s %16s %14s\n", "method", "points", "b", "+-",
	       "t(N=1e4) s", "us/disk largest", "bytes/disk");
	for (int m = 0; m < NMETHOD; m++) {
		int last = nb - 1;
		while (last > 0 && !isfinite(bx[last].t[m]))
			last--;
		const box *b = &bx[last];
		printf("  %-10s %6d %7.3f %7.3f %12.4g %16.3f %14.1f\n", method_name[m],
		       P[m].npts, P[m].b, P[m].b_err, exp(P[m].a + P[m].b * log(1e4)),
		       1e6 * b->t[m] / (double)b->n, b->bytes[m] / (double)b->n);
	}
}

static int write_data(lz_lesson *L, const box *bx, int nb)
{
	static const char *names[] = {"L", "N", "t_field", "t_all_pairs", "t_grid",
	                              "t_field_fit", "t_all_pairs_fit", "t_grid_fit",
	                              "bytes_field", "bytes_all_pairs", "bytes_grid",
	                              "tries_per_disk", "field_free_fraction"};
	static const char *units[] = {"sites", "disks", "s", "s", "s", "s", "s", "s", "bytes",
	                              "bytes", "bytes", "", ""};
	lz_data *d = lz_lesson_data(L, "insert_time.dat", "CPU seconds (median of 3) to add N "
	                            "disks of R = 4 at random up to coverage 0.3 by the field, "
	                            "by coordinates against all pairs and by coordinates in a "
	                            "cell grid; fitted power laws; memory", 13, names, units);
	if (!d)
		return LZ_EIO;
	for (int i = 0; i < nb; i++) {
		const box *b = &bx[i];
		double row[13] = {(double)b->L, (double)b->n, b->t[FIELD], b->t[ALLPAIRS], b->t[GRID],
		                  b->t_fit[FIELD], b->t_fit[ALLPAIRS], b->t_fit[GRID], b->bytes[FIELD],
		                  b->bytes[ALLPAIRS], b->bytes[GRID], b->tries, b->free_frac};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

static int write_json(lz_lesson *L, const box *bx, int nb, const powerlaw *P)
{
	lz_json *j = lz_lesson_json(L, "insert_time.json");
	if (!j)
		return LZ_EIO;
	lz_json_num(j, "radius", RADIUS);
	lz_json_num(j, "coverage", THETA);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "n_largest", (long long)bx[nb - 1].n);
	for (int m = 0; m < NMETHOD; m++) {
		char key[64];
		snprintf(key, sizeof key, "exponent_%s", method_name[m]);
		lz_json_err(j, key, P[m].b, P[m].b_err);
		snprintf(key, sizeof key, "seconds_1e4_%s", method_name[m]);
		lz_json_num(j, key, exp(P[m].a + P[m].b * log(1e4)));
	}
	const box *b = &bx[nb - 1];
	lz_json_num(j, "field_seconds_largest", b->t[FIELD]);
	lz_json_num(j, "grid_seconds_largest", b->t[GRID]);
	lz_json_num(j, "field_bytes_per_disk", b->bytes[FIELD] / (double)b->n);
	lz_json_num(j, "grid_bytes_per_disk", b->bytes[GRID] / (double)b->n);
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	static box bx[MAXL];
	powerlaw P[NMETHOD];
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "03", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("insert_time: disks of R = %g (sigma = %g) on the square lattice to coverage %g, "
	       "L = %lld .. %lld; field, all pairs (while under %g s), cell grid; CPU seconds, "
	       "median of %d; mt19937 seed %u\n", RADIUS, SIGMA, THETA, (long long)sz->lmin,
	       (long long)sz->lmax, sz->ap_max, REPEATS, SEED);
	int nb = 0;
	for (int64_t side = sz->lmin; side <= sz->lmax; side *= 2, nb++) {
		box *b = &bx[nb];
		b->L = side;
		b->n = (size_t)lround(THETA * (double)side * (double)side / (M_PI * RADIUS * RADIUS));
		double grow = nb ? (double)b->n / (double)bx[nb - 1].n : 1;
		int run[NMETHOD] = {1, nb == 0 || bx[nb - 1].t[ALLPAIRS] * grow * grow < sz->ap_max,
		                      1};
		if (run_box(b, run) != LZ_OK)
			return lz_lesson_error(&L);
	}
	for (int m = 0; m < NMETHOD; m++)
		fit_method(bx, nb, m, &P[m]);
	print_boxes(bx, nb);
	print_fits(bx, nb, P);

	int same = 1;
	for (int i = 0; i < nb; i++)
		same = same && bx[i].same;
	printf("  the three methods build the same configuration, disk by disk, in every box: "
	       "%s\n", lz_lesson_check(&L, same));
	printf("  all pairs grows like N^%.2f, faster than N^%.1f: %s\n", P[ALLPAIRS].b,
	       AP_EXPONENT_MIN, lz_lesson_check(&L, P[ALLPAIRS].b > AP_EXPONENT_MIN));
	printf("  field N^%.2f and grid N^%.2f, both slower than N^%.1f: %s\n", P[FIELD].b,
	       P[GRID].b, LINEAR_EXPONENT_MAX, lz_lesson_check(&L, P[FIELD].b <
	       LINEAR_EXPONENT_MAX && P[GRID].b < LINEAR_EXPONENT_MAX));
	if (write_data(&L, bx, nb) != LZ_OK || write_json(&L, bx, nb, P) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "identical configurations; all pairs O(N^2), field and "
	                        "grid O(N)");
}
