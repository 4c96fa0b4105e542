/* calendar.c — the calendar queue of lz/calendar.h: days, today's heap, the ring of
 * day lists and the overflow. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lz/bigmem.h"
#include "lz/calendar.h"
#include "lz/error.h"

#define NONE LZ_CAL_NONE
#define FAR INT64_MAX  /* the day of a key too late to count, or +INFINITY */

/* ---- days ---- */

/* The day of key t: non-decreasing in t (a key a hair before the origin, which a
 * prediction made before the first event can give, truncates to day 0 — today). */
static int64_t day_of(const lz_calendar *q, double t)
{
	double x = (t - q->origin) * q->inv;
	return x < 0x1p62 ? (int64_t)x : FAR;
}

static uint32_t slot_of(const lz_calendar *q, int64_t day)
{
	return (uint32_t)((uint64_t)day & (q->days - 1));
}

/* Where an item is, from its key alone: today (its day is today or before), the ring
 * (a later day before resorted + days) or the overflow (later still). */
enum { NEAR, RING, OVER };
static int place_of(const lz_calendar *q, int64_t day)
{
	return day <= q->today ? NEAR : day - q->resorted < (int64_t)q->days ? RING : OVER;
}

/* ---- today's heap: a binary heap of (key, id) ---- */

static void near_up(lz_calendar *q, size_t k)
{
	lz_heap_node x = q->near[k];
	while (k > 0 && q->near[(k - 1) / 2].t > x.t) {
		q->near[k] = q->near[(k - 1) / 2];
		k = (k - 1) / 2;
	}
	q->near[k] = x;
}

static void near_down(lz_calendar *q, size_t k)
{
	lz_heap_node x = q->near[k];
	for (;;) {
		size_t c = 2 * k + 1;
		if (c >= q->nnear)
			break;
		if (c + 1 < q->nnear && q->near[c + 1].t < q->near[c].t)
			c++;
		if (x.t <= q->near[c].t)
			break;
		q->near[k] = q->near[c];
		k = c;
	}
	q->near[k] = x;
}

static int near_push(lz_calendar *q, uint32_t id)
{
	if (q->nnear == q->capnear) {
		size_t cap = 2 * q->capnear;
		lz_heap_node *w = realloc(q->near, cap * sizeof *w);
		if (!w)
			return lz_error(LZ_ENOMEM, "no memory for %zu events of one day", cap);
		q->near = w;
		q->capnear = cap;
	}
	q->near[q->nnear] = (lz_heap_node){q->item[id].key, id};
	near_up(q, q->nnear++);
	return LZ_OK;
}

/* Take item id out of today's heap: found by a look at the top (the usual case: the
 * event just carried out), else along the few dozen nodes of today. */
static void near_remove(lz_calendar *q, uint32_t id)
{
	size_t k = 0;
	while (q->near[k].id != id)
		k++;
	lz_heap_node last = q->near[--q->nnear];
	if (k < q->nnear) {
		double old = q->near[k].t;
		q->near[k] = last;
		if (last.t < old)
			near_up(q, k);
		else
			near_down(q, k);
	}
	if (q->nnear == 0)
		q->near[0] = (lz_heap_node){INFINITY, 0};  /* the top of an empty calendar */
}

/* ---- the lists: head[0 .. days-1] the ring, head[days] the overflow ---- */

static void link_in(lz_calendar *q, uint32_t list, uint32_t id)
{
	q->item[id].prev = NONE;
	q->item[id].next = q->head[list];
	if (q->head[list] != NONE)
		q->item[q->head[list]].prev = id;
	q->head[list] = id;
	q->ring += list != q->days;
}

static void link_out(lz_calendar *q, uint32_t list, uint32_t id)
{
	if (q->ahead == id)  /* the walk along tomorrow's list steps past it */
		q->ahead = q->item[id].next;
	if (q->item[id].prev != NONE)
		q->item[q->item[id].prev].next = q->item[id].next;
	else
		q->head[list] = q->item[id].next;
	if (q->item[id].next != NONE)
		q->item[q->item[id].next].prev = q->item[id].prev;
	q->ring -= list != q->days;
}

