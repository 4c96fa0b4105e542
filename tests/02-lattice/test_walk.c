/* test_walk.c — hard-disk walkers on lattices: dense runs replayed move by move against
 * the rule (walk_check.c: every move that creates no overlap accepted, every other one
 * rejected, distances by a brute-force search over the periodic images), a free walker
 * accepting every move with uniform direction statistics (detailed balance of the
 * random walk), hand-worked touching pairs and moves that end exactly at contact on
 * each lattice, ballistic flight, the periodic boundary, the smallest and the largest
 * box, and a jammed lattice that rejects everything. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/lattice.h"
#include "lz/walk.h"
#include "walk_check.h"

/* Squared distance by brute force: the smallest over the images a, b, c in -2..2
 * of the raw difference, with the lattice's own metric. */
static int64_t brute_d2(lz_lattice_kind kind, int64_t L, const int32_t *p, const int32_t *q)
{
	int three = kind >= LZ_LATTICE_CUBIC;
	int64_t best = INT64_MAX;
	for (int a = -2; a <= 2; a++)
		for (int b = -2; b <= 2; b++)
			for (int c = three ? -2 : 0; c <= (three ? 2 : 0); c++) {
				int64_t x = p[0] - q[0] + a * L, y = p[1] - q[1] + b * L;
				int64_t z = three ? p[2] - q[2] + c * L : 0;
				int64_t d2 = kind == LZ_LATTICE_TRIANGULAR ? x * x + x * y + y * y
				                                             : x * x + y * y + z * z;
				if (d2 < best)
					best = d2;
			}
	return best;
}

static lz_walk *make(lz_lattice_kind kind, int64_t L, double R, size_t n, lz_walk_motion m)
{
	lz_walk *w = lz_walk_alloc(kind, L, R, n, m);
	ck_assert_msg(w != NULL, "lz_walk_alloc(%s, L = %lld, R = %g, n = %zu): %s",
	              lz_lattice_name(kind), (long long)L, R, n, lz_error_message());
	wc_require_box(w);
	return w;
}

static void put(lz_walk *w, size_t i, int x, int y, int z, int d)
{
	LZ_REQUIRE(lz_walk_set(w, i, (lz_site){x, y, z}, d) == LZ_OK, "lz_walk_set(particle %zu, "
	           "(%d, %d, %d), direction %d) refused: %s", i, x, y, z, d, lz_error_message());
}

static int dir_index(const lz_walk *w, int x, int y, int z)
{
	for (int d = 0; d < w->ndir; d++)
		if (w->dirs[d].x == x && w->dirs[d].y == y && w->dirs[d].z == z)
			return d;
	ck_abort_msg("no direction (%d,%d,%d) on the %s lattice", x, y, z,
	             lz_lattice_name(w->box->kind));
	return -1;
}

/* The direction index of the wrapped step from old to new, -1 if none, -2 if none
 * and the particle did not move. */
static int step_of(const lz_walk *w, const int32_t *old, const int32_t *now)
{
	int32_t L = w->box->side, d[3] = {0, 0, 0};
	int moved = 0;
	for (int c = 0; c < w->dim; c++) {
		int32_t u = now[c] - old[c];
		if (u > L / 2)
			u -= L;
		if (u <= -L / 2)
			u += L;
		d[c] = u;
		moved |= u != 0;
	}
	if (!moved)
		return -2;
	for (int k = 0; k < w->ndir; k++)
		if (w->dirs[k].x == d[0] && w->dirs[k].y == d[1] && w->dirs[k].z == d[2])
			return k;
	return -1;
}

static void check_no_overlap(const lz_walk *w, int sweep)
{
	int64_t L = w->box->side;
	for (size_t i = 0; i < w->n; i++) {
		const int32_t *p = w->r + i * (size_t)w->dim;
		for (int c = 0; c < w->dim; c++)
			LZ_REQUIRE(p[c] >= 0 && p[c] < L, "%s, sweep %d: particle %zu has coordinate "
			           "%d outside [0, %lld): wrap the new site with & mask",
			           lz_lattice_name(w->box->kind), sweep, i, p[c], (long long)L);
		for (size_t j = 0; j < i; j++) {
			int64_t d2 = brute_d2(w->box->kind, L, p, w->r + j * (size_t)w->dim);
			LZ_REQUIRE(d2 >= w->sigma2, "%s, sweep %d: particles %zu and %zu overlap, "
			           "distance² %lld < σ² = %lld — a move was accepted without checking "
			           "the new site against every other particle (minimum image)",
			           lz_lattice_name(w->box->kind), sweep, j, i, (long long)d2,
			           (long long)w->sigma2);
		}
	}
}

/* A dense run, every sweep replayed against the rule (walk_check.c), no pair ever
 * overlapping; ballistic particles redraw uniformly after a collision. */
