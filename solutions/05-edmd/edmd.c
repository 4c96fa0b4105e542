/* edmd.c — event-driven hard spheres: when two spheres touch, how they bounce, when a
 * particle leaves its cell, the prediction of a particle's next event and the event
 * loop itself (graded). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "lz/edmd.h"
#include "lz/heap.h"

/* LZ_HELPERS_BEGIN */
/* lz_edmd_pair_time with one branch, for the hot loop of lz_edmd_predict: the square
 * root is taken of max(disc, 0) whatever the case, and the verdict picked at the end,
 * which costs less than the mispredicted branches of the textbook version. */
static inline double collision_time(const double dr[3], const double dv[3])
{
	double b = dr[0] * dv[0] + dr[1] * dv[1] + dr[2] * dv[2];
	double dv2 = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
	double c = dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2] - 1.0;
	double disc = b * b - dv2 * c;
	double t = c > 0 ? c / (-b + __builtin_sqrt(disc > 0 ? disc : 0)) : 0.0;
	return b < 0 && disc > 0 ? t : INFINITY;
}
/* LZ_HELPERS_END */

double lz_edmd_pair_time(const double dr[3], const double dv[3])
{
	/* Hint: with b = dr·dv, the pair approaches only when b < 0. Solve
	 * |dr + dv t|² = 1: dv² t² + 2b t + (dr² - 1) = 0, discriminant b² - dv²(dr² - 1);
	 * no collision when it is <= 0 (a miss, or a graze with no approach). Of the two
	 * roots take the smaller, written as c / (-b + √disc), c = dr² - 1, which never
	 * subtracts nearly equal numbers. A touching pair (c <= 0) that approaches
	 * collides now. See §3 "When do two spheres touch?" in lessons/05-edmd/README.md. */
	/* LZ_SOLUTION_BEGIN */
	double b = dr[0] * dv[0] + dr[1] * dv[1] + dr[2] * dv[2];
	if (b >= 0)
		return INFINITY;
	double dv2 = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
	double c = dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2] - 1.0;
	double disc = b * b - dv2 * c;
	if (disc <= 0)
		return INFINITY;
	if (c <= 0)
		return 0.0;
	return c / (-b + sqrt(disc));
	/* LZ_SOLUTION_END */
}

double lz_edmd_bounce(lz_edmd_particle *a, lz_edmd_particle *b, const double dr[3],
                      double restitution)
{
	/* Hint: k = dr/|dr|; the normal relative velocity is u = (v_b - v_a)·k (< 0 when
	 * approaching). The impulse along k is d = (1 + e_r)/2 · u: a gains d·k, b loses
	 * it. Check with e_r = 1 that u changes sign and the energy stays. The virial is
	 * |dr| · |d|. See §3 "The bounce". */
	/* LZ_SOLUTION_BEGIN */
	double d = sqrt(dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2]);
	double k[3] = {dr[0] / d, dr[1] / d, dr[2] / d};
	double u = (b->v[0] - a->v[0]) * k[0] + (b->v[1] - a->v[1]) * k[1] +
	           (b->v[2] - a->v[2]) * k[2];
	double imp = 0.5 * (1.0 + restitution) * u;
	for (int x = 0; x < 3; x++) {
		a->v[x] += imp * k[x];
		b->v[x] -= imp * k[x];
	}
	return d * fabs(imp);
	/* LZ_SOLUTION_END */
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
	/* LZ_SOLUTION_BEGIN */
	uint32_t cc[3] = {c % (uint32_t)e->m[0], (c / (uint32_t)e->m[0]) % (uint32_t)e->m[1],
	                  c / ((uint32_t)e->m[0] * (uint32_t)e->m[1])};
	double best = INFINITY;
	*face = 0;
	for (int a = 0; a < e->dim; a++) {
		double lo = cc[a] * e->w[a], hi = (cc[a] + 1) * e->w[a];
		if (e->wall[a]) {
			if (cc[a] == 0)
				lo = 0.5;
			if ((int)cc[a] == e->m[a] - 1)
				hi = e->L - 0.5;
		}
		double t;
		int up;
		if (a == 0 && e->g > 0) {
			t = lz_edmd_fall_time(r[0], v[0], e->g, lo, hi, &up);
		} else if (v[a] > 0) {
			t = (hi - r[a]) / v[a];
			up = 1;
		} else if (v[a] < 0) {
			t = (lo - r[a]) / v[a];
			up = 0;
		} else {
			continue;
		}
		if (t < best) {
			best = t;
			*face = 2 * a + up;
		}
	}
	return best > 0 ? best : 0.0;
	/* LZ_SOLUTION_END */
}

