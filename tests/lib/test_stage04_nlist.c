/* test_stage04_nlist.c — the library half of lz/nlist.h, which students do not write:
 * the input checks of lz_nlist_alloc (with the allowed range in the message), empty
 * lists and rl2, the doubling growth of a copy, the memory count, the brute-force
 * audit against hand-made lists (a missing pair, a self entry, a duplicate, an
 * asymmetric entry, a stale one), and the one-copy refresh, which keeps a list that
 * did not move and loses C in the three-particle example of thesis fig. 2.7. The boxes
 * are made by hand and the lists are written by hand, so no graded function of this
 * stage runs except in the last test, which builds a list from real cell lists (the
 * reference, as this suite always does in `make check`). The distances of the audit
 * and of the one-copy refresh come from lz_lattice_min_dist2 (stage 02). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/cells.h"
#include "lz/lattice.h"
#include "lz/nlist.h"
#include "lztest.h"
#include "support.h"

/* A periodic box of side L made by hand: the distance-correction table is the
 * representative of u in (-L/2, L/2]. */
typedef struct {
	lz_lattice_box box;
	int32_t dc[64];
} hand_box;

static void hand_box_init(hand_box *h, lz_lattice_kind kind, int32_t L)
{
	ck_assert(L <= 64);
	h->box = (lz_lattice_box){.kind = kind, .dim = lz_lattice_dim(kind), .side = L,
	                          .mask = L - 1, .dc = h->dc};
	for (int32_t u = 0; u < L; u++)
		h->dc[u] = u <= L / 2 ? u : u - L;
}

/* Make rows[i] (each ended by -1) the list in use, written into the target. */
static void set_rows(lz_nlist *nl, const int *const *rows)
{
	lz_nbuf *t = &nl->buf[!nl->cur];
	t->len = 0;
	for (size_t i = 0; i < nl->n; i++) {
		t->start[i] = (uint32_t)t->len;
		for (const int *p = rows[i]; *p >= 0; p++)
			ck_assert(lz_nbuf_push(t, (uint32_t)*p) == LZ_OK);
	}
	t->start[nl->n] = (uint32_t)t->len;
	nl->cur = !nl->cur;
}

static int on_row(const lz_nlist *nl, size_t i, uint32_t j)
{
	size_t len;
	const uint32_t *row = lz_nlist_row(nl, i, &len);
	for (size_t k = 0; k < len; k++)
		if (row[k] == j)
			return 1;
	return 0;
}


LZ_TEST(nlist_alloc_rejects_bad_input)
{
	hand_box h;
	hand_box_init(&h, LZ_LATTICE_SQUARE, 64);
	lz_test_clear_error();
	lz_test_refused(lz_nlist_alloc(NULL, 10, 2) == NULL, "no box", "box", NULL);
	lz_test_refused(lz_nlist_alloc(&h.box, 0, 2) == NULL, "n = 0", "n = 0",
	                "1 <= n <= 2147483647");
	lz_test_refused(lz_nlist_alloc(&h.box, (size_t)1 << 31, 2) == NULL, "n = 2^31",
	                "n = 2147483648", "1 <= n <= 2147483647");
	lz_test_refused(lz_nlist_alloc(&h.box, 10, 0) == NULL, "rl = 0", "rl = 0", "0 < rl <= 32");
	lz_test_refused(lz_nlist_alloc(&h.box, 10, -1.5) == NULL, "rl = -1.5", "rl = -1.5",
	                "0 < rl <= 32");
	lz_test_refused(lz_nlist_alloc(&h.box, 10, NAN) == NULL, "rl = NaN", "rl = nan",
	                "0 < rl <= 32");
	lz_test_refused(lz_nlist_alloc(&h.box, 10, INFINITY) == NULL, "rl = inf", "rl = inf",
	                "0 < rl <= 32");
	lz_test_refused(lz_nlist_alloc(&h.box, 10, 32.5) == NULL, "rl = 32.5 in L = 64",
	                "larger than half the box", "0 < rl <= 32");
	lz_nlist *nl = lz_nlist_alloc(&h.box, 10, 32);
	ck_assert_msg(nl != NULL, "rl = L/2 is allowed: %s", lz_error_message());
	lz_nlist_free(nl);
	lz_nlist_free(NULL);
}
END_TEST

