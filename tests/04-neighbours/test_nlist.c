/* test_nlist.c — Verlet neighbour lists on a lattice: the all-pairs build and the build
 * from cells equal a brute-force list (complete within r_l, nothing at or beyond it,
 * symmetric, no self entry, no duplicate) on square, triangular and cubic lattices,
 * across the periodic boundary, with r_l exactly on a lattice distance; the fast
 * refresh equals a rebuild after small moves in a dense fluid, keeps the particle of
 * thesis fig. 2.7 that the one-copy refresh loses, never writes its source, stays
 * free of self entries and duplicates where many neighbours are shared, and in a dilute
 * gas is exactly its definition (the neighbours of the neighbours, missing what they
 * cannot reach); N = 1, N = 2, N = 3 and a million particles.
 *
 * The references here use their own arithmetic (minimum image by trying the nearby
 * periodic images) and cell grids made by hand in this file, so a bug in the stage's
 * cell lists (test_cells.c) is not charged twice. The lists a refresh starts from are
 * written by the test too, from brute force: every refresh test checks the refresh
 * alone. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/cells.h"
#include "lz/lattice.h"
#include "lz/nlist.h"
#include "lztest.h"


/* ---- references, by brute force ---- */


static int kdim(lz_lattice_kind kind) { return kind >= LZ_LATTICE_CUBIC ? 3 : 2; }

/* The squared length of an integer displacement. On the triangular lattice (x, y) is
 * the point (x + y/2, y √3/2), whose 4 × length² is (2x + y)² + 3y². */
static int64_t bf_d2(lz_lattice_kind kind, int64_t x, int64_t y, int64_t z)
{
	if (kind == LZ_LATTICE_TRIANGULAR)
		return ((2 * x + y) * (2 * x + y) + 3 * y * y) / 4;
	if (kind >= LZ_LATTICE_CUBIC)
		return x * x + y * y + z * z;
	return x * x + y * y;
}

/* d reduced into (-L/2, L/2]. */
static int64_t bf_near(int64_t d, int64_t L)
{
	d %= L;
	if (d > L / 2)
		d -= L;
	if (d <= -L / 2)
		d += L;
	return d;
}

/* The minimum-image distance² of sites p and q: the displacement reduced into the
 * box around 0, then every image one box away tried as well (on the sheared
 * triangular lattice the nearest image need not be the reduced one). */
static int64_t bf_min_d2(lz_lattice_kind kind, int64_t L, const int32_t *p, const int32_t *q)
{
	int three = kdim(kind) == 3;
	int64_t x = bf_near(p[0] - q[0], L), y = bf_near(p[1] - q[1], L);
	int64_t z = three ? bf_near(p[2] - q[2], L) : 0;
	if (kind != LZ_LATTICE_TRIANGULAR)
		return bf_d2(kind, x, y, z);
	int64_t best = INT64_MAX;
	for (int a = -1; a <= 1; a++)
		for (int b = -1; b <= 1; b++) {
			int64_t d2 = bf_d2(kind, x + a * L, y + b * L, 0);
			if (d2 < best)
				best = d2;
		}
	return best;
}

/* "(x, y)" or "(x, y, z)" of particle i, in buf. */
static const char *at(char *buf, int dim, const int32_t *r, size_t i)
{
	const int32_t *p = r + i * (size_t)dim;
	if (dim == 3)
		snprintf(buf, 48, "(%d, %d, %d)", p[0], p[1], p[2]);
	else
		snprintf(buf, 48, "(%d, %d)", p[0], p[1]);
	return buf;
}

/* want[i·n + j] = 1 when j != i is within r_l of i (distance² < rl2): the list. */
static uint8_t *bf_matrix(lz_lattice_kind kind, int64_t L, size_t n, const int32_t *r,
                          int64_t rl2)
{
	int dim = kdim(kind);
	uint8_t *want = calloc(n * n, 1);
	ck_assert(want != NULL);
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++)
			if (bf_min_d2(kind, L, r + i * dim, r + j * dim) < rl2)
				want[i * n + j] = want[j * n + i] = 1;
	return want;
}

static size_t count_ones(const uint8_t *a, size_t n)
{
	size_t c = 0;
	for (size_t k = 0; k < n; k++)
		c += a[k];
	return c;
}

/* Fail, in physics words, unless the list in use is exactly `want`: a well-formed row
 * table, every entry a real particle, no self entry, no duplicate, nothing at or
 * beyond r_l, every pair within r_l on both rows. */
static void check_list(const lz_nlist *nl, const int32_t *r, const uint8_t *want,
                       const char *what)
{
	size_t n = nl->n;
	int dim = nl->dim;
	lz_lattice_kind kind = nl->box->kind;
	int64_t L = nl->box->side;
	const lz_nbuf *b = &nl->buf[nl->cur];
	char pi[48], pj[48];
	LZ_REQUIRE(nl->cur == 0 || nl->cur == 1, "%s: cur = %d, it must be 0 or 1", what,
	              nl->cur);
	LZ_REQUIRE(b->start[0] == 0, "%s: the list in use starts at start[0] = %u, not 0",
	              what, b->start[0]);
	for (size_t i = 0; i < n; i++)
		LZ_REQUIRE(b->start[i] <= b->start[i + 1], "%s: start[%zu] = %u > start[%zu] = "
		              "%u: the rows must lie back to back in index order", what, i,
		              b->start[i], i + 1, b->start[i + 1]);
	LZ_REQUIRE(b->start[n] == b->len && b->len <= b->cap, "%s: start[n] = %u, len = %zu, "
	              "cap = %zu: the last row must end at len (t->start[n] = t->len), within the "
	              "room", what, b->start[n], b->len, b->cap);
	uint8_t *seen = calloc(n, 1);
	ck_assert(seen != NULL);
	for (size_t i = 0; i < n; i++) {
		size_t len;
		const uint32_t *row = lz_nlist_row(nl, i, &len);
		for (size_t k = 0; k < len; k++) {
			uint32_t j = row[k];
			LZ_REQUIRE(j < n, "%s: row %zu holds %u, but there are only %zu particles",
			              what, i, j, n);
			LZ_REQUIRE(j != i, "%s: particle %zu is on its own row: a self entry (its "
			              "distance to itself is 0, so it would always count as its own "
			              "neighbour)", what, i);
			LZ_REQUIRE(!seen[j], "%s: particle %u is twice on the row of particle %zu: a "
			              "duplicate (a neighbour listed twice is felt twice)", what, j, i);
			seen[j] = 1;
			LZ_REQUIRE(want[i * n + j], "%s: particle %u at %s is on the row of %zu at "
			              "%s, but their distance² is %lld, not below r_l² = %lld (r_l = %g): "
			              "listed at or beyond the list radius (the rule is d < r_l, "
			              "strictly; distances are minimum-image)", what, j,
			              at(pj, dim, r, j), i, at(pi, dim, r, i),
			              (long long)bf_min_d2(kind, L, r + i * dim, r + j * dim),
			              (long long)nl->rl2, nl->rl);
		}
		for (size_t j = 0; j < n; j++) {
			if (!want[i * n + j] || seen[j])
				continue;
			const int32_t *p = r + i * dim, *q = r + j * dim;
			int64_t raw = bf_d2(kind, p[0] - q[0], p[1] - q[1], dim == 3 ? p[2] - q[2] : 0);
			int64_t d2 = bf_min_d2(kind, L, p, q);
			ck_abort_msg("%s: particles %zu at %s and %zu at %s are at distance² %lld, below "
			             "r_l² = %lld (r_l = %g), but %zu is not on the row of %zu: a missing "
			             "neighbour%s", what, i, at(pi, dim, r, i), j, at(pj, dim, r, j),
			             (long long)d2, (long long)nl->rl2, nl->rl, j, i,
			             raw != d2 ? " (they are close only through the periodic boundary: "
			                         "use the minimum image)" : "");
		}
		for (size_t k = 0; k < len; k++)
			seen[row[k]] = 0;
	}
	free(seen);
	size_t pairs = count_ones(want, n * n);
	LZ_REQUIRE(lz_nlist_entries(nl) == pairs, "%s: lz_nlist_entries = %zu, expected %zu",
	              what, lz_nlist_entries(nl), pairs);
}

