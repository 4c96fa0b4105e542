/* pedmd_lib.c — the library half of lz/pedmd.h: the curve and its cuts, a rank's set-up,
 * its predictions and announcements, the queue of waiting messages, and the window
 * protocol of lz_pedmd_work (run, cut, decide). The rank's step, the application of a
 * message, state saving and the decisions are graded (solutions/06-parallel/pedmd.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/bigmem.h"
#include "lz/bits.h"
#include "lz/error.h"
#include "lz/pedmd.h"

/* Room for entries 0 .. n of `size` bytes in *v (capacity *cap), doubling. */
int lz_pedmd_grow(void **v, size_t *cap, size_t n, size_t size)
{
	if (n < *cap)
		return LZ_OK;
	size_t c = *cap ? 2 * *cap : 256;
	while (c <= n)
		c *= 2;
	void *w = realloc(*v, c * size);
	if (!w)
		return lz_error(LZ_ENOMEM, "no memory for %zu entries of %zu bytes", c, size);
	*v = w;
	*cap = c;
	return LZ_OK;
}

/* ---- the curve ---- */

static int by_code(const void *a, const void *b)
{
	const uint64_t *x = a, *y = b;
	return (x[0] > y[0]) - (x[0] < y[0]);
}

lz_pedmd_domains *lz_pedmd_domains_alloc(const lz_edmd *e, int P, int kind)
{
	if (kind != LZ_PEDMD_ROWS && kind != LZ_PEDMD_MORTON)
		return lz_error(LZ_EINVAL, "decomposition %d: rows (%d) or morton (%d)", kind,
		                LZ_PEDMD_ROWS, LZ_PEDMD_MORTON), NULL;
	if (P < 1 || P > LZ_PEDMD_RANKS_MAX || (size_t)P > e->ncells)
		return lz_error(LZ_EINVAL, "ranks = %d: 1 <= ranks <= %d and at most the %zu cells",
		                P, LZ_PEDMD_RANKS_MAX, e->ncells), NULL;
	lz_pedmd_domains *d = calloc(1, sizeof *d);
	uint64_t *code = malloc(2 * e->ncells * sizeof *code);
	if (d) {
		d->curve = malloc(e->ncells * sizeof *d->curve);
		d->place = malloc(e->ncells * sizeof *d->place);
	}
	if (!d || !code || !d->curve || !d->place) {
		free(code);
		lz_pedmd_domains_free(d);
		return lz_error(LZ_ENOMEM, "no memory for the curve of %zu cells", e->ncells), NULL;
	}
	d->P = P;
	d->kind = kind;
	d->ncells = e->ncells;
	uint32_t mx = (uint32_t)e->m[0], my = (uint32_t)e->m[1];
	for (uint32_t c = 0; c < e->ncells; c++) {
		uint32_t x = c % mx, y = c / mx % my, z = c / (mx * my);
		/* rows: the cell number itself (x fastest), so the cuts make slabs */
		code[2 * c] = kind == LZ_PEDMD_ROWS ? c
		              : e->dim == 3 ? lz_morton3_encode(x, y, z) : lz_morton2_encode(x, y);
		code[2 * c + 1] = c;
	}
	qsort(code, e->ncells, 2 * sizeof *code, by_code);
	for (size_t k = 0; k < e->ncells; k++) {
		d->curve[k] = (uint32_t)code[2 * k + 1];
		d->place[d->curve[k]] = (uint32_t)k;
	}
	free(code);
	for (int r = 0; r <= P; r++)
		d->cut[r] = (uint32_t)((double)e->ncells * r / P);
	return d;
}

void lz_pedmd_domains_free(lz_pedmd_domains *d)
{
	if (!d)
		return;
	free(d->curve);
	free(d->place);
	free(d);
}

double lz_pedmd_busiest(const lz_pedmd_domains *d, const double *load, const uint32_t *cut)
{
	double most = 0;
	for (int r = 0; r < d->P; r++) {
		double sum = 0;
		for (uint32_t k = cut[r]; k < cut[r + 1]; k++)
			sum += load[d->curve[k]];
		most = sum > most ? sum : most;
	}
	return most;
}

/* ---- a rank: set-up ---- */

static int check_params(const lz_pedmd_params *p)
{
	if (!(p->window > 0) || !isfinite(p->window))
		return lz_error(LZ_EINVAL, "window = %g: a window is a positive, finite time",
		                p->window);
	if (!(p->rebase > 0) || !isfinite(p->rebase))
		return lz_error(LZ_EINVAL, "rebase = %g: a positive, finite time", p->rebase);
	if (p->balance < 0)
		return lz_error(LZ_EINVAL, "balance = %d windows: 0 (never) or more", p->balance);
	if (!(p->threshold >= 0 && p->threshold < 1))
		return lz_error(LZ_EINVAL, "threshold = %g: in [0, 1)", p->threshold);
	if (p->recheck != 0 && p->recheck != 1)
		return lz_error(LZ_EINVAL, "recheck = %d: 0 or 1", p->recheck);
	if (p->work < 1)
		return lz_error(LZ_EINVAL, "work = %d events a turn: at least 1", p->work);
	if (p->compact != 0 && p->compact != 1)
		return lz_error(LZ_EINVAL, "compact = %d: 0 (a slot for every particle) or 1 (local "
		                "numbering)", p->compact);
	if (!(p->grow > 1 && p->grow <= 2))
		return lz_error(LZ_EINVAL, "grow = %g: the window's growth after a commit, in (1, 2]",
		                p->grow);
	return LZ_OK;
}

/* A system of n particles (records to come) in s's box, its clock at s's. */
static lz_edmd *copy_system(const lz_edmd *s, size_t n)
{
	lz_edmd_params q = {s->dim, n, 0, s->restitution, s->g,
	                    s->wall[0] ? (s->wall[1] ? LZ_EDMD_WALLS_BOX : LZ_EDMD_WALLS_X)
	                               : LZ_EDMD_WALLS_NONE, s->m[0], LZ_EDMD_CELLS, 0, 0};
	double v1 = s->dim == 3 ? M_PI / 6 : M_PI / 4;
	q.packing = (double)n * v1 / pow(s->L, s->dim);
	lz_edmd *e = lz_edmd_alloc(&q);
	if (!e)
		return NULL;
	if (e->ncells != s->ncells) {
		lz_edmd_free(e);
		return lz_error(LZ_EDOM, "the copy of the system has %zu cells, the original %zu",
		                e->ncells, s->ncells), NULL;
	}
	e->L = s->L;  /* the packing's round trip may round L: take the original's bits */
	for (int a = 0; a < 3; a++)
		e->w[a] = s->w[a];
	e->now = s->now;
	e->t_base = s->t_base;
	e->rebase_auto = 0;
	lz_edmd_reset_counts(e);
	return e;
}

/* Empty the lists of the cells r holds (owned and HALO; compact: only those, so that
 * the others' pages never take memory — no prediction reads a FAR cell). O(cells). */
static void clear_cells(lz_pedmd *r)
{
	lz_edmd *e = r->e;
	for (size_t c = 0; c < e->ncells; c++)
		if (!r->gid || r->cls[c] != LZ_PEDMD_FAR)
			e->list[c] = (lz_edmd_list){-1, -1};
}

