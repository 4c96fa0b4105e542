/* method_lattice_gas.c — the `lattice-gas` engine: HPP or FHP lattice gases of
 * lz/lgas.h, from a uniform gas, a shear wave, a density pulse or a uniform flow,
 * optionally around an obstacle (a plate or a disk of bounce-back wall sites).
 *
 * A run collides and propagates `steps` times and checks conservation exactly (a
 * lattice gas conserves bits, so any change is a bug, and the run fails): the number
 * of particles always; the integer momentum only without an obstacle, since walls
 * take momentum — then the summary reports what they took (the drag). The speed is
 * in site updates per second.
 *
 * Observables, each only for the initial state that asks for it:
 *   shear wave: u_x(y) = u0 sin(k y) decays as exp(-ν k² t); the amplitude is recorded
 *     (decay.dat) and ln(amplitude) fitted against t with gsl_fit_linear: ν, beside
 *     the Boltzmann (no-correlation) theory;
 *   pulse: the coarse-grained density at the end (density.dat) and the anisotropy of
 *     the sound front, the angular harmonic of the lattice's symmetry (m = 4 on HPP,
 *     6 on FHP) of the excess density in the ring the pulse has spread into
 *     (front.dat: the excess against the angle);
 *   flow, or any obstacle: the coarse-grained velocity field, averaged over the last
 *     `average` steps (velocity.dat), and the obstacle's sites (obstacle.dat).
 * Coarse-graining is over Cartesian blocks of `block` rows by `block` sites, in the
 * rectangular view of lz_lgas_position; wall sites are left out.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "lz/bits.h"
#include "lz/error.h"
#include "lz/lattice.h"
#include "lz/lgas.h"
#include "method.h"
#include "lz/progress.h"
#include "lz/rng.h"
#include "lz/timer.h"

enum { UNIFORM, SHEAR, PULSE, FLOW };
/* ANGLES: bins of 15°, so that the axes (0°, 60°, 90°) and the directions between them
 * (30°, 45°) are bin centres on both lattices. */
enum { DEFAULT_ROWS = 500, ANGLES = 24 };
/* The first fraction of the run is left out of the fit: the stress of the initial
 * (linearised-equilibrium) state relaxes within a few collision times. */
#define FIT_SKIP 0.05

static const lz_key keys[] = {
	{.name = "model", .type = LZ_KEY_ENUM, .def = "fhp", .choices = "hpp|fhp",
	 .help = "HPP (square lattice, 4 directions) or FHP (triangular, 6 directions, 2-, "
	         "3- and " "4-body collisions, particle-hole symmetric)"},
	{.name = "size", .type = LZ_KEY_INT, .def = "256", .min = 2, .max = LZ_LGAS_SIDE_MAX,
	 .unit = "sites", .help = "side L of the periodic L×L lattice, a power of two"},
	{.name = "density", .type = LZ_KEY_REAL, .def = "0.2", .min = 0, .max = 1,
	 .min_open = 1, .max_open = 1, .unit = "per link",
	 .help = "mean occupation of a link (site, direction) d; the particle-hole "
	         "symmetric FHP has " "its smallest viscosity at 1/2"},
	{.name = "steps", .type = LZ_KEY_INT, .def = "1000", .min = 1, .max = 1e9,
	 .help = "number of time steps"},
	{.name = "init", .type = LZ_KEY_ENUM, .def = "uniform",
	 .choices = "uniform|shear-wave|pulse|flow",
	 .help = "initial state: gas at rest; shear wave u_x(y) = amplitude·sin(2π y/L) "
	         "(viscosity); "
	         "density pulse of radius L/8 at the centre (front anisotropy); uniform "
	         "flow " "u_x = amplitude"},
	{.name = "amplitude", .type = LZ_KEY_REAL, .def = "0.1", .min = -10, .max = 10,
	 .min_open = 1, .max_open = 1,
	 .help = "shear-wave, flow: speed u0 in lattice units per step, abs(u0) <= 1/2 and "
	         "d (1 + 2 abs(u0)) < 1; pulse: relative density excess a, d(1 + a) < 1"},
	{.name = "obstacle", .type = LZ_KEY_ENUM, .def = "none", .choices = "none|plate|disk",
	 .help = "bounce-back walls centred at x = L/4 on the middle row: a plate across "
	         "the flow "
	         "(one site per row) or a filled disk; walls take momentum, so only mass "
	         "is then " "checked exactly"},
	{.name = "obstacle_size", .type = LZ_KEY_INT, .def = "", .min = 1,
	 .max = LZ_LGAS_SIDE_MAX / 2, .unit = "sites",
	 .help = "plate: rows it spans (length size·√3/2 on FHP); disk: diameter; in [1, "
	         "L/2] " "(default L/8)"},
	{.name = "block", .type = LZ_KEY_INT, .def = "8", .min = 1, .max = LZ_LGAS_SIDE_MAX,
	 .unit = "sites",
	 .help = "coarse-graining block of density.dat and velocity.dat: block rows by "
	         "block sites, " "a power of two up to L"},
	{.name = "average", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e9,
	 .help = "flow or obstacle: average the velocity field over the last k steps "
	         "(default " "steps/4)"},
	{.name = "sample", .type = LZ_KEY_INT, .def = "", .min = 1, .max = 1e9,
	 .help = "record the shear-wave amplitude every k steps (default: about 500 rows)"},
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto",
	 .help = "random seed of the initial state and of the collision chiralities"},
};

