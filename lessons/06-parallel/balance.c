/* balance — lesson 06, experiment: LOAD BALANCE. Cutting the curve into runs of
 * equally many cells gives every rank the same volume, not the same work. In an
 * uneven system the ranks that own the dense part carry most of the events and the
 * others wait for them at every cut. The remedy of Miller & Luding §III A: move the
 * cuts along the curve so that every rank gets the same share of the load.
 *
 * The system: 2D disks in a periodic box, a dense square (η = 0.45 on its own) in
 * one quarter of the box and a dilute gas (η = 0.05) in the rest, each on its own
 * square lattice, Maxwell velocities, melted serially for 2 time units. (The dense
 * square expands into the gas at about the speed of sound, slowly against the runs
 * below: the load moves little while it is measured.)
 *
 * For P = 4, 8, 16 (4, 8 with --quick), along rows and along the Morton curve: a
 * pilot run with even cuts over the first quarter of the measured time gives the
 * committed events of every cell (lz_pedmd_sim_load); lz_pedmd_rebalance cuts the
 * curve where the running total of that load reaches k/P of the whole; then the
 * measured run from the same start, once with the even cuts and once with the
 * balanced ones (lz_pedmd_sim_alloc_cut), on the cluster of pedmd_lesson.h in virtual
 * time, with the best of the windows of best_window. The load of a rank: its committed
 * events; the imbalance: the largest over the mean (1 is perfect).
 *
 * Also measured: the share of the cells, and of the pilot's events, that lie in
 * BORDER cells — where a rank's changes must be told and late news can hurt.
 *
 * Checks: every run commits the serial events and ends with the serial records; the
 * even cuts are out of balance (largest load at least 1.5 times the mean at P = 8);
 * balanced cuts bring it within 15 % of the mean for every P and curve; along the
 * Morton curve they make the run faster at every P; and they put a larger share of
 * the events into BORDER cells than the even cuts did (the price of balance: the
 * dense part, where the events are, is cut into more domains).
 *
 * Usage: balance OUTDIR [--quick]
 * Writes OUTDIR/balance.dat, balance_ranks.dat, balance_map.dat and balance.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/pedmd.h"
#include "lz/rng.h"

#include "pedmd_lesson.h"

#define SEED 6004u
#define ETA_DENSE 0.45
#define ETA_DILUTE 0.05
#define MELT 2.0
#define REBASE 1.0
#define NPS 3
#define MAP_P 8  /* the run whose cells are mapped */
#define NCOL 14

static const int ranks_of[NPS] = {4, 8, 16};
static const char *curve_name[2] = {"rows", "Morton"};

typedef struct {
	double L;     /* the box side */
	double time;  /* the measured run */
	int np;       /* how many of ranks_of */
} sizes;

static const sizes full = {400, 1.0, 3};
static const sizes quick = {300, 0.5, 2};

/* ---- the uneven system ---- */

/* Is (x, y) within `margin` of the dense square [0, L/2)², across the periodic
 * boundary too? */
static int near_square(double x, double y, double L, double margin)
{
	double u = x > L - margin ? x - L : x, w = y > L - margin ? y - L : y;
	return u > -margin && u < L / 2 + margin && w > -margin && w < L / 2 + margin;
}

/* The sites of both lattices into r (3 per site) when r is not NULL; their number.
 * The dense lattice fills [1/2, L/2 - 1/2]² with spacing >= its η's; the dilute one
 * has a whole number of sites per side (so that its spacing holds across the periodic
 * boundary) and keeps 1/2 away from the dense square: every pair is >= 1 apart. */
static size_t sites(double L, double *r)
{
	int nd = (int)floor((L / 2 - 1) / sqrt(M_PI / 4 / ETA_DENSE)) + 1;
	int ng = (int)floor(L / sqrt(M_PI / 4 / ETA_DILUTE));
	double ad = (L / 2 - 1) / (nd - 1), ag = L / ng;
	size_t n = 0;
	for (int a = 0; a < nd; a++)
		for (int b = 0; b < nd; b++, n++)
			if (r) {
				r[3 * n] = 0.5 + a * ad;
				r[3 * n + 1] = 0.5 + b * ad;
				r[3 * n + 2] = 0;
			}
	for (int a = 0; a < ng; a++)
		for (int b = 0; b < ng; b++) {
			double x = (a + 0.5) * ag, y = (b + 0.5) * ag;
			if (near_square(x, y, L, 0.5))
				continue;
			if (r) {
				r[3 * n] = x;
				r[3 * n + 1] = y;
				r[3 * n + 2] = 0;
			}
			n++;
		}
	return n;
}

