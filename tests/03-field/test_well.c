/* test_well.c — the square-well attraction. Fields and wells come from stage03.h's
 * fixtures (painted by brute force, the Metropolis table from its definition), so
 * the table test pays for lz_well_table alone, the ΔN test for lz_well_delta alone,
 * and the move tests for lz_field_try_move (with the hard-core test, ΔN and the step
 * it calls). The table against its definition; ΔN against a brute-force count of the
 * partners within rw for every particle and every step (the widest well a box allows
 * included); every trial of a long Metropolis walk against the rule (refused without
 * a draw when the hard cores forbid it, accepted without a draw when no partner is
 * lost, else accepted iff one u < e^{ε ΔN / kT}) with the well field and the energy
 * kept exact; the same for hand-made set-ups at the box edge and for particles so
 * small that their own shapes do not cover the neighbour site; the acceptance
 * frequency of steps that lose partners; and detailed balance for two particles: the
 * time they spend inside each other's well against the exact Boltzmann weight. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/well.h"
#include "stage03.h"

/* The number of centres other than `skip` within rw of point p (minimum image,
 * d2 < rw²): a particle's partners if it sat at p. */
static int bf_partners(const lz_field *f, const int32_t *p, size_t skip, double rw2)
{
	int n = 0;
	for (size_t j = 0; j < f->n; j++) {
		int32_t q[3];
		bf_centre(f, j, q);
		n += j != skip && (double)bf_min_d2(f->kind, f->side, p, q) < rw2;
	}
	return n;
}

/* The pairs with d2 < rw², over all pairs. */
static long bf_pairs(const lz_field *f, double rw2)
{
	long n = 0;
	for (size_t i = 0; i < f->n; i++) {
		int32_t p[3];
		bf_centre(f, i, p);
		n += bf_partners(f, p, i, rw2);
	}
	return n / 2;
}

/* Fail unless every well cell counts the centres within rw of its site. */
static void check_well_brute(const lz_field *f, const lz_well *w, const char *what)
{
	double rw2 = w->range * w->range;
	for (size_t s = 0; s < bf_box_sites(f); s++) {
		int32_t p[3];
		bf_site(f->dim, f->side, s, p);
		int want = bf_partners(f, p, f->n, rw2);
		int got = w->cell[lz_field_index(f, p[0], p[1], p[2])];
		LZ_REQUIRE(got == want, "%s: well cell (%d, %d, %d) holds %d, but %d centres lie "
		           "within rw = %g of it (%s): an accepted step must repaint the well "
		           "(+1 on the head points, -1 on the tail points of the WELL shape, from "
		           "the old centre)", what, p[0], p[1], p[2], got, want, w->range,
		           lz_lattice_name(f->kind));
	}
}

/* The direction whose step is (x, y, z). */
static int dir_of(const lz_field *f, int x, int y, int z)
{
	for (int d = 0; d < f->excl->ndir; d++) {
		lz_site e = f->excl->dirs[d];
		if (e.x == x && e.y == y && e.z == z)
			return d;
	}
	ck_abort_msg("no step (%d, %d, %d) on the %s lattice", x, y, z, lz_lattice_name(f->kind));
	return -1;
}

