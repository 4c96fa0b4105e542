/* test_lgas.c — the lattice gases' collision tables, propagation and collision step,
 * checked by invariants: mass and integer momentum of every table entry and of whole
 * lattices over many steps, free streaming (the particles' first moment advances by
 * the momentum), particle-hole symmetry, single particles followed by hand, full and
 * empty lattices with walls, bounce-back, independent chiralities. The tests of the
 * collision step use a table written out here, so that they judge lz_lgas_collide
 * apart from lz_lgas_table. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/bits.h"
#include "lz/lattice.h"
#include "lz/lgas.h"

/* ---- helpers computed another way: bit by bit from the direction tables ---- */

static const lz_site *dirs_of(lz_lgas_model model, int *n)
{
	return lz_lattice_dirs(model == LZ_LGAS_FHP ? LZ_LATTICE_TRIANGULAR : LZ_LATTICE_SQUARE,
	                       n);
}

/* Mass and integer momentum of one site state. */
static void site_moments(lz_lgas_model model, unsigned s, int *mass, int *px, int *py)
{
	int n;
	const lz_site *e = dirs_of(model, &n);
	*mass = *px = *py = 0;
	for (int k = 0; k < n; k++)
		if (s >> k & 1u) {
			++*mass;
			*px += e[k].x;
			*py += e[k].y;
		}
}

static const char *model_name(lz_lgas_model m) { return m == LZ_LGAS_FHP ? "FHP" : "HPP"; }

/* Whole-lattice totals by brute force (not lz_lgas_totals: the test's own count). */
static void totals(const lz_lgas *g, int64_t *mass, int64_t *px, int64_t *py)
{
	int n;
	const lz_site *e = dirs_of(g->model, &n);
	*mass = *px = *py = 0;
	for (size_t i = 0; i < (size_t)g->side * (size_t)g->side; i++)
		for (int k = 0; k < n; k++)
			if (g->site[i] >> k & 1u) {
				++*mass;
				*px += e[k].x;
				*py += e[k].y;
			}
}


static void fill_random(lz_lgas *g, double d, gsl_rng *r)
{
	for (size_t i = 0; i < (size_t)g->side * (size_t)g->side; i++) {
		unsigned s = 0;
		for (int k = 0; k < g->nbits; k++)
			if (gsl_rng_uniform(r) < d)
				s |= 1u << k;
		g->site[i] = (uint8_t)s;
	}
}

/* The collision rules of thesis 1.4 written out state by state (not by rotation
 * symmetry): every state unchanged but the HPP pair {0,2} <-> {1,3}; FHP head-on
 * pairs turning +60° (chirality 0) or -60° (1), the four-body states with a head-on
 * pair of holes turning like their holes, and the triples {0,2,4} <-> {1,3,5}. */
static void table_by_hand(lz_lgas_model model, uint8_t t[LZ_LGAS_TABLE_SIZE])
{
	for (unsigned i = 0; i < LZ_LGAS_TABLE_SIZE; i++)
		t[i] = (uint8_t)(i & 0x3Fu);
	for (unsigned c = 0; c < 2; c++) {
		if (model == LZ_LGAS_HPP) {
			t[c << 6 | 0x5] = 0xA;
			t[c << 6 | 0xA] = 0x5;
			continue;
		}
		static const unsigned pair[3] = {0x09, 0x12, 0x24}; /* {0,3}, {1,4}, {2,5} */
		for (int i = 0; i < 3; i++) {
			unsigned to = pair[(i + (c ? 2 : 1)) % 3];
			t[c << 6 | pair[i]] = (uint8_t)to;
			t[c << 6 | (0x3Fu & ~pair[i])] = (uint8_t)(0x3Fu & ~to);
		}
		t[c << 6 | 0x15] = 0x2A;
		t[c << 6 | 0x2A] = 0x15;
	}
}

/* ---- the collision tables ---- */

