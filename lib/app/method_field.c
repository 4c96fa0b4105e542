/* method_field.c — the `field` engine: hard disks (spheres) of radius R on a lattice in
 * the field representation (lz/field.h, thesis 2.4.4), placed by random sequential
 * adsorption up to a number, a coverage or exact jamming (thesis 2.5.1), then
 * optionally moved by random walk or ballistically, with a square-well attraction and
 * Metropolis moves when asked (lz/well.h).
 *
 * A run places the particles (timed alone, CPU seconds), builds the well on the placed
 * configuration, runs `equilibrate` sweeps and then `steps` measured sweeps, each
 * offering every particle, in index order, one trial move through lz_field_try_move
 * (the sweeps alone are timed for atomsteps_per_s). With a well the energy per
 * particle is recorded every `sample` sweeps (energy.dat) and averaged over the
 * measured ones, with an error bar from block means. Before it reports, a guard
 * checks the hard core (every centre is covered by its own excluded shape only) and
 * the free-site count. Files: config.dat and config.png (the disks, or a slice through
 * the spheres), energy.dat and energy.png with a well.
 */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/field.h"
#include "lz/lattice.h"
#include "lattice_scene.h"
#include "config.h"
#include "method.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/walk.h"
#include "lz/well.h"

enum { MOTION_NONE, MOTION_WALK, MOTION_BALLISTIC };
enum { NBLOCKS = 10 };  /* blocks of the energy's error bar */

static const lz_key keys[] = {
	LZ_KEY_LATTICE,
	{.name = "size", .type = LZ_KEY_INT, .def = "256", .min = 2, .max = 32768,
	 .unit = "sites",
	 .help = "box side L, a power of two, periodic; the field is L^dim bytes (L <= "
	         "32768 in 2D, " "1024 in 3D)"},
	{.name = "radius", .type = LZ_KEY_REAL, .def = "4", .min = 0, .max = 8192,
	 .min_open = 1, .unit = "lattice units",
	 .help = "particle radius R; the excluded disk of radius σ = 2R must fit in the "
	         "box: 4R <= L"},
	{.name = "n", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e9, .group = 1,
	 .help = "number of particles placed by random sequential adsorption (give one of "
	         "n, " "coverage and fill)"},
	{.name = "coverage", .type = LZ_KEY_REAL, .def = "", .min = 0, .max = LZ_WALK_CLOSE_2D,
	 .min_open = 1, .group = 1,
	 .help = "target coverage θ = N·πR²/(L²·cell), 4/3 πR³·N/L³ in 3D, n rounded from "
	         "it; " "adsorption jams near 0.547 (disks) and 0.384 (spheres)"},
	{.name = "fill", .type = LZ_KEY_ENUM, .def = "", .choices = "jam", .group = 1,
	 .help = "jam: adsorb until no free site is left (exact jamming, counted by the "
	         "field)"},
	{.name = "motion", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|walk|ballistic",
	 .help = "after the placement: none; walk: a new random direction every trial; "
	         "ballistic: " "keep it until a trial is refused"},
	{.name = "steps", .type = LZ_KEY_INT, .def = "1000", .min = 1, .max = 1e12,
	 .unit = "sweeps",
	 .help = "measured sweeps, each offering every particle one trial move (with "
	         "motion only)"},
	{.name = "equilibrate", .type = LZ_KEY_INT, .def = "0", .max = 1e12, .unit = "sweeps",
	 .help = "sweeps run and discarded before the measured ones (with motion only)"},
	{.name = "well_range", .type = LZ_KEY_REAL, .def = "0", .max = LZ_WELL_LAMBDA_MAX,
	 .unit = "σ",
	 .help = "square-well range λ: energy -ε for σ <= d < λσ, Metropolis moves; 0: "
	         "hard core " "only, else in (1, 3]"},
	{.name = "well_depth", .type = LZ_KEY_REAL, .def = "1", .max = 1000, .unit = "ε",
	 .help = "well depth ε, the energy unit (needs well_range)"},
	{.name = "temperature", .type = LZ_KEY_REAL, .def = "1", .min = 0, .max = 1000,
	 .min_open = 1, .unit = "ε/k", .help = "kT of the Metropolis moves (needs well_range)"},
	{.name = "sample", .type = LZ_KEY_INT, .def = "10", .min = 1, .max = 1e12,
	 .unit = "sweeps",
	 .help = "record the energy every k sweeps into energy.dat and its mean (needs "
	         "well_range)"},
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto",
	 .help = "random seed of the adsorption and the moves"},
};