LZ_TEST(well_table_is_the_metropolis_rule)
{
	static const struct { double depth, T; } tc[] = {
		{1, 1}, {0.5, 2}, {2.5, 0.7}, {1, 1e-3}, {3, 40},
	};
	for (size_t c = 0; c < sizeof tc / sizeof tc[0]; c++) {
		lz_well w = {.depth = tc[c].depth, .temperature = tc[c].T};
		for (int k = 0; k < 2 * LZ_WELL_KMAX + 1; k++)
			w.accept[k] = NAN;
		lz_well_table(&w);
		for (int k = -LZ_WELL_KMAX; k <= LZ_WELL_KMAX; k++) {
			double a = w.accept[k + LZ_WELL_KMAX];
			double want = k >= 0 ? 1 : exp(tc[c].depth * k / tc[c].T);
			LZ_REQUIRE(fabs(a - want) <= 1e-12 * want + 1e-300, "depth %g, kT %g: the "
			           "acceptance of a step that changes the partner count by %d is %.17g; "
			           "Metropolis gives min(1, exp(depth·ΔN/kT)) = %.17g (a gain of "
			           "partners lowers the energy and is always accepted)", tc[c].depth,
			           tc[c].T, k, a, want);
			LZ_REQUIRE(k == -LZ_WELL_KMAX || w.accept[k + LZ_WELL_KMAX - 1] <= a, "depth %g, "
			           "kT %g: losing more partners must never be likelier (entry %d > "
			           "entry %d)", tc[c].depth, tc[c].T, k - 1, k);
		}
	}
	/* kT far above the depth: every step is accepted, the hard core alone remains. */
	lz_well hot = {.depth = 1, .temperature = 1e9};
	lz_well_table(&hot);
	ck_assert_msg(hot.accept[0] > 1 - 1e-6 && hot.accept[0] < 1, "depth 1, kT = 1e9: losing "
	              "all 255 partners should be accepted with probability exp(-2.55e-7), "
	              "got %.17g", hot.accept[0]);
	/* No depth, no attraction: a table of ones. */
	lz_well flat = {.depth = 0, .temperature = 0.1};
	lz_well_table(&flat);
	for (int k = 0; k < 2 * LZ_WELL_KMAX + 1; k++)
		LZ_REQUIRE(flat.accept[k] == 1, "depth 0: every entry must be exactly 1, entry %d "
		           "is %.17g", k - LZ_WELL_KMAX, flat.accept[k]);
}
END_TEST

LZ_TEST(well_delta_matches_pair_count)
{
	/* R = 0.5 on square8 with λ = 1.2: rw² = 1.44 does not reach the diagonal
	 * neighbour (d2 = 2), so self[d] = 0 for the diagonal steps, while the excluded
	 * shape (radius 1) leaves out even the axis neighbours. The last box holds the
	 * widest well it allows, 2 rw = L. */
	static const struct { lz_lattice_kind kind; int L; double R, lambda; size_t n; } dc[] = {
		{LZ_LATTICE_SQUARE, 32, 2, 1.5, 30}, {LZ_LATTICE_SQUARE8, 16, 0.5, 1.2, 60},
		{LZ_LATTICE_TRIANGULAR, 32, 1.5, 2, 40}, {LZ_LATTICE_TRIANGULAR, 16, 0.5, 3, 50},
		{LZ_LATTICE_CUBIC, 16, 1, 1.5, 60}, {LZ_LATTICE_CUBIC26, 16, 1.2, 1.3, 40},
		{LZ_LATTICE_SQUARE8, 8, 1, 2, 8},
	};
	gsl_rng *rng = lz_test_rng(41);
	for (size_t k = 0; k < sizeof dc / sizeof dc[0]; k++) {
		lz_field *f = bf_field_new(dc[k].kind, dc[k].L, dc[k].R);
		/* A particle on the corner, so that steps and wells cross the boundary. */
		bf_put(f, (lz_site){dc[k].L - 1, 0, dc[k].L - 1});
		brute_config(f, rng, dc[k].n);
		lz_well *w = bf_well_new(f, dc[k].lambda, 1, 1);
		double rw2 = w->range * w->range;
		for (size_t i = 0; i < f->n; i++)
			for (int d = 0; d < f->excl->ndir; d++) {
				int32_t c[3], t[3];
				bf_centre(f, i, c);
				lz_site e = f->excl->dirs[d];
				t[0] = c[0] + e.x;
				t[1] = c[1] + e.y;
				t[2] = c[2] + (f->dim == 3 ? e.z : 0);
				int before = bf_partners(f, c, i, rw2), after = bf_partners(f, t, i, rw2);
				int got = lz_well_delta(w, f, i, d);
				LZ_REQUIRE(got == after - before, "%s R = %g, rw = %g: particle %zu has %d "
				           "partners within rw and would have %d after the step (%d, %d, "
				           "%d), so ΔN = %d; lz_well_delta says %d (the cell at the centre "
				           "counts i itself; at the target it does only if the WELL shape's "
				           "self[d] = 1)", lz_lattice_name(f->kind), f->radius, w->range, i,
				           before, after, e.x, e.y, e.z, after - before, got);
			}
		lz_well_free(w);
		lz_field_free(f);
	}
	gsl_rng_free(rng);
}
END_TEST

