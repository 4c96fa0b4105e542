/* equal — lesson 06, experiment: THE PARALLEL RUN IS THE SERIAL RUN. P ranks of the
 * optimistic engine (lz/pedmd.h) on the stub back-end commit the very events of the
 * serial engine of stage 05, and end with the very same particles, bit for bit —
 * whatever P, the curve the domains are cut along, and the order in which the stub
 * interleaves the ranks and delivers their messages.
 *
 * For 2D disks and 3D spheres, three gases (periodic and elastic; walls on x with
 * gravity; a closed box with restitution 0.8, cooling), each from its lattice start:
 * the serial run, re-based at the multiples of 0.5 as the ranks re-base, its events
 * logged; then P = 1, 2, 3, 4, 8 ranks along rows and along the Morton curve, under
 * two schedules: a seeded random interleaving with messages held back 0-3 turns, run
 * under the rollback check (every window rolled back and run again, which must end
 * alike), and virtual time on the cluster of pedmd_lesson.h. Every cut of every run is
 * audited
 * (lz_pedmd_audit: each particle owned once, in its owner's cell and heap; every ghost
 * a copy of its owner's record and event).
 *
 * Checks: every run commits exactly the serial events (the same count of each kind,
 * and the log record by record: time, particles, kind) and ends with every particle
 * record (position, velocity, own clock, collision count, cell: 64 bytes) equal to
 * the serial one (memcmp); the runs did roll back (the equality was earned, not given
 * by runs that never erred) and never needed a conservative step (a rollback ends the
 * next window at the error, which cannot come again at a window's end); the elastic gases
 * conserve energy (to 1e-10, relative), the inelastic one loses some.
 *
 * Usage: equal OUTDIR [--quick]
 * Writes OUTDIR/equal.dat and equal.json.
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

#define SEED 6001u
#define NVAR 3
#define NP 5
#define NCOL 16

static const int ranks_of[NP] = {1, 2, 3, 4, 8};
static const char *variant_name[NVAR] = {"periodic", "walls+gravity", "box, e=0.8"};
static const char *curve_name[2] = {"rows", "Morton"};
static const char *policy_name[2] = {"random", "virtual"};

typedef struct {
	size_t n2, n3;  /* particles in 2D, 3D */
	double time;    /* of every run */
} sizes;

static const sizes full = {1600, 2000, 2.0};
static const sizes quick = {400, 500, 1.0};

/* Gas v in dimension dim. */
static gas gas_of(int v, int dim, const sizes *sz)
{
	gas g = {dim, dim == 2 ? sz->n2 : sz->n3, 0.3, LZ_EDMD_WALLS_NONE, 0, 1, SEED, 0, 0.5};
	if (v == 1) {  /* a gas falling onto the floor x = 1/2 */
		g.eta = 0.2;
		g.walls = LZ_EDMD_WALLS_X;
		g.gravity = 1;
	} else if (v == 2) {  /* a granular gas cooling in a closed box */
		g.eta = 0.15;
		g.walls = LZ_EDMD_WALLS_BOX;
		g.restitution = 0.8;
	}
	return g;
}

/* The total energy of particles that all sit at their own clock t0 (a gathered
 * picture at the end of a run): kinetic plus g x. */
static double energy_at_t0(const lz_edmd *e)
{
	double E = 0;
	for (size_t i = 0; i < e->n; i++) {
		const lz_edmd_particle *p = &e->p[i];
		E += 0.5 * (p->v[0] * p->v[0] + p->v[1] * p->v[1] + p->v[2] * p->v[2]) + e->g * p->r[0];
	}
	return E;
}

typedef struct {
	int runs, exact, audited;
	uint64_t rollbacks, conservative, events;
	int energy_ok;
} tally;

