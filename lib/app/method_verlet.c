/* method_verlet.c — the `verlet` engine: time-stepped molecular dynamics with the
 * integrators of lz/integrate.h on harmonic oscillators or a Lennard-Jones fluid.
 *
 * A run steps the state, measures the energy after every step (its worst error and,
 * for the harmonic oscillator, the error of the shadow energy the scheme conserves
 * exactly), writes every `sample`-th step to energy.dat, and summarises: drift (a
 * gsl_fit line), spread, cost (force evaluations, steps per second) and for the
 * fluid the temperature and pressure as block averages.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/integrate.h"
#include "method.h"
#include "lz/potential.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/vec.h"

enum { HARMONIC, LJ };
enum { DEFAULT_ROWS = 1000, NBLOCKS = 10 };
/* A fluid that was not equilibrated (equilibrate = 0) is still melting from its
 * lattice early in the run: its averages skip this fraction of the run. */
#define MELTING 0.2

static const lz_key keys[] = {
	{.name = "potential", .type = LZ_KEY_ENUM, .def = "harmonic", .choices = "harmonic|lj",
	 .help = "force law: independent harmonic oscillators, or Lennard-Jones (cut and "
	         "shifted, " "periodic box, all pairs)"},
	{.name = "integrator", .type = LZ_KEY_ENUM, .def = "velocity-verlet",
	 .choices = "euler|symplectic-euler|verlet|velocity-verlet|leapfrog",
	 .help = "time-stepping scheme"},
	{.name = "dt", .type = LZ_KEY_REAL, .min = 0, .max = 10, .min_open = 1, .unit = "τ",
	 .help = "time step"},
	{.name = "steps", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e12,
	 .group = 1, .help = "number of steps (give steps or time, not both)"},
	{.name = "time", .type = LZ_KEY_REAL, .def = "", .min = 0, .max = 1e12, .min_open = 1,
	 .unit = "τ",
	 .group = 1,
	 .help = "duration, rounded to whole steps (give steps or time, not both)"},
	{.name = "omega", .type = LZ_KEY_REAL, .def = "1", .min = 0, .max = 1e6, .min_open = 1,
	 .unit = "1/τ",
	 .help = "angular frequency ω of the oscillators (harmonic); stable for ω·dt < 2"},
	{.name = "x0", .type = LZ_KEY_REAL, .def = "1", .min = -1e6, .max = 1e6, .unit = "σ",
	 .help = "initial position of every coordinate (harmonic)"},
	{.name = "v0", .type = LZ_KEY_REAL, .def = "0", .min = -1e6, .max = 1e6, .unit = "σ/τ",
	 .help = "initial velocity of every coordinate (harmonic)"},
	{.name = "n", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e8,
	 .help = "particles; harmonic: default 1; lj: 4m³ in 3D (default 108), 2m² in 2D "
	         "(default 200)"},
	{.name = "dim", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 3,
	 .help = "dimensions; harmonic 1..3 (default 1), lj 2..3 (default 3)"},
	{.name = "density", .type = LZ_KEY_REAL, .def = "0.8", .min = 0, .max = 3,
	 .min_open = 1, .unit = "σ⁻ᵈ", .help = "number density ρ (lj)"},
	{.name = "temperature", .type = LZ_KEY_REAL, .def = "1", .max = 100, .unit = "ε/k_B",
	 .help = "temperature of the Maxwell velocities and of the equilibration (lj)"},
	{.name = "equilibrate", .type = LZ_KEY_INT, .def = "0", .max = 1e9,
	 .help = "lj: steps of velocity Verlet with the velocities rescaled to "
	         "`temperature` before "
	         "the measured NVE run (a lattice start melts and cools by about half "
	         "otherwise)"},
	{.name = "rc", .type = LZ_KEY_REAL, .def = "2.5", .min = 0, .max = 100, .min_open = 1,
	 .unit = "σ", .help = "cutoff (lj); at most L/2"},
	{.name = "precision", .type = LZ_KEY_ENUM, .def = "double", .choices = "double|float",
	 .help = "float: round the state (and the LJ forces) to single precision after "
	         "every step"},
	{.name = "sample", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e12,
	 .help = "write an energy row every k steps (default: about 1000 rows)"},
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto",
	 .help = "random seed of the Maxwell velocities (lj)"},
};