/* Write `want` into the target of nl by hand and make it the list in use (the source
 * of the next refresh), rows in decreasing index order. */
static void fill_list(lz_nlist *nl, const uint8_t *want)
{
	size_t n = nl->n;
	lz_nbuf *t = &nl->buf[!nl->cur];
	t->len = 0;
	for (size_t i = 0; i < n; i++) {
		t->start[i] = (uint32_t)t->len;
		for (size_t j = n; j-- > 0;)
			if (want[i * n + j])
				LZ_REQUIRE(lz_nbuf_push(t, (uint32_t)j) == LZ_OK, "test set-up: no memory");
	}
	t->start[n] = (uint32_t)t->len;
	nl->cur = !nl->cur;
}

static void check_marks_clear(const lz_nlist *nl, const char *what)
{
	for (size_t i = 0; i < nl->n; i++)
		LZ_REQUIRE(nl->mark[i] == 0, "%s: mark[%zu] = %u after the call; mark[] must be "
		              "all 0 between calls (clear every mark you set, or the next row, or the "
		              "next refresh, refuses that particle)", what, i, nl->mark[i]);
}

static lz_lattice_box *box_new(lz_lattice_kind kind, int64_t L)
{
	lz_lattice_box *b = lz_lattice_box_alloc(kind, L);
	LZ_REQUIRE(b != NULL, "lz_lattice_box_alloc(%s, %lld): %s", lz_lattice_name(kind),
	              (long long)L, lz_error_message());
	return b;
}

static lz_nlist *nl_new(const lz_lattice_box *b, size_t n, double rl)
{
	lz_nlist *nl = lz_nlist_alloc(b, n, rl);
	LZ_REQUIRE(nl != NULL, "lz_nlist_alloc(n = %zu, rl = %g): %s", n, rl,
	              lz_error_message());
	return nl;
}

static void rand_sites(gsl_rng *g, int dim, int64_t L, size_t n, int32_t *r)
{
	for (size_t k = 0; k < n * (size_t)dim; k++)
		r[k] = (int32_t)gsl_rng_uniform_int(g, (unsigned long)L);
}

/* Random sequential placement of hard particles of diameter σ (no two centres closer
 * than σ: distance² >= sigma2) until n are placed; returns how many were. */
static size_t rsa_sites(gsl_rng *g, lz_lattice_kind kind, int64_t L, int64_t sigma2,
                        size_t n, int32_t *r)
{
	int dim = kdim(kind);
	size_t placed = 0;
	for (size_t t = 0; t < 2000 * n && placed < n; t++) {
		int32_t *p = r + placed * dim;
		rand_sites(g, dim, L, 1, p);
		int ok = 1;
		for (size_t j = 0; j < placed && ok; j++)
			ok = bf_min_d2(kind, L, p, r + j * dim) >= sigma2;
		placed += ok;
	}
	return placed;
}

