/* lz/msg.h — messages between the ranks of a parallel run: one API, two back-ends.
 *
 * A run has P ranks, 0 .. P-1. A rank sends a message (a few bytes) to another rank
 * and polls for the messages sent to it; a message is delivered exactly once, and two
 * messages from one rank to another arrive in the order they were sent (MPI's
 * non-overtaking rule) — nothing else about their order is promised. A reduction
 * (the minimum, maximum or sum of a few doubles over all ranks) is started by every
 * rank and completes on every rank, without blocking any of them in between.
 *
 * The stub back-end (lz_stub) runs the P ranks inside one process, one after the
 * other, as its scheduling policy picks them: round robin; a seeded random
 * interleaving; one rank running far ahead of the others; or virtual time, which
 * models a machine (a cost per event, per message and a latency) so that a run can
 * predict the speed-up of more ranks than there are cores. Messages are delayed by a
 * seeded number of scheduler turns (or by the latency, in virtual time). The same
 * seed gives the same interleaving, bit for bit. A deadlock — every rank waiting and
 * nothing that could wake one — is an error with a message, never a hang. The tests
 * and the students use this back-end; it needs no MPI.
 *
 * The MPI back-end (lz/msg_mpi.h, linked into build/bin/lz-mpi only, so that liblz.a
 * needs no MPI) gives each process its own rank on a communicator of its own.
 *
 * Sizes: a message holds at most LZ_MSG_MAX bytes; a reduction at most LZ_MSG_RMAX
 * doubles. The clock is in seconds: wall time with MPI, virtual time with the stub's
 * virtual-time policy, scheduler turns otherwise.
 */
#ifndef LZ_MSG_H
#define LZ_MSG_H

#include <stddef.h>
#include <stdint.h>

#define LZ_MSG_MAX 4096
#define LZ_MSG_RMAX 8

typedef enum { LZ_MSG_MINIMUM, LZ_MSG_MAXIMUM, LZ_MSG_SUM } lz_msg_op;

/* What a rank has sent and received so far. */
typedef struct {
	uint64_t sent, received;            /* messages */
	uint64_t bytes_sent, bytes_received;
	uint64_t reductions;                /* completed */
} lz_msg_counts;

/* One rank's end of the connection; the back-end's own functions make it. */
typedef struct lz_msg lz_msg;

/* What a back-end provides (the functions below call these). */
typedef struct {
	int (*send)(lz_msg *m, int to, const void *data, size_t n);
	int (*poll)(lz_msg *m, int *from, void *buf, size_t cap, size_t *n);
	int (*reduce_start)(lz_msg *m, lz_msg_op op, const double *in, size_t n);
	int (*reduce_test)(lz_msg *m, double *out);
	double (*clock)(const lz_msg *m);
	void (*charge)(lz_msg *m, double events);
} lz_msg_backend;

struct lz_msg {
	const lz_msg_backend *b;
	int rank, size;
	lz_msg_counts counts;
	void *impl;  /* the back-end's own state */
};

static inline int lz_msg_rank(const lz_msg *m) { return m->rank; }
static inline int lz_msg_size(const lz_msg *m) { return m->size; }
static inline lz_msg_counts lz_msg_counters(const lz_msg *m) { return m->counts; }

/* Send n <= LZ_MSG_MAX bytes to rank `to` (another rank): the bytes are copied, the
 * call returns at once. LZ_OK; LZ_EINVAL naming the bad rank or size. */
int lz_msg_send(lz_msg *m, int to, const void *data, size_t n);

/* The next message that has arrived for this rank: 1 with its sender in *from and
 * its bytes in buf (*n of them); 0 when none has arrived yet. A message larger than
 * cap is an error (LZ_EINVAL, it stays queued). */
int lz_msg_poll(lz_msg *m, int *from, void *buf, size_t cap, size_t *n);

/* Start a reduction of in[0 .. n-1] (n <= LZ_MSG_RMAX, the same n and op on every
 * rank), element by element over all ranks. One reduction at a time per rank. Then
 * lz_msg_reduce_test returns 0 until every rank has started it, and 1 (with the
 * result in out) once, after which the next may start. LZ_EINVAL on misuse. */
int lz_msg_reduce_start(lz_msg *m, lz_msg_op op, const double *in, size_t n);
int lz_msg_reduce_test(lz_msg *m, double *out);

/* The rank's clock in seconds (see above). */
double lz_msg_clock(const lz_msg *m);

/* Tell the back-end that this rank did `events` events of work since the last call:
 * the stub's virtual-time policy advances the rank's clock by their cost; MPI ignores
 * it. */
void lz_msg_charge(lz_msg *m, double events);

/* ---- the stub back-end ---- */

typedef enum {
	LZ_STUB_ROUND_ROBIN,  /* every rank one turn in order */
	LZ_STUB_RANDOM,       /* a random rank each turn (seeded) */
	LZ_STUB_AHEAD,        /* as random, but rank `ahead` takes `ahead_turns` turns at a time */
	LZ_STUB_VIRTUAL       /* the rank with the earliest virtual clock runs next */
} lz_stub_policy;

typedef struct {
	int ranks;               /* 1 <= P <= LZ_STUB_RANKS_MAX */
	lz_stub_policy policy;
	unsigned long seed;      /* of the interleaving and the delays */
	int delay;               /* messages wait 0 .. delay turns before they can arrive */
	int ahead, ahead_turns;  /* LZ_STUB_AHEAD: which rank, how many turns in a row */
	/* LZ_STUB_VIRTUAL, in seconds: */
	double cost_event;       /* one event of work */
	double cost_message;     /* sending or receiving one message */
	double latency;          /* from send to the earliest arrival */
} lz_stub_params;

#define LZ_STUB_RANKS_MAX 1024

/* What a rank's work function says of itself after one turn. */
typedef enum { LZ_WORK_BUSY, LZ_WORK_WAIT, LZ_WORK_DONE } lz_work;

/* One turn of rank `rank`: do a little (some events, some messages), set *state, and
 * return LZ_OK or an error code. */
typedef int lz_work_fn(int rank, void *arg, lz_work *state);

typedef struct lz_stub lz_stub;

/* P ranks in one process. NULL with lz_error on a bad parameter (naming its range)
 * or no memory. */
lz_stub *lz_stub_alloc(const lz_stub_params *p);
void lz_stub_free(lz_stub *s);

/* Rank r's end (0 <= r < P), owned by the stub. */
lz_msg *lz_stub_rank(lz_stub *s, int r);

/* Run until every rank is done: each turn the policy picks a rank that is not done
 * and calls work on it. LZ_OK when all are done; the work's own error code when it
 * returns one; LZ_EDOM with lz_error on a deadlock (every rank that is not done
 * waits, no message is on its way and no reduction can complete), which names what
 * each rank waits for. */
int lz_stub_run(lz_stub *s, lz_work_fn *work, void *arg);

/* The stub's clock: the largest rank clock (virtual time), or the turns so far. */
double lz_stub_time(const lz_stub *s);

#endif