/* Put the present particles into their cells in s's list order (s numbers them, r
 * holds them in slots). s may be r's own system (lz_pedmd_adopt): every list is read
 * before any is written. LZ_OK or LZ_ENOMEM. O(N + cells), 4 bytes a particle for the
 * while. */
static int fill_cells(lz_pedmd *r, const lz_edmd *s)
{
	uint32_t *seq = malloc(s->n * sizeof *seq), k = 0;  /* the lists one after another */
	if (!seq)
		return lz_error(LZ_ENOMEM, "no memory to file %zu particles", s->n);
	for (uint32_t c = 0; c < s->ncells; c++)
		for (int32_t j = s->list[c].head; j >= 0; j = s->next[j])
			seq[k++] = (uint32_t)j;
	lz_edmd *e = r->e;
	clear_cells(r);
	while (k-- > 0) {  /* each inserted at its list's head: backwards keeps the order */
		int64_t i = lz_pedmd_slot(r, seq[k]);
		if (i >= 0 && r->role[i] != LZ_PEDMD_ABSENT)
			lz_edmd_cell_insert(e, (uint32_t)i, e->p[i].cell);
	}
	free(seq);
	return LZ_OK;
}

/* Whether cell c's block holds a HALO or BORDER cell (r->near). */
static inline int is_near(const lz_pedmd *r, uint32_t c)
{
	return (int)(r->near[c >> 6] >> (c & 63) & 1);
}

static void mark_near(lz_pedmd *r)
{
	const lz_edmd *e = r->e;
	lz_edmd_block b;
	memset(r->near, 0, (e->ncells + 63) / 64 * sizeof *r->near);
	for (uint32_t c = 0; c < e->ncells; c++) {
		lz_edmd_block_of(e, c, &b);
		int near = 0;
		for (int z = 0; z < b.n[2]; z++)
			for (int y = 0; y < b.n[1]; y++)
				for (int x = 0; x < b.n[0]; x++) {
					uint8_t k = r->cls[b.off[0][x] + b.off[1][y] + b.off[2][z]];
					near |= k == LZ_PEDMD_HALO || k == LZ_PEDMD_BORDER;
				}
		r->near[c >> 6] |= (uint64_t)near << (c & 63);
	}
}

/* Every cell's class for r under the cuts in r->d, the near bits, no read stamps
 * (compact: only where r holds the cell; the stamps of FAR cells are never read). */
static void classify_cells(lz_pedmd *r)
{
	lz_pedmd_classify(r->e, r->d, r->rank, r->cls);
	mark_near(r);
	for (size_t c = 0; c < r->e->ncells; c++)
		if (!r->gid || r->cls[c] != LZ_PEDMD_FAR)
			r->read[c] = -INFINITY;
}

/* Particle i with its event ev at t, in a cell of class k: OWNED, GHOST or ABSENT,
 * as if never handed over and never heard of. */
static void take_particle(lz_pedmd *r, uint32_t i, uint8_t k, double t, lz_edmd_event ev)
{
	lz_pedmd_event x = {t, ev};
	r->role[i] = k == LZ_PEDMD_HALO ? LZ_PEDMD_GHOST
	             : k == LZ_PEDMD_FAR ? LZ_PEDMD_ABSENT : LZ_PEDMD_OWNED;
	r->own[i] = r->role[i] == LZ_PEDMD_OWNED ? x : (lz_pedmd_event){-INFINITY, {LZ_EDMD_NONE, 0}};
	r->ghost[i] = r->role[i] == LZ_PEDMD_ABSENT ? (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}} : x;
	r->heard[i] = -INFINITY;
}

/* The owned particles into the emptied heap by their own events, the clock at the
 * system's, and the keys of the border's particles from the ghosts aimed at them —
 * in the order of the particles' numbers, whatever their slots. LZ_OK or LZ_ENOMEM. */
static int fill_heap(lz_pedmd *r)
{
	lz_edmd *e = r->e;
	uint32_t *order = lz_pedmd_by_number(r);
	if (!order)
		return LZ_ENOMEM;
	lz_heap_clear(e->heap);
	for (size_t k = 0; k < r->nslots; k++)
		if (r->role[order[k]] == LZ_PEDMD_OWNED)
			lz_heap_push(e->heap, order[k], r->own[order[k]].t);
	r->clock = e->now;
	for (size_t k = 0; k < r->nslots; k++) {
		uint32_t i = order[k];
		if (r->role[i] == LZ_PEDMD_OWNED && r->cls[e->p[i].cell] == LZ_PEDMD_BORDER)
			lz_pedmd_retarget(r, i);
	}
	free(order);
	return LZ_OK;
}

/* The slots a compact rank needs for its share of s — the particles in its cells and
 * halo and the partners of their events — and an eighth more for those it will meet:
 * room made at once, not by doubling (which would leave the freed halves behind). */
static size_t held(const lz_pedmd *r, const lz_edmd *s)
{
	size_t n = 0;
	for (uint32_t id = 0; id < s->n; id++) {
		int32_t j = s->ev[id].partner;
		n += r->cls[s->p[id].cell] != LZ_PEDMD_FAR ||
		     (j >= 0 && r->cls[s->p[j].cell] != LZ_PEDMD_FAR);
	}
	return n + n / 8 + 64;
}

/* The rank's share of system s under its domains r->d: records (compact: of the
 * particles in its cells and halo only), classes, roles, own and ghost events from
 * s's heap keys and events, cells in s's list order, the heap, the read stamps
 * cleared, the clock at s's. r->e may be s itself (lz_pedmd_adopt, not compact): s's
 * keys are read before its heap is emptied, its lists before they are rebuilt. */
static int take_system(lz_pedmd *r, const lz_edmd *s)
{
	classify_cells(r);
	int st = r->gid ? lz_pedmd_reserve(r, held(r, s)) : LZ_OK;
	for (uint32_t id = 0; id < s->n && st == LZ_OK; id++) {
		uint8_t k = r->cls[s->p[id].cell];
		if (k == LZ_PEDMD_FAR && r->gid)
			continue;
		lz_pedmd_message m;
		uint32_t from = id;
		lz_pedmd_start_part(s, &from, &m, 1);
		if ((st = lz_pedmd_incoming(r, &m)) == LZ_OK) {  /* slots for it and its partner */
			r->e->p[m.id] = m.p;
			r->e->ev[m.id] = m.event.ev;
			take_particle(r, m.id, k, m.event.t, m.event.ev);
		}
	}
	if (st != LZ_OK || fill_cells(r, s) != LZ_OK)
		return LZ_ENOMEM;
	for (uint32_t i = 0; i < r->e->n; i++)  /* after s's lists are read: s may be r's own */
		if (r->role[i] == LZ_PEDMD_ABSENT)
			r->e->p[i].count = LZ_PEDMD_UNKNOWN;  /* what a rank need not hold (lz/pedmd.h) */
	return fill_heap(r);
}

/* size bytes of zeros in huge pages where there are any (lz_bigmem_alloc); NULL when
 * out of memory. */
static void *zeroed(size_t size)
{
	void *v = lz_bigmem_alloc(size);
	return v ? memset(v, 0, size) : NULL;
}

/* A rank whose own system is e (copy_system of s, or s itself), its share of s
 * taken, in slots of its own when `compact` — or, when s has no particles' arrays (a
 * shape: lz_pedmd_open), nothing taken yet; e is freed on failure. */