/* ---- the scene ---- */

static int scene_dim(const lz_scene *s)
{
	return lz_lattice_dim(lz_scene_lattice(s));
}

/* The coverage of n particles. */
static double scene_coverage(const lz_scene *s, long long n)
{
	return lz_walk_packing(lz_scene_lattice(s), lz_scene_int(s, "size"),
	                       lz_scene_real(s, "radius"), (size_t)n);
}

/* The number of particles asked for: n, rounded from the coverage, or 0 (fill = jam). */
static long long particles(const lz_scene *s)
{
	return lz_scene_count(s, "coverage", scene_coverage(s, 1));
}

/* The key that sets the number of particles. */
static const char *count_key(const lz_scene *s)
{
	return lz_scene_has(s, "n") ? "n" : lz_scene_has(s, "coverage") ? "coverage" : "fill";
}

/* Size and radius, checked by building the (empty) field: lz_field_alloc holds the
 * rules and names the bad value. The field is kept for the well's check. */
static int check_box(const lz_scene *s, lz_field **f)
{
	long long side = lz_scene_int(s, "size");
	double sites = pow((double)side, scene_dim(s));
	const char *key = (side & (side - 1)) != 0 || sites > (double)LZ_FIELD_SITES_MAX
	                  ? "size" : "radius";
	*f = lz_field_alloc(lz_scene_lattice(s), side, lz_scene_real(s, "radius"));
	return *f ? LZ_OK : lz_scene_fail(s, key, "%s", lz_error_message());
}

/* Exactly one of n, coverage and fill; at least one particle, at most close packing. */
static int check_count(const lz_scene *s)
{
	int given = lz_scene_has(s, "n") + lz_scene_has(s, "coverage") + lz_scene_has(s, "fill");
	if (given != 1)
		return lz_scene_fail(s, given ? count_key(s) : "radius", "give exactly one of n, "
		                     "coverage and fill = jam (%s)", given ? "several given"
		                                                           : "none given");
	if (lz_scene_has(s, "fill"))
		return LZ_OK;
	long long n = particles(s);
	int dim = scene_dim(s);
	double close = dim == 2 ? LZ_WALK_CLOSE_2D : LZ_WALK_CLOSE_3D, theta = scene_coverage(s, n);
	if (n < 1)
		return lz_scene_fail(s, "coverage", "coverage = %g is less than one particle of "
		                     "radius %g in a box of side %lld (one covers %.3g)",
		                     lz_scene_real(s, "coverage"), lz_scene_real(s, "radius"),
		                     lz_scene_int(s, "size"), scene_coverage(s, 1));
	if (theta > close)
		return lz_scene_fail(s, count_key(s), "%lld particles cover θ = %.4f, beyond close "
		                     "packing %.4f in %dD: the coverage must be in (0, %.4f] (and "
		                     "random adsorption jams well before, near %s)", n, theta,
		                     close, dim, close, dim == 2 ? "0.547" : "0.384");
	return LZ_OK;
}

/* steps and equilibrate only mean something with motion. */
static int check_motion(const lz_scene *s)
{
	if (lz_scene_enum(s, "motion") != MOTION_NONE)
		return LZ_OK;
	const char *key = lz_scene_given(s, "steps") ? "steps"
	                  : lz_scene_given(s, "equilibrate") ? "equilibrate" : NULL;
	return key ? lz_scene_fail(s, key, "%s is given but motion = none: add motion = walk "
	                           "or motion = ballistic", key) : LZ_OK;
}

/* The well keys go with well_range; its values are checked by building the well on the
 * empty field (lz_well_alloc holds the rules). */
