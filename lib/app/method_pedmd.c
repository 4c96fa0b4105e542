/* method_pedmd.c — the `pedmd` engine: event-driven hard spheres and disks run by P
 * optimistic ranks (lz/pedmd.h), here all in one process over the stub back-end of
 * lz/msg.h; lz-mpi runs the same scenes with one process per rank (pedmd_scene.h).
 *
 * A run builds the system of the edmd keys, starts and equilibrates it serially (so
 * that every rank, and the serial reference, starts from the same bits), then runs the
 * ranks for `time`: the committed events, and with check = yes the serial run of the
 * same time, which they must equal bit for bit (the run fails otherwise). The schedule
 * decides how the stub interleaves the ranks; `virtual` models a machine (a cost per
 * event and per message and a latency) and gives the run's time on it, from which the
 * speed-up over one rank follows. balance = pilot runs the same time once first and
 * cuts the curve so that every rank gets the same share of the pilot's committed
 * events. Summary: the counts by kind, the efficiency (committed / processed events),
 * windows, rollbacks, conservative steps, the most bytes a window saved, the pressure
 * from the committed virial, virtual time and speed-up, and the identity with the serial
 * run. Files: domains.dat (x y [z] rank of every particle at the end) and domains.png.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/pedmd.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "edmd_scene.h"
#include "method.h"
#include "pedmd_scene.h"

#define PLOT_DISKS 20000.0  /* about this many points at most in domains.png */

static const lz_key keys[] = {
	LZ_EDMD_SYSTEM_KEYS,
	{.name = "time", .type = LZ_KEY_REAL, .def = "1", .min = 0, .max = 1e6, .min_open = 1,
	 .unit = "τ", .help = "simulated time the ranks run, after the equilibration"},
	{.name = "ranks", .type = LZ_KEY_INT, .def = "4", .min = 1, .max = LZ_PEDMD_RANKS_MAX,
	 .help = "ranks P, at most the cells (under lz-mpi: the processes, which decide)"},
	{.name = "decomposition", .type = LZ_KEY_ENUM, .def = "morton", .choices = "rows|morton",
	 .help = "the curve through the cells that the ranks cut: row by row (slabs) or "
	         "the Morton curve (compact domains)"},
	{.name = "schedule", .type = LZ_KEY_ENUM, .def = "virtual",
	 .choices = "round-robin|random|ahead|virtual",
	 .help = "how the stub interleaves the ranks: in turn, at random, rank 0 running "
	         "ahead, or in the virtual time of a modelled machine"},
	{.name = "delay", .type = LZ_KEY_INT, .def = "3", .min = 0, .max = 1000,
	 .help = "round-robin, random, ahead: a message waits 0 .. delay turns"},
	{.name = "cost_event", .type = LZ_KEY_REAL, .def = "1e-6", .min = 0, .max = 1, .unit = "s",
	 .help = "virtual: the time of one event on one rank"},
	{.name = "cost_message", .type = LZ_KEY_REAL, .def = "2e-6", .min = 0, .max = 1, .unit = "s",
	 .help = "virtual: the time to send or receive one message"},
	{.name = "latency", .type = LZ_KEY_REAL, .def = "5e-6", .min = 0, .max = 1, .unit = "s",
	 .help = "virtual: the time a message is on its way, at least"},
	{.name = "window", .type = LZ_KEY_REAL, .def = "0.05", .min = 0, .max = 1e6,
	 .min_open = 1, .unit = "τ",
	 .help = "the first optimistic window; it grows by `grow` after a commit and halves "
	         "after a rollback, within 1/64 .. 64 times this"},
	{.name = "grow", .type = LZ_KEY_REAL, .def = "1.125", .min = 1, .max = 2, .min_open = 1,
	 .help = "the window's growth after a commit: about ln grow / (ln grow + ln 2) of the "
	         "windows are rolled back (1.125: one in seven; 1.02, for windows of 10^4 "
	         "events and more: one in 36)"},
	{.name = "rebase", .type = LZ_KEY_REAL, .def = "0.5", .min = 0, .max = 1e6,
	 .min_open = 1, .unit = "τ",
	 .help = "the clocks are re-based at the multiples of this absolute time (the serial "
	         "reference re-bases there too)"},
	{.name = "work", .type = LZ_KEY_INT, .def = "16", .min = 1, .max = 1e6,
	 .help = "events a rank runs in one turn before it looks at its messages"},
	{.name = "balance", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|pilot|dynamic",
	 .help = "pilot: run once first and cut the curve so that every rank gets the same "
	         "share of the pilot's committed events; dynamic: move the cuts during the run, "
	         "at a cut every balance_every windows, to even out the events since the last "
	         "move, when the busiest rank gains 10 %"},
	{.name = "balance_every", .type = LZ_KEY_INT, .def = "16", .min = 1, .max = 1e6,
	 .help = "balance = dynamic: windows between two looks at the load"},
	{.name = "recheck", .type = LZ_KEY_BOOL, .def = "no",
	 .help = "the rollback check: every window is rolled back and run again, and must "
	         "end as the first time (twice the work)"},
	{.name = "check", .type = LZ_KEY_BOOL, .def = "yes",
	 .help = "run the serial reference too; the committed events and the final state "
	         "must equal it bit for bit"},
	{.name = "write_config", .type = LZ_KEY_BOOL, .def = "yes",
	 .help = "write domains.dat (every particle's position and rank) and domains.png"},
};