/* Fail unless a try that reported `moved` left centre i at old + e (wrapped), and a
 * refused one left it at old. */
static void check_step(const lz_field *f, size_t i, const int32_t *old, lz_site e, int moved)
{
	int32_t c[3];
	bf_centre(f, i, c);
	int ez[3] = {e.x, e.y, e.z};
	for (int a = 0; a < f->dim; a++) {
		int32_t want = moved ? (int32_t)((old[a] + ez[a]) & f->mask) : old[a];
		LZ_REQUIRE(c[a] == want, "lz_field_try_move returned %d, but coordinate %d of "
		           "particle %zu went from %d to %d (1 means the particle stepped by (%d, "
		           "%d, %d), wrapped into the box, 0 that it stayed)", moved, a, i, old[a],
		           c[a], e.x, e.y, e.z);
	}
}

/* One lz_field_try_move(f, w, i, d) checked against the Metropolis rule, decided here
 * by brute force: refused without a draw when the step would bring i closer than σ
 * to another particle; accepted without a draw when no well or ΔN >= 0; otherwise
 * exactly one u = gsl_rng_uniform and accepted iff u < e^{ε ΔN / kT}. twin is a
 * scratch generator. Returns the case: 0 blocked, 1 sure, 2 uncertain. */
static int checked_try(lz_field *f, lz_well *w, size_t i, int d, gsl_rng *rng, gsl_rng *twin)
{
	lz_site e = f->excl->dirs[d];
	int32_t c[3], t[3];
	bf_centre(f, i, c);
	t[0] = c[0] + e.x;
	t[1] = c[1] + e.y;
	t[2] = c[2] + (f->dim == 3 ? e.z : 0);
	int blocked = bf_clashes(f, t, i), dN = 0;
	if (w) {
		double rw2 = w->range * w->range;
		dN = bf_partners(f, t, i, rw2) - bf_partners(f, c, i, rw2);
	}
	int kind = blocked ? 0 : w && dN < 0 ? 2 : 1;
	const char *with = w ? "with a well" : "without a well";
	gsl_rng_memcpy(twin, rng);
	int moved = lz_field_try_move(f, w, i, d, rng);
	if (kind == 0) {
		LZ_REQUIRE(moved == 0, "%s: particle %zu stepped by (%d, %d, %d) closer than σ to "
		           "another particle (%s): the hard core must refuse it",
		           lz_lattice_name(f->kind), i, e.x, e.y, e.z, with);
		LZ_REQUIRE(rng_same(rng, twin), "%s: a step the hard core refuses drew a random "
		           "number (%s): test lz_field_can_move first, draw only after it",
		           lz_lattice_name(f->kind), with);
	} else if (kind == 1) {
		LZ_REQUIRE(moved == 1, "%s: particle %zu, step (%d, %d, %d), ΔN = %d %s: the step is "
		           "free and loses no partner, it must be accepted", lz_lattice_name(f->kind),
		           i, e.x, e.y, e.z, dN, with);
		LZ_REQUIRE(rng_same(rng, twin), "%s: a step accepted for sure (ΔN = %d >= 0, or no "
		           "well) drew a random number: draw only when accept[ΔN] < 1",
		           lz_lattice_name(f->kind), dN);
	} else {
		double u = gsl_rng_uniform(twin), a = exp(w->depth * dN / w->temperature);
		LZ_REQUIRE(rng_same(rng, twin), "%s: a step losing %d partner(s) must draw exactly "
		           "one u = gsl_rng_uniform(rng), no more, no less", lz_lattice_name(f->kind),
		           -dN);
		LZ_REQUIRE(moved == (u < a), "%s: particle %zu, step (%d, %d, %d), ΔN = %d, depth "
		           "%g, kT %g: drew u = %g against exp(ε ΔN / kT) = %g, so the step should be "
		           "%s (is ΔN the partners at the target minus those at the centre?)",
		           lz_lattice_name(f->kind), i, e.x, e.y, e.z, dN, w->depth, w->temperature,
		           u, a, u < a ? "accepted" : "refused");
	}
	check_step(f, i, c, e, moved);
	return kind;
}

