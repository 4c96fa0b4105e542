/* window — lesson 06, experiment: THE TRADE. How far should a rank run ahead before
 * the ranks meet at a cut? A short window costs a cut (a few reductions, each a
 * latency) for little work; a long one saves more state and is more likely to be
 * rolled back, wasting the work done since its start. The answer is never wrong —
 * every run commits the serial events bit for bit — so the trade is not cost against
 * error, as in the earlier lessons, but speed against memory and wasted work.
 *
 * The system: 2D disks at η = 0.3, melted, P = 8 ranks along the Morton curve, on the
 * cluster of pedmd_lesson.h, in virtual time. The first window is c·P/R (R: serial
 * events per unit time), about c events per rank; it adapts — an eighth longer after a commit,
 * halved after a rollback — between 1/64 and 64 times that, so c sets both where it
 * starts and how far it may grow. c runs from 1/64 to 64 in factors of 2. Measured:
 * the virtual time, the efficiency (committed/processed events), the fraction of
 * windows rolled back, the conservative steps, the most bytes a rank saved in one
 * window. Then, at the best c, the work per turn (events a rank carries out before it
 * looks at its messages again) from 1 to 256.
 *
 * Checks: every run commits the serial events and ends with the serial records; the
 * virtual time has its minimum inside the range of c (neither end is best: both
 * costs are real); the saved state at the largest c is at least 4 times that at the
 * smallest; long turns (64 and 256 events before the messages are read) are slower
 * than reading them after every event.
 *
 * Usage: window OUTDIR [--quick]
 * Writes OUTDIR/window.dat, window_work.dat and window.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/edmd.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/pedmd.h"

#include "pedmd_lesson.h"

#define SEED 6003u
#define P 8
#define NW 13  /* c = 2^-6 .. 2^6 */
#define NWORK 5
#define NCOL 13

static const int work_of[NWORK] = {1, 4, 16, 64, 256};

typedef struct {
	size_t n;
	double time;
} sizes;

static const sizes full = {40000, 1.0};
static const sizes quick = {10000, 0.5};

typedef struct {
	double c;
	int work;
	par_result r;
} point;

static void print_point(const point *p)
{
	const par_result *r = &p->r;
	printf("  %7.4g %5d %11.5g %10.3f %10.3f %9llu %9llu %11llu %12.1f%s\n", p->c, p->work,
	       r->vtime, (double)r->c.committed / (double)r->c.processed,
	       (double)r->c.rollbacks / (double)r->c.windows, (unsigned long long)r->c.windows,
	       (unsigned long long)r->c.rollbacks, (unsigned long long)r->c.conservative,
	       (double)r->c.saved_bytes / 1024, exact(r) ? "" : "  NOT THE SERIAL RUN");
}

static void data_row(lz_data *d, const point *p, double T1)
{
	const par_result *r = &p->r;
	double row[NCOL] = {p->c, p->work, r->vtime, (double)r->c.committed / (double)r->c.processed,
	                    (double)r->c.rollbacks / (double)r->c.windows, (double)r->c.windows,
	                    (double)r->c.rollbacks, (double)r->c.conservative,
	                    (double)r->c.saved_bytes, (double)r->messages,
	                    (double)r->c.processed, exact(r), T1};
	lz_data_row(d, row);
}

static const char *names[NCOL] = {"c", "work", "T_virtual", "efficiency", "rollback_fraction",
                                  "windows", "rollbacks", "conservative", "saved_bytes",
                                  "messages", "processed", "exact", "T_one_rank"};
