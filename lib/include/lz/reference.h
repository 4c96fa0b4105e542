/* lz/reference.h — literature values, read from the tables of datasets/reference/.
 *
 * Every value the tests, the lessons and the engines compare with (equations of state,
 * jamming coverages, Lennard-Jones pressures, ...) lives in one CSV file per subject,
 * with its uncertainty and its source, and is read from there, never copied into the
 * code. A file is '#' comment lines, then a header line, then one row per value:
 *     quantity,dim,state,value,uncertainty,source
 *     Z,3,eta=0.30,3.9840,0.0005,"Clisby & McCoy, J. Stat. Phys. 122, 15 (2006): ..."
 * Fields may be quoted ("..."; "" is a quote). Rows whose value or uncertainty is not a
 * number (a formula, "exact", "not stated") document a result and cannot be looked up.
 *
 * The directory is $LZ_REFERENCE_DIR when set, else the tree's own datasets/reference/
 * (its absolute path is compiled in). Units are those the file's header states.
 */
#ifndef LZ_REFERENCE_H
#define LZ_REFERENCE_H

#include <stddef.h>

/* A value and its uncertainty (one standard error, or the spread the source gives). */
typedef struct {
	double value, err;
} lz_ref;

/* The directory the tables are read from. */
const char *lz_reference_dir(void);

/* The row of `file` (e.g. "hard-spheres.csv") whose quantity, dim and state columns are
 * exactly the ones given. LZ_OK with *r; LZ_EIO when the file cannot be read; LZ_EINVAL
 * naming the file and the row asked for when there is no such row; LZ_ESYNTAX when the
 * row's value or uncertainty is not a number. O(rows). */
int lz_reference(const char *file, const char *quantity, const char *dim, const char *state,
                 lz_ref *r);

/* The rows of `file` with this quantity and dim whose state reads "VAR=x" (x a number),
 * in the file's order: x into xs[k], the values into ys[k], at most max of them; their
 * number in *n. Errors as lz_reference (LZ_EINVAL when no row matches). O(rows). */
int lz_reference_table(const char *file, const char *quantity, const char *dim,
                       const char *var, double *xs, lz_ref *ys, size_t max, size_t *n);

/* The row of lz_reference_table whose x equals `x` (to 1e-9): e.g. Z at eta = 0.3,
 * however the file writes the number. Errors as lz_reference. O(rows). */
int lz_reference_at(const char *file, const char *quantity, const char *dim, const char *var,
                    double x, lz_ref *r);

#endif