/* ---- the scene: defaults that depend on the potential, and cross-key checks ---- */

static int scene_dim(const lz_scene *s)
{
	if (lz_scene_has(s, "dim"))
		return (int)lz_scene_int(s, "dim");
	return lz_scene_enum(s, "potential") == LJ ? 3 : 1;
}

static size_t particles(const lz_scene *s)
{
	if (lz_scene_has(s, "n"))
		return (size_t)lz_scene_int(s, "n");
	if (lz_scene_enum(s, "potential") == HARMONIC)
		return 1;
	return scene_dim(s) == 3 ? 108 : 200;
}

static unsigned long long scene_steps(const lz_scene *s)
{
	if (lz_scene_has(s, "steps"))
		return (unsigned long long)lz_scene_int(s, "steps");
	return (unsigned long long)llround(lz_scene_real(s, "time") / lz_scene_real(s, "dt"));
}

static int check_lj(const lz_scene *s)
{
	int dim = scene_dim(s);
	if (dim < 2)
		return lz_scene_fail(s, "dim", "dim = %d: the Lennard-Jones fluid needs dim 2 or 3",
		                     dim);
	if (lz_lattice_check(particles(s), dim) != LZ_OK)
		return lz_scene_fail(s, "n", "%s", lz_error_message());
	lz_lj p;
	if (lz_lj_init(&p, particles(s), dim, lz_scene_real(s, "density"),
	               lz_scene_real(s, "rc")) != LZ_OK)
		return lz_scene_fail(s, "rc", "%s", lz_error_message());
	return LZ_OK;
}

static int check(const lz_scene *s)
{
	int has_steps = lz_scene_has(s, "steps"), has_time = lz_scene_has(s, "time");
	if (has_steps && has_time)
		return lz_scene_fail(s, "time", "give steps or time, not both");
	if (!has_steps && !has_time)
		return lz_scene_fail(s, "dt", "say how long to run: steps = N or time = T");
	if (has_time && scene_steps(s) < 1)
		return lz_scene_fail(s, "time", "time = %g is less than one step dt = %g",
		                     lz_scene_real(s, "time"), lz_scene_real(s, "dt"));
	if (lz_scene_enum(s, "potential") == LJ)
		return check_lj(s);
	if (lz_scene_int(s, "equilibrate") > 0)
		return lz_scene_fail(s, "equilibrate", "equilibrate = %lld: only the Lennard-Jones "
		                     "fluid is equilibrated (the oscillators start where x0, v0 say)",
		                     lz_scene_int(s, "equilibrate"));
	if (lz_scene_real(s, "x0") == 0.0 && lz_scene_real(s, "v0") == 0.0)
		return lz_scene_fail(s, "x0", "x0 = v0 = 0: the oscillator would rest at the origin "
		                     "and every relative energy error would be 0/0");
	return LZ_OK;
}

/* ---- the state ---- */

typedef struct {
	int potential;
	lz_integrator integ;
	int single;               /* precision = float */
	int equilibrated;         /* the fluid was melted before the run */
	double dt;
	unsigned long long steps, sample;
	lz_harmonic harmonic;
	lz_lj lj;
	lz_md *md;
	/* The sampled rows kept for the fits and block averages (steps/sample + 1). */
	size_t nrows, cap;
	double *t, *e_rel, *temp, *press;
	/* Measured every step. */
	double e0, escale, h0, hscale, err_max, shadow_err_max;
} sim;

static int has_shadow(const sim *m)
{
	return m->potential == HARMONIC && m->integ != LZ_EULER;
}

