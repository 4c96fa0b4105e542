/* method_nlist.c — the `nlist` engine: one hard-disk random walk on a lattice with the
 * four neighbour drivers of thesis table 2.2 (lz/nwalk.h): Verlet lists rebuilt from
 * all pairs (nl), the same lists refreshed from the neighbours of the neighbours (fnl),
 * cell lists (cl) and the field (fr).
 *
 * A run places the particles by random sequential adsorption, numbers them cell by cell
 * when asked, builds the driver's structure and runs `steps` sweeps, refreshing every
 * `refresh` sweeps (by default the longest safe interval) and, with audit = yes,
 * counting before each refresh the pairs within the interaction range that the driver
 * could not see. The speed (atom-steps per CPU second) counts the sweeps and the
 * refreshes, not the audit. An interval beyond the safe one is allowed — it is the
 * trade the lesson measures — so a run with overlaps still completes, reports them and
 * warns. Files: config.dat and config.png (the disks, or a slice through the spheres).
 */
#include <math.h>
#include <stdio.h>

#include "lz/error.h"
#include "lattice_scene.h"
#include "config.h"
#include "method.h"
#include "lz/nwalk.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/walk.h"

enum { ORDER_NONE, ORDER_ROW, ORDER_MORTON };
#define DEFAULT_SKIN 4.0  /* nl, cl: a safe interval of 2 sweeps (1 on cubic26) */
enum { STORE_LINKED, STORE_ARRAY };

static const lz_key keys[] = {
	{.name = "driver", .type = LZ_KEY_ENUM, .choices = "nl|fnl|cl|fr",
	 .help = "nl: Verlet lists rebuilt from all pairs (O(N²) per refresh); fnl: "
	         "refreshed from "
	         "the neighbours' lists (O(N)); cl: cell lists, a step tested against the "
	         "3^dim " "cells around; fr: the field, one look-up per step"},
	LZ_KEY_LATTICE,
	{.name = "size", .type = LZ_KEY_INT, .def = "1024", .min = 2, .max = 32768,
	 .unit = "sites",
	 .help = "box side L, a power of two, periodic (the placement paints an L^dim-byte "
	         "field: " "L <= 1024 in 3D)"},
	{.name = "radius", .type = LZ_KEY_REAL, .def = "12", .min = 0, .max = 8192,
	 .min_open = 1, .unit = "lattice units",
	 .help = "particle radius R; σ = 2R, and 4R <= L"},
	{.name = "n", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e9, .group = 1,
	 .help = "number of particles, placed by random sequential adsorption (give n or "
	         "packing)"},
	{.name = "packing", .type = LZ_KEY_REAL, .def = "", .min = 0, .max = LZ_WALK_CLOSE_2D,
	 .min_open = 1, .group = 1,
	 .help = "packing fraction η = N·πR²/(L²·cell) (4/3 πR³/L³ in 3D), n rounded from "
	         "it; " "adsorption jams near 0.547 (2D), 0.38 (3D)"},
	{.name = "skin", .type = LZ_KEY_REAL, .def = "", .max = 16384, .unit = "lattice units",
	 .help = "Δr > 0 (nl, fnl, cl; fr ignores it): lists hold pairs within r_l = σ + "
	         "lmax + Δr, cl cells are at least r_l wide. Default: 4 for nl and cl (exact "
	         "at any skin with the safe refresh); for fnl the skin at which its lists "
	         "hold about 24 particles, R·(24/η)^(1/dim) - σ - lmax rounded up, within "
	         "L/2 (61 at R = 12, η = 0.474): its refresh finds a newcomer only through a "
	         "common neighbour, and the thinnest lists that missed no pair held 3 to 19 "
	         "(datasets/scenes/README.md); a thinner skin is faster where it is safe"},
	{.name = "refresh", .type = LZ_KEY_INT, .def = "0", .max = 1e9, .unit = "sweeps",
	 .help = "sweeps between refreshes; 0: the safe interval floor(Δr/(2 lmax)) (a "
	         "skin of at " "least two steps); longer ones miss pairs (fr: no lists)"},
	{.name = "steps", .type = LZ_KEY_INT, .def = "1000", .min = 1, .max = 1e12,
	 .unit = "sweeps",
	 .help = "sweeps, each offering every particle, in index order, one random step"},
	{.name = "cell_order", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|row|morton",
	 .help = "none: cells row-major, particles as placed; row, morton: cells in that "
	         "order and "
	         "the particles renumbered cell by cell (near in space = near in memory)"},
	{.name = "cell_store", .type = LZ_KEY_ENUM, .def = "linked", .choices = "linked|array",
	 .help = "cl: linked lists (head/next) or fixed arrays per cell (contiguous, room "
	         "for twice " "the densest packing)"},
	{.name = "copies", .type = LZ_KEY_INT, .def = "2", .min = 1, .max = 2,
	 .help = "fnl: 2 = source and target lists; 1 = rows rewritten in place, which "
	         "loses " "particles (thesis fig. 2.7; for the demonstration)"},
	{.name = "audit", .type = LZ_KEY_BOOL, .def = "yes",
	 .help = "before every refresh, count the pairs closer than r_c = σ + lmax that "
	         "the driver " "cannot see (timed apart)"},
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto",
	 .help = "random seed of the placement and the steps"},
};

