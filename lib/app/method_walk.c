/* method_walk.c — the `walk` engine: hard disks (spheres) of radius R on a lattice,
 * moved by random walk or ballistically with rejection of overlapping moves
 * (lz/walk.h, thesis 2.2 and 2.4.1).
 *
 * A run places the particles at random (random sequential placement, or a random
 * subset of a grid with start = grid; inside the slit with walls = slit), runs `equilibrate` sweeps, then `steps` measured sweeps; every
 * `sample`-th configuration goes to a g(r) accumulator (observe = gr, lz/gr.h, σ =
 * 2R; gr.dat) or to a density profile across the slit (observe = profile,
 * lz/profile.h; profile.dat). It always writes the final configuration (config.dat) and summarises the
 * acceptance, the packing fraction and the speed in atom-steps per second (the
 * sweeps alone are timed, not the g(r) sampling).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/gr.h"
#include "lz/lattice.h"
#include "lattice_scene.h"
#include "config.h"
#include "method.h"
#include "lz/profile.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/walk.h"

enum { OBSERVE_NONE, OBSERVE_GR, OBSERVE_PROFILE };
enum { WALLS_NONE, WALLS_SLIT };


static const lz_key keys[] = {
	LZ_KEY_LATTICE,
	{.name = "size", .type = LZ_KEY_INT, .def = "64", .min = 2, .max = LZ_LATTICE_SIDE_MAX,
	 .unit = "sites",
	 .help = "box side L in lattice units, a power of two (periodic in every direction)"},
	{.name = "radius", .type = LZ_KEY_REAL, .def = "3", .min = 0,
	 .max = LZ_LATTICE_SIDE_MAX / 4, .min_open = 1, .unit = "lattice units",
	 .help = "particle radius R; the diameter σ = 2R must be at most L/2"},
	{.name = "n", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e7,
	 .group = 1, .help = "number of particles (give n or packing, not both)"},
	{.name = "packing", .type = LZ_KEY_REAL, .def = "", .min = 0, .max = LZ_WALK_CLOSE_2D,
	 .min_open = 1, .group = 1,
	 .help = "packing fraction η = N·πR²/(L²·cell) (4/3 πR³/L³ in 3D), of the slit "
	         "N·πR²/(L·H) " "with walls = slit; n is rounded from it"},
	{.name = "motion", .type = LZ_KEY_ENUM, .def = "walk", .choices = "walk|ballistic",
	 .help = "walk: a new random direction every step; ballistic: keep it until a "
	         "collision"},
	{.name = "start", .type = LZ_KEY_ENUM, .def = "random", .choices = "random|grid",
	 .help = "random: random sequential placement (jams near η = 0.55); grid: a random "
	         "subset of "
	         "a grid of spacing ceil(2R), for denser or narrow systems (equilibrate it)"},
	{.name = "steps", .type = LZ_KEY_INT, .def = "1000", .min = 1, .max = 1e12,
	 .unit = "sweeps",
	 .help = "measured ensemble steps (one move offered to every particle each)"},
	{.name = "equilibrate", .type = LZ_KEY_INT, .def = "0", .max = 1e12, .unit = "sweeps",
	 .help = "sweeps run and discarded before the measured ones"},
	{.name = "walls", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|slit",
	 .help = "slit: hard walls across the last axis (y; z in 3D), slit_width apart; "
	         "periodic " "along the others"},
	{.name = "slit_width", .type = LZ_KEY_REAL, .def = "", .min = 0,
	 .max = LZ_LATTICE_SIDE_MAX, .min_open = 1, .max_open = 1, .unit = "lattice units",
	 .help = "distance H between the walls (Cartesian); centres keep R from both; at "
	         "most L " "(L·√3/2 triangular)"},
	{.name = "observe", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|gr|profile",
	 .help = "gr: g(r) raw and lattice-corrected into gr.dat (no walls); profile: the "
	         "density " "across the last axis into profile.dat"},
	{.name = "sample", .type = LZ_KEY_INT, .def = "10", .min = 1, .max = 1e12,
	 .unit = "sweeps", .help = "add a configuration to g(r) or the profile every k sweeps"},
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto",
	 .help = "random seed of the placement and the moves"},
};

/* ---- the scene ---- */

