/* edmd_list.c — the neighbour lists of lz/edmd.h: building a particle's list from the
 * cells, the prediction from a list, the skin event, and the checks. It calls the
 * cells (edmd_cells.c), the heap and the graded bounce; edmd_lib.c and edmd_run.c call
 * it, never the other way round. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "lz/bigmem.h"
#include "lz/edmd.h"
#include "lz/error.h"

#define NONE UINT32_MAX

/* ---- a particle's block: its centre, count, flags and the first cap neighbours ---- */

static inline lz_edmd_nbl *blk(const lz_edmd_lists *l, uint32_t i)
{
	return (lz_edmd_nbl *)(l->block + (size_t)i * l->stride);
}

/* i's centre in σ (exactly: a multiple of the unit). */
static inline void centre_of(const lz_edmd_lists *l, uint32_t i, double c[3])
{
	const lz_edmd_nbl *b = blk(l, i);
	for (int a = 0; a < 3; a++)
		c[a] = b->c[a] * l->unit;
}

/* Where the neighbours of i are: the block itself when they fit, else copied into buf
 * (the first cap - 1 from the block, the rest from its chain of chunks). Their number
 * in *n. O(neighbours). */
static const uint32_t *neighbours(const lz_edmd_lists *l, uint32_t i, uint32_t *buf, int *n)
{
	const lz_edmd_nbl *b = blk(l, i);
	*n = b->count;
	if (b->count <= l->cap)
		return b->nb;
	int k = (int)l->cap - 1;
	memcpy(buf, b->nb, (size_t)k * sizeof *buf);
	for (uint32_t h = b->nb[l->cap - 1]; h != NONE; h = l->chunk[h].next)
		for (int q = 0; q < LZ_EDMD_CHUNK && k < b->count; q++)
			buf[k++] = l->chunk[h].nb[q];
	return buf;
}

/* The slot of i's k-th neighbour (k < count). */
static uint32_t *slot(const lz_edmd_lists *l, uint32_t i, int k)
{
	lz_edmd_nbl *b = blk(l, i);
	if (b->count <= l->cap || k < (int)l->cap - 1)
		return &b->nb[k];
	uint32_t h = b->nb[l->cap - 1];
	for (k -= (int)l->cap - 1; k >= LZ_EDMD_CHUNK; k -= LZ_EDMD_CHUNK)
		h = l->chunk[h].next;
	return &l->chunk[h].nb[k];
}

/* A chunk from the free ones, or a new one. NONE when out of memory. */
static uint32_t chunk_new(lz_edmd_lists *l)
{
	if (l->spare == NONE) {
		if (l->nchunk == l->capchunk) {
			size_t cap = l->capchunk ? 2 * l->capchunk : 256;
			lz_edmd_chunk *c = realloc(l->chunk, cap * sizeof *c);
			if (!c || cap >= NONE)
				return NONE;
			l->chunk = c;
			l->capchunk = cap;
		}
		l->chunk[l->nchunk].next = NONE;
		l->spare = (uint32_t)l->nchunk++;
	}
	uint32_t h = l->spare;
	l->spare = l->chunk[h].next;
	l->chunk[h].next = NONE;
	l->chunks++;
	return h;
}

static void chunk_free(lz_edmd_lists *l, uint32_t h)
{
	l->chunk[h].next = l->spare;
	l->spare = h;
	l->chunks--;
}

/* j appended to i's list. LZ_OK, LZ_ENOMEM, or LZ_EDOM past 255 neighbours. */
static int add(lz_edmd_lists *l, uint32_t i, uint32_t j)
{
	lz_edmd_nbl *b = blk(l, i);
	int n = b->count;
	if (n == 255)
		return lz_error(LZ_EDOM, "particle %u would have more than 255 neighbours: the shell "
		                "%g is too wide for this density", i, l->shell);
	if (n < (int)l->cap) {
		b->nb[n] = j;
	} else if (n == (int)l->cap) {  /* the last slot becomes the chunk chain */
		uint32_t h = chunk_new(l);
		if (h == NONE)
			return lz_error(LZ_ENOMEM, "no memory for the long neighbour lists");
		l->chunk[h].nb[0] = b->nb[n - 1];
		l->chunk[h].nb[1] = j;
		b->nb[n - 1] = h;
	} else {
		int k = n - ((int)l->cap - 1);  /* its place in the chain */
		uint32_t h = b->nb[l->cap - 1];
		for (; k >= LZ_EDMD_CHUNK; k -= LZ_EDMD_CHUNK) {
			if (l->chunk[h].next == NONE && k == LZ_EDMD_CHUNK) {
				uint32_t g = chunk_new(l);
				if (g == NONE)
					return lz_error(LZ_ENOMEM, "no memory for the long neighbour lists");
				l->chunk[h].next = g;
			}
			h = l->chunk[h].next;
		}
		l->chunk[h].nb[k] = j;
	}
	b->count++;
	return LZ_OK;
}

