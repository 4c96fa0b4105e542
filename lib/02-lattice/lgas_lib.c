/* lgas_lib.c — the library half of lz/lgas.h: allocation, initial states, totals. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/bits.h"
#include "lz/error.h"
#include "lz/lattice.h"
#include "lz/lgas.h"

const char *lz_lgas_model_name(lz_lgas_model model)
{
	return model == LZ_LGAS_HPP ? "hpp" : model == LZ_LGAS_FHP ? "fhp" : "?";
}

int lz_lgas_parse(const char *name, lz_lgas_model *model)
{
	if (name && strcmp(name, "hpp") == 0)
		*model = LZ_LGAS_HPP;
	else if (name && strcmp(name, "fhp") == 0)
		*model = LZ_LGAS_FHP;
	else
		return lz_error(LZ_EINVAL, "lattice-gas model '%s' is not one of hpp|fhp",
		                name ? name : "(null)");
	return LZ_OK;
}

lz_lattice_kind lz_lgas_lattice(lz_lgas_model model)
{
	return model == LZ_LGAS_HPP ? LZ_LATTICE_SQUARE : LZ_LATTICE_TRIANGULAR;
}

lz_lgas *lz_lgas_alloc(lz_lgas_model model, int64_t side)
{
	if (model != LZ_LGAS_HPP && model != LZ_LGAS_FHP)
		return lz_error(LZ_EINVAL, "lattice-gas model %d is not hpp (0) or fhp (1)",
		                (int)model), NULL;
	if (side < 2)
		return lz_error(LZ_EINVAL, "lattice-gas size = %lld must be a power of two in "
		                "[2, %d]", (long long)side, LZ_LGAS_SIDE_MAX), NULL;
	if (lz_check_pow2("lattice-gas size", (uint64_t)side, LZ_LGAS_SIDE_MAX) != LZ_OK)
		return NULL;
	lz_lgas *g = calloc(1, sizeof *g);
	size_t n = (size_t)side * (size_t)side;
	if (g) {
		g->site = calloc(n, 1);
		g->next = calloc(n, 1);
	}
	if (!g || !g->site || !g->next) {
		lz_lgas_free(g);
		return lz_error(LZ_ENOMEM, "no memory for a lattice gas of %lld² sites",
		                (long long)side), NULL;
	}
	g->model = model;
	g->nbits = model == LZ_LGAS_FHP ? 6 : 4;
	g->side = (int32_t)side;
	g->mask = (int32_t)side - 1;
	g->shift = lz_log2_pow2((uint64_t)side);
	return g;
}

void lz_lgas_free(lz_lgas *g)
{
	if (!g)
		return;
	free(g->site);
	free(g->next);
	free(g);
}

/* The unit vector of direction k: k·60° (FHP) or k·90° (HPP). */
static void unit_dir(const lz_lgas *g, int k, double *cx, double *cy)
{
	double a = 2.0 * M_PI * k / g->nbits;
	*cx = cos(a);
	*cy = sin(a);
}

static int check_density(double d)
{
	if (!(d > 0.0 && d < 1.0))
		return lz_error(LZ_EINVAL, "lattice-gas density = %g per link is outside (0, 1): "
		                "a link holds at most one particle", d);
	return LZ_OK;
}

/* Fill site i (not a wall) with link probabilities p[k]. */
static void fill_site(lz_lgas *g, size_t i, const double *p, gsl_rng *rng)
{
	if (g->site[i] & LZ_LGAS_WALL)
		return;
	unsigned s = 0;
	for (int k = 0; k < g->nbits; k++)
		if (gsl_rng_uniform(rng) < p[k])
			s |= 1u << k;
	g->site[i] = (uint8_t)s;
}

int lz_lgas_init_uniform(lz_lgas *g, double d, gsl_rng *rng)
{
	if (check_density(d) != LZ_OK)
		return LZ_EINVAL;
	double p[6] = {d, d, d, d, d, d};
	size_t n = (size_t)g->side * (size_t)g->side;
	for (size_t i = 0; i < n; i++)
		fill_site(g, i, p, rng);
	return LZ_OK;
}