static int init_harmonic(sim *m, const lz_scene *s)
{
	m->harmonic.omega = lz_scene_real(s, "omega");
	m->md = lz_md_alloc(particles(s), scene_dim(s), lz_harmonic_force, &m->harmonic);
	if (!m->md)
		return LZ_ENOMEM;
	size_t len = m->md->n * (size_t)m->md->dim;
	double x0 = lz_scene_real(s, "x0"), v0 = lz_scene_real(s, "v0");
	for (size_t i = 0; i < len; i++) {
		m->md->r[i] = x0;
		m->md->v[i] = v0;
	}
	return LZ_OK;
}

static int init_lj(sim *m, const lz_scene *s)
{
	size_t n = particles(s);
	int dim = scene_dim(s);
	int status = lz_lj_init(&m->lj, n, dim, lz_scene_real(s, "density"),
	                        lz_scene_real(s, "rc"));
	if (status != LZ_OK)
		return status;
	m->lj.single = m->single;
	m->md = lz_md_alloc(n, dim, lz_lj_force, &m->lj);
	lz_rng *rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	status = !m->md || !rng ? LZ_ENOMEM : lz_lattice_start(m->md->r, n, dim, m->lj.box);
	if (status == LZ_OK)
		lz_maxwell_velocities(m->md->v, n, dim, lz_scene_real(s, "temperature"), rng);
	lz_rng_free(rng);
	return status;
}

/* Melt the lattice at temperature T: velocity Verlet with the velocities rescaled
 * to T after every step (an isokinetic thermostat). The measured run then starts
 * afresh from the equilibrated positions and velocities, at t = 0 and no cost. */
static int equilibrate(lz_md *s, double dt, unsigned long long steps, double T)
{
	size_t len = s->n * (size_t)s->dim;
	double dof = (double)s->dim * (double)(s->n > 1 ? s->n - 1 : 1);
	int status = lz_md_start(s, LZ_VELOCITY_VERLET, dt);
	for (unsigned long long i = 0; i < steps && status == LZ_OK; i++) {
		status = lz_md_step(s, LZ_VELOCITY_VERLET, dt);
		double now = 2.0 * lz_md_kinetic(s, LZ_VELOCITY_VERLET) / dof;
		if (status == LZ_OK && now > 0.0)
			for (size_t k = 0; k < len; k++)
				s->v[k] *= sqrt(T / now);
	}
	s->t = 0.0;
	s->force_evals = 0;
	return status;
}

static int sim_init(sim *m, const lz_scene *s)
{
	m->potential = lz_scene_enum(s, "potential");
	if (lz_integrator_parse(lz_scene_text(s, "integrator"), &m->integ) != LZ_OK)
		return LZ_EINVAL;
	m->single = lz_scene_enum(s, "precision") == 1;
	m->dt = lz_scene_real(s, "dt");
	m->steps = scene_steps(s);
	m->sample = lz_scene_has(s, "sample") ? (unsigned long long)lz_scene_int(s, "sample")
	                                      : (m->steps + DEFAULT_ROWS - 1) / DEFAULT_ROWS;
	m->cap = (size_t)(m->steps / m->sample) + 1;
	m->t = malloc(4 * m->cap * sizeof(double));
	if (!m->t)
		return lz_error(LZ_ENOMEM, "no memory for %zu energy samples", m->cap);
	m->e_rel = m->t + m->cap;
	m->temp = m->e_rel + m->cap;
	m->press = m->temp + m->cap;
	int status = m->potential == LJ ? init_lj(m, s) : init_harmonic(m, s);
	m->equilibrated = m->potential == LJ && lz_scene_int(s, "equilibrate") > 0;
	if (status == LZ_OK && m->equilibrated)
		status = equilibrate(m->md, m->dt, (unsigned long long)lz_scene_int(s, "equilibrate"),
		                     lz_scene_real(s, "temperature"));
	if (status == LZ_OK)
		status = lz_md_start(m->md, m->integ, m->dt);
	if (status == LZ_OK && m->single)
		lz_md_round_float(m->md);
	return status;
}