static void run_dense(lz_lattice_kind kind, int64_t L, double R, int spacing,
                      lz_walk_motion motion, int sweeps, int every)
{
	int per = (int)(L / spacing), dim = lz_lattice_dim(kind);
	size_t n = (size_t)per * (size_t)per * (size_t)(dim == 3 ? per : 1);
	lz_walk *w = make(kind, L, R, n, motion);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 2024);
	size_t i = 0;
	for (int a = 0; a < per; a++)
		for (int b = 0; b < per; b++)
			for (int c = 0; c < (dim == 3 ? per : 1); c++)
				put(w, i++, a * spacing, b * spacing, c * spacing,
				    (int)gsl_rng_uniform_int(rng, (unsigned long)w->ndir));
	check_no_overlap(w, 0);
	wc_run *run = wc_run_new(w);
	size_t total = 0;
	for (int s = 1; s <= sweeps; s++) {
		total += wc_sweep(run, rng);
		if (s % every == 0 || s == sweeps)
			check_no_overlap(w, s);
	}
	ck_assert_msg(total > 0 && total < (size_t)sweeps * n, "%s: %zu of %zu moves accepted in a "
	              "dense system — expected some accepted and some rejected",
	              lz_lattice_name(kind), total, (size_t)sweeps * n);
	if (motion == LZ_WALK_BALLISTIC)
		wc_require_uniform_redraws(run, lz_lattice_name(kind));
	else
		wc_require_uniform_directions(run, lz_lattice_name(kind));
	wc_run_free(run);
	gsl_rng_free(rng);
	lz_walk_free(w);
}

LZ_TEST(walk_moves_never_create_overlap)
{
	run_dense(LZ_LATTICE_SQUARE, 64, 3, 7, LZ_WALK_RANDOM, 200, 4);
	run_dense(LZ_LATTICE_SQUARE8, 64, 3, 7, LZ_WALK_BALLISTIC, 200, 4);
	run_dense(LZ_LATTICE_TRIANGULAR, 64, 3, 7, LZ_WALK_RANDOM, 200, 4);
	run_dense(LZ_LATTICE_TRIANGULAR, 32, 2.5, 5, LZ_WALK_BALLISTIC, 200, 4);
	run_dense(LZ_LATTICE_CUBIC, 32, 2, 5, LZ_WALK_RANDOM, 40, 10);
}
END_TEST

/* One walker alone: every move accepted; the step directions uniform (chi-square). */
static void free_walker(lz_lattice_kind kind, unsigned long seed)
{
	enum { SWEEPS = 60000 };
	lz_walk *w = make(kind, 16, 1, 1, LZ_WALK_RANDOM);
	put(w, 0, 15, 0, 15, 0);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, seed);
	long count[26] = {0};
	int32_t old[3];
	for (int s = 0; s < SWEEPS; s++) {
		memcpy(old, w->r, (size_t)w->dim * sizeof *old);
		size_t acc = lz_walk_sweep(w, rng);
		int st = step_of(w, old, w->r);
		LZ_REQUIRE(acc == 1 && st >= 0, "%s: a lone walker's move was %s at sweep %d "
		           "(returned %zu) — with no other particle every move is allowed; does "
		           "the overlap check skip the particle itself?", lz_lattice_name(kind),
		           st == -2 ? "rejected" : "not one lattice step", s, acc);
		LZ_REQUIRE(st == w->dir[0], "%s, sweep %d: the walker stepped along direction %d but "
		           "holds direction %d — the random walk stores its fresh draw in dir[i] and "
		           "moves along it", lz_lattice_name(kind), s, st, w->dir[0]);
		count[st]++;
	}
	ck_assert_msg(w->moves == SWEEPS && w->accepted == SWEEPS, "%s: counters moves = %llu, "
	              "accepted = %llu after %d accepted moves", lz_lattice_name(kind),
	              (unsigned long long)w->moves, (unsigned long long)w->accepted, SWEEPS);
	double expect = (double)SWEEPS / w->ndir, chi2 = 0;
	for (int d = 0; d < w->ndir; d++)
		chi2 += (count[d] - expect) * (count[d] - expect) / expect;
	double q = gsl_cdf_chisq_Q(chi2, w->ndir - 1);
	ck_assert_msg(q > 1e-4, "%s: the random walk's directions are not uniform: chi² = %.1f "
	              "for %d directions (p = %.2g; first counts %ld %ld %ld %ld of %.0f expected) "
	              "— draw a fresh direction with gsl_rng_uniform_int(rng, ndir) every step",
	              lz_lattice_name(kind), chi2, w->ndir, q, count[0], count[1], count[2],
	              count[3], expect);
	gsl_rng_free(rng);
	lz_walk_free(w);
}

LZ_TEST(walk_free_walker_uniform_directions)
{
	free_walker(LZ_LATTICE_SQUARE, 11);
	free_walker(LZ_LATTICE_SQUARE8, 12);
	free_walker(LZ_LATTICE_TRIANGULAR, 13);
	free_walker(LZ_LATTICE_CUBIC, 14);
}
END_TEST

