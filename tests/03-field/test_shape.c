/* test_shape.c — the lattice points of a disk (sphere) and its step tables. Each test
 * hands one graded function the state lz_shape_alloc would give it (stage03.h's
 * bf_shape_blank, its points filled by brute force for the step tables), so a wrong
 * point set costs the point tests and a wrong step table the step tests. Points:
 * counts and membership against a brute-force scan over a wide box on every metric,
 * hand-counted small shapes, the strict boundary (distance exactly r is outside).
 * Steps: the head and tail tables against the set differences (S + e) \ S and
 * S \ (S + e) for every direction, and the one-point-per-row rule of an axis step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stage03.h"

/* The shape's points by the graded lz_shape_fill_points, on a blank shape. */
static lz_shape *points_of(lz_lattice_kind kind, double r)
{
	lz_shape *s = bf_shape_blank(kind, r);
	LZ_REQUIRE(lz_shape_fill_points(s) == LZ_OK, "lz_shape_fill_points(%s, r = %g) did "
	           "not return LZ_OK: %s", lz_lattice_name(kind), r, lz_error_message());
	LZ_REQUIRE(s->n <= s->cap, "%s r = %g: %zu points written, but the bounding box holds "
	           "only %zu", lz_lattice_name(kind), r, s->n, s->cap);
	return s;
}

/* The step tables by the graded lz_shape_fill_moves, on a shape whose points were
 * filled by brute force, in a scrambled order (any order is allowed). */
static lz_shape *moves_of(lz_lattice_kind kind, double r, gsl_rng *rng)
{
	lz_shape *s = bf_shape_blank(kind, r);
	bf_shape_points(s, rng);
	LZ_REQUIRE(lz_shape_fill_moves(s) == LZ_OK, "lz_shape_fill_moves(%s, r = %g) did not "
	           "return LZ_OK: %s", lz_lattice_name(kind), r, lz_error_message());
	for (int d = 0; d < s->ndir; d++)
		LZ_REQUIRE(s->nmove[d] <= s->n, "%s r = %g: nmove[%d] = %zu, more than the %zu "
		           "points of the shape", lz_lattice_name(kind), r, d, s->nmove[d], s->n);
	return s;
}

static int inside(lz_lattice_kind kind, double r, int64_t x, int64_t y, int64_t z)
{
	return (double)bf_d2(kind, x, y, z) < r * r;
}

/* A membership bitmap over the box |coord| <= B, for set comparisons. */
typedef struct {
	int B, dim;
	unsigned char *bit;
} bitmap;

static bitmap bm_new(int B, int dim)
{
	size_t w = 2 * (size_t)B + 1, n = w * w * (dim == 3 ? w : 1);
	bitmap m = {B, dim, calloc(n, 1)};
	LZ_REQUIRE(m.bit != NULL, "no memory for a bitmap");
	return m;
}

static unsigned char *bm_at(bitmap *m, lz_site p)
{
	int B = m->B;
	LZ_REQUIRE(abs(p.x) <= B && abs(p.y) <= B && abs(p.z) <= B && (m->dim == 3 || p.z == 0),
	           "offset (%d, %d, %d) is far outside the shape's bounding box", p.x, p.y, p.z);
	size_t w = 2 * (size_t)B + 1;
	return m->bit + (size_t)(p.x + B) + w * ((size_t)(p.y + B) + w * (size_t)(p.z + (m->dim == 3 ? B : 0)));
}

static const struct { lz_lattice_kind kind; double r; } cases[] = {
	{LZ_LATTICE_SQUARE, 0.5}, {LZ_LATTICE_SQUARE, 1}, {LZ_LATTICE_SQUARE, 1.5},
	{LZ_LATTICE_SQUARE, 2}, {LZ_LATTICE_SQUARE, 2.3}, {LZ_LATTICE_SQUARE, 5},
	{LZ_LATTICE_SQUARE, 6.1}, {LZ_LATTICE_SQUARE, 12.5}, {LZ_LATTICE_SQUARE8, 3.2},
	{LZ_LATTICE_TRIANGULAR, 0.5}, {LZ_LATTICE_TRIANGULAR, 1}, {LZ_LATTICE_TRIANGULAR, 1.5},
	{LZ_LATTICE_TRIANGULAR, 2.7}, {LZ_LATTICE_TRIANGULAR, 7}, {LZ_LATTICE_TRIANGULAR, 10.4},
	{LZ_LATTICE_CUBIC, 0.5}, {LZ_LATTICE_CUBIC, 1.5}, {LZ_LATTICE_CUBIC, 2},
	{LZ_LATTICE_CUBIC, 3.3}, {LZ_LATTICE_CUBIC, 6}, {LZ_LATTICE_CUBIC18, 2.5},
	{LZ_LATTICE_CUBIC26, 4.1},
};
#define NCASES (sizeof cases / sizeof cases[0])

