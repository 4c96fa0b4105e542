/* method_lattice_gas.c — the `lattice-gas` engine: HPP or FHP lattice gases of
 * lz/lgas.h, from a uniform gas, a shear wave or a density pulse.
 *
 * A run collides and propagates `steps` times, checks that the number of particles
 * and the integer momentum did not change (exactly: a lattice gas conserves them bit
 * for bit, so any change is a bug, and the run fails), and summarises the speed in
 * site updates per second. A shear wave u_x(y) = u0 sin(k y) decays as
 * exp(-ν k² t); the run records its amplitude (decay.dat) and fits ln(amplitude)
 * against t with gsl_fit_linear to measure the kinematic viscosity ν, next to the
 * Boltzmann (no-correlation) theory. A pulse writes the final coarse-grained density
 * (density.dat): on HPP the sound front is a square, on FHP a circle.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "lz/bits.h"
#include "lz/error.h"
#include "lz/lgas.h"
#include "lz/method.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"

enum { UNIFORM, SHEAR, PULSE };
enum { DEFAULT_ROWS = 500, BLOCK = 8 };
/* The first fraction of the run is left out of the fit: the stress of the initial
 * (linearised-equilibrium) state relaxes within a few collision times. */
#define FIT_SKIP 0.05

static const lz_key keys[] = {
	{"model", LZ_KEY_ENUM, "fhp", 0, 0, 0, 0, "hpp|fhp", NULL,
	 "HPP (square lattice, 4 directions) or FHP (triangular, 6 directions, 2-, 3- and "
	 "4-body collisions, particle-hole symmetric)"},
	{"size", LZ_KEY_INT, "256", 2, LZ_LGAS_SIDE_MAX, 0, 0, NULL, "sites",
	 "side L of the periodic L×L lattice, a power of two"},
	{"density", LZ_KEY_REAL, "0.2", 0, 1, 1, 1, NULL, "per link",
	 "mean occupation of a link (site, direction) d; the particle-hole symmetric FHP has "
	 "its smallest viscosity at 1/2"},
	{"steps", LZ_KEY_INT, "1000", 1, 1e9, 0, 0, NULL, NULL, "number of time steps"},
	{"init", LZ_KEY_ENUM, "uniform", 0, 0, 0, 0, "uniform|shear-wave|pulse", NULL,
	 "initial state: gas at rest; shear wave u_x(y) = amplitude·sin(2π y/L) (measures "
	 "the viscosity); density pulse of radius L/8 at the centre"},
	{"amplitude", LZ_KEY_REAL, "0.1", -10, 10, 1, 1, NULL, NULL,
	 "shear-wave: flow speed u0 in lattice units per step, d (1 + 2 abs(u0)) < 1; pulse: "
	 "relative density excess a, d(1 + a) < 1"},
	{"sample", LZ_KEY_INT, "", 1, 1e9, 0, 0, NULL, NULL,
	 "record the shear-wave amplitude every k steps (default: about 500 rows)"},
	{"seed", LZ_KEY_SEED, "auto", 0, 0, 0, 0, NULL, NULL,
	 "random seed of the initial state and of the collision chiralities"},
};

static int check(const lz_scene *s)
{
	long long L = lz_scene_int(s, "size");
	if (lz_check_pow2("size", (uint64_t)L, LZ_LGAS_SIDE_MAX) != LZ_OK)
		return lz_scene_fail(s, "size", "%s (the lattice wraps by mask)", lz_error_message());
	double d = lz_scene_real(s, "density"), a = lz_scene_real(s, "amplitude");
	int init = lz_scene_enum(s, "init");
	if (init == SHEAR && !(d * (1.0 + 2.0 * fabs(a)) < 1.0))
		return lz_scene_fail(s, "amplitude", "amplitude = %g at density = %g: the "
		                     "occupation d (1 + 2 u0) = %g must stay below 1; take |amplitude| "
		                     "< %g", a, d, d * (1.0 + 2.0 * fabs(a)), (1.0 / d - 1.0) / 2.0);
	if (init == PULSE && !(a > -1.0 && d * (1.0 + a) < 1.0))
		return lz_scene_fail(s, "amplitude", "amplitude = %g at density = %g: the pulse "
		                     "density d (1 + a) = %g must be in (0, 1)", a, d, d * (1.0 + a));
	return LZ_OK;
}

/* ---- the state ---- */

