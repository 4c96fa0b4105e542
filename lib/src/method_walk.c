/* method_walk.c — the `walk` engine: hard disks (spheres) of radius R on a lattice,
 * moved by random walk or ballistically with rejection of overlapping moves
 * (lz/walk.h, thesis 2.2 and 2.4.1).
 *
 * A run places the particles at random (random sequential placement), runs
 * `equilibrate` sweeps, then `steps` measured sweeps; with observe = gr it adds every
 * `sample`-th configuration to a g(r) accumulator (lz/gr.h, σ = 2R) and writes
 * gr.dat. It always writes the final configuration (config.dat) and summarises the
 * acceptance, the packing fraction and the speed in atom-steps per second (the
 * sweeps alone are timed, not the g(r) sampling).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/gr.h"
#include "lz/lattice.h"
#include "lz/method.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/walk.h"

enum { OBSERVE_NONE, OBSERVE_GR };

/* The densest packings: hexagonal disks π/√12, fcc spheres π/√18. */
#define CLOSE_2D 0.90689968211710892
#define CLOSE_3D 0.74048048969306104

static const lz_key keys[] = {
	{"lattice", LZ_KEY_ENUM, "square", 0, 0, 0, 0, "square|square8|triangular|cubic", NULL,
	 "lattice and its moves: 4, 4+4 diagonal, 6 (sheared) neighbours; cubic is 3D with 6"},
	{"size", LZ_KEY_INT, "64", 2, LZ_LATTICE_SIDE_MAX, 0, 0, NULL, "sites",
	 "box side L in lattice units, a power of two (periodic in every direction)"},
	{"radius", LZ_KEY_REAL, "3", 0, LZ_LATTICE_SIDE_MAX / 4, 1, 0, NULL, "lattice units",
	 "particle radius R; the diameter σ = 2R must be at most L/2"},
	{"n", LZ_KEY_INT, "", 1, 1e7, 0, 0, NULL, NULL,
	 "number of particles (give n or packing, not both)"},
	{"packing", LZ_KEY_REAL, "", 0, CLOSE_2D, 1, 0, NULL, NULL,
	 "packing fraction η = N·πR²/(L²·cell) (4/3 πR³/L³ in 3D); n is rounded from it"},
	{"motion", LZ_KEY_ENUM, "walk", 0, 0, 0, 0, "walk|ballistic", NULL,
	 "walk: a new random direction every step; ballistic: keep it until a collision"},
	{"steps", LZ_KEY_INT, "1000", 1, 1e12, 0, 0, NULL, "sweeps",
	 "measured ensemble steps (one move offered to every particle each)"},
	{"equilibrate", LZ_KEY_INT, "0", 0, 1e12, 0, 0, NULL, "sweeps",
	 "sweeps run and discarded before the measured ones"},
	{"observe", LZ_KEY_ENUM, "none", 0, 0, 0, 0, "none|gr", NULL,
	 "gr: accumulate g(r) (raw and lattice-corrected) into gr.dat"},
	{"sample", LZ_KEY_INT, "10", 1, 1e12, 0, 0, NULL, "sweeps",
	 "add a configuration to g(r) every k sweeps (observe = gr)"},
	{"seed", LZ_KEY_SEED, "auto", 0, 0, 0, 0, NULL, NULL,
	 "random seed of the placement and the moves"},
};

/* ---- the scene ---- */

static lz_lattice_kind scene_kind(const lz_scene *s)
{
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE8,
	                                        LZ_LATTICE_TRIANGULAR, LZ_LATTICE_CUBIC};
	return kinds[lz_scene_enum(s, "lattice")];
}

/* n as given, or rounded from the packing fraction. */
static long long scene_n(const lz_scene *s)
{
	if (lz_scene_has(s, "n"))
		return lz_scene_int(s, "n");
	lz_lattice_kind kind = scene_kind(s);
	double one = lz_walk_packing(kind, lz_scene_int(s, "size"), lz_scene_real(s, "radius"), 1);
	return llround(lz_scene_real(s, "packing") / one);
}