static void sim_free(sim *m)
{
	lz_md_free(m->md);
	free(m->t);
}

/* ---- observables ---- */

/* The quantity the scheme conserves exactly on the harmonic oscillator
 * (datasets/reference/harmonic.csv), with v and r taken at the same time: Verlet's v lags one step and
 * pairs with r_prev; leapfrog's kinetic energy is synchronised by lz_md_kinetic. */
static double shadow_energy(const sim *m)
{
	const lz_md *s = m->md;
	size_t len = s->n * (size_t)s->dim;
	const double *x = m->integ == LZ_VERLET && s->v_lags ? s->r_prev : s->r;
	double w2 = m->harmonic.omega * m->harmonic.omega, big_omega2 = w2 * m->dt * m->dt;
	double k = lz_md_kinetic(s, m->integ), x2 = lz_norm2(x, len);
	if (m->integ == LZ_SYMPLECTIC_EULER)
		return k + 0.5 * w2 * x2 - 0.5 * m->dt * w2 * lz_dot(x, s->v, len);
	return k + 0.5 * w2 * x2 * (1.0 - 0.25 * big_omega2);
}

/* Kinetic temperature with the momentum fixed: dim (n - 1) degrees of freedom. */
static double temperature(const sim *m)
{
	const lz_md *s = m->md;
	double dof = (double)s->dim * (double)(s->n > 1 ? s->n - 1 : 1);
	return 2.0 * lz_md_kinetic(s, m->integ) / dof;
}

/* Virial pressure P = ρ T + W / (dim V), W = Σ_pairs r·F of the last evaluation
 * (for Verlet one step ahead of T: it does not matter for an average). */
static double pressure(const sim *m, double temp)
{
	const lz_md *s = m->md;
	double volume = pow(m->lj.box, s->dim);
	return ((double)s->n * temp + m->lj.virial / s->dim) / volume;
}

/* The energy e (at time `when`) and the shadow energy after a step: track the worst
 * errors, and keep and write every sample-th step. */
static void measure(sim *m, unsigned long long step, double e, double when, lz_data *data)
{
	m->err_max = fmax(m->err_max, fabs(e - m->e0) / m->escale);
	double h = has_shadow(m) ? shadow_energy(m) : 0.0;
	m->shadow_err_max = fmax(m->shadow_err_max, fabs(h - m->h0) / m->hscale);
	if (step % m->sample != 0 || m->nrows == m->cap)
		return;
	double k = lz_md_kinetic(m->md, m->integ), row[7] = {when, e, k, e - k};
	int ncol = 4;
	if (has_shadow(m))
		row[ncol++] = h;
	m->t[m->nrows] = when;
	m->e_rel[m->nrows] = (e - m->e0) / m->escale;
	if (m->potential == LJ) {
		double temp = temperature(m), p = pressure(m, temp);
		m->temp[m->nrows] = temp;
		m->press[m->nrows] = p;
		row[ncol++] = temp;
		row[ncol++] = p;
	}
	m->nrows++;
	lz_data_row(data, row);
}

/* ---- files ---- */

static lz_data *open_data(const sim *m, const lz_run *run)
{
	static const char *const names[] = {"t", "E", "K", "U", "H_shadow", "T", "P"};
	static const char *const units[] = {"τ", "ε", "ε", "ε", "ε", "ε/k_B", "ε/σ^d"};
	const char *n[7], *u[7];
	int ncol = 0;
	for (int c = 0; c < 7; c++) {
		if ((c == 4 && !has_shadow(m)) || (c >= 5 && m->potential != LJ))
			continue;
		n[ncol] = names[c];
		u[ncol++] = units[c];
	}
	char path[4200];
	if (lz_rundir_file(run->dir, "energy.dat", path, sizeof path) != LZ_OK)
		return NULL;
	char title[256];
	snprintf(title, sizeof title, "energy of %s on %s, dt = %g, every %llu steps%s",
	         lz_integrator_name(m->integ),
	         m->potential == LJ ? "a Lennard-Jones fluid" : "harmonic oscillators", m->dt,
	         m->sample, has_shadow(m) ? "; H_shadow is what the scheme conserves exactly" : "");
	return lz_data_open(path, title, ncol, n, u);
}

