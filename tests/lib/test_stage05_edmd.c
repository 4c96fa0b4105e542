/* test_stage05_edmd.c — the library half of lz/heap.h and lz/edmd.h, which students
 * do not write: the input checks of lz_heap_alloc, lz_edmd_alloc, lz_edmd_set and
 * lz_edmd_place_lattice (with what fits in the message), the automatic cells, the
 * block of cells and the cell across a face, the cell lists, the fall under gravity,
 * the re-base and the renumbering (both keep the trajectory), the run's stop time,
 * the observables against brute force, and the audits against hand-broken states.
 * Many of these call the graded functions (lz_edmd_start predicts): this suite runs
 * against the reference, as `make check` always does. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_poly.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "lz/edmd.h"
#include "lz/heap.h"
#include "lz/rng.h"
#include "lztest.h"
#include "support.h"


static double particle_volume(int dim) { return dim == 3 ? M_PI / 6 : M_PI / 4; }


static lz_edmd_params params(int dim, size_t n, double eta)
{
	return (lz_edmd_params){dim, n, eta, 1.0, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
}

static lz_edmd *alloc_ok(const lz_edmd_params *p)
{
	lz_edmd *e = lz_edmd_alloc(p);
	ck_assert_msg(e != NULL, "lz_edmd_alloc(dim %d, n %zu, packing %g, walls %d, cells %d): %s",
	              p->dim, p->n, p->packing, p->walls, p->cells, lz_error_message());
	return e;
}

static lz_edmd *lattice(int dim, size_t n, double eta, int walls, unsigned long seed)
{
	lz_edmd_params p = params(dim, n, eta);
	p.walls = walls;
	lz_edmd *e = alloc_ok(&p);
	lz_rng *r = lz_rng_alloc(NULL, seed);
	ck_assert(r);
	int st = lz_edmd_place_lattice(e, r);
	lz_rng_free(r);
	ck_assert_msg(st == LZ_OK, "lz_edmd_place_lattice(dim %d, n %zu, packing %g): %s", dim, n,
	              eta, lz_error_message());
	return e;
}

/* A system of n particles in a box of side L. */
static lz_edmd *box_of_side(int dim, size_t n, double L, int walls)
{
	lz_edmd_params p = params(dim, n, n * particle_volume(dim) / pow(L, dim));
	p.walls = walls;
	return alloc_ok(&p);
}

/* ---- the heap ---- */

LZ_TEST(heap_alloc_rejects_bad_capacity_and_audit_finds_defects)
{
	lz_test_clear_error();
	lz_test_refused(lz_heap_alloc(0) == NULL, "lz_heap_alloc(0)", "capacity 0", NULL);
	lz_test_refused(lz_heap_alloc(LZ_HEAP_NONE) == NULL, "lz_heap_alloc(2^32 - 1)",
	                "capacity 4294967295", NULL);
	lz_heap_free(NULL);
	lz_heap *h = lz_heap_alloc(6);
	ck_assert(h);
	ck_assert_msg(h->n == 0 && h->cap == 6 && lz_heap_audit(h) == LZ_OK,
	              "a new heap is empty and valid");
	for (uint32_t i = 0; i < 6; i++)
		ck_assert_msg(h->pos[i] == LZ_HEAP_NONE && !lz_heap_contains(h, i),
		              "a new heap contains no item (pos[%u] = %u)", i, h->pos[i]);
	ck_assert_msg(!lz_heap_contains(h, 99), "item 99 is beyond the capacity of 6");
	/* a valid heap by hand: 1, 2, 3, 4 at items 3, 0, 5, 1 */
	uint32_t ids[4] = {3, 0, 5, 1};
	for (uint32_t k = 0; k < 4; k++) {
		h->node[k] = (lz_heap_node){k + 1.0, ids[k]};
		h->pos[ids[k]] = k;
	}
	h->n = 4;
	ck_assert_msg(lz_heap_audit(h) == LZ_OK, "a valid heap made by hand: %s", lz_error_message());
	h->node[3].t = 0.5;  /* earlier than its parent node 1 */
	ck_assert_msg(lz_heap_audit(h) == LZ_EDOM && strstr(lz_error_message(), "order"),
	              "a node earlier than its parent: %s", lz_error_message());
	h->node[3].t = 4;
	h->pos[5] = 1;  /* points at item 0's node */
	ck_assert_msg(lz_heap_audit(h) == LZ_EDOM && strstr(lz_error_message(), "pos"),
	              "pos[5] pointing at another node: %s", lz_error_message());
	h->pos[5] = 2;
	h->pos[4] = 0;  /* an item out of the heap claims the root */
	ck_assert_msg(lz_heap_audit(h) == LZ_EDOM, "pos[4] set for an item not in the heap");
	h->pos[4] = LZ_HEAP_NONE;
	h->node[2].id = 9;
	ck_assert_msg(lz_heap_audit(h) == LZ_EDOM && strstr(lz_error_message(), "item 9"),
	              "a node holding item 9 of 6: %s", lz_error_message());
	h->node[2].id = 5;
	h->n = 7;
	ck_assert_msg(lz_heap_audit(h) == LZ_EDOM, "n = 7 nodes for 6 items");
	h->n = 4;
	ck_assert_msg(lz_heap_audit(h) == LZ_OK, "the repaired heap: %s", lz_error_message());
	lz_heap_clear(h);
	ck_assert_msg(h->n == 0 && h->pos[3] == LZ_HEAP_NONE && lz_heap_audit(h) == LZ_OK,
	              "lz_heap_clear empties the heap");
	lz_heap_free(h);
}
END_TEST

/* ---- the box ---- */