LZ_TEST(table_conserves_mass_and_momentum)
{
	for (int m = 0; m < 2; m++) {
		lz_lgas_model model = m ? LZ_LGAS_FHP : LZ_LGAS_HPP;
		int nstates = m ? 64 : 16;
		uint8_t t[LZ_LGAS_TABLE_SIZE];
		memset(t, 0xFF, sizeof t);
		lz_lgas_table(model, t);
		for (unsigned c = 0; c < 2; c++)
			for (unsigned s = 0; s < (unsigned)nstates; s++) {
				unsigned out = t[c << 6 | s];
				LZ_REQUIRE(out < (unsigned)nstates, "%s table[chirality %u][state %u] = "
				           "%u uses bits beyond the %d directions", model_name(model), c,
				           s, out, m ? 6 : 4);
				int m0, x0, y0, m1, x1, y1;
				site_moments(model, s, &m0, &x0, &y0);
				site_moments(model, out, &m1, &x1, &y1);
				LZ_REQUIRE(m0 == m1, "%s collision of state %u (chirality %u) -> %u: %d "
				           "particles in, %d out — a collision must conserve mass",
				           model_name(model), s, c, out, m0, m1);
				LZ_REQUIRE(x0 == x1 && y0 == y1, "%s collision of state %u (chirality %u) "
				           "-> %u: momentum (%d, %d) in sheared lattice units became "
				           "(%d, %d) — only head-on pairs and symmetric triples may turn",
				           model_name(model), s, c, out, x0, y0, x1, y1);
			}
	}
}
END_TEST

LZ_TEST(table_collides_head_on_pairs_and_triples)
{
	uint8_t t[LZ_LGAS_TABLE_SIZE];
	lz_lgas_table(LZ_LGAS_FHP, t);
	/* Head-on pairs turn by +60° for chirality 0 and -60° for chirality 1. */
	static const unsigned pair[3] = {0x09, 0x12, 0x24}; /* {0,3}, {1,4}, {2,5} */
	for (int i = 0; i < 3; i++) {
		ck_assert_msg(t[pair[i]] == pair[(i + 1) % 3] && t[64 | pair[i]] == pair[(i + 2) % 3],
		              "FHP head-on pair 0x%02x must turn by +60° (chirality 0) to 0x%02x and "
		              "by -60° (chirality 1) to 0x%02x; got 0x%02x and 0x%02x", pair[i],
		              pair[(i + 1) % 3], pair[(i + 2) % 3], t[pair[i]], t[64 | pair[i]]);
		unsigned q = 0x3Fu & ~pair[i];
		ck_assert_msg(t[q] == (0x3Fu & ~pair[(i + 1) % 3]), "FHP four-body state 0x%02x "
		              "(a head-on pair of holes) must turn like its holes, to 0x%02x; got "
		              "0x%02x (thesis 1.4: four-body collisions)", q,
		              0x3Fu & ~pair[(i + 1) % 3], t[q]);
	}
	for (unsigned c = 0; c < 2; c++)
		ck_assert_msg(t[c << 6 | 0x15] == 0x2A && t[c << 6 | 0x2A] == 0x15,
		              "FHP symmetric triples {0,2,4} = 0x15 and {1,3,5} = 0x2A must swap "
		              "(chirality %u); got 0x%02x and 0x%02x", c, t[c << 6 | 0x15],
		              t[c << 6 | 0x2A]);
	for (unsigned c = 0; c < 2; c++) {
		int changed = 0;
		for (unsigned s = 0; s < 64; s++)
			changed += t[c << 6 | s] != s;
		ck_assert_msg(changed == 3 + 3 + 2, "FHP changes 8 states per chirality (3 pairs, 3 "
		              "hole pairs, 2 triples); with chirality %u this table changes %d", c,
		              changed);
	}
	lz_lgas_table(LZ_LGAS_HPP, t);
	for (unsigned c = 0; c < 2; c++)
		for (unsigned s = 0; s < 16; s++) {
			unsigned want = s == 5 ? 10 : s == 10 ? 5 : s;
			ck_assert_msg(t[c << 6 | s] == want, "HPP state 0x%x (chirality %u) must become "
			              "0x%x; got 0x%x (only the head-on pairs {0,2} <-> {1,3} collide)",
			              s, c, want, t[c << 6 | s]);
		}
}
END_TEST

LZ_TEST(table_is_a_particle_hole_symmetric_permutation)
{
	for (int m = 0; m < 2; m++) {
		lz_lgas_model model = m ? LZ_LGAS_FHP : LZ_LGAS_HPP;
		unsigned nstates = m ? 64 : 16, full = nstates - 1;
		uint8_t t[LZ_LGAS_TABLE_SIZE];
		lz_lgas_table(model, t);
		for (unsigned c = 0; c < 2; c++) {
			int seen[64] = {0};
			for (unsigned s = 0; s < nstates; s++) {
				unsigned out = t[c << 6 | s] & 0x3Fu;
				LZ_REQUIRE(out < nstates && !seen[out], "%s table (chirality %u) is not a "
				           "permutation: state %u is reached twice — a collision rule "
				           "must be reversible", model_name(model), c, out);
				seen[out] = 1;
				unsigned hole = t[c << 6 | (full & ~s)];
				LZ_REQUIRE(hole == (full & ~out), "%s particle-hole symmetry (chirality "
				           "%u): collide(~0x%02x) = 0x%02x, but ~collide(0x%02x) = 0x%02x "
				           "— holes must collide like particles", model_name(model), c,
				           s, hole, s, full & ~out);
			}
		}
	}
}
END_TEST

