/* speedup — lesson 06, experiment: HOW MUCH FASTER ARE P RANKS? The speed-up of the
 * optimistic engine against the number of ranks at a fixed system size (strong
 * scaling, as in Miller & Luding's figs. 6 and 7), in the virtual time of the stub:
 * each rank's clock advances by the cost of the events it carries out and of the
 * messages it sends and receives, a message arrives a latency after it was sent, a
 * reduction completes a latency after the last rank joined it (lz/msg.h). The
 * machine is the cluster of pedmd_lesson.h (1 µs an event, 0.5 µs a message at each
 * end, 2 µs latency); the same CPU on an ideal network (messages free and instant)
 * separates what the network costs from what the algorithm itself wastes.
 *
 * The systems: 2D disks at η = 0.3 and 3D spheres at η = 0.25 (the paper's volume
 * fractions), periodic, elastic, melted from the lattice, then run for a fixed time.
 * P = 1, 2, 4, ..., 32 (16 with --quick), along rows and along the Morton curve.
 * The window: its first length is c·P/R, R the serial events per unit time — about c
 * events per rank — and it adapts between 1/64 and 64 times that; for every P the
 * fastest of c = 1/64, 1/16, 1/4, 1 and 4 is kept, tried upwards while they get faster
 * (the runs are deterministic: "fastest" is a property of the setup, not luck). T(1): one
 * rank, windows as long as the re-base interval (one rank never rolls back). Also
 * printed: the fraction of the cells that are BORDER cells, where events must be
 * told to other ranks.
 *
 * S(P) = T(1)/T(P). Efficiency: committed/processed events (the rest was rolled back).
 * The exponent a of S ∝ P^a is fitted on P >= 2 (gsl_fit_linear on log-log).
 *
 * Checks: every run commits the serial events and ends with the serial records bit for
 * bit; T(1) is the serial engine's cost (E·cost_event) within 1 %; in 2D along the
 * Morton curve the speed-up at the largest P exceeds 2.
 *
 * Usage: speedup OUTDIR [--quick]
 * Writes OUTDIR/speedup.dat, speedup_fit.dat and speedup.json.
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

#include "pedmd_lesson.h"

#define SEED 6002u
#define PMAX_N 6
#define NSERIES 3  /* rows on the cluster, Morton on the cluster, Morton ideal */
#define NCOL 17

static const int ranks_of[PMAX_N] = {1, 2, 4, 8, 16, 32};
static const char *series_name[NSERIES] = {"rows, cluster", "Morton, cluster",
                                           "Morton, ideal network"};
static const int series_kind[NSERIES] = {LZ_PEDMD_ROWS, LZ_PEDMD_MORTON, LZ_PEDMD_MORTON};
static const machine *series_machine[NSERIES] = {&CLUSTER, &CLUSTER, &IDEAL};

typedef struct {
	size_t n2, n3;
	double time2, time3;  /* the measured run, after the melt */
	int np;               /* how many of ranks_of */
} sizes;

static const sizes full = {100000, 50000, 0.5, 0.25, 6};
static const sizes quick = {20000, 10000, 0.5, 0.25, 5};

typedef struct {
	double S[NSERIES][PMAX_N];
	double a[NSERIES], a_err[NSERIES];
	double T1, T1_serial;
	int exact_runs, runs;
	size_t n;
	double eta;
} dim_result;