LZ_TEST(edmd_alloc_rejects_bad_input)
{
	lz_test_clear_error();
	lz_edmd_params p = params(3, 100, 0.3);
	p.dim = 1;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "dim 1", "dim = 1", "2 or 3");
	p = params(3, 0, 0.3);
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "n = 0", "n = 0", NULL);
	p = params(3, 100, 0.75);
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "3D packing 0.75", "packing = 0.75",
	                "close packing");
	p = params(3, 100, LZ_EDMD_CLOSE_3D);
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "3D packing at close packing", "0.7405", NULL);
	p = params(2, 100, 0.91);
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "2D packing 0.91", "packing = 0.91", "0.9069");
	p = params(2, 100, 0);
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "packing 0", "packing = 0", NULL);
	p = params(2, 100, NAN);
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "packing NaN", "packing = nan", NULL);
	p = params(3, 100, 0.3);
	p.restitution = 0;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "restitution 0", "restitution = 0", "(0, 1]");
	p.restitution = 1.5;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "restitution 1.5", "restitution = 1.5", NULL);
	p.restitution = NAN;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "restitution NaN", "restitution = nan", NULL);
	p = params(3, 100, 0.3);
	p.gravity = -1;
	p.walls = LZ_EDMD_WALLS_X;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "gravity -1", "gravity = -1", NULL);
	p.gravity = INFINITY;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "gravity inf", "gravity = inf", "finite");
	p.gravity = 1;
	p.walls = LZ_EDMD_WALLS_NONE;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "gravity without walls", "gravity = 1", "walls");
	p = params(3, 100, 0.3);
	p.walls = 7;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "walls 7", "walls = 7", NULL);
	/* cells given by hand: at least 3 per periodic side, each at least σ wide */
	p = params(3, 1000, 0.3);  /* L = 12.05 */
	p.cells = 2;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "cells = 2 periodic", "cells = 2", "[3, 12]");
	p.cells = 13;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "cells = 13 in L = 12.05", "cells = 13", NULL);
	p.cells = 12;
	lz_edmd *e = alloc_ok(&p);
	ck_assert_msg(e->m[0] == 12 && e->m[1] == 12 && e->m[2] == 12 && e->w[0] >= 1,
	              "cells = 12 in L = %g: m = %d, w = %g", e->L, e->m[0], e->w[0]);
	lz_edmd_free(e);
	/* and at most 2^27 cells (cell numbers are 32-bit): 600 per side of a box of
	 * L = 640 would be 2.2e8 */
	p = params(3, 50000, 1e-4);
	p.cells = 600;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "cells = 600 in 3D", "cells = 600", "[3, 512]");
	lz_edmd_free(NULL);
}
END_TEST

LZ_TEST(edmd_alloc_refuses_a_box_below_three_cells_and_says_which_n_fits)
{
	/* a periodic box needs 3 cells of at least σ per side, so L >= 3: at packing
	 * η that is n >= 3^dim η / v1; the message names that n, and it fits */
	lz_test_clear_error();
	static const struct {
		int dim;
		double eta;
	} cases[] = {{3, 0.3}, {3, 0.05}, {2, 0.5}, {2, 0.8}, {3, 0.7}};
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
		int dim = cases[c].dim;
		double eta = cases[c].eta;
		double nmin = ceil(pow(3.0, dim) * eta / particle_volume(dim));
		char say[64], call[96];
		snprintf(say, sizeof say, "n >= %.0f", nmin);
		lz_edmd_params p = params(dim, (size_t)nmin - 1, eta);
		snprintf(call, sizeof call, "%dD, n = %.0f at packing %g", dim, nmin - 1, eta);
		lz_test_refused(lz_edmd_alloc(&p) == NULL, call, say, "3");
		p.n = (size_t)nmin;
		lz_edmd *e = lz_edmd_alloc(&p);
		ck_assert_msg(e != NULL, "%dD at packing %g: the message said %s fits, but n = %.0f is "
		              "refused: %s", dim, eta, say, nmin, lz_error_message());
		ck_assert_msg(e->L >= 3 && e->m[0] == 3, "%dD, n = %.0f at packing %g: L = %g, m = %d",
		              dim, nmin, eta, e->L, e->m[0]);
		lz_edmd_free(e);
	}
	/* with walls on every side a small box is fine: one cell */
	lz_edmd_params p = params(2, 3, 0.3);
	p.walls = LZ_EDMD_WALLS_BOX;
	lz_edmd *e = alloc_ok(&p);
	ck_assert_msg(e->m[0] >= 1 && e->w[0] >= 1, "a walled box of side %g: m = %d", e->L, e->m[0]);
	lz_edmd_free(e);
	/* with walls on x only the periodic axes still need 3 cells */
	p.walls = LZ_EDMD_WALLS_X;
	lz_test_refused(lz_edmd_alloc(&p) == NULL, "walls on x only, L < 3", "3", NULL);
}
END_TEST

LZ_TEST(edmd_auto_cells_follow_miller_and_luding)
{
	/* dense: as many as fit (side >= σ); dilute: about 3 per particle (3D: lesson 05 §6), 1.5 (2D) */
	static const struct {
		int dim;
		size_t n;
		double eta;
	} cases[] = {{3, 1000, 0.3}, {3, 1000, 0.49}, {3, 1000, 1e-4}, {3, 100000, 0.01},
	             {2, 1000, 0.7}, {2, 1000, 1e-4}, {2, 100000, 0.05}, {3, 27, 0.1}};
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
		int dim = cases[c].dim;
		size_t n = cases[c].n;
		double L = pow(n * particle_volume(dim) / cases[c].eta, 1.0 / dim);
		int m = lz_edmd_auto_cells(dim, n, L);
		double per = dim == 3 ? 3 : 1.5;
		int want = (int)fmin(floor(L), fmax(3, ceil(pow(per * n, 1.0 / dim))));
		ck_assert_msg(m == want, "%dD, n = %zu, L = %g: lz_edmd_auto_cells gave %d per side, "
		              "expected %d (min of floor(L) = %g and the %.1f-per-particle count)", dim,
		              n, L, m, want, floor(L), per);
		ck_assert_msg(L / m >= 1 && m >= 3, "%dD, n = %zu: cells of side %g (m = %d)", dim, n,
		              L / m, m);
	}
	ck_assert_msg(lz_edmd_auto_cells(3, 10, 2.99) == 0, "L = 2.99 fits no 3 cells");
	ck_assert_msg(lz_edmd_auto_cells(2, 10, 3.0) == 3, "L = 3 fits exactly 3 cells");
}
END_TEST

/* The coordinate of cell c on axis a (row-major, x fastest). */
static int coord(const lz_edmd *e, uint32_t c, int a)
{
	return a == 0 ? (int)(c % (uint32_t)e->m[0])
	       : a == 1 ? (int)(c / (uint32_t)e->m[0] % (uint32_t)e->m[1])
	                : (int)(c / ((uint32_t)e->m[0] * (uint32_t)e->m[1]));
}