/* The unit steps (length 1) of each lattice. */
static const int32_t steps2[6][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}};
static const int32_t steps3[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                     {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

/* Every particle offered `steps` random unit steps, each refused if it makes an overlap
 * (sigma2 > 0) — so no particle moves farther than `steps`. Returns the steps taken. */
static size_t hard_moves(gsl_rng *g, lz_lattice_kind kind, int64_t L, int64_t sigma2,
                         size_t n, int32_t *r, int steps)
{
	int dim = kdim(kind);
	unsigned long nd = kind == LZ_LATTICE_TRIANGULAR ? 6 : dim == 3 ? 6 : 4;
	size_t taken = 0;
	for (size_t i = 0; i < n; i++)
		for (int s = 0; s < steps; s++) {
			unsigned long d = gsl_rng_uniform_int(g, nd);
			int32_t p[3];
			for (int a = 0; a < dim; a++)
				p[a] = (int32_t)((r[i * dim + a] + (dim == 3 ? steps3[d][a] : steps2[d][a]) + L)
				                 % L);
			int ok = 1;
			for (size_t j = 0; j < n && ok && sigma2 > 0; j++)
				ok = j == i || bf_min_d2(kind, L, p, r + j * dim) >= sigma2;
			if (ok) {
				memcpy(r + i * dim, p, (size_t)dim * sizeof *p);
				taken++;
			}
		}
	return taken;
}

/* ---- cell grids made by hand (the layout of lz/cells.h) ---- */

/* A periodic lattice grid of side L cut into cells of side w (a power of two, L / w
 * >= 3), linked lists filled later by grid_bin. scramble: the cells are stored in a
 * random order (rank/unrank set), as a Morton grid would be — only full[] tells which
 * cells touch. */
static lz_cells *grid_new(int dim, int32_t L, int32_t w, int scramble, gsl_rng *g)
{
	lz_cells *c = calloc(1, sizeof *c);
	ck_assert(c != NULL);
	c->dim = dim;
	c->periodic = 1;
	c->side = L;
	c->cutoff = w;
	c->m = L / w;
	c->width = w;
	c->inv_width = (double)c->m / L;
	while ((1 << c->shift) < w)
		c->shift++;
	LZ_REQUIRE((1 << c->shift) == w && c->m >= 3, "test set-up: w = %d must be a power "
	              "of two with L / w >= 3", w);
	size_t m = (size_t)c->m, nc = dim == 3 ? m * m * m : m * m;
	c->ncells = nc;
	c->order = scramble ? LZ_CELLS_MORTON : LZ_CELLS_ROW;
	c->nfull = dim == 3 ? 27 : 9;
	c->nhalf = (c->nfull + 1) / 2;
	c->full = malloc((nc + 1) * (size_t)c->nfull * sizeof *c->full);
	c->head = malloc((nc + 1) * sizeof *c->head);
	uint32_t *perm = malloc(nc * sizeof *perm);
	ck_assert(c->full && c->head && perm);
	for (size_t q = 0; q < nc; q++)
		perm[q] = (uint32_t)q;
	if (scramble) {
		for (size_t q = nc - 1; q > 0; q--) {
			size_t k = gsl_rng_uniform_int(g, q + 1);
			uint32_t tmp = perm[q];
			perm[q] = perm[k];
			perm[k] = tmp;
		}
		c->rank = perm;
		c->unrank = malloc(nc * sizeof *c->unrank);
		ck_assert(c->unrank != NULL);
		for (size_t q = 0; q < nc; q++)
			c->unrank[perm[q]] = (uint32_t)q;
	}
	for (size_t q = 0; q < nc; q++) {
		int64_t cx = (int64_t)(q % m), cy = (int64_t)(q / m % m), cz = (int64_t)(q / (m * m));
		int k = 1;
		uint32_t *blk = c->full + (size_t)perm[q] * (size_t)c->nfull;
		blk[0] = perm[q];
		for (int a = dim == 3 ? -1 : 0; a <= (dim == 3 ? 1 : 0); a++)
			for (int b = -1; b <= 1; b++)
				for (int d = -1; d <= 1; d++) {
					if (a == 0 && b == 0 && d == 0)
						continue;
					size_t nx = (size_t)((cx + d + (int64_t)m) % (int64_t)m);
					size_t ny = (size_t)((cy + b + (int64_t)m) % (int64_t)m);
					size_t nz = (size_t)((cz + a + (int64_t)m) % (int64_t)m);
					blk[k++] = perm[nx + m * (ny + m * nz)];
				}
	}
	for (int k = 0; k < c->nfull; k++)
		c->full[nc * (size_t)c->nfull + (size_t)k] = (uint32_t)nc;
	for (size_t q = 0; q <= nc; q++)
		c->head[q] = -1;
	if (!scramble)
		free(perm);
	return c;
}

/* Bin n sites (x >> shift on every axis) and link them, each pushed at its cell's
 * head: the lists run in decreasing index. */
static void grid_bin(lz_cells *c, size_t n, const int32_t *r)
{
	int dim = c->dim;
	size_t m = (size_t)c->m;
	free(c->of);
	free(c->next);
	c->of = malloc(n * sizeof *c->of);
	c->next = malloc(n * sizeof *c->next);
	ck_assert(c->of && c->next);
	c->n = c->nmax = n;
	for (size_t q = 0; q <= c->ncells; q++)
		c->head[q] = -1;
	for (size_t i = 0; i < n; i++) {
		const int32_t *p = r + i * dim;
		size_t q = (size_t)(p[0] >> c->shift) + m * (size_t)(p[1] >> c->shift);
		if (dim == 3)
			q += m * m * (size_t)(p[2] >> c->shift);
		uint32_t s = c->rank ? c->rank[q] : (uint32_t)q;
		c->of[i] = s;
		c->next[i] = c->head[s];
		c->head[s] = (int32_t)i;
	}
}

static void grid_free(lz_cells *c)
{
	free(c->rank);
	free(c->unrank);
	free(c->full);
	free(c->head);
	free(c->of);
	free(c->next);
	free(c);
}

/* ---- the all-pairs build ---- */

LZ_TEST(allpairs_matches_brute_force)
{
	static const struct { lz_lattice_kind kind; int L; size_t n; double rl; } cs[] = {
		{LZ_LATTICE_SQUARE, 64, 200, 7.5}, {LZ_LATTICE_SQUARE8, 32, 80, 16},
		{LZ_LATTICE_TRIANGULAR, 64, 200, 6}, {LZ_LATTICE_TRIANGULAR, 16, 60, 7.5},
		{LZ_LATTICE_CUBIC, 16, 150, 4.5}, {LZ_LATTICE_CUBIC26, 8, 40, 2.9},
		/* r_l = L/2, the largest allowed: a pair L/2 apart along an axis is exactly r_l
		 * away through both images, and not listed */
		{LZ_LATTICE_SQUARE, 8, 30, 4},
	};
	gsl_rng *g = lz_test_rng(41);
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		int dim = kdim(cs[k].kind);
		lz_lattice_box *b = box_new(cs[k].kind, cs[k].L);
		lz_nlist *nl = nl_new(b, cs[k].n, cs[k].rl);
		int32_t *r = malloc(cs[k].n * (size_t)dim * sizeof *r);
		char what[160];
		/* Three builds on two configurations: each must replace the list in use. The
		 * first particles sit at the corners of the box, so pairs wrap round it. */
		for (int round = 0; round < 3; round++) {
			if (round < 2) {
				rand_sites(g, dim, cs[k].L, cs[k].n, r);
				for (int a = 0; a < dim; a++) {
					r[a] = 0;
					r[dim + a] = cs[k].L - 1;
					r[2 * dim + a] = a == 0 ? 1 : cs[k].L - 2;
				}
			} else {
				rand_sites(g, dim, cs[k].L, cs[k].n / 2, r);
			}
			snprintf(what, sizeof what, "all-pairs build %d, %s lattice, L = %d, %zu "
			         "particles, r_l = %g", round + 1, lz_lattice_name(cs[k].kind), cs[k].L,
			         cs[k].n, cs[k].rl);
			uint8_t *want = bf_matrix(cs[k].kind, cs[k].L, cs[k].n, r, nl->rl2);
			int cur = nl->cur;
			LZ_REQUIRE(lz_nlist_build_allpairs(nl, r) == LZ_OK, "%s: %s", what,
			              lz_error_message());
			LZ_REQUIRE(nl->cur == !cur, "%s: cur went from %d to %d; a build writes the "
			              "target buf[!cur] and then flips cur", what, cur, nl->cur);
			check_list(nl, r, want, what);
			free(want);
		}
		free(r);
		lz_nlist_free(nl);
		lz_lattice_box_free(b);
	}
	gsl_rng_free(g);
}
END_TEST

/* Build three times from the same sites: each build must give the list `want`. The
 * copies take turns as the target, so the third build writes over the first one's
 * list, which must not linger. */
static void build_allpairs_thrice(lz_nlist *nl, const int32_t *r, const uint8_t *want,
                                  const char *what)
{
	char again[200];
	snprintf(again, sizeof again, "%s, built a third time into the copy of the first build "
	         "(its old entries must go: t->len = 0 first)", what);
	for (int k = 0; k < 3; k++) {
		LZ_REQUIRE(lz_nlist_build_allpairs(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
		check_list(nl, r, want, k == 2 ? again : what);
	}
}

/* Pairs placed exactly at r_l (on an integer lattice distance) and just inside. */
LZ_TEST(allpairs_pair_at_exactly_rl_is_not_listed)
{
	/* Square, r_l = 5: (3, 4), (5, 0), (-4, 3) are at exactly 5; (4, 2) at √20. */
	static const int32_t sq[] = {10, 10, 13, 14, 15, 10, 6, 13, 14, 12, 0, 0, 61, 4, 1, 63};
	/* Triangular, r_l = 7: (7, 0), (5, 3), (-8, 3), (3, 5) are at exactly 7 (x² + xy + y²
	 * = 49); (4, 3) is at √37. The last two wrap: (-8, 3) from (2, 40). */
	static const int32_t tri[] = {20, 20, 27, 20, 25, 23, 12, 23, 23, 25, 24, 23, 2, 40, 58, 43};
	/* Cubic, r_l = 3: (2, 2, 1), (3, 0, 0), (1, 2, 2) at exactly 3; (2, 2, 0) at √8. */
	static const int32_t cub[] = {4, 4, 4, 6, 6, 5, 7, 4, 4, 5, 6, 6, 6, 6, 4, 0, 0, 0, 14, 14, 15};
	static const struct { lz_lattice_kind kind; int L; double rl; const int32_t *r; size_t n; }
	cs[] = {
		{LZ_LATTICE_SQUARE, 64, 5, sq, 8},
		{LZ_LATTICE_TRIANGULAR, 64, 7, tri, 8},
		{LZ_LATTICE_CUBIC, 16, 3, cub, 7},
		/* A hair above 5: the pairs at exactly 5 are now inside. */
		{LZ_LATTICE_SQUARE, 64, 5.000001, sq, 8},
	};
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		lz_lattice_box *b = box_new(cs[k].kind, cs[k].L);
		lz_nlist *nl = nl_new(b, cs[k].n, cs[k].rl);
		char what[160];
		snprintf(what, sizeof what, "%s lattice, r_l = %.7g, pairs placed at distances exactly "
		         "r_l and just below", lz_lattice_name(cs[k].kind), cs[k].rl);
		uint8_t *want = bf_matrix(cs[k].kind, cs[k].L, cs[k].n, cs[k].r, nl->rl2);
		build_allpairs_thrice(nl, cs[k].r, want, what);
		free(want);
		lz_nlist_free(nl);
		lz_lattice_box_free(b);
	}
}
END_TEST

LZ_TEST(allpairs_one_particle_and_pairs_across_the_boundary)
{
	/* One particle: one empty row. Two: neighbours only through the boundary (the
	 * triangular (8, 3) in L = 16 is at distance 7 through the image (-8, 3), though
	 * its components are the nearest ones). */
	static const int32_t one[] = {5, 5};
	static const int32_t sq[] = {0, 7, 63, 8};
	static const int32_t tri[] = {0, 0, 8, 3};
	static const int32_t tri_far[] = {0, 0, 15, 15};  /* (-1, -1): √3, beyond 1.5 */
	static const int32_t cub[] = {0, 0, 15, 15, 15, 0};
	static const struct { lz_lattice_kind kind; int L; double rl; const int32_t *r; size_t n;
	                      size_t pairs; } cs[] = {
		{LZ_LATTICE_SQUARE, 64, 3, one, 1, 0},
		{LZ_LATTICE_SQUARE, 64, 1.5, sq, 2, 1},
		{LZ_LATTICE_TRIANGULAR, 16, 7.5, tri, 2, 1},
		{LZ_LATTICE_TRIANGULAR, 16, 1.5, tri_far, 2, 0},
		{LZ_LATTICE_CUBIC, 16, 2, cub, 2, 1},
	};
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		lz_lattice_box *b = box_new(cs[k].kind, cs[k].L);
		lz_nlist *nl = nl_new(b, cs[k].n, cs[k].rl);
		char what[160];
		snprintf(what, sizeof what, "all pairs, %zu particle%s on the %s lattice (L = %d, r_l = "
		         "%g)", cs[k].n, cs[k].n > 1 ? "s" : "", lz_lattice_name(cs[k].kind), cs[k].L,
		         cs[k].rl);
		uint8_t *want = bf_matrix(cs[k].kind, cs[k].L, cs[k].n, cs[k].r, nl->rl2);
		LZ_REQUIRE(count_ones(want, cs[k].n * cs[k].n) == 2 * cs[k].pairs, "test set-up");
		build_allpairs_thrice(nl, cs[k].r, want, what);
		free(want);
		lz_nlist_free(nl);
		lz_lattice_box_free(b);
	}
}
END_TEST

/* ---- the build from cells ---- */

/* Build from a hand-made grid of cell side w and compare with brute force. */
static void cells_case(lz_lattice_kind kind, int32_t L, int32_t w, double rl, size_t n,
                       const int32_t *r, int scramble, gsl_rng *g, const char *what)
{
	lz_lattice_box *b = box_new(kind, L);
	lz_nlist *nl = nl_new(b, n, rl);
	lz_cells *c = grid_new(kdim(kind), L, w, scramble, g);
	grid_bin(c, n, r);
	uint8_t *want = bf_matrix(kind, L, n, r, nl->rl2);
	int cur = nl->cur;
	LZ_REQUIRE(lz_nlist_build_cells(nl, c, r) == LZ_OK, "%s: %s", what, lz_error_message());
	LZ_REQUIRE(nl->cur == !cur, "%s: cur went from %d to %d; a build writes the target "
	              "buf[!cur] and then flips cur", what, cur, nl->cur);
	check_list(nl, r, want, what);
	/* Once more on the same grid: the new list replaces the old one. */
	LZ_REQUIRE(lz_nlist_build_cells(nl, c, r) == LZ_OK, "%s: %s", what, lz_error_message());
	check_list(nl, r, want, what);
	free(want);
	grid_free(c);
	lz_nlist_free(nl);
	lz_lattice_box_free(b);
}

LZ_TEST(cells_build_matches_brute_force)
{
	static const struct { lz_lattice_kind kind; int L, w; size_t n; double rl; } cs[] = {
		{LZ_LATTICE_SQUARE, 64, 8, 300, 7.5}, {LZ_LATTICE_TRIANGULAR, 64, 8, 300, 6},
		{LZ_LATTICE_SQUARE8, 32, 8, 150, 5.5}, {LZ_LATTICE_CUBIC, 32, 8, 400, 4.5},
		{LZ_LATTICE_CUBIC18, 16, 4, 150, 2.5},
	};
	gsl_rng *g = lz_test_rng(43);
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++)
		for (int scramble = 0; scramble < 2; scramble++) {
			int dim = kdim(cs[k].kind);
			int32_t *r = malloc(cs[k].n * (size_t)dim * sizeof *r);
			rand_sites(g, dim, cs[k].L, cs[k].n, r);
			char what[200];
			snprintf(what, sizeof what, "build from cells, %s lattice, L = %d, %zu particles, "
			         "r_l = %g, cells of side %d stored %s", lz_lattice_name(cs[k].kind),
			         cs[k].L, cs[k].n, cs[k].rl, cs[k].w,
			         scramble ? "out of row order (use c->full for the block)" : "by rows");
			cells_case(cs[k].kind, cs[k].L, cs[k].w, cs[k].rl, cs[k].n, r, scramble, g, what);
			free(r);
		}
	gsl_rng_free(g);
}
END_TEST