static int check_well(const lz_scene *s, const lz_field *f)
{
	static const char *const needs[] = {"well_depth", "temperature", "sample"};
	double lambda = lz_scene_real(s, "well_range");
	for (int k = 0; lambda == 0 && k < 3; k++)
		if (lz_scene_given(s, needs[k]))
			return lz_scene_fail(s, needs[k], "%s is given but well_range = 0 (no well): "
			                     "add well_range in (1, %g]", needs[k], LZ_WELL_LAMBDA_MAX);
	if (lambda == 0)
		return LZ_OK;
	if (lambda <= 1)
		return lz_scene_fail(s, "well_range", "well_range = %g: a well must reach beyond "
		                     "the hard core, λ in (1, %g] (or 0 for no well)", lambda,
		                     LZ_WELL_LAMBDA_MAX);
	lz_well *w = lz_well_alloc(f, lambda, lz_scene_real(s, "well_depth"),
	                           lz_scene_real(s, "temperature"));
	lz_well_free(w);
	return w ? LZ_OK : lz_scene_fail(s, "well_range", "%s", lz_error_message());
}

static int check(const lz_scene *s)
{
	lz_field *f = NULL;
	int status = check_box(s, &f);
	if (status == LZ_OK)
		status = check_count(s);
	if (status == LZ_OK)
		status = check_motion(s);
	if (status == LZ_OK)
		status = check_well(s, f);
	lz_field_free(f);
	return status;
}

/* ---- the energy's mean and error bar, without storing the series ---- */

typedef struct {
	unsigned long long per_block;  /* samples per block; 0: too few for an error bar */
	unsigned long long count;      /* samples so far */
	double sum;
	double block[NBLOCKS];         /* sums of the first NBLOCKS · per_block samples */
} series;

static void series_add(series *e, double x)
{
	if (e->per_block > 0 && e->count / e->per_block < NBLOCKS)
		e->block[e->count / e->per_block] += x;
	e->sum += x;
	e->count++;
}

/* The mean of all samples, and the standard error from the NBLOCKS block means (NaN
 * with fewer than NBLOCKS samples). */
static void series_result(const series *e, double *mean, double *err)
{
	*mean = e->count > 0 ? e->sum / (double)e->count : NAN;
	*err = NAN;
	if (e->per_block == 0)
		return;
	double means[NBLOCKS];
	for (int b = 0; b < NBLOCKS; b++)
		means[b] = e->block[b] / (double)e->per_block;
	*err = gsl_stats_sd(means, 1, NBLOCKS) / sqrt(NBLOCKS);
}

/* ---- the run ---- */

/* What a run holds. */
typedef struct {
	lz_rng *rng;
	lz_field *f;
	lz_well *w;              /* NULL without a well */
	int *dir;                /* ballistic: each particle's direction; else NULL */
	lz_data *energy;         /* energy.dat: with a well and motion */
	int jammed;              /* the placement ended with no free site */
	size_t free_sites;       /* nfree when the placement ended */
	double insert_s;         /* CPU seconds of the placement */
	double sweep_s;          /* CPU seconds of the measured sweeps */
	unsigned long long done; /* sweeps run, equilibration included */
	unsigned long long sample;  /* the energy is recorded every `sample` sweeps */
	uint64_t offered, accepted; /* trial moves since the measurement began */
	series e;                /* energy per particle over the measured sweeps */
} state;

static void state_free(state *st)
{
	if (st->energy)
		lz_data_close(st->energy);
	free(st->dir);
	lz_well_free(st->w);
	lz_field_free(st->f);
	lz_rng_free(st->rng);
}

/* Random sequential adsorption up to the number asked for, or to jamming; a target
 * the box jams before reaching is an error, not a silent shortfall. */
static int place(const lz_scene *s, state *st)
{
	size_t target = (size_t)particles(s);
	double t0 = lz_cpu_now();
	int status = lz_field_rsa(st->f, st->rng->gsl, target, &st->jammed);
	st->insert_s = lz_cpu_now() - t0;
	st->free_sites = st->f->nfree;
	if (status != LZ_OK || st->f->n >= target)
		return status;
	int dim = st->f->dim;
	char asked[80];
	if (lz_scene_has(s, "n"))
		snprintf(asked, sizeof asked, "n = %zu", target);
	else
		snprintf(asked, sizeof asked, "coverage = %g (%zu particles)",
		         lz_scene_real(s, "coverage"), target);
	return lz_scene_fail(s, count_key(s), "%s cannot be reached: random sequential "
	                     "adsorption jammed first, no free site was left at θ = %.4f with "
	                     "%zu placed (the RSA limit is about %s for %s, different on a coarse "
	                     "lattice, §4 of lesson 03); ask for less, or use fill = jam", asked,
	                     lz_field_coverage(st->f), st->f->n, dim == 2 ? "0.547" : "0.384",
	                     dim == 2 ? "disks" : "spheres");
}