/* Particle 0 at (10,10,10) touching particle 1 at (10,10,10) + t; every direction
 * tried once from the same start; `reject` lists the displacements that overlap. */
static void touching(lz_lattice_kind kind, double R, int tx, int ty, int tz,
                     const int (*reject)[3], int nreject)
{
	lz_walk *w = make(kind, 32, R, 2, LZ_WALK_RANDOM);
	for (int d = 0; d < w->ndir; d++) {
		put(w, 0, 10, 10, 10, 0);
		put(w, 1, 10 + tx, 10 + ty, 10 + tz, 0);
		lz_site s = w->dirs[d];
		int want = 1;
		for (int k = 0; k < nreject; k++)
			if (reject[k][0] == s.x && reject[k][1] == s.y && reject[k][2] == s.z)
				want = 0;
		uint64_t m0 = w->moves, a0 = w->accepted;
		int got = lz_walk_try_move(w, 0, d);
		int32_t *p = w->r, *q = w->r + w->dim;
		LZ_REQUIRE(got == want, "%s, R = %g, partner at (%d,%d,%d): the move (%d,%d,%d) "
		           "was %s; it should be %s (distance² after the move %lld, σ² = %lld; "
		           "touching, d2 = σ², is allowed)", lz_lattice_name(kind), R, tx, ty, tz,
		           s.x, s.y, s.z, got ? "accepted" : "rejected",
		           want ? "accepted" : "rejected",
		           (long long)(kind == LZ_LATTICE_TRIANGULAR
		                ? (int64_t)(tx - s.x) * (tx - s.x) + (int64_t)(tx - s.x) * (ty - s.y) +
		                  (int64_t)(ty - s.y) * (ty - s.y)
		                : (int64_t)(tx - s.x) * (tx - s.x) + (int64_t)(ty - s.y) * (ty - s.y) +
		                  (int64_t)(tz - s.z) * (tz - s.z)), (long long)w->sigma2);
		int32_t want0[3] = {10 + (want ? s.x : 0), 10 + (want ? s.y : 0), 10 + (want ? s.z : 0)};
		for (int c = 0; c < w->dim; c++) {
			LZ_REQUIRE(p[c] == want0[c], "%s: after a%s move (%d,%d,%d) particle 0 is at "
			           "coordinate %d = %d, want %d", lz_lattice_name(kind),
			           want ? "n accepted" : " rejected", s.x, s.y, s.z, c, p[c],
			           want0[c]);
			int32_t t[3] = {10 + tx, 10 + ty, 10 + tz};
			LZ_REQUIRE(q[c] == t[c], "%s: moving particle 0 changed particle 1",
			           lz_lattice_name(kind));
		}
		LZ_REQUIRE(w->moves == m0 + 1 && w->accepted == a0 + (uint64_t)want, "%s: the "
		           "counters moves/accepted went from %llu/%llu to %llu/%llu on one %s move",
		           lz_lattice_name(kind), (unsigned long long)m0, (unsigned long long)a0,
		           (unsigned long long)w->moves, (unsigned long long)w->accepted,
		           want ? "accepted" : "rejected");
	}
	lz_walk_free(w);
}

