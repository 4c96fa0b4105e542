/* method_edmd.c — the `edmd` engine: event-driven hard spheres (3D) and hard disks (2D)
 * (lz/edmd.h), measured with lz/edmd_obs.h.
 *
 * A run builds the box from n and the packing, starts from a lattice (a random subset
 * of its sites, Maxwell velocities at kT = 1, zero momentum) or from a config file,
 * equilibrates elastically for `equilibrate` events per particle (the lattice melts;
 * restitution < 1 applies from the measurement on, so the cooling starts from an
 * equilibrium fluid at kT = 1 and t = 0), then measures `events` per particle or a
 * `time` in `blocks` blocks: the pressure from the collisional virial, the collision
 * rate and the identity between them, with the standard error of the block means; the
 * guards (overlaps, energy, collapse) end the run with a message. The speed is events
 * per CPU second of the measured event loop alone. Only what a scene asks for is built:
 * g(r), the mean-square displacement and the temperature history are observations
 * made between pieces of the run (which changes nothing in the trajectory) and cost
 * nothing when not asked for. Files: config.dat (the final state, readable back as
 * config) and config.png, gr.dat + gr.png, msd.dat + msd.png, temperature.dat +
 * temperature.png (restitution < 1).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_histogram.h>
#include <gsl/gsl_randist.h>

#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "config.h"
#include "edmd_scene.h"
#include "method.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"

enum { OBS_GR = 1, OBS_MSD = 2 };
#define DEFAULT_EVENTS 100.0  /* events per particle when neither events nor time */
#define PLOT_DISKS 20000.0    /* about this many circles at most in config.png */
#define PROGRESS_EVENTS 256   /* events between progress updates (on a terminal) */

static const lz_key keys[] = {
	LZ_EDMD_SYSTEM_KEYS,
	{.name = "events", .type = LZ_KEY_REAL, .def = "", .min = 0, .max = 1e9, .min_open = 1,
	 .unit = "per particle", .group = 1,
	 .help = "events per particle measured, in blocks of equal events (give events or "
	         "time; " "default 100)"},
	{.name = "time", .type = LZ_KEY_REAL, .def = "", .min = 0, .max = 1e9, .min_open = 1,
	 .unit = "τ", .group = 1,
	 .help = "simulated time measured, in blocks of equal duration (give events or time)"},
	{.name = "blocks", .type = LZ_KEY_INT, .def = "20", .min = 2, .max = 1e6,
	 .help = "blocks of the error bars (the standard error of the block means)"},
	{.name = "observe", .type = LZ_KEY_TEXT, .def = "pressure",
	 .help = "a comma list of gr, msd (pressure and the collision rate are always "
	         "measured, " "from counters; pressure or none alone: nothing more)"},
	{.name = "gr_range", .type = LZ_KEY_REAL, .def = "3", .min = 0, .max = 1e6,
	 .min_open = 1, .unit = "σ",
	 .help = "observe = gr: g(r) over [0, gr_range), at most L/2"},
	{.name = "gr_bins", .type = LZ_KEY_INT, .def = "150", .min = 1, .max = 1e6,
	 .help = "observe = gr: histogram bins"},
	{.name = "sample", .type = LZ_KEY_REAL, .def = "2", .min = 0, .max = 1e9, .min_open = 1,
	 .unit = "per particle",
	 .help = "events per particle between g(r) samples, msd rows and temperature rows"},
	{.name = "neighbours", .type = LZ_KEY_ENUM, .def = "auto", .choices = "auto|cells|list",
	 .help = "where a prediction looks for partners: the 3^dim cells around the particle, "
	         "or its list of the particles within the shell (rebuilt when it strays half "
	         "the shell's width beyond σ); auto: lists in 3D from packing 0.35 (0.28 "
	         "below 32768 particles), in 2D from 0.5, where they were measured faster "
	         "(lesson 05 §10)"},
	{.name = "shell", .type = LZ_KEY_REAL, .def = "", .min = 1, .max = 4, .min_open = 1,
	 .unit = "σ",
	 .help = "neighbours = list: the shell S of a list; unset: 1.3 to 1.5 (3D) or 1.8 (2D) "
	         "in a dense fluid, wider below (lz_edmd_list_shell)"},
	{.name = "queue", .type = LZ_KEY_ENUM, .def = "auto", .choices = "auto|heap|heap4|calendar",
	 .help = "what orders the events: the binary heap (the assignment), a 4-ary heap or "
	         "a calendar queue (both with lists only); auto: the calendar with lists, "
	         "the heap with cells"},
	{.name = "sort", .type = LZ_KEY_BOOL, .def = "no",
	 .help = "renumber the particles cell by cell at every re-base (near in space = "
	         "near in "
	         "memory; no gain measured once the loop prefetches, lesson 05 §9); not "
	         "with " "observe = msd"},
	{.name = "write_config", .type = LZ_KEY_BOOL, .def = "yes",
	 .help = "write config.dat (the final state, readable as config) and config.png"},
};