/* ---- propagation ---- */

LZ_TEST(propagate_moves_one_particle_one_site)
{
	for (int m = 0; m < 2; m++) {
		lz_lgas_model model = m ? LZ_LGAS_FHP : LZ_LGAS_HPP;
		int n;
		const lz_site *e = dirs_of(model, &n);
		lz_lgas *g = lz_lgas_alloc(model, 8);
		ck_assert(g);
		for (int k = 0; k < n; k++) {
			/* From the middle and from every corner: the moves off an edge wrap. An
			 * empty wall site at (5, 2), off every path, must keep its bit. */
			static const int32_t starts[][2] = {{3, 4}, {0, 0}, {7, 7}, {0, 7}, {7, 0}};
			for (int st = 0; st < 5; st++) {
				memset(g->site, 0, 64);
				g->site[2 * 8 + 5] = LZ_LGAS_WALL;
				int32_t x = starts[st][0], y = starts[st][1];
				g->site[y * 8 + x] = (uint8_t)(1u << k);
				lz_lgas_propagate(g);
				int32_t wx = (x + e[k].x + 8) % 8, wy = (y + e[k].y + 8) % 8;
				for (int32_t i = 0; i < 64; i++) {
					unsigned want = (i == wy * 8 + wx ? 1u << k : 0u) |
					                (i == 2 * 8 + 5 ? LZ_LGAS_WALL : 0u);
					LZ_REQUIRE(g->site[i] == want, "%s, L = 8: a particle at (%d, %d) "
					           "moving in direction %d (%+d, %+d) must land on (%d, %d)"
					           "%s; site (%d, %d) holds 0x%02x, expected 0x%02x",
					           model_name(model), x, y, k, e[k].x, e[k].y, wx, wy,
					           st ? " (wrapped periodically)" : "", i % 8, i / 8,
					           g->site[i], want);
				}
			}
		}
		lz_lgas_free(g);
	}
}
END_TEST