/* The linearised equilibrium d (1 + 2 c_k·u) is a probability for every direction
 * only when |u| <= 1/2 and d (1 + 2 |u|) < 1. */
static int check_velocity(const char *what, double d, double u0)
{
	if (check_density(d) != LZ_OK)
		return LZ_EINVAL;
	if (!(fabs(u0) <= 0.5 && d * (1.0 + 2.0 * fabs(u0)) < 1.0))
		return lz_error(LZ_EINVAL, "%s u0 = %g at density %g: the linearised equilibrium "
		                "d (1 + 2 c·u) must stay in [0, 1) for every direction; take |u0| <= "
		                "1/2 and |u0| < (1/d - 1)/2 = %g", what, u0, d, (1.0 / d - 1.0) / 2.0);
	return LZ_OK;
}

/* Fill every row y with the linearised equilibrium of the flow (u(y), 0). */
static void fill_flow(lz_lgas *g, double d, double u0, int wave, gsl_rng *rng)
{
	for (int32_t y = 0; y < g->side; y++) {
		double u = wave ? u0 * sin(2.0 * M_PI * y / g->side) : u0, p[6];
		for (int k = 0; k < g->nbits; k++) {
			double cx, cy;
			unit_dir(g, k, &cx, &cy);
			p[k] = d * (1.0 + 2.0 * cx * u);
		}
		for (int32_t x = 0; x < g->side; x++)
			fill_site(g, lz_lgas_index(g, x, y), p, rng);
	}
}

int lz_lgas_init_shear(lz_lgas *g, double d, double u0, gsl_rng *rng)
{
	if (check_velocity("shear-wave amplitude", d, u0) != LZ_OK)
		return LZ_EINVAL;
	fill_flow(g, d, u0, 1, rng);
	return LZ_OK;
}

int lz_lgas_init_flow(lz_lgas *g, double d, double u0, gsl_rng *rng)
{
	if (check_velocity("flow speed", d, u0) != LZ_OK)
		return LZ_EINVAL;
	fill_flow(g, d, u0, 0, rng);
	return LZ_OK;
}

int lz_lgas_init_pulse(lz_lgas *g, double d, double a, gsl_rng *rng)
{
	if (check_density(d) != LZ_OK)
		return LZ_EINVAL;
	if (!(a > -1.0 && d * (1.0 + a) < 1.0))
		return lz_error(LZ_EINVAL, "pulse amplitude a = %g at density %g: the pulse density "
		                "d (1 + a) = %g must be in (0, 1)", a, d, d * (1.0 + a));
	double in[6], out[6], r = g->side / 8.0, c = g->side / 2.0;
	for (int k = 0; k < 6; k++) {
		in[k] = d * (1.0 + a);
		out[k] = d;
	}
	int tri = g->model == LZ_LGAS_FHP;
	for (int32_t y = 0; y < g->side; y++)
		for (int32_t x = 0; x < g->side; x++) {
			/* Cartesian offset from the centre: sheared for FHP. */
			double dx = x - c, dy = y - c;
			double X = tri ? dx + 0.5 * dy : dx, Y = tri ? dy * sqrt(3.0) / 2.0 : dy;
			fill_site(g, lz_lgas_index(g, x, y), X * X + Y * Y <= r * r ? in : out, rng);
		}
	return LZ_OK;
}

void lz_lgas_set_wall(lz_lgas *g, int32_t x, int32_t y)
{
	g->site[lz_lgas_index(g, x, y)] |= LZ_LGAS_WALL;
}

void lz_lgas_position(const lz_lgas *g, int32_t x, int32_t y, double *X, double *Y)
{
	x &= g->mask;
	y &= g->mask;
	if (g->model != LZ_LGAS_FHP) {
		*X = x;
		*Y = y;
		return;
	}
	/* 2X is an integer: wrap it into [0, 2L) exactly. */
	int64_t twice = (2 * (int64_t)x + y - g->side / 2) % (2 * (int64_t)g->side);
	*X = 0.5 * (double)(twice < 0 ? twice + 2 * (int64_t)g->side : twice);
	*Y = y * (sqrt(3.0) / 2.0);
}