static lz_pedmd *rank_of(lz_edmd *e, const lz_edmd *s, const lz_pedmd_domains *d,
                         lz_msg *msg, const lz_pedmd_params *p, int compact)
{
	lz_pedmd *r = e ? calloc(1, sizeof *r) : NULL;
	if (!r) {
		lz_edmd_free(e);
		return lz_error(LZ_ENOMEM, "no memory for a rank"), NULL;
	}
	r->e = e;
	r->d = d;
	r->msg = msg;
	r->p = *p;
	r->p.compact = compact;
	r->rank = lz_msg_rank(msg);
	r->N = s->n;
	r->nslots = e->n;
	size_t n = e->n, nc = s->ncells;
	/* Arrays read at random in every event: huge pages where the kernel has them (at
	 * 10^6 particles each would otherwise miss the address translation as well as the
	 * cache; lz/bigmem.h). */
	r->cls = lz_bigmem_alloc(nc);
	r->near = malloc((nc + 63) / 64 * sizeof *r->near);
	r->read = lz_bigmem_sparse(nc * sizeof *r->read);
	r->load = lz_bigmem_sparse(nc * sizeof *r->load);
	r->role = zeroed(n);
	r->own = lz_bigmem_alloc(n * sizeof *r->own);
	r->ghost = lz_bigmem_alloc(n * sizeof *r->ghost);
	r->heard = lz_bigmem_alloc(n * sizeof *r->heard);
	r->mark = zeroed(n * sizeof *r->mark);
	r->rmark = lz_bigmem_sparse(nc * sizeof *r->rmark);
	if (!r->cls || !r->near || !r->read || !r->load || !r->role || !r->own || !r->ghost ||
	    !r->heard || !r->mark || !r->rmark) {
		lz_pedmd_free(r);
		return lz_error(LZ_ENOMEM, "no memory for a rank of %zu particles", n), NULL;
	}
	if (compact && lz_pedmd_slots_init(r) != LZ_OK) {
		lz_pedmd_free(r);
		return NULL;
	}
	if (!s->p) {  /* a shape: the cells empty, the particles to come (lz_pedmd_take) */
		classify_cells(r);
		clear_cells(r);
		r->clock = e->now;
	} else if (take_system(r, s) != LZ_OK) {
		lz_pedmd_free(r);
		return NULL;
	}
	r->T = r->e->t_base + r->e->now;
	r->width = p->window;
	r->forced_end = NAN;
	r->t_error = INFINITY;
	return r;
}

/* The checks common to lz_pedmd_alloc and lz_pedmd_adopt: LZ_OK or LZ_EINVAL. */
static int check_rank(const lz_edmd *s, const lz_pedmd_domains *d, lz_msg *msg,
                      const lz_pedmd_params *p)
{
	if (check_params(p))
		return LZ_EINVAL;
	if (d->ncells != s->ncells || d->P != lz_msg_size(msg))
		return lz_error(LZ_EINVAL, "the decomposition has %zu cells for %d ranks, the system "
		                "%zu cells and the messages %d ranks", d->ncells, d->P, s->ncells,
		                lz_msg_size(msg));
	return LZ_OK;
}

lz_pedmd *lz_pedmd_alloc(const lz_edmd *s, const lz_pedmd_domains *d, lz_msg *msg,
                         const lz_pedmd_params *p)
{
	if (check_rank(s, d, msg, p))
		return NULL;
	return rank_of(copy_system(s, p->compact ? 1 : s->n), s, d, msg, p, p->compact);
}

lz_pedmd *lz_pedmd_adopt(lz_edmd *s, const lz_pedmd_domains *d, lz_msg *msg,
                         const lz_pedmd_params *p)
{
	int st = check_rank(s, d, msg, p);
	if (st == LZ_OK && (s->lists || s->cal || s->heap->arity != 2 || s->rebase_auto ||
	                    s->sort_every))
		st = lz_error(LZ_EINVAL, "a rank adopts a system with cells and the binary heap, "
		              "re-based only when asked and never renumbered (lz/pedmd.h)");
	if (st != LZ_OK) {
		lz_edmd_free(s);
		return NULL;
	}
	lz_edmd_reset_counts(s);
	if (!p->compact || d->P == 1)  /* one rank holds every particle: no copy */
		return rank_of(s, s, d, msg, p, 0);
	lz_pedmd *r = rank_of(copy_system(s, 1), s, d, msg, p, 1);
	lz_edmd_free(s);  /* the rank holds its share: the whole is not kept */
	return r;
}

lz_pedmd *lz_pedmd_open(const lz_edmd *shape, const lz_pedmd_domains *d, lz_msg *msg,
                        const lz_pedmd_params *p)
{
	if (check_rank(shape, d, msg, p))
		return NULL;
	if (!p->compact)
		return lz_error(LZ_EINVAL, "a rank opened empty holds its particles in local "
		                "numbering: compact = 1"), NULL;
	lz_edmd bare = *shape;  /* its box, cells and clock; none of its arrays */
	bare.list = NULL;
	bare.next = NULL;
	bare.p = NULL;
	bare.ev = NULL;
	bare.heap = NULL;
	bare.cal = NULL;
	bare.lists = NULL;
	return rank_of(copy_system(&bare, 1), &bare, d, msg, p, 1);
}

lz_edmd *lz_pedmd_release(lz_pedmd *r)
{
	lz_edmd *e = r->e;
	if (r->gid) {  /* a frame of all N, the owned records at their numbers */
		if (!(e = copy_system(r->e, r->N))) {
			lz_pedmd_free(r);
			return NULL;
		}
		memset(e->p, 0, e->n * sizeof *e->p);
		for (uint32_t i = 0; i < r->nslots; i++)
			if (r->role[i] == LZ_PEDMD_OWNED)
				e->p[r->gid[i]] = r->e->p[i];
		e->now = r->e->now;
		e->t_base = r->e->t_base;
	} else {
		r->e = NULL;
	}
	lz_pedmd_free(r);
	return e;
}

/* ---- moving the cuts ---- */

int lz_pedmd_balance_due(const lz_pedmd *r, double t_stop)
{
	return r->p.balance > 0 && r->phase == LZ_PEDMD_BEGIN && r->T < t_stop &&
	       isnan(r->forced_end) && !r->rerun && r->counts.windows >= r->next_balance;
}

int lz_pedmd_load_since(lz_pedmd *r, double *delta)
{
	size_t nc = r->e->ncells;
	if (!r->load0 && !(r->load0 = lz_bigmem_sparse(nc * sizeof *r->load0)))
		return lz_error(LZ_ENOMEM, "no memory for the load of %zu cells", nc);
	for (size_t c = 0; c < nc; c++) {
		delta[c] = r->load[c] - r->load0[c];
		if (delta[c] != 0)  /* written where it changed: the rank's own cells */
			r->load0[c] = r->load[c];
	}
	r->next_balance = r->counts.windows + (uint64_t)r->p.balance;
	return LZ_OK;
}

size_t lz_pedmd_owned_part(const lz_pedmd *r, uint32_t *from, lz_pedmd_message *out,
                           size_t most)
{
	const lz_edmd *e = r->e;
	size_t k = 0;
	uint32_t i = *from;
	for (; i < e->n && k < most; i++)
		if (r->role[i] == LZ_PEDMD_OWNED) {
			if (out)
				out[k] = lz_pedmd_outgoing(r, i, LZ_PEDMD_MIGRATE, e->now);
			k++;
		}
	*from = i;
	return k;
}