/* ---- the run a scene describes (pedmd_scene.h) ---- */

static lz_stub_params stub_of(const lz_scene *s)
{
	lz_stub_params p = {
		.ranks = (int)lz_scene_int(s, "ranks"),
		.policy = (lz_stub_policy)lz_scene_enum(s, "schedule"),
		.seed = lz_scene_seed(s, "seed"),
		.delay = (int)lz_scene_int(s, "delay"),
		.ahead = 0,
		.ahead_turns = 8,
		.cost_event = lz_scene_real(s, "cost_event"),
		.cost_message = lz_scene_real(s, "cost_message"),
		.latency = lz_scene_real(s, "latency"),
	};
	return p;
}

/* The system of the scene, started and equilibrated (the same bits every time). */
static lz_edmd *scene_system(const lz_scene *s, int quiet, int *status)
{
	lz_config c = {0};
	size_t n = 0;
	*status = LZ_OK;
	if (lz_scene_has(s, "config"))
		*status = lz_config_read(lz_scene_text(s, "config"), (int)lz_scene_int(s, "dim"), &c);
	if (*status == LZ_OK)
		*status = lz_edmd_scene_particles(s, &c, &n);
	lz_config_free(&c);
	lz_edmd *e = *status == LZ_OK ? lz_edmd_scene_system(s, n, NULL) : NULL;
	if (!e) {
		*status = *status ? *status : LZ_EINVAL;
		return NULL;
	}
	lz_rng *rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	*status = rng ? lz_edmd_scene_start(s, e, rng) : LZ_ENOMEM;
	if (*status == LZ_OK)
		*status = lz_edmd_scene_equilibrate(s, e, quiet);
	lz_rng_free(rng);
	if (*status != LZ_OK) {
		lz_edmd_free(e);
		return NULL;
	}
	e->rebase_auto = 0;
	lz_edmd_reset_counts(e);
	return e;
}

int lz_pedmd_scene_make(const lz_scene *s, int quiet, int build, lz_pedmd_scene *out)
{
	int status = LZ_OK;
	memset(out, 0, sizeof *out);
	if (build)
		out->system = scene_system(s, quiet, &status);
	if (out->system && lz_scene_bool(s, "check"))
		out->reference = scene_system(s, 1, &status);
	if (status != LZ_OK) {
		lz_pedmd_scene_free(out);
		return status;
	}
	out->kind = lz_scene_enum(s, "decomposition") == 0 ? LZ_PEDMD_ROWS : LZ_PEDMD_MORTON;
	out->stub = stub_of(s);
	int every = lz_scene_enum(s, "balance") == 2 ? (int)lz_scene_int(s, "balance_every") : 0;
	out->params = (lz_pedmd_params){lz_scene_real(s, "window"), lz_scene_real(s, "rebase"),
	                                every, 0.1, 0, (int)lz_scene_int(s, "work"),
	                                lz_scene_bool(s, "recheck"), lz_scene_real(s, "grow"),
	                                1 /* local numbering: each rank holds its share */};
	out->t_stop = lz_scene_real(s, "time");
	out->check = out->reference != NULL;
	return LZ_OK;
}

void lz_pedmd_scene_free(lz_pedmd_scene *p)
{
	lz_edmd_free(p->system);
	lz_edmd_free(p->reference);
	p->system = p->reference = NULL;
}

int lz_pedmd_scene_serial(lz_pedmd_scene *p)
{
	return lz_pedmd_serial(p->reference, p->t_stop, p->params.rebase);
}

size_t lz_pedmd_scene_differ(const lz_edmd *a, const lz_edmd *b)
{
	size_t k = 0;
	for (size_t i = 0; i < a->n; i++)
		k += memcmp(a->p[i].r, b->p[i].r, sizeof a->p[i].r) != 0 ||
		     memcmp(a->p[i].v, b->p[i].v, sizeof a->p[i].v) != 0 || a->p[i].t0 != b->p[i].t0;
	return k;
}

/* ---- the stub run ---- */