static const char *units[NCOL] = {"events per rank (first window)", "events per turn", "s",
                                  "committed/processed", "rollbacks/windows", "", "", "",
                                  "bytes (largest, one rank, one window)", "", "", "1: yes",
                                  "s (the serial engine's cost)"};

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "06", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	gas g = {2, sz->n, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, SEED, 1, 1};
	lz_edmd *start, *ref, *pic;
	double t_stop;
	if (gas_runs(&g, sz->time, &start, &ref, &pic, &t_stop) != LZ_OK)
		return lz_lesson_error(&L);
	double R = (double)ref->events / sz->time;
	printf("window: 2D, N = %zu, η = 0.3, P = %d Morton, %s; %llu serial events in %g time "
	       "units (R = %.4g), seed %u\n", sz->n, P, CLUSTER.name, (unsigned long long)ref->events,
	       sz->time, R, SEED);
	printf("        c  work   T virtual  committed/  rolled back  windows rollbacks "
	       "conservative   saved kB\n                                processed   fraction\n");

	point pts[NW], wk[NWORK];
	int best = 0, good = 0;
	for (int k = 0; k < NW; k++) {
		pts[k].c = ldexp(1, k - NW / 2);
		pts[k].work = 1;
		par_setup q = {P, LZ_PEDMD_MORTON, stub_on(&CLUSTER, P, SEED),
		               {pts[k].c * P / R, g.rebase, 0, 0.1, 0, 1, 0, 1.125, 1}, NULL, 0};
		if (par_run(start, &q, t_stop, ref, NULL, pic, NULL, &pts[k].r) != LZ_OK)
			return lz_lesson_error(&L);
		print_point(&pts[k]);
		good += exact(&pts[k].r);
		if (pts[k].r.vtime < pts[best].r.vtime)
			best = k;
	}
	printf("  work per turn at c = %g:\n", pts[best].c);
	int best_work = 0;
	for (int k = 0; k < NWORK; k++) {
		wk[k].c = pts[best].c;
		wk[k].work = work_of[k];
		par_setup q = {P, LZ_PEDMD_MORTON, stub_on(&CLUSTER, P, SEED),
		               {wk[k].c * P / R, g.rebase, 0, 0.1, 0, wk[k].work, 0, 1.125, 1}, NULL, 0};
		if (par_run(start, &q, t_stop, ref, NULL, pic, NULL, &wk[k].r) != LZ_OK)
			return lz_lesson_error(&L);
		print_point(&wk[k]);
		good += exact(&wk[k].r);
		if (wk[k].r.vtime < wk[best_work].r.vtime)
			best_work = k;
	}
	double T1 = (double)ref->events * CLUSTER.cost_event;
	lz_edmd_free(start);
	lz_edmd_free(ref);
	lz_edmd_free(pic);

	lz_data *d = lz_lesson_data(&L, "window.dat", "the window against the virtual time, the "
	                            "wasted work and the saved state", NCOL, names, units);
	if (!d)
		return lz_lesson_error(&L);
	for (int k = 0; k < NW; k++)
		data_row(d, &pts[k], T1);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	d = lz_lesson_data(&L, "window_work.dat", "events per turn at the best window", NCOL, names,
	                   units);
	if (!d)
		return lz_lesson_error(&L);
	for (int k = 0; k < NWORK; k++)
		data_row(d, &wk[k], T1);
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	int runs = NW + NWORK;
	printf("  %d of %d runs committed the serial events and ended with the serial records: "
	       "%s\n", good, runs, lz_lesson_check(&L, good == runs));
	printf("  fastest at c = %g (T = %.4g s, S = %.2f against one rank's %.4g s), inside "
	       "[%g, %g]: %s\n", pts[best].c, pts[best].r.vtime, T1 / pts[best].r.vtime, T1,
	       pts[0].c, pts[NW - 1].c, lz_lesson_check(&L, best > 0 && best < NW - 1));
	double mem = (double)pts[NW - 1].r.c.saved_bytes / (double)pts[0].r.c.saved_bytes;
	printf("  saved state at c = %g is %.3g times that at c = %g (at least 4): %s\n",
	       pts[NW - 1].c, mem, pts[0].c, lz_lesson_check(&L, mem >= 4));
	printf("  work per turn: fastest at %d; %d and %d events per turn slower than 1 (messages "
	       "read late): %s\n", wk[best_work].work, work_of[NWORK - 2], work_of[NWORK - 1],
	       lz_lesson_check(&L, wk[NWORK - 2].r.vtime > wk[0].r.vtime &&
	                           wk[NWORK - 1].r.vtime > wk[0].r.vtime));

	lz_json *j = lz_lesson_json(&L, "window.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", (long long)sz->n);
	lz_json_int(j, "P", P);
	lz_json_num(j, "best_c", pts[best].c);
	lz_json_num(j, "best_T_virtual_s", pts[best].r.vtime);
	lz_json_num(j, "best_speedup", T1 / pts[best].r.vtime);
	lz_json_num(j, "T_virtual_smallest_c", pts[0].r.vtime);
	lz_json_num(j, "T_virtual_largest_c", pts[NW - 1].r.vtime);
	lz_json_num(j, "efficiency_largest_c",
	            (double)pts[NW - 1].r.c.committed / (double)pts[NW - 1].r.c.processed);
	lz_json_num(j, "saved_kB_smallest_c", (double)pts[0].r.c.saved_bytes / 1024);
	lz_json_num(j, "saved_kB_largest_c", (double)pts[NW - 1].r.c.saved_bytes / 1024);
	lz_json_int(j, "identical_runs", good);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "every window exact; a best window inside the range");
}