/* ---- the scene ---- */

/* The particles asked for: n, or rounded from the packing. */
static long long particles(const lz_scene *s)
{
	double one = lz_walk_packing(lz_scene_lattice(s), lz_scene_int(s, "size"),
	                             lz_scene_real(s, "radius"), 1);
	return lz_scene_count(s, "packing", one);
}

static const char *count_key(const lz_scene *s)
{
	return lz_scene_has(s, "n") ? "n" : "packing";
}

static lz_nwalk_params scene_params(const lz_scene *s)
{
	int order = lz_scene_enum(s, "cell_order");
	lz_nwalk_params p = {
		.driver = (lz_nwalk_driver)lz_scene_enum(s, "driver"),
		.kind = lz_scene_lattice(s),
		.side = lz_scene_int(s, "size"),
		.radius = lz_scene_real(s, "radius"),
		.n = (size_t)particles(s),
		.refresh = (int)lz_scene_int(s, "refresh"),
		.order = order == ORDER_MORTON ? LZ_CELLS_MORTON : LZ_CELLS_ROW,
		.renumber = order != ORDER_NONE,
		.linked = lz_scene_enum(s, "cell_store") == STORE_LINKED,
		.single = lz_scene_int(s, "copies") == 1,
		.audit = lz_scene_bool(s, "audit"),
	};
	p.skin = lz_scene_has(s, "skin") ? lz_scene_real(s, "skin")
	         : p.driver == LZ_NWALK_FNL ? lz_nwalk_fnl_skin(p.kind, p.side, p.radius, p.n)
	         : DEFAULT_SKIN;
	return p;
}

static int check_count(const lz_scene *s)
{
	int given = lz_scene_has(s, "n") + lz_scene_has(s, "packing");
	if (given != 1)
		return lz_scene_fail(s, given ? "packing" : "radius", "give exactly one of n and "
		                     "packing (%s)", given ? "both given" : "none given");
	if (particles(s) < 1)
		return lz_scene_fail(s, "packing", "packing = %g is less than one particle of "
		                     "radius %g in a box of side %lld", lz_scene_real(s, "packing"),
		                     lz_scene_real(s, "radius"), lz_scene_int(s, "size"));
	return LZ_OK;
}

/* The choices that only one driver can honour. */
static int check_driver_keys(const lz_scene *s, lz_nwalk_driver d)
{
	if (lz_scene_int(s, "copies") == 1 && d != LZ_NWALK_FNL)
		return lz_scene_fail(s, "copies", "copies = 1 (the one-copy refresh) needs driver "
		                     "= fnl, not %s; allowed copies = 2 with the other drivers",
		                     lz_nwalk_driver_name(d));
	if (lz_scene_enum(s, "cell_store") == STORE_ARRAY && d != LZ_NWALK_CL)
		return lz_scene_fail(s, "cell_store", "cell_store = array needs driver = cl, not "
		                     "%s; allowed cell_store = linked with the other drivers",
		                     lz_nwalk_driver_name(d));
	return LZ_OK;
}

