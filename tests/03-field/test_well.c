/* test_well.c — the square-well attraction: the Metropolis table against its
 * definition, ΔN against a brute-force count of the partners within rw for every
 * particle and every step, a long Metropolis walk that keeps the well field and the
 * energy exact, no random number for a step the hard core refuses (or that is
 * accepted for sure), the acceptance frequency of steps that lose partners, and
 * detailed balance for two particles: the time they spend inside each other's well
 * against the exact Boltzmann weight of the relative offsets. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/well.h"
#include "stage03.h"

static lz_well *well_new(const lz_field *f, double lambda, double depth, double T)
{
	lz_well *w = lz_well_alloc(f, lambda, depth, T);
	ck_assert_msg(w != NULL, "lz_well_alloc(lambda = %g, depth = %g, T = %g): %s", lambda,
	              depth, T, lz_error_message());
	return w;
}

static const int32_t *centre(const lz_field *f, size_t i) { return f->r + i * (size_t)f->dim; }

/* The number of centres other than `skip` within rw of point p (minimum image,
 * d2 < rw²): a particle's partners if it sat at p. */
static int bf_partners(const lz_field *f, const int32_t *p, size_t skip, double rw2)
{
	int n = 0;
	for (size_t j = 0; j < f->n; j++)
		n += j != skip && (double)bf_min_d2(f->kind, f->side, p, centre(f, j)) < rw2;
	return n;
}

/* The pairs with d2 < rw², over all pairs. */
static long bf_pairs(const lz_field *f, double rw2)
{
	long n = 0;
	for (size_t i = 0; i < f->n; i++)
		for (size_t j = 0; j < i; j++)
			n += (double)bf_min_d2(f->kind, f->side, centre(f, i), centre(f, j)) < rw2;
	return n;
}