/* ---- the scene ---- */

/* The engine the scene asks for: neighbours (auto: lz_edmd_list_pays), shell, queue. */
static lz_edmd_params engine_of(const lz_scene *s, size_t n)
{
	static const int queues[] = {LZ_EDMD_QUEUE_AUTO, LZ_EDMD_HEAP, LZ_EDMD_HEAP4,
	                             LZ_EDMD_CALENDAR};
	int dim = (int)lz_scene_int(s, "dim"), k = lz_scene_enum(s, "neighbours");
	lz_edmd_params p = {0};
	p.neighbours = k == 1 ? LZ_EDMD_CELLS : k == 2 ? LZ_EDMD_LIST
	               : lz_edmd_list_pays(dim, n, lz_scene_real(s, "packing"));
	p.shell = lz_scene_has(s, "shell") ? lz_scene_real(s, "shell") : 0;
	p.queue = queues[lz_scene_enum(s, "queue")];
	return p;
}

/* The bits of observe, or -1 with lz_error naming the bad word. */
static int parse_observe(const char *text)
{
	char word[64];
	int bits = 0, n = 0;
	for (const char *c = text;; c++) {
		if (*c && *c != ',' && *c != ' ' && *c != '\t') {
			if (n < (int)sizeof word - 1)
				word[n++] = *c;
			continue;
		}
		word[n] = '\0';
		if (n > 0) {
			if (strcmp(word, "gr") == 0)
				bits |= OBS_GR;
			else if (strcmp(word, "msd") == 0)
				bits |= OBS_MSD;
			else if (strcmp(word, "pressure") != 0 && strcmp(word, "none") != 0)
				return lz_error(LZ_EINVAL, "observe: '%s' is not an observable; allowed: "
				                "a comma list of none, pressure, gr, msd", word), -1;
		}
		n = 0;
		if (!*c)
			return bits;
	}
}

static int scene_observe(const lz_scene *s)
{
	return parse_observe(lz_scene_text(s, "observe"));
}

/* ---- the system ---- */

/* The particles: the config file's rows, else n. */




/* events and time, observe and its keys, sort. */
static int check_keys(const lz_scene *s)
{
	if (lz_scene_has(s, "events") && lz_scene_has(s, "time"))
		return lz_scene_fail(s, "time", "give events or time, not both");
	int obs = scene_observe(s);
	if (obs < 0)
		return lz_scene_fail(s, "observe", "%s", lz_error_message());
	static const char *const gr_keys[] = {"gr_range", "gr_bins"};
	for (int k = 0; k < 2; k++)
		if (!(obs & OBS_GR) && lz_scene_given(s, gr_keys[k]))
			return lz_scene_fail(s, gr_keys[k], "%s is given but g(r) is not observed: "
			                     "add observe = gr", gr_keys[k]);
	if (!obs && lz_scene_real(s, "restitution") == 1 && lz_scene_given(s, "sample"))
		return lz_scene_fail(s, "sample", "sample is given but nothing is sampled: add "
		                     "observe = gr or msd, or restitution < 1 (temperature.dat)");
	if (lz_scene_given(s, "shell") && lz_scene_enum(s, "neighbours") == 1)
		return lz_scene_fail(s, "shell", "shell is given but neighbours = cells: a shell "
		                     "belongs to neighbours = list (or auto)");
	if ((obs & OBS_MSD) && lz_scene_given(s, "sort") && lz_scene_bool(s, "sort"))
		return lz_scene_fail(s, "sort", "sort = yes renumbers the particles, which the "
		                     "mean-square displacement cannot follow: say sort = no, or "
		                     "leave it out (no is the default)");
	return LZ_OK;
}