size_t lz_pedmd_start_part(const lz_edmd *s, uint32_t *from, lz_pedmd_message *out,
                           size_t most)
{
	size_t k = 0;
	for (; *from < s->n && k < most; k++, ++*from) {
		uint32_t i = *from;
		out[k] = (lz_pedmd_message){s->now, i, LZ_PEDMD_MIGRATE, s->p[i],
		                            {lz_heap_key(s->heap, i), s->ev[i]}};
	}
	return k;
}

size_t lz_pedmd_owned(const lz_pedmd *r, lz_pedmd_message *out)
{
	uint32_t from = 0;
	return lz_pedmd_owned_part(r, &from, out, SIZE_MAX);
}

/* A bit of role[] that marks a particle between lz_pedmd_take_begin and _end: it came
 * in the picture. */
enum { TAKEN = 0x80 };

/* LZ_OK when all[0 .. n-1] names particles of the system, each once; else LZ_EINVAL
 * (or LZ_ENOMEM), and r as it was. O(n), a bit a particle for the while. */
static int check_picture(const lz_pedmd *r, const lz_pedmd_message *all, size_t n)
{
	uint64_t *seen = calloc(r->N / 64 + 1, sizeof *seen);
	if (!seen)
		return lz_error(LZ_ENOMEM, "no memory to check a picture of %zu particles", r->N);
	int st = LZ_OK;
	for (size_t k = 0; k < n && st == LZ_OK; k++) {
		uint32_t i = all[k].id;
		if (i >= r->N || all[k].p.cell >= r->e->ncells || (seen[i / 64] >> (i % 64) & 1))
			st = lz_error(LZ_EINVAL, "rank %d: particle %u is twice in the picture, or not in "
			              "the system (or its cell %u)", r->rank, i, all[k].p.cell);
		else
			seen[i / 64] |= UINT64_C(1) << (i % 64);
	}
	free(seen);
	return st;
}

int lz_pedmd_take_begin(lz_pedmd *r)
{
	if (r->phase != LZ_PEDMD_BEGIN || r->nwait > 0)
		return lz_error(LZ_EINVAL, "rank %d: new cuts only at a cut, between windows with no "
		                "message waiting", r->rank);
	r->nformer = 0;
	for (uint32_t i = 0; i < r->nslots; i++)
		if (r->role[i] == LZ_PEDMD_OWNED) {
			if (lz_pedmd_grow((void **)&r->former, &r->capformer, r->nformer,
			                  sizeof *r->former))
				return LZ_ENOMEM;
			r->former[r->nformer++] = i;
		}
	for (uint32_t i = 0; i < r->e->n; i++)
		r->role[i] = LZ_PEDMD_ABSENT;
	classify_cells(r);
	return LZ_OK;
}

/* The records of former owned particles stay as they were until _end: only their old
 * owner, this rank, sends them, so what comes back in _part is the same. */
size_t lz_pedmd_take_share(const lz_pedmd *r, size_t *from, lz_pedmd_message *out,
                           size_t most)
{
	size_t k = 0;
	for (; *from < r->nformer && k < most; k++, ++*from)
		out[k] = lz_pedmd_outgoing(r, r->former[*from], LZ_PEDMD_MIGRATE, r->e->now);
	return k;
}

int lz_pedmd_take_part(lz_pedmd *r, const lz_pedmd_message *m, size_t n)
{
	for (size_t k = 0; k < n; k++) {
		lz_pedmd_message q = m[k];
		int64_t had = q.id < r->N ? lz_pedmd_slot(r, q.id) : -1;
		if (q.id >= r->N || q.p.cell >= r->e->ncells || (had >= 0 && (r->role[had] & TAKEN)))
			return lz_error(LZ_EINVAL, "rank %d: particle %u came twice in the picture, or is "
			                "not in the system (or its cell %u)", r->rank, q.id, q.p.cell);
		uint8_t cls = r->cls[q.p.cell];
		if (cls == LZ_PEDMD_FAR && r->gid)
			continue;  /* compact: no slot for a particle it does not hold */
		int st = lz_pedmd_incoming(r, &q);
		if (st != LZ_OK)
			return st;
		if (cls != LZ_PEDMD_FAR) {
			r->e->p[q.id] = q.p;
			r->e->ev[q.id] = q.event.ev;
		}
		take_particle(r, q.id, cls, q.event.t, q.event.ev);
		r->role[q.id] |= TAKEN;
	}
	return LZ_OK;
}

int lz_pedmd_take_end(lz_pedmd *r)
{
	lz_edmd *e = r->e;
	for (uint32_t i = 0; i < e->n; i++) {
		if (!(r->role[i] & TAKEN))
			take_particle(r, i, LZ_PEDMD_FAR, -INFINITY, (lz_edmd_event){LZ_EDMD_NONE, 0});
		r->role[i] &= (uint8_t)~TAKEN;
		if (r->role[i] == LZ_PEDMD_ABSENT)
			e->p[i].count = LZ_PEDMD_UNKNOWN;  /* what a rank need not hold (lz/pedmd.h) */
	}
	lz_heap_clear(e->heap);  /* refilled below */
	if (lz_pedmd_compact(r) != LZ_OK)
		return LZ_ENOMEM;
	clear_cells(r);
	uint32_t *order = lz_pedmd_by_number(r);
	if (!order)
		return LZ_ENOMEM;
	for (size_t k = r->nslots; k-- > 0;)  /* at the heads: each list by number */
		if (r->role[order[k]] != LZ_PEDMD_ABSENT)
			lz_edmd_cell_insert(e, order[k], e->p[order[k]].cell);
	free(order);
	r->nformer = 0;
	r->counts.balances += r->counts.windows > 0;  /* before any window: the set-up */
	return fill_heap(r);
}

int lz_pedmd_take(lz_pedmd *r, const lz_pedmd_message *all, size_t n)
{
	if (r->phase != LZ_PEDMD_BEGIN || r->nwait > 0)
		return lz_error(LZ_EINVAL, "rank %d: new cuts only at a cut, between windows with no "
		                "message waiting", r->rank);
	if (n != r->N)
		return lz_error(LZ_EINVAL, "rank %d: the picture holds %zu particles, the system %zu",
		                r->rank, n, r->N);
	int st = check_picture(r, all, n);  /* n of them, none twice: every particle once */
	if (st == LZ_OK)
		st = lz_pedmd_take_begin(r);
	if (st == LZ_OK)
		st = lz_pedmd_take_part(r, all, n);
	return st == LZ_OK ? lz_pedmd_take_end(r) : st;
}

int lz_pedmd_recut(lz_pedmd *const *ranks, int P, lz_pedmd_domains *d, const uint32_t *cut)
{
	for (int k = 0; k < P; k++)
		if (ranks[k]->phase != LZ_PEDMD_BEGIN || ranks[k]->nwait > 0 ||
		    ranks[k]->T != ranks[0]->T)
			return lz_error(LZ_EINVAL, "rank %d: new cuts only at a cut, every rank between "
			                "windows at one time with no message waiting", k);
	size_t N = ranks[0]->N, n = 0;
	lz_pedmd_message *all = malloc(N * sizeof *all);
	if (!all)
		return lz_error(LZ_ENOMEM, "no memory for the picture of %zu particles", N);
	for (int k = 0; k < P; k++)
		if (n + lz_pedmd_owned(ranks[k], NULL) <= N)
			n += lz_pedmd_owned(ranks[k], all + n);
		else
			n = N + 1;
	memcpy(d->cut, cut, (size_t)(P + 1) * sizeof *cut);
	int st = LZ_OK;
	for (int k = 0; k < P && st == LZ_OK; k++)
		st = lz_pedmd_take(ranks[k], all, n);
	free(all);
	return st;
}