/* Mark a wall; 1 if the site was not one yet (on a tiny lattice the disk's box wraps
 * onto itself). */
static int mark_wall(lz_lgas *g, int32_t x, int32_t y)
{
	int fresh = !(g->site[lz_lgas_index(g, x, y)] & LZ_LGAS_WALL);
	lz_lgas_set_wall(g, x, y);
	return fresh;
}

int64_t lz_lgas_add_obstacle(lz_lgas *g, lz_lgas_obstacle kind, int64_t size)
{
	if (kind == LZ_LGAS_NO_OBSTACLE)
		return 0;
	if (kind != LZ_LGAS_PLATE && kind != LZ_LGAS_DISK)
		return lz_error(LZ_EINVAL, "obstacle kind %d is not a plate (1) or a disk (2)",
		                (int)kind), -1;
	int64_t max = lz_lgas_obstacle_max(g->side);
	if (size < 1 || size > max)
		return lz_error(LZ_EINVAL, "obstacle size = %lld sites is outside [1, %lld]: at most "
		                "half the side L = %d, so that the flow can pass", (long long)size,
		                (long long)max, (int)g->side), -1;
	int tri = g->model == LZ_LGAS_FHP;
	int32_t L = g->side, mid = L / 2;
	double X0 = L / 4.0, h = tri ? sqrt(3.0) / 2.0 : 1.0, shift;
	int64_t marked = 0;
	if (kind == LZ_LGAS_PLATE) {
		/* Row y's sites sit at X = x + shift (mod L): take the one nearest X0. Rows
		 * one apart differ by half a spacing in shift, so x steps by 0 or 1. */
		for (int32_t y = mid - (int32_t)(size / 2); y < mid - (int32_t)(size / 2) + size; y++) {
			shift = tri ? (y - mid) / 2.0 : 0.0;
			marked += mark_wall(g, (int32_t)floor(X0 - shift + 0.5), y);
		}
		return marked;
	}
	double r = size / 2.0;
	int32_t rows = (int32_t)ceil(r / h);
	for (int32_t y = mid - rows; y <= mid + rows; y++) {
		double dy = (y - mid) * h;
		shift = tri ? (y - mid) / 2.0 : 0.0;
		for (int32_t x = (int32_t)floor(X0 - shift - r) - 1; x <= (int32_t)ceil(X0 - shift + r) + 1;
		     x++) {
			double dx = x + shift - X0;
			if (dx * dx + dy * dy <= r * r)
				marked += mark_wall(g, x, y);
		}
	}
	return marked;
}

void lz_lgas_totals(const lz_lgas *g, int64_t *mass, int64_t p[2])
{
	int n;
	const lz_site *e = lz_lattice_dirs(lz_lgas_lattice(g->model), &n);
	/* Count the particles of each direction; then mass and momentum are sums. */
	int64_t count[6] = {0};
	size_t sites = (size_t)g->side * (size_t)g->side;
	for (size_t i = 0; i < sites; i++)
		for (int k = 0; k < n; k++)
			count[k] += (g->site[i] >> k) & 1u;
	*mass = 0;
	p[0] = p[1] = 0;
	for (int k = 0; k < n; k++) {
		*mass += count[k];
		p[0] += count[k] * e[k].x;
		p[1] += count[k] * e[k].y;
	}
}

int64_t lz_lgas_row_px2(const lz_lgas *g, int32_t y)
{
	int n;
	const lz_site *e = lz_lattice_dirs(lz_lgas_lattice(g->model), &n);
	int64_t count[6] = {0}, px2 = 0;
	const uint8_t *row = g->site + lz_lgas_index(g, 0, y);
	for (int32_t x = 0; x < g->side; x++)
		for (int k = 0; k < n; k++)
			count[k] += (row[x] >> k) & 1u;
	for (int k = 0; k < n; k++)
		px2 += count[k] * (g->model == LZ_LGAS_FHP ? 2 * e[k].x + e[k].y : 2 * e[k].x);
	return px2;
}