LZ_TEST(well_walk_keeps_field_and_energy_exact)
{
	static const struct {
		lz_lattice_kind kind; int L; double R, lambda; size_t n; double depth, T;
	} wc[] = {
		{LZ_LATTICE_TRIANGULAR, 32, 1.5, 1.5, 60, 1, 0.5},
		{LZ_LATTICE_SQUARE8, 16, 0.5, 1.2, 60, 1, 0.7},
		{LZ_LATTICE_CUBIC, 16, 1, 1.5, 80, 1, 1},
	};
	gsl_rng *rng = lz_test_rng(43), *twin = lz_test_rng(0);
	for (size_t k = 0; k < sizeof wc / sizeof wc[0]; k++) {
		lz_field *f = bf_field_new(wc[k].kind, wc[k].L, wc[k].R);
		brute_config(f, rng, wc[k].n);
		lz_well *w = bf_well_new(f, wc[k].lambda, wc[k].depth, wc[k].T);
		double rw2 = w->range * w->range;
		long seen[3] = {0, 0, 0};
		for (int block = 0; block < 4; block++) {
			for (int step = 0; step < 5000; step++) {
				size_t i = gsl_rng_uniform_int(rng, f->n);
				int d = (int)gsl_rng_uniform_int(rng, (unsigned long)f->excl->ndir);
				seen[checked_try(f, w, i, d, rng, twin)]++;
			}
			lz_well *fresh = bf_well_new(f, wc[k].lambda, wc[k].depth, wc[k].T);
			LZ_REQUIRE(memcmp(w->cell, fresh->cell, f->nsites) == 0, "%s: after %d "
			           "Metropolis trials the well field differs from one painted afresh "
			           "for the same centres (repaint the well by its head and tail points "
			           "from the OLD centre, on every accepted step and only then)",
			           lz_lattice_name(f->kind), 5000 * (block + 1));
			lz_well_free(fresh);
			check_field_exact(f, "Metropolis trials, against the centres painted afresh");
			long pairs = bf_pairs(f, rw2);
			double E = lz_well_energy(w, f);
			LZ_REQUIRE(E == -wc[k].depth * (double)pairs, "%s: the energy from the well "
			           "field is %g, but %ld pairs lie within rw = %g: E = -depth · pairs "
			           "= %g", lz_lattice_name(f->kind), E, pairs, w->range,
			           -wc[k].depth * (double)pairs);
		}
		/* The set-up itself: blocked, sure and uncertain trials all occur often. */
		ck_assert_msg(seen[0] > 500 && seen[1] > 1000 && seen[2] > 500, "%s: %ld blocked, "
		              "%ld sure and %ld uncertain trials", lz_lattice_name(f->kind), seen[0],
		              seen[1], seen[2]);
		check_well_brute(f, w, "after 20000 Metropolis trials");
		check_field_brute(f, "after 20000 Metropolis trials");
		lz_well_free(w);
		lz_field_free(f);
	}
	gsl_rng_free(rng);
	gsl_rng_free(twin);
}
END_TEST

/* Hand-made set-ups for single trials, with the box edge at x = 0.
 * Square, R = 1 (σ² = 4), λ = 2 (rw² = 16), L = 32: particle 0 at (0, 10) touches
 * particle 1 at (2, 10); particle 2 at (29, 10), across the edge, is in 0's well but
 * not after 0 steps +x, which the hard core forbids: a blocked step that would also
 * lose a partner. 0's step -x crosses the edge into exact contact with 2.
 * Square8, R = 1/2 (σ = 1), λ = 1.2 (rw² = 1.44), L = 8: the excluded shapes are
 * single sites (self = 0 for every step) while the wells cover the axis neighbours
 * but not the diagonal ones: 0 at (0, 0) touches 1 at (1, 0) and sits diagonally to
 * 2 at (7, 1); stepping onto 1 or 2 is refused although their cells hold 1. */
static const struct { lz_lattice_kind kind; int L; double R, lambda; lz_site p[3]; } setups[] = {
	{LZ_LATTICE_SQUARE, 32, 1, 2, {{0, 10, 0}, {2, 10, 0}, {29, 10, 0}}},
	{LZ_LATTICE_SQUARE8, 8, 0.5, 1.2, {{0, 0, 0}, {1, 0, 0}, {7, 1, 0}}},
};