void lz_pedmd_free(lz_pedmd *r)
{
	if (!r)
		return;
	size_t nc = r->d->ncells;
	lz_edmd_free(r->e);
	lz_bigmem_free(r->cls);
	free(r->near);
	lz_bigmem_sparse_free(r->read, nc * sizeof *r->read);
	lz_bigmem_sparse_free(r->load, nc * sizeof *r->load);
	lz_bigmem_sparse_free(r->load0, nc * sizeof *r->load0);
	lz_bigmem_free(r->role);
	lz_bigmem_free(r->own);
	lz_bigmem_free(r->ghost);
	lz_bigmem_free(r->heard);
	lz_bigmem_free(r->mark);
	lz_bigmem_sparse_free(r->rmark, nc * sizeof *r->rmark);
	free(r->stamps);
	free(r->wait);
	free(r->wait0);
	free(r->saved);
	free(r->wlog);
	free(r->clog);
	free(r->former);
	lz_bigmem_free(r->gid);
	lz_bigmem_free(r->index);
	free(r);
}

const lz_edmd *lz_pedmd_system(const lz_pedmd *r) { return r->e; }
lz_pedmd_counts lz_pedmd_counters(const lz_pedmd *r) { return r->counts; }
int lz_pedmd_role(const lz_pedmd *r, uint32_t id)
{
	int64_t i = lz_pedmd_slot(r, id);
	return i < 0 ? LZ_PEDMD_ABSENT : r->role[i];
}

const lz_pedmd_record *lz_pedmd_log(const lz_pedmd *r, size_t *n)
{
	*n = r->nclog;
	return r->clog;
}

/* ---- predictions and ghosts' events ---- */

/* Every cell of c's block, with f called on it. */
#define FOR_BLOCK(e, c, b, q)                                                       \
	lz_edmd_block_of((e), (c), &(b));                                           \
	for (int z_ = 0; z_ < (b).n[2]; z_++)                                       \
		for (int y_ = 0; y_ < (b).n[1]; y_++)                               \
			for (int x_ = 0, q = 0; x_ < (b).n[0] &&                    \
			     ((q = (int)((b).off[0][x_] + (b).off[1][y_] + (b).off[2][z_])), 1); \
			     x_++)

/* The earliest valid ghost event aimed at owned particle i, if earlier than t:
 * *from gets the ghost. */
static double ghost_aim(const lz_pedmd *r, uint32_t i, double t, int32_t *from)
{
	const lz_edmd *e = r->e;
	lz_edmd_block b;
	*from = -1;
	FOR_BLOCK(e, e->p[i].cell, b, c) {
		if (r->cls[c] != LZ_PEDMD_HALO)
			continue;
		for (int32_t j = e->list[c].head; j >= 0; j = e->next[j]) {
			const lz_pedmd_event *g = &r->ghost[j];
			if (g->ev.partner == (int32_t)i && g->ev.pcount == e->p[i].count && g->t < t) {
				t = g->t;
				*from = j;
			}
		}
	}
	return t;
}

/* Key owned i by the earlier of own[i] and the ghosts' aims. */
static double set_key(lz_pedmd *r, uint32_t i)
{
	lz_edmd *e = r->e;
	int32_t j;
	double t = r->own[i].t;
	e->ev[i] = r->own[i].ev;
	if (is_near(r, e->p[i].cell)) {
		t = ghost_aim(r, i, t, &j);
		if (j >= 0)
			e->ev[i] = (lz_edmd_event){j, e->p[j].count};
	}
	if (lz_heap_contains(e->heap, i))
		lz_heap_update(e->heap, i, t);
	else
		lz_heap_push(e->heap, i, t);
	return t;
}

int lz_pedmd_predict(lz_pedmd *r, uint32_t i)
{
	lz_edmd *e = r->e;
	int st = lz_pedmd_save(r, i);
	if (st != LZ_OK)
		return st;
	lz_edmd_predict(e, i);
	r->own[i] = (lz_pedmd_event){lz_heap_key(e->heap, i), e->ev[i]};
	uint32_t cell = e->p[i].cell;
	if (!is_near(r, cell))
		return LZ_OK;
	lz_edmd_block b;
	FOR_BLOCK(e, cell, b, c)
		if (r->cls[c] == LZ_PEDMD_HALO || r->cls[c] == LZ_PEDMD_BORDER)
			lz_pedmd_read_at(r, c, e->now);
	double t = set_key(r, i);
	return t < r->clock ? lz_pedmd_late(r, t) : LZ_OK;
}

int lz_pedmd_retarget(lz_pedmd *r, uint32_t i)
{
	int st = lz_pedmd_save(r, i);
	if (st != LZ_OK)
		return st;
	double t = set_key(r, i);
	return t < r->clock ? lz_pedmd_late(r, t) : LZ_OK;
}

int lz_pedmd_late(lz_pedmd *r, double t)
{
	if (t < r->t_error)
		r->t_error = t;
	return LZ_OK;
}

int lz_pedmd_block_at(const lz_pedmd *r, uint32_t cell, double t)
{
	const lz_edmd *e = r->e;
	lz_edmd_block b;
	FOR_BLOCK(e, cell, b, c)
		for (int32_t j = e->list[c].head; j >= 0; j = e->next[j])
			if (e->p[j].t0 > t)
				return 0;
	return 1;
}

/* ---- messages out ---- */

static int send_one(lz_pedmd *r, int to, uint32_t kind, uint32_t i, double t)
{
	lz_pedmd_message m = lz_pedmd_outgoing(r, i, kind, t);
	if (kind == LZ_PEDMD_MIGRATE)
		m.event = (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}};
	r->woke = 1;
	return lz_msg_send(r->msg, to, &m, sizeof m);
}

static int member(const int *set, int n, int x)
{
	for (int k = 0; k < n; k++)
		if (set[k] == x)
			return 1;
	return 0;
}

int lz_pedmd_announce(lz_pedmd *r, uint32_t i, uint32_t from, int to_owner, double t)
{
	int now[27], before[27], nn, nb = 0, st = LZ_OK;
	uint32_t cell = r->e->p[i].cell;
	/* nobody else sees either cell (far from the border: asked of the bitmap first,
	 * which is in cache) */
	if (to_owner < 0 && ((!is_near(r, cell) && !is_near(r, from)) ||
	                     (r->cls[cell] == LZ_PEDMD_INTERIOR && r->cls[from] == LZ_PEDMD_INTERIOR)))
		return LZ_OK;
	nn = lz_pedmd_listeners(r->e, r->d, r->rank, cell, now);
	if (from != cell)
		nb = lz_pedmd_listeners(r->e, r->d, r->rank, from, before);
	if (to_owner >= 0)  /* the new owner tells the new cell's listeners */
		st = send_one(r, to_owner, LZ_PEDMD_MIGRATE, i, t);
	for (int k = 0; k < nn && st == LZ_OK && to_owner < 0; k++)
		st = send_one(r, now[k], LZ_PEDMD_STATE, i, t);
	for (int k = 0; k < nb && st == LZ_OK; k++)
		if (!member(now, nn, before[k]))
			st = send_one(r, before[k], LZ_PEDMD_LEAVE, i, t);
	return st;
}