LZ_TEST(walk_touching_pair_rejects_exactly_overlaps)
{
	/* Square, R = 2, σ² = 16, partner 4 to the right: only +x overlaps (d2 9); ±y give
	 * 17. With diagonals (1,±1) give 10: rejected; (-1,±1) give 26. */
	static const int sq[][3] = {{1, 0, 0}};
	static const int sq8[][3] = {{1, 0, 0}, {1, 1, 0}, {1, -1, 0}};
	touching(LZ_LATTICE_SQUARE, 2, 4, 0, 0, sq, 1);
	touching(LZ_LATTICE_SQUARE8, 2, 4, 0, 0, sq8, 3);
	/* Touching on a diagonal: partner at (3,3), R = 2.1, σ² = ceil(17.64) = 18: the
	 * moves (1,0) and (0,1) give 13 < 18, rejected; (1,1) gives 8; others >= 25. */
	static const int sq8d[][3] = {{1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
	touching(LZ_LATTICE_SQUARE8, 2.1, 3, 3, 0, sq8d, 3);
	/* Triangular (sheared), R = 1, σ² = 4, partner at (2, 0): (1,0) → 1, (0,1) → 4-2+1 = 3
	 * and (1,-1) → 1+1+1 = 3 overlap; (-1,1) → 9-3+1 = 7, (-1,0) → 9, (0,-1) → 7 do not.
	 * The square metric would accept (0,1) (d2 5): the test tells the metrics apart. */
	static const int tri[][3] = {{1, 0, 0}, {0, 1, 0}, {1, -1, 0}};
	touching(LZ_LATTICE_TRIANGULAR, 1, 2, 0, 0, tri, 3);
	/* Cubic, R = 1.5, σ² = 9, partner at (0, 0, 3): only +z overlaps. */
	static const int cub[][3] = {{0, 0, 1}};
	touching(LZ_LATTICE_CUBIC, 1.5, 0, 0, 3, cub, 1);
	/* Moves that END exactly at contact, d2 = σ², must be accepted: the partner one
	 * step further away than touching, every move allowed. Square (5, 0), R = 2:
	 * +x ends at d2 16; square8 (4, 4), R = 2.1, σ² = 18: (1,1) ends at 18;
	 * triangular (3, 0), R = 1: (1,0) ends at 4; cubic (0, 0, 4), R = 1.5: +z at 9. */
	touching(LZ_LATTICE_SQUARE, 2, 5, 0, 0, NULL, 0);
	touching(LZ_LATTICE_SQUARE8, 2.1, 4, 4, 0, NULL, 0);
	touching(LZ_LATTICE_TRIANGULAR, 1, 3, 0, 0, NULL, 0);
	touching(LZ_LATTICE_CUBIC, 1.5, 0, 0, 4, NULL, 0);
	/* σ² = ceil((2R)²) = ceil(17.64) = 18 for R = 2.1: the integer d2 = 17 overlaps.
	 * Partner (5, 1): (1,0) ends at 17 and (1,1) at 16, rejected; (1,-1) at 20. */
	static const int sq8c[][3] = {{1, 0, 0}, {1, 1, 0}};
	touching(LZ_LATTICE_SQUARE8, 2.1, 5, 1, 0, sq8c, 2);
	/* Triangular partner (3, -1), d2 = 7: (1,-1) ends at (2, 0), contact, accepted;
	 * (1,0) ends at (2, -1), d2 = 4 - 2 + 1 = 3, rejected (the square metric says 5). */
	static const int tric[][3] = {{1, 0, 0}};
	touching(LZ_LATTICE_TRIANGULAR, 1, 3, -1, 0, tric, 1);
}
END_TEST

/* One ballistic sweep of a pair: particle 0 at (10,10) flies along f0 into particle 1
 * and must stay; particle 1 at p1 flies along f1 to a site exactly at contact with
 * particle 0 and must move there, keeping its direction. Returns particle 0's new
 * direction. */
static int blocked_pair(lz_walk *w, gsl_rng *rng, const int *f0, const int *p1, const int *f1)
{
	int d0 = dir_index(w, f0[0], f0[1], 0), d1 = dir_index(w, f1[0], f1[1], 0);
	put(w, 0, 10, 10, 0, d0);
	put(w, 1, p1[0], p1[1], 0, d1);
	uint64_t m0 = w->moves, a0 = w->accepted;
	size_t acc = lz_walk_sweep(w, rng);
	int qx = p1[0] + f1[0], qy = p1[1] + f1[1];
	LZ_REQUIRE(acc == 1 && w->r[0] == 10 && w->r[1] == 10 && w->r[2] == qx && w->r[3] == qy &&
	           w->dir[1] == d1, "%s, blocked ballistic pair: particle 0 flying (%d,%d) from "
	           "(10,10) into particle 1 must stay; particle 1 flying (%d,%d) from (%d,%d) ends "
	           "at (%d,%d), exactly at contact (d2 = σ² = %lld is allowed), and must move "
	           "there keeping its direction; got (%d,%d), (%d,%d), direction %d, %zu "
	           "accepted", lz_lattice_name(w->box->kind), f0[0], f0[1], f1[0], f1[1], p1[0],
	           p1[1], qx, qy, (long long)w->sigma2, w->r[0], w->r[1], w->r[2], w->r[3],
	           w->dir[1], acc);
	LZ_REQUIRE(w->moves == m0 + 2 && w->accepted == a0 + 1, "%s: a sweep of two offered "
	           "moves, one accepted, took the counters moves/accepted from %llu/%llu to "
	           "%llu/%llu", lz_lattice_name(w->box->kind), (unsigned long long)m0,
	           (unsigned long long)a0, (unsigned long long)w->moves,
	           (unsigned long long)w->accepted);
	LZ_REQUIRE(w->dir[0] >= 0 && w->dir[0] < w->ndir, "blocked ballistic particle: new "
	           "direction %d is not one of the %d", w->dir[0], w->ndir);
	return w->dir[0];
}

LZ_TEST(walk_ballistic_keeps_direction_until_blocked)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 77);
	/* A free flyer goes straight, wrapping, and keeps its direction. */
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE8,
	                                        LZ_LATTICE_TRIANGULAR, LZ_LATTICE_CUBIC};
	for (int k = 0; k < 4; k++) {
		lz_walk *w = make(kinds[k], 8, 1, 1, LZ_WALK_BALLISTIC);
		for (int d = 0; d < w->ndir; d++) {
			put(w, 0, 3, 4, 5, d);
			for (int s = 0; s < 20; s++) {
				int32_t old[3];
				memcpy(old, w->r, (size_t)w->dim * sizeof *old);
				LZ_REQUIRE(lz_walk_sweep(w, rng) == 1 && step_of(w, old, w->r) == d &&
				           w->dir[0] == d, "%s: a lone ballistic particle flying along "
				           "direction %d left it at sweep %d (now direction %d) — "
				           "ballistic motion keeps its direction until a collision",
				           lz_lattice_name(kinds[k]), d, s, w->dir[0]);
			}
		}
		lz_walk_free(w);
	}
	/* Blocked, square, R = 2 (σ² = 16): particle 0 at (10,10) flies +x into particle 1
	 * at (14,11) (the move ends at d2 = 10) and stays, drawing a new direction, uniform
	 * over all four; particle 1 flies -y to (14,10), exactly at contact (d2 = 16), and
	 * moves, keeping its direction. */
	lz_walk *w = make(LZ_LATTICE_SQUARE, 32, 2, 2, LZ_WALK_BALLISTIC);
	int seen[4] = {0, 0, 0, 0};
	for (int rep = 0; rep < 400; rep++)
		seen[blocked_pair(w, rng, (const int[]){1, 0}, (const int[]){14, 11},
		                  (const int[]){0, -1})]++;
	for (int d = 0; d < 4; d++)
		ck_assert_msg(seen[d] >= 60, "after a collision the new direction should be uniform "
		              "over the 4 directions: over 400 collisions direction (%d,%d) came %d "
		              "times (counts %d %d %d %d) — draw a fresh random direction after a "
		              "rejected move, do not keep, reverse or turn it", w->dirs[d].x,
		              w->dirs[d].y, seen[d], seen[0], seen[1], seen[2], seen[3]);
	lz_walk_free(w);
	/* The same on the triangular lattice, R = 1 (σ² = 4): particle 0 flies (1,0) to
	 * (11,10), d2 = 3 from particle 1 at (12,11); particle 1 flies (0,-1) to (12,10),
	 * d2 = 4 from particle 0: contact. */
	w = make(LZ_LATTICE_TRIANGULAR, 32, 1, 2, LZ_WALK_BALLISTIC);
	for (int rep = 0; rep < 20; rep++)
		blocked_pair(w, rng, (const int[]){1, 0}, (const int[]){12, 11}, (const int[]){0, -1});
	lz_walk_free(w);
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(walk_pair_across_periodic_boundary)
{
	/* L = 32, R = 3 (σ² = 36): particle 0 at x = 0, particle 1 at x = 26, touching
	 * through the boundary (distance 6). */
	lz_walk *w = make(LZ_LATTICE_SQUARE, 32, 3, 2, LZ_WALK_RANDOM);
	int mx = dir_index(w, -1, 0, 0), px = dir_index(w, 1, 0, 0);
	put(w, 0, 0, 5, 0, 0);
	put(w, 1, 26, 5, 0, 0);
	ck_assert_msg(lz_walk_try_move(w, 0, mx) == 0 && w->r[0] == 0, "particle 0 at x = 0 "
	              "moving to x = -1 ≡ 31 comes within 5 of particle 1 at x = 26 through the "
	              "periodic boundary (σ = 6): the move must be rejected — use the minimum "
	              "image of the difference");
	ck_assert_msg(lz_walk_try_move(w, 1, px) == 0 && w->r[2] == 26, "particle 1 at x = 26 "
	              "moving to 27 comes within 5 of particle 0 at x = 0 ≡ 32: must be rejected");
	ck_assert_msg(lz_walk_try_move(w, 0, px) == 1 && w->r[0] == 1, "particle 0 moving away "
	              "(+x) from its periodic neighbour must be accepted, to x = 1");
	ck_assert_msg(lz_walk_try_move(w, 1, mx) == 1 && w->r[2] == 25, "particle 1 moving away "
	              "(-x) must be accepted, to x = 25");
	/* Back towards each other through the boundary, x = 1 and 25 (8 apart): to 0 (7
	 * apart), then to 31, exactly at contact (6 apart: allowed), then 30 overlaps. */
	ck_assert_msg(lz_walk_try_move(w, 0, mx) == 1 && w->r[0] == 0, "particle 0 at x = 1 "
	              "moving to 0, 7 from its periodic neighbour at 25 (σ = 6): must be accepted");
	ck_assert_msg(lz_walk_try_move(w, 0, mx) == 1 && w->r[0] == 31, "particle 0 at x = 0 "
	              "moving to x = 31 ends exactly at contact with particle 1 at 25 (distance 6 "
	              "= σ, through the boundary): touching is allowed, the move must be accepted "
	              "and land on 31; it is at %d", w->r[0]);
	ck_assert_msg(lz_walk_try_move(w, 0, mx) == 0 && w->r[0] == 31, "particle 0 at x = 31 "
	              "moving to 30 comes within 5 of particle 1 at 25: must be rejected");
	ck_assert_msg(w->moves == 7 && w->accepted == 4, "7 moves offered, 4 accepted, but the "
	              "counters say moves = %llu, accepted = %llu — count every offer in moves, "
	              "every success in accepted", (unsigned long long)w->moves,
	              (unsigned long long)w->accepted);
	/* Wrapping of the new site itself: a particle at 0 moving -x lands at L - 1, and at
	 * L - 1 moving +x lands at 0 (not -1 or L). */
	put(w, 0, 0, 0, 0, 0);
	put(w, 1, 16, 16, 0, 0);
	int my = dir_index(w, 0, -1, 0);
	ck_assert_msg(lz_walk_try_move(w, 0, mx) == 1 && w->r[0] == 31 && w->r[1] == 0,
	              "from (0,0) the move (-1,0) must land on (31,0); got (%d,%d)", w->r[0],
	              w->r[1]);
	ck_assert_msg(lz_walk_try_move(w, 0, my) == 1 && w->r[0] == 31 && w->r[1] == 31,
	              "from (31,0) the move (0,-1) must land on (31,31); got (%d,%d)", w->r[0],
	              w->r[1]);
	ck_assert_msg(lz_walk_try_move(w, 0, px) == 1 && w->r[0] == 0,
	              "from x = 31 the move +x must wrap to x = 0; got %d", w->r[0]);
	lz_walk_free(w);
	/* Triangular: partner at (0, 30) ≡ (0, -2), R = 1: the move (1,-1) of particle 0 at
	 * the origin brings the difference to (1, 1): d2 = 1 + 1 + 1 = 3 < 4. */
	w = make(LZ_LATTICE_TRIANGULAR, 32, 1, 2, LZ_WALK_RANDOM);
	put(w, 0, 0, 0, 0, 0);
	put(w, 1, 0, 30, 0, 0);
	ck_assert_msg(lz_walk_try_move(w, 0, dir_index(w, 1, -1, 0)) == 0, "triangular lattice: "
	              "from (0,0) the move (1,-1) ends at distance² 3 from the partner at (0,30) "
	              "≡ (0,-2) through the boundary (σ² = 4): must be rejected");
	ck_assert_msg(lz_walk_try_move(w, 0, dir_index(w, -1, 1, 0)) == 1 && w->r[0] == 31 &&
	              w->r[1] == 1, "triangular: from (0,0) the move (-1,1) must be accepted and "
	              "land on (31,1); got (%d,%d)", w->r[0], w->r[1]);
	lz_walk_free(w);
}
END_TEST