static lz_edmd_params params_of(double L, size_t n)
{
	lz_edmd_params p = {2, n, (double)n * M_PI / 4 / (L * L), 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	return p;
}

/* The uneven system of side L, melted: the same bits every call. NULL with lz_error. */
static lz_edmd *uneven(double L)
{
	size_t n = sites(L, NULL);
	lz_edmd_params p = params_of(L, n);
	lz_edmd *e = lz_edmd_alloc(&p);
	double *r = malloc(3 * n * sizeof *r), *v = malloc(3 * n * sizeof *v);
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	int st = e && r && v && rng ? LZ_OK : LZ_ENOMEM;
	if (st == LZ_OK) {
		sites(L, r);
		lz_edmd_maxwell(e, rng, v);
		st = lz_edmd_set(e, r, v);
	}
	free(r);
	free(v);
	lz_rng_free(rng);
	if (st == LZ_OK) {
		e->rebase_auto = 0;
		st = melt_in(e, MELT, REBASE);
	}
	if (st != LZ_OK) {
		lz_edmd_free(e);
		return NULL;
	}
	return e;
}

/* ---- the runs ---- */

typedef struct {
	int P, kind, balanced;
	double c, predicted;  /* the pilot's largest share over the mean, for these cuts */
	double border;        /* BORDER cells / cells */
	double border_load;   /* the pilot's events in BORDER cells / all */
	par_result r;
} point;

/* The busiest rank's load over the mean, for cuts `cut` and the cells' load. */
static double imbalance(const lz_pedmd_domains *d, const double *load, const uint32_t *cut)
{
	double total = 0;
	for (size_t c = 0; c < d->ncells; c++)
		total += load[c];
	return total > 0 ? lz_pedmd_busiest(d, load, cut) * d->P / total : 1;
}

typedef struct {
	const lz_edmd *start, *ref, *pilot_ref;
	lz_edmd *pic;
	double R, t_stop, t_pilot;
	double *load;         /* per cell, the pilot's */
	double *map_load;     /* per cell, for the map: the pilot of MAP_P along Morton */
	uint32_t map_cut[2][LZ_PEDMD_RANKS_MAX + 1];
} bench;

/* Pilot, rebalance, and the two measured runs for P ranks along `kind`. */
static int one_setup(bench *b, int P, int kind, point out[2])
{
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(b->start, P, kind);
	if (!d)
		return LZ_EINVAL;
	par_setup q = {P, kind, stub_on(&CLUSTER, P, SEED), {P / b->R, REBASE, 0, 0.05, 0, 1, 0, 1.125, 1},
	               NULL, 0};
	par_result pilot;
	int st = par_run(b->start, &q, b->t_pilot, b->pilot_ref, NULL, b->pic, b->load, &pilot);
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1];
	if (st == LZ_OK && !exact(&pilot))
		st = lz_error(LZ_EDOM, "the pilot run of %d ranks is not the serial run", P);
	if (st == LZ_OK) {
		int moved = lz_pedmd_rebalance(d, b->load, q.pp.threshold, cut);
		printf("  P = %2d %-6s pilot to t = %g: imbalance %.3f with even cuts, %.3f with the "
		       "new ones (%s)\n", P, curve_name[kind], b->t_pilot,
		       imbalance(d, b->load, d->cut), imbalance(d, b->load, cut),
		       moved ? "moved" : "kept: not better by the threshold");
		if (P == MAP_P && kind == LZ_PEDMD_MORTON) {
			memcpy(b->map_load, b->load, d->ncells * sizeof *b->load);
			memcpy(b->map_cut[0], d->cut, (size_t)(P + 1) * sizeof *cut);
			memcpy(b->map_cut[1], cut, (size_t)(P + 1) * sizeof *cut);
		}
	}
	for (int bal = 0; bal < 2 && st == LZ_OK; bal++) {
		point *p = &out[bal];
		p->P = P;
		p->kind = kind;
		p->balanced = bal;
		q.cut = bal ? cut : NULL;
		p->predicted = imbalance(d, b->load, bal ? cut : d->cut);
		p->border = border_share(b->start, P, kind, q.cut, NULL);
		p->border_load = border_share(b->start, P, kind, q.cut, b->load);
		st = isnan(p->border) || isnan(p->border_load) ? LZ_ENOMEM
		                      : best_window(b->start, q, b->R, b->t_stop, b->ref, b->pic, &p->r,
		                                    &p->c);
	}
	lz_pedmd_domains_free(d);
	return st;
}

/* ---- output ---- */