LZ_TEST(shape_counts_match_brute_force)
{
	for (size_t k = 0; k < NCASES; k++) {
		lz_lattice_kind kind = cases[k].kind;
		double r = cases[k].r;
		int three = kind >= LZ_LATTICE_CUBIC, B = (int)ceil(2 * r) + 2;
		size_t want = 0;
		for (int z = three ? -B : 0; z <= (three ? B : 0); z++)
			for (int y = -B; y <= B; y++)
				for (int x = -B; x <= B; x++)
					want += inside(kind, r, x, y, z);
		lz_shape *s = points_of(kind, r);
		LZ_REQUIRE(s->n == want, "a %s shape of radius %g has %zu lattice points, but "
		           "%zu points lie strictly closer than r to the centre (is the bounding "
		           "box scanned fully, the sheared metric used, d2 < r² strict?)",
		           lz_lattice_name(kind), r, s->n, want);
		bitmap m = bm_new(B, three ? 3 : 2);
		for (size_t i = 0; i < s->n; i++) {
			lz_site p = s->pts[i];
			LZ_REQUIRE(inside(kind, r, p.x, p.y, p.z), "%s r = %g: point (%d, %d, %d) is "
			           "at distance² %lld >= r² = %g, outside the disk",
			           lz_lattice_name(kind), r, p.x, p.y, p.z,
			           (long long)bf_d2(kind, p.x, p.y, p.z), r * r);
			LZ_REQUIRE(three || p.z == 0, "a 2D point has z = %d", p.z);
			unsigned char *b = bm_at(&m, p);
			LZ_REQUIRE(!*b, "%s r = %g: point (%d, %d, %d) is listed twice",
			           lz_lattice_name(kind), r, p.x, p.y, p.z);
			*b = 1;
			LZ_REQUIRE(abs(p.x) <= s->reach && abs(p.y) <= s->reach && abs(p.z) <= s->reach,
			           "%s r = %g: point (%d, %d, %d) lies beyond the reach %d",
			           lz_lattice_name(kind), r, p.x, p.y, p.z, s->reach);
		}
		/* Then the set is S, which is point-symmetric: a mirror image missing is a
		 * scan that runs one way further than the other. */
		for (size_t i = 0; i < s->n; i++) {
			lz_site p = s->pts[i], q = {-p.x, -p.y, -p.z};
			LZ_REQUIRE(*bm_at(&m, q), "%s r = %g: (%d, %d, %d) is in the shape but its "
			           "mirror image through the centre is not", lz_lattice_name(kind), r,
			           p.x, p.y, p.z);
		}
		free(m.bit);
		lz_shape_free(s);
	}
}
END_TEST

/* 1 if the point (x, y, z) is among the shape's points. */
static int listed(const lz_shape *s, int32_t x, int32_t y, int32_t z)
{
	for (size_t i = 0; i < s->n; i++)
		if (s->pts[i].x == x && s->pts[i].y == y && s->pts[i].z == z)
			return 1;
	return 0;
}

