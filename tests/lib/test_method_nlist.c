/* test_method_nlist.c — the four neighbour drivers of one hard-disk walk (lz/nwalk.h)
 * and the `nlist` method (lib/app/method_nlist.c): the scene checks; the drivers walk
 * the same path, bit for bit, while their structures are safe (the decisions depend
 * only on the pairs closer than r_c, which each of them then sees); the audit finds
 * what a stale list, a refresh beyond the safe interval or the one-copy refresh misses;
 * one and two particles; placement beyond jamming; the summary's determinism. They
 * need the graded code of stages 02-04 (lattice, field, cells, nlist). Each run is
 * small: the suite takes a few seconds with -O2. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "method.h"
#include "lz/nwalk.h"
#include "lz/rng.h"
#include "lz/walk.h"
#include "lztest.h"
#include "support.h"

static int bind_nlist(const char *assignments)
{
	return lzt_bind(&lz_method_nlist, assignments);
}

/* Bind must fail with a message that contains every one of the words. */
static void assert_refused(const char *scene, const char *w1, const char *w2)
{
	ck_assert_msg(bind_nlist(scene) == LZ_EINVAL, "%s was accepted", scene);
	const char *msg = lz_error_message();
	ck_assert_msg(strstr(msg, w1) && (!w2 || strstr(msg, w2)), "%s: the message should "
	              "name '%s'%s%s: %s", scene, w1, w2 ? " and " : "", w2 ? w2 : "", msg);
}

/* Run an nlist scene built from the assignments; the summary (fails if the run does).
 * *dir gets the directory that holds the run directory "run". */
static lzt_json *run_nlist(const char *assignments, const char **dir)
{
	*dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_nlist, NULL, assignments, lzt_path(*dir, "run"));
	ck_assert_msg(status == LZ_OK, "method nlist with %s failed: %s", assignments,
	              lz_error_message());
	return lzt_summary(lzt_path(*dir, "run"));
}

/* A walk of the given driver from seed `seed`, or NULL (the message says why). */
static lz_nwalk *walk(lz_nwalk_params p, lz_nwalk_driver d, unsigned long seed,
                      lz_rng **rng)
{
	p.driver = d;
	*rng = lz_rng_alloc(NULL, seed);
	ck_assert(*rng != NULL);
	return lz_nwalk_alloc(&p, (*rng)->gsl);
}

LZ_TEST(nlist_scene_checks)
{
	ck_assert_msg(lz_method_find("nlist") == &lz_method_nlist, "method nlist is not "
	              "registered");
	ck_assert_msg(bind_nlist("driver=fnl;packing=0.474") == LZ_OK, "%s", lz_error_message());
	assert_refused("packing=0.474", "driver", NULL);
	ck_assert_msg(bind_nlist("driver=fr;skin=0;n=10;size=64;radius=2") == LZ_OK,
	              "fr has no lists, a zero skin is fine: %s", lz_error_message());
	ck_assert_msg(bind_nlist("driver=cl;lattice=cubic;size=64;radius=2;packing=0.2;"
	                         "cell_order=morton;cell_store=array") == LZ_OK, "%s",
	              lz_error_message());
	assert_refused("driver=nl;skin=0;packing=0.3", "skin", "Δr > 0");
	assert_refused("driver=cl;skin=-1;packing=0.3", "skin", "range");
	assert_refused("driver=nl;refresh=-1;packing=0.3", "refresh", "[0,");
	assert_refused("driver=vl;packing=0.3", "nl|fnl|cl|fr", NULL);
	assert_refused("driver=cl;packing=0.95", "0.9069", NULL);
	assert_refused("driver=cl;lattice=cubic;size=64;radius=4;packing=0.8", "close packing", NULL);
	assert_refused("driver=cl;n=10;packing=0.3", "exactly one", NULL);
	assert_refused("driver=cl;radius=3", "exactly one", NULL);
	assert_refused("driver=cl;size=1000;n=10", "1000", NULL);
	assert_refused("driver=fr;size=64;radius=17;n=1", "R <= 16", NULL);
	/* r_l = σ + 1 + Δr against L/2 = 32 (lists) and 3 cells of side r_l (cells). */
	assert_refused("driver=nl;size=64;radius=4;skin=30;n=5", "L/2", "Δr <= 23");
	assert_refused("driver=cl;size=64;radius=4;skin=10;n=5", "3 cells", "L >= 128");
	assert_refused("driver=fnl;skin=1.5;packing=0.3", "refresh_safe = 0", NULL);
	ck_assert_msg(bind_nlist("driver=fnl;skin=1.5;refresh=1;packing=0.3") == LZ_OK,
	              "an explicit interval with a short skin is the trade, allowed: %s",
	              lz_error_message());
	assert_refused("driver=nl;copies=1;packing=0.3", "copies", "fnl");
	assert_refused("driver=fnl;cell_store=array;packing=0.3", "cell_store", "cl");
	assert_refused("size=32;radius=4;n=2;cell_order=morton;driver=fr", "cell_order = none",
	               NULL);
	ck_assert(bind_nlist("driver=cl;packing=0.3;audit=maybe") == LZ_EINVAL);
}
END_TEST