/* Offer particle i the move (x, y) and require the outcome: moved to (wx, wy), or not. */
static void expect_move(lz_walk *w, size_t i, int x, int y, int accept, int32_t wx, int32_t wy,
                        const char *why)
{
	uint64_t m0 = w->moves, a0 = w->accepted;
	int got = lz_walk_try_move(w, i, dir_index(w, x, y, 0));
	int32_t *p = w->r + i * (size_t)w->dim;
	ck_assert_msg(got == accept && p[0] == wx && p[1] == wy, "%s, side %d: particle %zu "
	              "offered (%d,%d) was %s and is at (%d,%d); it must be %s at (%d,%d) — %s",
	              lz_lattice_name(w->box->kind), w->box->side, i, x, y,
	              got ? "accepted" : "rejected", p[0], p[1], accept ? "accepted" : "rejected",
	              wx, wy, why);
	ck_assert_msg(w->moves == m0 + 1 && w->accepted == a0 + (uint64_t)accept, "%s: one %s "
	              "move took the counters moves/accepted from %llu/%llu to %llu/%llu",
	              lz_lattice_name(w->box->kind), accept ? "accepted" : "rejected",
	              (unsigned long long)m0, (unsigned long long)a0,
	              (unsigned long long)w->moves, (unsigned long long)w->accepted);
}