static int check(const lz_scene *s)
{
	int status = check_keys(s);
	if (status != LZ_OK)
		return status;
	lz_config c = {0};
	int dim = (int)lz_scene_int(s, "dim");
	if (lz_scene_has(s, "config") && lz_config_read(lz_scene_text(s, "config"), dim, &c))
		return lz_scene_fail(s, "config", "%s", lz_error_message());
	size_t n = 0;
	status = lz_edmd_scene_particles(s, &c, &n);
	lz_edmd_params engine = engine_of(s, n);
	lz_edmd *e = status == LZ_OK ? lz_edmd_scene_system(s, n, &engine) : NULL;
	if (status == LZ_OK && !e)
		status = LZ_EINVAL;
	if (status == LZ_OK && (scene_observe(s) & OBS_GR) && lz_scene_real(s, "gr_range") > e->L / 2)
		status = lz_scene_fail(s, "gr_range", "gr_range = %g is beyond half the box, L/2 = "
		                       "%.4g σ: allowed (0, %.4g]", lz_scene_real(s, "gr_range"),
		                       e->L / 2, e->L / 2);
	if (status == LZ_OK && c.n > 0) {
		lz_rng *rng = lz_rng_alloc(NULL, 1);
		status = rng ? lz_edmd_scene_place_config(s, e, &c, rng) : LZ_ENOMEM;
		lz_rng_free(rng);
	}
	lz_edmd_free(e);
	lz_config_free(&c);
	return status;
}

/* ---- the observations ---- */

typedef struct {
	const lz_scene *s;
	lz_edmd *e;
	int observe;             /* OBS_* */
	double T0;               /* kT at the start of the measurement */
	uint64_t sample;         /* events between samples */
	uint64_t track_every;    /* events between track updates */
	uint64_t base, seen;     /* events of the finished blocks; e->events at the last call */
	uint64_t next_sample, next_track;  /* the event counts of the next ones */
	double interval;         /* with g(r): time between samples (lz_edmd_plan) */
	double next_time;        /* with g(r): the time of the next sample */
	gsl_histogram *gr;       /* observe = gr */
	size_t gr_samples;
	lz_edmd_track *track;    /* observe = msd */
	lz_data *msd;            /* msd.dat */
	double *msd_t, *msd_x;   /* its rows, for the fit */
	size_t msd_rows, msd_cap;
	lz_data *temp;           /* temperature.dat (restitution < 1) */
	int quiet;
	int by_time;             /* the progress line counts simulated time, not events */
	lz_progress bar;
} watch;

/* A sample: a g(r) histogram (with_gr), a row of msd.dat and of temperature.dat. */
static int watch_sample(watch *w, double t, int with_gr)
{
	lz_edmd *e = w->e;
	if (w->gr && with_gr) {
		int status = lz_edmd_gr_add(e, lz_scene_real(w->s, "gr_range"), w->gr);
		if (status != LZ_OK)
			return status;
		w->gr_samples++;
	}
	if (w->msd) {
		double x = lz_edmd_track_msd(w->track), row[2] = {t, x};
		lz_data_row(w->msd, row);
		if (w->msd_rows == w->msd_cap) {
			size_t cap = w->msd_cap ? 2 * w->msd_cap : 256;
			double *a = realloc(w->msd_t, cap * sizeof *a);
			if (a)
				w->msd_t = a;
			double *b = a ? realloc(w->msd_x, cap * sizeof *b) : NULL;
			if (b)
				w->msd_x = b;
			if (!a || !b)
				return lz_error(LZ_ENOMEM, "no memory for %zu msd rows", cap);
			w->msd_cap = cap;
		}
		w->msd_t[w->msd_rows] = t;
		w->msd_x[w->msd_rows++] = x;
	}
	if (w->temp) {
		double row[2] = {t, lz_edmd_temperature(e)};
		lz_data_row(w->temp, row);
	}
	return LZ_OK;
}

/* The observer of lz_edmd_blocks_plan: the track follows every `track_every` events,
 * the samples are taken every `sample` events (with g(r): at fixed times about as far
 * apart, so that no sample sits on a collision), the progress line moves. */