/* Put item id (its key set, in no list) where its day says. */
static int place(lz_calendar *q, uint32_t id)
{
	int64_t day = day_of(q, q->item[id].key);
	switch (place_of(q, day)) {
	case NEAR:
		return near_push(q, id);
	case RING:
		link_in(q, slot_of(q, day), id);
		return LZ_OK;
	default:
		link_in(q, q->days, id);
		return LZ_OK;
	}
}

/* Take item id out of wherever its key says it is. */
static void unplace(lz_calendar *q, uint32_t id)
{
	int64_t day = day_of(q, q->item[id].key);
	switch (place_of(q, day)) {
	case NEAR:
		near_remove(q, id);
		break;
	case RING:
		link_out(q, slot_of(q, day), id);
		break;
	default:
		link_out(q, q->days, id);
	}
}

/* The overflow placed again from today: what has come within reach moves to the ring
 * (or today). */
static int resort_overflow(lz_calendar *q)
{
	q->resorted = q->today;
	uint32_t id = q->head[q->days];
	q->head[q->days] = NONE;
	while (id != NONE) {
		uint32_t after = q->item[id].next;
		int st = place(q, id);
		if (st != LZ_OK)
			return st;
		id = after;
	}
	return LZ_OK;
}

/* Turn the days over until today has an event (or nothing with a finite key is left):
 * each new day's list becomes today's heap; at every turn of the ring the overflow is
 * sorted out again; with the ring empty, today jumps to the overflow's earliest day. */
static int new_day(lz_calendar *q)
{
	while (q->nnear == 0) {
		if (q->ring == 0) {
			int64_t first = FAR;
			for (uint32_t id = q->head[q->days]; id != NONE; id = q->item[id].next) {
				int64_t d = day_of(q, q->item[id].key);
				first = d < first ? d : first;
			}
			if (first == FAR)
				return LZ_OK;  /* nothing will ever happen: the top is +INFINITY */
			q->today = first;
			int st = resort_overflow(q);
			if (st != LZ_OK)
				return st;
			continue;
		}
		q->today++;
		uint32_t s = slot_of(q, q->today);
		if (s == 0) {
			int st = resort_overflow(q);
			if (st != LZ_OK)
				return st;
		}
		uint32_t id = q->head[s];
		q->head[s] = NONE;
		q->ahead = NONE;  /* tomorrow is another list now */
		while (id != NONE) {
			uint32_t after = q->item[id].next;
			q->ring--;
			int st = near_push(q, id);
			if (st != LZ_OK)
				return st;
			id = after;
		}
	}
	return LZ_OK;
}

/* ---- the calendar ---- */

/* The most days in the ring: 2^15 heads, 128 kB, stay in the second-level cache, where
 * a change finds its day's head; a million spheres at 32 events a day would want a
 * megabyte of heads and wait on it at every change. Longer days instead (interleaved
 * runs at N = 10^6): 2^16 days 1.04-1.07 times as fast, 2^15 about 3 % more; at 10^4,
 * whose heads are in cache anyway, longer days cost 3 %, so only large calendars have
 * them. */
#define DAYS_MAX 32768u

/* Days in the ring for cap items: the power of two from cap/4 up (a byte or two per
 * item), so that the ring spans about 8 events of every item — the rare later ones
 * wait in the overflow — but at most DAYS_MAX. */
static uint32_t ring_days(size_t cap)
{
	uint32_t d = 64;
	while (d < cap / 4 && d < DAYS_MAX)
		d *= 2;
	return d;
}

/* The events a day for a ring of `days` days for cap items: 32, or more in
 * proportion where the ring stopped short of cap/4 days. */
static double day_events(size_t cap, uint32_t days)
{
	return fmax(32, 32 * ((double)cap / 4) / days);
}

