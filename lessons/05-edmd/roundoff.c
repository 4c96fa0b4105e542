/* roundoff — lesson 05, experiment: the absolute-time problem (DynamO, Bannerman, Sargant & Lue, J. Comput. Chem. 32, 3329 (2011):
 * "round-off error will accumulate in these stored absolute times").
 *
 * A double carries 53 bits: next to a time T0 the smallest step it can express is
 * ulp(T0) ≈ 2.2e-16 · T0. Every event time is now + (time to the event), every
 * position r + v (now - t0): once T0 is large those differences lose their low digits,
 * and a collision is carried out up to ulp(T0) early or late — the spheres overlap by
 * about |v_rel| · ulp(T0), or part before they touch.
 *
 * The same system (hard spheres, η = 0.3, from the lattice) runs the same number of
 * events with the clock started at T0 = 1 .. 1e14, twice:
 *   - re-based, as the engine does (lz_edmd_set_time: the clock reads T0, now stays
 *     small, lz_edmd_run re-bases every 8N events): the trajectory cannot depend on T0,
 *     and it does not, bit for bit;
 *   - not re-based: now, every particle's t0 and every heap key are shifted by T0
 *     right after the start and the events are carried out by lz_edmd_step alone
 *     (lz_edmd_run would re-base).
 * Measured: the largest overlap (lz_edmd_max_overlap) at CHECKS times during the run,
 * the relative energy change, and whether the engine's invariants still hold at the
 * end (lz_edmd_audit: every particle inside its cell to 1e-9).
 *
 * Checks: re-based, every T0 gives the same final state bit for bit, with overlaps
 * below 1e-12 σ; not re-based, the overlap never falls as T0 grows, and at the
 * largest T0 it is within a factor 10 of the estimate |v_rel| · ulp(T0), v_rel = √6 the
 * rms relative speed of two spheres at kT = 1.
 *
 * Usage: roundoff OUTDIR [--quick]
 * Writes OUTDIR/roundoff.dat and roundoff.json.
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
#include "lz/rng.h"

#define SEED 5007u
#define ETA 0.3
#define NT0 8
#define CHECKS 10

static const double t0_of[NT0] = {1, 1e3, 1e6, 1e9, 1e11, 1e12, 1e13, 1e14};

typedef struct {
	size_t n;
	double events;   /* per particle */
} sizes;

static const sizes full = {4000, 200};
static const sizes quick = {1000, 100};

typedef struct {
	double overlap;     /* largest over the run */
	double energy;      /* |E/E0 - 1| at the end */
	int audit;          /* lz_edmd_audit at the end: LZ_OK or LZ_EDOM */
	char audit_msg[200];
	double *state;      /* final positions and velocities (re-based runs), 6n */
} outcome;