static int watch_observe(const lz_edmd *e, void *arg)
{
	watch *w = arg;
	if (e->events < w->seen)  /* a new block began: its counters were reset */
		w->base += w->seen;
	w->seen = e->events;
	uint64_t done = w->base + e->events;
	if (w->track && done >= w->next_track) {
		w->next_track = done + w->track_every;
		lz_edmd_track_update(w->track, e);
	}
	int due = w->gr && w->interval > 0
	              ? lz_edmd_time(e) >= w->next_time - 1e-9 * w->interval
	              : done >= w->next_sample;
	if (due) {
		while (w->next_sample <= done)  /* on a fixed grid of `sample` events */
			w->next_sample += w->sample;
		while (w->interval > 0 && w->next_time <= lz_edmd_time(e) + 1e-9 * w->interval)
			w->next_time += w->interval;
		int status = watch_sample(w, lz_edmd_time(e), 1);
		if (status != LZ_OK)
			return status;
	}
	if (!w->quiet)
		lz_progress_update(&w->bar, w->by_time ? lz_edmd_time(e) : (double)done);
	return LZ_OK;
}

static void watch_free(watch *w)
{
	gsl_histogram_free(w->gr);
	lz_edmd_track_free(w->track);
	if (w->msd)
		lz_data_close(w->msd);
	if (w->temp)
		lz_data_close(w->temp);
	free(w->msd_t);
	free(w->msd_x);
}

/* Open a data file of two columns in the run directory. */
static lz_data *open_two(const lz_run *run, const char *file, const char *title,
                         const char *const names[2], const char *const units[2])
{
	char path[4200];
	if (lz_rundir_file(run->dir, file, path, sizeof path) != LZ_OK)
		return NULL;
	return lz_data_open(path, title, 2, names, units);
}

/* What the scene asks to watch: the histogram, the track and the data files. */
static int watch_begin(const lz_scene *s, lz_edmd *e, const lz_run *run, watch *w)
{
	static const char *const msd_names[] = {"t", "msd"}, *const msd_units[] = {"τ", "σ²"};
	static const char *const t_names[] = {"t", "kT"}, *const t_units[] = {"τ", "kT(0)"};
	double per = lz_scene_real(s, "sample") * (double)e->n;
	*w = (watch){.s = s, .e = e, .observe = scene_observe(s), .quiet = run->quiet};
	w->T0 = lz_edmd_temperature(e);
	w->sample = per < 1 ? 1 : (uint64_t)llround(per);
	w->next_sample = w->sample;
	/* no particle may fly L/2 between two updates of the track: an eighth of an event
	 * per particle is a fraction of a cell for all but the fastest */
	w->track_every = w->sample < e->n / 8 + 1 ? w->sample : e->n / 8 + 1;
	w->next_track = w->track_every;
	/* g(r) is sampled at fixed times (lz_edmd_plan says why), `sample` events per
	 * particle apart at the event rate of the equilibration */
	double rate = (double)e->events / (lz_edmd_time(e) - e->t_reset);
	w->interval = rate > 0 && isfinite(rate) ? (double)(w->track ? w->track_every : w->sample) / rate : 0;
	w->next_time = lz_edmd_time(e) + w->interval;
	char title[240];
	if (w->observe & OBS_GR) {
		w->gr = gsl_histogram_alloc((size_t)lz_scene_int(s, "gr_bins"));
		if (!w->gr)
			return lz_error(LZ_ENOMEM, "no memory for the g(r) histogram");
		gsl_histogram_set_ranges_uniform(w->gr, 0, lz_scene_real(s, "gr_range"));
	}
	if (w->observe & OBS_MSD) {
		if (!(w->track = lz_edmd_track_alloc(e)))
			return LZ_ENOMEM;
		snprintf(title, sizeof title, "mean-square displacement of %zu hard %s, η = %g, "
		         "every %g events per particle", e->n, e->dim == 3 ? "spheres" : "disks",
		         lz_scene_real(s, "packing"), lz_scene_real(s, "sample"));
		if (!(w->msd = open_two(run, "msd.dat", title, msd_names, msd_units)))
			return LZ_EIO;
	}
	if (e->restitution < 1) {
		snprintf(title, sizeof title, "granular temperature of %zu hard %s, η = %g, "
		         "restitution %g, kT(0) = %.6g", e->n, e->dim == 3 ? "spheres" : "disks",
		         lz_scene_real(s, "packing"), e->restitution, w->T0);
		if (!(w->temp = open_two(run, "temperature.dat", title, t_names, t_units)))
			return LZ_EIO;
	}
	return w->msd || w->temp ? watch_sample(w, lz_edmd_time(e), 0) : LZ_OK;  /* t = 0 */
}

/* ---- the run ---- */



