/* test_gr.c — lattice points per shell (thesis table 2.4 and a brute-force count) and
 * the normalisation of g(r): exact on a full lattice, 1 within statistics for an
 * ideal gas once corrected, and visibly jagged when raw. The accumulators here are
 * built by the test itself, so lz_gr_result is tested apart from lz_shell_counts. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/gr.h"
#include "lz/lattice.h"

/* Thesis table 2.4: lattice points in the shells [k, k+1), k = 0..9. */
static const uint64_t table24_square[10] = {1, 8, 16, 20, 24, 40, 36, 48, 56, 56};
static const uint64_t table24_triangular[10] = {1, 12, 18, 24, 30, 36, 48, 66, 60, 66};
static const uint64_t table24_cubic[10] = {1, 26, 66, 158, 234, 410, 470, 738, 866, 1170};

static int64_t metric(lz_lattice_kind kind, int64_t x, int64_t y, int64_t z)
{
	if (kind == LZ_LATTICE_TRIANGULAR)
		return x * x + x * y + y * y;
	if (kind >= LZ_LATTICE_CUBIC)
		return x * x + y * y + z * z;
	return x * x + y * y;
}

static int shell_of(int64_t d2)
{
	int k = 0;
	while ((int64_t)(k + 1) * (k + 1) <= d2)
		k++;
	return k;
}

/* Lattice points per shell by brute force over a window wide enough for the
 * triangular ellipse (|dx| <= 2r/√3 < 2r). */
static void brute_counts(lz_lattice_kind kind, int nshells, uint64_t *count)
{
	int three = kind >= LZ_LATTICE_CUBIC, w = 2 * nshells;
	memset(count, 0, (size_t)nshells * sizeof *count);
	for (int x = -w; x <= w; x++)
		for (int y = -w; y <= w; y++)
			for (int z = three ? -w : 0; z <= (three ? w : 0); z++) {
				int64_t d2 = metric(kind, x, y, z);
				if (d2 < (int64_t)nshells * nshells)
					count[shell_of(d2)]++;
			}
}

static void check_table24(lz_lattice_kind kind, const uint64_t *want)
{
	/* count[] is an output: garbage in it must not show (set, do not add). */
	uint64_t got[10];
	memset(got, 0xA5, sizeof got);
	int status = lz_shell_counts(kind, 10, got);
	ck_assert_msg(status == LZ_OK, "lz_shell_counts(%s, 10) returned %d: %s",
	              lz_lattice_name(kind), status, lz_error_message());
	for (int k = 0; k < 10; k++)
		ck_assert_msg(got[k] == want[k], "%s lattice: shell [%d, %d) holds %" PRIu64 " lattice "
		              "points (thesis table 2.4), counted %" PRIu64 " — %s",
		              lz_lattice_name(kind), k, k + 1, want[k], got[k],
		              got[k] < want[k] && k > 0 && got[k - 1] > want[k - 1]
		              ? "points on the circle d2 = k² belong to the OUTER shell k"
		              : got[k] > want[k] && k + 1 < 10
		              ? "points exactly on a boundary go to the outer shell, once"
		              : "count every site with k² <= d2 < (k+1)², all four quadrants "
		                "(octants) and the axes once");
}

LZ_TEST(shell_counts_square_table_2_4)
{
	check_table24(LZ_LATTICE_SQUARE, table24_square);
	check_table24(LZ_LATTICE_SQUARE8, table24_square);
}
END_TEST

LZ_TEST(shell_counts_triangular_table_2_4)
{
	check_table24(LZ_LATTICE_TRIANGULAR, table24_triangular);
}
END_TEST

LZ_TEST(shell_counts_cubic_table_2_4)
{
	check_table24(LZ_LATTICE_CUBIC, table24_cubic);
	check_table24(LZ_LATTICE_CUBIC18, table24_cubic);
	check_table24(LZ_LATTICE_CUBIC26, table24_cubic);
}
END_TEST

