/* run_table.h — the table `lz run` prints after a run: the method's headline
 * observables with their error bars and references, its speed and the seed, read back
 * from the run's summary.json, so that what is printed is what was written.
 *
 *   05-spheres (edmd)
 *     quantity          value              reference
 *     Z                 4.0999 ± 0.0036    4.1078 (table)
 *     ...
 *     speed             2.31e+06 events/s (CPU)
 *     seed              42
 */
#ifndef LZ_RUN_TABLE_H
#define LZ_RUN_TABLE_H

#include <stddef.h>
#include <stdio.h>

#include "method.h"

/* "v ± err" with err rounded to 2 significant digits and v to the same decimal place
 * (4.0999 ± 0.0036, 123460 ± 340, (1.2345 ± 0.0034)e-5 beyond 10^±5); v alone with 6
 * significant digits when err is not a positive number. */
void lz_format_err(double v, double err, char *buf, size_t size);

/* Characters of UTF-8 text, not bytes (±, σ, τ), for aligning columns. */
int lz_text_width(const char *t);

/* The table of the summary.json at `path` on f, under the title "NAME (method)":
 * m's headline rows that the summary holds, its first speed figure it holds, and
 * `seed`. LZ_OK, or LZ_EIO when the file cannot be read. O(summary). */
int lz_run_table(FILE *f, const lz_method *m, const char *name, const char *path);

#endif