/* The measurement: blocks of events or of time, watched when anything is asked for. */
static int measure(const lz_scene *s, lz_edmd *e, watch *w, lz_edmd_result *r)
{
	size_t blocks = (size_t)lz_scene_int(s, "blocks");
	lz_edmd_plan plan = {UINT64_MAX, INFINITY, 0, NULL, NULL, 0};
	double total;
	if (lz_scene_has(s, "time")) {
		plan.duration = lz_scene_real(s, "time") / (double)blocks;
		total = lz_scene_real(s, "time");
		w->by_time = 1;
	} else {
		double per = lz_scene_has(s, "events") ? lz_scene_real(s, "events") : DEFAULT_EVENTS;
		total = per * (double)e->n;
		plan.events = (uint64_t)fmax(1, llround(total / (double)blocks));
		total = (double)plan.events * (double)blocks;
	}
	if (w->gr || w->track || w->temp || !w->quiet) {
		plan.observe = watch_observe;
		plan.arg = w;
		plan.every = w->track ? w->track_every : w->sample;
		if (!w->quiet && plan.every > PROGRESS_EVENTS)
			plan.every = PROGRESS_EVENTS;
		if (w->gr)
			plan.interval = w->interval;
	}
	if (!w->quiet)
		lz_progress_begin(&w->bar, "edmd", total);
	int status = lz_edmd_blocks_plan(e, blocks, &plan, r);
	if (!w->quiet)
		lz_progress_end(&w->bar);
	return status;
}

/* ---- the summary ---- */

/* The contact value g(σ) that gives Z: Z = 1 + 2^(dim-1) η g(σ). */
static double contact(int dim, double packing, double Z)
{
	return (Z - 1) / ((dim == 3 ? 4 : 2) * packing);
}

/* Z_ref for a periodic elastic fluid without gravity; NaN otherwise. */
static double z_ref(const lz_edmd *e, double packing, const char **source)
{
	if (e->wall[0] || e->g > 0 || e->restitution < 1) {
		*source = "none (walls, gravity or restitution < 1: no bulk equilibrium fluid)";
		return NAN;
	}
	return lz_edmd_z_reference(e->dim, packing, source);
}

/* g(σ) extrapolated from the first 5 bins at and beyond r = 1: a line through ln g(r),
 * which follows the steep, convex fall of the contact peak better than g itself. */
static double gr_contact(const lz_edmd *e, const watch *w)
{
	double r[5], g[5];
	size_t k = 0;
	for (size_t b = 0; b < w->gr->n && k < 5; b++) {
		double lo, hi;
		gsl_histogram_get_range(w->gr, b, &lo, &hi);
		if (lo < 1)
			continue;
		double x = lz_edmd_gr_value(e, w->gr, b, w->gr_samples);
		if (!(x > 0))
			return NAN;
		r[k] = 0.5 * (lo + hi) - 1;
		g[k++] = log(x);
	}
	double c0, c1, cov00, cov01, cov11, sumsq;
	if (k < 2 || gsl_fit_linear(r, 1, g, 1, k, &c0, &c1, &cov00, &cov01, &cov11, &sumsq))
		return NAN;
	return exp(c0);
}

/* D from a line through the second half of the msd rows: msd = a + 2 dim D t. */
static double diffusion(const lz_edmd *e, const watch *w)
{
	size_t from = w->msd_rows / 2, k = w->msd_rows - from;
	double c0, c1, cov00, cov01, cov11, sumsq;
	if (k < 3 || gsl_fit_linear(w->msd_t + from, 1, w->msd_x + from, 1, k, &c0, &c1, &cov00,
	                            &cov01, &cov11, &sumsq))
		return NAN;
	return c1 / (2 * e->dim);
}

/* Haff's time t0 of T(t) = T0 / (1 + t/t0)²: dT/dt = -(1 - e²) Γ T / dim with Γ from the
 * identity at Z_ref, so t0 = √π / ((1 - e²)(Z_ref - 1)√T0). */
static double haff_t0(const lz_edmd *e, double packing, double T0)
{
	if (e->wall[0] || e->g > 0)
		return NAN;
	double Z = lz_edmd_z_reference(e->dim, packing, NULL);
	double q = 1 - e->restitution * e->restitution;
	return sqrt(M_PI) / (q * (Z - 1) * sqrt(T0));
}

static double mean_height(const lz_edmd *e)
{
	double sum = 0;
	for (size_t i = 0; i < e->n; i++)
		sum += e->p[i].r[0];
	return sum / (double)e->n;
}

