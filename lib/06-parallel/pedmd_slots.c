/* pedmd_slots.c — local numbering of a rank (lz/pedmd.h, params.compact): the slots
 * of the particles a rank holds, the index from a particle's number to its slot, and
 * the translation of messages at the rank's edge. Inside a rank everything — cells,
 * heap, events, saved versions — speaks of slots, as the serial engine speaks of
 * particles; only what leaves or enters the rank speaks of numbers.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/bigmem.h"
#include "lz/error.h"
#include "lz/pedmd.h"

enum { EMPTY = UINT32_MAX };

/* An entry of the index: the number in the high half, the slot in the low (one cache
 * line read a lookup); all ones where empty. */
static uint64_t entry(uint32_t id, uint32_t slot) { return (uint64_t)id << 32 | slot; }

uint32_t lz_pedmd_id(const lz_pedmd *r, uint32_t i) { return r->gid ? r->gid[i] : i; }

size_t lz_pedmd_particles(const lz_pedmd *r) { return r->N; }

/* Where the search for id starts: Fibonacci hashing, the top bits of a product. */
static size_t home(const lz_pedmd *r, uint32_t id)
{
	return (size_t)((id * UINT64_C(0x9E3779B97F4A7C15)) >> (64 - r->hbits));
}

int64_t lz_pedmd_slot(const lz_pedmd *r, uint32_t id)
{
	if (!r->gid)
		return id < r->e->n ? (int64_t)id : -1;
	for (size_t k = home(r, id);; k = (k + 1) & (r->hcap - 1)) {
		uint32_t key = (uint32_t)(r->index[k] >> 32);
		if (key == id)
			return (uint32_t)r->index[k];
		if (key == EMPTY)
			return -1;
	}
}

static void index_put(lz_pedmd *r, uint32_t id, uint32_t slot)
{
	size_t k = home(r, id);
	while (r->index[k] != UINT64_MAX)
		k = (k + 1) & (r->hcap - 1);
	r->index[k] = entry(id, slot);
}

/* An index of 2^bits entries holding the slots in use. LZ_OK or LZ_ENOMEM (the old
 * index kept). O(2^bits + slots). */
static int index_make(lz_pedmd *r, int bits)
{
	size_t cap = (size_t)1 << bits;
	uint64_t *index = lz_bigmem_alloc(cap * sizeof *index);
	if (!index)
		return lz_error(LZ_ENOMEM, "rank %d: no memory for an index of %zu slots", r->rank, cap);
	lz_bigmem_free(r->index);
	r->index = index;
	r->hcap = cap;
	r->hbits = bits;
	memset(index, 0xff, cap * sizeof *index);
	for (uint32_t i = 0; i < r->nslots; i++)
		index_put(r, r->gid[i], i);
	return LZ_OK;
}

/* Slot i as a particle the rank never heard of: ABSENT, in no cell and not in the
 * heap, its count LZ_PEDMD_UNKNOWN (no event can aim at it with that count). */
static void blank(lz_pedmd *r, uint32_t i)
{
	lz_edmd *e = r->e;
	e->p[i] = (lz_edmd_particle){.count = LZ_PEDMD_UNKNOWN};
	e->ev[i] = (lz_edmd_event){LZ_EDMD_NONE, 0};
	e->next[i] = -1;
	r->role[i] = LZ_PEDMD_ABSENT;
	r->own[i] = (lz_pedmd_event){-INFINITY, {LZ_EDMD_NONE, 0}};
	r->ghost[i] = (lz_pedmd_event){INFINITY, {LZ_EDMD_NONE, 0}};
	r->heard[i] = -INFINITY;
	r->mark[i] = 0;
	r->gid[i] = EMPTY;
}

/* *v, an array of `old` entries of `size` bytes, with room for n. */
static int resize(void **v, size_t old, size_t n, size_t size)
{
	void *w = lz_bigmem_resize(*v, old * size, n * size);
	if (!w)
		return LZ_ENOMEM;
	*v = w;
	return LZ_OK;
}

/* The index's size for n slots: at most three quarters full. */
static int bits_for(size_t n)
{
	int bits = 6;
	while (3 * ((size_t)1 << bits) < 4 * n)
		bits++;
	return bits;
}

/* n slots (at least those in use): the system, the rank's arrays and the index, more
 * or fewer, the new slots blank; the window's snapshot of the system follows them (a
 * rollback restores the scalars, not the arrays). LZ_OK or LZ_ENOMEM. O(n). */
static int resize_slots(lz_pedmd *r, size_t n)
{
	lz_edmd *e = r->e;
	size_t old = e->n;
	if (lz_edmd_resize(e, n) != LZ_OK ||
	    resize((void **)&r->role, old, n, sizeof *r->role) ||
	    resize((void **)&r->own, old, n, sizeof *r->own) ||
	    resize((void **)&r->ghost, old, n, sizeof *r->ghost) ||
	    resize((void **)&r->heard, old, n, sizeof *r->heard) ||
	    resize((void **)&r->mark, old, n, sizeof *r->mark) ||
	    resize((void **)&r->gid, old, n, sizeof *r->gid))
		return lz_error(LZ_ENOMEM, "rank %d: no memory for %zu slots", r->rank, n);
	for (size_t i = old; i < n; i++)
		blank(r, (uint32_t)i);
	r->snap.n = e->n;
	r->snap.p = e->p;
	r->snap.ev = e->ev;
	r->snap.next = e->next;
	return index_make(r, bits_for(n));
}

int lz_pedmd_reserve(lz_pedmd *r, size_t n)
{
	return n <= r->e->n ? LZ_OK : resize_slots(r, n);
}