/* Cells exactly as wide as the reach of r_l, 4 per side, with pairs straddling cell
 * faces and the box's faces at just below r_l and exactly at it. */
LZ_TEST(cells_side_exactly_reach_four_cells_per_side)
{
	/* Square, r_l = 16 = w: (15, 0) across a face, (15, 5) at √250, (-15, 0) across the
	 * box, (16, 0) exactly r_l. */
	static const int32_t sq[] = {15, 8, 30, 8, 0, 40, 15, 45, 0, 20, 49, 20, 33, 60, 49, 60,
	                             47, 2, 47, 50};
	/* Triangular, r_l = 13.8, reach ceil(2 r_l/√3) = 16 = w: (15, -8) at √169 spans 15
	 * cells' worth of x; (-15, 8) wraps. */
	static const int32_t tri[] = {16, 40, 31, 32, 2, 10, 51, 18, 40, 40, 40, 55};
	static const struct { lz_lattice_kind kind; int L, w; double rl; const int32_t *r; size_t nfix; }
	cs[] = {
		{LZ_LATTICE_SQUARE, 64, 16, 16, sq, 10},
		{LZ_LATTICE_TRIANGULAR, 64, 16, 13.8, tri, 6},
		{LZ_LATTICE_CUBIC, 32, 8, 8, NULL, 0},
	};
	gsl_rng *g = lz_test_rng(47);
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		int dim = kdim(cs[k].kind);
		LZ_REQUIRE(lz_lattice_reach(cs[k].kind, cs[k].rl) == cs[k].w, "test set-up: reach");
		size_t n = cs[k].nfix + 120;
		int32_t *r = malloc(n * (size_t)dim * sizeof *r);
		if (cs[k].nfix)
			memcpy(r, cs[k].r, cs[k].nfix * (size_t)dim * sizeof *r);
		rand_sites(g, dim, cs[k].L, n - cs[k].nfix, r + cs[k].nfix * dim);
		for (int scramble = 0; scramble < 2; scramble++) {
			char what[200];
			snprintf(what, sizeof what, "build from cells, %s lattice, r_l = %g, cells of side "
			         "%d = the reach of r_l, %d per side", lz_lattice_name(cs[k].kind),
			         cs[k].rl, cs[k].w, cs[k].L / cs[k].w);
			cells_case(cs[k].kind, cs[k].L, cs[k].w, cs[k].rl, n, r, scramble, g, what);
		}
		free(r);
	}
	gsl_rng_free(g);
}
END_TEST