static void summarise(const lz_scene *s, const lz_edmd *e, const watch *w,
                      const lz_edmd_result *r, double setup_s, lz_json *j)
{
	double eta = lz_scene_real(s, "packing"), n = (double)e->n;
	const char *source = "";
	double Zref = z_ref(e, eta, &source);
	double bytes = lz_edmd_bytes(e);
	double watch_bytes = (w->track ? 6 * sizeof(double) : 0) + (w->gr ? 3 * sizeof(double) : 0);
	lz_json_int(j, "n_run", (long long)e->n);
	lz_json_num(j, "box_side", e->L);
	lz_json_str(j, "neighbours_run", e->lists ? "list" : "cells");
	if (e->lists)
		lz_json_num(j, "shell_run", e->lists->shell);
	lz_json_str(j, "queue_run", e->cal ? "calendar" : e->heap->arity == 4 ? "heap4" : "heap");
	lz_json_int(j, "cells_per_side", e->m[0]);
	lz_json_num(j, "cells_per_particle", (double)e->ncells / n);
	lz_json_err(j, "Z", r->Z, r->Z_err);
	lz_json_num(j, "Z_ref", Zref);
	lz_json_str(j, "Z_ref_source", source);
	lz_json_err(j, "Z_gamma", r->Z_gamma, r->Z_gamma_err);
	lz_json_err(j, "collision_rate", r->gamma, r->gamma_err);
	lz_json_num(j, "mean_free_time", r->free_time);
	lz_json_err(j, "contact_value", contact(e->dim, eta, r->Z), r->Z_err /
	            ((e->dim == 3 ? 4 : 2) * eta));
	lz_json_num(j, "contact_value_ref", contact(e->dim, eta, Zref));
	lz_json_err(j, "temperature", r->T, r->T_err);
	lz_json_int(j, "blocks_run", (long long)r->blocks);
	lz_json_num(j, "time_run", r->time);
	lz_json_int(j, "events_run", (long long)r->events);
	lz_json_int(j, "collisions", (long long)r->collisions);
	lz_json_int(j, "cell_crossings", (long long)r->crossings);
	lz_json_int(j, "list_rebuilds", (long long)r->rebuilds);
	lz_json_int(j, "wall_bounces", (long long)r->bounces);
	lz_json_int(j, "stale_events", (long long)r->stale);
	lz_json_num(j, "energy_rel_drift", r->energy_rel_drift);
	lz_json_num(j, "momentum_abs_drift", r->momentum_abs_drift);
	lz_json_num(j, "max_overlap", r->max_overlap);
	if (w->gr) {
		lz_json_int(j, "gr_samples", (long long)w->gr_samples);
		lz_json_num(j, "gr_contact", gr_contact(e, w));
	}
	if (w->track) {
		lz_json_num(j, "msd_final", lz_edmd_track_msd(w->track));
		lz_json_num(j, "diffusion", diffusion(e, w));
	}
	if (e->restitution < 1) {
		lz_json_num(j, "haff_t0", haff_t0(e, eta, w->T0));
		lz_json_num(j, "temperature_final", lz_edmd_temperature(e));
	}
	if (e->g > 0)
		lz_json_num(j, "height_mean", mean_height(e));
	lz_json_num(j, "bytes_per_particle", bytes);
	lz_json_num(j, "state_bytes_per_particle", bytes + watch_bytes);
	lz_json_num(j, "setup_s", setup_s);
	lz_json_num(j, "cpu_s", r->cpu_s);
	lz_json_num(j, "events_per_s", r->cpu_s > 0 ? (double)r->events / r->cpu_s : NAN);
	lz_json_num(j, "collisions_per_s", r->cpu_s > 0 ? (double)r->collisions / r->cpu_s : NAN);
}

/* ---- files ---- */

/* config.dat (lz_config_write_edmd) and its picture. */
static int write_config(const lz_scene *s, const lz_edmd *e, const lz_run *run)
{
	char about[128];
	snprintf(about, sizeof about, "packing %g, walls %s", lz_scene_real(s, "packing"),
	         lz_scene_text(s, "walls"));
	int status = lz_config_write_edmd(run, e, about);
	if (status != LZ_OK)
		return status;
	/* the picture: the whole box, or a corner with about PLOT_DISKS circles */
	double shown = e->dim == 2 ? (double)e->n : (double)e->n / e->L;
	double window = shown > PLOT_DISKS ? e->L * sqrt(PLOT_DISKS / shown) : e->L;
	char title[256];
	snprintf(title, sizeof title, "%zu hard %s, η = %g, restitution %g%s, t = %.4g τ%s",
	         e->n, e->dim == 3 ? "spheres" : "disks", lz_scene_real(s, "packing"),
	         e->restitution, e->g > 0 ? ", gravity along -x" : "", lz_edmd_time(e),
	         window < e->L ? " (a corner)" : "");
	return lz_run_plot_disks(run, "edmd", e->dim, e->L, window, e->g > 0, title);
}