/* j taken off i's list: the last neighbour takes its place. */
static void drop(lz_edmd_lists *l, uint32_t i, uint32_t j)
{
	lz_edmd_nbl *b = blk(l, i);
	int n = b->count, k = 0;
	while (k < n && *slot(l, i, k) != j)
		k++;
	if (k == n)
		return;
	*slot(l, i, k) = *slot(l, i, n - 1);
	if (n - 1 == (int)l->cap) {  /* the chain's one left goes back into the block */
		uint32_t h = b->nb[l->cap - 1];
		b->nb[l->cap - 1] = l->chunk[h].nb[0];
		chunk_free(l, h);
	} else if (n - 1 > (int)l->cap && (n - (int)l->cap) % LZ_EDMD_CHUNK == 0) {
		/* the chain's last chunk held only the one moved: it goes */
		uint32_t h = b->nb[l->cap - 1], before = NONE;
		while (l->chunk[h].next != NONE) {
			before = h;
			h = l->chunk[h].next;
		}
		l->chunk[before].next = NONE;
		chunk_free(l, h);
	}
	b->count--;
}

/* i's list emptied (its chunks freed). */
static void forget(lz_edmd_lists *l, uint32_t i)
{
	lz_edmd_nbl *b = blk(l, i);
	if (b->count > l->cap)
		for (uint32_t h = b->nb[l->cap - 1], g; h != NONE; h = g) {
			g = l->chunk[h].next;
			chunk_free(l, h);
		}
	b->count = 0;
}

/* ---- sizes ---- */

double lz_edmd_list_shell(int dim, double packing)
{
	/* From dense to dilute: the fastest S, narrowed where the fastest would
	 * need more than 160 bytes per particle (lesson 05 §10). */
	static const double dense3[][2] = {{0.57, 1.3}, {0.52, 1.35}, {0.38, 1.4},
	                                   {0.3, 1.5}, {0.15, 1.8}};
	if (dim == 2)
		return packing >= 0.45 ? 1.8 : 2.2;
	for (size_t k = 0; k < sizeof dense3 / sizeof dense3[0]; k++)
		if (packing >= dense3[k][0])
			return dense3[k][1];
	return 2.2;
}

int lz_edmd_list_pays(int dim, size_t n, double packing)
{
	double S = lz_edmd_list_shell(dim, packing), v1 = dim == 3 ? M_PI / 6 : M_PI / 4;
	double L = pow((double)n * v1 / packing, 1.0 / dim);
	/* in 3D from 0.28 while the system fits the caches (n < LZ_EDMD_FAR), where a
	 * list's extra reads cost little and its dozen candidates beat 27 cells' (measured
	 * 1.03-1.13 times as fast from 0.28 to 0.3; from 10^5 particles on, cells win at
	 * 0.3) */
	double from = dim == 2 ? 0.5 : n < LZ_EDMD_FAR ? 0.28 : 0.35;
	int dense = packing >= from;
	return dense && L >= 3 * S && L > 4 * S - 2 ? LZ_EDMD_LIST : LZ_EDMD_CELLS;
}

int lz_edmd_list_cells(int dim, size_t n, double L, double shell)
{
	double most = floor(L / shell);
	double want = ceil(pow(3.0 * (double)n, 1.0 / dim));
	double m = fmin(most, fmax(want, 3));
	return m < 3 ? 0 : (int)m;
}

static int wide_runs(void);

lz_edmd_lists *lz_edmd_list_alloc(const lz_edmd *e, double shell)
{
	lz_edmd_lists *l = calloc(1, sizeof *l);
	if (!l)
		return lz_error(LZ_ENOMEM, "no memory for neighbour lists"), NULL;
	l->shell = shell;
	l->skin = 0.5 * (shell - 1);
	l->unit = e->L / 65536;
	/* room in the block for the mean number of centres within the shell, and two: the
	 * longer lists go on in chunks */
	double rho = (double)e->n / pow(e->L, e->dim);
	double mean = rho * (e->dim == 3 ? 4 * M_PI / 3 * pow(shell, 3) : M_PI * shell * shell);
	l->cap = (uint32_t)fmax(2, fmin(255, ceil(mean) + 2));
	l->stride = sizeof(lz_edmd_nbl) + l->cap * sizeof(uint32_t);
	l->spare = NONE;
	l->block = lz_bigmem_alloc(e->n * l->stride);
	l->wide = wide_runs();
	if (!l->block) {
		lz_edmd_list_free(l);
		return lz_error(LZ_ENOMEM, "no memory for the neighbour lists of %zu particles",
		                e->n), NULL;
	}
	return l;
}

void lz_edmd_list_free(lz_edmd_lists *l)
{
	if (!l)
		return;
	lz_bigmem_free(l->block);
	free(l->chunk);
	free(l);
}

double lz_edmd_list_mean(const lz_edmd *e)
{
	double sum = 0;
	for (uint32_t i = 0; i < e->n; i++)
		sum += blk(e->lists, i)->count;
	return sum / (double)e->n;
}

double lz_edmd_list_bytes(const lz_edmd *e)
{
	const lz_edmd_lists *l = e->lists;
	return (double)l->stride + (double)l->nchunk * sizeof *l->chunk / (double)e->n;
}

/* ---- centres ---- */

/* The flags of a centre c (lz_edmd_nbl.edge). */
static uint8_t edge_of(const lz_edmd *e, const double c[3])
{
	const lz_edmd_lists *l = e->lists;
	uint8_t f = 0;
	for (int a = 0; a < e->dim; a++) {
		if (!e->wall[a])
			f |= c[a] < l->shell || c[a] > e->L - l->shell;
		else if (c[a] < 0.5 + l->skin + 1e-9 || c[a] > e->L - 0.5 - l->skin - 1e-9)
			f |= (uint8_t)(2 << a);
	}
	return f;
}