LZ_TEST(cells_all_particles_in_one_cell)
{
	/* Forty particles in the last cell of the grid (its block wraps round the box),
	 * two pairs of them on the same site: distinct particles at distance 0 are
	 * neighbours (only i itself is left off its row). Six more sit just across the
	 * box's faces and its corner, in cells that touch the crowded one only through the
	 * wrap: each is a neighbour of some of the forty. */
	gsl_rng *g = lz_test_rng(53);
	for (int three = 0; three < 2; three++) {
		lz_lattice_kind kind = three ? LZ_LATTICE_CUBIC : LZ_LATTICE_SQUARE;
		int dim = kdim(kind);
		size_t n = 46;
		int32_t r[46 * 3];
		for (size_t k = 0; k < 40 * (size_t)dim; k++)
			r[k] = 56 + (int32_t)gsl_rng_uniform_int(g, 8);
		memcpy(r + 5 * dim, r + 4 * dim, (size_t)dim * sizeof *r);
		memcpy(r + 39 * dim, r, (size_t)dim * sizeof *r);
		for (size_t e = 0; e < 6; e++) {
			int32_t *p = r + (40 + e) * (size_t)dim;
			for (int a = 0; a < dim; a++)
				p[a] = e == 5 ? 1 : 60 + (int32_t)(e % 4);
			if (e < 5)
				p[e % (size_t)dim] = (int32_t)(e % 3);
		}
		char what[200];
		snprintf(what, sizeof what, "build from cells, %s lattice: 40 particles crowded in "
		         "one cell of side 8 (two pairs on one site), 6 more just across the box's "
		         "faces and corner", lz_lattice_name(kind));
		cells_case(kind, 64, 8, 7.5, n, r, 1, g, what);
	}
	gsl_rng_free(g);
}
END_TEST

LZ_TEST(cells_one_particle_and_pairs_across_the_boundary)
{
	static const int32_t one[] = {5, 60};
	static const int32_t sq[] = {0, 7, 63, 8};
	static const int32_t tri[] = {0, 0, 31, 1};
	static const int32_t cub[] = {0, 31, 0, 31, 0, 31};
	gsl_rng *g = lz_test_rng(59);
	cells_case(LZ_LATTICE_SQUARE, 64, 4, 3, 1, one, 0, g,
	           "build from cells, one particle (its row must stay empty)");
	cells_case(LZ_LATTICE_SQUARE, 64, 4, 1.5, 2, sq, 0, g,
	           "build from cells, two particles neighbours across the box's edge");
	cells_case(LZ_LATTICE_TRIANGULAR, 32, 4, 3, 2, tri, 0, g,
	           "build from cells, two nearest neighbours (-1, 1) on the triangular lattice "
	           "across the box's edge");
	cells_case(LZ_LATTICE_CUBIC, 32, 4, 2, 2, cub, 1, g,
	           "build from cells, two particles neighbours across a corner of the box");
	gsl_rng_free(g);
}
END_TEST

/* One refused build: LZ_EINVAL, a message, and the list in use untouched. */
static void refused(lz_nlist *nl, const lz_cells *c, const int32_t *r, const char *why)
{
	int cur = nl->cur;
	size_t entries = lz_nlist_entries(nl);
	int st = lz_nlist_build_cells(nl, c, r);
	LZ_REQUIRE(st == LZ_EINVAL, "lz_nlist_build_cells returned %d on %s; it must refuse "
	              "with LZ_EINVAL (such cells cannot give the right list)", st, why);
	LZ_REQUIRE(lz_error_message()[0] != '\0', "refusing %s, lz_error must say why", why);
	LZ_REQUIRE(nl->cur == cur && lz_nlist_entries(nl) == entries, "refusing %s, the list "
	              "in use changed: a refused build must leave it alone", why);
}

LZ_TEST(cells_refuses_a_grid_that_cannot_work)
{
	gsl_rng *g = lz_test_rng(61);
	enum { N = 50 };
	int32_t r[N * 3];
	rand_sites(g, 2, 64, N, r);
	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, 64);
	lz_lattice_box *bt = box_new(LZ_LATTICE_TRIANGULAR, 64);
	lz_nlist *nl = nl_new(b, N, 7.5);
	lz_nlist *nt = nl_new(bt, N, 7);
	uint8_t *want = bf_matrix(LZ_LATTICE_SQUARE, 64, N, r, nl->rl2);
	fill_list(nl, want);

	lz_cells *narrow = grid_new(2, 64, 4, 0, g);  /* 4 < reach 8 */
	grid_bin(narrow, N, r);
	refused(nl, narrow, r, "cells of side 4 for r_l = 7.5 (a pair could be two cells apart)");
	/* Triangular r_l = 7 reaches 9 sites along an axis: side 8 >= r_l is not enough. */
	lz_cells *tri8 = grid_new(2, 64, 8, 0, g);
	grid_bin(tri8, N, r);
	refused(nt, tri8, r, "cells of side 8 on the triangular lattice for r_l = 7, whose reach "
	        "is ceil(2·7/√3) = 9");
	lz_cells *other = grid_new(2, 128, 16, 0, g);
	grid_bin(other, N, r);
	refused(nl, other, r, "a grid of side 128 for a box of side 64");
	lz_cells *deep = grid_new(3, 64, 16, 0, g);
	int32_t r3[N * 3];
	rand_sites(g, 3, 64, N, r3);
	grid_bin(deep, N, r3);
	refused(nl, deep, r, "a 3D grid for a 2D box");
	lz_cells *fresh = grid_new(2, 64, 16, 0, g);
	refused(nl, fresh, r, "a grid on which nothing was binned (c->n = 0)");
	grid_bin(fresh, N - 1, r);
	refused(nl, fresh, r, "a grid binned on 49 of the 50 particles");
	grid_bin(fresh, N, r);
	fresh->shift = -1;  /* as lz_cells_alloc makes it for continuous points */
	refused(nl, fresh, r, "a grid for continuous points (shift = -1), not for lattice sites");
	/* What can work must not be refused: cells exactly as wide as the reach 8 of
	 * r_l = 7.5, stored out of row order. */
	lz_cells *right = grid_new(2, 64, 8, 1, g);
	grid_bin(right, N, r);
	LZ_REQUIRE(lz_nlist_build_cells(nl, right, r) == LZ_OK, "lz_nlist_build_cells refused "
	       "cells of side 8 for r_l = 7.5 on the square lattice, exactly its reach ceil(7.5) "
	       "= 8: a pair within r_l differs by at most 7 < 8 on each axis, so it sits in "
	       "touching cells and the grid is fine (refuse only width < reach): %s",
	       lz_error_message());
	check_list(nl, r, want, "build from cells exactly as wide as the reach of r_l, after the "
	           "refusals");
	free(want);
	grid_free(right);

	grid_free(narrow);
	grid_free(tri8);
	grid_free(other);
	grid_free(deep);
	grid_free(fresh);
	lz_nlist_free(nl);
	lz_nlist_free(nt);
	lz_lattice_box_free(b);
	lz_lattice_box_free(bt);
	gsl_rng_free(g);
}
END_TEST

/* A million particles on a 2048² square box, r_l = 3, from cells of side 4. Every
 * listed pair is checked, and the number of pairs is counted independently: the
 * occupation of every site, summed over the 25 offsets with x² + y² < 9 around each
 * particle (less the particle itself). */