LZ_TEST(shell_counts_brute_force_many_shells)
{
	static const struct { lz_lattice_kind kind; int nshells; } cases[] = {
		{LZ_LATTICE_SQUARE, 1}, {LZ_LATTICE_SQUARE, 64}, {LZ_LATTICE_TRIANGULAR, 1},
		{LZ_LATTICE_TRIANGULAR, 64}, {LZ_LATTICE_CUBIC, 1}, {LZ_LATTICE_CUBIC26, 16},
	};
	uint64_t got[64], want[64];
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
		lz_lattice_kind kind = cases[c].kind;
		int ns = cases[c].nshells;
		brute_counts(kind, ns, want);
		memset(got, 0xA5, sizeof got);
		ck_assert_msg(lz_shell_counts(kind, ns, got) == LZ_OK, "lz_shell_counts(%s, %d): %s",
		              lz_lattice_name(kind), ns, lz_error_message());
		for (int k = 0; k < ns; k++)
			LZ_REQUIRE(got[k] == want[k], "%s lattice with %d shells: shell [%d, %d) "
			           "holds %" PRIu64 " lattice points, counted %" PRIu64 " — %s",
			           lz_lattice_name(kind), ns, k, k + 1, want[k], got[k],
			           kind == LZ_LATTICE_TRIANGULAR && got[k] < want[k]
			           ? "in sheared coordinates a circle of radius r reaches |dx| = "
			             "2r/√3 > r: the loop must go that far"
			           : "is floor(√d2) computed exactly (an integer root, not a "
			             "rounded sqrt)?");
	}
}
END_TEST

LZ_TEST(shell_counts_bad_input)
{
	uint64_t guard[2] = {77, 77};
	static const struct { int kind, nshells; } bad[] = {{LZ_LATTICE_SQUARE, 0},
		{LZ_LATTICE_CUBIC, -3}, {LZ_NLATTICES, 4}, {-1, 4}};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		int status = lz_shell_counts((lz_lattice_kind)bad[i].kind, bad[i].nshells, guard);
		ck_assert_msg(status == LZ_EINVAL && guard[0] == 77, "lz_shell_counts(kind %d, "
		              "nshells %d) returned %d and wrote %" PRIu64 "; it must refuse with "
		              "LZ_EINVAL and write nothing", bad[i].kind, bad[i].nshells, status,
		              guard[0]);
	}
	/* The smallest allowed inputs: one shell holds the origin alone, two add the
	 * nearest neighbours (table 2.4); nothing beyond count[nshells - 1] is written. */
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE8, LZ_LATTICE_TRIANGULAR,
	                                        LZ_LATTICE_CUBIC18};
	const uint64_t *tables[] = {table24_square, table24_triangular, table24_cubic};
	for (int k = 0; k < 3; k++)
		for (int ns = 1; ns <= 2; ns++) {
			uint64_t c[3] = {99, 99, 99};
			int status = lz_shell_counts(kinds[k], ns, c);
			ck_assert_msg(status == LZ_OK && c[0] == 1 && (ns == 1 || c[1] == tables[k][1]) &&
			              c[ns] == 99, "lz_shell_counts(%s, %d), the smallest allowed: returned "
			              "%d with counts %" PRIu64 ", %" PRIu64 ", %" PRIu64 "; expected 1 (the "
			              "origin)%s and count[%d] untouched — is d2 = k² put in the outer "
			              "shell k, and are exactly nshells entries set?",
			              lz_lattice_name(kinds[k]), ns, status, c[0], c[1], c[2],
			              ns == 2 ? " then the nearest neighbours of table 2.4" : "", ns);
		}
}
END_TEST

/* ---- g(r) ---- */

/* An accumulator built by hand: lattice counts by brute force, never lz_shell_counts. */
static lz_gr *gr_by_hand(lz_lattice_kind kind, int32_t side, int nshells, size_t n)
{
	lz_gr *g = calloc(1, sizeof *g);
	g->kind = kind;
	g->dim = kind >= LZ_LATTICE_CUBIC ? 3 : 2;
	g->side = side;
	g->nshells = nshells;
	g->n = n;
	g->d2max = (int64_t)nshells * nshells;
	g->shell_of = malloc((size_t)g->d2max * sizeof *g->shell_of);
	for (int64_t d2 = 0; d2 < g->d2max; d2++)
		g->shell_of[d2] = (uint32_t)shell_of(d2);
	g->pairs = calloc((size_t)nshells, sizeof *g->pairs);
	g->lattice = calloc((size_t)nshells, sizeof *g->lattice);
	brute_counts(kind, nshells, g->lattice);
	return g;
}