/* Centre particle i at r (inside the box): the multiple of the unit just below r (the
 * particle starts at most a unit off it: nothing in the invariants needs the centre to
 * be where the particle was, only near), its flags and the cell of that centre. */
static void set_centre(lz_edmd *e, uint32_t i, const double r[3])
{
	lz_edmd_lists *l = e->lists;
	lz_edmd_nbl *b = blk(l, i);
	double c[3];
	for (int a = 0; a < 3; a++) {
		double q = floor(r[a] / l->unit);
		b->c[a] = (uint16_t)(q < 0 ? 0 : q > 65535 ? 65535 : q);
		c[a] = b->c[a] * l->unit;
	}
	b->edge = edge_of(e, c);
	e->p[i].cell = lz_edmd_cell_of(e, c);
}

/* i's position now, wrapped into the box: its new centre, flags and cell. */
static void recentre(lz_edmd *e, uint32_t i)
{
	lz_edmd_particle *p = &e->p[i];
	for (int a = 0; a < e->dim; a++)
		if (!e->wall[a]) {
			p->r[a] -= e->L * floor(p->r[a] / e->L);
			if (p->r[a] >= e->L)  /* -1e-17 + L rounds to L */
				p->r[a] = 0;
		}
	uint32_t old = p->cell;
	set_centre(e, i, p->r);
	if (p->cell != old) {
		uint32_t c = p->cell;
		p->cell = old;
		lz_edmd_cell_remove(e, i);
		lz_edmd_cell_insert(e, i, c);
	}
}

/* Put j on i's list and i on j's. LZ_OK or add's error. */
static int link_pair(lz_edmd *e, uint32_t i, uint32_t j)
{
	int st = add(e->lists, i, j);
	return st ? st : add(e->lists, j, i);
}

/* lz_edmd_nbl.edge of a particle on the list being built again (rebuild): set on
 * every former neighbour before the search, taken off those found again; a block
 * carries it only inside rebuild. */
#define FORMER 0x80

/* Of the candidates cand[0 .. nc-1] (seen from the cells from[]: i's centre there is
 * seen[from]), those other than i (and above i when `after`) whose centres lie within
 * the shell of i's go on i's list, and i on theirs unless they are marked FORMER (it
 * is there already; the mark comes off): the distances in one loop without a branch,
 * then the links. LZ_OK or add's error. */
static int link_near(lz_edmd *e, uint32_t i, int after, uint32_t *cand, const uint8_t *from,
                     int nc, const double (*seen)[3])
{
	const lz_edmd_lists *l = e->lists;
	double S2 = l->shell * l->shell;
	int nh = 0;
	for (int q = 0; q < nc; q++) {
		const uint16_t *cj = blk(l, cand[q])->c;
		const double *sk = seen[from[q]], u = l->unit;
		double d0 = cj[0] * u - sk[0], d1 = cj[1] * u - sk[1], d2 = cj[2] * u - sk[2];
		uint32_t j = cand[q];
		cand[nh] = j;
		nh += (d0 * d0 + d1 * d1 + d2 * d2 < S2) & (j != i) & (!after | (j > i));
	}
	for (int q = 0; q < nh; q++) {
		uint32_t j = cand[q];
		__builtin_prefetch(&e->p[j]);  /* i's prediction reads it next */
		lz_edmd_nbl *bj = blk(l, j);
		int was = bj->edge & FORMER;
		bj->edge &= (uint8_t)~FORMER;
		int st = was ? add(e->lists, i, j) : link_pair(e, i, j);
		if (st != LZ_OK)
			return st;
	}
	return LZ_OK;
}

/* Particle j (-1: none) of the block's cell k as the next candidate: *cand and *from
 * written, its centre asked for (link_near reads it soon); 1 when there was one. */
static inline int take(const lz_edmd_lists *l, int32_t j, int k, uint32_t *cand,
                       uint8_t *from)
{
	*cand = (uint32_t)j;
	*from = (uint8_t)k;
	if (j >= 0)
		__builtin_prefetch(blk(l, (uint32_t)j)->c);
	return j >= 0;
}

/* Every j of the block around i's cell (all of them, or only j > i when `after`)
 * whose centre lies within the shell of i's: linked both ways. The cells' particles
 * are gathered breadth first — every cell's head, then every cell's second (both read
 * with the head, lz_edmd_list), then every cell's third, ... — so that the reads along
 * different cells' lists overlap instead of waiting on each other (link_near then
 * takes their distances). LZ_OK or grow's error. */
