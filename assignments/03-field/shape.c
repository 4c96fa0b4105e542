/* YOUR FILE — this is the file you fill in for stage 03-field.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/03-field/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=03`; see your own code at work with
 * `make lesson STAGE=03`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* shape.c — the lattice points of a disk (sphere) and its head and tail tables
 * (graded). */
#include <stddef.h>
#include <stdint.h>

#include "lz/error.h"
#include "lz/shape.h"

/* Scan the bounding box and keep the offsets strictly inside: the integer test
 * d2 < r2 needs no floating point and no square root. */
int lz_shape_fill_points(lz_shape *s)
{
	/* Hint: three nested loops over -reach .. reach (the z loop runs only from 0 to 0
	 * in 2D). An offset is in the shape when lz_lattice_dist2(s->kind, x, y, z) <
	 * s->r2 — strictly below: a point at distance exactly r is outside (lz_shape_contains
	 * says it in one call). Append it to s->pts and count it in s->n (start n at 0).
	 * See the field section of lessons/03-field/README.md. */
	LZ_TODO();
}

/* A head point is p + e for a point p of S with p + e outside S; a tail point is a
 * point p of S with p - e outside S (it is not in S + e). Each point of S is looked
 * at once per direction, and membership is the O(1) distance test. */
int lz_shape_fill_moves(lz_shape *s)
{
	/* Hint: for every direction d with step e = s->dirs[d]: go through the points p of
	 * s->pts; if p + e is not in the shape, p + e is a head point (the shape gains it
	 * when its centre steps by e); if p - e is not in the shape, p is a tail point (the
	 * shape loses it). Both are offsets from the centre before the step. Count them in
	 * s->nmove[d] (there are as many heads as tails). self[d] is 1 when e itself is in
	 * the shape. See fig. 2.9 of the thesis and lessons/03-field/README.md. */
	LZ_TODO();
}