static int one_dim(const gas *g, double time, int np, lz_data *d, dim_result *out)
{
	lz_edmd *start = gas_make(g), *ref = gas_make(g), *pic = gas_blank(g);
	int st = start && ref && pic ? LZ_OK : LZ_ENOMEM;
	double t_stop = start ? lz_edmd_time(start) + time : 0;
	if (st == LZ_OK)
		st = serial_run(ref, t_stop, g->rebase, NULL);
	double R = (double)ref->events / time;
	if (st == LZ_OK)
		printf("  %dD, N = %zu, η = %g, %zu cells: %llu serial events in %g time units "
		       "(R = %.4g per unit time)\n", g->dim, g->n, g->eta, ref->ncells,
		       (unsigned long long)ref->events, time, R);
	out->T1_serial = (double)ref->events * CLUSTER.cost_event;
	out->n = g->n;
	out->eta = g->eta;
	for (int s = 0; s < NSERIES && st == LZ_OK; s++) {
		printf("    %s:\n      P  border  best c  T virtual s      S   committed/  windows  "
		       "rollbacks  conservative  messages/  saved kB  load max/\n        cells"
		       "                                    processed                                "
		       "  event               mean\n", series_name[s]);
		double T1 = NAN;
		for (int k = 0; k < np && st == LZ_OK; k++) {
			int P = ranks_of[k];
			par_result r = {0};
			double c = NAN;
			par_setup q = {P, series_kind[s], stub_on(series_machine[s], P, SEED),
			               {NAN, g->rebase, 0, 0.1, 0, 1, 0, 1.125, 1}, NULL, 0};
			if ((st = best_window(start, q, R, t_stop, ref, pic, &r, &c)) != LZ_OK)
				break;
			if (P == 1)
				T1 = r.vtime;
			if (s == 0 && P == 1)
				out->T1 = r.vtime;
			double S = T1 / r.vtime, eff = (double)r.c.committed / (double)r.c.processed;
			double mpe = (double)r.messages / (double)r.c.committed;
			double bf = border_share(start, P, series_kind[s], NULL, NULL);
			if (isnan(bf)) {
				st = LZ_ENOMEM;
				break;
			}
			out->S[s][k] = S;
			out->runs++;
			out->exact_runs += exact(&r);
			printf("    %3d %7.4f %6.2g %12.5g %7.3f %10.3f %9llu %9llu %11llu %14.3f %9.1f %9.3f%s\n",
			       P, bf, c, r.vtime, S, eff, (unsigned long long)r.c.windows,
			       (unsigned long long)r.c.rollbacks, (unsigned long long)r.c.conservative, mpe,
			       (double)r.c.saved_bytes / 1024, r.load_ratio,
			       exact(&r) ? "" : "  NOT THE SERIAL RUN");
			double row[NCOL] = {g->dim, s, P, c, r.vtime, S, eff, (double)r.c.windows,
			                    (double)r.c.rollbacks, (double)r.c.conservative,
			                    (double)r.messages, mpe, (double)r.c.saved_bytes,
			                    r.load_ratio, (double)r.c.committed, (double)r.c.processed, bf};
			lz_data_row(d, row);
		}
		if (st == LZ_OK) {
			fit_power(ranks_of, out->S[s], np, &out->a[s], &out->a_err[s]);
			printf("      S ∝ P^%.2f ± %.2f (P = 2 .. %d)\n", out->a[s], out->a_err[s],
			       ranks_of[np - 1]);
		}
	}
	lz_edmd_free(start);
	lz_edmd_free(ref);
	lz_edmd_free(pic);
	return st;
}

/* The fitted exponents, with S(2) (the plot draws the paper's exponents through it)
 * and the system, per dimension and series. */