LZ_TEST(shape_small_radii_by_hand_and_strict_boundary)
{
	/* r = 1/2: the centre alone, on every lattice. r = 1: still the centre alone (the
	 * nearest neighbours are at distance exactly 1, outside); one ulp more and they
	 * are in. */
	static const struct { lz_lattice_kind kind; double r; size_t n; const char *why; } hand[] = {
		{LZ_LATTICE_SQUARE, 1e-9, 1, "the smallest radii hold the centre alone"},
		{LZ_LATTICE_SQUARE, 0.5, 1, "the centre alone"},
		{LZ_LATTICE_SQUARE, 1.0, 1, "the neighbours at distance exactly 1 are outside"},
		{LZ_LATTICE_SQUARE, 1.0000000000000002, 5, "one ulp above 1: the centre and its "
		 "four neighbours"},
		{LZ_LATTICE_SQUARE, 1.5, 9, "d2 = 0, 1, 2: a 3 x 3 block"},
		{LZ_LATTICE_SQUARE, 2.0, 9, "d2 = 4 is on the circle, outside"},
		{LZ_LATTICE_SQUARE, 2.01, 13, "the 3 x 3 block and the four points at distance 2"},
		{LZ_LATTICE_TRIANGULAR, 1.0, 1, "the six neighbours are at distance exactly 1"},
		{LZ_LATTICE_TRIANGULAR, 1.5, 7, "the centre and its six neighbours (a hexagon)"},
		{LZ_LATTICE_TRIANGULAR, 1.8, 13, "plus the six second neighbours at √3"},
		{LZ_LATTICE_CUBIC, 1.0, 1, "the face neighbours are at distance exactly 1"},
		{LZ_LATTICE_CUBIC, 1.5, 19, "centre, 6 faces, 12 edges: d2 <= 2"},
		{LZ_LATTICE_CUBIC, 1.8, 27, "a 3 x 3 x 3 block: d2 <= 3"},
	};
	for (size_t k = 0; k < sizeof hand / sizeof hand[0]; k++) {
		lz_shape *s = points_of(hand[k].kind, hand[k].r);
		LZ_REQUIRE(s->n == hand[k].n, "a %s shape of radius %.17g should have %zu points "
		           "(%s), got %zu", lz_lattice_name(hand[k].kind), hand[k].r, hand[k].n,
		           hand[k].why, s->n);
		lz_shape_free(s);
	}
	/* The sheared disk is wider than it looks: storage offset (16, -8) is the point
	 * (12, -4√3) of the plane, at distance² 256 - 128 + 64 = 192 < 196, so it belongs
	 * to the triangular disk of radius 14 although |x| = 16 > r + 1. */
	lz_shape *s = points_of(LZ_LATTICE_TRIANGULAR, 14);
	ck_assert_msg(listed(s, 16, -8, 0) && listed(s, -16, 8, 0), "the triangular disk of "
	              "radius 14 must contain the storage offsets (16, -8) and (-16, 8) "
	              "(distance² 192 < 196): the sheared bounding box is |x|, |y| < 2r/√3 "
	              "(s->reach), wider than the |x| <= r of a round disk");
	lz_shape_free(s);
}
END_TEST

LZ_TEST(shape_heads_and_tails_are_the_set_differences)
{
	gsl_rng *rng = lz_test_rng(2);
	for (size_t k = 0; k < NCASES; k++) {
		lz_lattice_kind kind = cases[k].kind;
		double r = cases[k].r;
		lz_shape *s = moves_of(kind, r, rng);
		int ndir, three = s->dim == 3, B = s->reach + 2;
		const lz_site *dirs = lz_lattice_dirs(kind, &ndir);
		LZ_REQUIRE(s->ndir == ndir, "fixture: %d directions", s->ndir);
		for (int d = 0; d < ndir; d++) {
			lz_site e = dirs[d];
			bitmap want_h = bm_new(B, s->dim), want_t = bm_new(B, s->dim);
			size_t nh = 0, nt = 0;
			for (int z = three ? -B + 1 : 0; z <= (three ? B - 1 : 0); z++)
				for (int y = -B + 1; y <= B - 1; y++)
					for (int x = -B + 1; x <= B - 1; x++) {
						int in = inside(kind, r, x, y, z);
						int in_moved = inside(kind, r, x - e.x, y - e.y, z - e.z);
						lz_site p = {x, y, z};
						if (in_moved && !in)
							*bm_at(&want_h, p) = 1, nh++;
						if (in && !in_moved)
							*bm_at(&want_t, p) = 1, nt++;
					}
			LZ_REQUIRE(s->nmove[d] == nh, "%s r = %g, step (%d, %d, %d): %zu head points, "
			           "but the shifted shape gains %zu sites (and loses %zu): head = "
			           "(S + e) \\ S, tail = S \\ (S + e)", lz_lattice_name(kind), r, e.x,
			           e.y, e.z, s->nmove[d], nh, nt);
			for (size_t i = 0; i < s->nmove[d]; i++) {
				lz_site h = s->head[d][i], t = s->tail[d][i];
				unsigned char *bh = bm_at(&want_h, h), *bt = bm_at(&want_t, t);
				LZ_REQUIRE(*bh == 1, "%s r = %g, step (%d, %d, %d): head point (%d, %d, "
				           "%d) is not gained by the step, or listed twice (offsets are "
				           "from the centre before the step)", lz_lattice_name(kind), r,
				           e.x, e.y, e.z, h.x, h.y, h.z);
				LZ_REQUIRE(*bt == 1, "%s r = %g, step (%d, %d, %d): tail point (%d, %d, "
				           "%d) is not lost by the step, or listed twice (a tail point p "
				           "is in S with p - e outside)", lz_lattice_name(kind), r, e.x,
				           e.y, e.z, t.x, t.y, t.z);
				*bh = *bt = 2;
			}
			LZ_REQUIRE(s->self[d] == inside(kind, r, e.x, e.y, e.z), "%s r = %g: self[%d] "
			           "= %d, but the step (%d, %d, %d) %s inside the shape",
			           lz_lattice_name(kind), r, d, s->self[d], e.x, e.y, e.z,
			           inside(kind, r, e.x, e.y, e.z) ? "is" : "is not");
			free(want_h.bit);
			free(want_t.bit);
		}
		lz_shape_free(s);
	}
	gsl_rng_free(rng);
}
END_TEST