/* The smallest box, L = 2 (mask 1, one image on each side is the same site), and the
 * largest, L = 65536, with pairs touching across the edge of the box. */
LZ_TEST(walk_smallest_and_largest_boxes)
{
	/* L = 2, R = 1/2, σ² = 1: partner at (1, 0) is both +x and -x of (0, 0). */
	lz_walk *w = make(LZ_LATTICE_SQUARE, 2, 0.5, 2, LZ_WALK_RANDOM);
	put(w, 0, 0, 0, 0, 0);
	put(w, 1, 1, 0, 0, 0);
	expect_move(w, 0, 1, 0, 0, 0, 0, "the site +x is the partner's (d2 = 0)");
	expect_move(w, 0, -1, 0, 0, 0, 0, "-x wraps to x = 1, the partner's site");
	expect_move(w, 0, 0, 1, 1, 0, 1, "(0,1) is at d2 = 2 from the partner");
	expect_move(w, 0, 0, 1, 1, 0, 0, "(0,1) + (0,1) wraps to (0,0), at contact (d2 = 1 = σ²)");
	lz_walk_free(w);
	/* L = 65536, R = 2, σ² = 16: (65535, 65535) and (3, 65535) touch through x = 0. */
	const int32_t T = LZ_LATTICE_SIDE_MAX - 1;
	w = make(LZ_LATTICE_SQUARE, LZ_LATTICE_SIDE_MAX, 2, 2, LZ_WALK_RANDOM);
	put(w, 0, T, T, 0, 0);
	put(w, 1, 3, T, 0, 0);
	expect_move(w, 0, 1, 0, 0, T, T, "+x wraps to x = 0, 3 from the partner at x = 3");
	expect_move(w, 0, -1, 0, 1, T - 1, T, "moving away to 5 from the partner");
	expect_move(w, 0, 1, 0, 1, T, T, "back to contact through the edge (d2 = 16 = σ²)");
	expect_move(w, 0, 0, 1, 1, T, 0, "+y wraps to y = 0; d2 = 4² + 1 from the partner");
	lz_walk_free(w);
	/* Triangular, L = 65536, R = 1, σ² = 4: (65535, 0) and (1, 65534) differ by
	 * (2, -2) through both edges: d2 = 4 - 4 + 4, contact. */
	w = make(LZ_LATTICE_TRIANGULAR, LZ_LATTICE_SIDE_MAX, 1, 2, LZ_WALK_RANDOM);
	put(w, 0, T, 0, 0, 0);
	put(w, 1, 1, T - 1, 0, 0);
	expect_move(w, 0, 1, 0, 0, T, 0, "(0, 0) differs from the partner by (1, -2): d2 = 3");
	expect_move(w, 0, 0, -1, 0, T, 0, "(65535, 65535) differs by (2, -1): d2 = 3");
	expect_move(w, 0, -1, 1, 1, T - 1, 1, "(65534, 1) differs by (3, -3): d2 = 9");
	expect_move(w, 0, 1, -1, 1, T, 0, "back to contact through both edges (d2 = 4 = σ²)");
	lz_walk_free(w);
}
END_TEST

