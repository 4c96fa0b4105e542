/* lz/calendar.h — a calendar queue of events: one key (an event time) per item, the
 * earliest first, in O(1) per change on average (Brown, Commun. ACM 31, 1220 (1988);
 * the event lists of DynamO and of Smallenburg, Eur. Phys. J. E 45, 22 (2022), §2.3).
 *
 * A heap orders every event against every other; an event loop only ever needs the
 * earliest. The calendar cuts time into days of `width`: day k holds the events with
 * floor((t - origin) / width) = k. The events of today sit in a small binary heap
 * (near[]), the only ones kept in order; those of the next `days` - 1 days wait,
 * unordered, in a ring of doubly linked lists, one per day; later ones (and those that
 * never happen, at +INFINITY) in an overflow list. A change of key unlinks the item
 * and links it again — O(1) unless it lands today. When today runs out, the next
 * day's list becomes the heap (O(events of that day)); every `days` days the overflow
 * is sorted out again. The day of a key is a non-decreasing function of the key (a
 * difference, a product and a floor, each monotone), so that an earlier key never
 * lands on a later day: the order is exact, ties apart.
 *
 * Sized right, a day holds a few dozen events (more past 1.3·10^5 items, where the ring
 * stops at 2^15 days, whose heads stay in cache: 244 at 10^6) and nearly every change
 * lands in the ring: lz_calendar_alloc takes the width from the expected rate of
 * events, and lz_calendar_shift (a re-based clock) lays the calendar out again with the
 * width the events since the last shift call for. Items are the integers 0 .. cap-1.
 *
 * Invariants: every item with a key is in exactly one of near (its day d <= today),
 * the ring (today < d < resorted + days, at slot d mod days) or the overflow (later,
 * or +INFINITY) — where an item is follows from its key, so none is stored; near is a
 * binary heap by key; near is empty only when the ring is too (today is advanced past
 * empty days eagerly), so that the top is near[0].
 *
 * Memory: 8 (key) + 8 (links) bytes per item, 4 per day, 16 per event of today. Cost: top O(1); set O(1) on average (O(log today) when the key lands today);
 * a new day O(its events).
 */
#ifndef LZ_CALENDAR_H
#define LZ_CALENDAR_H

#include <stddef.h>
#include <stdint.h>

#include "lz/heap.h"

/* The end of a list. */
#define LZ_CAL_NONE UINT32_MAX

/* An item: its key, the event time (NaN: it has none; where the item is follows from
 * it — today, the ring or the overflow), and its links in the list of its day (or the
 * overflow's). 16 bytes: a change reads one place of memory, not three. */
typedef struct {
	double key;
	uint32_t next, prev;
} lz_cal_item;

typedef struct {
	size_t n, cap;        /* items with a key; items 0 .. cap-1 */
	double origin;        /* the time of day 0 */
	double width;         /* the length of a day (> 0) */
	double inv;           /* 1 / width */
	int64_t today;        /* the day whose events are in near[] */
	int64_t resorted;     /* today when the overflow was last sorted out: it holds only
	                         days from resorted + days on, and is sorted out again on
	                         the next day that is a multiple of days, before them */
	uint32_t days;        /* the ring's days (a power of two), today's slot included */
	double per_day;       /* the events a day that widths aim at: 32, more when the
	                         ring is at its most days (past 1.3·10^5 items) */
	lz_cal_item *item;    /* item[id]: its key and links, in one place */
	uint32_t *head;       /* head[days]: each day's list; head[days]: the overflow */
	size_t ring;          /* items in the ring (not today, not overflow) */
	lz_heap_node *near;   /* today's events, a binary heap by t */
	size_t nnear, capnear;
	uint64_t changes;     /* lz_calendar_set calls since the last shift (the rate) */
	uint32_t ahead;       /* where the walk along tomorrow's list has come (a hint) */
} lz_calendar;