typedef struct {
	lz_lgas *g;
	lz_rng *rng;
	uint8_t table[LZ_LGAS_TABLE_SIZE];
	int init;
	double d, a;
	unsigned long long steps, sample;
	double *sinr;             /* sin(2π y / L) per row */
	size_t nrows, cap;
	double *t, *lnamp;        /* the decay record */
	double amp0;
} sim;

/* Boltzmann theory of the kinematic viscosity, lattice units²/step. FHP with two- and
 * three-body collisions only (FHP-I): 1/(12 d (1 - d)³) - 1/8. The four-body
 * collisions of the particle-hole symmetric model add the hole-pair rate d³(1 - d) to
 * the pair rate d (1 - d)³ (the triples do not relax shear stress at all). */
static double nu_fhp1(double d) { return 1.0 / (12.0 * d * pow(1.0 - d, 3)) - 0.125; }
static double nu_model(double d)
{
	return 1.0 / (12.0 * d * (1.0 - d) * ((1.0 - d) * (1.0 - d) + d * d)) - 0.125;
}

/* The shear wave's wave number in inverse lattice spacings: rows are √3/2 apart on the
 * triangular lattice. */
static double wave_number(const sim *m)
{
	double rows = m->g->side * (m->g->model == LZ_LGAS_FHP ? sqrt(3.0) / 2.0 : 1.0);
	return 2.0 * M_PI / rows;
}

/* The sine amplitude of the row-averaged x-momentum per site (lattice units). */
static double amplitude(const sim *m)
{
	double sum = 0.0;
	for (int32_t y = 0; y < m->g->side; y++)
		sum += (double)lz_lgas_row_px2(m->g, y) * m->sinr[y];
	double per_site = 0.5 / ((double)m->g->side * (double)m->g->side);
	return 2.0 * sum * per_site;
}

static int sim_init(sim *m, const lz_scene *s)
{
	lz_lgas_model model = lz_scene_enum(s, "model") == 0 ? LZ_LGAS_HPP : LZ_LGAS_FHP;
	m->init = lz_scene_enum(s, "init");
	m->d = lz_scene_real(s, "density");
	m->a = lz_scene_real(s, "amplitude");
	m->steps = (unsigned long long)lz_scene_int(s, "steps");
	m->sample = lz_scene_has(s, "sample") ? (unsigned long long)lz_scene_int(s, "sample")
	                                      : (m->steps + DEFAULT_ROWS - 1) / DEFAULT_ROWS;
	m->g = lz_lgas_alloc(model, lz_scene_int(s, "size"));
	if (!m->g)
		return LZ_EINVAL;
	m->rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	m->cap = (size_t)(m->steps / m->sample) + 1;
	m->sinr = malloc((size_t)m->g->side * sizeof(double));
	m->t = malloc(2 * m->cap * sizeof(double));
	if (!m->rng || !m->sinr || !m->t)
		return lz_error(LZ_ENOMEM, "no memory for the lattice gas's records");
	m->lnamp = m->t + m->cap;
	for (int32_t y = 0; y < m->g->side; y++)
		m->sinr[y] = sin(2.0 * M_PI * y / m->g->side);
	lz_lgas_table(model, m->table);
	gsl_rng *r = m->rng->gsl;
	switch (m->init) {
	case SHEAR:
		return lz_lgas_init_shear(m->g, m->d, m->a, r);
	case PULSE:
		return lz_lgas_init_pulse(m->g, m->d, m->a, r);
	default:
		return lz_lgas_init_uniform(m->g, m->d, r);
	}
}

static void sim_free(sim *m)
{
	lz_lgas_free(m->g);
	lz_rng_free(m->rng);
	free(m->sinr);
	free(m->t);
}

/* ---- files ---- */

static lz_data *open_decay(const sim *m, const lz_run *run)
{
	static const char *const names[] = {"t", "amplitude", "theory"};
	static const char *const units[] = {"steps", "momentum/site", "momentum/site"};
	char path[4200], title[256];
	if (lz_rundir_file(run->dir, "decay.dat", path, sizeof path) != LZ_OK)
		return NULL;
	snprintf(title, sizeof title, "shear-wave decay, %s, L = %d, d = %g, u0 = %g; theory: "
	         "amplitude(0)·exp(-ν k² t) with the Boltzmann ν", lz_lgas_model_name(m->g->model),
	         (int)m->g->side, m->d, m->a);
	return lz_data_open(path, title, 3, names, units);
}

/* The coarse-grained density (particles per link) in BLOCK×BLOCK blocks, at the
 * Cartesian centre of each block. */
