/* weak — lesson 06, experiment: DOES A LARGER MACHINE RUN A LARGER SYSTEM AS FAST? The
 * speed-up of the optimistic engine when the system grows with the ranks, N = n·P
 * (weak scaling, as in Miller & Luding's fig. 8), in the virtual time of the stub on
 * the cluster of pedmd_lesson.h (1 µs an event, 0.5 µs a message at each end, 2 µs
 * latency), and the memory a rank needs for it (their fig. 9).
 *
 * The systems: 2D disks at η = 0.3 and 3D spheres at η = 0.25, periodic, elastic,
 * melted from the lattice, n particles per rank, along the Morton curve; P = 1, 2, 4,
 * ..., 64 (16 with --quick). The first window is the best of c = 1/64 .. 4 events per
 * rank (best_window). Scaled speed-up: S_w(P) = P·T(1)/T(P), T(P) the virtual time of
 * P ranks on N = n·P particles for the same simulated time — P when the larger machine
 * keeps pace, 1 when it is no faster per particle than one rank. Its exponent a of
 * S_w ∝ P^a is fitted on P >= 2 (gsl_fit_linear on log-log). Memory: the most bytes one
 * rank saved in one window, and what a rank that keeps only its own particles, its
 * ghosts and its saved state would hold: 64 bytes a record for N/P + ghosts, against
 * the 64·N of the arrays each stub rank keeps for all N.
 *
 * Checks: every run commits the serial events and ends with the serial records bit for
 * bit; in 2D the fitted exponent is at least the paper's, 0.5.
 *
 * Usage: weak OUTDIR [--quick]
 * Writes OUTDIR/weak.dat and weak.json.
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

#define SEED 6005u
#define PMAX_N 7
#define NCOL 12

static const int ranks_of[PMAX_N] = {1, 2, 4, 8, 16, 32, 64};

typedef struct {
	size_t n2, n3;        /* particles per rank */
	double time2, time3;  /* the measured run, after the melt */
	int np;               /* how many of ranks_of */
} sizes;

static const sizes full = {2500, 1500, 0.5, 0.25, 7};
static const sizes quick = {1000, 600, 0.5, 0.25, 5};

typedef struct {
	double S[PMAX_N];
	double a, a_err;
	int exact_runs, runs;
} dim_result;

/* The most particles any rank of P holds along the Morton curve: its own and its
 * ghosts, every particle in a cell that is not FAR to it. 0 without memory. */
static size_t most_held(const lz_edmd *e, int P)
{
	lz_pedmd_domains *d = lz_pedmd_domains_alloc(e, P, LZ_PEDMD_MORTON);
	uint8_t *cls = d ? malloc(e->ncells) : NULL;
	size_t most = 0;
	for (int r = 0; cls && r < P; r++) {
		size_t held = 0;
		lz_pedmd_classify(e, d, r, cls);
		for (size_t i = 0; i < e->n; i++)
			held += cls[e->p[i].cell] != LZ_PEDMD_FAR;
		most = held > most ? held : most;
	}
	free(cls);
	lz_pedmd_domains_free(d);
	return most;
}

/* One point: P ranks on N = n·P particles. */
static int one_point(const gas *g, double time, int P, double *T1, lz_data *d, dim_result *out,
                     int k)
{
	lz_edmd *start = gas_make(g), *ref = gas_make(g), *pic = gas_blank(g);
	int st = start && ref && pic ? LZ_OK : LZ_ENOMEM;
	double t_stop = start ? lz_edmd_time(start) + time : 0;
	if (st == LZ_OK)
		st = serial_run(ref, t_stop, g->rebase, NULL);
	par_result r = {0};
	double c = NAN;
	if (st == LZ_OK) {
		double R = (double)ref->events / time;
		par_setup q = {P, LZ_PEDMD_MORTON, stub_on(&CLUSTER, P, SEED),
		               {NAN, g->rebase, 0, 0.1, 0, 1, 0, 1.125, 1}, NULL, 0};
		st = best_window(start, q, R, t_stop, ref, pic, &r, &c);
	}
	double held = st == LZ_OK ? (double)most_held(start, P) : 0;
	if (st == LZ_OK && held == 0)
		st = lz_error(LZ_ENOMEM, "no memory to count the particles a rank holds");
	if (st == LZ_OK) {
		if (P == 1)
			*T1 = r.vtime;
		double S = P * *T1 / r.vtime, eff = (double)r.c.committed / (double)r.c.processed;
		double lean = 64 * held + (double)r.c.saved_bytes, stub = 64.0 * (double)g->n;
		out->S[k] = S;
		out->runs++;
		out->exact_runs += exact(&r);
		printf("    %3d %8zu %6.2g %11.5g %7.3f %10.3f %9llu %10.3f %9.1f %11.1f %9.1f%s\n", P,
		       g->n, c, r.vtime, S, eff, (unsigned long long)r.c.rollbacks,
		       (double)r.messages / (double)r.c.committed, (double)r.c.saved_bytes / 1024,
		       lean / 1024, stub / 1024, exact(&r) ? "" : "  NOT THE SERIAL RUN");
		double row[NCOL] = {g->dim, P, (double)g->n, c, r.vtime, S, eff, (double)r.c.rollbacks,
		                    (double)r.messages / (double)r.c.committed, (double)r.c.saved_bytes,
		                    lean, stub};
		lz_data_row(d, row);
	}
	lz_edmd_free(start);
	lz_edmd_free(ref);
	lz_edmd_free(pic);
	return st;
}