LZ_TEST(propagate_returns_after_L_steps_and_keeps_walls)
{
	/* Free flight on a periodic ring of side L: after L steps every particle is home. */
	gsl_rng *r = lz_test_rng(7);
	for (int m = 0; m < 2; m++) {
		lz_lgas *g = lz_lgas_alloc(m ? LZ_LGAS_FHP : LZ_LGAS_HPP, 16);
		fill_random(g, 0.3, r);
		g->site[5] |= LZ_LGAS_WALL;
		uint8_t start[256];
		memcpy(start, g->site, 256);
		lz_lgas_propagate(g);
		ck_assert_msg(memcmp(start, g->site, 256) != 0, "%s: propagation changed nothing",
		              model_name(g->model));
		ck_assert_msg(g->site[5] & LZ_LGAS_WALL, "%s: the wall bit (0x80) of a site must "
		              "stay at its site during propagation", model_name(g->model));
		for (int s = 1; s < 16; s++)
			lz_lgas_propagate(g);
		for (int i = 0; i < 256; i++)
			LZ_REQUIRE(g->site[i] == start[i], "%s, L = 16: after 16 free-flight steps "
			           "site (%d, %d) holds 0x%02x but started with 0x%02x — every "
			           "particle should be back (periodic wrap)", model_name(g->model),
			           i % 16, i / 16, g->site[i], start[i]);
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST

/* ---- whole steps ---- */

/* The particles' first moment: Σ over every particle of the (sheared) coordinates of
 * its site. A collision moves no particle; streaming moves each by its direction
 * vector, so one step advances the moment by the momentum, modulo L (a particle that
 * wraps jumps back by L). */
static void first_moment(const lz_lgas *g, int64_t *sx, int64_t *sy)
{
	unsigned bits = (1u << g->nbits) - 1u;
	*sx = *sy = 0;
	for (uint32_t i = 0; i < (uint32_t)g->side * (uint32_t)g->side; i++) {
		int64_t n = __builtin_popcount(g->site[i] & bits);
		*sx += n * (int64_t)(i & (uint32_t)g->mask);
		*sy += n * (int64_t)(i >> g->shift);
	}
}

static int64_t mod_side(int64_t v, int64_t L) { return (v % L + L) % L; }

/* One collide-and-stream step, checked: mass and momentum conserved exactly, the
 * first moment moved by the momentum (p0x, p0y). */
static void checked_step(lz_lgas *g, const uint8_t *t, gsl_rng *r, int step, int64_t m0,
                         int64_t p0x, int64_t p0y)
{
	int64_t ax, ay, bx, by, m1, x1, y1;
	first_moment(g, &ax, &ay);
	lz_lgas_collide(g, t, r);
	lz_lgas_propagate(g);
	totals(g, &m1, &x1, &y1);
	ck_assert_msg(m1 == m0 && x1 == p0x && y1 == p0y, "%s, L = %d, d = 0.35: after %d steps "
	              "mass %" PRId64 " -> %" PRId64 ", momentum (%" PRId64 ", %" PRId64 ") -> (%"
	              PRId64 ", %" PRId64 ") in integer units — both must be conserved exactly",
	              model_name(g->model), g->side, step, m0, m1, p0x, p0y, x1, y1);
	first_moment(g, &bx, &by);
	ck_assert_msg(mod_side(bx - ax - p0x, g->side) == 0 && mod_side(by - ay - p0y, g->side) == 0,
	              "%s, step %d: the particles' first moment Σ(x, y) moved by (%" PRId64 ", %"
	              PRId64 "), but streaming moves every particle one site along its own "
	              "direction, so it must move by the momentum (%" PRId64 ", %" PRId64 ") modulo "
	              "L = %d — are particles pulled from r - e_k (not r + e_k), and is the new "
	              "lattice swapped into g->site?", model_name(g->model), step, bx - ax, by - ay,
	              p0x, p0y, g->side);
}

LZ_TEST(random_gas_conserves_mass_and_momentum_exactly)
{
	gsl_rng *r = lz_test_rng(2024);
	for (int m = 0; m < 2; m++) {
		lz_lgas_model model = m ? LZ_LGAS_FHP : LZ_LGAS_HPP;
		lz_lgas *g = lz_lgas_alloc(model, 32);
		uint8_t t[LZ_LGAS_TABLE_SIZE];
		table_by_hand(model, t);
		fill_random(g, 0.35, r);
		/* A net flow, so momentum conservation is not 0 = 0. */
		for (int i = 0; i < 1024; i += 3)
			g->site[i] |= 1u;
		int64_t m0, x0, y0;
		totals(g, &m0, &x0, &y0);
		/* Streaming backwards would move the moment by -p: seen only if 2p is not a
		 * multiple of L. */
		ck_assert_msg(mod_side(2 * x0, 32) != 0, "test set-up: the net flow %" PRId64
		              " must not be a multiple of L/2", x0);
		int changed = 0;
		for (int step = 1; step <= 10000; step++) {
			uint8_t before = g->site[100];
			if (step % 500 == 0 || step == 1) {
				checked_step(g, t, r, step, m0, x0, y0);
				continue;
			}
			lz_lgas_collide(g, t, r);
			changed |= g->site[100] != before;
			lz_lgas_propagate(g);
		}
		ck_assert_msg(changed, "%s: the collision never changed site 100 in 10^4 steps",
		              model_name(model));
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(collisions_happen_with_both_chiralities)
{
	/* Every site a head-on pair {0,3}: about half must turn each way, each site on its
	 * own coin. */
	gsl_rng *r = lz_test_rng(99);
	lz_lgas *g = lz_lgas_alloc(LZ_LGAS_FHP, 64);
	uint8_t t[LZ_LGAS_TABLE_SIZE];
	table_by_hand(LZ_LGAS_FHP, t);
	memset(g->site, 0x09, 4096);
	lz_lgas_collide(g, t, r);
	int plus = 0, minus = 0;
	for (int i = 0; i < 4096; i++) {
		plus += g->site[i] == 0x12;
		minus += g->site[i] == 0x24;
	}
	ck_assert_msg(plus + minus == 4096, "FHP: every head-on pair {0,3} must turn to {1,4} or "
	              "{2,5}; %d of 4096 did", plus + minus);
	ck_assert_msg(plus > 1800 && minus > 1800, "FHP: 4096 head-on pairs turned +60° %d "
	              "times and -60° %d times; each chirality should come up about half the "
	              "time, independently per site", plus, minus);
	/* Neighbours in storage order agree half the time if their coins are independent:
	 * 4095 pairs, 2047.5 ± 32; 5 standard deviations is a false alarm once in 10^6. */
	int agree = 0;
	for (int i = 0; i + 1 < 4096; i++)
		agree += g->site[i] == g->site[i + 1];
	ck_assert_msg(fabs(agree - 2047.5) < 5 * 32, "FHP: consecutive sites turned the same way "
	              "%d times out of 4095, expected 2048 ± 32 for independent chiralities — "
	              "each site needs a fresh bit (shift the random word after using a bit)",
	              agree);
	lz_lgas_free(g);
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(all_holes_and_all_particles_stay)
{
	/* Walls too: a full wall site bounced back is still full, and an empty one empty,
	 * so walls change nothing here, and keep their bit. */
	gsl_rng *r = lz_test_rng(3);
	for (int m = 0; m < 2; m++) {
		lz_lgas_model model = m ? LZ_LGAS_FHP : LZ_LGAS_HPP;
		unsigned full = m ? 0x3F : 0x0F;
		uint8_t t[LZ_LGAS_TABLE_SIZE];
		table_by_hand(model, t);
		for (int f = 0; f < 2; f++) {
			lz_lgas *g = lz_lgas_alloc(model, 16);
			memset(g->site, f ? (int)full : 0, 256);
			for (int y = 4; y < 12; y++)
				lz_lgas_set_wall(g, 5, y);
			for (int step = 0; step < 50; step++) {
				lz_lgas_collide(g, t, r);
				lz_lgas_propagate(g);
			}
			for (int i = 0; i < 256; i++) {
				unsigned wall = i % 16 == 5 && i / 16 >= 4 && i / 16 < 12 ? LZ_LGAS_WALL : 0u;
				LZ_REQUIRE(g->site[i] == ((f ? full : 0u) | wall), "%s: a lattice of all %s "
				           "with a plate of walls must stay so; after 50 steps site (%d, %d)%s "
				           "holds 0x%02x, expected 0x%02x — a wall site keeps its bit 0x80 "
				           "through collision and propagation", model_name(model),
				           f ? "particles" : "holes", i % 16, i / 16, wall ? " (a wall)" : "",
				           g->site[i], (f ? full : 0u) | wall);
			}
			lz_lgas_free(g);
		}
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(walls_bounce_particles_back)
{
	gsl_rng *r = lz_test_rng(5);
	for (int m = 0; m < 2; m++) {
		lz_lgas_model model = m ? LZ_LGAS_FHP : LZ_LGAS_HPP;
		int n;
		const lz_site *e = dirs_of(model, &n);
		uint8_t t[LZ_LGAS_TABLE_SIZE];
		table_by_hand(model, t);
		lz_lgas *g = lz_lgas_alloc(model, 8);
		/* Every state at a wall site is reversed, for both chiralities. */
		for (unsigned s = 0; s < (1u << n); s++) {
			g->site[9] = (uint8_t)(LZ_LGAS_WALL | s);
			lz_lgas_collide(g, t, r);
			unsigned want = 0;
			for (int k = 0; k < n; k++)
				if (s >> k & 1u)
					want |= 1u << ((k + n / 2) % n);
			ck_assert_msg(g->site[9] == (LZ_LGAS_WALL | want), "%s: a wall site with state "
			              "0x%02x must reverse every particle to 0x%02x and keep the wall bit; "
			              "got 0x%02x", model_name(model), s, LZ_LGAS_WALL | want, g->site[9]);
		}
		/* A particle flies into a wall and comes back where it started, reversed. */
		for (int k = 0; k < n; k++) {
			memset(g->site, 0, 64);
			lz_lgas_set_wall(g, 3 + e[k].x, 3 + e[k].y);
			g->site[3 * 8 + 3] = (uint8_t)(1u << k);
			for (int step = 0; step < 2; step++) {
				lz_lgas_collide(g, t, r);
				lz_lgas_propagate(g);
			}
			unsigned back = 1u << ((k + n / 2) % n);
			ck_assert_msg(g->site[3 * 8 + 3] == back, "%s: a particle leaving (3, 3) in "
			              "direction %d towards a wall must be back at (3, 3) after two steps, "
			              "moving in direction %d (state 0x%02x); the site holds 0x%02x",
			              model_name(model), k, (k + n / 2) % n, back, g->site[3 * 8 + 3]);
		}
		lz_lgas_free(g);
	}
	gsl_rng_free(r);
}
END_TEST