/* The velocity field is written for a flow and around any obstacle. */
static int wants_field(int init, int obstacle) { return init == FLOW || obstacle != 0; }

static int check(const lz_scene *s)
{
	long long L = lz_scene_int(s, "size");
	if (lz_check_pow2("size", (uint64_t)L, LZ_LGAS_SIDE_MAX) != LZ_OK)
		return lz_scene_fail(s, "size", "%s (the lattice wraps by mask)", lz_error_message());
	double d = lz_scene_real(s, "density"), a = lz_scene_real(s, "amplitude");
	int init = lz_scene_enum(s, "init"), obstacle = lz_scene_enum(s, "obstacle");
	if ((init == SHEAR || init == FLOW) && !(fabs(a) <= 0.5 && d * (1.0 + 2.0 * fabs(a)) < 1.0))
		return lz_scene_fail(s, "amplitude", "amplitude = %g at density = %g: the "
		                     "occupation d (1 + 2 c·u) of every direction must stay in "
		                     "[0, 1); take |amplitude| <= 1/2 and |amplitude| < (1/d - 1)/2 "
		                     "= %g", a, d, (1.0 / d - 1.0) / 2.0);
	if (init == PULSE && !(a > -1.0 && d * (1.0 + a) < 1.0))
		return lz_scene_fail(s, "amplitude", "amplitude = %g at density = %g: the pulse "
		                     "density d (1 + a) = %g must be in (0, 1)", a, d, d * (1.0 + a));
	if (obstacle == 0 && lz_scene_given(s, "obstacle_size"))
		return lz_scene_fail(s, "obstacle_size", "obstacle_size is given but obstacle = "
		                     "none: say obstacle = plate or disk");
	long long size = lz_scene_has(s, "obstacle_size") ? lz_scene_int(s, "obstacle_size") : 1;
	if (size > lz_lgas_obstacle_max(L))
		return lz_scene_fail(s, "obstacle_size", "obstacle_size = %lld sites is outside [1, "
		                     "%lld]: at most half the side L = %lld, so that the flow can "
		                     "pass", size, (long long)lz_lgas_obstacle_max(L), L);
	long long b = lz_scene_int(s, "block");
	if (lz_check_pow2("block", (uint64_t)b, (uint64_t)L) != LZ_OK)
		return lz_scene_fail(s, "block", "%s (blocks tile the L = %lld lattice)",
		                     lz_error_message(), L);
	if (lz_scene_given(s, "average") && (init == PULSE || !wants_field(init, obstacle)))
		return lz_scene_fail(s, "average", "average is for the velocity field of a flow or "
		                     "around an obstacle (a pulse's fields are its last state)");
	if (lz_scene_has(s, "average") && lz_scene_int(s, "average") > lz_scene_int(s, "steps"))
		return lz_scene_fail(s, "average", "average = %lld steps is more than the run's "
		                     "steps = %lld", lz_scene_int(s, "average"),
		                     lz_scene_int(s, "steps"));
	return LZ_OK;
}

/* ---- the state ---- */

typedef struct {
	lz_lgas *g;
	lz_rng *rng;
	uint8_t table[LZ_LGAS_TABLE_SIZE];
	int init, obstacle, field;
	double d, a;
	unsigned long long steps, sample, average;
	int64_t walls;            /* wall sites */
	/* shear wave */
	double *sinr;             /* sin(2π y / L) per row */
	size_t nrows, cap;
	double *t, *amp;          /* the decay record */
	/* coarse-graining: per block the particles, 2 p_x and p_y / h summed over the
	 * fluid sites and the sampled steps, h the row spacing (√3/2 or 1) */
	int lb;                   /* log2 block */
	int32_t nbx;              /* blocks per row of blocks, L / block */
	unsigned long long samples;
	int64_t *bn, *bpx2, *bpy;
	int8_t mass[64], px2[64], py[64];  /* per state: particles, 2 p_x, p_y / h */
} sim;