/* The packing fraction of n particles: of the box, or of the slit. */
static double scene_packing(const lz_scene *s, long long n)
{
	lz_lattice_kind kind = lz_scene_lattice(s);
	long long side = lz_scene_int(s, "size");
	double radius = lz_scene_real(s, "radius");
	if (lz_scene_enum(s, "walls") == WALLS_SLIT)
		return lz_walk_slit_packing(lz_lattice_dim(kind), side,
		                            lz_scene_real(s, "slit_width"), radius, (size_t)n);
	return lz_walk_packing(kind, side, radius, (size_t)n);
}

/* n as given, or rounded from the packing fraction. */
static long long particles(const lz_scene *s)
{
	return lz_scene_count(s, "packing", scene_packing(s, 1));
}

/* The walls: slit_width exactly when walls = slit, and a width lz_walk_set_slit
 * accepts (tried on a one-particle walker, so the rules live in one place). */
static int check_walls(const lz_scene *s)
{
	int slit = lz_scene_enum(s, "walls") == WALLS_SLIT, has_w = lz_scene_has(s, "slit_width");
	if (slit != has_w)
		return lz_scene_fail(s, slit ? "walls" : "slit_width", "%s", slit ?
		                     "walls = slit needs slit_width (the distance between the walls)" :
		                     "slit_width is given but walls = none; add walls = slit");
	if (!slit)
		return LZ_OK;
	if (lz_scene_enum(s, "observe") == OBSERVE_GR)
		return lz_scene_fail(s, "observe", "observe = gr needs walls = none: g(r) assumes a "
		                     "homogeneous periodic box; use observe = profile in a slit");
	lz_walk *w = lz_walk_alloc(lz_scene_lattice(s), lz_scene_int(s, "size"),
	                           lz_scene_real(s, "radius"), 1, LZ_WALK_RANDOM);
	int status = w ? lz_walk_set_slit(w, lz_scene_real(s, "slit_width")) : LZ_ENOMEM;
	lz_walk_free(w);
	return status == LZ_OK ? LZ_OK : lz_scene_fail(s, "slit_width", "%s", lz_error_message());
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
	if (check_walls(s) != LZ_OK)
		return LZ_EINVAL;
	int has_n = lz_scene_has(s, "n"), has_p = lz_scene_has(s, "packing");
	if (has_n == has_p)
		return lz_scene_fail(s, has_n ? "packing" : "radius", "give exactly one of n and "
		                     "packing (%s)", has_n ? "both given" : "neither given");
	lz_lattice_kind kind = lz_scene_lattice(s);
	long long n = particles(s);
	if (n < 1)
		return lz_scene_fail(s, "packing", "packing = %g is less than one particle of radius "
		                     "%g in a box of side %lld", lz_scene_real(s, "packing"), radius,
		                     side);
	double eta = scene_packing(s, n);
	double close = lz_lattice_dim(kind) == 2 ? LZ_WALK_CLOSE_2D : LZ_WALK_CLOSE_3D;
	if (eta > close)
		return lz_scene_fail(s, has_n ? "n" : "packing", "n = %lld particles of radius %g "
		                     "in a %s of side %lld pack %.4f, beyond close packing %.4f in "
		                     "%dD", n, radius, lz_scene_enum(s, "walls") ? "slit" : "box",
		                     side, eta, close, lz_lattice_dim(kind));
	if (lz_scene_enum(s, "observe") == OBSERVE_GR && n < 2)
		return lz_scene_fail(s, "observe", "observe = gr needs at least 2 particles (n = %lld)",
		                     n);
	return LZ_OK;
}

/* ---- files ---- */

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

/* The profile in reduced units, ρσ^dim, row by row (rows lo .. hi), in a new array
 * (NULL with lz_error on failure). Computed once, for the summary and the file. */
static double *profile_reduced(const lz_walk *w, const lz_profile *p)
{
	int rows = p->hi - p->lo + 1;
	double *rho = malloc((size_t)rows * sizeof *rho);
	if (!rho)
		return lz_error(LZ_ENOMEM, "no memory for %d profile rows", rows), NULL;
	if (lz_profile_result(p, rho) != LZ_OK) {
		free(rho);
		return NULL;
	}
	double scale = pow(2 * w->radius, w->dim);
	for (int c = 0; c < rows; c++)
		rho[c] *= scale;
	return rho;
}