/* Fail unless every well cell counts the centres within rw of its site. */
static void check_well_brute(const lz_field *f, const lz_well *w, const char *what)
{
	double rw2 = w->range * w->range;
	for (size_t s = 0; s < f->nsites; s++) {
		int32_t p[3];
		bf_site(f->dim, f->side, s, p);
		int want = bf_partners(f, p, f->n, rw2);
		int got = w->cell[lz_field_index(f, p[0], p[1], p[2])];
		ck_assert_msg(got == want, "%s: well cell (%d, %d, %d) holds %d, but %d centres lie "
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

static int rng_same(const gsl_rng *a, const gsl_rng *b)
{
	return memcmp(gsl_rng_state(a), gsl_rng_state(b), gsl_rng_size(a)) == 0;
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
			ck_assert_msg(fabs(a - want) <= 1e-12 * want + 1e-300, "depth %g, kT %g: the "
			              "acceptance of a step that changes the partner count by %d is %.17g; "
			              "Metropolis gives min(1, exp(depth·ΔN/kT)) = %.17g (a gain of "
			              "partners lowers the energy and is always accepted)", tc[c].depth,
			              tc[c].T, k, a, want);
			if (k > -LZ_WELL_KMAX)
				ck_assert_msg(w.accept[k + LZ_WELL_KMAX - 1] <= a, "depth %g, kT %g: "
				              "losing more partners must never be likelier (entry %d > "
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
		ck_assert_msg(flat.accept[k] == 1, "depth 0: every entry must be exactly 1, entry "
		              "%d is %.17g", k - LZ_WELL_KMAX, flat.accept[k]);
}
END_TEST

LZ_TEST(well_delta_matches_pair_count)
{
	/* R = 0.5 on square8 with λ = 1.2: rw² = 1.44 does not reach the diagonal
	 * neighbour (d2 = 2), so self[d] = 0 for the diagonal steps. */
	static const struct { lz_lattice_kind kind; int L; double R, lambda; size_t n; } dc[] = {
		{LZ_LATTICE_SQUARE, 32, 2, 1.5, 30}, {LZ_LATTICE_SQUARE8, 16, 0.5, 1.2, 60},
		{LZ_LATTICE_TRIANGULAR, 32, 1.5, 2, 40}, {LZ_LATTICE_TRIANGULAR, 16, 0.5, 3, 50},
		{LZ_LATTICE_CUBIC, 16, 1, 1.5, 60}, {LZ_LATTICE_CUBIC26, 16, 1.2, 1.3, 40},
	};
	gsl_rng *rng = rng_new(41);
	for (size_t k = 0; k < sizeof dc / sizeof dc[0]; k++) {
		lz_field *f = field_new(dc[k].kind, dc[k].L, dc[k].R);
		/* A particle on the corner, so that steps and wells cross the boundary. */
		place(f, (lz_site){dc[k].L - 1, 0, dc[k].L - 1});
		brute_config(f, rng, dc[k].n);
		lz_well *w = well_new(f, dc[k].lambda, 1, 1);
		check_well_brute(f, w, "a well painted by lz_well_alloc");
		double rw2 = w->range * w->range;
		for (size_t i = 0; i < f->n; i++)
			for (int d = 0; d < f->excl->ndir; d++) {
				const int32_t *c = centre(f, i);
				lz_site e = f->excl->dirs[d];
				int32_t t[3] = {c[0] + e.x, c[1] + e.y, f->dim == 3 ? c[2] + e.z : 0};
				int before = bf_partners(f, c, i, rw2), after = bf_partners(f, t, i, rw2);
				int got = lz_well_delta(w, f, i, d);
				ck_assert_msg(got == after - before, "%s R = %g, rw = %g: particle %zu has %d "
				              "partners within rw and would have %d after the step (%d, %d, "
				              "%d), so ΔN = %d; lz_well_delta says %d (the cell at the centre "
				              "counts i itself; at the target it does only if self[d] = 1)",
				              lz_lattice_name(f->kind), f->radius, w->range, i, before, after,
				              e.x, e.y, e.z, after - before, got);
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
	const int32_t *c = centre(f, i);
	int ez[3] = {e.x, e.y, e.z};
	for (int a = 0; a < f->dim; a++) {
		int32_t want = moved ? (int32_t)((old[a] + ez[a]) & f->mask) : old[a];
		ck_assert_msg(c[a] == want, "lz_field_try_move returned %d, but coordinate %d of "
		              "particle %zu went from %d to %d (1 means the particle stepped by (%d, "
		              "%d, %d), 0 that it stayed)", moved, a, i, old[a], c[a], e.x, e.y, e.z);
	}
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
	gsl_rng *rng = rng_new(43);
	for (size_t k = 0; k < sizeof wc / sizeof wc[0]; k++) {
		lz_field *f = field_new(wc[k].kind, wc[k].L, wc[k].R);
		brute_config(f, rng, wc[k].n);
		lz_well *w = well_new(f, wc[k].lambda, wc[k].depth, wc[k].T);
		double rw2 = w->range * w->range;
		long moved = 0;
		for (int block = 0; block < 4; block++) {
			for (int step = 0; step < 5000; step++) {
				size_t i = gsl_rng_uniform_int(rng, f->n);
				int d = (int)gsl_rng_uniform_int(rng, (unsigned long)f->excl->ndir);
				int32_t old[3];
				memcpy(old, centre(f, i), (size_t)f->dim * sizeof *old);
				int m = lz_field_try_move(f, w, i, d, rng);
				check_step(f, i, old, f->excl->dirs[d], m);
				moved += m;
			}
			lz_well *fresh = well_new(f, wc[k].lambda, wc[k].depth, wc[k].T);
			ck_assert_msg(memcmp(w->cell, fresh->cell, f->nsites) == 0, "%s: after %d "
			              "Metropolis trials the well field differs from one painted afresh "
			              "for the same centres (repaint the well by its head and tail points "
			              "from the OLD centre, on every accepted step and only then)",
			              lz_lattice_name(f->kind), 5000 * (block + 1));
			lz_well_free(fresh);
			long pairs = bf_pairs(f, rw2);
			double E = lz_well_energy(w, f);
			ck_assert_msg(E == -wc[k].depth * (double)pairs, "%s: the energy from the well "
			              "field is %g, but %ld pairs lie within rw = %g: E = -depth · pairs "
			              "= %g", lz_lattice_name(f->kind), E, pairs, w->range,
			              -wc[k].depth * (double)pairs);
		}
		ck_assert_msg(moved > 1000, "%s: only %ld of 20000 trials moved a particle",
		              lz_lattice_name(f->kind), moved);
		check_well_brute(f, w, "after 20000 Metropolis trials");
		check_field_brute(f, "after 20000 Metropolis trials");
		for (size_t i = 0; i < f->n; i++)
			for (size_t j = 0; j < i; j++)
				ck_assert_msg((double)bf_min_d2(f->kind, f->side, centre(f, i), centre(f, j)) >=
				              bf_sigma2(f->radius), "particles %zu and %zu overlap after "
				              "Metropolis trials: the hard core must be checked first", i, j);
		lz_well_free(w);
		lz_field_free(f);
	}
	gsl_rng_free(rng);
}
END_TEST

/* Square lattice, R = 1 (σ² = 4), λ = 2 (rw² = 16): particle 0 at (10, 10) touches
 * particle 1 at (12, 10); particle 2 at (7, 10) is in 0's well but not after 0 steps
 * +x, which the hard core forbids: a blocked step that would also lose a partner. */
static const lz_site trio[] = {{10, 10, 0}, {12, 10, 0}, {7, 10, 0}};
#define NTRIO (sizeof trio / sizeof trio[0])

/* One try of particle i along d on a fresh copy of the trio, with a well of the given
 * depth or none; checks the draws. Returns the kind of case seen: 0 blocked, 1 sure,
 * 2 uncertain (ΔN < 0 with a well). */
static int try_trio(size_t i, int d, int with_well, gsl_rng *rng, gsl_rng *twin)
{
	lz_field *f = field_new(LZ_LATTICE_SQUARE, 32, 1);
	for (size_t j = 0; j < NTRIO; j++)
		place(f, trio[j]);
	lz_well *w = with_well ? well_new(f, 2, 1, 1) : NULL;
	lz_site e = f->excl->dirs[d];
	const int32_t *c = centre(f, i);
	int32_t t[3] = {c[0] + e.x, c[1] + e.y, 0}, old[3] = {c[0], c[1], 0};
	int blocked = 0;
	for (size_t j = 0; j < f->n; j++)
		blocked |= j != i && (double)bf_min_d2(f->kind, f->side, t, centre(f, j)) < 4;
	int dN = bf_partners(f, t, i, 16) - bf_partners(f, c, i, 16);
	int kind = blocked ? 0 : with_well && dN < 0 ? 2 : 1;
	uint8_t *cell0 = malloc(f->nsites), *well0 = malloc(f->nsites);
	memcpy(cell0, f->cell, f->nsites);
	if (w)
		memcpy(well0, w->cell, f->nsites);
	gsl_rng_memcpy(twin, rng);
	int moved = lz_field_try_move(f, w, i, d, rng);
	const char *with = with_well ? "with a well" : "without a well";
	if (kind == 0) {
		ck_assert_msg(moved == 0, "particle %zu stepped by (%d, %d) into particle contact "
		              "closer than σ (%s): the hard core must refuse it", i, e.x, e.y, with);
		ck_assert_msg(rng_same(rng, twin), "a step the hard core refuses drew a random "
		              "number (%s): test lz_field_can_move first, draw only after it", with);
		ck_assert_msg(memcmp(cell0, f->cell, f->nsites) == 0 &&
		              (!w || memcmp(well0, w->cell, f->nsites) == 0), "a refused step "
		              "changed the field or the well (%s)", with);
	} else if (kind == 1) {
		ck_assert_msg(moved == 1, "particle %zu, step (%d, %d), ΔN = %d %s: the step is "
		              "free and gains no energy, it must be accepted", i, e.x, e.y, dN, with);
		ck_assert_msg(rng_same(rng, twin), "a step accepted for sure (ΔN = %d >= 0, or no "
		              "well) drew a random number: draw only when accept[ΔN] < 1", dN);
	} else {
		double u = gsl_rng_uniform(twin);
		ck_assert_msg(rng_same(rng, twin), "a step losing %d partner(s) must draw exactly "
		              "one u = gsl_rng_uniform(rng), no more, no less", -dN);
		ck_assert_msg(moved == (u < exp(dN)), "particle %zu, ΔN = %d, depth = kT = 1: drew "
		              "u = %g against exp(ΔN) = %g, so the step should be %s", i, dN, u,
		              exp(dN), u < exp(dN) ? "accepted" : "refused");
	}
	check_step(f, i, old, e, moved);
	free(cell0);
	free(well0);
	lz_well_free(w);
	lz_field_free(f);
	return kind;
}

LZ_TEST(try_move_refuses_hard_core_without_a_draw)
{
	gsl_rng *rng = rng_new(47), *twin = rng_new(0);
	int seen[3] = {0, 0, 0};
	for (int rep = 0; rep < 4; rep++)
		for (int with_well = 0; with_well <= 1; with_well++)
			for (size_t i = 0; i < NTRIO; i++)
				for (int d = 0; d < 4; d++)
					seen[try_trio(i, d, with_well, rng, twin)]++;
	/* The set-up itself: blocked, sure and uncertain steps all occur. */
	ck_assert(seen[0] > 0 && seen[1] > 0 && seen[2] > 0);
	gsl_rng_free(rng);
	gsl_rng_free(twin);
}
END_TEST

/* Step particle 0 along `away` (losing partners) and back, `trials` times; the
 * number of accepted steps away. The way back gains partners: always accepted. */
static long out_and_back(lz_field *f, lz_well *w, int away, int back, long trials,
                         gsl_rng *rng)
{
	long accepted = 0;
	for (long t = 0; t < trials; t++)
		if (lz_field_try_move(f, w, 0, away, rng)) {
			accepted++;
			ck_assert_msg(lz_field_try_move(f, w, 0, back, rng) == 1, "the step back into "
			              "the well gains partners (ΔN > 0): it must always be accepted");
		}
	return accepted;
}

LZ_TEST(metropolis_acceptance_frequency)
{
	/* Square, R = 1 (σ² = 4), λ = 1.5 (rw² = 9). Particle 0 steps -x: from (4, 4)
	 * with a partner at (6, 4), it loses one (d2 9 is not below 9); from (8, 8) with
	 * partners at (10, 7) and (10, 9), it loses two (d2 5 -> 10). */
	static const struct { lz_site p[3]; size_t n; int dN; double depth, T; } mc[] = {
		{{{4, 4, 0}, {6, 4, 0}}, 2, -1, 1, 1},
		{{{4, 4, 0}, {6, 4, 0}}, 2, -1, 0.3, 1.5},
		{{{8, 8, 0}, {10, 7, 0}, {10, 9, 0}}, 3, -2, 0.4, 1},
	};
	const long trials = 20000;
	gsl_rng *rng = rng_new(53);
	for (size_t k = 0; k < sizeof mc / sizeof mc[0]; k++) {
		lz_field *f = field_new(LZ_LATTICE_SQUARE, 16, 1);
		for (size_t j = 0; j < mc[k].n; j++)
			place(f, mc[k].p[j]);
		lz_well *w = well_new(f, 1.5, mc[k].depth, mc[k].T);
		int away = dir_of(f, -1, 0, 0), back = dir_of(f, 1, 0, 0);
		const int32_t *c = centre(f, 0);
		int32_t t[3] = {c[0] - 1, c[1], 0};
		ck_assert(bf_partners(f, t, 0, 9) - bf_partners(f, c, 0, 9) == mc[k].dN);
		long acc = out_and_back(f, w, away, back, trials, rng);
		double p = exp(mc[k].dN * mc[k].depth / mc[k].T);
		double sd = sqrt(trials * p * (1 - p));
		ck_assert_msg(fabs((double)acc - trials * p) < 4 * sd, "a step losing %d partner(s) "
		              "at depth %g, kT %g was accepted %ld times in %ld; Metropolis gives "
		              "exp(%g) = %.4f, i.e. %.0f ± %.0f (4 standard deviations) — accept iff "
		              "u < accept[ΔN + KMAX]", -mc[k].dN, mc[k].depth, mc[k].T, acc, trials,
		              mc[k].dN * mc[k].depth / mc[k].T, p, trials * p, 4 * sd);
		lz_well_free(w);
		lz_field_free(f);
	}
	gsl_rng_free(rng);
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
	gsl_rng *rng = rng_new(59);
	for (size_t k = 0; k < sizeof bc / sizeof bc[0]; k++) {
		lz_field *f = field_new(LZ_LATTICE_SQUARE, L, 1);
		place(f, (lz_site){0, 0, 0});
		place(f, (lz_site){8, 8, 0});
		lz_well *w = well_new(f, 2, bc[k].depth, bc[k].T);
		const long burn = 20000, trials = 2000000;
		long inside = 0;
		for (long t = 0; t < burn + trials; t++) {
			size_t i = gsl_rng_uniform_int(rng, 2);
			lz_field_try_move(f, w, i, (int)gsl_rng_uniform_int(rng, 4), rng);
			if (t >= burn)
				inside += bf_min_d2(f->kind, L, centre(f, 0), centre(f, 1)) < 16;
		}
		double bz = A * exp(bc[k].depth / bc[k].T);
		double want = bz / (bz + B), got = (double)inside / (double)trials;
		ck_assert_msg(fabs(got - want) < bc[k].tol, "two particles, depth %g, kT %g: inside "
		              "each other's well %.4f of the time; detailed balance gives A e^{ε/kT} / "
		              "(A e^{ε/kT} + B) = %.4f ± %.3f with A = %d offsets inside the well and "
		              "B = %d outside (is the acceptance min(1, exp(+ε ΔN / kT)), and is the "
		              "well repainted on every accepted step?)", bc[k].depth, bc[k].T, got,
		              want, bc[k].tol, A, B);
		lz_well_free(w);
		lz_field_free(f);
	}
	gsl_rng_free(rng);
}
END_TEST