static int check(const lz_scene *s)
{
	long long side = lz_scene_int(s, "size");
	if (lz_lattice_side_check(side) != LZ_OK)
		return lz_scene_fail(s, "size", "%s", lz_error_message());
	double radius = lz_scene_real(s, "radius");
	if (4.0 * radius > (double)side)
		return lz_scene_fail(s, "radius", "radius = %g is too large for size = %lld: the "
		                     "diameter 2R must be at most L/2, so R <= %lld", radius, side,
		                     side / 4);
	int has_n = lz_scene_has(s, "n"), has_p = lz_scene_has(s, "packing");
	if (has_n == has_p)
		return lz_scene_fail(s, has_n ? "packing" : "radius", "give exactly one of n and "
		                     "packing (%s)", has_n ? "both given" : "neither given");
	lz_lattice_kind kind = scene_kind(s);
	long long n = scene_n(s);
	if (n < 1)
		return lz_scene_fail(s, "packing", "packing = %g is less than one particle of radius "
		                     "%g in a box of side %lld", lz_scene_real(s, "packing"), radius,
		                     side);
	double eta = lz_walk_packing(kind, side, radius, (size_t)n);
	double close = lz_lattice_dim(kind) == 2 ? CLOSE_2D : CLOSE_3D;
	if (eta > close)
		return lz_scene_fail(s, has_n ? "n" : "packing", "n = %lld particles of radius %g "
		                     "in a box of side %lld pack %.4f, beyond close packing %.4f in "
		                     "%dD", n, radius, side, eta, close, lz_lattice_dim(kind));
	if (lz_scene_enum(s, "observe") == OBSERVE_GR && n < 2)
		return lz_scene_fail(s, "observe", "observe = gr needs at least 2 particles (n = %lld)",
		                     n);
	return LZ_OK;
}

/* ---- files ---- */

/* Site (x, y) of the sheared triangular lattice in Cartesian coordinates. */
static void cartesian(lz_lattice_kind kind, const int32_t *p, int dim, double *c)
{
	c[0] = p[0];
	c[1] = p[1];
	c[2] = dim == 3 ? p[2] : 0;
	if (kind == LZ_LATTICE_TRIANGULAR) {
		c[0] = p[0] + 0.5 * p[1];
		c[1] = 0.8660254037844386 * p[1];
	}
}