lz_calendar *lz_calendar_alloc(size_t cap, double width)
{
	if (cap < 1 || cap >= LZ_CAL_NONE)
		return lz_error(LZ_EINVAL, "calendar capacity %zu must be in [1, 2^31)", cap), NULL;
	if (!(width > 0) || !isfinite(width))
		return lz_error(LZ_EINVAL, "calendar day width %g must be positive and finite",
		                width), NULL;
	lz_calendar *q = calloc(1, sizeof *q);
	if (!q)
		return lz_error(LZ_ENOMEM, "no memory for a calendar"), NULL;
	q->cap = cap;
	q->days = ring_days(cap);
	q->per_day = day_events(cap, q->days);
	q->width = width;
	q->inv = 1 / width;
	q->capnear = 64;
	q->item = lz_bigmem_alloc(cap * sizeof *q->item);
	q->head = lz_bigmem_alloc((q->days + 1) * sizeof *q->head);
	q->near = malloc(q->capnear * sizeof *q->near);
	if (!q->item || !q->head || !q->near) {
		lz_calendar_free(q);
		return lz_error(LZ_ENOMEM, "no memory for a calendar of %zu items", cap), NULL;
	}
	lz_calendar_clear(q, 0);
	return q;
}

void lz_calendar_free(lz_calendar *q)
{
	if (!q)
		return;
	lz_bigmem_free(q->item);
	lz_bigmem_free(q->head);
	free(q->near);
	free(q);
}

void lz_calendar_clear(lz_calendar *q, double origin)
{
	q->n = q->ring = q->nnear = 0;
	q->origin = origin;
	q->today = q->resorted = 0;
	q->ahead = NONE;
	for (size_t i = 0; i < q->cap; i++)
		q->item[i].key = NAN;
	for (uint32_t d = 0; d <= q->days; d++)
		q->head[d] = NONE;
	q->near[0] = (lz_heap_node){INFINITY, 0};
}

/* One step along tomorrow's list, asking the memory for the next item: its items are
 * read one after the other when tomorrow comes, each address in the one before, so
 * that walk would wait on every miss in turn; walked a step per change today (a day
 * sees about as many changes as it has items), the misses come in the shadow of
 * today's work. A hint only. O(1). */
static void look_ahead(lz_calendar *q)
{
	uint32_t id = q->ahead == NONE ? q->head[slot_of(q, q->today + 1)] : q->item[q->ahead].next;
	q->ahead = id;
	if (id != NONE)
		__builtin_prefetch(&q->item[id]);
}

int lz_calendar_set(lz_calendar *q, uint32_t id, double t)
{
	if (!isnan(q->item[id].key))
		unplace(q, id);
	else
		q->n++;
	q->item[id].key = t;
	q->changes++;
	int st = place(q, id);
	if (st == LZ_OK && q->nnear == 0)
		st = new_day(q);
	look_ahead(q);
	return st;
}

int lz_calendar_layout(lz_calendar *q, double width)
{
	if (!(width > 0) || !isfinite(width))
		return lz_error(LZ_EINVAL, "calendar day width %g must be positive and finite", width);
	double *keep = malloc(q->cap * sizeof *keep);
	if (!keep)
		return lz_error(LZ_ENOMEM, "no memory to lay out a calendar of %zu items", q->cap);
	double first = INFINITY;
	for (size_t i = 0; i < q->cap; i++) {
		keep[i] = q->item[i].key;
		if (keep[i] < first)  /* NaN: no key */
			first = keep[i];
	}
	size_t n = q->n;
	q->width = width;
	q->inv = 1 / width;
	lz_calendar_clear(q, isfinite(first) ? first : 0);
	int st = LZ_OK;
	for (size_t i = 0; i < q->cap && st == LZ_OK; i++)
		if (!isnan(keep[i])) {
			q->item[i].key = keep[i];
			q->n++;
			st = place(q, (uint32_t)i);
		}
	free(keep);
	if (st == LZ_OK && q->nnear == 0)
		st = new_day(q);
	if (st == LZ_OK && q->n != n)
		st = lz_error(LZ_EDOM, "the calendar lost items while laid out again (%zu of %zu)",
		              q->n, n);
	return st;
}