static int gather(lz_edmd *e, uint32_t i, int after)
{
	double ci[3];
	centre_of(e->lists, i, ci);
	lz_edmd_block b;
	lz_edmd_block_of(e, e->p[i].cell, &b);
	int32_t at[27], at2[27];  /* each cell's head and second (lz_edmd_list: one read) */
	double seen[27][3];  /* i's centre as seen from each cell of the block */
	/* on each axis, how far i's centre is from each cell of the block's row: a cell
	 * farther than the shell on the three axes together holds no neighbour (about a
	 * quarter of the 27 in 3D), and its particles are not read */
	double gap[3][3] = {{0}};
	uint32_t stride[3] = {1, (uint32_t)e->m[0], (uint32_t)e->m[0] * (uint32_t)e->m[1]};
	for (int a = 0; a < e->dim; a++)
		for (int x = 0; x < b.n[a]; x++) {
			double lo = (double)(b.off[a][x] / stride[a]) * e->w[a] + b.shift[a][x];
			double below = lo - ci[a], above = ci[a] - (lo + e->w[a]);
			gap[a][x] = below > 0 ? below : above > 0 ? above : 0;
		}
	double S2 = e->lists->shell * e->lists->shell;
	int nk = 0;
	for (int z = 0; z < b.n[2]; z++)
		for (int y = 0; y < b.n[1]; y++)
			for (int x = 0; x < b.n[0]; x++) {
				double g2 = gap[0][x] * gap[0][x] + gap[1][y] * gap[1][y] + gap[2][z] * gap[2][z];
				lz_edmd_list head = e->list[b.off[0][x] + b.off[1][y] + b.off[2][z]];
				at[nk] = head.head;
				at2[nk] = head.second;
				seen[nk][0] = ci[0] - b.shift[0][x];
				seen[nk][1] = ci[1] - b.shift[1][y];
				seen[nk][2] = ci[2] - b.shift[2][z];
				nk += g2 < S2;
			}
	uint32_t cand[LZ_EDMD_GATHER];
	uint8_t from[LZ_EDMD_GATHER];
	int nc = 0, live = 0, st = LZ_OK;
	for (int k = 0; k < nk; k++)  /* every cell's head, then its second: no walk yet */
		nc += take(e->lists, at[k], k, cand + nc, from + nc);
	for (int k = 0; k < nk; k++) {
		nc += take(e->lists, at2[k], k, cand + nc, from + nc);
		at[k] = e->next[at2[k]];  /* next[-1] = -1 */
		live += at[k] >= 0;
	}
	while (live > 0 && st == LZ_OK) {
		if (nc + nk > LZ_EDMD_GATHER) {  /* crowded cells: link what we have */
			st = link_near(e, i, after, cand, from, nc, seen);
			nc = 0;
		}
		live = 0;
		for (int k = 0; k < nk; k++) {
			int32_t j = at[k];
			nc += take(e->lists, j, k, cand + nc, from + nc);
			at[k] = e->next[j];  /* next[-1] = -1: a finished list stays finished */
			live += at[k] >= 0;
		}
	}
	return st == LZ_OK ? link_near(e, i, after, cand, from, nc, seen) : st;
}

/* i's list built again around where it is now. Most of its neighbours stay: they
 * keep i on their lists, and only those that left take it off theirs (the others'
 * lists are not touched). Which is which without a search: the former neighbours are
 * marked FORMER, the search takes the mark off those it finds again. LZ_OK or add's
 * error. */
static int rebuild(lz_edmd *e, uint32_t i)
{
	lz_edmd_lists *l = e->lists;
	lz_edmd_advance(e, &e->p[i], e->now);
	uint32_t old[255];
	int n;
	const uint32_t *nb = neighbours(l, i, old, &n);
	if (nb != old)
		memcpy(old, nb, (size_t)n * sizeof *old);
	for (int k = 0; k < n; k++)
		blk(l, old[k])->edge |= FORMER;
	forget(l, i);
	recentre(e, i);
	int st = gather(e, i, 0);
	for (int k = 0; k < n; k++) {
		lz_edmd_nbl *b = blk(l, old[k]);
		if (b->edge & FORMER) {
			b->edge &= (uint8_t)~FORMER;
			if (st == LZ_OK)
				drop(l, old[k], i);
		}
	}
	return st;
}

/* The calendar's days sized from the first events: per_day of them a day, at the
 * rate that the particles' mean time to their first event gives. */
static int first_days(lz_edmd *e)
{
	double sum = 0;
	size_t k = 0;
	for (uint32_t i = 0; i < e->n; i++)
		if (isfinite(e->cal->item[i].key)) {
			sum += e->cal->item[i].key - e->now;
			k++;
		}
	double width = k > 0 && sum > 0 ? e->cal->per_day * (sum / k) / (double)k : e->cal->width;
	return lz_calendar_layout(e->cal, width);
}

int lz_edmd_list_start(lz_edmd *e)
{
	lz_edmd_lists *l = e->lists;
	lz_edmd_cell_clear(e);
	for (size_t i = e->n; i-- > 0;) {
		e->p[i].t0 = 0;
		set_centre(e, (uint32_t)i, e->p[i].r);
		lz_edmd_cell_insert(e, (uint32_t)i, e->p[i].cell);
		blk(l, (uint32_t)i)->count = 0;
	}
	free(l->chunk);
	l->chunk = NULL;
	l->nchunk = l->capchunk = l->chunks = 0;
	l->spare = NONE;
	e->now = 0;
	e->since_rebase = 0;
	if (e->cal)
		lz_calendar_clear(e->cal, 0);
	else
		lz_heap_clear(e->heap);
	for (uint32_t i = 0; i < e->n; i++) {
		int st = gather(e, i, 1);
		if (st != LZ_OK)
			return st;
	}
	for (uint32_t i = 0; i < e->n; i++) {
		int st = lz_edmd_list_predict(e, i);
		if (st != LZ_OK)
			return st;
	}
	return e->cal ? first_days(e) : LZ_OK;
}

/* ---- the prediction ---- */

/* When a particle at offset d from its centre, velocity v, leaves the skin δ: the
 * positive root of |d + v t| = δ (|d| < δ), computed without cancellation; 0 when it
 * is out already (round-off), INFINITY at rest. Under gravity g, the earlier time at
 * which |d| + |v| t + g t²/2 = δ, a bound. */