void lz_edmd_predict(lz_edmd *e, uint32_t i)
{
	/* Hint: get i's position and velocity now (lz_edmd_state). Start from the cell
	 * time (partner LZ_EDMD_FACE(face), or LZ_EDMD_NONE at infinity). Then for every
	 * cell of lz_edmd_block(e, p[i].cell, ...) and every j != i in its list
	 * (head/next), take j's state now, dr = r_j + shift - r_i, dv = v_j - v_i, and
	 * keep the earliest lz_edmd_pair_time with the partner's count. Store ev[i] and
	 * give i the key now + t in the heap (lz_heap_contains: update, else push).
	 * See §5 "One event per particle". */
	/* LZ_SOLUTION_BEGIN */
	const lz_edmd_particle *pi = &e->p[i];
	double ri[3], vi[3];
	lz_edmd_state(e, pi, e->now, ri, vi);
	int face;
	double best = lz_edmd_cell_time(e, ri, vi, pi->cell, &face);
	lz_edmd_event ev = {isinf(best) ? LZ_EDMD_NONE : LZ_EDMD_FACE(face), 0};
	uint32_t nb[27];
	double shift[27][3];
	int nnb = lz_edmd_block(e, pi->cell, nb, shift);
	const double now = e->now, g = e->g;
	for (int k = 0; k < nnb; k++) {
		/* i seen from cell nb[k]: its position moved by -shift, once per cell */
		const double x = ri[0] - shift[k][0], y = ri[1] - shift[k][1], z = ri[2] - shift[k][2];
		for (int32_t j = e->head[nb[k]]; j >= 0; j = e->next[j]) {
			const lz_edmd_particle *pj = &e->p[j];
			double dt = now - pj->t0;
			double dv[3] = {pj->v[0] - g * dt - vi[0], pj->v[1] - vi[1], pj->v[2] - vi[2]};
			double dr[3] = {pj->r[0] + (pj->v[0] - 0.5 * g * dt) * dt - x,
			                pj->r[1] + pj->v[1] * dt - y, pj->r[2] + pj->v[2] * dt - z};
			double t = collision_time(dr, dv);
			if (t < best && (uint32_t)j != i) {
				best = t;
				ev.partner = j;
				ev.pcount = pj->count;
			}
		}
	}
	e->ev[i] = ev;
	if (lz_heap_contains(e->heap, i))
		lz_heap_update(e->heap, i, e->now + best);
	else
		lz_heap_push(e->heap, i, e->now + best);
	/* LZ_SOLUTION_END */
}

/* LZ_HELPERS_BEGIN */
/* The nearest-image separation r_b - r_a of two particles brought to the same time. */
static void separation(const lz_edmd *e, const lz_edmd_particle *a, const lz_edmd_particle *b,
                       double dr[3])
{
	for (int x = 0; x < 3; x++) {
		dr[x] = b->r[x] - a->r[x];
		if (!e->wall[x] && x < e->dim)
			dr[x] -= e->L * rint(dr[x] / e->L);
	}
}
/* LZ_HELPERS_END */

int lz_edmd_step(lz_edmd *e)
{
	/* Hint: i = lz_heap_top, t = lz_heap_top_t; infinity means nothing will ever
	 * happen: return -1. Otherwise follow the four cases of the header: validate a
	 * collision by the partner's count before touching anything; bring the
	 * particles to t with lz_edmd_advance; the separation for the bounce is the
	 * nearest image (subtract L·rint(dx/L) on periodic axes); a face is a wall when
	 * that axis has walls and the cell is at that edge; lz_edmd_cell_across gives
	 * the next cell and the jump across the boundary; counters as the header says.
	 * See §5 "The event loop". */
	/* LZ_SOLUTION_BEGIN */
	uint32_t i = lz_heap_top(e->heap);
	double t = lz_heap_top_t(e->heap);
	if (isinf(t))
		return -1;
	e->events++;
	e->now = t;
	lz_edmd_event ev = e->ev[i];
	lz_edmd_particle *pi = &e->p[i];
	if (ev.partner >= 0) {
		lz_edmd_particle *pj = &e->p[ev.partner];
		if (pj->count != ev.pcount) {
			e->stale++;
			lz_edmd_predict(e, i);
			return 0;
		}
		lz_edmd_advance(e, pi, t);
		lz_edmd_advance(e, pj, t);
		double dr[3];
		separation(e, pi, pj, dr);
		e->virial += lz_edmd_bounce(pi, pj, dr, e->restitution);
		pi->count++;
		pj->count++;
		e->collisions++;
		lz_edmd_predict(e, i);
		lz_edmd_predict(e, (uint32_t)ev.partner);
		return 0;
	}
	int f = -1 - ev.partner, a = f / 2, up = f % 2;
	lz_edmd_advance(e, pi, t);
	uint32_t c = pi->cell, ca = a == 0 ? c % (uint32_t)e->m[0]
	                          : a == 1 ? (c / (uint32_t)e->m[0]) % (uint32_t)e->m[1]
	                                   : c / ((uint32_t)e->m[0] * (uint32_t)e->m[1]);
	if (e->wall[a] && (int)ca == (up ? e->m[a] - 1 : 0)) {
		pi->r[a] = up ? e->L - 0.5 : 0.5;
		pi->v[a] = -pi->v[a];
		pi->count++;
		e->bounces++;
	} else {
		double jump;
		uint32_t to = lz_edmd_cell_across(e, c, f, &jump);
		pi->r[a] += jump;
		lz_edmd_cell_remove(e, i);
		lz_edmd_cell_insert(e, i, to);
		e->crossings++;
	}
	lz_edmd_predict(e, i);
	return 0;
	/* LZ_SOLUTION_END */
}