/* A fresh system, placed on the lattice (the same seed every time). */
static lz_edmd *fresh(size_t n)
{
	lz_edmd_params p = {3, n, ETA, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	if (!e || !rng || lz_edmd_place_lattice(e, rng) != LZ_OK) {
		lz_edmd_free(e);
		e = NULL;
	}
	lz_rng_free(rng);
	return e;
}

/* Shift the clock by T0 without re-basing: every stored time gets T0 added. */
static void shift_clock(lz_edmd *e, double T0)
{
	e->now += T0;
	for (size_t i = 0; i < e->n; i++)
		e->p[i].t0 += T0;
	lz_heap_shift(e->heap, -T0);
}

static int run(size_t n, const sizes *sz, double T0, int rebase, outcome *o)
{
	lz_edmd *e = fresh(n);
	if (!e)
		return LZ_EINVAL;
	double E0 = lz_edmd_energy(e);
	if (rebase)
		lz_edmd_set_time(e, T0);
	else
		shift_clock(e, T0);
	uint64_t per = (uint64_t)(sz->events * (double)n / CHECKS);
	o->overlap = 0;
	int st = LZ_OK;
	for (int c = 0; c < CHECKS && st == LZ_OK; c++) {
		if (rebase) {
			st = lz_edmd_run(e, per, INFINITY);
		} else {
			for (uint64_t k = 0; k < per; k++)
				if (lz_edmd_step(e) < 0) {
					st = lz_error(LZ_EPHYS, "nothing left to happen");
					break;
				}
		}
		o->overlap = fmax(o->overlap, lz_edmd_max_overlap(e, NULL, NULL));
	}
	if (st == LZ_OK) {
		o->energy = fabs(lz_edmd_energy(e) / E0 - 1);
		o->audit = lz_edmd_audit(e);
		snprintf(o->audit_msg, sizeof o->audit_msg, "%s",
		         o->audit == LZ_OK ? "invariants hold" : lz_error_message());
		if (o->state) {
			lz_edmd_sync(e);
			for (size_t i = 0; i < n; i++)
				for (int a = 0; a < 3; a++) {
					o->state[6 * i + a] = e->p[i].r[a];
					o->state[6 * i + 3 + a] = e->p[i].v[a];
				}
		}
	}
	lz_edmd_free(e);
	return st;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	size_t n = sz->n;
	printf("roundoff: %zu hard spheres at η = %g from the lattice, %g events per particle, "
	       "the clock started at T0 = %g .. %g; seed %u\n", n, ETA, sz->events, t0_of[0],
	       t0_of[NT0 - 1], SEED);
	outcome reb[NT0], raw[NT0];
	double *states = malloc(NT0 * 6 * n * sizeof *states);
	if (!states)
		return lz_lesson_error(&L);
	/* the relative speed of two spheres at kT = 1: √(2·3) σ per time unit */
	const double vrel = sqrt(6.0);
	int same = 1, clean = 1;
	printf("        T0   ulp(T0)  |v|·ulp   re-based: overlap   energy   not re-based: "
	       "overlap   energy   audit\n");
	for (int k = 0; k < NT0; k++) {
		reb[k].state = states + (size_t)k * 6 * n;
		raw[k].state = NULL;
		if (run(n, sz, t0_of[k], 1, &reb[k]) != LZ_OK ||
		    run(n, sz, t0_of[k], 0, &raw[k]) != LZ_OK) {
			free(states);
			return lz_lesson_error(&L);
		}
		double ulp = nextafter(t0_of[k], INFINITY) - t0_of[k];
		printf("  %8.0e %9.2e %8.2e %19.2e %8.1e %22.2e %8.1e   %s\n", t0_of[k], ulp,
		       vrel * ulp, reb[k].overlap, reb[k].energy, raw[k].overlap, raw[k].energy,
		       raw[k].audit_msg);
		same = same && memcmp(reb[k].state, reb[0].state, 6 * n * sizeof *states) == 0;
		clean = clean && reb[k].overlap < 1e-12;
	}
	free(states);

	static const char *names[] = {"T0", "ulp", "vrel_ulp", "overlap_rebased",
	                              "energy_rebased", "overlap_raw", "energy_raw", "audit_raw"};
	static const char *units[] = {"time", "time", "σ", "σ", "relative", "σ", "relative",
	                              "1 = invariants hold"};
	lz_data *d = lz_lesson_data(&L, "roundoff.dat", "the largest overlap against the "
	                            "absolute time at the start, with and without re-basing",
	                            8, names, units);
	if (!d)
		return lz_lesson_error(&L);
	for (int k = 0; k < NT0; k++) {
		double ulp = nextafter(t0_of[k], INFINITY) - t0_of[k];
		double row[8] = {t0_of[k], ulp, vrel * ulp, reb[k].overlap, reb[k].energy,
		                 raw[k].overlap, raw[k].energy, raw[k].audit == LZ_OK};
		lz_data_row(d, row);
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);

	int last = NT0 - 1, grows = 1;
	for (int k = 1; k < NT0; k++)
		grows = grows && raw[k].overlap >= raw[k - 1].overlap;
	double ulp_last = nextafter(t0_of[last], INFINITY) - t0_of[last];
	printf("  re-based: the final state is the same bit for bit at every T0, overlaps "
	       "below 1e-12 σ: %s\n", lz_lesson_check(&L, same && clean));
	double ratio = raw[last].overlap / (vrel * ulp_last);
	printf("  not re-based: the overlap never falls as T0 grows, and at T0 = %g it is "
	       "%.2g σ, %.2f times |v_rel|·ulp(T0) = %.2g (between 0.1 and 10): %s\n",
	       t0_of[last], raw[last].overlap, ratio, vrel * ulp_last,
	       lz_lesson_check(&L, grows && ratio > 0.1 && ratio < 10));

	lz_json *j = lz_lesson_json(&L, "roundoff.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_int(j, "N", (long long)n);
	for (int k = 0; k < NT0; k += 3) {
		char key[64];
		snprintf(key, sizeof key, "overlap_not_rebased_T0_%.0e", t0_of[k]);
		lz_json_num(j, key, raw[k].overlap);
	}
	lz_json_num(j, "overlap_not_rebased_T0_max", raw[last].overlap);
	lz_json_num(j, "overlap_rebased_max", reb[last].overlap);
	lz_json_bool(j, "rebased_bit_identical", same);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "re-basing keeps the overlaps at round-off at any T0");
}