static inline __attribute__((always_inline)) double
skin_time(const double d[3], const double v[3], double skin, double g)
{
	double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
	double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
	double c = dd - skin * skin;
	if (c >= 0)
		return 0;
	if (g > 0) {
		double room = skin - sqrt(dd), speed = sqrt(vv);
		return 2 * room / (speed + sqrt(vv + 2 * g * room));
	}
	if (vv == 0)
		return INFINITY;
	double b = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
	double root = sqrt(b * b - vv * c);
	return b > 0 ? -c / (b + root) : (root - b) / vv;
}

/* The earliest wall contact of a particle at r, v (axes whose flag is set): *face. */
static double wall_time(const lz_edmd *e, uint8_t flags, const double r[3], const double v[3],
                        int *face)
{
	double best = INFINITY;
	for (int a = 0; a < e->dim; a++) {
		if (!(flags & (2 << a)))
			continue;
		int up;
		double t;
		if (a == 0 && e->g > 0) {
			t = lz_edmd_fall_time(r[0], v[0], e->g, 0.5, e->L - 0.5, &up);
		} else {
			up = v[a] > 0;
			t = v[a] != 0 ? ((up ? e->L - 0.5 : 0.5) - r[a]) / v[a] : INFINITY;
		}
		if (t < best) {
			best = t > 0 ? t : 0;
			*face = 2 * a + up;
		}
	}
	return best;
}

/* Four pairs at a time: a vector of four doubles, and of four comparison results. */
typedef double v4 __attribute__((vector_size(32)));
typedef long long m4 __attribute__((vector_size(32)));

/* The state of four particles, one lane each: position, velocity and own clock. */
typedef struct {
	v4 r[3], v[3], t0;
} four;

_Static_assert(offsetof(lz_edmd_particle, v) == 24 && offsetof(lz_edmd_particle, t0) == 48 &&
                       sizeof(lz_edmd_particle) == 64,
               "four_of reads a record as r0 r1 r2 v0 | v1 v2 t0 (count, cell)");

/* Lanes i, j, k, l of the eight of x and y (x's 0-3, y's 4-7). */
#ifdef __clang__
#define PICK(x, y, i, j, k, l) __builtin_shufflevector(x, y, i, j, k, l)
#else
#define PICK(x, y, i, j, k, l) __builtin_shuffle(x, y, (m4){i, j, k, l})
#endif

/* Rows a, b, c, d of four lanes each as columns (a 4 x 4 transpose), in place. */
static inline __attribute__((always_inline)) void transpose(v4 *a, v4 *b, v4 *c, v4 *d)
{
	v4 t0 = PICK(*a, *b, 0, 4, 2, 6), t1 = PICK(*a, *b, 1, 5, 3, 7);
	v4 t2 = PICK(*c, *d, 0, 4, 2, 6), t3 = PICK(*c, *d, 1, 5, 3, 7);
	*a = PICK(t0, t2, 0, 1, 4, 5);
	*b = PICK(t1, t3, 0, 1, 4, 5);
	*c = PICK(t0, t2, 2, 3, 6, 7);
	*d = PICK(t1, t3, 2, 3, 6, 7);
}

/* Records a, b, c, d: their first (h = 0) or second 32 bytes, as rows. */
static inline __attribute__((always_inline)) void
rows(const lz_edmd_particle *a, const lz_edmd_particle *b, const lz_edmd_particle *c,
     const lz_edmd_particle *d, int h, v4 x[4])
{
	memcpy(&x[0], h ? &a->v[1] : a->r, sizeof x[0]);
	memcpy(&x[1], h ? &b->v[1] : b->r, sizeof x[1]);
	memcpy(&x[2], h ? &c->v[1] : c->r, sizeof x[2]);
	memcpy(&x[3], h ? &d->v[1] : d->r, sizeof x[3]);
}

/* Particles a, b, c, d as lanes: each record read as two halves of 32 bytes (r0 r1 r2
 * v0 | v1 v2 t0, count and cell), turned into columns by two transposes — 8 loads and
 * 16 shuffles instead of 28 loads of one number each and their inserts (with lanes
 * below, the event loop ran 1.03 times as fast at eta = 0.5, N = 10^4; 1.13 at 10^6). */
static inline __attribute__((always_inline)) void
four_of(const lz_edmd_particle *a, const lz_edmd_particle *b, const lz_edmd_particle *c,
        const lz_edmd_particle *d, four *f)
{
	v4 x[4], y[4];
	rows(a, b, c, d, 0, x);
	rows(a, b, c, d, 1, y);
	transpose(&x[0], &x[1], &x[2], &x[3]);
	transpose(&y[0], &y[1], &y[2], &y[3]);
	*f = (four){{x[0], x[1], x[2]}, {x[3], y[0], y[1]}, y[2]};
}

/* Bit k set when lane k of a comparison is true: its sign bits, two lanes at a time
 * (SSE2, in both builds of the prediction; 2 instructions where the lanes one by one
 * took 12). */
static inline __attribute__((always_inline)) unsigned lanes(const m4 *ok)
{
#if defined(__x86_64__) && defined(__GNUC__)
	typedef double v2 __attribute__((vector_size(16)));
	v2 lo, hi;
	memcpy(&lo, ok, sizeof lo);
	memcpy(&hi, (const char *)ok + sizeof lo, sizeof hi);
	return (unsigned)__builtin_ia32_movmskpd(lo) | (unsigned)__builtin_ia32_movmskpd(hi) << 2;
#else
	return (unsigned)(((*ok)[0] & 1) | ((*ok)[1] & 2) | ((*ok)[2] & 4) | ((*ok)[3] & 8));
#endif
}