/* The nearest-image distance² by the test's own search. */
static int64_t near2(lz_lattice_kind kind, int64_t L, int64_t dx, int64_t dy, int64_t dz)
{
	int three = kind >= LZ_LATTICE_CUBIC;
	int64_t best = INT64_MAX;
	for (int a = -1; a <= 1; a++)
		for (int b = -1; b <= 1; b++)
			for (int c = three ? -1 : 0; c <= (three ? 1 : 0); c++) {
				int64_t d = metric(kind, dx + a * L, dy + b * L, dz + c * L);
				if (d < best)
					best = d;
			}
	return best;
}

/* Add every pair of the n sites r[3i..3i+2] (coordinates in [0, L)) and close. */
static void add_sites(lz_gr *g, const int32_t *r, size_t n)
{
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++)
			lz_gr_add_pair(g, near2(g->kind, g->side, r[3 * i] - r[3 * j],
			                        r[3 * i + 1] - r[3 * j + 1], r[3 * i + 2] - r[3 * j + 2]));
	lz_gr_end_sample(g);
}

/* The thesis's lattice measure, written out here: count · cell / exact shell measure. */
static double measure(lz_lattice_kind kind, int k, uint64_t count)
{
	double cell = kind == LZ_LATTICE_TRIANGULAR ? sqrt(3.0) / 2.0 : 1.0;
	double exact = kind >= LZ_LATTICE_CUBIC ? 4.0 * M_PI / 3.0 * (3.0 * k * k + 3.0 * k + 1.0)
	                                        : M_PI * (2.0 * k + 1.0);
	return (double)count * cell / exact;
}

LZ_TEST(gr_full_lattice_exact)
{
	/* Every site occupied: each site sees each other site once, so shell k >= 1 gets
	 * V·count(k)/2 pairs out of V(V-1)/2 and corrected g = V/(V-1) exactly; shell 0
	 * (the site itself) gets none. Added twice, to count the samples. */
	static const struct { lz_lattice_kind kind; int32_t L; int nshells; } cases[] = {
		{LZ_LATTICE_SQUARE, 8, 4}, {LZ_LATTICE_TRIANGULAR, 8, 4}, {LZ_LATTICE_CUBIC, 4, 2},
		{LZ_LATTICE_TRIANGULAR, 2, 1},
	};
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
		lz_lattice_kind kind = cases[c].kind;
		int32_t L = cases[c].L;
		int three = kind >= LZ_LATTICE_CUBIC, ns = cases[c].nshells;
		size_t V = (size_t)L * (size_t)L * (three ? (size_t)L : 1);
		int32_t *r = calloc(3 * V, sizeof *r);
		for (size_t i = 0; i < V; i++) {
			r[3 * i] = (int32_t)(i % (size_t)L);
			r[3 * i + 1] = (int32_t)(i / (size_t)L % (size_t)L);
			r[3 * i + 2] = three ? (int32_t)(i / ((size_t)L * (size_t)L)) : 0;
		}
		lz_gr *g = gr_by_hand(kind, L, ns, V);
		add_sites(g, r, V);
		add_sites(g, r, V);
		double raw[8], cor[8];
		ck_assert_msg(lz_gr_result(g, raw, cor) == LZ_OK, "lz_gr_result: %s",
		              lz_error_message());
		double vv = (double)V / ((double)V - 1.0);
		for (int k = 0; k < ns; k++) {
			double want = k == 0 ? 0.0 : vv;
			ck_assert_msg(fabs(cor[k] - want) < 1e-12, "full %s lattice of side %d (N = V = "
			              "%zu, 2 samples): corrected g in shell %d is %.15g, exactly %.15g "
			              "expected (V/(V-1)) — %s", lz_lattice_name(kind), L, V, k, cor[k],
			              want, fabs(cor[k] - 1.0) < 1e-12 ? "normalise by the N(N-1)/2 "
			              "distinct pairs, not N²/2" : fabs(cor[k] - 2.0 * want) < 1e-9 ?
			              "divide by the number of samples" : "the ideal gas puts S·N(N-1)/2·"
			              "count(k)/V pairs into shell k");
			double wraw = want * measure(kind, k, g->lattice[k]);
			ck_assert_msg(fabs(raw[k] - wraw) < 1e-12 * (1.0 + wraw), "full %s lattice of "
			              "side %d: raw g in shell %d is %.15g, expected %.15g = the "
			              "corrected value times the lattice measure count·cell/exact "
			              "(exact = π(2k+1) in 2D, 4π/3(3k²+3k+1) in 3D; cell = √3/2 on the "
			              "triangular lattice)", lz_lattice_name(kind), L, k, raw[k], wraw);
		}
		lz_gr_free(g);
		free(r);
	}
}
END_TEST

