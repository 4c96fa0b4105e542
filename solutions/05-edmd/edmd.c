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
	 * |dr| · |d|. See §3 "When do two spheres touch, and how do they bounce?". */
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
		} else {
			/* the sign of v is a coin toss: chosen without a branch (v = 0: the
			 * face at infinity) */
			up = v[a] > 0;
			t = v[a] != 0 ? ((up ? hi : lo) - r[a]) / v[a] : INFINITY;
		}
		int earlier = t < best;
		best = earlier ? t : best;
		*face = earlier ? 2 * a + up : *face;
	}
	return best > 0 ? best : 0.0;
	/* LZ_SOLUTION_END */
}

/* LZ_HELPERS_BEGIN */
/* The earliest collision of particle self (velocity vi at now) with the nc candidates
 * cand[q], seen from cell from[q] of the block (i's position there: seen[from[q]]),
 * if earlier than *best: then *best and *ev become it. lz_edmd_pair_time without
 * branches. fall (gravity) and shifted (some cell of the block is seen across the
 * periodic boundary; else seen[0] serves all) are constants at each call, since the
 * function is always inlined: without gravity the compiler drops the fall terms, so
 * that gravity costs nothing when a scene has none. */
static inline __attribute__((always_inline)) void
earliest(const lz_edmd *e, int32_t self, const int32_t *cand, const uint8_t *from, int nc,
         const double seen[][3], const double vi[3], double *best, lz_edmd_event *ev,
         int fall, int shifted)
{
	const double now = e->now, g = e->g;
	double first = *best;
	int32_t who = -1;
	for (int q = 0; q < nc; q++) {
		const lz_edmd_particle *pj = &e->p[cand[q]];
		const double *ro = seen[shifted ? from[q] : 0];
		double dt = now - pj->t0;
		double x0 = pj->r[0] + pj->v[0] * dt, u0 = pj->v[0];  /* as lz_edmd_state */
		if (fall) {
			x0 -= 0.5 * g * dt * dt;
			u0 -= g * dt;
		}
		double dv0 = u0 - vi[0], dv1 = pj->v[1] - vi[1], dv2 = pj->v[2] - vi[2];
		double dr0 = x0 - ro[0];
		double dr1 = pj->r[1] + pj->v[1] * dt - ro[1], dr2 = pj->r[2] + pj->v[2] * dt - ro[2];
		double b = dr0 * dv0 + dr1 * dv1 + dr2 * dv2;
		double vv = dv0 * dv0 + dv1 * dv1 + dv2 * dv2;
		double c = dr0 * dr0 + dr1 * dr1 + dr2 * dr2 - 1.0;
		double disc = b * b - vv * c;
		/* max(x, 0) = (x + |x|)/2 exactly, without a branch: t = 0 when touching,
		 * and a negative disc (a miss, rejected below) is not rooted */
		double cp = 0.5 * (c + fabs(c)), dp = 0.5 * (disc + fabs(disc));
		/* a pair that recedes or misses never collides, nor does i with itself (it is
		 * among the candidates: excluded here rather than by a branch in the
		 * gathering, and never trusted to give exactly dr = dv = 0). Whether a
		 * candidate approaches is a coin toss a branch would miss half the time, so
		 * the verdict is an index instead: t + 0 or t + ∞ */
		static const double never[2] = {INFINITY, 0};
		double t = cp / (-b + sqrt(dp)) + never[(b < 0) & (disc > 0) & (cand[q] != self)];
		int earlier = t < first;  /* and keep the earliest, without a branch either */
		who = earlier ? q : who;
		first = earlier ? t : first;
	}
	if (who >= 0) {
		*best = first;
		ev->partner = cand[who];
		ev->pcount = e->p[cand[who]].count;
	}
}