static void print_point(const point *p, double T1)
{
	const par_result *r = &p->r;
	printf("  P = %2d %-6s %-8s  imbalance %6.3f (pilot %6.3f)  border: cells %.3f, events "
	       "%.3f  c %4.2g  T %.5g s  S %6.3f  committed/processed %.3f  rollbacks %4llu%s\n",
	       p->P, curve_name[p->kind], p->balanced ? "balanced" : "even", r->load_ratio,
	       p->predicted, p->border, p->border_load, p->c, r->vtime, T1 / r->vtime,
	       (double)r->c.committed / (double)r->c.processed, (unsigned long long)r->c.rollbacks,
	       exact(r) ? "" : "  NOT THE SERIAL RUN");
}

static void point_row(lz_data *d, const point *p, double T1)
{
	const par_result *r = &p->r;
	double row[NCOL] = {p->P, p->kind, p->balanced, r->load_ratio, p->predicted, p->border,
	                    p->border_load, p->c, r->vtime, T1 / r->vtime,
	                    (double)r->c.committed / (double)r->c.processed, (double)r->c.rollbacks,
	                    (double)r->messages, exact(r)};
	lz_data_row(d, row);
}

static int write_points(lz_lesson *L, const point *pts, int n, double T1)
{
	static const char *names[NCOL] = {"P", "curve", "balanced", "imbalance",
	                                  "imbalance_pilot", "border_fraction", "border_load", "c",
	                                  "T_virtual", "S", "efficiency", "rollbacks", "messages",
	                                  "exact"};
	static const char *units[NCOL] = {"", "0 rows, 1 Morton", "0 even cuts, 1 balanced",
	                                  "largest rank load / mean", "the same, predicted",
	                                  "BORDER cells / cells",
	                                  "pilot events in BORDER cells / all",
	                                  "events per rank", "s", "T(1)/T(P)",
	                                  "committed/processed", "", "", "1: yes"};
	lz_data *d = lz_lesson_data(L, "balance.dat", "even against balanced cuts of an uneven "
	                            "system", NCOL, names, units);
	if (!d)
		return LZ_EIO;
	for (int kind = 0; kind < 2; kind++)  /* a series at a time: gnuplot joins its points */
		for (int bal = 0; bal < 2; bal++)
			for (int k = 0; k < n; k++)
				if (pts[k].kind == kind && pts[k].balanced == bal)
					point_row(d, &pts[k], T1);
	if (lz_data_close(d) != LZ_OK)
		return LZ_EIO;
	static const char *rnames[] = {"rank", "committed_even", "committed_balanced"};
	static const char *runits[] = {"", "events", "events"};
	d = lz_lesson_data(L, "balance_ranks.dat", "each rank's committed events, P = 8 along the "
	                   "Morton curve", 3, rnames, runits);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < n; k += 2)
		if (pts[k].P == MAP_P && pts[k].kind == LZ_PEDMD_MORTON)
			for (int r = 0; r < MAP_P; r++) {
				double row[3] = {r, pts[k].r.per_rank[r], pts[k + 1].r.per_rank[r]};
				lz_data_row(d, row);
			}
	return lz_data_close(d);
}

/* The map of the cells: centre, pilot load, owner with even and with balanced cuts;
 * rows of cells separated by blank lines (gnuplot's `with image`). */