/* The four drivers, same seed, safe interval: the same final configuration, bit for
 * bit, no missed pair and no overlap — on the square, triangular and square8 lattices
 * and in 3D, with the particles as placed and renumbered in Morton order, cells as
 * linked lists and as arrays. The skin is large enough for the fnl bet to hold here. */
LZ_TEST(nlist_drivers_walk_the_same_path)
{
	static const struct {
		lz_lattice_kind kind;
		int64_t side;
		double radius, packing, skin;
		int renumber;
	} cases[] = {
		{LZ_LATTICE_SQUARE, 256, 4, 0.4, 12, 0},
		{LZ_LATTICE_SQUARE, 256, 4, 0.4, 12, 1},
		{LZ_LATTICE_TRIANGULAR, 256, 4, 0.4, 12, 0},
		{LZ_LATTICE_SQUARE8, 256, 4, 0.4, 12, 1},
		{LZ_LATTICE_CUBIC, 64, 3, 0.3, 8, 1},
	};
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
		lz_nwalk_params p = {
			.kind = cases[c].kind, .side = cases[c].side, .radius = cases[c].radius,
			.skin = cases[c].skin, .order = cases[c].renumber ? LZ_CELLS_MORTON : LZ_CELLS_ROW,
			.renumber = cases[c].renumber, .linked = 1, .audit = 1,
		};
		p.n = (size_t)llround(cases[c].packing / lz_walk_packing(p.kind, p.side, p.radius, 1));
		int32_t *first = NULL;
		size_t bytes = p.n * (size_t)lz_lattice_dim(p.kind) * sizeof *first;
		for (int d = 0; d <= 4; d++) {
			lz_rng *rng;
			p.linked = d != 4;
			lz_nwalk *nw = walk(p, d == 4 ? LZ_NWALK_CL : (lz_nwalk_driver)d, 11, &rng);
			ck_assert_msg(nw != NULL, "case %zu: %s", c, lz_error_message());
			ck_assert(lz_nwalk_run(nw, rng->gsl, 200) == LZ_OK);
			const char *name = d == 4 ? "cl (arrays)" : lz_nwalk_driver_name(nw->p.driver);
			ck_assert_msg(nw->missed == 0 && lz_nwalk_overlaps(nw) == 0, "case %zu, %s: "
			              "%llu missed pairs, %zu overlaps at the safe interval %d", c, name,
			              (unsigned long long)nw->missed, lz_nwalk_overlaps(nw), nw->refresh);
			ck_assert_msg(nw->accepted > 0 && nw->accepted < nw->moves, "case %zu: a dense "
			              "walk accepts some steps and refuses others", c);
			if (d == 0) {
				ck_assert(nw->refreshes == 200 / (uint64_t)nw->refresh);
				first = malloc(bytes);
				memcpy(first, lz_nwalk_positions(nw), bytes);
			} else {
				ck_assert_msg(memcmp(first, lz_nwalk_positions(nw), bytes) == 0, "case %zu: "
				              "%s ended in another configuration than nl: the same random "
				              "numbers and a safe structure must give the same decisions",
				              c, name);
			}
			lz_nwalk_free(nw);
			lz_rng_free(rng);
		}
		free(first);
	}
}
END_TEST

