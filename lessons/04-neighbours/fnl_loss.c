/* fnl_loss — lesson 04, experiment: what the fast neighbour-list refresh can lose
 * (thesis 2.4.2, fig. 2.7).
 *
 * The fast refresh finds a newcomer to i's list only through a common neighbour: a
 * particle listed both on i's row and on the newcomer's. That is a bet on the lists
 * being long enough that every pair about to come within r_l shares somebody.
 *
 * (a) The bet against the skin, one copy against two. 4400 hard disks (R = 12,
 * packing 0.474, box 2048) walk with the FNL driver at skins Δr = 4 .. 48, refreshed
 * at the safe interval floor(Δr / 2), once with the one-copy refresh (rows rewritten in
 * place, lz_nlist_refresh_single) and once with the source and target copies
 * (lz_nlist_refresh), from the same start with the same random numbers. Before every
 * refresh the audit counts the pairs closer than r_c = σ + 1 that the lists do not
 * hold — pairs whose next step would be judged blind; at the end, the overlapping
 * pairs count the damage.
 *
 * (b) The bet against the density. Two copies at Δr = 32 (the skin that is safe in
 * (a)) at packings 0.01 .. 0.474 (box 2048, N from the packing); NL, which rebuilds
 * from all pairs with the same skin, is the control (always 0). The thinner the fluid,
 * the shorter the lists and the likelier two disks drift together with nobody in
 * between — but the rarer encounters are: the audit sees a miss only when the pair is
 * closer than r_c.
 *
 * Usage: fnl_loss OUTDIR [--quick]
 * Writes OUTDIR/fnl_skin.dat, fnl_density.dat and fnl_loss.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/nwalk.h"
#include "lz/output.h"

#define SEED 2205u
#define RADIUS 12.0
#define SIDE 2048
#define DENSE 0.474
#define SAFE_SKIN 32.0
#define NPACK 7
#define NSKIN 7

static const double packing_of[NPACK] = {0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.474};
static const double skin_of[NSKIN] = {4, 8, 12, 16, 24, 32, 48};

typedef struct {
	long sweeps;        /* sweeps per run */
} sizes;

static const sizes full = {960};
static const sizes quick = {192};

/* One audited run: pairs missed per refresh per 1000 particles, overlaps at the end,
 * list entries per particle. */
typedef struct {
	size_t n;
	int refresh;
	double missed, entries;
	uint64_t overlaps;
} loss;

static int run(lz_nwalk_driver d, double packing, double skin, int single, long sweeps,
               loss *out)
{
	lz_nwalk_params p = lz_nwalk_params_for(d, LZ_LATTICE_SQUARE, SIDE, RADIUS, packing);
	p.skin = skin;
	p.single = single;
	lz_nwalk *nw = lz_nwalk_alloc_seeded(&p, SEED);
	double ns;
	int status = nw ? lz_nwalk_time(nw, SEED + 1, (uint64_t)sweeps, 1, &ns) : LZ_EINVAL;
	if (status == LZ_OK) {
		out->n = p.n;
		out->refresh = nw->refresh;
		out->missed = nw->refreshes ? 1000.0 * (double)nw->missed /
		                              ((double)nw->refreshes * (double)p.n) : 0;
		out->entries = (double)lz_nlist_entries(nw->nl) / (double)p.n;
		out->overlaps = lz_nwalk_overlaps(nw);
	}
	lz_nwalk_free(nw);
	return status;
}