LZ_TEST(nlist_alloc_starts_empty)
{
	hand_box h;
	hand_box_init(&h, LZ_LATTICE_TRIANGULAR, 16);
	static const struct { double rl; int64_t rl2; } cs[] = {
		{2.5, 7}, {5, 25}, {0.5, 1}, {8, 64}, {1.0000001, 2},
	};
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
		size_t n = 1 + 17 * k;
		lz_nlist *nl = lz_nlist_alloc(&h.box, n, cs[k].rl);
		ck_assert_msg(nl != NULL, "%s", lz_error_message());
		ck_assert_msg(nl->rl2 == cs[k].rl2, "rl = %.8g: rl2 = %lld, expected ceil(rl²) = %lld",
		              cs[k].rl, (long long)nl->rl2, (long long)cs[k].rl2);
		ck_assert(nl->box == &h.box && nl->dim == 2 && nl->n == n && nl->rl == cs[k].rl);
		ck_assert(nl->cur == 0 || nl->cur == 1);
		for (int c = 0; c < 2; c++) {
			ck_assert(nl->buf[c].len == 0);
			for (size_t i = 0; i <= n; i++)
				ck_assert_msg(nl->buf[c].start[i] == 0, "copy %d: start[%zu] = %u in a new "
				              "list", c, i, nl->buf[c].start[i]);
		}
		for (size_t i = 0; i < n; i++) {
			size_t len = 99;
			lz_nlist_row(nl, i, &len);
			ck_assert(len == 0 && nl->mark[i] == 0);
		}
		ck_assert(lz_nlist_entries(nl) == 0);
		size_t bytes = 2 * (n + 1) * 4 + (nl->buf[0].cap + nl->buf[1].cap) * 4 + n;
		ck_assert_msg(lz_nlist_bytes(nl) == bytes, "bytes = %zu, expected %zu",
		              lz_nlist_bytes(nl), bytes);
		lz_nlist_free(nl);
	}
}
END_TEST

LZ_TEST(nbuf_grows_by_doubling_and_keeps_entries)
{
	hand_box h;
	hand_box_init(&h, LZ_LATTICE_SQUARE, 16);
	lz_nlist *nl = lz_nlist_alloc(&h.box, 5, 3);
	ck_assert(nl != NULL);
	lz_nbuf *b = &nl->buf[0];
	size_t grew = 0, last = b->cap;
	for (uint32_t v = 0; v < 100000; v++) {
		LZ_REQUIRE_TRUE(lz_nbuf_push(b, v * 7u) == LZ_OK);
		if (b->cap != last) {
			LZ_REQUIRE(last == 0 || b->cap == 2 * last, "the room went from %zu to %zu: "
			              "it must double", last, b->cap);
			last = b->cap;
			grew++;
		}
	}
	ck_assert(b->len == 100000 && b->cap >= 100000 && grew <= 20);
	for (uint32_t v = 0; v < 100000; v++)
		if (b->idx[v] != v * 7u)
			ck_abort_msg("entry %u is %u after growing, expected %u", v, b->idx[v], v * 7u);
	size_t bytes = 2 * 6 * 4 + (b->cap + nl->buf[1].cap) * 4 + 5;
	ck_assert_msg(lz_nlist_bytes(nl) == bytes, "bytes = %zu, expected %zu (the room of both "
	              "copies counts)", lz_nlist_bytes(nl), bytes);
	lz_nlist_free(nl);

	/* The 32-bit offsets cap a copy: growth beyond is refused, b unchanged. */
	lz_nbuf full = {.start = NULL, .idx = NULL, .len = UINT32_MAX, .cap = UINT32_MAX};
	lz_test_clear_error();
	ck_assert(lz_nbuf_grow(&full) == LZ_ENOMEM);
	ck_assert(lz_test_last_error() == LZ_ENOMEM && strstr(lz_error_message(), "32-bit"));
	ck_assert(full.idx == NULL && full.cap == UINT32_MAX && full.len == UINT32_MAX);
	ck_assert(lz_nbuf_push(&full, 1) == LZ_ENOMEM && full.len == UINT32_MAX);
}
END_TEST