/* The first of the keys that the scene gives, for the place of a message. */
static const char *given_key(const lz_scene *s, const char *const *names, int n)
{
	for (int k = 0; k < n; k++)
		if (lz_scene_given(s, names[k]))
			return names[k];
	return names[n - 1];
}

static int check(const lz_scene *s)
{
	static const char *const blame[] = {"skin", "refresh", "cell_order", "radius", "size"};
	int status = check_count(s);
	if (status != LZ_OK)
		return status;
	lz_nwalk_params p = scene_params(s);
	status = check_driver_keys(s, p.driver);
	if (status == LZ_OK && lz_nwalk_check(&p) != LZ_OK)
		status = lz_scene_fail(s, given_key(s, blame, 5), "%s", lz_error_message());
	return status;
}

/* ---- the run ---- */

/* `steps` sweeps, cut into pieces of about 2^16 moves for the progress line; the
 * refresh schedule does not depend on the cut (lz_nwalk_run). */
static int measure(const lz_scene *s, lz_nwalk *nw, lz_rng *rng, int quiet)
{
	uint64_t steps = (uint64_t)lz_scene_int(s, "steps"), done = 0;
	uint64_t piece = nw->p.n >= 65536 ? 1 : 65536 / nw->p.n;
	lz_progress bar;
	if (!quiet)
		lz_progress_begin(&bar, "nlist", (double)steps);
	int status = LZ_OK;
	while (status == LZ_OK && done < steps) {
		uint64_t k = steps - done < piece ? steps - done : piece;
		status = lz_nwalk_run(nw, rng->gsl, k);
		done += k;
		if (!quiet)
			lz_progress_update(&bar, (double)done);
	}
	if (!quiet)
		lz_progress_end(&bar);
	return status;
}

/* What a move costs in look-ups: the list entries per particle (nl, fnl), the distance
 * tests per move (cl), the points a step repaints (fr). */
static double neighbours_per_particle(const lz_nwalk *nw)
{
	switch (nw->p.driver) {
	case LZ_NWALK_NL:
	case LZ_NWALK_FNL:
		return (double)lz_nlist_entries(nw->nl) / (double)nw->p.n;
	case LZ_NWALK_CL:
		return nw->moves ? (double)nw->candidates / (double)nw->moves : NAN;
	case LZ_NWALK_FR:
		return lz_shape_mean_move(nw->field->excl);
	}
	return NAN;
}

static void summarise(const lz_nwalk *nw, size_t overlaps, lz_json *j)
{
	const lz_nwalk_params *p = &nw->p;
	int lists = p->driver != LZ_NWALK_FR;
	double n = (double)p->n, bytes = (double)lz_nwalk_list_bytes(nw);
	lz_json_int(j, "n_placed", (long long)p->n);
	lz_json_num(j, "packing_fraction", lz_walk_packing(p->kind, p->side, p->radius, p->n));
	lz_json_num(j, "interaction_range", nw->rc);
	lz_json_num(j, "skin_run", lists ? p->skin : NAN);
	lz_json_num(j, "list_radius", lists ? nw->rl : NAN);
	lz_json_int(j, "sweeps", (long long)nw->sweeps);
	lz_json_num(j, "acceptance", nw->moves ? (double)nw->accepted / (double)nw->moves : NAN);
	lz_json_num(j, "missed_pairs", p->audit || !lists ? (double)nw->missed : NAN);
	lz_json_num(j, "missed_pairs_per_refresh", (p->audit || !lists) && nw->refreshes
	            ? (double)nw->missed / (double)nw->refreshes : NAN);
	lz_json_int(j, "overlaps", (long long)overlaps);
	lz_json_int(j, "refreshes", (long long)nw->refreshes);
	lz_json_num(j, "refresh_interval", lists ? nw->refresh : NAN);
	lz_json_num(j, "refresh_safe", lists ? nw->refresh_safe : NAN);
	lz_json_int(j, "list_bytes", (long long)bytes);
	lz_json_num(j, "bytes_per_particle", bytes / n);
	lz_json_num(j, "state_bytes_per_particle", bytes / n + nw->dim * (double)sizeof(int32_t));
	lz_json_num(j, "neighbours_per_particle", neighbours_per_particle(nw));
	lz_json_num(j, "move_s", nw->move_s);
	lz_json_num(j, "audit_s", nw->audit_s);
	lz_json_num(j, "atomsteps_per_s", lz_nwalk_speed(nw));
}