/* One checked try of particle i along d on a fresh copy of set-up k, with a well
 * (depth = kT = 1) or none; afterwards the field and the well must be exact. */
static int try_setup(size_t k, size_t i, int d, int with_well, gsl_rng *rng, gsl_rng *twin)
{
	lz_field *f = bf_field_new(setups[k].kind, setups[k].L, setups[k].R);
	for (size_t j = 0; j < 3; j++)
		bf_put(f, setups[k].p[j]);
	lz_well *w = with_well ? bf_well_new(f, setups[k].lambda, 1, 1) : NULL;
	int kind = checked_try(f, w, i, d, rng, twin);
	check_field_brute(f, "one Metropolis trial");
	if (w)
		check_well_brute(f, w, "one Metropolis trial");
	lz_well_free(w);
	lz_field_free(f);
	return kind;
}

LZ_TEST(try_move_refuses_hard_core_without_a_draw)
{
	gsl_rng *rng = lz_test_rng(47), *twin = lz_test_rng(0);
	for (size_t k = 0; k < sizeof setups / sizeof setups[0]; k++) {
		int seen[3] = {0, 0, 0}, ndir;
		lz_lattice_dirs(setups[k].kind, &ndir);
		for (int rep = 0; rep < 4; rep++)
			for (int with_well = 0; with_well <= 1; with_well++)
				for (size_t i = 0; i < 3; i++)
					for (int d = 0; d < ndir; d++)
						seen[try_setup(k, i, d, with_well, rng, twin)]++;
		/* The set-up itself: blocked, sure and uncertain steps all occur. */
		ck_assert_msg(seen[0] > 0 && seen[1] > 0 && seen[2] > 0, "%s set-up: %d blocked, "
		              "%d sure, %d uncertain trials", lz_lattice_name(setups[k].kind),
		              seen[0], seen[1], seen[2]);
	}
	gsl_rng_free(rng);
	gsl_rng_free(twin);
}
END_TEST

/* Step particle 0 along `away` (losing partners) and back, `trials` times; the
 * number of accepted steps away. After each accepted step the field and the well
 * must be those of the configuration reached (painted afresh in `there`), and the
 * way back, which gains partners, must be accepted without a draw. */
static long out_and_back(lz_field *f, lz_well *w, int away, int back, long trials,
                         const lz_field *there, const lz_well *wthere, gsl_rng *rng,
                         gsl_rng *twin)
{
	uint8_t *cell0 = malloc(f->nsites), *well0 = malloc(f->nsites);
	ck_assert(cell0 != NULL && well0 != NULL);
	memcpy(cell0, f->cell, f->nsites);
	memcpy(well0, w->cell, f->nsites);
	size_t nfree0 = f->nfree;
	int32_t home[3], far[3];
	bf_centre(f, 0, home);
	bf_centre(there, 0, far);
	long accepted = 0;
	for (long t = 0; t < trials; t++) {
		if (!lz_field_try_move(f, w, 0, away, rng))
			continue;
		accepted++;
		int32_t c[3];
		bf_centre(f, 0, c);
		LZ_REQUIRE(c[0] == far[0] && c[1] == far[1], "the step away across the box edge "
		           "should bring particle 0 to (%d, %d), wrapped; it is at (%d, %d)", far[0],
		           far[1], c[0], c[1]);
		LZ_REQUIRE(memcmp(f->cell, there->cell, f->nsites) == 0 &&
		           memcmp(w->cell, wthere->cell, f->nsites) == 0, "after an accepted step "
		           "the field or the well differs from the new configuration painted afresh "
		           "(repaint the well from the OLD centre, then move)");
		LZ_REQUIRE(f->nfree == there->nfree, "after an accepted step nfree = %zu, but the "
		           "new configuration leaves %zu sites free (a move must keep nfree)",
		           f->nfree, there->nfree);
		gsl_rng_memcpy(twin, rng);
		LZ_REQUIRE(lz_field_try_move(f, w, 0, back, rng) == 1 && rng_same(rng, twin),
		           "the step back into the well gains partners (ΔN > 0): it must be "
		           "accepted, without a draw");
		bf_centre(f, 0, c);
		LZ_REQUIRE(c[0] == home[0] && c[1] == home[1] && memcmp(f->cell, cell0, f->nsites) == 0
		           && memcmp(w->cell, well0, f->nsites) == 0 && f->nfree == nfree0,
		           "out and back again, "
		           "particle 0 at (%d, %d) (from (%d, %d)): the field, nfree and the well "
		           "must be as before", c[0], c[1], home[0], home[1]);
	}
	free(cell0);
	free(well0);
	return accepted;
}