static int is_fhp(const sim *m) { return m->g->model == LZ_LGAS_FHP; }
/* The row spacing: rows of the triangular lattice are √3/2 apart. */
static double row_h(const sim *m) { return is_fhp(m) ? sqrt(3.0) / 2.0 : 1.0; }

/* Boltzmann theory of the kinematic viscosity, lattice units²/step. FHP with two- and
 * three-body collisions only (FHP-I): 1/(12 d (1 - d)³) - 1/8. The four-body
 * collisions of the particle-hole symmetric model add the hole-pair rate d³(1 - d) to
 * the pair rate d (1 - d)³ (the triples do not relax shear stress at all). */
static double nu_fhp1(double d) { return 1.0 / (12.0 * d * pow(1.0 - d, 3)) - 0.125; }
static double nu_model(double d)
{
	return 1.0 / (12.0 * d * (1.0 - d) * ((1.0 - d) * (1.0 - d) + d * d)) - 0.125;
}

/* The shear wave's wave number in inverse lattice spacings. */
static double wave_number(const sim *m) { return 2.0 * M_PI / (m->g->side * row_h(m)); }

/* The sine amplitude of the row-averaged x-momentum per site (lattice units). */
static double amplitude(const sim *m)
{
	double sum = 0.0;
	for (int32_t y = 0; y < m->g->side; y++)
		sum += (double)lz_lgas_row_px2(m->g, y) * m->sinr[y];
	double per_site = 0.5 / ((double)m->g->side * (double)m->g->side);
	return 2.0 * sum * per_site;
}

/* Per-state tables of the particles and the Cartesian momentum: direction k is the
 * sheared integer vector e_k, Cartesian (e_x + e_y/2, e_y h) on FHP, so 2 p_x and
 * p_y / h are integers. */
static void state_tables(sim *m)
{
	int n;
	const lz_site *e = lz_lattice_dirs(lz_lgas_lattice(m->g->model), &n);
	for (unsigned s = 0; s < 64; s++) {
		int mass = 0, px2 = 0, py = 0;
		for (int k = 0; k < n; k++)
			if (s >> k & 1u) {
				mass++;
				px2 += 2 * e[k].x + (is_fhp(m) ? e[k].y : 0);
				py += e[k].y;
			}
		m->mass[s] = (int8_t)mass;
		m->px2[s] = (int8_t)px2;
		m->py[s] = (int8_t)py;
	}
}