/* energy.dat, opened for the rows the sweeps write. */
static int open_energy(const lz_scene *s, state *st, const lz_run *run)
{
	static const char *const names[] = {"sweep", "energy_per_particle"};
	static const char *const units[] = {NULL, "ε"};
	char path[4200], title[240];
	int status = lz_rundir_file(run->dir, "energy.dat", path, sizeof path);
	if (status != LZ_OK)
		return status;
	snprintf(title, sizeof title, "square-well energy per particle E/N every %llu sweeps, "
	         "λ = %g, kT/ε = %g, %zu particles; the first %lld sweeps equilibrate", st->sample,
	         lz_scene_real(s, "well_range"), st->w->temperature, st->f->n,
	         lz_scene_int(s, "equilibrate"));
	st->energy = lz_data_open(path, title, 2, names, units);
	return st->energy ? LZ_OK : LZ_EIO;
}

/* The field, its particles, the well, the directions and energy.dat. */
static int setup(const lz_scene *s, state *st, const lz_run *run)
{
	int motion = lz_scene_enum(s, "motion");
	double lambda = lz_scene_real(s, "well_range");
	st->sample = (unsigned long long)lz_scene_int(s, "sample");
	st->rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	if (!st->rng)
		return LZ_ENOMEM;
	st->f = lz_field_alloc(lz_scene_lattice(s), lz_scene_int(s, "size"), lz_scene_real(s, "radius"));
	if (!st->f)
		return LZ_EINVAL;
	int status = place(s, st);
	if (status == LZ_OK && lambda > 0 &&
	    !(st->w = lz_well_alloc(st->f, lambda, lz_scene_real(s, "well_depth"),
	                            lz_scene_real(s, "temperature"))))
		status = LZ_EINVAL;
	if (status == LZ_OK && motion == MOTION_BALLISTIC) {
		st->dir = malloc((st->f->n ? st->f->n : 1) * sizeof *st->dir);
		if (!st->dir)
			return lz_error(LZ_ENOMEM, "no memory for %zu directions", st->f->n);
		for (size_t i = 0; i < st->f->n; i++)
			st->dir[i] = (int)gsl_rng_uniform_int(st->rng->gsl,
			                                      (unsigned long)st->f->excl->ndir);
	}
	if (status == LZ_OK && st->w && motion != MOTION_NONE)
		status = open_energy(s, st, run);
	return status;
}

/* One sweep: every particle, in index order, offered one trial move. Walk: a fresh
 * direction each time; ballistic: its own, redrawn after a refusal for the next sweep. */
static void sweep(state *st)
{
	lz_field *f = st->f;
	gsl_rng *rng = st->rng->gsl;
	unsigned long ndir = (unsigned long)f->excl->ndir;
	uint64_t accepted = 0;
	if (st->dir) {
		for (size_t i = 0; i < f->n; i++) {
			int moved = lz_field_try_move(f, st->w, i, st->dir[i], rng);
			if (!moved)
				st->dir[i] = (int)gsl_rng_uniform_int(rng, ndir);
			accepted += (uint64_t)moved;
		}
	} else {
		for (size_t i = 0; i < f->n; i++)
			accepted += (uint64_t)lz_field_try_move(f, st->w, i,
			                                        (int)gsl_rng_uniform_int(rng, ndir), rng);
	}
	st->accepted += accepted;
	st->offered += f->n;
}

/* The energy per particle now: a row of energy.dat, and a sample of e when measuring. */
static void record(state *st, series *e)
{
	double x = st->f->n ? lz_well_energy(st->w, st->f) / (double)st->f->n : 0;
	double row[2] = {(double)st->done, x};
	lz_data_row(st->energy, row);
	if (e)
		series_add(e, x);
}

/* `count` sweeps, their CPU time added to *cpu; with a well the energy is recorded
 * whenever the sweep number reaches a multiple of `sample`. */