/* energy.gp: the relative energy error against time, and the shadow energy's. */
static int write_plot(const sim *m, const lz_run *run)
{
	FILE *f = lz_run_script(run, "energy", "verlet", "the relative energy error of the run",
	                        900, 560);
	if (!f)
		return LZ_EIO;
	fprintf(f, "set key below horizontal\nset grid\n"
	        "set title \"%s, dt = %g τ\"\nset xlabel 'time t [τ]'\n"
	        "set ylabel 'relative error (X - X_0)/|X_0|'\nset format y '%%.1e'\n",
	        lz_integrator_name(m->integ), m->dt);
	fprintf(f, "plot 'energy.dat' u 1:(($2 - %.17g)/%.17g) w l lw 2 t 'energy E'",
	        m->e0, m->escale);
	if (has_shadow(m))
		fprintf(f, ", '' u 1:(($5 - %.17g)/%.17g) w l lw 2 t 'shadow energy (conserved)'",
		        m->h0, m->hscale);
	fprintf(f, "\n");
	return lz_run_plot(run, f, "energy");
}

/* ---- summary ---- */

/* Mean and error of x[from..n) from NBLOCKS block means. */
static void block_average(const double *x, size_t from, size_t n, double *mean, double *err)
{
	double means[NBLOCKS];
	size_t len = (n - from) / NBLOCKS;
	if (len == 0) {
		*mean = n > from ? gsl_stats_mean(x + from, 1, n - from) : NAN;
		*err = NAN;
		return;
	}
	for (int b = 0; b < NBLOCKS; b++)
		means[b] = gsl_stats_mean(x + from + b * len, 1, len);
	*mean = gsl_stats_mean(means, 1, NBLOCKS);
	*err = gsl_stats_sd(means, 1, NBLOCKS) / sqrt(NBLOCKS);
}

static void summarise(const sim *m, lz_json *j, double wall)
{
	const lz_md *s = m->md;
	lz_json_num(j, "energy_rel_err_max", m->err_max);
	double c0 = 0, c1 = NAN, cov00, cov01, cov11 = NAN, sumsq;
	if (m->nrows >= 3)
		gsl_fit_linear(m->t, 1, m->e_rel, 1, m->nrows, &c0, &c1, &cov00, &cov01, &cov11,
		               &sumsq);
	lz_json_err(j, "energy_drift_per_time", c1, sqrt(cov11));
	lz_json_num(j, "energy_rms_rel", m->nrows >= 2 ? gsl_stats_sd(m->e_rel, 1, m->nrows) : NAN);
	if (has_shadow(m))
		lz_json_num(j, "shadow_energy_rel_err", m->shadow_err_max);
	if (m->potential == LJ) {
		size_t from = m->equilibrated ? 0 : (size_t)(MELTING * (double)m->nrows);
		double mean, err;
		lz_json_num(j, "averages_from_time", from < m->nrows ? m->t[from] : NAN);
		block_average(m->temp, from, m->nrows, &mean, &err);
		lz_json_err(j, "temperature_mean", mean, err);
		block_average(m->press, from, m->nrows, &mean, &err);
		lz_json_err(j, "pressure_mean", mean, err);
	}
	/* The parameters as resolved: the scene writes n, dim and steps as given, and
	 * null for a default that depends on other keys. */
	lz_json_int(j, "particles", (long long)s->n);
	lz_json_int(j, "dimensions", s->dim);
	lz_json_int(j, "steps_run", (long long)m->steps);
	lz_json_int(j, "force_evals", (long long)s->force_evals);
	lz_json_num(j, "steps_per_s", (double)m->steps / wall);
	lz_json_num(j, "atomsteps_per_s", (double)s->n * (double)m->steps / wall);
	/* r, v, a, r_prev and scratch: the five arrays of an lz_md. */
	lz_json_int(j, "state_bytes_per_particle", (long long)(5 * s->dim * sizeof(double)));
}

