/* walk_check.c — the box precondition and the replayed sweep of walk_check.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>

#include "lztest.h"
#include "walk_check.h"

static int64_t metric(lz_lattice_kind kind, int64_t x, int64_t y, int64_t z)
{
	if (kind == LZ_LATTICE_TRIANGULAR)
		return x * x + x * y + y * y;
	return x * x + y * y + z * z;
}

/* x mod L in (-L/2, L/2], by division (the tests' way, not the mask's). */
static int64_t nearest_component(int64_t x, int64_t L)
{
	int64_t u = (x % L + L) % L;
	return 2 * u > L ? u - L : u;
}

int64_t wc_near_d2(lz_lattice_kind kind, int64_t L, const int32_t *p, const int32_t *q)
{
	int64_t x = (int64_t)p[0] - q[0], y = (int64_t)p[1] - q[1];
	if (kind != LZ_LATTICE_TRIANGULAR) {
		int64_t z = lz_lattice_dim(kind) == 3 ? (int64_t)p[2] - q[2] : 0;
		/* Square and cubic metrics separate: each component's nearest image. */
		return metric(kind, nearest_component(x, L), nearest_component(y, L),
		              nearest_component(z, L));
	}
	/* The rhombus: for differences in (-L, L) the nearest image is one box away at
	 * most (the rhombus is two equilateral triangles, covered by their corners'
	 * hexagons). */
	int64_t best = INT64_MAX;
	for (int a = -1; a <= 1; a++)
		for (int b = -1; b <= 1; b++) {
			int64_t d = metric(kind, x + a * L, y + b * L, 0);
			if (d < best)
				best = d;
		}
	return best;
}

/* The smallest distance² over the images a, b, c in -2..2 of a raw displacement in
 * [-L, L]: enough, since the nearest image of a reduced one is one box away. */
static int64_t brute_image(lz_lattice_kind kind, int64_t L, int64_t x, int64_t y, int64_t z)
{
	int three = lz_lattice_dim(kind) == 3;
	int64_t best = INT64_MAX;
	for (int a = -2; a <= 2; a++)
		for (int b = -2; b <= 2; b++)
			for (int c = three ? -2 : 0; c <= (three ? 2 : 0); c++) {
				int64_t d = metric(kind, x + a * L, y + b * L, three ? z + c * L : 0);
				if (d < best)
					best = d;
			}
	return best;
}

static void require_table(const lz_lattice_box *b)
{
	for (int32_t u = 0; u < b->side; u++) {
		int32_t want = 2 * (int64_t)u <= b->side ? u : u - b->side;
		LZ_REQUIRE(b->dc[u] == want, "precondition: the walkers' box of side %d has dc[%d] "
		           "= %d, but the nearest image of a masked difference %d is %d — fix "
		           "lz_lattice_dctable first (its own tests say how); walkers on a wrong "
		           "box cannot be judged", b->side, u, b->dc[u], u, want);
	}
}

/* Every displacement on a grid of spacing L/8 over [-L, L]^dim: it holds the far
 * corners of the rhombus, where the triangular table alone is wrong. */
static void require_min_image(const lz_lattice_box *b)
{
	int64_t L = b->side, s = L >= 8 ? L / 8 : 1, zs = b->dim == 3 ? s : 2 * L + 1;
	for (int64_t x = -L; x <= L; x += s)
		for (int64_t y = -L; y <= L; y += s)
			for (int64_t z = b->dim == 3 ? -L : 0; z <= L; z += zs) {
				int64_t want = brute_image(b->kind, L, x, y, z);
				int64_t got = lz_lattice_min_dist2(b, (int32_t)x, (int32_t)y, (int32_t)z);
				LZ_REQUIRE(got == want, "precondition: in the walkers' %s box of side %lld "
				           "the displacement (%lld, %lld, %lld) has nearest-image "
				           "distance² %lld, lz_lattice_min_dist2 says %lld — fix it first "
				           "(its own tests say how); overlaps cannot be judged with a wrong "
				           "distance", lz_lattice_name(b->kind), (long long)L, (long long)x,
				           (long long)y, (long long)z, (long long)want, (long long)got);
			}
}

void wc_require_box(const lz_walk *w)
{
	require_table(w->box);
	if (w->n >= 2)
		require_min_image(w->box);
}