/* Fail unless the nmove[d] points of `pts` lie in different rows across the step e
 * and each is `in` the shape while p - e is not (for tails), or out of it while
 * p - e is in (for heads): the one point per row an axis step gains or loses. */
static void check_rows(const lz_shape *s, int d, const lz_site *pts, int tail)
{
	lz_site e = s->dirs[d];
	int B = s->reach + 1;
	unsigned char *row = calloc(2 * (size_t)B + 1, 1);
	LZ_REQUIRE(row != NULL, "no memory");
	for (size_t i = 0; i < s->nmove[d]; i++) {
		lz_site p = pts[i];
		int in = bf_in(s, p.x, p.y, 0), before = bf_in(s, p.x - e.x, p.y - e.y, 0);
		int y = e.x != 0 ? p.y : p.x;
		LZ_REQUIRE(tail ? in && !before : !in && before, "square r = %g, step (%d, %d): "
		           "%s point (%d, %d) is %s the disk and (%d, %d) %s: a head point is "
		           "just beyond the rim in front (outside, its predecessor inside), a tail "
		           "point just inside the rim behind (inside, its predecessor outside)",
		           s->radius, e.x, e.y, tail ? "tail" : "head", p.x, p.y,
		           in ? "inside" : "outside", p.x - e.x, p.y - e.y,
		           before ? "inside" : "outside");
		LZ_REQUIRE(abs(y) <= B && !row[y + B], "square r = %g, step (%d, %d): two %s "
		           "points in row %d — a disk meets each row in one run of points, so a "
		           "step gains (loses) one point per row", s->radius, e.x, e.y,
		           tail ? "tail" : "head", y);
		row[y + B] = 1;
	}
	free(row);
}

LZ_TEST(shape_axis_step_gains_one_point_per_row)
{
	/* A disk meets every row in one run of points, so an axis step gains exactly one
	 * point per row it crosses: 2·floor(√(r2 - 1)) + 1 rows on the square lattice. The
	 * thesis's fig. 2.9 disk, r = 6.1, has 13. The step itself is inside the disk
	 * (self = 1) only for r > 1: at r = 1 it is exactly on the circle, outside. */
	static const double radii[] = {0.5, 1, 1.5, 2, 6.1, 12.5, 24.2};
	gsl_rng *rng = lz_test_rng(3);
	for (size_t k = 0; k < sizeof radii / sizeof radii[0]; k++) {
		double r = radii[k];
		lz_shape *s = moves_of(LZ_LATTICE_SQUARE, r, rng);
		int64_t r2 = (int64_t)ceil(r * r), rows = 0;
		while ((rows + 1) * (rows + 1) < r2)
			rows++;
		for (int d = 0; d < s->ndir; d++) {
			LZ_REQUIRE(s->nmove[d] == (size_t)(2 * rows + 1), "square r = %g: an axis "
			           "step should gain %lld points (one per row), got %zu", r,
			           (long long)(2 * rows + 1), s->nmove[d]);
			check_rows(s, d, s->head[d], 0);
			check_rows(s, d, s->tail[d], 1);
			LZ_REQUIRE(s->self[d] == (r > 1), "square r = %g: self[%d] = %d, but the unit "
			           "step is %s the disk (distance 1 %s r)", r, d, s->self[d],
			           r > 1 ? "inside" : "outside", r > 1 ? "<" : ">=");
		}
		lz_shape_free(s);
	}
	gsl_rng_free(rng);
}
END_TEST