LZ_TEST(edmd_block_is_the_touching_cells_with_their_shifts)
{
	/* every cell of the block is a neighbour (coordinate differs by at most one,
	 * modulo m), each once; its shift brings it next to the centre cell; walls cut
	 * the block */
	static const struct {
		int dim, walls;
		size_t n;
		double L;
	} cases[] = {{3, LZ_EDMD_WALLS_NONE, 10, 12}, {3, LZ_EDMD_WALLS_NONE, 10, 3.5},
	             {2, LZ_EDMD_WALLS_NONE, 10, 20}, {3, LZ_EDMD_WALLS_BOX, 10, 12},
	             {3, LZ_EDMD_WALLS_X, 10, 12},    {2, LZ_EDMD_WALLS_BOX, 10, 9.5}};
	for (size_t q = 0; q < sizeof cases / sizeof cases[0]; q++) {
		lz_edmd *e = box_of_side(cases[q].dim, cases[q].n, cases[q].L, cases[q].walls);
		for (uint32_t c = 0; c < e->ncells; c++) {
			lz_edmd_block b;
			lz_edmd_block_of(e, c, &b);
			int want = 1, count = 0;
			for (int a = 0; a < 3; a++) {
				int k = a < e->dim ? 3 : 1;
				if (e->wall[a])
					k -= (coord(e, c, a) == 0) + (coord(e, c, a) == e->m[a] - 1);
				LZ_REQUIRE(b.n[a] == k, "%dD, m = %d, walls %d, cell %u: %d cells of the "
				              "block on axis %d, expected %d", e->dim, e->m[0], cases[q].walls,
				              c, b.n[a], a, k);
				want *= k;
			}
			char *seen = calloc(e->ncells, 1);
			LZ_REQUIRE_TRUE(seen);
			for (int z = 0; z < b.n[2]; z++)
				for (int y = 0; y < b.n[1]; y++)
					for (int x = 0; x < b.n[0]; x++, count++) {
						uint32_t nb = b.off[0][x] + b.off[1][y] + b.off[2][z];
						int idx[3] = {x, y, z};
						LZ_REQUIRE(nb < e->ncells && !seen[nb], "cell %u: block cell %u "
						              "twice or beyond the grid", c, nb);
						seen[nb] = 1;
						for (int a = 0; a < 3; a++) {
							/* the neighbour's centre, shifted, is within one cell */
							double mine = (coord(e, c, a) + 0.5) * e->w[a];
							double its = (coord(e, nb, a) + 0.5) * e->w[a] + b.shift[a][idx[a]];
							LZ_REQUIRE(fabs(fabs(its - mine) - e->w[a]) < 1e-9 ||
							                      fabs(its - mine) < 1e-9,
							              "%dD, m = %d, cell %u, block cell %u: on axis %d "
							              "its centre %g shifted by %g is %g from the centre "
							              "cell's %g, not 0 or one cell", e->dim, e->m[0], c,
							              nb, a, (coord(e, nb, a) + 0.5) * e->w[a],
							              b.shift[a][idx[a]], its - mine, mine);
						}
					}
			LZ_REQUIRE(count == want && seen[c], "%dD cell %u: %d block cells (want %d), "
			              "itself %s", e->dim, c, count, want, seen[c] ? "in" : "missing");
			free(seen);
		}
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(edmd_cell_across_every_face_and_the_jump)
{
	lz_edmd *e = box_of_side(3, 10, 12, LZ_EDMD_WALLS_NONE);  /* m = 3 or more */
	for (uint32_t c = 0; c < e->ncells; c++)
		for (int f = 0; f < 6; f++) {
			int a = f / 2, up = f % 2;
			double jump = 99;
			uint32_t to = lz_edmd_cell_across(e, c, f, &jump);
			int from = coord(e, c, a), want = (from + (up ? 1 : -1) + e->m[a]) % e->m[a];
			double want_jump = up && from == e->m[a] - 1 ? -e->L : !up && from == 0 ? e->L : 0;
			ck_assert_msg(to < e->ncells && coord(e, to, a) == want && jump == want_jump,
			              "cell %u, face %d: expected the cell at coordinate %d on axis %d with "
			              "jump %g, got cell %u (coordinate %d) with jump %g", c, f, want, a,
			              want_jump, to, to < e->ncells ? coord(e, to, a) : -1, jump);
			for (int o = 0; o < 3; o++)
				if (o != a)
					ck_assert_msg(coord(e, to, o) == coord(e, c, o), "cell %u, face %d: axis "
					              "%d changed", c, f, o);
		}
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(edmd_cell_lists_remove_and_insert)
{
	lz_edmd *e = box_of_side(2, 6, 9, LZ_EDMD_WALLS_NONE);
	lz_edmd_cell_clear(e);
	for (size_t c = 0; c < e->ncells; c++)
		ck_assert_msg(e->list[c].head == -1 && e->list[c].second == -1, "cleared cell %zu: head %d, "
		              "second %d", c, e->list[c].head, e->list[c].second);
	for (uint32_t i = 0; i < 6; i++)
		lz_edmd_cell_insert(e, i, i < 4 ? 2 : 5);  /* cell 2: 3 2 1 0; cell 5: 5 4 */
	ck_assert_msg(e->list[2].head == 3 && e->next[3] == 2 && e->next[2] == 1 && e->next[1] == 0 &&
	                      e->next[0] == -1 && e->p[1].cell == 2,
	              "insert puts the particle at the head of the list and sets its cell");
	ck_assert_msg(e->list[2].second == 2 && e->list[5].second == 4, "second[] holds each list's second "
	              "particle: cell 2 (3 2 1 0) says %d, cell 5 (5 4) says %d", e->list[2].second,
	              e->list[5].second);
	ck_assert_msg(e->next[-1] == -1, "the sentinel next[-1] must be -1");
	lz_edmd_cell_remove(e, 1);  /* middle */
	lz_edmd_cell_remove(e, 3);  /* head */
	lz_edmd_cell_remove(e, 0);  /* tail */
	ck_assert_msg(e->list[2].head == 2 && e->next[2] == -1 && e->list[2].second == -1, "after removing "
	              "1, 3 and 0 the list of cell 2 is just 2: head %d, next %d, second %d",
	              e->list[2].head, e->next[2], e->list[2].second);
	lz_edmd_cell_remove(e, 2);
	ck_assert_msg(e->list[2].head == -1, "an emptied cell has head -1, got %d", e->list[2].head);
	lz_edmd_cell_insert(e, 0, 5);
	ck_assert_msg(e->list[5].head == 0 && e->next[0] == 5 && e->next[5] == 4 && e->next[4] == -1 &&
	                      e->list[5].second == 5,
	              "cell 5 is now 0 5 4, second 5: second = %d", e->list[5].second);
	lz_edmd_cell_remove(e, 5);  /* the second goes: the third moves up */
	ck_assert_msg(e->list[5].second == 4, "cell 5 is now 0 4: second %d", e->list[5].second);
	ck_assert_msg(e->next[-1] == -1, "the sentinel next[-1] must stay -1");
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(edmd_fall_time_is_the_first_root)
{
	/* against GSL's quadratic solver: the top if the particle gets that high, else
	 * the bottom; the edge cases exactly */
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, 5101);
	for (int trial = 0; trial < 100000; trial++) {
		double g = exp(gsl_ran_flat(r, log(1e-3), log(1e3)));
		double lo = gsl_ran_flat(r, 0, 5), hi = lo + gsl_ran_flat(r, 0.5, 3);
		double x = lo + (hi - lo) * gsl_rng_uniform(r), v = gsl_ran_gaussian(r, 3);
		int up = -1;
		double t = lz_edmd_fall_time(x, v, g, lo, hi, &up);
		double r1, r2, t_up = INFINITY;
		if (gsl_poly_solve_quadratic(-0.5 * g, v, x - hi, &r1, &r2) == 2 && r1 >= 0)
			t_up = r1;
		gsl_poly_solve_quadratic(-0.5 * g, v, x - lo, &r1, &r2);
		double t_down = r2, want = fmin(t_up, t_down);
		LZ_REQUIRE(fabs(t - want) <= 1e-10 * (1 + want) && up == (t_up <= t_down),
		              "fall from x = %.10g at v = %.6g under g = %.4g in [%.6g, %.6g]: expected "
		              "%s at t = %.12g, got %s at t = %.12g", x, v, g, lo, hi,
		              t_up <= t_down ? "the top" : "the bottom", want, up ? "the top" : "the bottom",
		              t);
	}
	gsl_rng_free(r);
	int up;
	double t = lz_edmd_fall_time(1, -2, 1, 1, 3, &up);
	ck_assert_msg(t == 0 && up == 0, "at the bottom moving down: now, got %g (up %d)", t, up);
	t = lz_edmd_fall_time(3, 2, 1, 1, 3, &up);
	ck_assert_msg(t == 0 && up == 1, "at the top moving up: now, got %g (up %d)", t, up);
	t = lz_edmd_fall_time(3, 0, 2, 1, 3, &up);
	ck_assert_msg(fabs(t - sqrt(2.0)) < 1e-15 && up == 0, "dropped from rest 2 above the "
	              "bottom under g = 2: t = √2, got %.17g", t);
	t = lz_edmd_fall_time(1, 1, 1, 1, 3, &up);
	ck_assert_msg(fabs(t - 2) < 1e-15 && up == 0, "thrown up at 1 from the bottom, g = 1, "
	              "not reaching the top: back at t = 2, got %.17g (up %d)", t, up);
	/* a fast particle just below the top: no cancellation in the small root */
	double x = 3 - 1e-12, rise = 3 - x;  /* exact (Sterbenz) */
	t = lz_edmd_fall_time(x, 1e3, 1, 1, 3, &up);
	ck_assert_msg(up == 1 && fabs(t - rise / 1e3) < 1e-12 * rise / 1e3, "%.3g below the top at "
	              "speed 1e3: t = %.17g to 1e-12, got %.17g", rise, rise / 1e3, t);
	/* lo slightly above x by round-off: no negative time */
	t = lz_edmd_fall_time(1 - 1e-15, -1, 1, 1, 3, &up);
	ck_assert_msg(t >= 0 && t < 1e-14, "x a hair below the bottom moving down: t = 0, got %g", t);
}
END_TEST

/* ---- the states ---- */

LZ_TEST(edmd_place_lattice_places_and_refuses)
{
	lz_test_clear_error();
	static const struct {
		int dim, walls;
		size_t n;
		double eta;
	} ok[] = {{3, LZ_EDMD_WALLS_NONE, 500, 0.3}, {3, LZ_EDMD_WALLS_NONE, 4000, 0.5},
	          {2, LZ_EDMD_WALLS_NONE, 400, 0.7},  {3, LZ_EDMD_WALLS_BOX, 400, 0.3},
	          {2, LZ_EDMD_WALLS_X, 300, 0.4},     {3, LZ_EDMD_WALLS_NONE, 1, 0.001}};
	for (size_t c = 0; c < sizeof ok / sizeof ok[0]; c++) {
		lz_edmd *e = lattice(ok[c].dim, ok[c].n, ok[c].eta, ok[c].walls, 77 + c);
		int dim = e->dim;
		double P[3], over = lz_edmd_max_overlap(e, NULL, NULL);
		lz_edmd_momentum(e, P);
		LZ_REQUIRE(over == 0, "%dD lattice at η = %g: overlap %g", dim, ok[c].eta, over);
		if (e->n > 1) {
			LZ_REQUIRE(fabs(P[0]) + fabs(P[1]) + fabs(P[2]) < 1e-10 * e->n, "%dD lattice: total "
			              "momentum (%g, %g, %g), expected 0", dim, P[0], P[1], P[2]);
			LZ_REQUIRE(fabs(lz_edmd_temperature(e) - 1) < 1e-12, "%dD lattice: kT = %.15g, "
			              "expected 1", dim, lz_edmd_temperature(e));
		}
		for (uint32_t i = 0; i < e->n; i++)
			for (int a = 0; a < 3; a++) {
				double x = e->p[i].r[a];
				if (a >= dim)
					LZ_REQUIRE(x == 0 && e->p[i].v[a] == 0, "2D: z must be 0");
				else if (e->wall[a])
					LZ_REQUIRE(x >= 0.5 && x <= e->L - 0.5, "%dD, walls: %c = %g beyond the "
					              "contacts", dim, "xyz"[a], x);
				else
					LZ_REQUIRE(x >= 0 && x < e->L, "%dD: %c = %g outside [0, %g)", dim,
					              "xyz"[a], x, e->L);
			}
		LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%dD lattice: %s", dim, lz_error_message());
		lz_edmd_free(e);
	}
	/* 2D near close packing: no square lattice fits */
	lz_edmd_params p = params(2, 400, 0.85);
	lz_edmd *e = alloc_ok(&p);
	lz_rng *r = lz_rng_alloc(NULL, 1);
	lz_test_refused(lz_edmd_place_lattice(e, r) != LZ_OK, "2D lattice at η = 0.85",
	                "do not fit", "400 particles");
	lz_edmd_free(e);
	/* 3D at 0.73 fits only a full fcc lattice of 4M^3 sites: 500 fit, 501 do not */
	p = params(3, 501, 0.73);
	e = alloc_ok(&p);
	lz_test_refused(lz_edmd_place_lattice(e, r) != LZ_OK, "3D lattice of 501 at η = 0.73",
	                "do not fit", "4M^3");
	lz_edmd_free(e);
	p.n = 500;
	e = alloc_ok(&p);
	ck_assert_msg(lz_edmd_place_lattice(e, r) == LZ_OK && lz_edmd_max_overlap(e, NULL, NULL) == 0,
	              "3D, 500 = 4·5^3 at η = 0.73 fill an fcc lattice: %s", lz_error_message());
	lz_edmd_free(e);
	lz_rng_free(r);
}
END_TEST

LZ_TEST(edmd_set_refuses_bad_states_naming_the_particle)
{
	lz_test_clear_error();
	lz_edmd *e = box_of_side(3, 4, 10, LZ_EDMD_WALLS_NONE);
	double r[12] = {1, 1, 1, 5, 5, 5, 8, 2, 6, 2, 8, 3}, v[12] = {0};
	ck_assert_msg(lz_edmd_set(e, r, v) == LZ_OK, "a good state: %s", lz_error_message());
	/* two particles closer than σ, across the periodic boundary */
	double r2[12] = {0.3, 1, 1, 5, 5, 5, 8, 2, 6, 9.6, 1.1, 0.9};
	lz_test_refused(lz_edmd_set(e, r2, v) != LZ_OK,
	                "particles 0 and 3 overlap through the wrap", "particles 0 and 3",
	                "overlap");
	double r3[12] = {1, 1, 1, 5, 5, 5, 5.5, 5.5, 5.5, 2, 8, 3};
	lz_test_refused(lz_edmd_set(e, r3, v) != LZ_OK, "particles 1 and 2 overlap",
	                "particles 1 and 2", "0.866");
	double r4[12] = {1, 1, 1, 5, 5, NAN, 8, 2, 6, 2, 8, 3};
	lz_test_refused(lz_edmd_set(e, r4, v) != LZ_OK, "a NaN position", "particle 1", "finite");
	double r8[12] = {1, 1, 1, 5, 5, 5, 8, 10.5, 6, 2, 8, 3};
	lz_test_refused(lz_edmd_set(e, r8, v) != LZ_OK, "y = 10.5 in a box of 10", "particle 2",
	                "outside the box");
	double r9[12] = {1, 1, 1, 5, 5, 5, 8, 2, 6, 2, -1e-13, 3};
	ck_assert_msg(lz_edmd_set(e, r9, v) == LZ_OK, "y = -1e-13 is round-off, wrapped: %s",
	              lz_error_message());
	ck_assert_msg(e->p[3].r[1] >= 0 && e->p[3].r[1] < e->L, "y = -1e-13 must be wrapped into "
	              "[0, L), got %.17g", e->p[3].r[1]);
	double v5[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, INFINITY, 0};
	lz_test_refused(lz_edmd_set(e, r, v5) != LZ_OK, "an infinite velocity", "particle 3",
	                "finite");
	/* touching to 1e-11 is allowed (round-off), overlapping by 1e-9 is not */
	double r6[12] = {1, 1, 1, 2 - 1e-11, 1, 1, 8, 2, 6, 2, 8, 3};
	ck_assert_msg(lz_edmd_set(e, r6, v) == LZ_OK, "touching within 1e-11: %s", lz_error_message());
	double r7[12] = {1, 1, 1, 2 - 1e-9, 1, 1, 8, 2, 6, 2, 8, 3};
	lz_test_refused(lz_edmd_set(e, r7, v) != LZ_OK, "overlap 1e-9", "particles 0 and 1", NULL);
	lz_edmd_free(e);
	/* walls: a centre beyond the contact 1/2 */
	e = box_of_side(2, 3, 10, LZ_EDMD_WALLS_X);
	double w[9] = {0.4, 5, 0, 5, 5, 0, 7, 7, 0}, wv[9] = {0};
	lz_test_refused(lz_edmd_set(e, w, wv) != LZ_OK, "x = 0.4 with a wall at 0",
	                "particle 0", "beyond the wall");
	double w2[9] = {0.5, 5, 0, 5, 5, 0, 7, 9.7, 0};
	ck_assert_msg(lz_edmd_set(e, w2, wv) == LZ_OK, "x = 0.5 touches the wall, y = 9.7 is "
	              "periodic: %s", lz_error_message());
	double w3[9] = {0.5, 5, 0, 9.6, 5, 0, 7, 7, 0};
	lz_test_refused(lz_edmd_set(e, w3, wv) != LZ_OK, "x = 9.6 with a wall at 10",
	                "particle 1", "beyond the wall");
	lz_edmd_free(e);
}
END_TEST

/* ---- the run around the loop ---- */

LZ_TEST(edmd_run_stops_at_t_stop_and_when_nothing_happens)
{
	lz_test_clear_error();
	lz_edmd *e = lattice(3, 300, 0.3, LZ_EDMD_WALLS_NONE, 11);
	int st = lz_edmd_run(e, 100000000, 2.5);
	ck_assert_msg(st == LZ_OK && fabs(lz_edmd_time(e) - 2.5) < 1e-12, "run to t = 2.5: status "
	              "%d, the clock reads %.15g", st, lz_edmd_time(e));
	for (uint32_t i = 0; i < e->n; i++)
		ck_assert_msg(e->p[i].t0 == e->now, "at t_stop every particle is brought to now: "
		              "particle %u has t0 = %g, now = %g", i, e->p[i].t0, e->now);
	ck_assert_msg(lz_edmd_audit(e) == LZ_OK, "after a run to t_stop: %s", lz_error_message());
	/* the run goes on from there as if it had not stopped */
	uint64_t before = e->events;
	st = lz_edmd_run(e, 1000, INFINITY);
	ck_assert_msg(st == LZ_OK && e->events == before + 1000, "1000 more events: status %d, "
	              "%llu events", st, (unsigned long long)(e->events - before));
	lz_edmd_free(e);
	/* two particles at rest: nothing will ever happen */
	e = box_of_side(3, 2, 10, LZ_EDMD_WALLS_NONE);
	double r[6] = {2, 2, 2, 6, 6, 6}, v[6] = {0};
	ck_assert(lz_edmd_set(e, r, v) == LZ_OK);
	st = lz_edmd_run(e, 10, INFINITY);
	ck_assert_msg(st == LZ_EPHYS && strstr(lz_error_message(), "nothing left"), "particles at "
	              "rest: expected LZ_EPHYS, nothing left to happen; got %d: %s", st,
	              lz_error_message());
	lz_edmd_free(e);
}
END_TEST

/* Positions now of all particles, sorted lexicographically (a multiset that does
 * not depend on the numbering). */
static int cmp3(const void *a, const void *b)
{
	const double *x = a, *y = b;
	for (int k = 0; k < 3; k++)
		if (x[k] != y[k])
			return x[k] < y[k] ? -1 : 1;
	return 0;
}

static double *sorted_positions(const lz_edmd *e)
{
	double *r = malloc(3 * e->n * sizeof *r), v[3];
	ck_assert(r);
	for (uint32_t i = 0; i < e->n; i++)
		lz_edmd_state(e, &e->p[i], e->now, r + 3 * i, v);
	qsort(r, e->n, 3 * sizeof *r, cmp3);
	return r;
}


LZ_TEST(edmd_sort_renumbers_without_changing_the_trajectory)
{
	/* the same start run with and without renumbering at each re-base: the same
	 * events, the same positions (as a set), and the renumbered system in cell order */
	lz_edmd *a = lattice(3, 1500, 0.3, LZ_EDMD_WALLS_NONE, 21);
	lz_edmd *b = lattice(3, 1500, 0.3, LZ_EDMD_WALLS_NONE, 21);
	a->sort_every = 1;
	b->sort_every = 0;
	ck_assert(lz_edmd_run(a, 240000, INFINITY) == LZ_OK && lz_edmd_run(b, 240000, INFINITY) == LZ_OK);
	ck_assert_msg(a->rebases >= 15, "240000 events of 1500 particles: %u re-bases", a->rebases);
	ck_assert_msg(a->collisions == b->collisions && a->crossings == b->crossings &&
	                      a->stale == b->stale,
	              "sorted and unsorted runs differ: %llu/%llu collisions, %llu/%llu crossings, "
	              "%llu/%llu stale", (unsigned long long)a->collisions,
	              (unsigned long long)b->collisions, (unsigned long long)a->crossings,
	              (unsigned long long)b->crossings, (unsigned long long)a->stale,
	              (unsigned long long)b->stale);
	ck_assert_msg(a->virial == b->virial && lz_edmd_time(a) == lz_edmd_time(b),
	              "sorted and unsorted runs: virial %.17g / %.17g, time %.17g / %.17g", a->virial,
	              b->virial, lz_edmd_time(a), lz_edmd_time(b));
	double *ra = sorted_positions(a), *rb = sorted_positions(b);
	for (size_t k = 0; k < 3 * a->n; k++)
		LZ_REQUIRE(ra[k] == rb[k], "sorted and unsorted runs: position %zu differs, %.17g / "
		              "%.17g", k / 3, ra[k], rb[k]);
	free(ra);
	free(rb);
	/* the cells in row-major order: every particle after those of lower cells */
	ck_assert_msg(lz_edmd_sort(a) == LZ_OK && lz_edmd_audit(a) == LZ_OK, "sort: %s",
	              lz_error_message());
	for (uint32_t i = 1; i < a->n; i++)
		LZ_REQUIRE(a->p[i].cell >= a->p[i - 1].cell, "after lz_edmd_sort particle %u is "
		              "in cell %u, after particle %u in cell %u: not in cell order", i,
		              a->p[i].cell, i - 1, a->p[i - 1].cell);
	for (uint32_t i = 0; i < a->n; i++)
		if (a->ev[i].partner >= 0) {
			uint32_t j = (uint32_t)a->ev[i].partner;
			double d = 0, ri[3], rj[3], v[3];
			lz_edmd_state(a, &a->p[i], a->now, ri, v);
			lz_edmd_state(a, &a->p[j], a->now, rj, v);
			for (int x = 0; x < 3; x++) {
				double dx = rj[x] - ri[x];
				dx -= a->L * rint(dx / a->L);
				d += dx * dx;
			}
			ck_assert_msg(sqrt(d) < 3 * a->w[0], "after the sort particle %u's partner %u is "
			              "%g away: the partners were not renumbered", i, j, sqrt(d));
		}
	lz_edmd_free(a);
	lz_edmd_free(b);
}
END_TEST

LZ_TEST(edmd_rebase_keeps_the_clock_and_the_trajectory)
{
	lz_edmd *a = lattice(3, 500, 0.3, LZ_EDMD_WALLS_NONE, 31);
	lz_edmd *b = lattice(3, 500, 0.3, LZ_EDMD_WALLS_NONE, 31);
	for (int k = 0; k < 20; k++) {
		for (int s = 0; s < 100; s++) {
			LZ_REQUIRE_TRUE(lz_edmd_step(a) == 0);
			LZ_REQUIRE_TRUE(lz_edmd_step(b) == 0);
		}
		double t = lz_edmd_time(b), now = b->now;
		uint32_t top = lz_heap_top(b->heap);
		lz_edmd_rebase(b);
		LZ_REQUIRE(b->now == 0 && fabs(lz_edmd_time(b) - t) <= 1e-15 * t &&
		                      fabs(b->t_base - t) <= 1e-15 * t,
		              "after a re-base now = %g (want 0), the clock %.17g (was %.17g)", b->now,
		              lz_edmd_time(b), t);
		LZ_REQUIRE(lz_heap_top(b->heap) == top, "the re-base changed the heap's top");
		for (uint32_t i = 0; i < b->n; i++)
			LZ_REQUIRE(b->p[i].t0 == 0, "after a re-base particle %u has t0 = %g", i,
			              b->p[i].t0);
		LZ_REQUIRE(lz_edmd_audit(b) == LZ_OK, "after a re-base at now = %g: %s", now,
		              lz_error_message());
	}
	ck_assert_msg(b->rebases == 20, "20 re-bases counted as %u", b->rebases);
	ck_assert_msg(a->collisions == b->collisions && a->crossings == b->crossings,
	              "2000 events with and without re-bases: %llu/%llu collisions, %llu/%llu "
	              "crossings", (unsigned long long)a->collisions, (unsigned long long)b->collisions,
	              (unsigned long long)a->crossings, (unsigned long long)b->crossings);
	ck_assert_msg(fabs(lz_edmd_time(a) - lz_edmd_time(b)) < 1e-12, "the clocks differ: %.17g / "
	              "%.17g", lz_edmd_time(a), lz_edmd_time(b));
	for (uint32_t i = 0; i < a->n; i++) {
		double ra[3], rb[3], v[3];
		lz_edmd_state(a, &a->p[i], a->now, ra, v);
		lz_edmd_state(b, &b->p[i], b->now, rb, v);
		for (int x = 0; x < 3; x++)
			LZ_REQUIRE(fabs(ra[x] - rb[x]) < 1e-9, "particle %u: %c = %.15g with re-bases, "
			              "%.15g without", i, "xyz"[x], rb[x], ra[x]);
	}
	lz_edmd_free(a);
	lz_edmd_free(b);
}
END_TEST

LZ_TEST(edmd_clock_counters_and_observables)
{
	lz_edmd *e = lattice(2, 200, 0.4, LZ_EDMD_WALLS_NONE, 41);
	ck_assert(lz_edmd_run(e, 5000, INFINITY) == LZ_OK);
	lz_edmd_set_time(e, 1000);
	ck_assert_msg(fabs(lz_edmd_time(e) - 1000) < 1e-12, "set_time(1000): the clock reads %.15g",
	              lz_edmd_time(e));
	lz_edmd_reset_counts(e);
	ck_assert_msg(e->events == 0 && e->collisions == 0 && e->crossings == 0 && e->bounces == 0 &&
	                      e->stale == 0 && e->virial == 0 && e->t_reset == lz_edmd_time(e),
	              "reset_counts zeroes the counters and sets t_reset to the clock");
	/* energy, momentum, temperature against sums of the states now */
	double ke = 0, P[3] = {0, 0, 0}, Pe[3];
	for (uint32_t i = 0; i < e->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		for (int a = 0; a < 3; a++) {
			ke += 0.5 * v[a] * v[a];
			P[a] += v[a];
		}
	}
	lz_edmd_momentum(e, Pe);
	ck_assert_msg(fabs(lz_edmd_energy(e) - ke) < 1e-12 * ke &&
	                      fabs(lz_edmd_temperature(e) - ke / e->n) < 1e-12,
	              "energy %.15g (sum %.15g), temperature %.15g (KE/n %.15g in 2D)",
	              lz_edmd_energy(e), ke, lz_edmd_temperature(e), ke / e->n);
	for (int a = 0; a < 3; a++)
		ck_assert_msg(fabs(Pe[a] - P[a]) < 1e-12, "momentum %c: %g, sum %g", "xyz"[a], Pe[a], P[a]);
	/* max_overlap against all pairs, after pushing some particles together by hand
	 * (within their cells, so the cell lists stay right) */
	lz_edmd_sync(e);
	for (uint32_t i = 0; i < e->n; i += 7) {
		double lo = (e->p[i].cell % (uint32_t)e->m[0]) * e->w[0];
		e->p[i].r[0] = lo + 0.5 * e->w[0];
	}
	double worst = 0;
	for (uint32_t i = 0; i < e->n; i++)
		for (uint32_t j = i + 1; j < e->n; j++) {
			double d2 = 0;
			for (int a = 0; a < 2; a++) {
				double d = e->p[j].r[a] - e->p[i].r[a];
				d -= e->L * rint(d / e->L);
				d2 += d * d;
			}
			if (d2 < 1)
				worst = fmax(worst, 1 - sqrt(d2));
		}
	ck_assert_msg(worst > 0.01, "the test meant to make overlaps, the largest is %g", worst);
	uint32_t pi = 0, pj = 0;
	double over = lz_edmd_max_overlap(e, &pi, &pj);
	ck_assert_msg(fabs(over - worst) < 1e-12, "max_overlap %.15g (pair %u, %u), all pairs give "
	              "%.15g", over, pi, pj, worst);
	double bytes = lz_edmd_bytes(e);
	ck_assert_msg(bytes > 80 && bytes < 200, "bytes per particle %g: the header says about 110",
	              bytes);
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(edmd_audit_finds_hand_broken_states)
{
	lz_edmd *e = lattice(3, 200, 0.3, LZ_EDMD_WALLS_NONE, 51);
	ck_assert(lz_edmd_run(e, 3000, INFINITY) == LZ_OK);
	lz_edmd_sync(e);
	ck_assert_msg(lz_edmd_audit(e) == LZ_OK, "a good state: %s", lz_error_message());
	uint32_t i = 17;
	lz_edmd_particle keep = e->p[i];
	/* outside its cell */
	e->p[i].r[1] += e->w[1];
	if (e->p[i].r[1] >= e->L)
		e->p[i].r[1] -= 2 * e->w[1];
	ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM && strstr(lz_error_message(), "particle 17") &&
	                      strstr(lz_error_message(), "outside its cell"),
	              "particle 17 moved a cell away: %s", lz_error_message());
	e->p[i] = keep;
	/* a clock ahead of now */
	e->p[i].t0 = e->now + 1;
	ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM && strstr(lz_error_message(), "particle 17"),
	              "t0 ahead of now: %s", lz_error_message());
	e->p[i] = keep;
	/* it says it is in another cell than the list it is in */
	e->p[i].cell = (e->p[i].cell + 1) % (uint32_t)e->ncells;
	ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM && strstr(lz_error_message(), "17"),
	              "cell number wrong: %s", lz_error_message());
	e->p[i] = keep;
	/* a second[] that is not the list's second particle */
	uint32_t c = e->p[i].cell;
	int32_t second = e->list[c].second;
	e->list[c].second = second >= 0 ? -1 : (int32_t)i;
	ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM && strstr(lz_error_message(), "second"),
	              "second[] broken: %s", lz_error_message());
	e->list[c].second = second;
	/* an event in the past */
	lz_heap_node *nd = &e->heap->node[e->heap->pos[i]];
	double t = nd->t;
	nd->t = e->now - 1;
	ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM, "an event before now: %s", lz_error_message());
	nd->t = t;
	/* a partner that is not a particle */
	lz_edmd_event ev = e->ev[i];
	e->ev[i].partner = (int32_t)e->n + 5;
	ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM && strstr(lz_error_message(), "particle 17"),
	              "partner beyond n: %s", lz_error_message());
	e->ev[i] = ev;
	/* the heap order broken */
	if (e->heap->n > 2) {
		lz_heap_node x = e->heap->node[0];
		e->heap->node[0] = e->heap->node[e->heap->n - 1];
		e->heap->node[e->heap->n - 1] = x;
		e->heap->pos[e->heap->node[0].id] = 0;
		e->heap->pos[x.id] = (uint32_t)(e->heap->n - 1);
		ck_assert_msg(lz_edmd_audit(e) == LZ_EDOM && strstr(lz_error_message(), "order"),
		              "heap order broken: %s", lz_error_message());
		x = e->heap->node[0];
		e->heap->node[0] = e->heap->node[e->heap->n - 1];
		e->heap->node[e->heap->n - 1] = x;
		e->heap->pos[e->heap->node[0].id] = 0;
		e->heap->pos[x.id] = (uint32_t)(e->heap->n - 1);
	}
	ck_assert_msg(lz_edmd_audit(e) == LZ_OK, "the repaired state: %s", lz_error_message());
	lz_edmd_free(e);
}
END_TEST

