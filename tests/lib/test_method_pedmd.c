/* test_method_pedmd.c — the `pedmd` method (lib/app/method_pedmd.c): a scene's parallel
 * run commits the serial run's events bit for bit and says so; its counts add up and
 * its files are there; the checks refuse what cannot run, naming the key and the
 * range; a pilot run's cuts share a sediment's load out. They need the graded code of
 * stages 05 and 06; each run is small. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "method.h"
#include "lztest.h"
#include "support.h"

static lzt_json *run_pedmd(const char *assignments, const char **dir)
{
	*dir = lzt_tmpdir();
	int status = lzt_run(&lz_method_pedmd, NULL, assignments, lzt_path(*dir, "run"));
	ck_assert_msg(status == LZ_OK, "method pedmd with %s failed: %s", assignments,
	              lz_error_message());
	return lzt_summary(lzt_path(*dir, "run"));
}

static int is_true(const lzt_json *j, const char *key)
{
	const lzt_member *m = lzt_json_get(j, key);
	return m && m->kind == LZT_TRUE;
}

LZ_TEST(pedmd_scene_equals_the_serial_run)
{
	const char *scenes[] = {
		"dim=2;n=900;packing=0.4;time=1;ranks=3;decomposition=rows;schedule=random;seed=3",
		"dim=3;n=1500;packing=0.3;time=0.3;ranks=5;schedule=virtual;seed=4",
		"dim=2;n=600;packing=0.25;walls=box;gravity=1;restitution=0.9;time=1;ranks=4;"
		"schedule=ahead;seed=5",
	};
	for (int k = 0; k < 3; k++) {
		const char *dir;
		lzt_json *j = run_pedmd(scenes[k], &dir);
		ck_assert_msg(is_true(j, "identical_to_serial"), "%s: not identical to the serial run",
		              scenes[k]);
		double committed = lzt_num(j, "committed_events"), processed = lzt_num(j, "processed_events");
		double kinds = lzt_num(j, "collisions") + lzt_num(j, "cell_crossings") +
		               lzt_num(j, "wall_bounces") + lzt_num(j, "stale_events");
		ck_assert_msg(committed > 0 && committed == kinds && processed >= committed &&
		              lzt_num(j, "efficiency") == committed / processed, "%s: %g committed "
		              "(%g by kind), %g processed, efficiency %g", scenes[k], committed, kinds,
		              processed, lzt_num(j, "efficiency"));
		char *text = lzt_slurp(lzt_path(lzt_path(dir, "run"), "domains.dat"), NULL);
		ck_assert_msg(text != NULL, "%s: no domains.dat", scenes[k]);
		int rows = 0, ranks = (int)lzt_num(j, "ranks_run"), bad = 0;
		for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
			double x, y, z, r;
			if (line[0] == '#')
				continue;
			bad += sscanf(line, "%lf %lf %lf %lf", &x, &y, &z, &r) != 4 || r < 0 || r >= ranks;
			rows++;
		}
		ck_assert_msg(rows == (int)lzt_num(j, "n_run") && bad == 0, "%s: domains.dat has %d rows "
		              "(%d bad) for %g particles", scenes[k], rows, bad, lzt_num(j, "n_run"));
		free(text);
		free(j);
	}
}
END_TEST

LZ_TEST(pedmd_scene_moves_its_cuts_and_stays_exact)
{
	/* a falling sediment with balance = dynamic: the cuts move, the run is the serial run */
	const char *dir;
	lzt_json *j = run_pedmd("dim=2;n=1200;packing=0.2;walls=box;gravity=1;equilibrate=50;"
	                        "time=1.5;ranks=4;balance=dynamic;balance_every=4;seed=3", &dir);
	ck_assert_msg(is_true(j, "identical_to_serial") && lzt_num(j, "cut_moves") > 0,
	              "balance = dynamic: %g moves of the cuts, identical to the serial run: %d",
	              lzt_num(j, "cut_moves"), is_true(j, "identical_to_serial"));
	free(j);
}
END_TEST

LZ_TEST(pedmd_scene_refuses_what_cannot_run)
{
	struct {
		const char *scene, *w1, *w2;
	} bad[] = {
		{"dim=2;n=20;packing=0.1;ranks=200", "ranks", "cells"},
		{"dim=2;n=400;schedule=virtual;delay=2", "delay", "latency"},
		{"dim=2;n=400;ranks=0", "ranks", "1"},
		{"dim=2;n=400;ranks=300", "ranks", "256"},
		{"dim=2;n=400;schedule=fast", "schedule", "virtual"},
		{"dim=2;n=400;decomposition=hilbert", "decomposition", "morton"},
		{"dim=2;n=400;time=0", "time", NULL},
	};
	for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
		ck_assert_msg(lzt_bind(&lz_method_pedmd, bad[k].scene) != LZ_OK, "%s was accepted",
		              bad[k].scene);
		const char *msg = lz_error_message();
		ck_assert_msg(strstr(msg, bad[k].w1) && (!bad[k].w2 || strstr(msg, bad[k].w2)), "%s: the "
		              "message should name '%s' and '%s': %s", bad[k].scene, bad[k].w1,
		              bad[k].w2 ? bad[k].w2 : "", msg);
	}
	/* only the required key: a correct run with the defaults */
	ck_assert_int_eq(lzt_bind(&lz_method_pedmd, "n=300"), LZ_OK);
}
END_TEST

LZ_TEST(pedmd_pilot_cuts_share_a_sediment)
{
	const char *dir;
	lzt_json *j = run_pedmd("dim=2;n=800;packing=0.2;walls=box;gravity=1;equilibrate=200;"
	                        "time=1;ranks=4;balance=pilot;seed=6", &dir);
	double ratio = lzt_num(j, "pilot_busiest_share_ratio");
	ck_assert_msg(ratio > 0 && ratio < 0.9, "disks settled at the bottom of a box: the pilot's "
	              "cuts should take at least a tenth off the busiest rank's share; ratio %g", ratio);
	ck_assert_msg(is_true(j, "identical_to_serial"), "balanced cuts must not change the run");
	free(j);
}
END_TEST