static void scan(const lz_edmd *e, int32_t self, const int32_t *cand, const uint8_t *from,
                 int nc, const double seen[][3], const double vi[3], double *best,
                 lz_edmd_event *ev, int shifted)
{
	if (e->g > 0)  /* rare: one inlined copy, shifted looked at each time */
		earliest(e, self, cand, from, nc, seen, vi, best, ev, 1, shifted);
	else if (shifted)
		earliest(e, self, cand, from, nc, seen, vi, best, ev, 0, 1);
	else
		earliest(e, self, cand, from, nc, seen, vi, best, ev, 0, 0);
}
/* LZ_HELPERS_END */

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
	/* LZ_SOLUTION_BEGIN */
	const lz_edmd_particle *pi = &e->p[i];
	double ri[3], vi[3];
	lz_edmd_state(e, pi, e->now, ri, vi);
	int face;
	double best = lz_edmd_cell_time(e, ri, vi, pi->cell, &face);
	lz_edmd_event ev = {isinf(best) ? LZ_EDMD_NONE : LZ_EDMD_FACE(face), 0};
	/* The block's particles are gathered into a list breadth first, then scanned
	 * by earliest, so that the hot loops have almost no branch to mispredict and
	 * the memory reads of different cells overlap instead of waiting on each
	 * other: the heads of all the cells; the second particle of every cell (the
	 * sentinel next[-1] = -1 makes that read safe for an empty cell, and no branch
	 * depends on it); then the rare third and later ones. In a big system
	 * (e->prefetch) the candidates' records are requested before the scan reads
	 * them. See §9 "Speed". */
	lz_edmd_block b;
	lz_edmd_block_of(e, pi->cell, &b);
	int32_t first[27], second[27], cand[LZ_EDMD_GATHER];
	uint8_t from[LZ_EDMD_GATHER], more[27];
	double seen[27][3];  /* i's position as seen from each cell of the block */
	int nk = 0, shifted = b.wraps || b.n[0] < 3;  /* seen[k] per cell, or seen[0] */
	if (!shifted) {
		/* inside the box: each row of the block is three cells side by side, and
		 * every cell sees i where it is (seen[0]) */
		for (int z = 0; z < b.n[2]; z++)
			for (int y = 0; y < b.n[1]; y++, nk += 3) {
				uint32_t row = b.off[0][0] + b.off[1][y] + b.off[2][z];
				for (int x = 0; x < 3; x++) {
					first[nk + x] = e->list[row + x].head;
					second[nk + x] = e->list[row + x].second;
				}
			}
		for (int a = 0; a < 3; a++)
			seen[0][a] = ri[a];
	} else {
		for (int z = 0; z < b.n[2]; z++)
			for (int y = 0; y < b.n[1]; y++)
				for (int x = 0; x < b.n[0]; x++, nk++) {
					uint32_t c = b.off[0][x] + b.off[1][y] + b.off[2][z];
					first[nk] = e->list[c].head;
					second[nk] = e->list[c].second;
					seen[nk][0] = ri[0] - b.shift[0][x];
					seen[nk][1] = ri[1] - b.shift[1][y];
					seen[nk][2] = ri[2] - b.shift[2][z];
				}
	}
	int nc = 0, nm = 0;
	for (int k = 0; k < nk; k++) {
		cand[nc] = first[k];
		from[nc] = (uint8_t)k;
		nc += first[k] >= 0;
		cand[nc] = second[k];
		from[nc] = (uint8_t)k;
		nc += second[k] >= 0;
		more[nm] = (uint8_t)k;  /* the cells with a second particle may have more */
		nm += second[k] >= 0;
	}
	if (e->prefetch)
		for (int q = 0; q < nc; q++)
			__builtin_prefetch(&e->p[cand[q]]);
	for (int r = 0; r < nm; r++) {
		int k = more[r];
		for (int32_t j = e->next[second[k]]; j >= 0; j = e->next[j]) {
			if (nc == LZ_EDMD_GATHER) {  /* a crowded block: scan what we have */
				scan(e, (int32_t)i, cand, from, nc, seen, vi, &best, &ev, shifted);
				nc = 0;
			}
			__builtin_prefetch(&e->p[j]);
			cand[nc] = j;
			from[nc++] = (uint8_t)k;
		}
	}
	scan(e, (int32_t)i, cand, from, nc, seen, vi, &best, &ev, shifted);
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
	 * See §5 "One event per particle; counters, not deletion". */
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
	uint32_t c = e->p[i].cell, ca = a == 0 ? c % (uint32_t)e->m[0]
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