static int write_fits(lz_lesson *L, const dim_result *res, int np)
{
	static const char *names[] = {"dim", "series", "a", "a_err", "S_at_P2", "P_max", "N",
	                              "eta"};
	static const char *units[] = {"", "0 rows cluster, 1 Morton cluster, 2 Morton ideal", "",
	                              "", "", "", "", ""};
	lz_data *d = lz_lesson_data(L, "speedup_fit.dat", "S ∝ P^a fitted on P >= 2", 8, names,
	                            units);
	if (!d)
		return LZ_EIO;
	for (int dim = 2; dim <= 3; dim++)
		for (int s = 0; s < NSERIES; s++) {
			const dim_result *r = &res[dim - 2];
			double row[8] = {dim, s, r->a[s], r->a_err[s], r->S[s][1], ranks_of[np - 1],
			                 (double)r->n, r->eta};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "06", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("speedup: strong scaling in virtual time; %s: %g µs an event, %g µs a message at "
	       "each end, %g µs latency; seed %u\n", CLUSTER.name, CLUSTER.cost_event * 1e6,
	       CLUSTER.cost_message * 1e6, CLUSTER.latency * 1e6, SEED);
	static const char *names[NCOL] = {"dim", "series", "P", "c", "T_virtual", "S",
	                                  "efficiency", "windows", "rollbacks", "conservative",
	                                  "messages", "messages_per_event", "saved_bytes",
	                                  "load_max_over_mean", "committed", "processed",
	                                  "border_fraction"};
	static const char *units[NCOL] = {"", "0 rows cluster, 1 Morton cluster, 2 Morton ideal",
	                                  "", "events per rank (first window)", "s", "T(1)/T(P)",
	                                  "committed/processed", "", "", "", "", "", "bytes", "",
	                                  "", "", "BORDER cells / cells"};
	lz_data *d = lz_lesson_data(&L, "speedup.dat", "speed-up of the optimistic engine at "
	                            "fixed N, virtual time", NCOL, names, units);
	if (!d)
		return lz_lesson_error(&L);
	gas g2 = {2, sz->n2, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, SEED, 1, 1};
	gas g3 = {3, sz->n3, 0.25, LZ_EDMD_WALLS_NONE, 0, 1, SEED, 1, 1};
	dim_result res[2];
	memset(res, 0, sizeof res);
	int st = one_dim(&g2, sz->time2, sz->np, d, &res[0]);
	if (st == LZ_OK)
		st = one_dim(&g3, sz->time3, sz->np, d, &res[1]);
	if (st != LZ_OK || lz_data_close(d) != LZ_OK || write_fits(&L, res, sz->np) != LZ_OK)
		return lz_lesson_error(&L);

	int runs = res[0].runs + res[1].runs, good = res[0].exact_runs + res[1].exact_runs;
	printf("  %d of %d runs committed the serial events and ended with the serial records "
	       "bit for bit: %s\n", good, runs, lz_lesson_check(&L, good == runs));
	for (int k = 0; k < 2; k++)
		printf("  %dD: T(1) = %.5g s against the serial engine's E·cost_event = %.5g s (within "
		       "1 %%): %s\n", k + 2, res[k].T1, res[k].T1_serial,
		       lz_lesson_check(&L, fabs(res[k].T1 / res[k].T1_serial - 1) < 0.01));
	double S2 = res[0].S[1][sz->np - 1];
	printf("  2D Morton on the cluster: S(%d) = %.2f > 2: %s\n", ranks_of[sz->np - 1], S2,
	       lz_lesson_check(&L, S2 > 2));
	printf("  Miller & Luding (figs. 6, 7): S ∝ P^0.49 (2D), P^0.45 (3D); here on the "
	       "cluster, Morton: P^%.2f (2D), P^%.2f (3D)\n", res[0].a[1], res[1].a[1]);

	lz_json *j = lz_lesson_json(&L, "speedup.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N_2D", (long long)sz->n2);
	lz_json_int(j, "N_3D", (long long)sz->n3);
	lz_json_int(j, "P_max", ranks_of[sz->np - 1]);
	lz_json_num(j, "S_max_2D_morton", res[0].S[1][sz->np - 1]);
	lz_json_num(j, "S_max_2D_rows", res[0].S[0][sz->np - 1]);
	lz_json_num(j, "S_max_3D_morton", res[1].S[1][sz->np - 1]);
	lz_json_num(j, "S_max_3D_rows", res[1].S[0][sz->np - 1]);
	lz_json_err(j, "exponent_2D_morton", res[0].a[1], res[0].a_err[1]);
	lz_json_err(j, "exponent_3D_morton", res[1].a[1], res[1].a_err[1]);
	lz_json_err(j, "exponent_2D_morton_ideal", res[0].a[2], res[0].a_err[2]);
	lz_json_err(j, "exponent_3D_morton_ideal", res[1].a[2], res[1].a_err[2]);
	lz_json_int(j, "identical_runs", good);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "every run the serial run; T(1) the serial cost; 2D speed-up "
	                        "above 2");
}