/* An ideal gas: S samples of n independent uniform sites of an L-sided box. */
static lz_gr *ideal_gas(lz_lattice_kind kind, int32_t L, int nshells, size_t n, int S,
                        unsigned long seed)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, seed);
	lz_gr *g = gr_by_hand(kind, L, nshells, n);
	int32_t *r = calloc(3 * n, sizeof *r);
	for (int s = 0; s < S; s++) {
		for (size_t i = 0; i < n; i++) {
			r[3 * i] = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
			r[3 * i + 1] = (int32_t)gsl_rng_uniform_int(rng, (unsigned long)L);
		}
		add_sites(g, r, n);
	}
	free(r);
	gsl_rng_free(rng);
	return g;
}

/* The relative error bar of shell k: 1/√(expected pairs). */
static double sigma(const lz_gr *g, int k)
{
	double V = (double)g->side * (double)g->side;
	double expect = (double)g->nsamples * (double)g->n * ((double)g->n - 1) / 2.0 *
	                (double)g->lattice[k] / V;
	return 1.0 / sqrt(expect);
}

LZ_TEST(gr_ideal_gas_corrected_is_one)
{
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_TRIANGULAR};
	for (size_t c = 0; c < 2; c++) {
		lz_gr *g = ideal_gas(kinds[c], 64, 32, 64, 1500, 20240 + c);
		double raw[32], cor[32];
		ck_assert_msg(lz_gr_result(g, raw, cor) == LZ_OK, "lz_gr_result: %s",
		              lz_error_message());
		double chi2 = 0.0;
		for (int k = 0; k < 32; k++) {
			double z = (cor[k] - 1.0) / sigma(g, k);
			chi2 += z * z;
			ck_assert_msg(fabs(z) < 5.0, "ideal gas on the %s lattice (64 points, 1500 "
			              "samples): corrected g in shell [%d, %d) is %.4f ± %.4f, %.1f error "
			              "bars from 1 — divide the pairs by S·N(N-1)/2·count(k)/V",
			              lz_lattice_name(kinds[c]), k, k + 1, cor[k], sigma(g, k), z);
		}
		/* 32 shells: chi² has mean 32 and sd 8. */
		ck_assert_msg(chi2 < 80.0, "ideal gas on the %s lattice: corrected g scatters around "
		              "1 with chi² = %.1f over 32 shells (expected about 32 ± 8)",
		              lz_lattice_name(kinds[c]), chi2);
		lz_gr_free(g);
	}
}
END_TEST