/* Part (a): FNL with one copy and with two, against the skin. */
static int skins(lz_lesson *L, const sizes *sz, loss a[NSKIN][2])
{
	static const char *names[] = {"skin", "refresh", "entries_two", "missed_one",
	                              "missed_two", "overlaps_one", "overlaps_two"};
	static const char *units[] = {"lattice", "sweeps", "per particle", "per refresh per 1000",
	                              "per refresh per 1000", "pairs", "pairs"};
	lz_data *d = lz_lesson_data(L, "fnl_skin.dat", "FNL driver, 4400 disks at packing "
	                            "0.474, safe refresh: pairs closer than r_c missing from the "
	                            "lists, one copy and two, against the skin", 7, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < NSKIN; k++) {
		for (int c = 0; c < 2; c++)
			if (run(LZ_NWALK_FNL, DENSE, skin_of[k], c == 0, sz->sweeps, &a[k][c]) != LZ_OK) {
				lz_data_close(d);
				return LZ_EINVAL;
			}
		printf("  (a) skin %4.0f refresh %2d entries %6.2f  missed per refresh per 1000: "
		       "one copy %9.4f, two %9.4f;  overlaps %llu, %llu\n", skin_of[k],
		       a[k][1].refresh, a[k][1].entries, a[k][0].missed, a[k][1].missed,
		       (unsigned long long)a[k][0].overlaps, (unsigned long long)a[k][1].overlaps);
		double row[7] = {skin_of[k], a[k][1].refresh, a[k][1].entries, a[k][0].missed,
		                 a[k][1].missed, (double)a[k][0].overlaps, (double)a[k][1].overlaps};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

/* Part (b): FNL (two copies) and NL at the safe skin, against the packing. */
static int densities(lz_lesson *L, const sizes *sz, loss b[NPACK][2])
{
	static const char *names[] = {"packing", "N", "fnl_missed", "nl_missed", "fnl_overlaps",
	                              "entries"};
	static const char *units[] = {"", "", "per refresh per 1000", "per refresh per 1000",
	                              "pairs", "per particle"};
	lz_data *d = lz_lesson_data(L, "fnl_density.dat", "two-copy FNL against NL at skin 32: "
	                            "pairs closer than r_c missing at a refresh, against the "
	                            "packing", 6, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < NPACK; k++) {
		for (int c = 0; c < 2; c++)
			if (run(c ? LZ_NWALK_NL : LZ_NWALK_FNL, packing_of[k], SAFE_SKIN, 0, sz->sweeps,
			        &b[k][c]) != LZ_OK) {
				lz_data_close(d);
				return LZ_EINVAL;
			}
		printf("  (b) packing %5.3f N %5zu entries %6.2f  missed per refresh per 1000: FNL "
		       "%9.4f, NL %g;  FNL overlaps %llu\n", packing_of[k], b[k][0].n, b[k][0].entries,
		       b[k][0].missed, b[k][1].missed, (unsigned long long)b[k][0].overlaps);
		double row[6] = {packing_of[k], (double)b[k][0].n, b[k][0].missed, b[k][1].missed,
		                 (double)b[k][0].overlaps, b[k][0].entries};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "04", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("fnl_loss: R = %g, box %d, %ld sweeps a run, safe refresh, seed %u\n", RADIUS,
	       SIDE, sz->sweeps, SEED);
	static loss a[NSKIN][2], b[NPACK][2];
	if (skins(&L, sz, a) != LZ_OK || densities(&L, sz, b) != LZ_OK)
		return lz_lesson_error(&L);

	int safe = NSKIN - 2;   /* skin_of[safe] == SAFE_SKIN */
	int nl_clean = 1, thin = 0;
	double worst = 0;
	for (int k = 0; k < NPACK; k++) {
		nl_clean = nl_clean && b[k][1].missed == 0 && b[k][1].overlaps == 0;
		if (k < NPACK - 1 && b[k][0].missed > worst) {
			worst = b[k][0].missed;
			thin = k;
		}
	}
	printf("  short lists lose pairs even with two copies (skin %g): %s\n", skin_of[0],
	       lz_lesson_check(&L, a[0][1].missed > 0));
	printf("  two copies at skin %g miss nothing at packing %g: %s\n", SAFE_SKIN, DENSE,
	       lz_lesson_check(&L, a[safe][1].missed == 0 && a[safe][1].overlaps == 0));
	printf("  NL misses nothing at any packing; FNL at skin %g misses below packing %g "
	       "(most, %.3g, at %g): %s\n", SAFE_SKIN, DENSE, worst, packing_of[thin],
	       lz_lesson_check(&L, nl_clean && worst > 0));

	lz_json *j = lz_lesson_json(&L, "fnl_loss.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_num(j, "missed_two_copies_skin4", a[0][1].missed);
	lz_json_num(j, "missed_one_copy_skin4", a[0][0].missed);
	lz_json_num(j, "missed_two_copies_skin32", a[safe][1].missed);
	lz_json_num(j, "missed_one_copy_skin32", a[safe][0].missed);
	lz_json_num(j, "fnl_most_missed_below_dense", worst);
	lz_json_num(j, "fnl_most_missed_at_packing", packing_of[thin]);
	lz_json_num(j, "fnl_missed_at_0.474", b[NPACK - 1][0].missed);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "long lists and two copies lose nothing in a dense fluid");
}