int lz_pedmd_hold(lz_pedmd *r, uint32_t id, uint32_t *slot)
{
	int64_t s = lz_pedmd_slot(r, id);
	if (s >= 0) {
		*slot = (uint32_t)s;
		return LZ_OK;
	}
	if (id >= r->N)
		return lz_error(LZ_EDOM, "rank %d: particle %u is not one of the %zu", r->rank, id,
		                r->N);
	if (r->nslots == r->e->n && lz_pedmd_reserve(r, r->nslots < 32 ? 64 : 2 * r->nslots))
		return LZ_ENOMEM;
	*slot = (uint32_t)r->nslots++;
	r->gid[*slot] = id;
	index_put(r, id, *slot);
	return LZ_OK;
}

lz_pedmd_message lz_pedmd_outgoing(const lz_pedmd *r, uint32_t i, uint32_t kind, double t)
{
	lz_pedmd_message m = {t, lz_pedmd_id(r, i), kind, r->e->p[i], r->own[i]};
	if (m.event.ev.partner >= 0)
		m.event.ev.partner = (int32_t)lz_pedmd_id(r, (uint32_t)m.event.ev.partner);
	return m;
}

int lz_pedmd_incoming(lz_pedmd *r, lz_pedmd_message *m)
{
	uint32_t i, j;
	int st = lz_pedmd_hold(r, m->id, &i);
	if (st == LZ_OK && m->event.ev.partner >= 0 &&
	    (st = lz_pedmd_hold(r, (uint32_t)m->event.ev.partner, &j)) == LZ_OK)
		m->event.ev.partner = (int32_t)j;
	m->id = i;
	return st;
}

/* The slot a partner moved to (to[]), or NONE when it was dropped. */
static void remap(int32_t *partner, const uint32_t *to)
{
	if (*partner >= 0)
		*partner = to[*partner] == EMPTY ? LZ_EDMD_NONE : (int32_t)to[*partner];
}

int lz_pedmd_compact(lz_pedmd *r)
{
	if (!r->gid)
		return LZ_OK;
	lz_edmd *e = r->e;
	uint32_t *to = malloc((r->nslots ? r->nslots : 1) * sizeof *to), k = 0;
	if (!to)
		return lz_error(LZ_ENOMEM, "rank %d: no memory to renumber %zu slots", r->rank, r->nslots);
	for (uint32_t i = 0; i < r->nslots; i++)
		to[i] = r->role[i] != LZ_PEDMD_ABSENT ? 0 : EMPTY;
	for (uint32_t i = 0; i < r->nslots; i++) {  /* and the partners they name */
		int32_t a = r->own[i].ev.partner, b = r->ghost[i].ev.partner;
		if (r->role[i] != LZ_PEDMD_ABSENT && a >= 0)
			to[a] = 0;
		if (r->role[i] != LZ_PEDMD_ABSENT && b >= 0)
			to[b] = 0;
	}
	for (uint32_t i = 0; i < r->nslots; i++)
		if (to[i] != EMPTY) {  /* k <= i: moved down, never over one still to move */
			to[i] = k;
			e->p[k] = e->p[i];
			e->ev[k] = e->ev[i];
			r->role[k] = r->role[i];
			r->own[k] = r->own[i];
			r->ghost[k] = r->ghost[i];
			r->heard[k] = r->heard[i];
			r->gid[k++] = r->gid[i];
		}
	for (uint32_t i = 0; i < k; i++) {
		remap(&e->ev[i].partner, to);
		remap(&r->own[i].ev.partner, to);
		remap(&r->ghost[i].ev.partner, to);
	}
	free(to);
	for (uint32_t i = k; i < r->nslots; i++)
		blank(r, i);
	for (uint32_t i = 0; i < k; i++)
		r->mark[i] = 0;
	r->nslots = k;
	size_t room = k + k / 8 + 64;
	if (2 * e->n > 3 * room)  /* a share much smaller than before: give the room back */
		return resize_slots(r, room);
	return index_make(r, r->hbits);
}

static int by_first(const void *a, const void *b)
{
	const uint64_t *x = a, *y = b;
	return (*x > *y) - (*x < *y);
}

uint32_t *lz_pedmd_by_number(const lz_pedmd *r)
{
	size_t n = r->nslots;
	uint32_t *out = malloc((n ? n : 1) * sizeof *out);
	uint64_t *pair = r->gid ? malloc((n ? n : 1) * sizeof *pair) : NULL;
	if (!out || (r->gid && !pair)) {
		free(out);
		free(pair);
		return lz_error(LZ_ENOMEM, "rank %d: no memory to sort %zu slots", r->rank, n), NULL;
	}
	for (uint32_t i = 0; i < n; i++)
		if (pair)
			pair[i] = (uint64_t)r->gid[i] << 32 | i;
		else
			out[i] = i;
	if (pair) {
		qsort(pair, n, sizeof *pair, by_first);
		for (size_t k = 0; k < n; k++)
			out[k] = (uint32_t)pair[k];
		free(pair);
	}
	return out;
}

/* The local numbering of a new rank (compact): no slot in use, an empty index.
 * LZ_OK or LZ_ENOMEM. */
int lz_pedmd_slots_init(lz_pedmd *r)
{
	r->gid = lz_bigmem_alloc(r->e->n * sizeof *r->gid);
	if (!r->gid)
		return lz_error(LZ_ENOMEM, "rank %d: no memory for its slots", r->rank);
	for (uint32_t i = 0; i < r->e->n; i++)
		blank(r, i);
	r->nslots = 0;
	return index_make(r, bits_for(r->e->n));
}