/* gr.dat and gr.png, with the contact value of the reference EoS. */
static int write_gr(const lz_scene *s, const lz_edmd *e, const watch *w, const lz_run *run)
{
	static const char *const names[] = {"r", "g"}, *const units[] = {"σ", NULL};
	double eta = lz_scene_real(s, "packing");
	const char *source;
	double gref = contact(e->dim, eta, z_ref(e, eta, &source));
	char title[240];
	snprintf(title, sizeof title, "pair distribution g(r) of %zu hard %s, η = %g, %zu "
	         "samples; bin centres; reference contact value %.5g (%s)", e->n,
	         e->dim == 3 ? "spheres" : "disks", eta, w->gr_samples, gref, source);
	lz_data *d = open_two(run, "gr.dat", title, names, units);
	if (!d)
		return LZ_EIO;
	for (size_t k = 0; k < w->gr->n; k++) {
		double lo, hi;
		gsl_histogram_get_range(w->gr, k, &lo, &hi);
		double row[2] = {0.5 * (lo + hi), lz_edmd_gr_value(e, w->gr, k, w->gr_samples)};
		lz_data_row(d, row);
	}
	int status = lz_data_close(d);
	if (status != LZ_OK)
		return status;
	FILE *f = lz_run_script(run, "gr", "edmd", "the pair distribution", 900, 560);
	if (!f)
		return LZ_EIO;
	fprintf(f, "set grid\nset key top right\nset xlabel 'r [σ]'\nset ylabel 'g(r)'\n"
	        "set title \"g(r) of %zu hard %s at η = %g (%zu samples)\" noenhanced\n"
	        "set xrange [0:%g]\n", e->n, e->dim == 3 ? "spheres" : "disks", eta,
	        w->gr_samples, lz_scene_real(s, "gr_range"));
	if (isfinite(gref))
		fprintf(f, "set arrow from 1, %.6g to 1.4, %.6g nohead dt 2 lw 2 lc rgb '#c03030'\n"
		        "set label 'contact value, reference EoS: %.4g' at 1.45, %.6g tc rgb "
		        "'#c03030'\n", gref, gref, gref, gref);
	fprintf(f, "plot 'gr.dat' u 1:2 w l lw 2 lc rgb '#3060c0' t 'measured', 1 w l dt 3 "
	        "lc rgb 'gray' t 'ideal gas'\n");
	return lz_run_plot(run, f, "gr");
}

/* msd.png: log-log, with the ballistic dim·kT·t² and the diffusive 2·dim·D·t lines. */
static int write_msd_plot(const lz_scene *s, const lz_edmd *e, watch *w, const lz_run *run)
{
	int status = lz_data_close(w->msd);
	w->msd = NULL;
	if (status != LZ_OK)
		return status;
	double D = diffusion(e, w);
	FILE *f = lz_run_script(run, "msd", "edmd", "the mean-square displacement", 900, 560);
	if (!f)
		return LZ_EIO;
	fprintf(f, "set grid\nset logscale xy\nset key top left\nset xlabel 't [τ]'\n"
	        "set ylabel 'mean-square displacement [σ²]'\nset title \"%zu hard %s, η = %g\" "
	        "noenhanced\nplot 'msd.dat' u 1:2 w lp pt 7 ps 0.5 lw 2 t 'measured', "
	        "%d * %.6g * x**2 dt 2 t 'ballistic, dim·kT·t²'", e->n,
	        e->dim == 3 ? "spheres" : "disks", lz_scene_real(s, "packing"), e->dim, w->T0);
	if (isfinite(D) && D > 0)
		fprintf(f, ", %g * x dt 3 t 'diffusive, 2·dim·D·t, D = %.4g'", 2 * e->dim * D, D);
	fputc('\n', f);
	return lz_run_plot(run, f, "msd");
}