/* Through the method: the four table-2.2 drivers write the same config.dat and the
 * same acceptance, the lists are refreshed at the safe interval floor(Δr / 2), and
 * fr has no interval (null). */
LZ_TEST(nlist_method_drivers_agree)
{
	static const char *const drivers[] = {"nl", "fnl", "cl", "fr"};
	char *first = NULL;
	double acceptance = 0;
	for (int d = 0; d < 4; d++) {
		char scene[200];
		snprintf(scene, sizeof scene, "driver=%s;size=256;radius=4;packing=0.4;skin=12;"
		         "steps=100;seed=5", drivers[d]);
		const char *dir;
		lzt_json *j = run_nlist(scene, &dir);
		ck_assert_msg(lzt_num(j, "overlaps") == 0 && lzt_num(j, "missed_pairs") == 0,
		              "%s: %g overlaps, %g missed pairs", drivers[d], lzt_num(j, "overlaps"),
		              lzt_num(j, "missed_pairs"));
		const lzt_member *safe = lzt_json_get(j, "refresh_safe");
		ck_assert(safe != NULL);
		if (d < 3)
			ck_assert_msg(safe->num == 6 && lzt_num(j, "refresh_interval") == 6 &&
			              lzt_num(j, "refreshes") == 16, "%s: skin 12 on the square lattice "
			              "is safe for floor(12/2) = 6 sweeps, 16 refreshes in 100 sweeps; got "
			              "%g, %g", drivers[d], safe->num, lzt_num(j, "refreshes"));
		else
			ck_assert_msg(safe->kind == LZT_NULL, "fr has no lists, refresh_safe is null");
		ck_assert(lzt_num(j, "atomsteps_per_s") > 0 && lzt_num(j, "list_bytes") > 0);
		ck_assert(lzt_num(j, "neighbours_per_particle") > 0);
		char *config = lzt_slurp(lzt_path(lzt_path(dir, "run"), "config.dat"), NULL);
		ck_assert_msg(config != NULL, "%s wrote no config.dat", drivers[d]);
		if (d == 0) {
			first = config;
			acceptance = lzt_num(j, "acceptance");
		} else {
			ck_assert_msg(strcmp(first, config) == 0, "%s: config.dat differs from nl's",
			              drivers[d]);
			ck_assert(lzt_num(j, "acceptance") == acceptance);
			free(config);
		}
		free(j);
	}
	free(first);
}
END_TEST

/* An interval far beyond the safe one in a dense fluid: the audit counts pairs within
 * r_c that the lists (or the cells as last binned) cannot see, disks end up
 * overlapping, and the run still completes and reports it. */
LZ_TEST(nlist_unsafe_refresh_misses_pairs)
{
	static const char *const drivers[] = {"nl", "cl"};
	for (int d = 0; d < 2; d++) {
		char scene[200];
		snprintf(scene, sizeof scene, "driver=%s;size=256;radius=4;packing=0.45;skin=2;"
		         "refresh=40;steps=200;seed=3", drivers[d]);
		const char *dir;
		lzt_json *j = run_nlist(scene, &dir);
		ck_assert_msg(lzt_num(j, "refresh_safe") == 1 && lzt_num(j, "refresh_interval") == 40,
		              "%s: skin 2 is safe for 1 sweep, the scene asks 40", drivers[d]);
		ck_assert_msg(lzt_num(j, "missed_pairs") > 0, "%s: 40 sweeps on a skin of 2 must "
		              "let pairs into r_c unseen; the audit found none", drivers[d]);
		ck_assert_msg(lzt_num(j, "overlaps") > 0, "%s: missed pairs at packing 0.45 should "
		              "leave overlapping disks", drivers[d]);
		free(j);
	}
}
END_TEST