static int write_config(const lz_walk *w, const lz_run *run)
{
	static const char *const names[] = {"x", "y", "z", "R"};
	static const char *const u2[] = {"lattice units", "lattice units", "lattice units"};
	static const char *const names2[] = {"x", "y", "R"};
	char path[4200];
	int status = lz_rundir_file(run->dir, "config.dat", path, sizeof path);
	if (status != LZ_OK)
		return status;
	char title[200];
	snprintf(title, sizeof title, "final configuration, %zu particles of radius %g on the %s "
	         "lattice (Cartesian coordinates)", w->n, w->radius, lz_lattice_name(w->box->kind));
	int ncol = w->dim + 1;
	lz_data *d = lz_data_open(path, title, ncol, w->dim == 3 ? names : names2, u2);
	if (!d)
		return LZ_EIO;
	for (size_t i = 0; i < w->n; i++) {
		double c[3], row[4];
		cartesian(w->box->kind, w->r + i * (size_t)w->dim, w->dim, c);
		for (int k = 0; k < w->dim; k++)
			row[k] = c[k];
		row[w->dim] = w->radius;
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

static int write_gr(const lz_gr *g, double sigma, const lz_run *run)
{
	static const char *const names[] = {"r/sigma", "g_raw", "g"};
	static const char *const units[] = {"σ = 2R", NULL, NULL};
	double *raw = malloc(2 * (size_t)g->nshells * sizeof *raw);
	if (!raw)
		return lz_error(LZ_ENOMEM, "no memory for %d g(r) shells", g->nshells);
	double *cor = raw + g->nshells;
	int status = lz_gr_result(g, raw, cor);
	char path[4200];
	if (status == LZ_OK)
		status = lz_rundir_file(run->dir, "gr.dat", path, sizeof path);
	lz_data *d = NULL;
	if (status == LZ_OK) {
		char title[200];
		snprintf(title, sizeof title, "g(r) on the %s lattice, shells [k, k+1) at their "
		         "midpoints, %llu configurations; g_raw by the exact shell area, g by the "
		         "lattice point count", lz_lattice_name(g->kind),
		         (unsigned long long)g->nsamples);
		d = lz_data_open(path, title, 3, names, units);
		if (!d)
			status = LZ_EIO;
	}
	for (int k = 0; status == LZ_OK && k < g->nshells; k++) {
		double row[3] = {(k + 0.5) / sigma, raw[k], cor[k]};
		lz_data_row(d, row);
	}
	if (d && lz_data_close(d) != LZ_OK && status == LZ_OK)
		status = LZ_EIO;
	free(raw);
	return status;
}

/* walk.gp: g(r) when it was observed, otherwise the configuration (2D). */
static int write_plot(const lz_walk *w, int observe, double eta, const lz_run *run)
{
	if (observe != OBSERVE_GR && w->dim != 2)
		return LZ_OK;
	char path[4200];
	int status = lz_rundir_file(run->dir, "walk.gp", path, sizeof path);
	FILE *f = status == LZ_OK ? fopen(path, "w") : NULL;
	if (!f)
		return status != LZ_OK ? status : lz_error(LZ_EIO, "cannot write %s", path);
	fprintf(f, "# lz run, method walk: %s.\n"
	        "set terminal pngcairo size 800,700 enhanced font 'Sans,11'\n"
	        "set output 'walk.png'\nset key below horizontal\n",
	        observe == OBSERVE_GR ? "g(r), raw and lattice-corrected" : "the final disks");
	if (observe == OBSERVE_GR)
		fprintf(f, "set grid\nset title \"hard disks on the %s lattice, R = %g, η = %.3f\"\n"
		        "set xlabel 'r / σ'\nset ylabel 'g(r)'\nset xrange [0:*]\n"
		        "plot 'gr.dat' u 1:2 w l lw 1 lc rgb '#bbbbbb' t 'raw (exact shell area)', "
		        "'' u 1:3 w lp pt 7 ps 0.5 lw 2 t 'corrected (lattice point count)', "
		        "1 w l dt 2 lc rgb 'black' t 'ideal gas'\n",
		        lz_lattice_name(w->box->kind), w->radius, eta);
	else
		fprintf(f, "set title \"%zu disks on the %s lattice, R = %g, η = %.3f\"\n"
		        "set size ratio -1\nset xlabel 'x [lattice units]'\n"
		        "set ylabel 'y [lattice units]'\nunset key\n"
		        "plot 'config.dat' u 1:2:3 w circles fs transparent solid 0.4 lc rgb "
		        "'#3060c0'\n", w->n, lz_lattice_name(w->box->kind), w->radius, eta);
	if (fclose(f) != 0)
		return lz_error(LZ_EIO, "cannot write %s", path);
	status = lz_gnuplot(run->dir->tmp, "walk.gp");
	return status == 1 ? LZ_OK : status;
}

/* ---- the run ---- */

/* `count` sweeps; the time spent in them is added to *wall. */
static int sweeps(lz_walk *w, gsl_rng *rng, unsigned long long count, double *wall,
                  lz_progress *p, unsigned long long *done, int quiet)
{
	unsigned long long left = count;
	while (left > 0) {
		unsigned long long chunk = left < 64 ? left : 64;
		double t0 = lz_wall_now();
		for (unsigned long long k = 0; k < chunk; k++)
			lz_walk_sweep(w, rng);
		*wall += lz_wall_now() - t0;
		left -= chunk;
		*done += chunk;
		if (!quiet)
			lz_progress_update(p, (double)*done);
	}
	return LZ_OK;
}

static int run(const lz_scene *s, lz_run *run)
{
	lz_lattice_kind kind = scene_kind(s);
	int64_t side = lz_scene_int(s, "size");
	double radius = lz_scene_real(s, "radius");
	size_t n = (size_t)scene_n(s);
	int observe = lz_scene_enum(s, "observe");
	unsigned long long steps = (unsigned long long)lz_scene_int(s, "steps");
	unsigned long long equil = (unsigned long long)lz_scene_int(s, "equilibrate");
	unsigned long long sample = (unsigned long long)lz_scene_int(s, "sample");
	lz_walk_motion motion = lz_scene_enum(s, "motion") == 1 ? LZ_WALK_BALLISTIC
	                                                        : LZ_WALK_RANDOM;
	lz_rng *rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	lz_walk *w = rng ? lz_walk_alloc(kind, side, radius, n, motion) : NULL;
	lz_gr *g = NULL;
	int status = w ? LZ_OK : rng ? LZ_EINVAL : LZ_ENOMEM;
	if (status == LZ_OK)
		status = lz_walk_place(w, rng->gsl, 0);
	if (status == LZ_OK && observe == OBSERVE_GR) {
		int max_r = (int)(side / 2), cap = w->dim == 2 ? LZ_GR_MAX_SHELLS_2D
		                                              : LZ_GR_MAX_SHELLS_3D;
		g = lz_gr_alloc(kind, side, max_r < cap ? max_r : cap, n);
		if (!g)
			status = LZ_ENOMEM;
	}
	double wall = 0, equil_wall = 0;
	uint64_t moves0 = 0, acc0 = 0;
	if (status == LZ_OK) {
		lz_progress p;
		unsigned long long done = 0;
		if (!run->quiet)
			lz_progress_begin(&p, "walk", (double)(equil + steps));
		sweeps(w, rng->gsl, equil, &equil_wall, &p, &done, run->quiet);
		moves0 = w->moves;
		acc0 = w->accepted;
		for (unsigned long long k = 0; k < steps && status == LZ_OK;) {
			unsigned long long chunk = observe == OBSERVE_GR ? sample : steps;
			if (chunk > steps - k)
				chunk = steps - k;
			sweeps(w, rng->gsl, chunk, &wall, &p, &done, run->quiet);
			k += chunk;
			if (g && chunk == sample)
				status = lz_gr_add_config(g, w->box, w->r);
		}
		if (!run->quiet)
			lz_progress_end(&p);
	}
	if (status == LZ_OK && lz_walk_overlaps(w) != 0)
		status = lz_error(LZ_EPHYS, "%zu overlapping pairs after the run: a move was accepted "
		                  "that it should have rejected", lz_walk_overlaps(w));
	double eta = lz_walk_packing(kind, side, radius, n);
	if (status == LZ_OK) {
		lz_json *j = run->summary;
		uint64_t moves = w->moves - moves0, acc = w->accepted - acc0;
		if (wall <= 0)
			wall = 1e-9;
		lz_json_int(j, "n_placed", (long long)n);
		lz_json_num(j, "packing_fraction", eta);
		lz_json_num(j, "acceptance", moves ? (double)acc / (double)moves : NAN);
		lz_json_int(j, "steps_run", (long long)steps);
		lz_json_num(j, "steps_per_s", (double)steps / wall);
		lz_json_num(j, "atomsteps_per_s", (double)n * (double)steps / wall);
		lz_json_int(j, "state_bytes_per_particle",
		            (long long)(w->dim * sizeof(int32_t) + sizeof(int)));
		if (g)
			lz_json_int(j, "gr_samples", (long long)g->nsamples);
	}
	if (status == LZ_OK)
		status = write_config(w, run);
	if (status == LZ_OK && g && g->nsamples > 0)
		status = write_gr(g, 2 * radius, run);
	if (status == LZ_OK)
		status = write_plot(w, g && g->nsamples > 0 ? OBSERVE_GR : OBSERVE_NONE, eta, run);
	lz_gr_free(g);
	lz_walk_free(w);
	lz_rng_free(rng);
	return status;
}

const lz_method lz_method_walk = {
	.name = "walk",
	.help = "hard disks (spheres) on a lattice: random walk or ballistic moves with "
	        "rejection of overlaps, all pairs; g(r) on the lattice",
	.keys = keys,
	.nkeys = sizeof keys / sizeof keys[0],
	.check = check,
	.run = run,
};
