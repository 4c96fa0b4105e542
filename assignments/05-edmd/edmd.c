/* YOUR FILE — this is the file you fill in for stage 05-edmd.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/05-edmd/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=05`; see your own code at work with
 * `make lesson STAGE=05`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* edmd.c — event-driven hard spheres: when two spheres touch, how they bounce, when a
 * particle leaves its cell, the prediction of a particle's next event and the event
 * loop itself (graded). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "lz/edmd.h"
#include "lz/heap.h"

double lz_edmd_pair_time(const double dr[3], const double dv[3])
{
	/* Hint: with b = dr·dv, the pair approaches only when b < 0. Solve
	 * |dr + dv t|² = 1: dv² t² + 2b t + (dr² - 1) = 0, discriminant b² - dv²(dr² - 1);
	 * no collision when it is <= 0 (a miss, or a graze with no approach). Of the two
	 * roots take the smaller, written as c / (-b + √disc), c = dr² - 1, which never
	 * subtracts nearly equal numbers. A touching pair (c <= 0) that approaches
	 * collides now. See §3 "When do two spheres touch, and how do they bounce?" in
	 * lessons/05-edmd/README.md. */
	LZ_TODO();
}

double lz_edmd_bounce(lz_edmd_particle *a, lz_edmd_particle *b, const double dr[3],
                      double restitution)
{
	/* Hint: k = dr/|dr|; the normal relative velocity is u = (v_b - v_a)·k (< 0 when
	 * approaching). The impulse along k is d = (1 + e_r)/2 · u: a gains d·k, b loses
	 * it. Check with e_r = 1 that u changes sign and the energy stays. The virial is
	 * |dr| · |d|. See §3 "When do two spheres touch, and how do they bounce?". */
	LZ_TODO();
}

double lz_edmd_cell_time(const lz_edmd *e, const double r[3], const double v[3], uint32_t c,
                         int *face)
{
	/* Hint: the cell's coordinates are cx = c % m[0], cy = (c / m[0]) % m[1], cz =
	 * c / (m[0] m[1]); on axis a it spans [c_a w[a], (c_a + 1) w[a]). Moving up
	 * (v > 0) the particle meets the upper face at (hi - r)/v, moving down the lower
	 * at (lo - r)/v. On an axis with walls, an edge cell's wall-side face is the
	 * contact instead: lo = 1/2 in the first cell, hi = L - 1/2 in the last. Axis 0
	 * with gravity (e->g > 0) falls: use lz_edmd_fall_time. Take the earliest axis,
	 * never a negative time. See §6 "Cells and their faces". */
	LZ_TODO();
}


void lz_edmd_predict(lz_edmd *e, uint32_t i)
{
	/* Hint: get i's position and velocity now (lz_edmd_state). Start from the cell
	 * time (partner LZ_EDMD_FACE(face), or LZ_EDMD_NONE at infinity). Then for every
	 * cell of the block (lz_edmd_block_of(e, p[i].cell, &b): a loop over z, y, x) and
	 * every j != i in its list (j = list[c].head, then next[j]), take j's state now,
	 * dr = r_j + shift - r_i (the shifts of the cell's three axes), dv = v_j - v_i,
	 * and keep the earliest lz_edmd_pair_time with the partner's count. Store ev[i] and
	 * give i the key now + t in the heap (lz_heap_contains: update, else push).
	 * See §5 "One event per particle; counters, not deletion". */
	LZ_TODO();
}


int lz_edmd_step(lz_edmd *e)
{
	/* Hint: i = lz_heap_top, t = lz_heap_top_t; infinity means nothing will ever
	 * happen: return -1. Otherwise follow the four cases of the header: validate a
	 * collision by the partner's count before touching anything; bring the
	 * particles to t with lz_edmd_advance; the separation for the bounce is the
	 * nearest image (subtract L·rint(dx/L) on periodic axes); a face is a wall when
	 * that axis has walls and the cell is at that edge; lz_edmd_cell_across gives
	 * the next cell and the jump across the boundary; counters as the header says.
	 * See §5 "One event per particle; counters, not deletion". */
	LZ_TODO();
}