/* Thesis fig. 2.7 in a fluid: datasets/scenes/04-fnl-single.scene (seed 9, verified)
 * loses pairs with the one-copy refresh — a row rewritten in place drops a particle
 * before the row that should gain it is scanned — while the two-copy refresh of the
 * same walk misses none. */
LZ_TEST(nlist_one_copy_refresh_loses_pairs)
{
	static const char *const scene = "datasets/scenes/04-fnl-single.scene";
	double missed[2];
	for (int copies = 1; copies <= 2; copies++) {
		char over[32];
		snprintf(over, sizeof over, "copies=%d", copies);
		const char *dir = lzt_tmpdir();
		int status = lzt_run(&lz_method_nlist, scene, over, lzt_path(dir, "run"));
		ck_assert_msg(status == LZ_OK, "%s with %s: %s", scene, over, lz_error_message());
		lzt_json *j = lzt_summary(lzt_path(dir, "run"));
		missed[copies - 1] = lzt_num(j, "missed_pairs");
		free(j);
	}
	ck_assert_msg(missed[1] == 0, "the two-copy refresh of %s must miss no pair (it reads "
	              "only the source lists); missed_pairs = %g", scene, missed[1]);
	ck_assert_msg(missed[0] > 0, "the one-copy refresh of %s must lose pairs on this run "
	              "(missed_pairs = %g): the rows are rewritten in place", scene, missed[0]);
}
END_TEST

/* One particle accepts every step. Two collide sometimes and never overlap — but for
 * fnl, whose refresh only finds new partners among the neighbours' neighbours: two
 * lone disks that drift apart empty their rows and never find each other again (the
 * header's example of the bet on density failing), and the audit counts the pair
 * every time they meet unseen. */
LZ_TEST(nlist_one_and_two_particles)
{
	static const char *const drivers[] = {"nl", "fnl", "cl", "fr"};
	for (int d = 0; d < 4; d++) {
		char scene[200];
		const char *dir;
		snprintf(scene, sizeof scene, "driver=%s;n=1;size=32;radius=1;steps=300;seed=2",
		         drivers[d]);
		lzt_json *j = run_nlist(scene, &dir);
		ck_assert_msg(lzt_num(j, "acceptance") == 1, "%s: a lone particle accepts every "
		              "step, acceptance = %g", drivers[d], lzt_num(j, "acceptance"));
		ck_assert(lzt_num(j, "n_placed") == 1 && lzt_num(j, "sweeps") == 300);
		free(j);
		snprintf(scene, sizeof scene, "driver=%s;n=2;size=32;radius=2;skin=2;steps=3000;"
		         "seed=4;audit=%s", drivers[d], d == 1 ? "yes" : "no");
		j = run_nlist(scene, &dir);
		double acc = lzt_num(j, "acceptance");
		const lzt_member *missed = lzt_json_get(j, "missed_pairs");
		ck_assert(missed != NULL);
		if (d == 1) {
			ck_assert_msg(missed->kind == LZT_NUM && missed->num > 0, "fnl: two lone disks "
			              "lose each other's rows for good, so the audit must find them "
			              "meeting unseen; missed_pairs = %s", missed->text);
			free(j);
			continue;
		}
		ck_assert_msg(acc > 0 && acc < 1, "%s: two disks of σ = 4 in a 32² box must collide "
		              "sometimes: acceptance = %g", drivers[d], acc);
		ck_assert(lzt_num(j, "overlaps") == 0);
		ck_assert_msg(missed->kind == LZT_NULL || d == 3, "%s: audit = no, so missed_pairs "
		              "is not measured and must be null", drivers[d]);
		free(j);
	}
}
END_TEST