/* A run told to stop before the clock refuses: bringing every particle back to t_stop
 * would undo collisions and leave overlaps. */
LZ_TEST(edmd_run_refuses_to_go_back_in_time)
{
	lz_edmd *e = lattice(3, 500, 0.3, LZ_EDMD_WALLS_NONE, 1);
	ck_assert(lz_edmd_run(e, 1000000, 2.0) == LZ_OK);
	double t = lz_edmd_time(e);
	ck_assert_msg(fabs(t - 2.0) < 1e-12, "a run to t_stop = 2 ended at %.17g", t);
	int st = lz_edmd_run(e, 10, 1.0);
	ck_assert_msg(st == LZ_EINVAL && strstr(lz_error_message(), "before the clock"),
	              "lz_edmd_run(t_stop = 1) at t = 2 gave status %d (%s); it must refuse",
	              st, lz_error_message());
	ck_assert_msg(lz_edmd_time(e) == t && lz_edmd_audit(e) == LZ_OK &&
	                      lz_edmd_max_overlap(e, NULL, NULL) == 0,
	              "the refused run changed the system: t = %.17g, %s", lz_edmd_time(e),
	              lz_error_message());
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(edmd_resizes_and_runs_as_before)
{
	/* a system that grows and shrinks (a rank of lz/pedmd.h meeting particles and
	 * handing them over) keeps what it holds: records, cells, heap keys; the new
	 * particles are in no cell and not in the heap, so the run is the one it would have
	 * been, bit for bit; a 4-ary heap resizes too; a particle still in the heap cannot
	 * be dropped, nor can a system with lists resize */
	lz_edmd *a = lattice(2, 400, 0.3, LZ_EDMD_WALLS_NONE, 3);
	lz_edmd *b = lattice(2, 400, 0.3, LZ_EDMD_WALLS_NONE, 3);
	LZ_REQUIRE_TRUE(lz_edmd_run(a, 2000, INFINITY) == LZ_OK &&
	                lz_edmd_run(b, 2000, INFINITY) == LZ_OK);
	double key7 = lz_heap_key(b->heap, 7);
	ck_assert_msg(lz_edmd_resize(b, 1000) == LZ_OK && b->n == 1000 && b->heap->cap == 1000,
	              "grow to 1000: %s", lz_error_message());
	ck_assert_msg(lz_heap_audit(b->heap) == LZ_OK && lz_heap_key(b->heap, 7) == key7,
	              "the heap after growing: %s", lz_error_message());
	for (uint32_t i = 400; i < 1000; i++)
		LZ_REQUIRE(!lz_heap_contains(b->heap, i) && b->next[i] == -1 && b->p[i].count == 0 &&
		           b->ev[i].partner == LZ_EDMD_NONE, "new particle %u is not blank", i);
	LZ_REQUIRE_TRUE(lz_edmd_run(a, 5000, INFINITY) == LZ_OK &&
	                lz_edmd_run(b, 5000, INFINITY) == LZ_OK);
	ck_assert_msg(lz_edmd_resize(b, 400) == LZ_OK && b->n == 400, "back to 400: %s",
	              lz_error_message());
	lz_test_refused(lz_edmd_resize(b, 399) != LZ_OK, "lz_edmd_resize below a particle in the "
	                "heap", "its 400 nodes", NULL);
	ck_assert_msg(b->n == 400 && lz_heap_audit(b->heap) == LZ_OK, "a refused resize changed "
	              "the system: %s", lz_error_message());
	LZ_REQUIRE_TRUE(lz_edmd_run(a, 20000, INFINITY) == LZ_OK &&
	                lz_edmd_run(b, 20000, INFINITY) == LZ_OK);
	ck_assert_msg(a->collisions == b->collisions && lz_edmd_time(a) == lz_edmd_time(b),
	              "resized: %llu collisions, not resized: %llu", (unsigned long long)b->collisions,
	              (unsigned long long)a->collisions);
	for (uint32_t i = 0; i < a->n; i++)
		LZ_REQUIRE(memcmp(&a->p[i], &b->p[i], sizeof a->p[i]) == 0, "particle %u differs "
		           "after the system was resized", i);
	lz_edmd_free(a);
	lz_edmd_free(b);
	lz_heap *h = lz_heap_alloc_arity(5, 4);
	LZ_REQUIRE_TRUE(h);
	for (uint32_t id = 0; id < 5; id++)
		lz_heap_push(h, id, 10.0 - id);
	ck_assert_int_eq(lz_heap_resize(h, 40), LZ_OK);
	for (uint32_t id = 5; id < 40; id++)
		lz_heap_push(h, id, (double)((id * 7u) % 13u));
	ck_assert_msg(lz_heap_audit(h) == LZ_OK, "a grown 4-ary heap: %s", lz_error_message());
	double last = -1;
	while (h->n > 30) {
		LZ_REQUIRE(lz_heap_top_t(h) >= last, "popped %g after %g", lz_heap_top_t(h), last);
		last = lz_heap_top_t(h);
		lz_heap_pop(h);
	}
	lz_test_refused(lz_heap_resize(h, 3) != LZ_OK, "lz_heap_resize below its nodes", "capacity 3",
	                NULL);
	lz_heap_free(h);
	lz_edmd_params q = {3, 500, 0.3, 1, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_LIST, 0, 0};
	lz_edmd *l = alloc_ok(&q);
	lz_test_refused(lz_edmd_resize(l, 600) != LZ_OK, "lz_edmd_resize with lists", "cells", NULL);
	lz_edmd_free(l);
}
END_TEST

LZ_TEST(edmd_prefetch_is_on_for_big_systems_and_changes_nothing)
{
	/* lz_edmd_alloc turns the prefetches on from LZ_EDMD_FAR particles on */
	lz_edmd_params p = params(3, LZ_EDMD_FAR - 1, 0.3);
	lz_edmd *small = alloc_ok(&p);
	p.n = LZ_EDMD_FAR;
	lz_edmd *big = alloc_ok(&p);
	ck_assert_msg(!small->prefetch && big->prefetch, "prefetch is %d at n = %d and %d at "
	              "n = %d: it must be off below LZ_EDMD_FAR and on from it", small->prefetch,
	              LZ_EDMD_FAR - 1, big->prefetch, LZ_EDMD_FAR);
	lz_edmd_free(small);
	lz_edmd_free(big);
	/* the same start with and without: the same events and the same state, bit for
	 * bit, periodic in 3D and between walls in 2D */
	for (int walls = 0; walls < 2; walls++) {
		int dim = walls ? 2 : 3;
		lz_edmd *a = lattice(dim, 1500, 0.3, walls ? LZ_EDMD_WALLS_BOX : LZ_EDMD_WALLS_NONE, 5);
		lz_edmd *b = lattice(dim, 1500, 0.3, walls ? LZ_EDMD_WALLS_BOX : LZ_EDMD_WALLS_NONE, 5);
		a->prefetch = 0;
		b->prefetch = 1;
		LZ_REQUIRE_TRUE(lz_edmd_run(a, 30000, INFINITY) == LZ_OK &&
		          lz_edmd_run(b, 30000, INFINITY) == LZ_OK);
		LZ_REQUIRE(a->collisions == b->collisions && a->virial == b->virial &&
		                      lz_edmd_time(a) == lz_edmd_time(b),
		              "%dD: with and without prefetching, %llu / %llu collisions, virial "
		              "%.17g / %.17g", dim, (unsigned long long)a->collisions,
		              (unsigned long long)b->collisions, a->virial, b->virial);
		for (uint32_t i = 0; i < a->n; i++)
			LZ_REQUIRE(memcmp(&a->p[i], &b->p[i], sizeof a->p[i]) == 0,
			              "%dD: particle %u differs with and without prefetching", dim, i);
		lz_edmd_free(a);
		lz_edmd_free(b);
	}
	/* a heap big enough for sift down's prefetches still pops in order */
	lz_heap *h = lz_heap_alloc(LZ_HEAP_FAR + 1000);
	LZ_REQUIRE_TRUE(h);
	for (uint32_t id = 0; id < h->cap; id++)
		lz_heap_push(h, id, (double)((id * 2654435761u) % 1000003u));
	double last = -1;
	while (h->n > 0) {
		double t = lz_heap_top_t(h);
		LZ_REQUIRE(t >= last, "popped %g after %g", t, last);
		last = t;
		lz_heap_pop(h);
	}
	lz_heap_free(h);
}
END_TEST