/* An empty calendar for the items 0 .. cap-1, whose days are about `width` long
 * (> 0: a few dozen events a day at the expected rate, say 32 / (events per time
 * unit)). NULL with lz_error on a bad argument or no memory. O(cap). */
lz_calendar *lz_calendar_alloc(size_t cap, double width);
void lz_calendar_free(lz_calendar *q);

/* Every item out; today = the day of `origin`. O(cap). */
void lz_calendar_clear(lz_calendar *q, double origin);

/* The earliest item and its key: precondition q->n > 0. O(1). */
static inline uint32_t lz_calendar_top(const lz_calendar *q) { return q->near[0].id; }
static inline double lz_calendar_top_t(const lz_calendar *q) { return q->near[0].t; }

/* 1 when id has a key; its key. O(1). */
static inline int lz_calendar_contains(const lz_calendar *q, uint32_t id)
{
	return id < q->cap && q->item[id].key == q->item[id].key;  /* not NaN */
}
static inline double lz_calendar_key(const lz_calendar *q, uint32_t id) { return q->item[id].key; }

/* Give item id the key t (no earlier than the top's, when there is one): inserted, or
 * moved. LZ_OK, or LZ_ENOMEM when today's heap cannot grow. O(1) on average. */
int lz_calendar_set(lz_calendar *q, uint32_t id, double t);

/* Lay every item out again with days of `width` (> 0), today the day of the earliest
 * key. LZ_OK, LZ_EINVAL (a bad width) or LZ_ENOMEM. O(cap + days). */
int lz_calendar_layout(lz_calendar *q, double width);

/* Subtract dt from every key and lay the calendar out again, with days long enough
 * for about 32 changes at the rate of the changes since the last shift (a clock
 * re-based by dt). LZ_OK or LZ_ENOMEM. O(cap + days). */
int lz_calendar_shift(lz_calendar *q, double dt);

/* Rename every item: id becomes to[id] (a permutation of 0 .. cap-1). LZ_OK or
 * LZ_ENOMEM (then nothing changed). O(cap). */
int lz_calendar_renumber(lz_calendar *q, const uint32_t *to);

/* The item most likely next after the top (the earlier child of today's root), or
 * the top itself when today holds one event. For a caller that fetches ahead. O(1). */
static inline uint32_t lz_calendar_second(const lz_calendar *q)
{
	if (q->nnear < 3)
		return q->near[q->nnear - 1].id;
	return q->near[q->near[2].t < q->near[1].t ? 2 : 1].id;
}

/* The items most likely next after the top, as lz_heap_next_items guesses them in
 * today's heap; both the root's earlier child (or the top itself) while today holds
 * fewer than 7 events. For a caller that fetches ahead. O(1). */
static inline void lz_calendar_next_items(const lz_calendar *q, uint32_t *second,
                                          uint32_t *third)
{
	if (q->nnear >= 7)
		lz_heap_nodes_next(q->near, second, third);
	else
		*second = *third = lz_calendar_second(q);
}

/* Ask the memory for what a change of item id's key reads first: its item. A hint.
 * O(1). */
static inline void lz_calendar_prefetch(const lz_calendar *q, uint32_t id)
{
	__builtin_prefetch(&q->item[id]);
}
/* ... and then, its item in the cache (lz_calendar_prefetch an event earlier), the
 * items beside it in its day's list, which unlinking it writes. A hint. O(1). */
static inline void lz_calendar_prefetch_links(const lz_calendar *q, uint32_t id)
{
	const lz_cal_item *x = &q->item[id];
	if (x->prev < q->cap)
		__builtin_prefetch(&q->item[x->prev]);
	if (x->next < q->cap)
		__builtin_prefetch(&q->item[x->next]);
}

/* LZ_OK when the invariants above hold, else LZ_EDOM naming the first broken item.
 * O(cap + days). For tests and guards. */
int lz_calendar_audit(const lz_calendar *q);

#endif