/* Square box of side 16, r_l = 3.5 (rl2 = 13). Within r_l: 0-1 at 2, 0-2 at 3, 0-4 at 3
 * through the edge; 1-2 is at exactly √13, 3 is alone. */
static const int32_t audit_r[] = {2, 2, 4, 2, 2, 5, 10, 10, 15, 2};

static lz_nlist_audit_report audit(lz_nlist *nl, const int *const *rows, int64_t r2)
{
	set_rows(nl, rows);
	lz_nlist_audit_report rep;
	memset(&rep, 0xff, sizeof rep);
	ck_assert(lz_nlist_audit(nl, audit_r, r2, &rep) == LZ_OK);
	return rep;
}

#define REPORT_IS(rep, m, b, s, d, a, what)                                               \
	ck_assert_msg((rep).missing == (m) && (rep).beyond == (b) && (rep).self == (s) &&   \
	              (rep).duplicates == (d) && (rep).asymmetric == (a),                   \
	              "%s: audit missing %zu beyond %zu self %zu duplicates %zu asymmetric " \
	              "%zu, expected %d %d %d %d %d", what, (rep).missing, (rep).beyond,    \
	              (rep).self, (rep).duplicates, (rep).asymmetric, m, b, s, d, a)

LZ_TEST(nlist_audit_finds_every_defect)
{
	hand_box h;
	hand_box_init(&h, LZ_LATTICE_SQUARE, 16);
	lz_nlist *nl = lz_nlist_alloc(&h.box, 5, 3.5);
	ck_assert(nl != NULL && nl->rl2 == 13);
	static const int r0[] = {1, 2, 4, -1}, r1[] = {0, -1}, r2[] = {0, -1}, r3[] = {-1},
	                 r4[] = {0, -1};
	const int *good[] = {r0, r1, r2, r3, r4};
	lz_nlist_audit_report rep = audit(nl, good, 13);
	REPORT_IS(rep, 0, 0, 0, 0, 0, "the right list");
	rep = audit(nl, good, 4);
	REPORT_IS(rep, 0, 0, 0, 0, 0, "the right list, r2 = 4");

	/* 0-4 (distance 3 through the edge) left off both rows: one pair missing. */
	static const int m0[] = {1, 2, -1}, m4[] = {-1};
	const int *missing[] = {m0, r1, r2, r3, m4};
	rep = audit(nl, missing, 13);
	REPORT_IS(rep, 1, 0, 0, 0, 0, "pair 0-4 left off");
	rep = audit(nl, missing, 9);
	REPORT_IS(rep, 0, 0, 0, 0, 0, "pair 0-4 (d² = 9) left off, r2 = 9: not yet needed");
	rep = audit(nl, missing, 10);
	REPORT_IS(rep, 1, 0, 0, 0, 0, "pair 0-4 (d² = 9) left off, r2 = 10");

	static const int s3[] = {3, -1};
	const int *self[] = {r0, r1, r2, s3, r4};
	rep = audit(nl, self, 13);
	REPORT_IS(rep, 0, 0, 1, 0, 0, "3 on its own row");

	static const int d0[] = {1, 2, 4, 2, -1};
	const int *dup[] = {d0, r1, r2, r3, r4};
	rep = audit(nl, dup, 13);
	REPORT_IS(rep, 0, 0, 0, 1, 0, "2 twice on row 0");

	/* 2 on row 0, but 0 not on row 2: one entry without its mirror, and the force of
	 * 0 on 2 would be lost (a missing pair as well). */
	static const int a2[] = {-1};
	const int *asym[] = {r0, r1, a2, r3, r4};
	rep = audit(nl, asym, 13);
	REPORT_IS(rep, 1, 0, 0, 0, 1, "0 left off row 2 only");
	/* 3 on row 1 only, far away: stale and without its mirror. */
	static const int a1[] = {0, 3, -1};
	const int *far1[] = {r0, a1, r2, r3, r4};
	rep = audit(nl, far1, 13);
	REPORT_IS(rep, 0, 1, 0, 0, 1, "3 on row 1 only");

	/* 1-2 at exactly r_l and 1-3 far, on both rows: four stale entries. */
	static const int t1[] = {0, 2, 3, -1}, t2[] = {0, 1, -1}, t3[] = {1, -1};
	const int *stale[] = {r0, t1, t2, t3, r4};
	rep = audit(nl, stale, 13);
	REPORT_IS(rep, 0, 4, 0, 0, 0, "1-2 (at exactly r_l) and 1-3 listed");
	lz_nlist_free(nl);
}
END_TEST

