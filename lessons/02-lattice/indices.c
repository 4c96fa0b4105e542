/* indices — lesson 02, experiment 1 (§1, §8): the order of indices and the cache.
 *
 * A square n×n array of int32 (a lattice of n² sites, C stores it row after row)
 * is swept once with the last index in the inner loop (row order: consecutive
 * addresses) and once with the first index in the inner loop (column order: a jump of
 * n·4 bytes between accesses). Each sweep adds 1 to every element, so both do the
 * same work and leave the same array. The sizes run from 32² (4 kB, inside L1) to
 * 8192² (256 MB, far outside every cache). A third sweep goes in column order over
 * the same n×n elements stored with a padded row length n + 16: the lattices of this
 * course are powers of two, and a stride of exactly 2^k bytes maps every access of a
 * column onto the same few cache sets.
 *
 * Usage: indices OUTDIR [--quick]   (quick: n <= 2048, 16 MB; full: n <= 8192, 256 MB)
 * Writes OUTDIR/indices.dat and indices.json. Checks that the two orders leave the
 * same array and that column order is slower outside the cache.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/timer.h"

#define MIN_CPU 0.1  /* seconds of CPU per timing, at least */
#define BATCH ((size_t)1 << 20)
#define PAD 16       /* extra int32 per row of the padded layout: 64 bytes */

/* One sweep, a[i][j] += 1 for all i, j, with row length ld >= n. */
static void sweep_rows(int32_t *a, size_t n, size_t ld)
{
	for (size_t i = 0; i < n; i++)
		for (size_t j = 0; j < n; j++)
			a[i * ld + j] += 1;
}

static void sweep_cols(int32_t *a, size_t n, size_t ld)
{
	for (size_t j = 0; j < n; j++)
		for (size_t i = 0; i < n; i++)
			a[i * ld + j] += 1;
}

/* CPU ns per element of repeated sweeps; *sweeps counts them (the array grows by
 * that much everywhere). */
static double ns_per_element(void (*sweep)(int32_t *, size_t, size_t), int32_t *a,
                             size_t n, size_t ld, long *sweeps)
{
	/* sweeps per look at the clock: about 2^20 elements, so that reading the clock
	 * (a system call, ~1 µs) does not count in the time of a 32² sweep */
	long batch = n * n >= BATCH ? 1 : (long)(BATCH / (n * n)), reps = 0;
	sweep(a, n, ld);  /* touch the pages and warm the caches once, untimed */
	(*sweeps)++;
	double t0 = lz_cpu_now(), used;
	do {
		for (long b = 0; b < batch; b++)
			sweep(a, n, ld);
		reps += batch;
		used = lz_cpu_now() - t0;
	} while (used < MIN_CPU);
	*sweeps += reps;
	return 1e9 * used / ((double)reps * (double)n * (double)n);
}

/* 1 when every a[i][j] (row length ld) equals v. */
static int all_equal(const int32_t *a, size_t n, size_t ld, long v)
{
	for (size_t i = 0; i < n; i++)
		for (size_t j = 0; j < n; j++)
			if (a[i * ld + j] != v)
				return 0;
	return 1;
}

int main(int argc, char **argv)
{
	static const char *names[] = {"n", "bytes", "row_ns", "col_ns", "col_padded_ns",
	                              "ratio", "ratio_padded"};
	static const char *units[] = {"sites", "B", "ns/site", "ns/site", "ns/site", "", ""};
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	size_t nmax = L.quick ? 2048 : 8192;
	printf("indices: n x n int32 arrays, n = 32 ... %zu, a[i][j] += 1 swept in row order "
	       "(j inner) and column order (i inner),\n  each timed for >= %.1f s of CPU; "
	       "padded column order uses rows of n + %d\n", nmax, MIN_CPU, PAD);
	lz_data *d = lz_lesson_data(&L, "indices.dat", "row- vs column-order sweeps of an "
	                            "n x n int32 array: CPU time per element", 7, names, units);
	if (!d)
		return lz_lesson_error(&L);
	double last_ratio = 0.0, small_ratio = 0.0, last_row = 0.0, last_col = 0.0;
	double last_pad = 0.0;
	int same = 1;
	printf("  %6s %10s %9s %9s %11s %7s %9s\n", "n", "bytes", "row ns", "col ns",
	       "col+pad ns", "ratio", "ratio pad");
	for (size_t n = 32; n <= nmax; n *= 2) {
		size_t ld = n + PAD;
		int32_t *a = calloc(n * ld, sizeof *a);
		if (!a) {
			lz_data_close(d);
			lz_error(LZ_ENOMEM, "no memory for a %zu x %zu array", n, ld);
			return lz_lesson_error(&L);
		}
		long rows = 0, cols = 0, padded = 0;
		double tr = ns_per_element(sweep_rows, a, n, n, &rows);
		double tc = ns_per_element(sweep_cols, a, n, n, &cols);
		/* the unpadded array ends where the padded one would start its 2nd row: keep
		 * the two layouts apart by clearing and re-using the buffer */
		same = same && all_equal(a, n, n, rows + cols);
		for (size_t k = 0; k < n * ld; k++)
			a[k] = 0;
		double tp = ns_per_element(sweep_cols, a, n, ld, &padded);
		same = same && all_equal(a, n, ld, padded);
		free(a);
		double bytes = 4.0 * (double)(n * n);
		double row[7] = {(double)n, bytes, tr, tc, tp, tc / tr, tp / tr};
		lz_data_row(d, row);
		printf("  %6zu %10.0f %9.3f %9.3f %11.3f %7.1f %9.1f\n", n, bytes, tr, tc, tp,
		       tc / tr, tp / tr);
		fflush(stdout);
		if (n == 64)
			small_ratio = tc / tr;
		last_ratio = tc / tr;
		last_row = tr;
		last_col = tc;
		last_pad = tp;
	}
	if (lz_data_close(d) != LZ_OK)
		return lz_lesson_error(&L);
	printf("  both orders leave every element at the number of sweeps: %s\n",
	       lz_lesson_check(&L, same));
	printf("  column order slower than row order outside the cache (ratio %.1f > 1.5; "
	       "the thesis saw 3-5 x): %s\n", last_ratio, lz_lesson_check(&L, last_ratio > 1.5));
	lz_json *j = lz_lesson_json(&L, "indices.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "n_max", (long long)nmax);
	lz_json_num(j, "row_ns_per_site_at_n_max", last_row);
	lz_json_num(j, "col_ns_per_site_at_n_max", last_col);
	lz_json_num(j, "col_padded_ns_per_site_at_n_max", last_pad);
	lz_json_num(j, "col_over_row_at_n_max", last_ratio);
	lz_json_num(j, "col_over_row_at_n_64", small_ratio);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "same result both ways, column order %.1f x slower at n = %zu",
	                        last_ratio, nmax);
}