static int write_map(lz_lesson *L, const lz_edmd *e, const bench *b)
{
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(e, MAP_P, LZ_PEDMD_MORTON);
	FILE *f = d ? lz_lesson_fopen(L, "balance_map.dat") : NULL;
	if (!f) {
		lz_pedmd_domains_free(d);
		return LZ_EIO;
	}
	fprintf(f, "# the cells of the uneven system, P = %d along the Morton curve: the pilot's "
	        "committed events per cell, and the owner under even and balanced cuts\n"
	        "# x [σ]  y [σ]  load [events]  owner_even  owner_balanced\n", MAP_P);
	for (int y = 0; y < e->m[1]; y++) {
		for (int x = 0; x < e->m[0]; x++) {
			uint32_t c = (uint32_t)(y * e->m[0] + x);
			memcpy(d->cut, b->map_cut[0], sizeof b->map_cut[0]);
			int even = lz_pedmd_owner(d, c);
			memcpy(d->cut, b->map_cut[1], sizeof b->map_cut[1]);
			fprintf(f, "%g %g %g %d %d\n", (x + 0.5) * e->w[0], (y + 0.5) * e->w[1],
			        b->map_load[c], even, lz_pedmd_owner(d, c));
		}
		fprintf(f, "\n");
	}
	lz_pedmd_domains_free(d);
	return lz_lesson_fclose(L, f, "balance_map.dat");
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "06", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	lz_edmd *start = uneven(sz->L), *ref = uneven(sz->L), *pilot_ref = uneven(sz->L);
	lz_edmd_params pp = params_of(sz->L, start ? start->n : 1);
	lz_edmd *pic = lz_edmd_alloc(&pp);
	double *load = start ? malloc(start->ncells * sizeof *load) : NULL;
	double *map_load = start ? calloc(start->ncells, sizeof *map_load) : NULL;
	if (!start || !ref || !pilot_ref || !pic || !load || !map_load)
		return lz_lesson_error(&L);
	bench b = {start, ref, pilot_ref, pic, 0, lz_edmd_time(start) + sz->time,
	           lz_edmd_time(start) + sz->time / 4, load, map_load, {{0}}};
	if (serial_run(ref, b.t_stop, REBASE, NULL) != LZ_OK ||
	    serial_run(pilot_ref, b.t_pilot, REBASE, NULL) != LZ_OK)
		return lz_lesson_error(&L);
	b.R = (double)ref->events / sz->time;
	double T1 = (double)ref->events * CLUSTER.cost_event;
	printf("balance: 2D, N = %zu in a box of side %g (η = %.3f overall): a dense square "
	       "(η = %g) in a quarter, a dilute gas (η = %g) in the rest; %zu cells; %llu serial "
	       "events in %g time units (one rank: %.4g virtual s); seed %u\n", start->n, sz->L,
	       pp.packing, ETA_DENSE, ETA_DILUTE, start->ncells, (unsigned long long)ref->events,
	       sz->time, T1, SEED);

	point pts[2 * 2 * NPS];
	int n = 0, st = LZ_OK;
	for (int k = 0; k < sz->np && st == LZ_OK; k++)
		for (int kind = 0; kind < 2 && st == LZ_OK; kind++, n += 2)
			st = one_setup(&b, ranks_of[k], kind, &pts[n]);
	if (st != LZ_OK)
		return lz_lesson_error(&L);
	for (int k = 0; k < n; k++)
		print_point(&pts[k], T1);
	if (write_points(&L, pts, n, T1) != LZ_OK || write_map(&L, start, &b) != LZ_OK)
		return lz_lesson_error(&L);

	int good = 0, within = 1, morton_faster = 1, more_border = 1;
	double even_min = INFINITY, bal_max = 0, gain_morton = INFINITY;
	for (int k = 0; k < n; k += 2) {
		const point *ev = &pts[k], *bal = &pts[k + 1];
		good += exact(&ev->r) + exact(&bal->r);
		within &= bal->r.load_ratio < 1.15;
		bal_max = fmax(bal_max, bal->r.load_ratio);
		more_border &= bal->border_load > ev->border_load;
		if (ev->P == MAP_P)
			even_min = fmin(even_min, ev->r.load_ratio);
		if (ev->kind == LZ_PEDMD_MORTON) {
			morton_faster &= bal->r.vtime < ev->r.vtime;
			gain_morton = fmin(gain_morton, ev->r.vtime / bal->r.vtime);
		}
	}
	printf("  %d of %d runs committed the serial events and ended with the serial records: "
	       "%s\n", good, n, lz_lesson_check(&L, good == n));
	printf("  even cuts at P = %d: imbalance at least %.3f (at least 1.5): %s\n", MAP_P,
	       even_min, lz_lesson_check(&L, even_min >= 1.5));
	printf("  balanced cuts: imbalance at most %.3f (below 1.15) for every P and curve: %s\n",
	       bal_max, lz_lesson_check(&L, within));
	printf("  balanced cuts along the Morton curve faster in virtual time at every P (at least "
	       "%.2f times): %s\n", gain_morton, lz_lesson_check(&L, morton_faster));
	printf("  balanced cuts put a larger share of the events into BORDER cells than even cuts, "
	       "for every P and curve: %s\n", lz_lesson_check(&L, more_border));

	lz_json *j = lz_lesson_json(&L, "balance.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", (long long)start->n);
	lz_json_num(j, "imbalance_even_P8_min", even_min);
	lz_json_num(j, "imbalance_balanced_max", bal_max);
	lz_json_num(j, "speed_gain_morton_min", gain_morton);
	lz_json_int(j, "identical_runs", good);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	free(load);
	free(map_load);
	lz_edmd_free(start);
	lz_edmd_free(ref);
	lz_edmd_free(pilot_ref);
	lz_edmd_free(pic);
	return lz_lesson_finish(&L, "every run exact; balanced cuts even out the load, and along "
	                        "the Morton curve run faster");
}