static int one_dim(int dim, size_t n, double time, int np, lz_data *d, dim_result *out)
{
	printf("  %dD, %zu particles per rank, η = %g, Morton, cluster:\n      P        N  best c   T "
	       "virtual     S_w  committed/  rollbacks  messages/  saved kB  lean rank  stub rank\n"
	       "                                                processed               event"
	       "               kB         kB\n", dim, n, dim == 2 ? 0.3 : 0.25);
	double T1 = NAN;
	int st = LZ_OK;
	for (int k = 0; k < np && st == LZ_OK; k++) {
		gas g = {dim, n * (size_t)ranks_of[k], dim == 2 ? 0.3 : 0.25, LZ_EDMD_WALLS_NONE, 0, 1,
		         SEED, 1, 1};
		st = one_point(&g, time, ranks_of[k], &T1, d, out, k);
	}
	if (st == LZ_OK) {
		fit_power(ranks_of, out->S, np, &out->a, &out->a_err);
		printf("      S_w ∝ P^%.2f ± %.2f (P = 2 .. %d)\n", out->a, out->a_err, ranks_of[np - 1]);
	}
	return st;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "06", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("weak: weak scaling in virtual time, N = n·P; %s: %g µs an event, %g µs a message "
	       "at each end, %g µs latency; seed %u\n", CLUSTER.name, CLUSTER.cost_event * 1e6,
	       CLUSTER.cost_message * 1e6, CLUSTER.latency * 1e6, SEED);
	static const char *names[NCOL] = {"dim", "P", "N", "c", "T_virtual", "S_w", "efficiency",
	                                  "rollbacks", "messages_per_event", "saved_bytes",
	                                  "lean_rank_bytes", "stub_rank_bytes"};
	static const char *units[NCOL] = {"", "", "", "events per rank (first window)", "s",
	                                  "P T(1)/T(P)", "committed/processed", "", "", "bytes",
	                                  "bytes", "bytes"};
	lz_data *d = lz_lesson_data(&L, "weak.dat", "scaled speed-up at fixed N per rank, virtual "
	                            "time", NCOL, names, units);
	if (!d)
		return lz_lesson_error(&L);
	dim_result res[2] = {{{0}, 0, 0, 0, 0}, {{0}, 0, 0, 0, 0}};
	int st = one_dim(2, sz->n2, sz->time2, sz->np, d, &res[0]);
	if (st == LZ_OK)
		st = one_dim(3, sz->n3, sz->time3, sz->np, d, &res[1]);
	if (st != LZ_OK || lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	int runs = res[0].runs + res[1].runs, good = res[0].exact_runs + res[1].exact_runs;
	int Pmax = ranks_of[sz->np - 1];
	printf("  %d of %d runs committed the serial events and ended with the serial records "
	       "bit for bit: %s\n", good, runs, lz_lesson_check(&L, good == runs));
	printf("  2D: S_w ∝ P^%.2f, at least P^0.5: %s\n", res[0].a,
	       lz_lesson_check(&L, res[0].a >= 0.5));
	printf("  Miller & Luding (fig. 8): S_w ∝ P^0.50; here on the cluster, Morton: P^%.2f "
	       "(2D), P^%.2f (3D)\n", res[0].a, res[1].a);

	lz_json *j = lz_lesson_json(&L, "weak.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "n_per_rank_2D", (long long)sz->n2);
	lz_json_int(j, "n_per_rank_3D", (long long)sz->n3);
	lz_json_int(j, "P_max", Pmax);
	lz_json_num(j, "S_w_max_2D", res[0].S[sz->np - 1]);
	lz_json_num(j, "S_w_max_3D", res[1].S[sz->np - 1]);
	lz_json_err(j, "exponent_2D", res[0].a, res[0].a_err);
	lz_json_err(j, "exponent_3D", res[1].a, res[1].a_err);
	lz_json_int(j, "identical_runs", good);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "every run the serial run; the 2D scaled speed-up at least P^0.5");
}