static int write_density(const sim *m, const lz_run *run)
{
	static const char *const names[] = {"x", "y", "density"};
	static const char *const units[] = {"lattice spacings", "lattice spacings", "per link"};
	char path[4200];
	if (lz_rundir_file(run->dir, "density.dat", path, sizeof path) != LZ_OK)
		return LZ_EINVAL;
	const lz_lgas *g = m->g;
	int b = g->side < BLOCK ? g->side : BLOCK, tri = g->model == LZ_LGAS_FHP;
	lz_data *data = lz_data_open(path, "coarse-grained density after the run", 3, names,
	                             units);
	if (!data)
		return LZ_EIO;
	for (int32_t by = 0; by < g->side; by += b)
		for (int32_t bx = 0; bx < g->side; bx += b) {
			long count = 0;
			for (int32_t y = by; y < by + b; y++)
				for (int32_t x = bx; x < bx + b; x++)
					count += lz_site_count(g->site[lz_lgas_index(g, x, y)]);
			double cx = bx + b / 2.0, cy = by + b / 2.0;
			double row[3] = {tri ? cx + 0.5 * cy : cx, tri ? cy * sqrt(3.0) / 2.0 : cy,
			                 (double)count / ((double)b * b * g->nbits)};
			lz_data_row(data, row);
		}
	return lz_data_close(data);
}

static int write_plot(const sim *m, const lz_run *run)
{
	if (m->init == UNIFORM)
		return LZ_OK;
	char path[4200];
	const char *name = m->init == SHEAR ? "decay.gp" : "density.gp";
	int status = lz_rundir_file(run->dir, name, path, sizeof path);
	FILE *f = status == LZ_OK ? fopen(path, "w") : NULL;
	if (!f)
		return status != LZ_OK ? status : lz_error(LZ_EIO, "cannot write %s", path);
	fprintf(f, "# lz run, method lattice-gas.\n"
	        "set terminal pngcairo size 900,700 enhanced font 'Sans,11'\n");
	if (m->init == SHEAR)
		fprintf(f, "set output 'decay.png'\nset key top right\nset grid\nset logscale y\n"
		        "set title \"%s shear wave, L = %d, d = %g\"\n"
		        "set xlabel 'time t [steps]'\nset ylabel 'shear-wave amplitude of j_x [momentum/site]'\n"
		        "plot 'decay.dat' u 1:2 w p pt 7 ps 0.5 t 'measured', "
		        "'' u 1:3 w l lw 2 t 'Boltzmann theory exp(-ν k^2 t)'\n",
		        lz_lgas_model_name(m->g->model), (int)m->g->side, m->d);
	else
		fprintf(f, "set output 'density.png'\nset size ratio -1\nunset key\n"
		        "set title \"%s pulse after %llu steps: density per link\"\n"
		        "set xlabel 'x [lattice spacings]'\nset ylabel 'y [lattice spacings]'\n"
		        "set palette defined (0 'white', 1 'blue', 2 'red')\n"
		        "plot 'density.dat' u 1:2:3 w p pt 5 ps 0.6 lc palette\n",
		        lz_lgas_model_name(m->g->model), m->steps);
	if (fclose(f) != 0)
		return lz_error(LZ_EIO, "cannot write %s", path);
	status = lz_gnuplot(run->dir->tmp, name);
	return status == 1 ? LZ_OK : status;
}

/* ---- the run ---- */

static void record(sim *m, unsigned long long step, lz_data *data)
{
	double a = amplitude(m), k = wave_number(m);
	if (step == 0)
		m->amp0 = a;
	double row[3] = {(double)step, a, m->amp0 * exp(-nu_model(m->d) * k * k * (double)step)};
	if (m->g->model != LZ_LGAS_FHP)
		row[2] = NAN;
	lz_data_row(data, row);
	/* Fit only while the wave stands clear of the noise: above a tenth of its start. */
	if (m->nrows < m->cap && a > 0.1 * fabs(m->amp0) && (double)step >= FIT_SKIP * m->steps) {
		m->t[m->nrows] = (double)step;
		m->lnamp[m->nrows++] = log(a);
	}
}

static int evolve(sim *m, lz_data *data, int quiet, double *wall)
{
	lz_progress p;
	if (!quiet)
		lz_progress_begin(&p, "lattice-gas", (double)m->steps);
	double busy = 0.0;
	if (data)
		record(m, 0, data);
	for (unsigned long long step = 1; step <= m->steps; step++) {
		double t0 = lz_wall_now();
		lz_lgas_collide(m->g, m->table, m->rng->gsl);
		lz_lgas_propagate(m->g);
		busy += lz_wall_now() - t0;
		if (data && step % m->sample == 0)
			record(m, step, data);
		if (!quiet)
			lz_progress_update(&p, (double)step);
	}
	if (!quiet)
		lz_progress_end(&p);
	*wall = busy > 0 ? busy : 1e-9;
	return LZ_OK;
}