/* The earliest collision of i (at ri, vi now) with its neighbours, if before best:
 * its time from now (else best) returned, its partner in *ev.
 * Two passes without a branch on the data (whether a pair approaches is a coin toss
 * that a branch would miss half the time): the first keeps the pairs that approach
 * (b < 0), do not miss (disc > 0) and could close their gap c before best even head
 * on (t >= c / 2|b|); the second roots only those. wrap and fall are constants at each
 * call (always inlined): a scene without gravity pays nothing for it. */
static inline __attribute__((always_inline)) double
neighbours_first(const lz_edmd *e, const uint32_t *nb, int n, const double ri[3],
                 const double vi[3], double best, lz_edmd_event *ev, int wrap, int fall)
{
	const double now = e->now, g = e->g, L = e->L, half = 0.5 * e->L;
	/* best may be +INFINITY (a particle at rest alone): 2 b · bound must not be 0 · ∞ */
	const double bound = best < 1e300 ? best : 1e300;
	v4 kb[64], kc[64], kd[64];  /* pair k's b, c and disc: kb[k / 4][k % 4] */
	uint64_t keep[4] = {0, 0, 0, 0};  /* bit k: pair k may collide before the bound */
	const v4 zero = {0, 0, 0, 0}, one = zero + 1, twob = zero + 2 * bound;
	const v4 vnow = zero + now, vx = zero + ri[0], vy = zero + ri[1], vz = zero + ri[2];
	const v4 wx = zero + vi[0], wy = zero + vi[1], wz = zero + vi[2];
	const v4 vL = zero + L, vh = zero + half;
	for (int k = 0; k < n; k += 4) {
		four f;
		four_of(&e->p[nb[k]], &e->p[nb[k + 1 < n ? k + 1 : k]], &e->p[nb[k + 2 < n ? k + 2 : k]],
		        &e->p[nb[k + 3 < n ? k + 3 : k]], &f);
		v4 dt = vnow - f.t0, ux = f.v[0], uy = f.v[1], uz = f.v[2];
		v4 d0 = f.r[0] + ux * dt - vx;
		v4 d1 = f.r[1] + uy * dt - vy;
		v4 d2 = f.r[2] + uz * dt - vz;
		ux -= wx;
		uy -= wy;
		uz -= wz;
		if (fall) {
			v4 g4 = zero + g;
			d0 -= 0.5 * g4 * dt * dt;
			ux -= g4 * dt;
		}
		if (wrap) {
			if (!e->wall[0])
				d0 -= vL * __builtin_convertvector((d0 < -vh) - (d0 > vh), v4);
			if (!e->wall[1])
				d1 -= vL * __builtin_convertvector((d1 < -vh) - (d1 > vh), v4);
			if (!e->wall[2])
				d2 -= vL * __builtin_convertvector((d2 < -vh) - (d2 > vh), v4);
		}
		v4 b = d0 * ux + d1 * uy + d2 * uz;
		v4 c = d0 * d0 + d1 * d1 + d2 * d2 - one;
		v4 disc = b * b - (ux * ux + uy * uy + uz * uz) * c;
		m4 ok = (b < zero) & (disc > zero) & (c + b * twob < zero);
		kb[k / 4] = b;
		kc[k / 4] = c;
		kd[k / 4] = disc;
		uint64_t bits = lanes(&ok);
		int left = n - k < 4 ? n - k : 4;
		keep[k / 64] |= (bits & ((1u << left) - 1)) << (k % 64);
	}
	double first = bound;
	int who = -1;
	for (int w = 0; w < 4; w++)
		for (uint64_t m = keep[w]; m; m &= m - 1) {
			int k = 64 * w + __builtin_ctzll(m);
			double bk = kb[k / 4][k % 4], ck = kc[k / 4][k % 4], dk = kd[k / 4][k % 4];
			double cp = 0.5 * (ck + fabs(ck));  /* touching: t = 0 */
			double t = cp / (-bk + sqrt(dk));
			int earlier = t < first;
			who = earlier ? k : who;
			first = earlier ? t : first;
		}
	if (who < 0)
		return best;
	ev->partner = (int32_t)nb[who];
	ev->pcount = e->p[nb[who]].count;
	return first;
}

/* The prediction, inlined into its two builds below. */
static inline __attribute__((always_inline)) int predict(lz_edmd *e, uint32_t i)
{
	const lz_edmd_lists *l = e->lists;
	double ri[3], vi[3], d[3];
	lz_edmd_state(e, &e->p[i], e->now, ri, vi);
	centre_of(l, i, d);
	for (int a = 0; a < 3; a++)
		d[a] = ri[a] - d[a];
	double best = skin_time(d, vi, l->skin, e->g);
	lz_edmd_event ev = {isinf(best) ? LZ_EDMD_NONE : LZ_EDMD_SHELL, 0};
	uint8_t flags = blk(l, i)->edge;
	if (flags & ~1u) {
		int face = 0;
		double t = wall_time(e, flags, ri, vi, &face);
		if (t < best) {
			best = t;
			ev.partner = LZ_EDMD_FACE(face);
		}
	}
	uint32_t buf[255];
	int n;
	const uint32_t *nb = neighbours(l, i, buf, &n);
	if (e->g > 0)
		best = neighbours_first(e, nb, n, ri, vi, best, &ev, flags & 1, 1);
	else if (flags & 1)
		best = neighbours_first(e, nb, n, ri, vi, best, &ev, 1, 0);
	else
		best = neighbours_first(e, nb, n, ri, vi, best, &ev, 0, 0);
	e->ev[i] = ev;
	if (e->cal)
		return lz_calendar_set(e->cal, i, e->now + best);
	lz_heap *h = e->heap;
	int in = lz_heap_contains(h, i);
	if (h->arity == 4)
		(in ? lz_heap4_update : lz_heap4_push)(h, i, e->now + best);
	else
		(in ? lz_heap_update : lz_heap_push)(h, i, e->now + best);
	return LZ_OK;
}