/* The side of the square the picture shows: the whole box, or for many particles its
 * bottom-left corner of about 80 R (1024 at R = 12, thesis fig. 2.18) — gnuplot takes
 * seconds over 10^5 circles, and nobody can see them. */
static double plot_window(const lz_nwalk_params *p)
{
	double w = 1;
	while (w < 80 * p->radius)
		w *= 2;
	return w < (double)p->side ? w : (double)p->side;
}

/* config.gp: the final configuration, or a corner of it. */
static int write_plot(const lz_nwalk *nw, size_t overlaps, const lz_run *run)
{
	const lz_nwalk_params *p = &nw->p;
	double W = plot_window(p);
	char title[256];
	snprintf(title, sizeof title, "%zu %s, R = %g, %s lattice, η = %.3f, driver %s after "
	         "%llu sweeps: %zu overlapping pairs%s", p->n, nw->dim == 2 ? "disks" : "spheres",
	         p->radius, lz_lattice_name(p->kind),
	         lz_walk_packing(p->kind, p->side, p->radius, p->n),
	         lz_nwalk_driver_name(p->driver), (unsigned long long)nw->sweeps, overlaps,
	         W < (double)p->side ? " (a corner of the box)" : "");
	return lz_run_plot_config(run, "nlist", p->kind, (int32_t)p->side, W, title);
}

/* The run completes (the trade experiment needs its numbers), but says why it broke. */
static void warn_overlaps(const lz_nwalk *nw, size_t overlaps)
{
	char why[160];
	if (nw->refresh > nw->refresh_safe)
		snprintf(why, sizeof why, "refresh = %d sweeps exceeds the safe interval %d of "
		         "skin %g", nw->refresh, nw->refresh_safe, nw->p.skin);
	else
		snprintf(why, sizeof why, "the fnl refresh lost pairs with no common neighbour "
		         "(a bet on density): take a larger skin");
	fprintf(stderr, "lz: warning: %zu overlapping pairs after %llu sweeps: %s\n", overlaps,
	        (unsigned long long)nw->sweeps, why);
}

static int run(const lz_scene *s, lz_run *run)
{
	lz_nwalk_params p = scene_params(s);
	lz_rng *rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	if (!rng)
		return LZ_ENOMEM;
	lz_nwalk *nw = lz_nwalk_alloc(&p, rng->gsl);
	/* The checks ran at bind: what is left is jamming, or a system too big for memory. */
	int status = nw ? measure(s, nw, rng, run->quiet)
	                : lz_scene_fail(s, count_key(s), "%s", lz_error_message());
	if (status == LZ_OK) {
		size_t overlaps = lz_nwalk_overlaps(nw);
		if (overlaps > 0 && !run->quiet)
			warn_overlaps(nw, overlaps);
		summarise(nw, overlaps, run->summary);
		status = lz_config_write_lattice(run, p.kind, (int32_t)p.side, p.n,
		                             lz_nwalk_positions(nw), p.radius);
		if (status == LZ_OK)
			status = write_plot(nw, overlaps, run);
	}
	lz_nwalk_free(nw);
	lz_rng_free(rng);
	return status;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "n_placed"}, {.key = "packing_fraction"}, {.key = "skin_run"},
	{.key = "acceptance"}, {.key = "missed_pairs"}, {.key = "overlaps"}, {NULL},
};
static const lz_speed speed[] = {{"atomsteps_per_s", "atom-steps/s (CPU)"}, {NULL}};

const lz_method lz_method_nlist = {
	LZ_METHOD_KEYS("nlist", keys),
	.help = "one hard-disk random walk, four ways to find the neighbours (thesis table "
	        "2.2): Verlet lists (nl), the fast O(N) refresh (fnl), cell lists (cl), the "
	        "field (fr); skin, refresh interval and the pairs they miss",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