LZ_TEST(gr_raw_shows_lattice_noise)
{
	static const lz_lattice_kind kinds[] = {LZ_LATTICE_SQUARE, LZ_LATTICE_TRIANGULAR};
	for (size_t c = 0; c < 2; c++) {
		lz_gr *g = ideal_gas(kinds[c], 64, 16, 64, 600, 777 + c);
		double raw[16], cor[16];
		ck_assert_msg(lz_gr_result(g, raw, cor) == LZ_OK, "lz_gr_result: %s",
		              lz_error_message());
		for (int k = 0; k < 16; k++) {
			double m = measure(kinds[c], k, g->lattice[k]);
			ck_assert_msg(fabs(raw[k] - m * cor[k]) < 1e-12 * (1.0 + raw[k]), "%s lattice, "
			              "shell %d: raw g = %.15g should be the lattice measure %.6f "
			              "(count·cell/exact area) times the corrected g %.15g — is the raw "
			              "g divided by the exact shell area π(2k+1) over the box area V·cell?",
			              lz_lattice_name(kinds[c]), k, raw[k], m, cor[k]);
		}
		/* The raw normalisation on its own: over the whole disk r < 16 the ideal gas
		 * puts S·N(N-1)/2·count/V pairs, so Σ pairs / Σ expected-by-area is the lattice
		 * measure of the disk, Σ count·cell / Σ exact, within 1/√(pairs). */
		double pairs = 0, area = 0, points = 0;
		for (int k = 0; k < 16; k++) {
			double exact = M_PI * (2.0 * k + 1.0);
			pairs += raw[k] * exact;
			area += exact;
			points += (double)g->lattice[k];
		}
		double disk = pairs / area, mdisk = points * (kinds[c] == LZ_LATTICE_TRIANGULAR ?
		              sqrt(3.0) / 2.0 : 1.0) / area;
		double npairs = (double)g->nsamples * 64.0 * 63.0 / 2.0 * points / 4096.0;
		double zd = (disk - mdisk) / (mdisk / sqrt(npairs));
		ck_assert_msg(fabs(zd) < 5.0, "%s lattice ideal gas: raw g averaged over the disk "
		              "r < 16 (area-weighted) is %.5f, the disk's lattice measure is %.5f, %.1f "
		              "error bars apart — raw g = pairs / (S·N(N-1)/2 · π(2k+1) / (V·cell))",
		              lz_lattice_name(kinds[c]), disk, mdisk, zd);
		/* Shell [0, 1) holds one site but has area π: raw g ≈ 1/π (√3/(2π) triangular),
		 * tens of error bars from 1 — the lattice noise the correction removes. */
		double z0 = (raw[0] - 1.0) / sigma(g, 0);
		ck_assert_msg(z0 < -10.0, "%s lattice ideal gas: raw g in shell [0, 1) is %.3f, only "
		              "%.1f error bars from 1; the lattice puts one site where the area is π, "
		              "so it should be near %.3f", lz_lattice_name(kinds[c]), raw[0], z0,
		              measure(kinds[c], 0, 1));
		lz_gr_free(g);
	}
}
END_TEST

LZ_TEST(gr_empty_accumulator_is_an_error)
{
	lz_gr *g = gr_by_hand(LZ_LATTICE_SQUARE, 16, 4, 10);
	double raw[4] = {5, 5, 5, 5}, cor[4] = {5, 5, 5, 5};
	int status = lz_gr_result(g, raw, cor);
	ck_assert_msg(status == LZ_EINVAL && raw[0] == 5 && cor[0] == 5, "lz_gr_result with no "
	              "sample returned %d and wrote raw[0] = %g, corrected[0] = %g; with nothing "
	              "to normalise it must return LZ_EINVAL and write nothing (0/0 is NaN)",
	              status, raw[0], cor[0]);
	lz_gr_free(g);
	/* Once samples are closed it normalises. Triangular, V = 256 sites, N = 2: one pair
	 * per sample at distance 1, two samples. An ideal gas would put count(1)/V = 12/256
	 * of a pair per sample in shell 1, so corrected g = V/12 there, and the raw g =
	 * V·cell/(3π), the shell's area being 3π; 0 elsewhere. */
	g = gr_by_hand(LZ_LATTICE_TRIANGULAR, 16, 4, 2);
	for (int s = 0; s < 2; s++) {
		lz_gr_add_pair(g, 1);
		lz_gr_end_sample(g);
	}
	ck_assert_msg(lz_gr_result(g, raw, cor) == LZ_OK, "lz_gr_result after two samples: %s",
	              lz_error_message());
	double wcor = 256.0 / 12.0, wraw = 256.0 * sqrt(3.0) / 2.0 / (3.0 * M_PI);
	ck_assert_msg(fabs(cor[1] - wcor) < 1e-12 * wcor && fabs(raw[1] - wraw) < 1e-12 * wraw &&
	              cor[0] == 0 && raw[2] == 0, "triangular, V = 256, N = 2, 2 samples of one "
	              "pair at r = 1: corrected g(1) = %.15g, raw g(1) = %.15g; expected V/12 = "
	              "%.15g and V·(√3/2)/(3π) = %.15g — divide by S·N(N-1)/2 pairs (here 2), by "
	              "count(k)/V (corrected) or by the area over V·cell (raw)", cor[1], raw[1],
	              wcor, wraw);
	lz_gr_free(g);
}
END_TEST