LZ_TEST(metropolis_acceptance_frequency)
{
	/* L = 16; particle 0 starts at the box edge and its step away crosses it.
	 * Square, R = 1 (σ² = 4), λ = 1.5 (rw² = 9): 0 at (0, 4) with a partner at
	 * (2, 4) steps -x and loses it (d2 9 is not below 9); at (0, 8) with partners at
	 * (2, 7) and (2, 9) it loses two (d2 5 -> 10).
	 * Square8, R = 1/2, λ = 1.2 (rw² = 1.44): 0 at (0, 4) touches its partner at
	 * (1, 4); the diagonal step (-1, -1) loses it (d2 1 -> 5), and so does the step -x
	 * (d2 1 -> 4). The well shape covers the axis step (self = 1) but not the diagonal
	 * one (self = 0), the excluded shape neither. */
	static const struct {
		lz_lattice_kind kind; double R, lambda; lz_site p[3]; size_t n; int ax, ay, dN;
		double depth, T;
	} mc[] = {
		{LZ_LATTICE_SQUARE, 1, 1.5, {{0, 4, 0}, {2, 4, 0}}, 2, -1, 0, -1, 1, 1},
		{LZ_LATTICE_SQUARE, 1, 1.5, {{0, 4, 0}, {2, 4, 0}}, 2, -1, 0, -1, 0.3, 1.5},
		{LZ_LATTICE_SQUARE, 1, 1.5, {{0, 8, 0}, {2, 7, 0}, {2, 9, 0}}, 3, -1, 0, -2, 0.4, 1},
		{LZ_LATTICE_SQUARE8, 0.5, 1.2, {{0, 4, 0}, {1, 4, 0}}, 2, -1, -1, -1, 1, 1},
		{LZ_LATTICE_SQUARE8, 0.5, 1.2, {{0, 4, 0}, {1, 4, 0}}, 2, -1, 0, -1, 0.5, 1},
	};
	const long trials = 20000;
	gsl_rng *rng = lz_test_rng(53), *twin = lz_test_rng(0);
	for (size_t k = 0; k < sizeof mc / sizeof mc[0]; k++) {
		lz_field *f = bf_field_new(mc[k].kind, 16, mc[k].R);
		lz_field *there = bf_field_new(mc[k].kind, 16, mc[k].R);
		for (size_t j = 0; j < mc[k].n; j++) {
			lz_site p = mc[k].p[j];
			bf_put(f, p);
			if (j == 0)
				p.x += mc[k].ax, p.y += mc[k].ay;
			bf_put(there, p);
		}
		lz_well *w = bf_well_new(f, mc[k].lambda, mc[k].depth, mc[k].T);
		lz_well *wthere = bf_well_new(there, mc[k].lambda, mc[k].depth, mc[k].T);
		int away = dir_of(f, mc[k].ax, mc[k].ay, 0), back = dir_of(f, -mc[k].ax, -mc[k].ay, 0);
		double rw2 = w->range * w->range;
		int32_t c[3], t[3];
		bf_centre(f, 0, c);
		bf_centre(there, 0, t);
		ck_assert(bf_partners(f, t, 0, rw2) - bf_partners(f, c, 0, rw2) == mc[k].dN);
		long acc = out_and_back(f, w, away, back, trials, there, wthere, rng, twin);
		double p = exp(mc[k].dN * mc[k].depth / mc[k].T);
		double sd = sqrt(trials * p * (1 - p));
		ck_assert_msg(fabs((double)acc - trials * p) < 4 * sd, "%s: a step (%d, %d) losing "
		              "%d partner(s) at depth %g, kT %g was accepted %ld times in %ld; "
		              "Metropolis gives exp(%g) = %.4f, i.e. %.0f ± %.0f (4 standard "
		              "deviations) — accept iff u < accept[ΔN + KMAX], ΔN counted without "
		              "the particle itself", lz_lattice_name(f->kind), mc[k].ax, mc[k].ay,
		              -mc[k].dN, mc[k].depth, mc[k].T, acc, trials,
		              mc[k].dN * mc[k].depth / mc[k].T, p, trials * p, 4 * sd);
		lz_well_free(w);
		lz_well_free(wthere);
		lz_field_free(f);
		lz_field_free(there);
	}
	gsl_rng_free(rng);
	gsl_rng_free(twin);
}
END_TEST