LZ_TEST(cells_million_particles_2d)
{
	enum { L = 2048 };
	const size_t n = 1000000;
	gsl_rng *g = lz_test_rng(67);
	int32_t *r = malloc(2 * n * sizeof *r);
	uint8_t *occ = calloc((size_t)L * L, 1);
	uint32_t *stamp = calloc(n, sizeof *stamp);
	ck_assert(r && occ && stamp);
	rand_sites(g, 2, L, n, r);
	for (size_t i = 0; i < n; i++) {
		uint8_t *o = occ + (size_t)r[2 * i] + (size_t)L * (size_t)r[2 * i + 1];
		LZ_REQUIRE(*o < 255, "test set-up: a site holds 255 particles");
		(*o)++;
	}
	size_t want = 0;
	for (size_t i = 0; i < n; i++)
		for (int dy = -2; dy <= 2; dy++)
			for (int dx = -2; dx <= 2; dx++)
				if (dx * dx + dy * dy < 9)
					want += occ[(size_t)((r[2 * i] + dx) & (L - 1)) +
					            (size_t)L * (size_t)((r[2 * i + 1] + dy) & (L - 1))];
	want -= n;
	free(occ);

	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, L);
	lz_nlist *nl = nl_new(b, n, 3);
	lz_cells *c = grid_new(2, L, 4, 0, g);
	grid_bin(c, n, r);
	LZ_REQUIRE(lz_nlist_build_cells(nl, c, r) == LZ_OK, "a million particles: %s",
	              lz_error_message());
	const char *what = "a million particles from cells (L = 2048, r_l = 3)";
	for (size_t i = 0; i < n; i++) {
		size_t len;
		const uint32_t *row = lz_nlist_row(nl, i, &len);
		for (size_t k = 0; k < len; k++) {
			uint32_t j = row[k];
			LZ_REQUIRE(j < n && j != i, "%s: row %zu holds %u (a self entry or no "
			              "particle)", what, i, j);
			LZ_REQUIRE(stamp[j] != i + 1, "%s: particle %u twice on the row of %zu: a "
			              "duplicate", what, j, i);
			stamp[j] = (uint32_t)(i + 1);
			int64_t dx = bf_near(r[2 * i] - r[2 * j], L);
			int64_t dy = bf_near(r[2 * i + 1] - r[2 * j + 1], L);
			LZ_REQUIRE(dx * dx + dy * dy < 9, "%s: particle %u on the row of %zu at "
			              "distance² %lld, not below r_l² = 9", what, j, i,
			              (long long)(dx * dx + dy * dy));
			size_t lj;
			const uint32_t *back = lz_nlist_row(nl, j, &lj);
			int found = 0;
			for (size_t q = 0; q < lj && !found; q++)
				found = back[q] == i;
			LZ_REQUIRE(found, "%s: %u is on the row of %zu but %zu is not on the row of "
			              "%u: the list must be symmetric", what, j, i, i, j);
		}
	}
	LZ_REQUIRE(lz_nlist_entries(nl) == want, "%s: %zu entries, but the particles have "
	              "%zu neighbours within r_l in all (counted site by site): pairs are missing",
	              what, lz_nlist_entries(nl), want);
	free(stamp);
	grid_free(c);
	lz_nlist_free(nl);
	lz_lattice_box_free(b);
	free(r);
	gsl_rng_free(g);
}
END_TEST

/* ---- the fast refresh ---- */

/* Fail (as a defect of the test, not of the code) unless every pair in `now` was in
 * `old` or had a common neighbour there — the condition under which the refresh must
 * equal a rebuild. Returns the pairs that entered the list. */
static size_t entered_via_common(const uint8_t *old, const uint8_t *now, size_t n,
                                 const char *what)
{
	size_t entered = 0;
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++) {
			if (!now[i * n + j] || old[i * n + j])
				continue;
			entered++;
			int common = 0;
			for (size_t k = 0; k < n && !common; k++)
				common = old[i * n + k] && old[k * n + j];
			LZ_REQUIRE(common, "test set-up (%s): pair %zu-%zu entered r_l without a "
			              "common neighbour; the fast refresh is not exact here", what, i, j);
		}
	return entered;
}

LZ_TEST(refresh_dense_random_moves_equals_rebuild)
{
	/* Hard disks of diameter σ = 4 at packing 0.45, r_l = 16 (hard spheres of σ = 3 at
	 * packing 0.35, r_l = 8): each particle takes at most 2 unit steps between
	 * refreshes, less than half the skin Δr = r_l - σ, so a pair that enters r_l was
	 * less than r_l + 4 apart at the last refresh. The refresh finds it exactly when
	 * the two had a neighbour in common then: some particle in the lens where their two
	 * disks of radius r_l overlap. Here that lens holds 10 to 30 particles on average
	 * (a bet on density, lz/nlist.h — with r_l = 10 about one entering pair in a few
	 * thousand has no common neighbour and is lost). For these fixed seeds it holds for
	 * every pair: checked by brute force before each refresh (entered_via_common), as
	 * is that pairs do enter (the scan of the neighbours' rows is needed). */
	static const struct { lz_lattice_kind kind; int L; int64_t sigma; double rl, packing; } cs[] = {
		{LZ_LATTICE_SQUARE, 128, 4, 16, 0.45},
		{LZ_LATTICE_TRIANGULAR, 128, 4, 16, 0.45},
		{LZ_LATTICE_CUBIC, 32, 3, 8, 0.35},
	};
	gsl_rng *g = lz_test_rng(71);
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		lz_lattice_kind kind = cs[k].kind;
		int dim = kdim(kind);
		double vol = pow(cs[k].L, dim) * (kind == LZ_LATTICE_TRIANGULAR ? sqrt(3) / 2 : 1);
		int64_t sigma = cs[k].sigma;
		double one = dim == 2 ? M_PI * sigma * sigma / 4 : M_PI * pow(sigma, 3) / 6;
		size_t n = (size_t)(cs[k].packing * vol / one);
		int32_t *r = malloc(n * (size_t)dim * sizeof *r);
		LZ_REQUIRE(rsa_sites(g, kind, cs[k].L, sigma * sigma, n, r) == n, "test set-up: "
		              "could not place %zu hard particles", n);
		lz_lattice_box *b = box_new(kind, cs[k].L);
		lz_nlist *nl = nl_new(b, n, cs[k].rl);
		uint8_t *want = bf_matrix(kind, cs[k].L, n, r, nl->rl2);
		fill_list(nl, want);
		size_t entered = 0;
		for (int round = 1; round <= 4; round++) {
			char what[200];
			snprintf(what, sizeof what, "refresh %d after moves of at most 2 steps, %zu hard "
			         "particles of diameter %d at packing %.2f on the %s lattice, r_l = %g",
			         round, n, (int)sigma, cs[k].packing, lz_lattice_name(kind), cs[k].rl);
			LZ_REQUIRE(hard_moves(g, kind, cs[k].L, sigma * sigma, n, r, 2) > n / 4, "test set-up: "
			       "the particles hardly move");
			uint8_t *old = want;
			want = bf_matrix(kind, cs[k].L, n, r, nl->rl2);
			entered += entered_via_common(old, want, n, what);
			free(old);
			int cur = nl->cur;
			LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
			LZ_REQUIRE(nl->cur == !cur, "%s: cur went from %d to %d; a refresh writes the "
			              "target buf[!cur] and then flips cur", what, cur, nl->cur);
			check_list(nl, r, want, what);
			check_marks_clear(nl, what);
		}
		LZ_REQUIRE(entered > 0, "test set-up: no pair entered r_l");
		free(want);
		free(r);
		lz_nlist_free(nl);
		lz_lattice_box_free(b);
	}
	gsl_rng_free(g);
}
END_TEST

/* Thesis fig. 2.7 on the square lattice, r_l = 5, particles A = 0, B = 1, C = 2:
 * before, A-B at 4 and A-C at 3 are listed, B-C at 7 is not; then C jumps past A to
 * 3 from B and 7 from A. The one-copy refresh rewrites A's row first and drops C, so
 * B's scan of A's row no longer finds C. A fourth particle D = 3 makes a triangle with
 * A and B before (√13 from each), then steps to √17 from A and exactly r_l from B:
 * A meets D on its own row and again on B's (listed once), and B must drop it (the
 * rule is d < r_l). Done twice: in the open and with the four straddling the box's
 * edge. */