/* ---- the log ---- */


void lz_pedmd_note(lz_pedmd *r, double t, uint32_t i, uint32_t j, uint32_t kind,
                   double virial)
{
	r->wcommit++;
	r->wvirial += virial;
	if (lz_pedmd_grow((void **)&r->wlog, &r->capwlog, r->nwlog, sizeof *r->wlog)) {
		r->nomem = 1;
		return;
	}
	uint32_t a = lz_pedmd_id(r, i), b = lz_pedmd_id(r, j), first = a < b ? i : j;
	r->wlog[r->nwlog++] = (lz_pedmd_record){r->e->t_base + t, a < b ? a : b, a < b ? b : a,
	                                        kind, r->e->p[first].cell};
}

/* ---- the messages that wait ---- */

/* Waiting messages by time, then by particle number (not slot: the same order on
 * every rank and in every run). */
static int wait_before(const lz_pedmd *r, const lz_pedmd_message *a, const lz_pedmd_message *b)
{
	return a->t < b->t || (a->t == b->t && lz_pedmd_id(r, a->id) < lz_pedmd_id(r, b->id));
}

int lz_pedmd_wait(lz_pedmd *r, const lz_pedmd_message *m)
{
	if (lz_pedmd_grow((void **)&r->wait, &r->capwait, r->nwait, sizeof *r->wait))
		return LZ_ENOMEM;
	size_t k = r->nwait++;
	while (k > 0 && wait_before(r, m, &r->wait[(k - 1) / 2])) {
		r->wait[k] = r->wait[(k - 1) / 2];
		k = (k - 1) / 2;
	}
	r->wait[k] = *m;
	return LZ_OK;
}

static lz_pedmd_message wait_pop(lz_pedmd *r)
{
	lz_pedmd_message top = r->wait[0], last = r->wait[--r->nwait];
	size_t k = 0;
	for (;;) {
		size_t c = 2 * k + 1;
		if (c >= r->nwait)
			break;
		if (c + 1 < r->nwait && wait_before(r, &r->wait[c + 1], &r->wait[c]))
			c++;
		if (!wait_before(r, &r->wait[c], &last))
			break;
		r->wait[k] = r->wait[c];
		k = c;
	}
	if (r->nwait > 0)
		r->wait[k] = last;
	return top;
}

/* ---- restore ---- */

void lz_pedmd_read_at(lz_pedmd *r, uint32_t c, double t)
{
	if (r->read[c] >= t)
		return;
	if (r->rmark[c] != r->epoch) {
		if (lz_pedmd_grow((void **)&r->stamps, &r->capstamps, r->nstamps, sizeof *r->stamps)) {
			r->nomem = 1;
			return;
		}
		r->stamps[r->nstamps++] = (lz_pedmd_stamp){c, r->read[c]};
		r->rmark[c] = r->epoch;
	}
	r->read[c] = t;
}

void lz_pedmd_unread(lz_pedmd *r)
{
	for (size_t k = 0; k < r->nstamps; k++)
		r->read[r->stamps[k].cell] = r->stamps[k].read;
	r->nstamps = 0;
}

/* ---- the window protocol ---- */


/* FNV-1a over n bytes, continuing from h. */
static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
	const unsigned char *b = data;
	for (size_t k = 0; k < n; k++)
		h = (h ^ b[k]) * 1099511628211u;
	return h;
}

/* A fingerprint of the rank: its owned particles (number, record, event as sent) and
 * the window's events, each in any order (events at one time may run in either
 * order: a rollback puts particles back into the heap, and ties may then pop
 * otherwise; and a rerun may meet particles in another order, so give them other
 * slots). O(slots + window). */
static uint64_t fingerprint(const lz_pedmd *r)
{
	const uint64_t basis = 14695981039346656037u;
	uint64_t owned = 0, events = 0;
	for (uint32_t i = 0; i < r->nslots; i++)
		if (r->role[i] == LZ_PEDMD_OWNED) {
			lz_pedmd_message m = lz_pedmd_outgoing(r, i, LZ_PEDMD_MIGRATE, 0);
			owned += fnv(fnv(fnv(basis, &m.id, sizeof m.id), &m.p, sizeof m.p), &m.event,
			             sizeof m.event);
		}
	for (size_t k = 0; k < r->nwlog; k++)
		events += fnv(basis, &r->wlog[k], sizeof r->wlog[k]);
	return fnv(fnv(basis, &owned, sizeof owned), &events, sizeof events);
}

/* The earliest time anything happens next on this rank (absolute). */
static double next_time(const lz_pedmd *r)
{
	double t = r->e->heap->n ? lz_heap_top_t(r->e->heap) : INFINITY;
	if (r->nwait > 0 && r->wait[0].t < t)
		t = r->wait[0].t;
	return r->e->t_base + t;
}

/* Where the window starting at T ends: T + width, the next re-base time or t_stop,
 * whichever comes first (or the end a cut forced); and what it saves at its start. */
static int begin_window(lz_pedmd *r, double t_stop)
{
	double rebase = (floor(r->T / r->p.rebase) + 1) * r->p.rebase;
	double end = isnan(r->forced_end) ? r->T + r->width : r->forced_end;
	r->rebase_at_end = rebase <= end && rebase < t_stop;  /* none at the very end, as serially */
	r->forced = !isnan(r->forced_end);
	r->forced_end = NAN;
	int st = lz_pedmd_begin(r, fmin(fmin(end, rebase), t_stop));
	if (r->p.recheck && !r->rerun)
		r->print0 = fingerprint(r);
	r->counts.windows++;
	r->phase = LZ_PEDMD_RUN;
	return st;
}

int lz_pedmd_begin(lz_pedmd *r, double t_end)
{
	lz_edmd *e = r->e;
	r->t_end = t_end;
	r->epoch++;
	r->nsaved = 0;
	r->nstamps = 0;
	r->snap = *e;
	if (r->nwait > 0 && lz_pedmd_grow((void **)&r->wait0, &r->capwait0, r->nwait, sizeof *r->wait0))
		return LZ_ENOMEM;
	if (r->nwait > 0)
		memcpy(r->wait0, r->wait, r->nwait * sizeof *r->wait);
	r->nwait0 = r->nwait;
	r->clock0 = r->clock;
	r->next0 = next_time(r);
	r->nwlog = 0;
	r->wcommit = 0;
	r->wvirial = 0;
	r->t_error = INFINITY;
	r->halted = 0;
	return LZ_OK;
}

/* Poll and apply every message that has arrived. Only while the window runs: a
 * message that comes while this rank still waits for the verdict belongs to the next
 * window (its sender has the verdict already) and stays with the transport until then.
 * After a causality error the window will be rolled back, so messages are only
 * counted (the cut needs every message received). */