static int check(const lz_scene *s)
{
	int dim = (int)lz_scene_int(s, "dim"), P = (int)lz_scene_int(s, "ranks");
	if (lz_scene_given(s, "delay") && lz_scene_enum(s, "schedule") == LZ_STUB_VIRTUAL)
		return lz_scene_fail(s, "delay", "delay is for the round-robin, random and ahead "
		                     "schedules; under virtual time the latency decides");
	if (lz_scene_has(s, "config") || lz_scene_real(s, "packing") <= 0)
		return LZ_OK;
	lz_edmd_params p = {dim, (size_t)lz_scene_int(s, "n"), lz_scene_real(s, "packing"), 1, 0,
	                    LZ_EDMD_WALLS_NONE, (int)lz_scene_int(s, "cells"), LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	if (!e)
		return LZ_OK;  /* the run names the key to blame */
	size_t cells = e->ncells;
	lz_edmd_free(e);
	if ((size_t)P > cells)
		return lz_scene_fail(s, "ranks", "ranks = %d, but the box has %zu cells: every rank "
		                     "needs one, so 1 <= ranks <= %zu", P, cells, cells);
	return LZ_OK;
}

int lz_pedmd_scene_pilot(const lz_pedmd_scene *p, uint32_t *cut, int *moved, double *ratio)
{
	lz_pedmd_sim *x = lz_pedmd_sim_alloc(p->system, p->kind, &p->stub, &p->params);
	if (!x)
		return LZ_EINVAL;
	int st = lz_pedmd_sim_run(x, p->t_stop);
	double *load = malloc(x->d->ncells * sizeof *load);
	if (st == LZ_OK && !load)
		st = lz_error(LZ_ENOMEM, "no memory for the load of %zu cells", x->d->ncells);
	if (st == LZ_OK) {
		lz_pedmd_sim_load(x, load);
		*moved = lz_pedmd_rebalance(x->d, load, p->params.threshold, cut);
		double before = lz_pedmd_busiest(x->d, load, x->d->cut);
		*ratio = before > 0 ? lz_pedmd_busiest(x->d, load, cut) / before : 1;
	}
	free(load);
	lz_pedmd_sim_free(x);
	return st;
}

/* domains.dat and domains.png: where every particle is, coloured by its rank. */
static int write_domains(const lz_pedmd_sim *x, const lz_edmd *e, const lz_run *run)
{
	static const char *const names[] = {"x", "y", "z", "rank"}, *const units[] = {"σ", "σ", "σ", ""};
	char path[4200];
	int st = lz_rundir_file(run->dir, "domains.dat", path, sizeof path);
	lz_data *d = st == LZ_OK ? lz_data_open(path, "the particles at the end and their ranks", 4,
	                                        names, units) : NULL;
	if (!d)
		return st ? st : LZ_EIO;
	for (uint32_t i = 0; i < e->n; i++)
		for (int k = 0; k < x->P; k++)
			if (lz_pedmd_role(x->rank[k], i) == LZ_PEDMD_OWNED) {
				double r[3], v[3];
				lz_edmd_state(e, &e->p[i], e->now, r, v);
				lz_data_row(d, (double[]){r[0], r[1], r[2], k});
			}
	if ((st = lz_data_close(d)) != LZ_OK)
		return st;
	FILE *f = lz_run_script(run, "domains", "pedmd", "the particles coloured by their rank",
	                        760, 700);
	if (!f)
		return LZ_EIO;
	unsigned every = (unsigned)ceil((double)e->n / PLOT_DISKS);
	fprintf(f, "set size ratio -1\nset xrange [0:%.6g]\nset yrange [0:%.6g]\n", e->L, e->L);
	fprintf(f, "set title '%zu %s, %d ranks along the %s curve%s'\n", e->n,
	        e->dim == 3 ? "spheres (x, y)" : "disks", x->P,
	        x->d->kind == LZ_PEDMD_ROWS ? "row" : "Morton", every > 1 ? " (a sample)" : "");
	fprintf(f, "set xlabel 'x / σ'\nset ylabel 'y / σ'\nset cblabel 'rank'\n");
	fprintf(f, "set palette maxcolors %d\nset cbrange [-0.5:%.1f]\n", x->P, x->P - 0.5);
	fprintf(f, "plot 'domains.dat' every %u u 1:2:4 w p pt 7 ps 0.7 lc palette notitle\n", every);
	return lz_run_plot(run, f, "domains");
}

static void summarise(const lz_pedmd_scene *p, const lz_pedmd_sim *x, double wall_s,
                      double pilot_gain, lz_json *j)
{
	const lz_edmd *e = p->system;
	lz_pedmd_counts c = lz_pedmd_sim_counts(x);
	double t = p->t_stop, kT = lz_edmd_temperature(e);
	lz_json_int(j, "n_run", (long long)e->n);
	lz_json_int(j, "ranks_run", x->P);
	lz_json_int(j, "cells_run", (long long)e->ncells);
	lz_json_int(j, "committed_events", (long long)c.committed);
	lz_json_int(j, "processed_events", (long long)c.processed);
	lz_json_num(j, "efficiency", c.processed ? (double)c.committed / (double)c.processed : NAN);
	lz_json_int(j, "collisions", (long long)c.collisions);
	lz_json_int(j, "cell_crossings", (long long)c.crossings);
	lz_json_int(j, "wall_bounces", (long long)c.bounces);
	lz_json_int(j, "stale_events", (long long)c.stale);
	lz_json_int(j, "windows", (long long)c.windows);
	lz_json_int(j, "rollbacks", (long long)c.rollbacks);
	lz_json_int(j, "conservative_steps", (long long)c.conservative);
	lz_json_int(j, "cut_moves", (long long)c.balances);
	lz_json_int(j, "late_harmless", (long long)c.late_harmless);
	lz_json_num(j, "saved_bytes_max", (double)c.saved_bytes);
	lz_json_int(j, "rechecked_windows", (long long)c.rechecks);
	if (e->restitution == 1 && e->g == 0 && !e->wall[0]) {
		const char *source = "";
		double eta = (double)e->n * (e->dim == 3 ? M_PI / 6 : M_PI / 4) / pow(e->L, e->dim);
		lz_json_num(j, "Z", 1 + c.virial / (e->dim * (double)e->n * kT * t));
		lz_json_num(j, "Z_ref", lz_edmd_z_reference(e->dim, eta, &source));
		lz_json_str(j, "Z_ref_source", source);
	}
	if (p->stub.policy == LZ_STUB_VIRTUAL) {
		double T = lz_stub_time(x->stub), serial = (double)c.committed * p->stub.cost_event;
		lz_json_num(j, "virtual_s", T);
		lz_json_num(j, "speedup_virtual", T > 0 ? serial / T : NAN);
	}
	if (!isnan(pilot_gain))
		lz_json_num(j, "pilot_busiest_share_ratio", pilot_gain);
	lz_json_num(j, "parallel_wall_s", wall_s);
	lz_json_num(j, "events_per_s", wall_s > 0 ? (double)c.committed / wall_s : NAN);
}

static int run(const lz_scene *s, lz_run *run)
{
	lz_pedmd_scene p;
	int st = lz_pedmd_scene_make(s, run->quiet, 1, &p);
	if (st != LZ_OK)
		return st;
	lz_edmd_scene_warn_phase(p.system, lz_scene_real(s, "packing"), run->quiet);
	uint32_t cut[LZ_PEDMD_RANKS_MAX + 1];
	int moved = 0;
	double ratio = NAN;
	if (lz_scene_enum(s, "balance") == 1)
		st = lz_pedmd_scene_pilot(&p, cut, &moved, &ratio);
	lz_pedmd_sim *x = NULL;
	double t0 = lz_wall_now();
	if (st == LZ_OK) {
		x = lz_pedmd_sim_alloc_cut(p.system, p.kind, moved ? cut : NULL, &p.stub, &p.params);
		st = x ? lz_pedmd_sim_run(x, p.t_stop) : LZ_EINVAL;
	}
	double wall_s = lz_wall_now() - t0;
	if (st == LZ_OK) {
		lz_pedmd_sim_gather(x, p.system);
		p.system->t_base = x->rank[0]->e->t_base;  /* the records' times are the ranks' */
		p.system->now = p.t_stop - p.system->t_base;
		summarise(&p, x, wall_s, ratio, run->summary);
	}
	if (st == LZ_OK && p.check && (st = lz_pedmd_scene_serial(&p)) == LZ_OK) {
		size_t k = lz_pedmd_scene_differ(p.system, p.reference);
		lz_json_bool(run->summary, "identical_to_serial", k == 0);
		if (k)
			st = lz_error(LZ_EPHYS, "%zu of the %zu particles end elsewhere than in the serial "
			              "run: the parallel engine is wrong", k, p.system->n);
	}
	if (st == LZ_OK && lz_scene_bool(s, "write_config"))
		st = write_domains(x, p.system, run);
	lz_pedmd_sim_free(x);
	lz_pedmd_scene_free(&p);
	return st;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "Z", .ref = "Z_ref", .source = "Z_ref_source"},
	{.key = "identical_to_serial"}, {.key = "efficiency"}, {.key = "rollbacks"},
	{.key = "speedup_virtual"}, {NULL},
};
static const lz_speed speed[] = {
	{"events_per_s", "events/s (wall; every rank in one process)"}, {NULL},
};

const lz_method lz_method_pedmd = {
	LZ_METHOD_KEYS("pedmd", keys),
	.help = "parallel event-driven hard spheres and disks: P optimistic ranks with "
	        "ghosts, state saving and rollback, in one process (the stub; lz-mpi: one "
	        "process per rank); equal to the serial run bit for bit",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