LZ_TEST(refresh_fig27_second_copy_keeps_c)
{
	static const int32_t before[] = {20, 20, 24, 20, 17, 20, 22, 23};
	static const int32_t after[] = {20, 20, 24, 20, 27, 20, 21, 24};
	static const int32_t shift[2][2] = {{0, 0}, {-22, 45}};
	enum { N = 4 };
	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, 64);
	for (int s = 0; s < 2; s++) {
		int32_t r0[2 * N], r1[2 * N];
		for (int k = 0; k < 2 * N; k++) {
			r0[k] = (before[k] + shift[s][k % 2] + 64) % 64;
			r1[k] = (after[k] + shift[s][k % 2] + 64) % 64;
		}
		uint8_t *w0 = bf_matrix(LZ_LATTICE_SQUARE, 64, N, r0, 25);
		uint8_t *w1 = bf_matrix(LZ_LATTICE_SQUARE, 64, N, r1, 25);
		LZ_REQUIRE(w0[0 * N + 1] && w0[0 * N + 2] && !w0[1 * N + 2] && w0[0 * N + 3] &&
		       w0[1 * N + 3] && w1[0 * N + 1] && w1[1 * N + 2] && !w1[0 * N + 2] &&
		       w1[0 * N + 3] && !w1[1 * N + 3] && !w1[2 * N + 3] &&
		       bf_min_d2(LZ_LATTICE_SQUARE, 64, r1 + 2, r1 + 6) == 25,
		       "test set-up: the geometry of fig. 2.7");
		/* The example does what the thesis says: one copy loses C. */
		lz_nlist *one = nl_new(b, N, 5);
		fill_list(one, w0);
		ck_assert(lz_nlist_refresh_single(one, r1) == LZ_OK);
		size_t len;
		const uint32_t *row = lz_nlist_row(one, 1, &len);
		LZ_REQUIRE(len == 1 && row[0] == 0, "test set-up: the one-copy refresh should have "
		              "lost C from B's row");
		lz_nlist_free(one);

		lz_nlist *nl = nl_new(b, N, 5);
		fill_list(nl, w0);
		const char *what = s ? "thesis fig. 2.7 (A, B, C, D across the box's edge): C moved "
		                       "from A's range into B's, D to exactly r_l from B"
		                     : "thesis fig. 2.7: C moved from A's range into B's, D to "
		                       "exactly r_l from B";
		LZ_REQUIRE(lz_nlist_refresh(nl, r1) == LZ_OK, "%s: %s", what, lz_error_message());
		row = lz_nlist_row(nl, 1, &len);
		int has_c = 0;
		for (size_t k = 0; k < len; k++)
			has_c |= row[k] == 2;
		LZ_REQUIRE(has_c, "%s: C (particle 2) is 3 from B (particle 1) but not on B's new "
		              "row. B's source row holds A, and A's SOURCE row holds C: read the old "
		              "rows only (the source buf[cur]), never the rows being rewritten", what);
		check_list(nl, r1, w1, what);
		check_marks_clear(nl, what);
		free(w0);
		free(w1);
		lz_nlist_free(nl);
	}
	lz_lattice_box_free(b);
}
END_TEST

LZ_TEST(refresh_never_writes_the_source)
{
	gsl_rng *g = lz_test_rng(73);
	enum { L = 64 };
	const int64_t sigma2 = 16;
	size_t n = 150;
	int32_t r[300];
	ck_assert(rsa_sites(g, LZ_LATTICE_SQUARE, L, sigma2, n, r) == n);
	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, L);
	lz_nlist *nl = nl_new(b, n, 12);
	uint8_t *want = bf_matrix(LZ_LATTICE_SQUARE, L, n, r, nl->rl2);
	fill_list(nl, want);
	uint32_t *start = malloc((n + 1) * sizeof *start);
	for (int round = 0; round < 3; round++) {
		char what[160];
		snprintf(what, sizeof what, "refresh %d of 150 hard disks (diameter 4, r_l = 12) "
		         "after moves of one step", round + 1);
		hard_moves(g, LZ_LATTICE_SQUARE, L, sigma2, n, r, 1);
		uint8_t *old = want;
		want = bf_matrix(LZ_LATTICE_SQUARE, L, n, r, nl->rl2);
		entered_via_common(old, want, n, what);
		free(old);
		int cur = nl->cur;
		const lz_nbuf *s = &nl->buf[cur];
		size_t len = s->len;
		memcpy(start, s->start, (n + 1) * sizeof *start);
		uint32_t *idx = malloc((len + 1) * sizeof *idx);
		memcpy(idx, s->idx, len * sizeof *idx);
		LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s", lz_error_message());
		LZ_REQUIRE(nl->cur == !cur, "refresh %d: cur went from %d to %d; the refresh "
		              "writes the target buf[!cur] and then flips cur", round + 1, cur, nl->cur);
		LZ_REQUIRE(s->len == len && memcmp(start, s->start, (n + 1) * sizeof *start) == 0 &&
		              memcmp(idx, s->idx, len * sizeof *idx) == 0, "refresh %d wrote into its "
		              "source buf[%d]: rows must be read from the old lists and written to the "
		              "other copy only (thesis fig. 2.7: a row rewritten in place hides the "
		              "particles it dropped from the rows scanned after it)", round + 1, cur);
		free(idx);
		/* A source left alone is not enough: the new list must be the right one. */
		check_list(nl, r, want, what);
		check_marks_clear(nl, what);
	}
	free(want);
	free(start);
	lz_nlist_free(nl);
	lz_lattice_box_free(b);
	gsl_rng_free(g);
}
END_TEST

/* The refresh's result by its definition (lz/nlist.h): j on row i when j != i is
 * within r_l now (now[]) and was on i's source row or on the source row of a particle
 * there (src[]). Symmetric when src is. */
static uint8_t *spec_refresh(const uint8_t *src, const uint8_t *now, size_t n)
{
	uint8_t *w = calloc(n * n, 1);
	ck_assert(w != NULL);
	for (size_t i = 0; i < n; i++)
		for (size_t j = 0; j < n; j++) {
			int cand = src[i * n + j];
			for (size_t k = 0; k < n && !cand; k++)
				cand = src[i * n + k] && src[k * n + j];
			w[i * n + j] = now[i * n + j] && cand;
		}
	return w;
}

/* Fail if a row of the list in use holds a pair that is within r_l but that the
 * definition leaves out (now[] but not want[]): found beyond the rows it may read. */
static void check_no_outsider(const lz_nlist *nl, const uint8_t *now, const uint8_t *want,
                              const char *what)
{
	size_t n = nl->n;
	for (size_t i = 0; i < n; i++) {
		size_t len;
		const uint32_t *row = lz_nlist_row(nl, i, &len);
		for (size_t k = 0; k < len; k++) {
			uint32_t j = row[k];
			LZ_REQUIRE(j >= n || !now[i * n + j] || want[i * n + j], "%s: particle %u came "
			       "within r_l of %zu and is on its row, but it was on neither %zu's source "
			       "row nor the source row of any particle there: the refresh reads only "
			       "those rows and must miss such a pair (lz/nlist.h, the bet on density) — "
			       "is it rebuilding from all pairs, or from cells?", what, j, i, i);
		}
	}
}

/* A dilute gas: 60 particles on a 64² square box, r_l = 6, three random unit steps per
 * particle (no hard core) between refreshes. Some pairs come within r_l with no
 * common neighbour, and the refresh must miss them, as its definition says; the list
 * in use must be exactly that definition applied to the source, every time (the source
 * of the next refresh being the incomplete list of the last). */
LZ_TEST(refresh_dilute_gas_keeps_to_the_neighbours_of_neighbours)
{
	enum { L = 64, N = 60 };
	gsl_rng *g = lz_test_rng(83);
	int32_t r[2 * N];
	rand_sites(g, 2, L, N, r);
	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, L);
	lz_nlist *nl = nl_new(b, N, 6);
	uint8_t *src = bf_matrix(LZ_LATTICE_SQUARE, L, N, r, nl->rl2);
	fill_list(nl, src);
	size_t lost = 0, found = 0;
	for (int round = 1; round <= 4; round++) {
		char what[160];
		snprintf(what, sizeof what, "refresh %d of a dilute gas of 60 particles (r_l = 6, "
		         "three random steps each between refreshes)", round);
		hard_moves(g, LZ_LATTICE_SQUARE, L, 0, N, r, 3);
		uint8_t *now = bf_matrix(LZ_LATTICE_SQUARE, L, N, r, nl->rl2);
		uint8_t *want = spec_refresh(src, now, N);
		for (size_t k = 0; k < (size_t)N * N; k++) {
			lost += now[k] && !want[k];
			found += want[k] && !src[k];
		}
		LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
		check_no_outsider(nl, now, want, what);
		check_list(nl, r, want, what);
		check_marks_clear(nl, what);
		free(now);
		free(src);
		src = want;
	}
	LZ_REQUIRE(lost > 0 && found > 0, "test set-up: %zu entries lost, %zu found through a "
	       "neighbour's row; both must happen", lost, found);
	free(src);
	lz_nlist_free(nl);
	lz_lattice_box_free(b);
	gsl_rng_free(g);
}
END_TEST