/* Thesis fig. 2.7: square lattice, r_l = 5, A = 0, B = 1, C = 2. Before, A-B at 4 and
 * A-C at 3 are listed, B-C at 7 is not; C then moves to 3 from B and 7 from A. */
LZ_TEST(nlist_refresh_single_loses_c_in_fig27)
{
	hand_box h;
	hand_box_init(&h, LZ_LATTICE_SQUARE, 64);
	const int32_t after[] = {20, 20, 24, 20, 27, 20};
	lz_nlist *nl = lz_nlist_alloc(&h.box, 3, 5);
	ck_assert(nl != NULL);
	static const int ra[] = {1, 2, -1}, rb[] = {0, -1}, rc[] = {0, -1};
	const int *before[] = {ra, rb, rc};
	set_rows(nl, before);
	int cur = nl->cur;
	ck_assert(lz_nlist_refresh_single(nl, after) == LZ_OK);
	ck_assert_msg(nl->cur == !cur, "the one-copy refresh flips cur like the real one");
	ck_assert_msg(on_row(nl, 0, 1) && on_row(nl, 1, 0), "A and B stay neighbours");
	ck_assert_msg(!on_row(nl, 0, 2) && !on_row(nl, 2, 0), "C left A's range");
	ck_assert_msg(!on_row(nl, 1, 2) && !on_row(nl, 2, 1), "the one-copy refresh should lose C: "
	              "A's row is rewritten first (C dropped), so B's scan of it no longer finds C");
	ck_assert(lz_nlist_entries(nl) == 2);
	lz_nlist_audit_report rep;
	ck_assert(lz_nlist_audit(nl, after, nl->rl2, &rep) == LZ_OK);
	REPORT_IS(rep, 1, 0, 0, 0, 0, "after the one-copy refresh of fig. 2.7");
	for (int i = 0; i < 3; i++)
		ck_assert(nl->mark[i] == 0);
	lz_nlist_free(nl);
}
END_TEST

/* Without moves the one-copy refresh gives the right list back: its loss needs a
 * particle that leaves one row before the row that should gain it is read. */