int lz_calendar_shift(lz_calendar *q, double dt)
{
	for (size_t i = 0; i < q->cap; i++)
		q->item[i].key -= dt;  /* NaN stays NaN */
	/* days of about per_day changes each at the rate since the last shift */
	double width = dt > 0 && q->changes > 64 ? q->per_day * dt / (double)q->changes : q->width;
	q->changes = 0;
	return lz_calendar_layout(q, width);
}

int lz_calendar_renumber(lz_calendar *q, const uint32_t *to)
{
	size_t cap = q->cap;
	lz_cal_item *item = lz_bigmem_alloc(cap * sizeof *item);
	if (!item)
		return lz_error(LZ_ENOMEM, "no memory to renumber a calendar of %zu items", cap);
	for (size_t i = 0; i < cap; i++) {
		lz_cal_item x = q->item[i];
		item[to[i]] = (lz_cal_item){x.key, x.next == NONE ? NONE : to[x.next],
		                            x.prev == NONE ? NONE : to[x.prev]};
	}
	lz_bigmem_free(q->item);
	q->item = item;
	for (uint32_t d = 0; d <= q->days; d++)
		if (q->head[d] != NONE)
			q->head[d] = to[q->head[d]];
	for (size_t k = 0; k < q->nnear; k++)
		q->near[k].id = to[q->near[k].id];
	return LZ_OK;
}

/* ---- the check ---- */

int lz_calendar_audit(const lz_calendar *q)
{
	size_t n = 0, ring = 0;
	uint8_t *seen = calloc(q->cap, 1);
	if (!seen)
		return lz_error(LZ_ENOMEM, "no memory to audit a calendar of %zu items", q->cap);
	int st = LZ_OK;
	for (size_t k = 0; k < q->nnear && st == LZ_OK; k++) {
		uint32_t id = q->near[k].id;
		if (id >= q->cap || seen[id]++ || q->near[k].t != q->item[id].key ||
		    place_of(q, day_of(q, q->item[id].key)) != NEAR)
			st = lz_error(LZ_EDOM, "calendar: today's heap holds item %u at %zu, twice, with "
			              "another key, or though its day is not today", id, k);
		else if (k > 0 && q->near[k].t < q->near[(k - 1) / 2].t)
			st = lz_error(LZ_EDOM, "calendar: today's heap is out of order at %zu", k);
	}
	for (uint32_t d = 0; d <= q->days && st == LZ_OK; d++) {
		uint32_t before = NONE;
		for (uint32_t id = q->head[d]; id != NONE && st == LZ_OK; id = q->item[id].next) {
			int64_t day = day_of(q, q->item[id].key);
			int want = d == q->days ? OVER : RING;
			if (seen[id]++ || q->item[id].prev != before || place_of(q, day) != want ||
			    (want == RING && slot_of(q, day) != d))
				st = lz_error(LZ_EDOM, "calendar: list %u holds item %u (day %lld, today "
				              "%lld), which belongs elsewhere, is listed twice, or has a "
				              "broken link", d, id, (long long)day, (long long)q->today);
			before = id;
			ring += want == RING;
		}
	}
	for (size_t id = 0; id < q->cap && st == LZ_OK; id++) {
		n += !isnan(q->item[id].key);
		if (!isnan(q->item[id].key) && !seen[id])
			st = lz_error(LZ_EDOM, "calendar: item %zu has a key but is in no list", id);
	}
	free(seen);
	if (st == LZ_OK && (n != q->n || ring != q->ring))
		st = lz_error(LZ_EDOM, "calendar: it counts %zu items (%zu in the ring), they are %zu "
		              "(%zu)", q->n, q->ring, n, ring);
	if (st == LZ_OK && q->nnear == 0 && q->ring > 0)
		st = lz_error(LZ_EDOM, "calendar: today is empty but the ring holds %zu items",
		              q->ring);
	return st;
}