/* Tight clusters (every member within r_l of every other) side by side: each particle
 * is reached through many neighbours, and itself through every one of them. */
LZ_TEST(refresh_no_self_no_duplicates_in_clusters)
{
	enum { L = 64, PER = 9, NCL = 6, N = PER * NCL + 3 };
	static const int32_t centre[NCL][2] = {{10, 10}, {15, 10}, {10, 15}, {15, 16},
	                                       {0, 0}, {60, 4}};
	int32_t r[2 * N];
	for (int c = 0; c < NCL; c++)
		for (int k = 0; k < PER; k++) {
			r[2 * (c * PER + k)] = (centre[c][0] + k % 3 - 1 + L) % L;
			r[2 * (c * PER + k) + 1] = (centre[c][1] + k / 3 - 1 + L) % L;
		}
	/* X and Y exactly r_l = 6 apart, Z a common neighbour of both: Y reaches X's
	 * candidates through Z, and must still be refused. */
	static const int32_t xyz[] = {40, 40, 46, 40, 43, 42};
	memcpy(r + 2 * PER * NCL, xyz, sizeof xyz);
	gsl_rng *g = lz_test_rng(79);
	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, L);
	lz_nlist *nl = nl_new(b, N, 6);
	uint8_t *want = bf_matrix(LZ_LATTICE_SQUARE, L, N, r, nl->rl2);
	fill_list(nl, want);
	for (int round = 1; round <= 3; round++) {
		char what[160];
		snprintf(what, sizeof what, "refresh %d of clusters of 9 particles within r_l = 6 of "
		         "each other (many common neighbours)", round);
		if (round > 1)
			hard_moves(g, LZ_LATTICE_SQUARE, L, 0, PER * NCL, r, 1);
		uint8_t *old = want;
		want = bf_matrix(LZ_LATTICE_SQUARE, L, N, r, nl->rl2);
		entered_via_common(old, want, N, what);
		free(old);
		LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
		check_list(nl, r, want, what);
		check_marks_clear(nl, what);
	}
	free(want);
	lz_nlist_free(nl);
	lz_lattice_box_free(b);
	gsl_rng_free(g);
}
END_TEST

/* Three particles straddling the box's edge, r_l = 3. First thesis fig. 2.7 across
 * it: A = 0 at (0, 10) is 2 from B = 1 at (62, 10) and from C = 2 at (2, 10), which
 * are 4 apart; C jumps to (61, 11), √10 from A and √2 from B. A's row, done first,
 * drops C, and B finds C only on A's SOURCE row. Then C steps to (63, 11), √2 from
 * both: A and C meet again through B, and the three are all neighbours. A last refresh
 * without a move starts from that triangle, where each particle meets each other one
 * twice (on its own row and on the third one's): listed once. */
static void three_across_the_edge(const lz_lattice_box *b)
{
	lz_nlist *nl = nl_new(b, 3, 3);
	int32_t r[6] = {0, 10, 62, 10, 61, 11};
	uint8_t star[9] = {0, 1, 1, 1, 0, 0, 1, 0, 0}, chain[9] = {0, 1, 0, 1, 0, 1, 0, 1, 0};
	uint8_t all[9] = {0, 1, 1, 1, 0, 1, 1, 1, 0};
	fill_list(nl, star);
	const char *what = "refresh of A, B, C across the box's edge: C left A's range for B's "
	                   "(fig. 2.7; B's source row holds A, A's source row holds C)";
	LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
	check_list(nl, r, chain, what);
	check_marks_clear(nl, what);
	r[4] = 63;
	what = "refresh of A, B, C across the box's edge: C came back within r_l of A (√2), "
	       "through their common neighbour B";
	LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
	check_list(nl, r, all, what);
	check_marks_clear(nl, what);
	what = "refresh of A, B, C, all three neighbours, without a move (every one met twice "
	       "on the rows scanned: listed once)";
	LZ_REQUIRE(lz_nlist_refresh(nl, r) == LZ_OK, "%s: %s", what, lz_error_message());
	check_list(nl, r, all, what);
	check_marks_clear(nl, what);
	lz_nlist_free(nl);
}

LZ_TEST(refresh_one_particle_and_a_pair_across_the_boundary)
{
	lz_lattice_box *b = box_new(LZ_LATTICE_SQUARE, 64);
	lz_nlist *nl = nl_new(b, 1, 3);
	int32_t one[2] = {0, 63};
	uint8_t none[4] = {0};
	fill_list(nl, none);
	LZ_REQUIRE(lz_nlist_refresh(nl, one) == LZ_OK, "%s", lz_error_message());
	check_list(nl, one, none, "refresh of a single particle (its row stays empty)");
	lz_nlist_free(nl);

	/* Two particles with empty rows drift within r_l of each other: a refresh reads only
	 * the source rows, so an empty row gains nobody (lz/nlist.h) — a rebuild would list
	 * them, the refresh must not. */
	nl = nl_new(b, 2, 3);
	int32_t lone[4] = {10, 10, 12, 11};
	fill_list(nl, none);
	LZ_REQUIRE(lz_nlist_refresh(nl, lone) == LZ_OK, "%s", lz_error_message());
	check_list(nl, lone, none, "refresh of two particles whose source rows are empty, now √5 "
	           "apart (r_l = 3): an empty row gains nobody, the refresh reads only the source "
	           "rows (is it rebuilding from all pairs?)");
	lz_nlist_free(nl);

	/* Two neighbours across the edge; both step across it and stay neighbours; then
	 * they part. */
	nl = nl_new(b, 2, 3);
	int32_t two[4] = {0, 7, 62, 8};
	uint8_t pair[4] = {0, 1, 1, 0};
	fill_list(nl, pair);
	two[0] = 63;
	two[2] = 1;
	LZ_REQUIRE(lz_nlist_refresh(nl, two) == LZ_OK, "%s", lz_error_message());
	check_list(nl, two, pair, "refresh of two neighbours that swapped sides across the box's "
	           "edge (distance 2 < r_l = 3)");
	two[2] = 60;
	LZ_REQUIRE(lz_nlist_refresh(nl, two) == LZ_OK, "%s", lz_error_message());
	check_list(nl, two, none, "refresh of two particles that moved √10 apart (r_l = 3: no "
	           "longer neighbours)");
	check_marks_clear(nl, "refresh of two particles");
	/* Neighbours 2 apart across the edge step to exactly r_l = 3 apart: no longer
	 * neighbours (d < r_l, strictly). */
	int32_t edge[4] = {1, 5, 63, 5};
	fill_list(nl, pair);
	edge[2] = 62;
	LZ_REQUIRE(lz_nlist_refresh(nl, edge) == LZ_OK, "%s", lz_error_message());
	check_list(nl, edge, none, "refresh of two neighbours that moved to exactly r_l = 3 apart "
	           "across the box's edge (d < r_l strictly: no longer neighbours)");
	lz_nlist_free(nl);
	three_across_the_edge(b);
	lz_lattice_box_free(b);
}
END_TEST