/* Two particles on the square lattice (R = 1, σ² = 4; λ = 2, rw² = 16; L = 16)
 * random-walk by Metropolis trials. Each relative offset p (minimum image) is
 * reached by L² placements, so at equilibrium the pair is in the well a fraction
 *     A e^{ε/kT} / (A e^{ε/kT} + B),
 * A the allowed offsets inside the well (σ² <= d2 < rw²), B those outside (d2 >= rw²).
 * Here A = 36, B = 211. The tolerance was measured: over seeds 1..100, with these
 * run lengths, the standard deviation of the measured fraction was 0.0025, 0.0030 and
 * 0.0012 for the three (ε, kT) below (their means within 1.5 standard errors of the
 * exact values); each tolerance is five of them. A sign error, a missing repaint or
 * a stale table moves the fraction by 0.1 or more. */
LZ_TEST(detailed_balance_two_particles)
{
	const int L = 16;
	int A = 0, B = 0;
	for (int y = 0; y < L; y++)
		for (int x = 0; x < L; x++) {
			int32_t o[3] = {0, 0, 0}, p[3] = {x, y, 0};
			int64_t d2 = bf_min_d2(LZ_LATTICE_SQUARE, L, o, p);
			A += d2 >= 4 && d2 < 16;
			B += d2 >= 16;
		}
	static const struct { double depth, T, tol; } bc[] = {
		{1.5, 1, 0.013}, {1, 0.5, 0.015}, {0, 1, 0.006},
	};
	gsl_rng *rng = lz_test_rng(59);
	for (size_t k = 0; k < sizeof bc / sizeof bc[0]; k++) {
		lz_field *f = bf_field_new(LZ_LATTICE_SQUARE, L, 1);
		bf_put(f, (lz_site){0, 0, 0});
		bf_put(f, (lz_site){8, 8, 0});
		lz_well *w = bf_well_new(f, 2, bc[k].depth, bc[k].T);
		const long burn = 20000, trials = 2000000;
		long inside = 0;
		for (long t = 0; t < burn + trials; t++) {
			size_t i = gsl_rng_uniform_int(rng, 2);
			lz_field_try_move(f, w, i, (int)gsl_rng_uniform_int(rng, 4), rng);
			/* Now and then the whole state: a cheap check on a 16² box. */
			if (t % 10000 == 0)
				check_field_exact(f, "during the two-particle run");
			if (t >= burn)
				inside += bf_min_d2(f->kind, L, f->r, f->r + 2) < 16;
		}
		double bz = A * exp(bc[k].depth / bc[k].T);
		double want = bz / (bz + B), got = (double)inside / (double)trials;
		ck_assert_msg(fabs(got - want) < bc[k].tol, "two particles, depth %g, kT %g: inside "
		              "each other's well %.4f of the time; detailed balance gives A e^{ε/kT} / "
		              "(A e^{ε/kT} + B) = %.4f ± %.3f with A = %d offsets inside the well and "
		              "B = %d outside (is the acceptance min(1, exp(+ε ΔN / kT)), and is the "
		              "well repainted on every accepted step?)", bc[k].depth, bc[k].T, got,
		              want, bc[k].tol, A, B);
		check_field_brute(f, "after the two-particle run");
		check_well_brute(f, w, "after the two-particle run");
		lz_well_free(w);
		lz_field_free(f);
	}
	gsl_rng_free(rng);
}
END_TEST