static void sweeps(state *st, unsigned long long count, double *cpu, series *e,
                   lz_progress *p, int quiet)
{
	unsigned long long every = st->energy ? st->sample : 64;
	while (count > 0) {
		unsigned long long chunk = every - st->done % every;
		if (chunk > count)
			chunk = count;
		double t0 = lz_cpu_now();
		for (unsigned long long k = 0; k < chunk; k++)
			sweep(st);
		*cpu += lz_cpu_now() - t0;
		st->done += chunk;
		count -= chunk;
		if (st->energy && st->done % every == 0)
			record(st, e);
		if (!quiet)
			lz_progress_update(p, (double)st->done);
	}
}

/* Equilibration, then the measured sweeps (none with motion = none). */
static void measure(const lz_scene *s, state *st, int quiet)
{
	if (lz_scene_enum(s, "motion") == MOTION_NONE)
		return;
	unsigned long long steps = (unsigned long long)lz_scene_int(s, "steps");
	unsigned long long equil = (unsigned long long)lz_scene_int(s, "equilibrate");
	lz_progress p;
	double equil_s = 0;
	if (!quiet)
		lz_progress_begin(&p, "field", (double)(equil + steps));
	if (st->energy)
		record(st, NULL);
	sweeps(st, equil, &equil_s, NULL, &p, quiet);
	st->offered = st->accepted = 0;
	st->e.per_block = steps / st->sample / NBLOCKS;
	sweeps(st, steps, &st->sweep_s, &st->e, &p, quiet);
	if (!quiet)
		lz_progress_end(&p);
}

/* The physics guard: a centre is covered by its own excluded shape only (cell == 1:
 * no other centre within σ), and the free-site count agrees with a full scan. */
static int guard(const lz_field *f)
{
	size_t overlapping = 0;
	for (size_t i = 0; i < f->n; i++) {
		const int32_t *c = f->r + i * (size_t)f->dim;
		overlapping += f->cell[lz_field_index(f, c[0], c[1], f->dim == 3 ? c[2] : 0)] != 1;
	}
	if (overlapping > 0)
		return lz_error(LZ_EPHYS, "%zu particles overlap another one (their centre lies in "
		                "a neighbour's excluded shape): a placement or a move broke the "
		                "hard core", overlapping);
	size_t scanned = lz_field_count_free(f);
	if (scanned != f->nfree)
		return lz_error(LZ_EPHYS, "the field counts %zu free sites but a scan finds %zu: "
		                "painting lost track of the free sites", f->nfree, scanned);
	return LZ_OK;
}

/* ---- the summary ---- */

static void summarise_placement(const state *st, lz_json *j)
{
	const lz_field *f = st->f;
	double L = f->side, sigma = 2 * f->radius;
	double bytes = (double)f->nsites * (st->w ? 2 : 1) +
	               (double)f->n * ((double)f->dim * sizeof(int32_t) + (st->dir ? sizeof(int) : 0));
	lz_json_int(j, "placed", (long long)f->n);
	lz_json_num(j, "placed_coverage", lz_field_coverage(f));
	lz_json_num(j, "reduced_density", (double)f->n * pow(sigma, f->dim) /
	            (pow(L, f->dim) * lz_lattice_cell_volume(f->kind)));
	lz_json_bool(j, "jammed", st->jammed);
	lz_json_int(j, "free_sites", (long long)st->free_sites);
	lz_json_int(j, "insert_attempts", (long long)f->tries);
	lz_json_num(j, "insert_s", st->insert_s);
	lz_json_num(j, "placed_per_s", st->insert_s > 0 ? (double)f->n / st->insert_s : NAN);
	lz_json_int(j, "excluded_points", (long long)f->excl->n);
	lz_json_num(j, "head_points", lz_shape_mean_move(f->excl));
	lz_json_int(j, "field_bytes", (long long)f->nsites);
	lz_json_int(j, "well_bytes", st->w ? (long long)f->nsites : 0);
	lz_json_num(j, "state_bytes_per_particle", f->n ? bytes / (double)f->n : NAN);
}

static void summarise_motion(const state *st, lz_json *j)
{
	double cpu = st->sweep_s > 0 ? st->sweep_s : 1e-9;
	double steps = st->f->n ? (double)st->offered / (double)st->f->n : 0;
	lz_json_int(j, "steps_run", (long long)steps);
	lz_json_num(j, "acceptance", st->offered ? (double)st->accepted / (double)st->offered
	                                         : NAN);
	lz_json_num(j, "steps_per_s", steps / cpu);
	lz_json_num(j, "atomsteps_per_s", (double)st->offered / cpu);
}