/* ---- the run ---- */

/* A step that failed, or an energy that is no longer finite, stops the run. */
static int physics_guard(const sim *m, int status, double e, unsigned long long step)
{
	if (status == LZ_OK && isfinite(e))
		return LZ_OK;
	char why[1024] = "the energy is not finite";
	if (status != LZ_OK)
		snprintf(why, sizeof why, "%s", lz_error_message());
	if (status != LZ_OK && status != LZ_EPHYS)
		return lz_error(status, "step %llu: %s", step, why);
	char hint[128] = "";
	if (m->potential == HARMONIC)
		snprintf(hint, sizeof hint, " (for the harmonic oscillator ω·dt must be < 2; here "
		         "ω·dt = %g)", m->harmonic.omega * m->dt);
	return lz_error(LZ_EPHYS, "the run blew up at step %llu (t = %g τ): %s; the "
	                "integration is unstable at dt = %g — try a smaller dt%s", step,
	                m->md->t, why, m->dt, hint);
}

static int integrate(sim *m, lz_data *data, int quiet)
{
	lz_progress p;
	if (!quiet)
		lz_progress_begin(&p, "verlet", (double)m->steps);
	int status = LZ_OK;
	for (unsigned long long step = 1; step <= m->steps && status == LZ_OK; step++) {
		status = lz_md_step(m->md, m->integ, m->dt);
		if (m->single)
			lz_md_round_float(m->md);
		double when, e = lz_md_energy(m->md, m->integ, &when);
		status = physics_guard(m, status, e, step);
		if (status == LZ_OK)
			measure(m, step, e, when, data);
		if (!quiet)
			lz_progress_update(&p, (double)step);
	}
	if (!quiet)
		lz_progress_end(&p);
	return status;
}

/* Relative errors need a scale; an energy of exactly zero has none. */
static double scale_of(double x)
{
	return x != 0.0 ? fabs(x) : 1.0;
}

static int run(const lz_scene *s, lz_run *run)
{
	sim m = {0};
	int status = sim_init(&m, s);
	lz_data *data = status == LZ_OK ? open_data(&m, run) : NULL;
	if (status == LZ_OK && !data)
		status = LZ_EIO;
	if (status == LZ_OK) {
		double when;
		m.e0 = lz_md_energy(m.md, m.integ, &when);
		m.escale = scale_of(m.e0);
		m.h0 = has_shadow(&m) ? shadow_energy(&m) : 0.0;
		m.hscale = scale_of(m.h0);
		measure(&m, 0, m.e0, when, data);
		double t0 = lz_wall_now();
		status = integrate(&m, data, run->quiet);
		double wall = lz_wall_now() - t0;
		if (status == LZ_OK)
			summarise(&m, run->summary, wall > 0 ? wall : 1e-9);
	}
	if (data && lz_data_close(data) != LZ_OK && status == LZ_OK)
		status = LZ_EIO;
	if (status == LZ_OK)
		status = write_plot(&m, run);
	sim_free(&m);
	return status;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "energy_rel_err_max"}, {.key = "energy_drift_per_time"},
	{.key = "shadow_energy_rel_err"}, {.key = "temperature_mean"},
	{.key = "pressure_mean"}, {NULL},
};
static const lz_speed speed[] = {{"steps_per_s", "steps/s"}, {NULL}};

const lz_method lz_method_verlet = {
	LZ_METHOD_KEYS("verlet", keys),
	.help = "time-stepped MD: Euler, Verlet, velocity Verlet, leapfrog on harmonic "
	        "oscillators or a Lennard-Jones fluid",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