/* The serial run of gas g and then every parallel run of it, into d and t. */
static int one_gas(lz_lesson *L, const gas *g, int v, double time, lz_data *d, tally *t)
{
	lz_edmd *start = gas_make(g), *ref = gas_make(g), *pic = gas_blank(g);
	event_log log = {NULL, 0, 0};
	int st = start && ref && pic ? LZ_OK : LZ_ENOMEM;
	double E0 = start ? lz_edmd_energy(start) : 0;
	if (st == LZ_OK)
		st = serial_run(ref, time, g->rebase, &log);
	double E1 = st == LZ_OK ? energy_at_t0(ref) : 0, drift = (E1 - E0) / fabs(E0);
	int conserves = g->restitution == 1 ? fabs(drift) < 1e-10 : drift < 0;
	t->energy_ok &= conserves;
	if (st == LZ_OK)
		printf("  %dD %-14s N = %zu, %zu serial events to t = %g; energy %+.2e relative "
		       "(%s): %s\n", g->dim, variant_name[v], g->n, log.n, time, drift,
		       g->restitution == 1 ? "conserved" : "lost", lz_lesson_check(L, conserves));
	for (int k = 0; k < NP && st == LZ_OK; k++)
		for (int kind = 0; kind < 2 && st == LZ_OK; kind++)
			for (int pol = 0; pol < 2 && st == LZ_OK; pol++) {
				par_setup q = {ranks_of[k], kind, stub_on(&CLUSTER, 1, SEED + 17u * (unsigned)k),
				               {0.05, g->rebase, 0, 0.1, 1, 16, 0, 1.125, 1}, NULL, 1};
				if (pol == 0) {  /* random, and every window rolled back and run again */
					q.sp.policy = LZ_STUB_RANDOM;
					q.sp.delay = 3;
					q.pp.recheck = 1;
				}
				par_result r;
				if ((st = par_run(start, &q, time, ref, &log, pic, NULL, &r)) != LZ_OK)
					break;
				int ok = exact(&r);
				t->runs++;
				t->exact += ok;
				t->audited += r.audits > 0;
				t->rollbacks += r.c.rollbacks;
				t->conservative += r.c.conservative;
				t->events += r.c.processed;
				printf("  %dD %-14s P = %d %-6s %-7s committed %6llu of %6zu, processed %6llu, "
				       "%4llu windows, %3llu rollbacks, %3llu conservative, %4llu audits: %s\n",
				       g->dim, variant_name[v], q.P, curve_name[kind],
				       policy_name[pol], (unsigned long long)r.c.committed, log.n,
				       (unsigned long long)r.c.processed, (unsigned long long)r.c.windows,
				       (unsigned long long)r.c.rollbacks, (unsigned long long)r.c.conservative,
				       (unsigned long long)r.audits,
				       ok ? "identical" : "DIFFERENT");
				double row[NCOL] = {t->runs, g->dim, v, q.P, kind, pol, (double)r.c.committed,
				                    (double)log.n, (double)r.c.processed, (double)r.c.windows,
				                    (double)r.c.rollbacks, (double)r.c.conservative,
				                    (double)r.messages,
				                    (double)r.audits, r.same_log == 1 && r.same_counts,
				                    r.same_records};
				lz_data_row(d, row);
			}
	free(log.ev);
	lz_edmd_free(start);
	lz_edmd_free(ref);
	lz_edmd_free(pic);
	return st;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "06", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("equal: the parallel runs against the serial run, bit for bit; 2D N = %zu, 3D "
	       "N = %zu, %g time units from the lattice, seed %u\n", sz->n2, sz->n3, sz->time, SEED);
	static const char *names[NCOL] = {"run", "dim", "gas", "P", "curve", "policy",
	                                  "committed", "serial_events", "processed", "windows",
	                                  "rollbacks", "conservative", "messages", "audits",
	                                  "same_events", "same_records"};
	static const char *units[NCOL] = {"", "", "0 periodic, 1 walls+gravity, 2 box e=0.8", "",
	                                  "0 rows, 1 Morton", "0 random, 1 virtual", "", "", "",
	                                  "", "", "", "", "", "1: yes", "1: yes"};
	lz_data *d = lz_lesson_data(&L, "equal.dat", "parallel runs against the serial run: "
	                            "what each did, and whether it ended identical", NCOL, names,
	                            units);
	if (!d)
		return lz_lesson_error(&L);
	tally t = {0, 0, 0, 0, 0, 0, 1};
	int st = LZ_OK;
	for (int dim = 2; dim <= 3 && st == LZ_OK; dim++)
		for (int v = 0; v < NVAR && st == LZ_OK; v++) {
			gas g = gas_of(v, dim, sz);
			st = one_gas(&L, &g, v, sz->time, d, &t);
		}
	if (st != LZ_OK || lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	printf("  %d of %d runs committed the serial events and ended with the serial records, "
	       "bit for bit: %s\n", t.exact, t.runs, lz_lesson_check(&L, t.exact == t.runs));
	printf("  %d of %d runs audited at their cuts: %s\n", t.audited, t.runs,
	       lz_lesson_check(&L, t.audited == t.runs));
	printf("  along the way: %llu rollbacks (at least one) and %llu conservative steps "
	       "(none needed): %s\n", (unsigned long long)t.rollbacks,
	       (unsigned long long)t.conservative,
	       lz_lesson_check(&L, t.rollbacks > 0 && t.conservative == 0));

	lz_json *j = lz_lesson_json(&L, "equal.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "runs", t.runs);
	lz_json_int(j, "identical_runs", t.exact);
	lz_json_int(j, "rollbacks", (long long)t.rollbacks);
	lz_json_int(j, "conservative_steps", (long long)t.conservative);
	lz_json_int(j, "events_processed", (long long)t.events);
	lz_json_bool(j, "energy_as_expected", t.energy_ok);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "%d parallel runs identical to the serial run", t.runs);
}