static int receive(lz_pedmd *r)
{
	lz_pedmd_message m;
	int from, st = LZ_OK;
	size_t n;
	while (r->phase == LZ_PEDMD_RUN && (st = lz_msg_poll(r->msg, &from, &m, sizeof m, &n)) == 1) {
		r->woke = 1;
		if (n != sizeof m)
			return lz_error(LZ_EDOM, "rank %d got a message of %zu bytes from rank %d, not "
			                "%zu", r->rank, n, from, sizeof m);
		if (m.kind == LZ_PEDMD_HALT) {  /* another rank's error: this window is lost */
			r->halted = 1;
			lz_pedmd_late(r, m.t);
			continue;
		}
		if (r->t_error != INFINITY)
			continue;
		if ((st = lz_pedmd_incoming(r, &m)) != LZ_OK)  /* numbers to slots */
			return st;
		int late = m.t < r->clock;
		if ((st = lz_pedmd_apply(r, &m)) != LZ_OK)
			return st;
		r->counts.late_harmless += late && r->t_error == INFINITY;
	}
	return st;
}

/* This rank found the window's first error: every other rank is told to stop running
 * a window that will be rolled back (else each runs on to its end, all of it lost). */
static int halt(lz_pedmd *r)
{
	lz_pedmd_message m = {.t = r->t_error, .kind = LZ_PEDMD_HALT,
	                      .event = {INFINITY, {LZ_EDMD_NONE, 0}}};
	int st = LZ_OK;
	r->halted = 1;
	r->woke = 1;
	for (int k = 0; k < lz_msg_size(r->msg) && st == LZ_OK; k++)
		if (k != r->rank)
			st = lz_msg_send(r->msg, k, &m, sizeof m);
	return st;
}

/* The serial engine's look ahead (lz_edmd_fetch_ahead), and the rank's own side of
 * the next event: saving and predicting its particle and partner read their marks,
 * roles, own and ghost events and last news — five arrays of N, each a miss of its
 * own at 10^6 particles unless asked for an event early. */
static void fetch_ahead(const lz_pedmd *r)
{
	const lz_edmd *e = r->e;
	lz_edmd_fetch_ahead(e);
	if (e->heap->n < 16)
		return;
	uint32_t c1, c2;
	lz_heap_next_items(e->heap, &c1, &c2);
	int32_t j1 = e->ev[c1].partner;
	uint32_t ids[2] = {c1, j1 >= 0 ? (uint32_t)j1 : c1};
	for (int k = 0; k < 2; k++) {
		uint32_t i = ids[k];
		__builtin_prefetch(&r->mark[i]);
		__builtin_prefetch(&r->role[i]);
		__builtin_prefetch(&r->own[i]);
		__builtin_prefetch(&r->ghost[i]);
		__builtin_prefetch(&r->heard[i]);
		if (r->gid)
			__builtin_prefetch(&r->gid[i]);
	}
}

/* The next thing to do in time order, if it is due before the window ends: the
 * earliest waiting message or event; *did = 1 when something was done. On a tie the
 * event goes first: a message at the time of one of this rank's events is the other
 * half of the same replicated collision, which the rank must carry out itself (the
 * message then brings the ghost's record this rank computed already). */
static int advance_one(lz_pedmd *r, int *did)
{
	lz_edmd *e = r->e;
	double te = e->heap->n ? lz_heap_top_t(e->heap) : INFINITY;
	if (r->nwait > 0 && r->wait[0].t < te && e->t_base + r->wait[0].t <= r->t_end) {
		lz_pedmd_message m = wait_pop(r);
		*did = 1;
		if (m.t > r->clock)  /* it is next: the rank's time moves on to it */
			r->clock = r->e->now = m.t;
		return lz_pedmd_apply(r, &m);
	}
	return lz_pedmd_step(r, did);
}

static void commit(lz_pedmd *r)
{
	for (size_t k = 0; k < r->nwlog; k++) {
		const lz_pedmd_record *q = &r->wlog[k];
		r->counts.collisions += q->kind == LZ_PEDMD_COLLISION;
		r->counts.crossings += q->kind == LZ_PEDMD_CROSSING;
		r->counts.bounces += q->kind == LZ_PEDMD_BOUNCE;
		r->counts.stale += q->kind == LZ_PEDMD_STALE;
		r->load[q->cell]++;
	}
	if (r->p.log && r->nwlog > 0 &&
	    lz_pedmd_grow((void **)&r->clog, &r->capclog, r->nclog + r->nwlog - 1, sizeof *r->clog) == LZ_OK) {
		memcpy(r->clog + r->nclog, r->wlog, r->nwlog * sizeof *r->wlog);
		r->nclog += r->nwlog;
	}
	r->counts.committed += r->wcommit;
	r->counts.virial += r->wvirial;
	uint64_t bytes = r->nsaved * sizeof *r->saved;
	if (bytes > r->counts.saved_bytes)
		r->counts.saved_bytes = bytes;
}

/* Re-base at the window's end, as lz_edmd_run then lz_edmd_rebase do serially. */
static void rebase(lz_pedmd *r)
{
	lz_edmd *e = r->e;
	e->now = r->t_end - e->t_base;
	double now = e->now;
	lz_edmd_rebase(e);
	for (size_t i = 0; i < e->n; i++) {
		r->own[i].t -= now;
		r->ghost[i].t -= now;
		r->heard[i] -= now;
	}
	for (size_t k = 0; k < r->nwait; k++)
		r->wait[k].t -= now;
	for (size_t c = 0; c < e->ncells; c++)
		if (!r->gid || r->cls[c] != LZ_PEDMD_FAR)
			r->read[c] -= now;
	r->clock = 0;
}

/* Every owned particle brought to t_stop, as lz_edmd_run's stop does. */
static void finish(lz_pedmd *r, double t_stop)
{
	lz_edmd *e = r->e;
	e->now = t_stop - e->t_base;
	for (size_t i = 0; i < e->n; i++)
		if (r->role[i] == LZ_PEDMD_OWNED)
			lz_edmd_advance(e, &e->p[i], e->now);
	r->phase = LZ_PEDMD_DONE;
}

/* The rollback check at a verdict: 1 when the window is to run again (its first run
 * rolled back), 0 to go on with the verdict; a difference sets r->failed. */
static int recheck(lz_pedmd *r, int v)
{
	if (v != LZ_PEDMD_COMMIT) {
		r->rerun = 0;  /* the rerun met an error the first run did not: nothing to compare */
		return 0;
	}
	uint64_t now = fingerprint(r);
	if (r->rerun) {
		r->rerun = 0;
		if (now != r->print1)
			r->failed = lz_error(LZ_EDOM, "rank %d, rollback check: the window [%.17g, %.17g] "
			                     "run again ended in another state", r->rank, r->T, r->t_end);
		return 0;
	}
	r->print1 = now;
	lz_pedmd_restore(r);
	if (fingerprint(r) != r->print0)
		r->failed = lz_error(LZ_EDOM, "rank %d, rollback check: the state restored at %.17g "
		                     "is not the one saved there", r->rank, r->T);
	r->rerun = 1;
	r->counts.rechecks++;
	r->forced_end = r->t_end;
	r->phase = LZ_PEDMD_BEGIN;
	return 1;
}