LZ_TEST(walk_jammed_lattice_rejects_everything)
{
	/* Disks of R = 1 on every second site (touching neighbours, σ² = 4): every one-step
	 * move comes within distance² 1 or 2 of a neighbour. */
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE8,
	                                        LZ_LATTICE_TRIANGULAR};
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 5);
	for (int k = 0; k < 3; k++)
		for (int m = 0; m < 2; m++) {
			lz_walk *w = make(kinds[k], 16, 1, 64, m ? LZ_WALK_BALLISTIC : LZ_WALK_RANDOM);
			for (int i = 0; i < 64; i++)
				put(w, (size_t)i, 2 * (i % 8), 2 * (i / 8), 0, 0);
			wc_run *run = wc_run_new(w);
			for (int s = 0; s < 5; s++) {
				size_t acc = wc_sweep(run, rng);
				ck_assert_msg(acc == 0, "%s, %s: a jammed lattice of touching disks accepted "
				              "%zu moves in sweep %d — every move overlaps a neighbour",
				              lz_lattice_name(kinds[k]), m ? "ballistic" : "walk", acc, s);
			}
			for (int i = 0; i < 64; i++)
				LZ_REQUIRE(w->r[2 * i] == 2 * (i % 8) && w->r[2 * i + 1] == 2 * (i / 8),
				           "%s: jammed particle %d moved", lz_lattice_name(kinds[k]), i);
			ck_assert_msg(w->moves == 5 * 64 && w->accepted == 0, "%s: counters moves = %llu, "
			              "accepted = %llu after 5 sweeps of 64 rejected moves",
			              lz_lattice_name(kinds[k]), (unsigned long long)w->moves,
			              (unsigned long long)w->accepted);
			/* 320 collisions: a ballistic disk redraws after every one of them; a random
			 * walker tried every direction alike. */
			if (m)
				wc_require_uniform_redraws(run, lz_lattice_name(kinds[k]));
			else
				wc_require_uniform_directions(run, lz_lattice_name(kinds[k]));
			wc_run_free(run);
			lz_walk_free(w);
		}
	gsl_rng_free(rng);
}
END_TEST

/* A slit on every lattice: walls reject the steps that would leave rows lo .. hi —
 * including the sheared triangular step (1, -1) — and count them as offered moves. */
LZ_TEST(walk_slit_walls_reject_steps_out)
{
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_SQUARE8,
	                                        LZ_LATTICE_TRIANGULAR, LZ_LATTICE_CUBIC,
	                                        LZ_LATTICE_CUBIC26};
	for (int k = 0; k < 5; k++) {
		lz_walk *w = make(kinds[k], 32, 2, 1, LZ_WALK_RANDOM);
		ck_assert(lz_walk_set_slit(w, 12) == LZ_OK);
		int last = w->dim - 1;
		for (int side = 0; side < 2; side++) {
			int32_t row = side ? w->hi : w->lo;
			for (int d = 0; d < w->ndir; d++) {
				int32_t at[3] = {5, 5, 5};
				at[last] = row;
				put(w, 0, at[0], at[1], at[2], 0);
				int32_t step = last == 1 ? w->dirs[d].y : w->dirs[d].z;
				int out = side ? step > 0 : step < 0;
				uint64_t moves = w->moves, acc = w->accepted;
				int moved = lz_walk_try_move(w, 0, d);
				LZ_REQUIRE(moved == !out, "%s, slit rows %d .. %d: a lone disk in row %d "
				           "offered step (%d,%d,%d) %s — a step %s", lz_lattice_name(kinds[k]),
				           w->lo, w->hi, row, w->dirs[d].x, w->dirs[d].y, w->dirs[d].z,
				           moved ? "moved" : "stayed", out ? "through the wall must be "
				           "rejected (lz_walk_row_allowed)" : "along or away from the wall "
				           "is free");
				LZ_REQUIRE(w->moves == moves + 1 && w->accepted == acc + (uint64_t)moved,
				           "%s: a move stopped by a wall still counts as offered",
				           lz_lattice_name(kinds[k]));
			}
		}
		lz_walk_free(w);
	}
}
END_TEST