/* The prediction compiled twice: for any processor, and, with gcc or clang on x86-64,
 * for those with AVX2 (a vector holds four pairs; else two vectors of two). Both do
 * the same IEEE operations in the same order, without fused multiply-adds (ISO C: no
 * contraction), so they give the same bits — which a test checks by running one
 * system with each (lz_edmd_list_wide). */
static int predict_any(lz_edmd *e, uint32_t i)
{
	return predict(e, i);
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2"))) static int predict_wide(lz_edmd *e, uint32_t i)
{
	return predict(e, i);
}

/* 1 when this processor has AVX2. */
static int wide_runs(void)
{
	__builtin_cpu_init();
	return __builtin_cpu_supports("avx2") != 0;
}
#else
#define predict_wide predict_any
static int wide_runs(void)
{
	return 0;
}
#endif

int lz_edmd_list_predict(lz_edmd *e, uint32_t i)
{
	return e->lists->wide ? predict_wide(e, i) : predict_any(e, i);
}

int lz_edmd_list_wide(lz_edmd *e, int wide)
{
	e->lists->wide = wide && wide_runs();
	return e->lists->wide;
}

/* ---- the event ---- */

/* Ask the memory for i's block, both its ends: a block whose stride is not a multiple
 * of 64 bytes mostly spans two cache lines (13 neighbours: 60 bytes). A hint. */
static inline void fetch_block(const lz_edmd_lists *l, uint32_t i)
{
	const char *b = (const char *)blk(l, i);
	__builtin_prefetch(b);
	__builtin_prefetch(b + l->stride - 1);
}

/* Ask the memory for the records of i's neighbours (those in its block). A hint. */
static void fetch_neighbours(const lz_edmd *e, uint32_t i)
{
	const lz_edmd_lists *l = e->lists;
	const lz_edmd_nbl *b = blk(l, i);
	for (int k = 0, n = b->count < l->cap ? b->count : (int)l->cap - 1; k < n; k++)
		__builtin_prefetch(&e->p[b->nb[k]]);
}

int lz_edmd_list_step(lz_edmd *e)
{
	uint32_t i = lz_edmd_first(e);
	double t = lz_edmd_first_t(e);
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
			return lz_edmd_list_predict(e, i);
		}
		if (e->prefetch)  /* j is predicted after i: its neighbours come meanwhile */
			fetch_neighbours(e, (uint32_t)ev.partner);
		lz_edmd_advance(e, pi, t);
		lz_edmd_advance(e, pj, t);
		double dr[3], half = 0.5 * e->L;
		for (int a = 0; a < 3; a++) {  /* the nearest image of a touching pair */
			dr[a] = pj->r[a] - pi->r[a];
			if (!e->wall[a])
				dr[a] -= e->L * ((dr[a] > half) - (dr[a] < -half));
		}
		e->virial += lz_edmd_bounce(pi, pj, dr, e->restitution);
		pi->count++;
		pj->count++;
		e->collisions++;
		int st = lz_edmd_list_predict(e, i);
		return st ? st : lz_edmd_list_predict(e, (uint32_t)ev.partner);
	}
	if (ev.partner == LZ_EDMD_SHELL) {
		int st = rebuild(e, i);
		if (st != LZ_OK)
			return st;
		e->rebuilds++;
	} else {  /* a wall */
		int f = -1 - ev.partner, a = f / 2;
		lz_edmd_advance(e, pi, t);
		pi->r[a] = f % 2 ? e->L - 0.5 : 0.5;
		pi->v[a] = -pi->v[a];
		pi->count++;
		e->bounces++;
	}
	return lz_edmd_list_predict(e, i);
}

void lz_edmd_list_fetch_ahead(const lz_edmd *e)
{
	const lz_heap *h = e->heap;
	const lz_edmd_lists *l = e->lists;
	uint32_t c1, c2;
	if (e->cal) {
		if (e->cal->nnear == 0)
			return;
		lz_calendar_next_items(e->cal, &c1, &c2);
	} else if (h->n < 21) {
		return;
	} else if (h->arity == 4) {
		lz_heap4_next_items(h, &c1, &c2);
	} else {
		lz_heap_next_items(h, &c1, &c2);
	}
	fetch_neighbours(e, c1);  /* its block was asked for an event ago */
	int32_t j1 = e->ev[c1].partner;
	if (j1 >= 0) {
		__builtin_prefetch(&e->p[j1]);
		fetch_block(l, (uint32_t)j1);
		if (h)
			lz_heap_prefetch_pos(h, (uint32_t)j1);
		else
			lz_calendar_prefetch(e->cal, (uint32_t)j1);
	}
	if (e->cal) {  /* this event's partner: its item came an event ago */
		int32_t j0 = e->ev[lz_edmd_first(e)].partner;
		if (j0 >= 0)
			lz_calendar_prefetch_links(e->cal, (uint32_t)j0);
	}
	/* the event after: its record, event and block */
	__builtin_prefetch(&e->p[c2]);
	__builtin_prefetch(&e->ev[c2]);
	fetch_block(l, c2);
}