static void summarise_well(const state *st, lz_json *j)
{
	const lz_well *w = st->w;
	lz_json_num(j, "well_radius", w->range);
	lz_json_int(j, "well_points", (long long)w->shape->n);
	lz_json_num(j, "well_head_points", lz_shape_mean_move(w->shape));
	lz_json_num(j, "energy_per_particle", st->f->n ? lz_well_energy(w, st->f) /
	            (double)st->f->n : 0);
	if (!st->energy)
		return;
	double mean, err;
	series_result(&st->e, &mean, &err);
	lz_json_err(j, "energy_per_particle_mean", mean, err);
	lz_json_int(j, "energy_samples", (long long)st->e.count);
}

/* ---- plots ---- */

/* config.gp: the final configuration. */
static int write_config_plot(const state *st, const lz_run *run)
{
	const lz_field *f = st->f;
	char well[80] = "", title[256];
	if (st->w)
		snprintf(well, sizeof well, ", well λ = %g, kT/ε = %g", st->w->range / (2 * f->radius),
		         st->w->temperature);
	snprintf(title, sizeof title, "%zu %s, R = %g, %s lattice, θ = %.4f%s%s", f->n,
	         f->dim == 2 ? "disks" : "spheres", f->radius, lz_lattice_name(f->kind),
	         lz_field_coverage(f), st->jammed ? " (jammed)" : "", well);
	return lz_run_plot_config(run, "field", f->kind, f->side, f->side, title);
}

/* energy.gp: the energy per particle against the sweeps. */
static int write_energy_plot(const lz_scene *s, const state *st, const lz_run *run)
{
	FILE *p = lz_run_script(run, "energy", "field", "the square-well energy per particle",
	                        900, 560);
	if (!p)
		return LZ_EIO;
	fprintf(p, "unset key\nset grid\nset title \"%zu square-well %s, λ = %g, kT/ε = %g\"\n"
	        "set xlabel 'sweeps'\nset ylabel 'E / (N ε)'\n", st->f->n,
	        st->f->dim == 2 ? "disks" : "spheres", lz_scene_real(s, "well_range"),
	        st->w->temperature);
	if (lz_scene_int(s, "equilibrate") > 0)
		fprintf(p, "set arrow from %lld, graph 0 to %lld, graph 1 nohead dt 2\n",
		        lz_scene_int(s, "equilibrate"), lz_scene_int(s, "equilibrate"));
	fprintf(p, "plot 'energy.dat' u 1:2 w l lw 2\n");
	return lz_run_plot(run, p, "energy");
}

static int write_files(const lz_scene *s, state *st, const lz_run *run)
{
	const lz_field *f = st->f;
	int status = lz_config_write_lattice(run, f->kind, f->side, f->n, f->r, f->radius);
	if (status == LZ_OK && st->energy) {
		status = lz_data_close(st->energy);
		st->energy = NULL;
		if (status == LZ_OK)
			status = write_energy_plot(s, st, run);
	}
	return status == LZ_OK ? write_config_plot(st, run) : status;
}

static int run(const lz_scene *s, lz_run *run)
{
	state st = {0};
	int status = setup(s, &st, run);
	if (status == LZ_OK) {
		measure(s, &st, run->quiet);
		status = guard(st.f);
	}
	if (status == LZ_OK) {
		summarise_placement(&st, run->summary);
		if (lz_scene_enum(s, "motion") != MOTION_NONE)
			summarise_motion(&st, run->summary);
		if (st.w)
			summarise_well(&st, run->summary);
		status = write_files(s, &st, run);
	}
	state_free(&st);
	return status;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "placed"}, {.key = "placed_coverage"}, {.key = "jammed"},
	{.key = "acceptance"}, {.key = "energy_per_particle_mean"}, {NULL},
};
static const lz_speed speed[] = {
	{"atomsteps_per_s", "atom-steps/s (CPU)"}, {"placed_per_s", "placements/s (CPU)"}, {NULL},
};

const lz_method lz_method_field = {
	LZ_METHOD_KEYS("field", keys),
	.help = "hard disks (spheres) painted on a byte field: random sequential adsorption to "
	        "a number, a coverage or exact jamming, O(1) collision tests, walk or ballistic "
	        "moves, square-well Metropolis",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