static void summarise(const sim *m, lz_json *j, double wall, int64_t dmass, int64_t dp)
{
	double sites = (double)m->g->side * (double)m->g->side;
	lz_json_int(j, "mass_change", (long long)dmass);
	lz_json_int(j, "momentum_change", (long long)dp);
	if (m->init == SHEAR) {
		double k = wave_number(m), c0, c1 = NAN, cov00, cov01, cov11 = NAN, sumsq;
		if (m->nrows >= 3)
			gsl_fit_linear(m->t, 1, m->lnamp, 1, m->nrows, &c0, &c1, &cov00, &cov01, &cov11,
			               &sumsq);
		/* The fit's own error bar sees only the fast noise; the thermal fluctuation of
		 * the same Fourier mode decays as slowly as the wave and bends the whole line.
		 * Its amplitude noise is σ = sqrt(2 d (1 - d) Σ c_x²) / L; the slope from the
		 * first and last fitted points then has the error below. The larger is kept. */
		double err = sqrt(cov11);
		if (m->nrows >= 3) {
			double cx2 = m->g->model == LZ_LGAS_FHP ? 3.0 : 2.0;
			double sigma = sqrt(2.0 * m->d * (1.0 - m->d) * cx2) / m->g->side;
			double a0 = exp(m->lnamp[0]), a1 = exp(m->lnamp[m->nrows - 1]);
			double span = m->t[m->nrows - 1] - m->t[0];
			err = fmax(err, sigma * sqrt(1.0 / (a0 * a0) + 1.0 / (a1 * a1)) / span);
		}
		lz_json_err(j, "viscosity", -c1 / (k * k), err / (k * k));
		int fhp = m->g->model == LZ_LGAS_FHP;
		lz_json_num(j, "viscosity_theory", fhp ? nu_model(m->d) : NAN);
		lz_json_num(j, "viscosity_theory_fhp1", fhp ? nu_fhp1(m->d) : NAN);
		lz_json_num(j, "wave_number", k);
		lz_json_int(j, "fit_points", (long long)m->nrows);
	}
	lz_json_num(j, "site_updates_per_s", sites * (double)m->steps / wall);
	lz_json_int(j, "state_bytes_per_site", 2);
}

static int run(const lz_scene *s, lz_run *run)
{
	sim m = {0};
	int status = sim_init(&m, s);
	lz_data *data = NULL;
	if (status == LZ_OK && m.init == SHEAR && !(data = open_decay(&m, run)))
		status = LZ_EIO;
	int64_t mass0 = 0, p0[2] = {0, 0}, mass1 = 0, p1[2] = {0, 0};
	double wall = 1e-9;
	if (status == LZ_OK) {
		lz_lgas_totals(m.g, &mass0, p0);
		status = evolve(&m, data, run->quiet, &wall);
		lz_lgas_totals(m.g, &mass1, p1);
	}
	if (data && lz_data_close(data) != LZ_OK && status == LZ_OK)
		status = LZ_EIO;
	int64_t dmass = mass1 - mass0, dp = llabs(p1[0] - p0[0]) + llabs(p1[1] - p0[1]);
	if (status == LZ_OK && (dmass != 0 || dp != 0))
		status = lz_error(LZ_EPHYS, "a lattice gas conserves particles and momentum exactly, "
		                  "but after %llu steps the mass changed by %lld and the momentum "
		                  "(integer units) by (%lld, %lld): a collision rule or the "
		                  "propagation loses or makes particles", m.steps, (long long)dmass,
		                  (long long)(p1[0] - p0[0]), (long long)(p1[1] - p0[1]));
	if (status == LZ_OK) {
		lz_json_int(run->summary, "particles", (long long)mass1);
		summarise(&m, run->summary, wall, dmass, dp);
	}
	if (status == LZ_OK && m.init == PULSE)
		status = write_density(&m, run);
	if (status == LZ_OK)
		status = write_plot(&m, run);
	sim_free(&m);
	return status;
}

const lz_method lz_method_lattice_gas = {
	.name = "lattice-gas",
	.help = "HPP and FHP lattice gases: propagation by masks, collisions by table; "
	        "exact conservation, shear-wave viscosity",
	.keys = keys,
	.nkeys = sizeof keys / sizeof keys[0],
	.check = check,
	.run = run,
};