/* ---- checks ---- */

/* 1 when j is on i's list. */
static int listed(const lz_edmd_lists *l, uint32_t i, uint32_t j)
{
	uint32_t buf[255];
	int n;
	const uint32_t *nb = neighbours(l, i, buf, &n);
	for (int k = 0; k < n; k++)
		if (nb[k] == j)
			return 1;
	return 0;
}

/* The nearest-image distance of two centres. */
static double centre_distance(const lz_edmd *e, const double *a, const double *b)
{
	double d2 = 0;
	for (int x = 0; x < e->dim; x++) {
		double d = b[x] - a[x];
		if (!e->wall[x])
			d -= e->L * rint(d / e->L);
		d2 += d * d;
	}
	return sqrt(d2);
}

static int audit_one(const lz_edmd *e, uint32_t i)
{
	const lz_edmd_lists *l = e->lists;
	double r[3], v[3], ci[3], cj[3], d2 = 0;
	lz_edmd_state(e, &e->p[i], e->now, r, v);
	centre_of(l, i, ci);
	for (int a = 0; a < 3; a++)
		d2 += (r[a] - ci[a]) * (r[a] - ci[a]);
	if (sqrt(d2) > l->skin + 1e-9)
		return lz_error(LZ_EDOM, "particle %u is %.12g from its centre, beyond the skin %g: "
		                "its list may miss a partner", i, sqrt(d2), l->skin);
	if (e->p[i].cell != lz_edmd_cell_of(e, ci))
		return lz_error(LZ_EDOM, "particle %u is filed in cell %u, its centre lies in cell %u",
		                i, e->p[i].cell, lz_edmd_cell_of(e, ci));
	if (blk(l, i)->edge != edge_of(e, ci))
		return lz_error(LZ_EDOM, "particle %u: its edge flags are %u, its centre says %u", i,
		                blk(l, i)->edge, edge_of(e, ci));
	uint32_t buf[255];
	int n;
	const uint32_t *nb = neighbours(l, i, buf, &n);
	for (int k = 0; k < n; k++) {
		uint32_t j = nb[k];
		if (j >= e->n || j == i || !listed(l, j, i))
			return lz_error(LZ_EDOM, "particle %u lists %u, which does not list it back (or "
			                "is not a particle)", i, j);
		centre_of(l, j, cj);
		if (centre_distance(e, ci, cj) >= l->shell)
			return lz_error(LZ_EDOM, "particles %u and %u are listed with their centres "
			                "%.12g apart, beyond the shell %g", i, j, centre_distance(e, ci, cj),
			                l->shell);
	}
	return LZ_OK;
}

/* Every pair of centres closer than the shell is listed: a brute-force search over
 * the cell blocks. */
static int audit_complete(const lz_edmd *e, uint32_t i)
{
	const lz_edmd_lists *l = e->lists;
	double ci[3], cj[3];
	centre_of(l, i, ci);
	lz_edmd_block b;
	lz_edmd_block_of(e, e->p[i].cell, &b);
	for (int z = 0; z < b.n[2]; z++)
		for (int y = 0; y < b.n[1]; y++)
			for (int x = 0; x < b.n[0]; x++) {
				uint32_t c = b.off[0][x] + b.off[1][y] + b.off[2][z];
				for (int32_t j = e->list[c].head; j >= 0; j = e->next[j]) {
					centre_of(l, (uint32_t)j, cj);
					double d = centre_distance(e, ci, cj);
					if ((uint32_t)j != i && d < l->shell && !listed(l, i, (uint32_t)j))
						return lz_error(LZ_EDOM, "particles %u and %d have centres %.12g "
						                "apart, within the shell %g, but are not listed", i,
						                j, d, l->shell);
				}
			}
	return LZ_OK;
}

int lz_edmd_list_audit(const lz_edmd *e)
{
	for (uint32_t i = 0; i < e->n; i++) {
		int st = audit_one(e, i);
		if (st == LZ_OK)
			st = audit_complete(e, i);
		if (st)
			return st;
	}
	return LZ_OK;
}

int lz_edmd_list_renumber(lz_edmd *e, const uint32_t *to)
{
	lz_edmd_lists *l = e->lists;
	unsigned char *block = lz_bigmem_alloc(e->n * l->stride);
	if (!block)
		return lz_error(LZ_ENOMEM, "no memory to renumber the lists of %zu particles", e->n);
	for (size_t i = 0; i < e->n; i++)
		memcpy(block + to[i] * l->stride, blk(l, (uint32_t)i), l->stride);
	lz_bigmem_free(l->block);
	l->block = block;
	for (uint32_t i = 0; i < e->n; i++)  /* every neighbour number, in block and chain */
		for (int k = 0, n = blk(l, i)->count; k < n; k++) {
			uint32_t *s = slot(l, i, k);
			*s = to[*s];
		}
	return LZ_OK;
}