LZ_TEST(gr_pipeline_from_positions)
{
	/* The library's path end to end: box, accumulator, all pairs, result. A full
	 * triangular lattice of side 16, added twice, gives corrected g = V/(V-1) in every
	 * shell k >= 1 (raw g that times the lattice measure), and the accumulator's
	 * lattice counts are table 2.4's. */
	const int32_t L = 16;
	const size_t V = (size_t)L * L;
	lz_lattice_box *b = lz_lattice_box_alloc(LZ_LATTICE_TRIANGULAR, L);
	lz_gr *g = lz_gr_alloc(LZ_LATTICE_TRIANGULAR, L, 8, V);
	ck_assert_msg(b && g, "allocating a side-16 triangular box and g(r) up to r = 8 failed: %s",
	              lz_error_message());
	for (int32_t u = 0; u < L; u++)
		ck_assert_msg(b->dc[u] == (2 * u <= L ? u : u - L), "precondition: the box's table "
		              "has dc[%d] = %d, expected %d — fix lz_lattice_dctable first", u, b->dc[u],
		              2 * u <= L ? u : u - L);
	for (int k = 0; k < 8; k++)
		ck_assert_msg(g->lattice[k] == table24_triangular[k], "lz_gr_alloc's lattice count "
		              "of shell %d is %" PRIu64 ", table 2.4 says %" PRIu64 " (it comes from "
		              "lz_shell_counts)", k, g->lattice[k], table24_triangular[k]);
	int32_t *r = malloc(2 * V * sizeof *r);
	for (size_t i = 0; i < V; i++) {
		r[2 * i] = (int32_t)(i % (size_t)L);
		r[2 * i + 1] = (int32_t)(i / (size_t)L);
	}
	ck_assert(lz_gr_add_config(g, b, r) == LZ_OK);
	ck_assert(lz_gr_add_config(g, b, r) == LZ_OK);
	double raw[8], cor[8];
	ck_assert_msg(lz_gr_result(g, raw, cor) == LZ_OK, "lz_gr_result: %s", lz_error_message());
	for (int k = 1; k < 8; k++)
		ck_assert_msg(fabs(cor[k] - (double)V / (V - 1.0)) < 1e-12, "full triangular lattice "
		              "of side 16 through lz_gr_add_config: corrected g in shell %d is %.15g, "
		              "expected %.15g — if only the outer shells are off, the minimum image "
		              "on the rhombus (lz_lattice_min_dist2) needs the hexagon correction",
		              k, cor[k], (double)V / (V - 1.0));
	for (int k = 1; k < 8; k++) {
		double want = (double)V / (V - 1.0) * measure(LZ_LATTICE_TRIANGULAR, k, g->lattice[k]);
		ck_assert_msg(fabs(raw[k] - want) < 1e-12 * want, "full triangular lattice: raw g in "
		              "shell %d is %.15g, expected %.15g = V/(V-1) times the lattice measure "
		              "count·(√3/2)/(π(2k+1))", k, raw[k], want);
	}
	uint64_t inside = 0;
	for (int k = 1; k < 8; k++)
		inside += V / 2 * table24_triangular[k];
	ck_assert_msg(g->beyond == 2 * (V * (V - 1) / 2 - inside), "pairs beyond r = 8 over two "
	              "samples: %" PRIu64 ", expected %" PRIu64, g->beyond,
	              (uint64_t)(2 * (V * (V - 1) / 2 - inside)));
	free(r);
	lz_gr_free(g);
	lz_lattice_box_free(b);
}
END_TEST