/* Contact (the mean of the two wall rows) and middle (the middle fifth of the rows)
 * reduced densities: at a hard wall the contact density is the pressure, βP = ρ(contact). */
static void profile_summary(const lz_profile *p, const double *rho, lz_json *j)
{
	int rows = p->hi - p->lo + 1;
	int a = rows / 2 - rows / 10, b = rows / 2 + rows / 10;
	double mid = 0;
	for (int c = a; c <= b; c++)
		mid += rho[c] / (b - a + 1);
	lz_json_num(j, "contact_density", (rho[0] + rho[rows - 1]) / 2);
	lz_json_num(j, "middle_density", mid);
	lz_json_int(j, "profile_samples", (long long)p->nsamples);
}

static int write_profile(const lz_walk *w, const lz_profile *p, const double *rho,
                         const lz_run *run)
{
	static const char *const names[] = {"z/sigma", "rho_reduced"};
	static const char *const units[] = {"σ = 2R, from contact with the lower wall", "ρσ^dim"};
	char path[4200], title[240];
	int status = lz_rundir_file(run->dir, "profile.dat", path, sizeof path);
	if (status != LZ_OK)
		return status;
	snprintf(title, sizeof title, "density across a slit of width %g (walls at z/σ = -0.5 "
	         "and %g), %zu disks of radius %g on the %s lattice, %llu configurations",
	         w->slit_width, w->slit_width / (2 * w->radius) - 0.5, w->n, w->radius,
	         lz_lattice_name(w->box->kind), (unsigned long long)p->nsamples);
	lz_data *d = lz_data_open(path, title, 2, names, units);
	if (!d)
		return LZ_EIO;
	double h = lz_walk_row_spacing(w->box->kind), sigma = 2 * w->radius;
	for (int c = 0; c <= p->hi - p->lo; c++) {
		double row[2] = {((p->lo + c) * h - w->radius) / sigma, rho[c]};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

/* The plot of walk.gp below its terminal lines: g(r), the profile, or the disks. */
static void plot_body(FILE *f, const lz_walk *w, int observe, double eta)
{
	const char *lattice = lz_lattice_name(w->box->kind);
	if (observe == OBSERVE_GR)
		fprintf(f, "set grid\nset title \"hard disks on the %s lattice, R = %g, η = %.3f\"\n"
		        "set xlabel 'r / σ'\nset ylabel 'g(r)'\nset xrange [0:*]\n"
		        "plot 'gr.dat' u 1:2 w l lw 1 lc rgb '#bbbbbb' t 'raw (exact shell area)', "
		        "'' u 1:3 w lp pt 7 ps 0.5 lw 2 t 'corrected (lattice point count)', "
		        "1 w l dt 2 lc rgb 'black' t 'ideal gas'\n", lattice, w->radius, eta);
	else if (observe == OBSERVE_PROFILE)
		fprintf(f, "set grid\nset title \"%zu hard %s in a slit %g wide, R = %g (%s), η = "
		        "%.3f\"\nset xlabel 'z / σ from contact with the lower wall'\n"
		        "set ylabel 'ρσ^%d'\nset arrow from -0.5, graph 0 to -0.5, graph 1 nohead lw 3\n"
		        "set arrow from %g, graph 0 to %g, graph 1 nohead lw 3\nunset key\n"
		        "plot 'profile.dat' u 1:2 w l lw 2\n", w->n, w->dim == 2 ? "disks" : "spheres",
		        w->slit_width, w->radius, lattice, eta, w->dim,
		        w->slit_width / (2 * w->radius) - 0.5, w->slit_width / (2 * w->radius) - 0.5);
	else {
		for (int k = 0; w->slit && k < 2; k++)  /* the walls, at y = 0 and H */
			fprintf(f, "set arrow from graph 0, first %g to graph 1, first %g nohead lw 3\n",
			        k * w->slit_width, k * w->slit_width);
		fprintf(f, "set title \"%zu disks on the %s lattice, R = %g, η = %.3f\"\n"
		        "set size ratio -1\nset xlabel 'x [lattice units]'\n"
		        "set ylabel 'y [lattice units]'\nunset key\n"
		        "plot 'config.dat' u 1:2:3 w circles fs transparent solid 0.4 lc rgb "
		        "'#3060c0'\n", w->n, lattice, w->radius, eta);
	}
}

/* walk.gp: g(r) or the profile when observed, otherwise the configuration (2D). */
static int write_plot(const lz_walk *w, int observe, double eta, const lz_run *run)
{
	if (observe == OBSERVE_NONE && w->dim != 2)
		return LZ_OK;
	static const char *const what[] = {"the final disks", "g(r), raw and lattice-corrected",
	                                   "the density profile across the slit"};
	FILE *f = lz_run_script(run, "walk", "walk", what[observe], 800, 700);
	if (!f)
		return LZ_EIO;
	fprintf(f, "set key below horizontal\n");
	plot_body(f, w, observe, eta);
	return lz_run_plot(run, f, "walk");
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

/* What a run holds: the walkers and at most one observer. */
typedef struct {
	lz_rng *rng;
	lz_walk *w;
	lz_gr *g;          /* observe = gr */
	lz_profile *prof;  /* observe = profile */
	double *rho;       /* its reduced density per row, once measured */
	double wall;       /* seconds in the measured sweeps */
	uint64_t moves0, acc0;  /* the counters when the measurement began */
} state;

static void state_free(state *st)
{
	free(st->rho);
	lz_profile_free(st->prof);
	lz_gr_free(st->g);
	lz_walk_free(st->w);
	lz_rng_free(st->rng);
}

/* Walkers placed (in the slit, if any) and the observer the scene asks for. */
static int setup(const lz_scene *s, state *st)
{
	lz_lattice_kind kind = lz_scene_lattice(s);
	int64_t side = lz_scene_int(s, "size");
	size_t n = (size_t)particles(s);
	lz_walk_motion motion = lz_scene_enum(s, "motion") == 1 ? LZ_WALK_BALLISTIC
	                                                        : LZ_WALK_RANDOM;
	st->rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	if (!st->rng)
		return LZ_ENOMEM;
	st->w = lz_walk_alloc(kind, side, lz_scene_real(s, "radius"), n, motion);
	if (!st->w)
		return LZ_EINVAL;
	int status = LZ_OK;
	if (lz_scene_enum(s, "walls") == WALLS_SLIT)
		status = lz_walk_set_slit(st->w, lz_scene_real(s, "slit_width"));
	if (status == LZ_OK)
		status = lz_scene_enum(s, "start") == 1 ? lz_walk_place_grid(st->w, st->rng->gsl)
		                                        : lz_walk_place(st->w, st->rng->gsl, 0);
	if (status != LZ_OK)
		return status;
	int observe = lz_scene_enum(s, "observe");
	if (observe == OBSERVE_GR) {
		int max_r = (int)(side / 2), cap = st->w->dim == 2 ? LZ_GR_MAX_SHELLS_2D
		                                                  : LZ_GR_MAX_SHELLS_3D;
		st->g = lz_gr_alloc(kind, side, max_r < cap ? max_r : cap, n);
		return st->g ? LZ_OK : LZ_ENOMEM;
	}
	if (observe == OBSERVE_PROFILE) {
		st->prof = lz_profile_alloc(kind, side, st->w->lo, st->w->hi, n);
		return st->prof ? LZ_OK : LZ_ENOMEM;
	}
	return LZ_OK;
}

/* Equilibration, then the measured sweeps with a sample every `sample` sweeps. */
static int measure(const lz_scene *s, state *st, int quiet)
{
	unsigned long long steps = (unsigned long long)lz_scene_int(s, "steps");
	unsigned long long equil = (unsigned long long)lz_scene_int(s, "equilibrate");
	unsigned long long sample = (unsigned long long)lz_scene_int(s, "sample");
	int observing = st->g || st->prof, status = LZ_OK;
	lz_progress p;
	unsigned long long done = 0;
	double equil_wall = 0;
	if (!quiet)
		lz_progress_begin(&p, "walk", (double)(equil + steps));
	sweeps(st->w, st->rng->gsl, equil, &equil_wall, &p, &done, quiet);
	st->moves0 = st->w->moves;
	st->acc0 = st->w->accepted;
	for (unsigned long long k = 0; k < steps && status == LZ_OK;) {
		unsigned long long chunk = observing ? sample : steps;
		if (chunk > steps - k)
			chunk = steps - k;
		sweeps(st->w, st->rng->gsl, chunk, &st->wall, &p, &done, quiet);
		k += chunk;
		if (chunk == sample && st->g)
			status = lz_gr_add_config(st->g, st->w->box, st->w->r);
		else if (chunk == sample && st->prof)
			status = lz_profile_add_config(st->prof, st->w->r);
	}
	if (!quiet)
		lz_progress_end(&p);
	if (status == LZ_OK && lz_walk_overlaps(st->w) != 0)
		status = lz_error(LZ_EPHYS, "%zu overlapping pairs after the run: a move was accepted "
		                  "that it should have rejected", lz_walk_overlaps(st->w));
	return status;
}

/* N σ^dim per unit area (volume) of the box or of the slit: the reduced density. */
static double reduced_density(const lz_walk *w)
{
	double L = (double)w->box->side, sigma = 2 * w->radius;
	double volume = w->slit ? pow(L, w->dim - 1) * w->slit_width
	                        : pow(L, w->dim) * lz_lattice_cell_volume(w->box->kind);
	return (double)w->n * pow(sigma, w->dim) / volume;
}

static void summarise(const state *st, double eta, lz_json *j)
{
	const lz_walk *w = st->w;
	uint64_t moves = w->moves - st->moves0, acc = w->accepted - st->acc0;
	double wall = st->wall > 0 ? st->wall : 1e-9;
	double steps = (double)(moves / w->n);
	lz_json_int(j, "n_placed", (long long)w->n);
	lz_json_num(j, "packing_fraction", eta);
	lz_json_num(j, "reduced_density", reduced_density(w));
	lz_json_num(j, "acceptance", moves ? (double)acc / (double)moves : NAN);
	lz_json_int(j, "steps_run", (long long)steps);
	lz_json_num(j, "steps_per_s", steps / wall);
	lz_json_num(j, "atomsteps_per_s", (double)moves / wall);
	lz_json_int(j, "state_bytes_per_particle",
	            (long long)(w->dim * sizeof(int32_t) + sizeof(int)));
	if (st->g)
		lz_json_int(j, "gr_samples", (long long)st->g->nsamples);
	if (st->rho)
		profile_summary(st->prof, st->rho, j);
}

static int run(const lz_scene *s, lz_run *run)
{
	state st = {0};
	int status = setup(s, &st);
	if (status == LZ_OK)
		status = measure(s, &st, run->quiet);
	double eta = scene_packing(s, (long long)particles(s));
	if (status == LZ_OK && st.prof && st.prof->nsamples > 0 &&
	    !(st.rho = profile_reduced(st.w, st.prof)))
		status = LZ_ENOMEM;
	if (status == LZ_OK)
		summarise(&st, eta, run->summary);
	if (status == LZ_OK)
		status = lz_config_write_lattice(run, st.w->box->kind, st.w->box->side, st.w->n, st.w->r,
		                             st.w->radius);
	if (status == LZ_OK && st.g && st.g->nsamples > 0)
		status = write_gr(st.g, 2 * st.w->radius, run);
	if (status == LZ_OK && st.rho)
		status = write_profile(st.w, st.prof, st.rho, run);
	int shown = st.g && st.g->nsamples > 0 ? OBSERVE_GR
	            : st.rho ? OBSERVE_PROFILE : OBSERVE_NONE;
	if (status == LZ_OK)
		status = write_plot(st.w, shown, eta, run);
	state_free(&st);
	return status;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "n_placed"}, {.key = "packing_fraction"}, {.key = "acceptance"},
	{.key = "contact_density"}, {.key = "middle_density"}, {NULL},
};
static const lz_speed speed[] = {{"atomsteps_per_s", "atom-steps/s"}, {NULL}};

const lz_method lz_method_walk = {
	LZ_METHOD_KEYS("walk", keys),
	.help = "hard disks (spheres) on a lattice: random walk or ballistic moves with "
	        "rejection of overlaps, all pairs; g(r) on the lattice",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