/* Beyond jamming: random sequential adsorption stops near 0.547 (a little lower on a
 * coarse lattice), so 0.6 is refused with the coverage reached, and nothing is left. */
LZ_TEST(nlist_packing_beyond_jamming_is_an_error)
{
	const char *dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_nlist, NULL, "driver=fr;packing=0.6;size=64;radius=2;seed=1",
	                     lzt_path(dir, "run"));
	ck_assert_msg(status == LZ_EINVAL, "packing 0.6 cannot be reached by adsorption; the run "
	              "returned %d", status);
	const char *msg = lz_error_message();
	ck_assert_msg(strstr(msg, "jammed") && strstr(msg, "0.547"), "the message should say "
	              "that adsorption jammed and where it jams: %s", msg);
	ck_assert_msg(!lzt_exists(lzt_path(dir, "run")), "a failed run left a directory");
}
END_TEST

/* Same scene, same seed: the same summary.json but for the timings (*_s, *_per_s). */
LZ_TEST(nlist_summary_is_deterministic)
{
	static const char *const scenes[] = {
		"driver=fnl;size=256;radius=4;packing=0.4;skin=12;steps=60;seed=9;cell_order=morton",
		"driver=cl;size=256;radius=4;packing=0.4;steps=60;seed=9;cell_store=array",
	};
	for (int k = 0; k < 2; k++) {
		const char *d1, *d2;
		lzt_json *a = run_nlist(scenes[k], &d1), *b = run_nlist(scenes[k], &d2);
		ck_assert(a->n == b->n);
		for (int i = 0; i < a->n; i++) {
			const char *key = a->m[i].key;
			size_t len = strlen(key);
			if (len > 2 && strcmp(key + len - 2, "_s") == 0)
				continue;
			const lzt_member *m = lzt_json_get(b, key);
			ck_assert_msg(m && m->kind == a->m[i].kind && strcmp(m->text, a->m[i].text) == 0,
			              "%s: '%s' differs between two runs with the same seed (%s vs %s)",
			              scenes[k], key, a->m[i].text, m ? m->text : "missing");
		}
		free(a);
		free(b);
	}
}
END_TEST

/* A scene with only the required keys (a driver, and n or packing) loses no pair: nl
 * and cl at the default skin 4 (exact at the safe interval), fnl at the skin at which
 * its lists hold about 24 particles (lz_nwalk_fnl_skin), dense or dilute. */
LZ_TEST(nlist_default_skin_misses_nothing)
{
	static const struct {
		const char *scene;
		double skin;  /* 0: lz_nwalk_fnl_skin of the placed disks */
	} cases[] = {
		{"driver=fnl;packing=0.474;seed=1", 0}, {"driver=fnl;packing=0.2;seed=2", 0},
		{"driver=fnl;n=60;seed=3", 0},          {"driver=nl;packing=0.474;seed=4", 4},
		{"driver=cl;packing=0.474;seed=5", 4},
	};
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		const char *dir;
		lzt_json *j = run_nlist(cases[k].scene, &dir);
		double skin = cases[k].skin ? cases[k].skin
		              : lz_nwalk_fnl_skin(LZ_LATTICE_SQUARE, 1024, 12,
		                                  (size_t)lzt_num(j, "n_placed"));
		ck_assert_msg(lzt_num(j, "skin_run") == skin, "%s: skin_run = %g, the default is %g",
		              cases[k].scene, lzt_num(j, "skin_run"), skin);
		ck_assert_msg(lzt_num(j, "missed_pairs") == 0 && lzt_num(j, "overlaps") == 0,
		              "%s: the default skin %g missed %g pairs and left %g overlaps in 1000 "
		              "sweeps (%.3g list entries per disk)", cases[k].scene, skin,
		              lzt_num(j, "missed_pairs"), lzt_num(j, "overlaps"),
		              lzt_num(j, "neighbours_per_particle"));
		free(j);
		lz_rmtree(dir);
	}
}
END_TEST