/* temperature.png: Haff's law T0 / (1 + t/t0)² against the measured cooling. */
static int write_temperature_plot(const lz_scene *s, const lz_edmd *e, watch *w,
                                  const lz_run *run)
{
	int status = lz_data_close(w->temp);
	w->temp = NULL;
	if (status != LZ_OK)
		return status;
	double t0 = haff_t0(e, lz_scene_real(s, "packing"), w->T0);
	FILE *f = lz_run_script(run, "temperature", "edmd", "the granular temperature", 900,
	                        560);
	if (!f)
		return LZ_EIO;
	fprintf(f, "set grid\nset logscale xy\nset key bottom left\nset xlabel 't [τ]'\n"
	        "set ylabel 'kT / kT(0)'\nset title \"cooling of %zu hard %s, η = %g, "
	        "restitution %g\" noenhanced\nplot 'temperature.dat' u 1:($2/%.10g) w l lw 2 "
	        "t 'measured'", e->n, e->dim == 3 ? "spheres" : "disks",
	        lz_scene_real(s, "packing"), e->restitution, w->T0);
	if (isfinite(t0))
		fprintf(f, ", 1 / (1 + x / %.6g)**2 dt 2 lw 2 t \"Haff's law, t0 = %.4g τ\"", t0, t0);
	fputc('\n', f);
	return lz_run_plot(run, f, "temperature");
}

static int write_files(const lz_scene *s, const lz_edmd *e, watch *w, const lz_run *run)
{
	int status = LZ_OK;
	if (lz_scene_bool(s, "write_config"))
		status = write_config(s, e, run);
	if (status == LZ_OK && w->gr)
		status = write_gr(s, e, w, run);
	if (status == LZ_OK && w->msd)
		status = write_msd_plot(s, e, w, run);
	if (status == LZ_OK && w->temp)
		status = write_temperature_plot(s, e, w, run);
	return status;
}

static int run(const lz_scene *s, lz_run *run)
{
	lz_rng *rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	if (!rng)
		return LZ_ENOMEM;
	double t0 = lz_cpu_now();
	lz_config c = {0};
	size_t n = 0;
	int status = LZ_OK;
	if (lz_scene_has(s, "config"))
		status = lz_config_read(lz_scene_text(s, "config"), (int)lz_scene_int(s, "dim"), &c);
	if (status == LZ_OK)
		status = lz_edmd_scene_particles(s, &c, &n);
	lz_config_free(&c);
	lz_edmd_params engine = engine_of(s, n);
	lz_edmd *e = status == LZ_OK ? lz_edmd_scene_system(s, n, &engine) : NULL;
	if (status == LZ_OK && !e)
		status = LZ_EINVAL;
	watch w = {0};
	lz_edmd_result r = {0};
	if (status == LZ_OK) {
		e->sort_every = lz_scene_bool(s, "sort") ? 1 : 0;
		status = lz_edmd_scene_start(s, e, rng);
	}
	double setup_s = lz_cpu_now() - t0;
	if (status == LZ_OK) {
		lz_edmd_scene_warn_phase(e, lz_scene_real(s, "packing"), run->quiet);
		status = lz_edmd_scene_equilibrate(s, e, run->quiet);
	}
	if (status == LZ_OK) {
		if (scene_observe(s) & OBS_MSD)
			e->sort_every = 0;  /* the track follows particle numbers */
		status = watch_begin(s, e, run, &w);
	}
	if (status == LZ_OK)
		status = measure(s, e, &w, &r);
	if (status == LZ_OK) {
		lz_edmd_sync(e);
		summarise(s, e, &w, &r, setup_s, run->summary);
		status = write_files(s, e, &w, run);
	}
	watch_free(&w);
	lz_edmd_free(e);
	lz_rng_free(rng);
	return status;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "Z", .ref = "Z_ref", .source = "Z_ref_source"},
	{.key = "Z_gamma", .ref = "Z_ref"}, {.key = "collision_rate"},
	{.key = "contact_value", .ref = "contact_value_ref"},
	{.key = "gr_contact", .ref = "contact_value_ref"}, {.key = "temperature"},
	{.key = "temperature_final"}, {.key = "haff_t0"}, {.key = "diffusion"},
	{.key = "height_mean"}, {.key = "max_overlap"}, {NULL},
};
static const lz_speed speed[] = {{"events_per_s", "events/s (CPU)"}, {NULL}};

const lz_method lz_method_edmd = {
	LZ_METHOD_KEYS("edmd", keys),
	.help = "event-driven hard spheres (3D) and disks (2D): one event per particle in a "
	        "heap, cells, exact collisions; pressure, collision rate and their identity "
	        "with error bars; walls, gravity, inelastic cooling, g(r), msd",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