/* Dense disks in slits, walk and ballistic, 2D and 3D, every sweep replayed against
 * the rule: no centre ever leaves the allowed rows, no pair overlaps, and the walls
 * are not periodic. */
LZ_TEST(walk_slit_dense_run_stays_inside)
{
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE8, LZ_LATTICE_TRIANGULAR,
	                                        LZ_LATTICE_CUBIC};
	/* Packing about 0.35 of a 64 × 12 strip, 0.23 of a 32 × 32 × 9 slab. */
	static const int64_t sides[] = {64, 64, 32};
	static const size_t ns[] = {38, 38, 150};
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 77);
	for (int k = 0; k < 3; k++)
		for (int m = 0; m < 2; m++) {
			lz_walk *w = make(kinds[k], sides[k], 1.5, ns[k],
			                  m ? LZ_WALK_BALLISTIC : LZ_WALK_RANDOM);
			ck_assert(lz_walk_set_slit(w, k == 2 ? 9 : 12) == LZ_OK);
			ck_assert_msg(lz_walk_place(w, rng, 0) == LZ_OK, "%s", lz_error_message());
			uint64_t seen_lo = 0, seen_hi = 0;
			wc_run *run = wc_run_new(w);
			for (int s = 1; s <= 300; s++) {
				wc_sweep(run, rng);
				for (size_t i = 0; i < w->n; i++) {
					int32_t row = w->r[i * (size_t)w->dim + (size_t)w->dim - 1];
					LZ_REQUIRE(lz_walk_row_allowed(w, row), "%s, %s, sweep %d: particle %zu "
					           "is in row %d, outside the slit's rows %d .. %d",
					           lz_lattice_name(kinds[k]), m ? "ballistic" : "walk", s, i,
					           row, w->lo, w->hi);
					seen_lo += row == w->lo;
					seen_hi += row == w->hi;
				}
				if (s % 50 == 0)
					check_no_overlap(w, s);
			}
			ck_assert_msg(seen_lo > 0 && seen_hi > 0, "%s: no particle ever reached a wall row "
			              "in 300 sweeps", lz_lattice_name(kinds[k]));
			if (m)
				wc_require_uniform_redraws(run, lz_lattice_name(kinds[k]));
			else
				wc_require_uniform_directions(run, lz_lattice_name(kinds[k]));
			wc_run_free(run);
			lz_walk_free(w);
		}
	gsl_rng_free(rng);
}
END_TEST

/* Detailed balance at a wall: a lone random walker between walls visits every row
 * equally often. A rule that retries another direction after hitting the wall (or
 * bounces) starves or crowds the wall rows. */
LZ_TEST(walk_slit_lone_walker_profile_is_flat)
{
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_TRIANGULAR};
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 3);
	for (int k = 0; k < 2; k++) {
		lz_walk *w = make(kinds[k], 16, 1, 1, LZ_WALK_RANDOM);
		ck_assert(lz_walk_set_slit(w, 7.5) == LZ_OK);
		ck_assert(lz_walk_place(w, rng, 0) == LZ_OK);
		int rows = w->hi - w->lo + 1;
		uint64_t count[16] = {0};
		const long sweeps = 400000;
		wc_run *run = wc_run_new(w);
		for (long s = 0; s < sweeps; s++) {
			wc_sweep(run, rng);
			count[w->r[1] - w->lo]++;
		}
		wc_require_uniform_directions(run, lz_lattice_name(kinds[k]));
		wc_run_free(run);
		/* About rows² = 36 sweeps between independent rows: ~1e4 independent samples,
		 * so each row's share is known to about 3 %; 12 % is 4 of those. A retry rule
		 * shifts the wall rows by 25 % or more. */
		for (int c = 0; c < rows; c++) {
			double share = (double)count[c] * rows / (double)sweeps;
			ck_assert_msg(fabs(share - 1) < 0.12, "%s, slit rows %d .. %d: row %d is visited "
			              "%.3f times its fair share by a lone random walker — a move out "
			              "through a wall must simply be rejected, the walker staying where "
			              "it is", lz_lattice_name(kinds[k]), w->lo, w->hi, w->lo + c, share);
		}
		lz_walk_free(w);
	}
	gsl_rng_free(rng);
}
END_TEST