static int sim_init(sim *m, const lz_scene *s)
{
	lz_lgas_model model = lz_scene_enum(s, "model") == 0 ? LZ_LGAS_HPP : LZ_LGAS_FHP;
	m->init = lz_scene_enum(s, "init");
	m->obstacle = lz_scene_enum(s, "obstacle");
	m->field = wants_field(m->init, m->obstacle);
	m->d = lz_scene_real(s, "density");
	m->a = lz_scene_real(s, "amplitude");
	m->steps = (unsigned long long)lz_scene_int(s, "steps");
	m->sample = lz_scene_has(s, "sample") ? (unsigned long long)lz_scene_int(s, "sample")
	                                      : (m->steps + DEFAULT_ROWS - 1) / DEFAULT_ROWS;
	m->average = lz_scene_has(s, "average") ? (unsigned long long)lz_scene_int(s, "average")
	                                        : (m->steps + 3) / 4;
	m->g = lz_lgas_alloc(model, lz_scene_int(s, "size"));
	if (!m->g)
		return LZ_EINVAL;
	int32_t L = m->g->side;
	m->lb = lz_log2_pow2((uint64_t)lz_scene_int(s, "block"));
	m->nbx = L >> m->lb;
	size_t nblocks = (size_t)m->nbx * (size_t)m->nbx;
	m->rng = lz_rng_alloc(NULL, lz_scene_seed(s, "seed"));
	m->cap = (size_t)(m->steps / m->sample) + 1;
	m->sinr = malloc((size_t)L * sizeof(double));
	m->t = malloc(2 * m->cap * sizeof(double));
	m->bn = calloc(3 * nblocks, sizeof(int64_t));
	if (!m->rng || !m->sinr || !m->t || !m->bn)
		return lz_error(LZ_ENOMEM, "no memory for the lattice gas's records");
	m->amp = m->t + m->cap;
	m->bpx2 = m->bn + nblocks;
	m->bpy = m->bpx2 + nblocks;
	for (int32_t y = 0; y < L; y++)
		m->sinr[y] = sin(2.0 * M_PI * y / L);
	lz_lgas_table(model, m->table);
	state_tables(m);
	if (m->obstacle) {
		int64_t size = lz_scene_has(s, "obstacle_size") ? lz_scene_int(s, "obstacle_size")
		                                                : (L / 8 > 1 ? L / 8 : 1);
		m->walls = lz_lgas_add_obstacle(m->g, m->obstacle == 1 ? LZ_LGAS_PLATE : LZ_LGAS_DISK,
		                                size);
		if (m->walls < 0)
			return LZ_EINVAL;
	}
	gsl_rng *r = m->rng->gsl;
	switch (m->init) {
	case SHEAR:
		return lz_lgas_init_shear(m->g, m->d, m->a, r);
	case PULSE:
		return lz_lgas_init_pulse(m->g, m->d, m->a, r);
	case FLOW:
		return lz_lgas_init_flow(m->g, m->d, m->a, r);
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
	free(m->bn);
}

/* ---- coarse-graining ---- */

/* The block column of site x in a row whose Cartesian X is x + off/2 (mod L): X/block
 * rounded down, as in lz_lgas_position. 2L is a power of two, so the wrap is a mask
 * (and right for negative offsets too, in unsigned arithmetic). */
static inline uint32_t block_column(const sim *m, int32_t x, uint32_t off)
{
	return ((2u * (uint32_t)x + off) & (2u * (uint32_t)m->g->side - 1u)) >> (m->lb + 1);
}

static uint32_t row_offset(const sim *m, int32_t y)
{
	return is_fhp(m) ? (uint32_t)(y - m->g->side / 2) : 0u;
}

/* Add the present state to the blocks' sums. O(L²). */
static void accumulate(sim *m)
{
	const lz_lgas *g = m->g;
	for (int32_t y = 0; y < g->side; y++) {
		const uint8_t *row = g->site + lz_lgas_index(g, 0, y);
		size_t first = (size_t)(y >> m->lb) * (size_t)m->nbx;
		int64_t *n = m->bn + first, *px2 = m->bpx2 + first, *py = m->bpy + first;
		uint32_t off = row_offset(m, y);
		for (int32_t x = 0; x < g->side; x++) {
			unsigned s = row[x];
			if (s & LZ_LGAS_WALL)
				continue;
			uint32_t i = block_column(m, x, off);
			n[i] += m->mass[s];
			px2[i] += m->px2[s];
			py[i] += m->py[s];
		}
	}
	m->samples++;
}

/* Write the blocks: centre x, y (the mean position of the block's sites), then the
 * density per link, and with `velocity` the mean particle velocity u = p / n first.
 * Blocks made only of walls have nan. */
static int write_blocks(const sim *m, const lz_run *run, int velocity)
{
	static const char *const names[] = {"x", "y", "ux", "uy", "density"};
	static const char *const units[] = {"lattice spacings", "lattice spacings",
	                                    "spacings/step", "spacings/step", "per link"};
	static const char *const dnames[] = {"x", "y", "density"};
	static const char *const dunits[] = {"lattice spacings", "lattice spacings", "per link"};
	const lz_lgas *g = m->g;
	int32_t b = 1 << m->lb, nbx = m->nbx;
	double h = row_h(m);
	size_t nblocks = (size_t)nbx * (size_t)nbx;
	int64_t *fluid = calloc(nblocks, sizeof *fluid);
	double *xsum = calloc(nblocks, sizeof *xsum);
	if (!fluid || !xsum) {
		free(fluid);
		free(xsum);
		return lz_error(LZ_ENOMEM, "no memory for the coarse-grained field");
	}
	for (int32_t y = 0; y < g->side; y++) {
		size_t first = (size_t)(y >> m->lb) * (size_t)nbx;
		for (int32_t x = 0; x < g->side; x++) {
			double X, Y;
			lz_lgas_position(g, x, y, &X, &Y);
			size_t i = first + block_column(m, x, row_offset(m, y));
			xsum[i] += X;
			fluid[i] += !(g->site[lz_lgas_index(g, x, y)] & LZ_LGAS_WALL);
		}
	}
	char path[4200], title[256];
	int status = lz_rundir_file(run->dir, velocity ? "velocity.dat" : "density.dat", path,
	                            sizeof path);
	lz_data *data = NULL;
	if (status == LZ_OK) {
		if (velocity)
			snprintf(title, sizeof title, "coarse-grained flow in %d×%d blocks, averaged over "
			         "the last %llu steps; x, y Cartesian (lz_lgas_position)", b, b,
			         m->samples);
		else
			snprintf(title, sizeof title, "coarse-grained density in %d×%d blocks after %llu "
			         "steps; x, y Cartesian (lz_lgas_position)", b, b, m->steps);
		data = velocity ? lz_data_open(path, title, 5, names, units)
		                : lz_data_open(path, title, 3, dnames, dunits);
		status = data ? LZ_OK : LZ_EIO;
	}
	for (int32_t j = 0; status == LZ_OK && j < nbx; j++)
		for (int32_t i = 0; i < nbx; i++) {
			size_t k = (size_t)j * (size_t)nbx + (size_t)i;
			double n = (double)m->bn[k], sites = (double)fluid[k] * (double)m->samples;
			double row[5] = {xsum[k] / ((double)b * b), (j * b + (b - 1) / 2.0) * h, NAN, NAN,
			                 sites > 0 ? n / (sites * g->nbits) : NAN};
			if (n > 0) {
				row[2] = 0.5 * (double)m->bpx2[k] / n;
				row[3] = (double)m->bpy[k] * h / n;
			}
			if (velocity)
				lz_data_row(data, row);
			else
				lz_data_row(data, (double[]){row[0], row[1], row[4]});
		}
	free(fluid);
	free(xsum);
	if (data && lz_data_close(data) != LZ_OK && status == LZ_OK)
		status = LZ_EIO;
	return status;
}

/* The wall sites, Cartesian. */
static int write_obstacle(const sim *m, const lz_run *run)
{
	static const char *const names[] = {"x", "y"};
	static const char *const units[] = {"lattice spacings", "lattice spacings"};
	char path[4200];
	if (lz_rundir_file(run->dir, "obstacle.dat", path, sizeof path) != LZ_OK)
		return LZ_EINVAL;
	lz_data *data = lz_data_open(path, "wall sites of the obstacle, Cartesian "
	                             "(lz_lgas_position)", 2, names, units);
	if (!data)
		return LZ_EIO;
	const lz_lgas *g = m->g;
	for (int32_t y = 0; y < g->side; y++)
		for (int32_t x = 0; x < g->side; x++)
			if (g->site[lz_lgas_index(g, x, y)] & LZ_LGAS_WALL) {
				double row[2];
				lz_lgas_position(g, x, y, &row[0], &row[1]);
				lz_data_row(data, row);
			}
	return lz_data_close(data);
}

/* ---- the pulse's front ----
 * The excess n - nbits·d of every fluid site in the ring r_in <= r < r_out around the
 * pulse's centre, r_in = L/8 (the pulse's edge) and r_out = L/8 + steps (no particle
 * goes further: the light cone), capped at the radius within which the nearest
 * periodic image is the plain one (L/2 on the square lattice, L√3/4 on the
 * triangular). Its m-th angular harmonic H_m = Σ excess cos(mθ) / Σ excess, with m the
 * lattice's own symmetry (4 on HPP, 6 on FHP; θ from the lattice's direction 0), is
 * 0 for a round front, positive when the excess runs ahead along the lattice axes,
 * 1 for a gas that only streams along them. Its error is the binomial noise of the
 * sites: sqrt(nbits d (1 - d) Σ cos²(mθ)) / Σ excess. */
static int front(const sim *m, const lz_run *run, lz_json *j)
{
	static const char *const names[] = {"theta", "excess", "relative", "harmonic"};
	static const char *const units[] = {"degrees", "per link", NULL, NULL};
	const lz_lgas *g = m->g;
	int32_t L = g->side;
	int harm = is_fhp(m) ? 6 : 4;
	double h = row_h(m), r_in = L / 8.0;
	double r_out = fmin(r_in + (double)m->steps, is_fhp(m) ? L * sqrt(3.0) / 4.0 : L / 2.0);
	double background = g->nbits * m->d, sum = 0.0, c = 0.0, cc = 0.0, ex[ANGLES] = {0};
	long count[ANGLES] = {0}, sites = 0;
	for (int32_t y = 0; y < L; y++)
		for (int32_t x = 0; x < L; x++) {
			unsigned s = g->site[lz_lgas_index(g, x, y)];
			/* Offsets from the centre (L/2, L/2), in [-L/2, L/2). */
			int32_t dx = x - L / 2, dy = y - L / 2;
			double X = dx + (is_fhp(m) ? 0.5 * dy : 0.0), Y = dy * h, r = hypot(X, Y);
			if (s & LZ_LGAS_WALL || r < r_in || r >= r_out)
				continue;
			double theta = atan2(Y, X), dn = lz_site_count(s) - background;
			double cm = cos(harm * theta);
			sum += dn;
			c += dn * cm;
			cc += cm * cm;
			int bin = (int)floor(theta / (2.0 * M_PI) * ANGLES + 0.5);
			bin = (bin % ANGLES + ANGLES) % ANGLES;
			ex[bin] += dn;
			count[bin]++;
			sites++;
		}
	double H = sum > 0 ? c / sum : NAN;
	lz_json_int(j, "front_harmonic", harm);
	lz_json_err(j, "front_anisotropy", H, sum > 0 ? sqrt(background * (1.0 - m->d) * cc) / sum
	                                              : NAN);
	lz_json_num(j, "front_radius_in", r_in);
	lz_json_num(j, "front_radius_out", r_out);
	char path[4200], title[256];
	if (lz_rundir_file(run->dir, "front.dat", path, sizeof path) != LZ_OK)
		return LZ_EINVAL;
	snprintf(title, sizeof title, "%s pulse after %llu steps: excess density in the ring "
	         "%g <= r < %g by angle (15° bins); relative = excess / its mean; harmonic = "
	         "1 + 2 H_%d cos(%d θ), H_%d = %.4f", lz_lgas_model_name(g->model), m->steps, r_in,
	         r_out, harm, harm, harm, H);
	lz_data *data = lz_data_open(path, title, 4, names, units);
	if (!data)
		return LZ_EIO;
	double mean = sites > 0 ? sum / (double)sites : NAN;
	for (int k = 0; k < ANGLES; k++) {
		double theta = 360.0 * k / ANGLES, per_site = count[k] ? ex[k] / (double)count[k] : NAN;
		double row[4] = {theta, per_site / g->nbits, per_site / mean,
		                 1.0 + 2.0 * H * cos(harm * theta * M_PI / 180.0)};
		lz_data_row(data, row);
	}
	return lz_data_close(data);
}

/* ---- the shear wave's decay ---- */

/* Fit ln(amplitude) against t over the rows that stand clear of the noise (above a
 * tenth of the start) after the first FIT_SKIP of the run; write decay.dat with the
 * measured amplitude, the Boltzmann theory, the fitted line and which rows it used;
 * and the viscosity into the summary. */
static int decay(const sim *m, const lz_run *run, lz_json *j)
{
	static const char *const names[] = {"t", "amplitude", "theory", "fit", "fitted"};
	static const char *const units[] = {"steps", "momentum/site", "momentum/site",
	                                    "momentum/site", NULL};
	size_t n = m->nrows, nfit = 0;
	double amp0 = n ? m->amp[0] : NAN, k = wave_number(m);
	double *ft = malloc(2 * (n + 1) * sizeof *ft), *fy = ft ? ft + n + 1 : NULL;
	char *use = calloc(n + 1, 1);
	if (!ft || !use) {
		free(ft);
		free(use);
		return lz_error(LZ_ENOMEM, "no memory for the shear-wave fit");
	}
	for (size_t i = 0; i < n; i++)
		if (m->amp[i] > 0.1 * fabs(amp0) && m->t[i] >= FIT_SKIP * (double)m->steps) {
			use[i] = 1;
			ft[nfit] = m->t[i];
			fy[nfit++] = log(m->amp[i]);
		}
	double c0 = NAN, c1 = NAN, cov00, cov01, cov11 = NAN, sumsq;
	if (nfit >= 3)
		gsl_fit_linear(ft, 1, fy, 1, nfit, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
	/* The fit's own error bar sees only the fast noise; the thermal fluctuation of the
	 * same Fourier mode decays as slowly as the wave and bends the whole line. Its
	 * amplitude noise is σ = sqrt(2 d (1 - d) Σ c_x²) / L; the slope from the first and
	 * last fitted points then has the error below. The larger is kept. */
	double err = sqrt(cov11);
	if (nfit >= 3) {
		double cx2 = is_fhp(m) ? 3.0 : 2.0;
		double sigma = sqrt(2.0 * m->d * (1.0 - m->d) * cx2) / m->g->side;
		double a0 = exp(fy[0]), a1 = exp(fy[nfit - 1]), span = ft[nfit - 1] - ft[0];
		err = fmax(err, sigma * sqrt(1.0 / (a0 * a0) + 1.0 / (a1 * a1)) / span);
	}
	/* + 0.0 turns -0 into 0: on HPP every row keeps its x-momentum exactly, so a shear
	 * wave along the axes never decays and c1 is exactly 0. */
	lz_json_err(j, "viscosity", -c1 / (k * k) + 0.0, err / (k * k));
	lz_json_num(j, "viscosity_theory", is_fhp(m) ? nu_model(m->d) : NAN);
	lz_json_num(j, "viscosity_theory_fhp1", is_fhp(m) ? nu_fhp1(m->d) : NAN);
	lz_json_num(j, "wave_number", k);
	lz_json_int(j, "fit_points", (long long)nfit);

	char path[4200], title[320];
	int status = lz_rundir_file(run->dir, "decay.dat", path, sizeof path);
	lz_data *data = NULL;
	if (status == LZ_OK) {
		snprintf(title, sizeof title, "shear-wave decay, %s, L = %d, d = %g, u0 = %g; theory: "
		         "amplitude(0)·exp(-ν k² t) with the Boltzmann ν; fit: exp(c0 + c1 t) over "
		         "the rows with fitted = 1, ν = -c1/k², k = %.9g", lz_lgas_model_name(m->g->model),
		         (int)m->g->side, m->d, m->a, k);
		data = lz_data_open(path, title, 5, names, units);
		status = data ? LZ_OK : LZ_EIO;
	}
	for (size_t i = 0; status == LZ_OK && i < n; i++) {
		double row[5] = {m->t[i], m->amp[i],
		                 is_fhp(m) ? amp0 * exp(-nu_model(m->d) * k * k * m->t[i]) : NAN,
		                 exp(c0 + c1 * m->t[i]), use[i]};
		lz_data_row(data, row);
	}
	free(ft);
	free(use);
	if (data && lz_data_close(data) != LZ_OK && status == LZ_OK)
		status = LZ_EIO;
	return status;
}

/* ---- the run's own plot ---- */

static int write_plot(const sim *m, const lz_run *run)
{
	if (m->init == UNIFORM && !m->field)
		return LZ_OK;
	const char *name = m->init == SHEAR ? "decay" : m->init == PULSE ? "density" : "velocity";
	static const char *const what[] = {"the shear wave's decay", "the density after the pulse",
	                                   "the velocity field"};
	FILE *f = lz_run_script(run, name, "lattice-gas",
	                        what[m->init == SHEAR ? 0 : m->init == PULSE ? 1 : 2], 900,
	                        m->init == SHEAR ? 700 : (int)(100 + 700 * row_h(m)));
	if (!f)
		return LZ_EIO;
	const char *model = lz_lgas_model_name(m->g->model);
	int L = (int)m->g->side;
	double top = L * row_h(m);
	if (m->init == SHEAR)
		fprintf(f, "set key top right\nset grid\nset logscale y\n"
		        "set title \"%s shear wave, L = %d, d = %g\"\n"
		        "set xlabel 'time t [steps]'\n"
		        "set ylabel 'shear-wave amplitude of j_x [momentum/site]'\n"
		        "plot 'decay.dat' u 1:2 w p pt 7 ps 0.5 t 'measured', "
		        "'' u 1:4 w l lw 2 dt 2 t 'fit exp(-ν k^2 t)', "
		        "'' u 1:3 w l lw 2 t 'Boltzmann theory'\n", model, L, m->d);
	else if (m->init == PULSE)
		fprintf(f, "set size ratio -1\nunset key\n"
		        "set title \"%s pulse after %llu steps: density per link\"\n"
		        "set xlabel 'x [lattice spacings]'\nset ylabel 'y [lattice spacings]'\n"
		        "set xrange [0:%d]\nset yrange [0:%g]\n"
		        "set palette defined (0 'white', 1 'blue', 2 'red')\n"
		        "plot 'density.dat' u 1:2:3 w image\n", model, m->steps, L, top);
	else
		fprintf(f, "set size ratio -1\nunset key\n"
		        "set title \"%s flow after %llu steps, averaged over the last %llu\"\n"
		        "set xlabel 'x [lattice spacings]'\nset ylabel 'y [lattice spacings]'\n"
		        "set xrange [0:%d]\nset yrange [0:%g]\nset cblabel 'speed [spacings/step]'\n"
		        "stats 'velocity.dat' u (sqrt($3**2+$4**2)) nooutput\n"
		        "s = 0.9 * %d / STATS_max\n"
		        "plot 'velocity.dat' u 1:2:($3*s):($4*s):(sqrt($3**2+$4**2)) w vectors "
		        "filled head size 1.5,20 lc palette%s\n",
		        model, m->steps, m->samples, L, top, 1 << m->lb,
		        m->obstacle ? ", 'obstacle.dat' u 1:2 w p pt 5 ps 0.4 lc rgb 'black'" : "");
	return lz_run_plot(run, f, name);
}

/* ---- the run ---- */

static void record(sim *m, unsigned long long step)
{
	if (m->nrows < m->cap) {
		m->t[m->nrows] = (double)step;
		m->amp[m->nrows++] = amplitude(m);
	}
}

static int evolve(sim *m, int quiet, double *wall)
{
	lz_progress p;
	if (!quiet)
		lz_progress_begin(&p, "lattice-gas", (double)m->steps);
	double busy = 0.0;
	if (m->init == SHEAR)
		record(m, 0);
	for (unsigned long long step = 1; step <= m->steps; step++) {
		double t0 = lz_wall_now();
		lz_lgas_collide(m->g, m->table, m->rng->gsl);
		lz_lgas_propagate(m->g);
		busy += lz_wall_now() - t0;
		if (m->init == SHEAR && step % m->sample == 0)
			record(m, step);
		if (m->field && m->init != PULSE && step > m->steps - m->average)
			accumulate(m);
		if (!quiet)
			lz_progress_update(&p, (double)step);
	}
	if (!quiet)
		lz_progress_end(&p);
	if (m->init == PULSE)
		accumulate(m);
	*wall = busy > 0 ? busy : 1e-9;
	return LZ_OK;
}

/* The Cartesian momentum of the integer (sheared) one. */
static void cartesian(const sim *m, const int64_t p[2], double *px, double *py)
{
	*px = (double)p[0] + (is_fhp(m) ? 0.5 * (double)p[1] : 0.0);
	*py = (double)p[1] * row_h(m);
}

static int run(const lz_scene *s, lz_run *run)
{
	sim m = {0};
	int status = sim_init(&m, s);
	int64_t mass0 = 0, p0[2] = {0, 0}, mass1 = 0, p1[2] = {0, 0};
	double wall = 1e-9;
	if (status == LZ_OK) {
		lz_lgas_totals(m.g, &mass0, p0);
		status = evolve(&m, run->quiet, &wall);
		lz_lgas_totals(m.g, &mass1, p1);
	}
	int64_t dmass = mass1 - mass0, dp = llabs(p1[0] - p0[0]) + llabs(p1[1] - p0[1]);
	if (status == LZ_OK && dmass != 0)
		status = lz_error(LZ_EPHYS, "a lattice gas conserves particles exactly, but after "
		                  "%llu steps their number changed by %lld: a collision rule or the "
		                  "propagation loses or makes particles", m.steps, (long long)dmass);
	if (status == LZ_OK && dp != 0 && !m.obstacle)
		status = lz_error(LZ_EPHYS, "a lattice gas without walls conserves momentum exactly, "
		                  "but after %llu steps it changed by (%lld, %lld) in integer units: "
		                  "a collision rule does not keep the sum of the directions, or the "
		                  "propagation mixes them up", m.steps, (long long)(p1[0] - p0[0]),
		                  (long long)(p1[1] - p0[1]));
	if (status == LZ_OK) {
		lz_json *j = run->summary;
		double sx0, sy0, sx1, sy1, sites = (double)m.g->side * (double)m.g->side;
		cartesian(&m, p0, &sx0, &sy0);
		cartesian(&m, p1, &sx1, &sy1);
		lz_json_int(j, "particles", (long long)mass1);
		lz_json_int(j, "mass_change", (long long)dmass);
		lz_json_int(j, "momentum_change", (long long)dp);
		lz_json_num(j, "momentum_change_x", sx1 - sx0);
		lz_json_num(j, "momentum_change_y", sy1 - sy0);
		if (m.obstacle) {
			lz_json_int(j, "obstacle_sites", (long long)m.walls);
			lz_json_num(j, "obstacle_drag", -(sx1 - sx0) / (double)m.steps);
		}
		if (m.init == FLOW) {
			lz_json_num(j, "mean_velocity_x_start", sx0 / (double)mass0);
			lz_json_num(j, "mean_velocity_x_end", sx1 / (double)mass1);
		}
		if (m.init == SHEAR)
			status = decay(&m, run, j);
		if (status == LZ_OK && m.init == PULSE)
			status = front(&m, run, j);
		lz_json_num(j, "site_updates_per_s", sites * (double)m.steps / wall);
		lz_json_int(j, "state_bytes_per_site", 2);
	}
	if (status == LZ_OK && m.init == PULSE)
		status = write_blocks(&m, run, 0);
	if (status == LZ_OK && m.field)
		status = write_blocks(&m, run, 1);
	if (status == LZ_OK && m.obstacle)
		status = write_obstacle(&m, run);
	if (status == LZ_OK)
		status = write_plot(&m, run);
	sim_free(&m);
	return status;
}

/* The table after a run (run_table.h). */
static const lz_headline headline[] = {
	{.key = "mass_change"}, {.key = "momentum_change"},
	{.key = "viscosity", .ref = "viscosity_theory"}, {.key = "front_anisotropy"},
	{.key = "obstacle_drag"}, {NULL},
};
static const lz_speed speed[] = {{"site_updates_per_s", "site updates/s"}, {NULL}};

const lz_method lz_method_lattice_gas = {
	LZ_METHOD_KEYS("lattice-gas", keys),
	.help = "HPP and FHP lattice gases: propagation by masks, collisions by table; "
	        "exact conservation, shear-wave viscosity, pulse isotropy, flow past obstacles",
	.check = check,
	.run = run,
	.headline = headline,
	.speed = speed,
};