LZ_TEST(nlist_refresh_single_keeps_a_still_list)
{
	hand_box h;
	hand_box_init(&h, LZ_LATTICE_SQUARE, 32);
	enum { N = 120 };
	int32_t r[2 * N];
	gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(g, 83);
	for (int k = 0; k < 2 * N; k++)
		r[k] = (int32_t)gsl_rng_uniform_int(g, 32);
	gsl_rng_free(g);
	lz_nlist *nl = lz_nlist_alloc(&h.box, N, 6);
	ck_assert(nl != NULL);
	/* The list by brute force, with the test's own minimum image. */
	lz_nbuf *t = &nl->buf[!nl->cur];
	t->len = 0;
	for (size_t i = 0; i < N; i++) {
		t->start[i] = (uint32_t)t->len;
		for (size_t j = 0; j < N; j++) {
			int32_t dx = abs(r[2 * i] - r[2 * j]), dy = abs(r[2 * i + 1] - r[2 * j + 1]);
			dx = dx > 16 ? 32 - dx : dx;
			dy = dy > 16 ? 32 - dy : dy;
			if (j != i && dx * dx + dy * dy < 36)
				LZ_REQUIRE_TRUE(lz_nbuf_push(t, (uint32_t)j) == LZ_OK);
		}
	}
	t->start[N] = (uint32_t)t->len;
	nl->cur = !nl->cur;
	size_t entries = lz_nlist_entries(nl);
	ck_assert(entries > N);
	ck_assert(lz_nlist_refresh_single(nl, r) == LZ_OK);
	lz_nlist_audit_report rep;
	ck_assert(lz_nlist_audit(nl, r, nl->rl2, &rep) == LZ_OK);
	REPORT_IS(rep, 0, 0, 0, 0, 0, "one-copy refresh of a list that did not move");
	ck_assert(lz_nlist_entries(nl) == entries);
	for (size_t i = 0; i < N; i++)
		LZ_REQUIRE_TRUE(nl->mark[i] == 0);
	lz_nlist_free(nl);
}
END_TEST

/* Real cell lists (lz_cells_alloc_lattice, bin, link) give a list the audit passes,
 * on every lattice: the grid lz/cells.h makes for r_l is one lz_nlist_build_cells
 * accepts. */
LZ_TEST(nlist_from_real_cell_lists_passes_the_audit)
{
	static const struct { lz_lattice_kind kind; int L; double rl; size_t n; } cs[] = {
		{LZ_LATTICE_SQUARE, 64, 7.5, 400}, {LZ_LATTICE_TRIANGULAR, 64, 7, 400},
		{LZ_LATTICE_TRIANGULAR, 64, 13.8, 300}, {LZ_LATTICE_CUBIC26, 32, 5, 500},
	};
	gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(g, 89);
	for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++)
		for (int order = 0; order < 2; order++) {
			int dim = lz_lattice_dim(cs[k].kind);
			int32_t *r = malloc(cs[k].n * (size_t)dim * sizeof *r);
			for (size_t q = 0; q < cs[k].n * (size_t)dim; q++)
				r[q] = (int32_t)gsl_rng_uniform_int(g, (unsigned long)cs[k].L);
			lz_lattice_box *b = lz_lattice_box_alloc(cs[k].kind, cs[k].L);
			lz_nlist *nl = lz_nlist_alloc(b, cs[k].n, cs[k].rl);
			lz_cells *c = lz_cells_alloc_lattice(cs[k].kind, cs[k].L, cs[k].rl,
			                                     order ? LZ_CELLS_MORTON : LZ_CELLS_ROW,
			                                     cs[k].n, 0);
			ck_assert_msg(b && nl && c, "%s", lz_error_message());
			ck_assert(lz_cells_bin_sites(c, cs[k].n, r) == LZ_OK);
			lz_cells_link(c);
			ck_assert_msg(lz_nlist_build_cells(nl, c, r) == LZ_OK, "%s lattice, r_l = %g: %s",
			              lz_lattice_name(cs[k].kind), cs[k].rl, lz_error_message());
			lz_nlist_audit_report rep;
			ck_assert(lz_nlist_audit(nl, r, nl->rl2, &rep) == LZ_OK);
			REPORT_IS(rep, 0, 0, 0, 0, 0, "a list from real cell lists");
			ck_assert(lz_nlist_entries(nl) > cs[k].n);
			lz_cells_free(c);
			lz_nlist_free(nl);
			lz_lattice_box_free(b);
			free(r);
		}
	gsl_rng_free(g);
}
END_TEST