wc_run *wc_run_new(lz_walk *w)
{
	wc_run *run = calloc(1, sizeof *run);
	size_t len = w->n * (size_t)w->dim;
	run->w = w;
	run->old = malloc(len * sizeof *run->old);
	run->cur = malloc(len * sizeof *run->cur);
	run->odir = malloc(w->n * sizeof *run->odir);
	return run;
}

void wc_run_free(wc_run *run)
{
	free(run->old);
	free(run->cur);
	free(run->odir);
	free(run);
}

/* The move particle k was offered, and what the rule says of it. */
typedef struct {
	int d;            /* the direction tried */
	int32_t to[3];    /* the wrapped new site */
	int row_ok;       /* between the walls */
	int64_t nearest;  /* the smallest distance² from `to` to another particle */
	size_t who;       /* ... to that particle */
} offer;

static offer judge(const wc_run *run, size_t k, int d)
{
	const lz_walk *w = run->w;
	int dim = w->dim;
	int64_t L = w->box->side;
	const int32_t step[3] = {w->dirs[d].x, w->dirs[d].y, w->dirs[d].z};
	offer o = {d, {0, 0, 0}, 0, INT64_MAX, 0};
	for (int c = 0; c < dim; c++)
		o.to[c] = (int32_t)((((int64_t)run->old[k * (size_t)dim + (size_t)c] + step[c]) % L +
		                     L) % L);
	o.row_ok = o.to[dim - 1] >= w->lo && o.to[dim - 1] <= w->hi;
	for (size_t j = 0; j < w->n; j++) {
		if (j == k)
			continue;
		int64_t d2 = wc_near_d2(w->box->kind, L, o.to, run->cur + j * (size_t)dim);
		if (d2 < o.nearest) {
			o.nearest = d2;
			o.who = j;
		}
	}
	return o;
}

static int same_site(const int32_t *a, const int32_t *b, int dim)
{
	for (int c = 0; c < dim; c++)
		if (a[c] != b[c])
			return 0;
	return 1;
}

static void fail_move(const wc_run *run, size_t k, const offer *o, int allowed, int stayed)
{
	const lz_walk *w = run->w;
	const int32_t *now = w->r + k * (size_t)w->dim;
	const char *why;
	if (allowed)
		why = stayed ? "the move creates no overlap (touching, d2 = σ², is allowed) and stays "
		               "between the walls, so it must be accepted" :
		               "it must end on the old site plus the step of its direction, wrapped "
		               "into the box (for the random walk: is the drawn direction stored in "
		               "dir[i] and used?)";
	else
		why = !o->row_ok ? "that row is outside the walls: the move must be rejected" :
		      "there it overlaps: the move must be rejected, leaving it where it was";
	ck_abort_msg("%s, %s sweep: particle %zu at (%d, %d, %d) was offered direction %d "
	             "(%d, %d, %d) to (%d, %d, %d) — row %d of the allowed %d .. %d, nearest "
	             "other particle %zu at distance² %lld, σ² = %lld — and ended at (%d, %d, "
	             "%d); %s", lz_lattice_name(w->box->kind),
	             w->motion == LZ_WALK_BALLISTIC ? "ballistic" : "random-walk", k,
	             run->old[k * (size_t)w->dim], run->old[k * (size_t)w->dim + 1],
	             w->dim == 3 ? run->old[k * (size_t)w->dim + 2] : 0, o->d, w->dirs[o->d].x,
	             w->dirs[o->d].y, w->dirs[o->d].z, o->to[0], o->to[1], o->to[2],
	             o->to[w->dim - 1], w->lo, w->hi, o->who, (long long)o->nearest,
	             (long long)w->sigma2, now[0], now[1], w->dim == 3 ? now[2] : 0, why);
}