/* At the cut: act on the verdict. */
static void verdict(lz_pedmd *r, double t_error, double t_next, double t_stop)
{
	double end;
	int v = lz_pedmd_decide(t_error, r->T, t_next, &end);
	if (r->p.recheck && recheck(r, v))
		return;
	if (v == LZ_PEDMD_COMMIT) {
		commit(r);
		if (r->rebase_at_end)
			rebase(r);
		r->T = r->t_end;
		/* A window cut short by a cut proves nothing of the width. Slow growth, fast
		 * shrinking: a rollback loses the window's events up to the error, a commit
		 * gains a little more length (doubling, as the paper does, rolls back every
		 * other window; lesson §11) */
		if (!r->forced)
			r->width = fmin(r->p.grow * r->width, 64 * r->p.window);
		r->phase = r->T >= t_stop ? LZ_PEDMD_DONE : LZ_PEDMD_BEGIN;
		if (r->phase == LZ_PEDMD_DONE)
			finish(r, t_stop);
		return;
	}
	lz_pedmd_restore(r);
	if (v == LZ_PEDMD_ROLLBACK) {
		r->counts.rollbacks++;
		r->width = fmax(r->width / 2, r->p.window / 64);
	} else {
		r->counts.conservative++;
	}
	r->forced_end = end;
	r->phase = LZ_PEDMD_BEGIN;
}

/* The cut: rounds of (sent, received, busy) sums until two in a row agree, nothing is
 * in flight and nobody moved (Mattern's counters); then one round of (error, next)
 * minima, and the verdict. */
static int cut(lz_pedmd *r, double t_stop)
{
	double out[3];
	if (r->in_round) {
		int got = lz_msg_reduce_test(r->msg, out);
		if (got != 1)
			return got;  /* 0: not yet; an LZ_E code */
		r->in_round = 0;
		if (r->phase == LZ_PEDMD_DECIDE) {
			verdict(r, out[0], out[1], t_stop);
			return LZ_OK;
		}
		int quiet = out[2] == 0 && out[0] == out[1] && r->rounds > 0 &&
		            out[0] == r->last_sum[0] && out[1] == r->last_sum[1];
		memcpy(r->last_sum, out, sizeof out);
		r->rounds++;
		if (quiet) {
			double in[2] = {r->e->t_base + r->t_error, r->next0};
			r->phase = LZ_PEDMD_DECIDE;
			r->in_round = 1;
			return lz_msg_reduce_start(r->msg, LZ_MSG_MINIMUM, in, 2);
		}
	}
	lz_msg_counts c = lz_msg_counters(r->msg);
	double in[3] = {(double)c.sent, (double)c.received, (double)r->woke};
	r->woke = 0;
	r->in_round = 1;
	return lz_msg_reduce_start(r->msg, LZ_MSG_SUM, in, 3);
}

int lz_pedmd_work(lz_pedmd *r, double t_stop, lz_work *state)
{
	*state = LZ_WORK_BUSY;
	if (r->phase == LZ_PEDMD_DONE) {
		*state = LZ_WORK_DONE;
		return LZ_OK;
	}
	if (r->phase == LZ_PEDMD_BEGIN) {
		if (r->T >= t_stop) {
			finish(r, t_stop);
			*state = LZ_WORK_DONE;
			return LZ_OK;
		}
		int st = begin_window(r, t_stop);
		if (st != LZ_OK)
			return st;
		r->rounds = 0;
	}
	int st = receive(r);
	if (st != LZ_OK)
		return st;
	int did = 0, events = 0;
	while (r->phase == LZ_PEDMD_RUN && r->t_error == INFINITY && events < r->p.work) {
		int one = 0;
		if (r->e->prefetch)
			fetch_ahead(r);
		if ((st = advance_one(r, &one)) != LZ_OK)
			return st;
		if (!one)
			break;
		did = 1;
		events++;
		r->woke = 1;
	}
	if (r->nomem)
		return lz_error(LZ_ENOMEM, "rank %d: no memory for the log or the read stamps of a window", r->rank);
	lz_msg_charge(r->msg, events);
	if (r->t_error != INFINITY && !r->halted && (st = halt(r)) != LZ_OK)
		return st;
	int rounds = r->rounds, phase = r->phase;
	if ((!did || r->t_error != INFINITY || r->in_round) && (st = cut(r, t_stop)) != LZ_OK)
		return st;
	if (r->failed)
		return r->failed;
	did |= r->rounds != rounds || r->phase != phase;  /* the cut moved on */
	if (r->phase == LZ_PEDMD_DONE)
		*state = LZ_WORK_DONE;
	else if (!did)
		*state = LZ_WORK_WAIT;
	return LZ_OK;
}

/* ---- the audit ---- */

/* Particle id on rank r: its role, and in *m its record and event as r would send them
 * (numbers, not slots). */
static int held_as(const lz_pedmd *r, uint32_t id, lz_pedmd_message *m)
{
	int64_t i = lz_pedmd_slot(r, id);
	if (i < 0)
		return LZ_PEDMD_ABSENT;
	*m = lz_pedmd_outgoing(r, (uint32_t)i, LZ_PEDMD_STATE, 0);
	if (r->role[i] == LZ_PEDMD_GHOST) {
		m->event = r->ghost[i];
		if (m->event.ev.partner >= 0)
			m->event.ev.partner = (int32_t)lz_pedmd_id(r, (uint32_t)m->event.ev.partner);
	}
	return r->role[i];
}

static int audit_owned(lz_pedmd *const *ranks, int P, uint32_t id, int *owner,
                       lz_pedmd_message *m)
{
	*owner = -1;
	for (int k = 0; k < P; k++) {
		const lz_pedmd *r = ranks[k];
		if (held_as(r, id, m) != LZ_PEDMD_OWNED)
			continue;
		if (*owner >= 0)
			return lz_error(LZ_EDOM, "particle %u is owned by ranks %d and %d", id, *owner, k);
		*owner = k;
		uint32_t c = m->p.cell;
		if (lz_pedmd_owner(r->d, c) != k)
			return lz_error(LZ_EDOM, "rank %d owns particle %u in cell %u, which rank %d owns",
			                k, id, c, lz_pedmd_owner(r->d, c));
		if (!lz_heap_contains(r->e->heap, (uint32_t)lz_pedmd_slot(r, id)))
			return lz_error(LZ_EDOM, "rank %d owns particle %u, which is not in its heap", k, id);
	}
	if (*owner < 0)
		return lz_error(LZ_EDOM, "particle %u is owned by no rank", id);
	held_as(ranks[*owner], id, m);
	return LZ_OK;
}

int lz_pedmd_audit(lz_pedmd *const *ranks, int P)
{
	for (uint32_t id = 0; id < ranks[0]->N; id++) {
		int o;
		lz_pedmd_message own, g;
		if (audit_owned(ranks, P, id, &o, &own))
			return LZ_EDOM;
		for (int k = 0; k < P; k++) {
			const lz_pedmd *r = ranks[k];
			int halo = r->cls[own.p.cell] == LZ_PEDMD_HALO, role = held_as(r, id, &g);
			if (k == o || (!halo && role == LZ_PEDMD_ABSENT))
				continue;
			if (halo != (role == LZ_PEDMD_GHOST))
				return lz_error(LZ_EDOM, "particle %u (rank %d's, cell %u) is %s on rank %d",
				                id, o, own.p.cell, halo ? "missing as a ghost" : "a ghost out of the halo", k);
			if (memcmp(&g.p, &own.p, sizeof own.p) || memcmp(&g.event, &own.event, sizeof own.event))
				return lz_error(LZ_EDOM, "rank %d's ghost of particle %u differs from rank %d's "
				                "record or event", k, id, o);
		}
	}
	return LZ_OK;
}