/* Particle k against the rule; returns 1 if it moved. */
static int replay_one(wc_run *run, size_t k)
{
	lz_walk *w = run->w;
	int dim = w->dim;
	LZ_REQUIRE(w->dir[k] >= 0 && w->dir[k] < w->ndir, "after a sweep particle %zu has "
	           "direction %d, outside 0 .. %d", k, w->dir[k], w->ndir - 1);
	int ballistic = w->motion == LZ_WALK_BALLISTIC;
	offer o = judge(run, k, ballistic ? run->odir[k] : w->dir[k]);
	int allowed = o.row_ok && o.nearest >= w->sigma2;
	int32_t *now = w->r + k * (size_t)dim;
	int stayed = same_site(now, run->old + k * (size_t)dim, dim);
	if (!(allowed ? same_site(now, o.to, dim) : stayed))
		fail_move(run, k, &o, allowed, stayed);
	if (ballistic && allowed)
		LZ_REQUIRE(w->dir[k] == run->odir[k], "%s: ballistic particle %zu moved along "
		           "direction %d but then holds direction %d — a free flyer keeps its "
		           "direction; only a rejected move draws a new one",
		           lz_lattice_name(w->box->kind), k, run->odir[k], w->dir[k]);
	if (ballistic && !allowed) {
		run->rejected++;
		run->kept += w->dir[k] == run->odir[k];
	}
	if (!ballistic)
		run->tried[o.d]++;
	memcpy(run->cur + k * (size_t)dim, now, (size_t)dim * sizeof *now);
	return allowed;
}

size_t wc_sweep(wc_run *run, gsl_rng *rng)
{
	lz_walk *w = run->w;
	size_t len = w->n * (size_t)w->dim, moved = 0;
	memcpy(run->old, w->r, len * sizeof *run->old);
	memcpy(run->cur, w->r, len * sizeof *run->cur);
	memcpy(run->odir, w->dir, w->n * sizeof *run->odir);
	uint64_t moves = w->moves, accepted = w->accepted;
	size_t acc = lz_walk_sweep(w, rng);
	for (size_t k = 0; k < w->n; k++)
		moved += (size_t)replay_one(run, k);
	LZ_REQUIRE(acc == moved, "%s: lz_walk_sweep returned %zu accepted moves, but %zu "
	           "particles moved", lz_lattice_name(w->box->kind), acc, moved);
	LZ_REQUIRE(w->moves == moves + w->n && w->accepted == accepted + acc, "%s: one sweep of "
	           "%zu particles with %zu accepted moves took the counters moves/accepted from "
	           "%llu/%llu to %llu/%llu — every offer counts in moves, every success in "
	           "accepted", lz_lattice_name(w->box->kind), w->n, acc, (unsigned long long)moves,
	           (unsigned long long)accepted, (unsigned long long)w->moves,
	           (unsigned long long)w->accepted);
	return acc;
}

void wc_require_uniform_redraws(const wc_run *run, const char *what)
{
	double p = 1.0 / run->w->ndir, mean = (double)run->rejected * p;
	double sd = sqrt(mean * (1.0 - p));
	ck_assert_msg(run->rejected >= 100, "%s: only %ld ballistic collisions, too few to judge "
	              "the redraws", what, run->rejected);
	/* A binomial count: 5 standard deviations is a false alarm once in 10^6 runs. */
	ck_assert_msg(fabs((double)run->kept - mean) < 5.0 * sd, "%s: after %ld rejected "
	              "ballistic moves the new direction equalled the old one %ld times, expected "
	              "%.0f ± %.0f (1 in %d) — after a collision draw a fresh direction uniformly "
	              "from all %d, the old one included", what, run->rejected, run->kept, mean, sd,
	              run->w->ndir, run->w->ndir);
}

void wc_require_uniform_directions(const wc_run *run, const char *what)
{
	int nd = run->w->ndir;
	long total = 0;
	for (int d = 0; d < nd; d++)
		total += run->tried[d];
	double e = (double)total / nd, chi2 = 0;
	for (int d = 0; d < nd; d++)
		chi2 += ((double)run->tried[d] - e) * ((double)run->tried[d] - e) / e;
	double p = gsl_cdf_chisq_Q(chi2, nd - 1);
	ck_assert_msg(total >= 20L * nd && p > 1e-4, "%s: the random walk offered %ld moves over "
	              "%d directions with chi² = %.1f (p = %.2g; direction 0 %ld times, the last "
	              "%ld, %.0f expected each) — draw gsl_rng_uniform_int(rng, ndir) afresh "
	              "before every move", what, total, nd, chi2, p, run->tried[0],
	              run->tried[nd - 1], e);
}
