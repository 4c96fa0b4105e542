/* msg_mpi.c — the MPI back-end of the message API (lz/msg_mpi.h): one process per rank.
 *
 * The checks and the counters are the API's (msg.c); here are only the back-end's six
 * functions. Sends go out of a pool of LZ_MSG_MAX-byte buffers: buffer k is free (on
 * the stack `idle`, req[k] = MPI_REQUEST_NULL) or in flight (req[k] its MPI_Isend).
 * Buffers are never moved while MPI holds them: the pool grows by a new block of as
 * many buffers as it has, and only the arrays of handles and pointers are reallocated.
 * Compiled with mpicc, outside liblz.a (the Makefile's lz-mpi rule).
 */
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>

#include "lz/error.h"
#include "lz/msg_mpi.h"

#define POOL_FIRST 64  /* buffers at first (a power of two: see block_start) */
#define TAG 1          /* every message: the communicator is ours alone */

typedef struct {
	lz_msg m;
	MPI_Comm comm;
	/* the send pool */
	int cap;                 /* buffers */
	MPI_Request *req;        /* req[k]: buffer k's send, or MPI_REQUEST_NULL */
	unsigned char **buf;     /* buf[k]: LZ_MSG_MAX bytes */
	int *idle, nidle;        /* the free buffers */
	int *done;               /* scratch for MPI_Testsome */
	/* one reduction at a time */
	int in_round;
	size_t nround;
	MPI_Request round;
	double rin[LZ_MSG_RMAX], rout[LZ_MSG_RMAX];  /* MPI owns them while in_round */
} mpi_end;

static mpi_end *end_of(const lz_msg *m) { return m->impl; }

/* An MPI call that failed: LZ_EIO with what was called and MPI's own words. */
static int mpi_fail(const mpi_end *x, int rc, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
static int mpi_fail(const mpi_end *x, int rc, const char *fmt, ...)
{
	char call[256], text[MPI_MAX_ERROR_STRING];
	int len = 0;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(call, sizeof call, fmt, ap);
	va_end(ap);
	if (MPI_Error_string(rc, text, &len) != MPI_SUCCESS)
		snprintf(text, sizeof text, "MPI error code %d", rc);
	return lz_error(LZ_EIO, "rank %d: %s failed: %s", x->m.rank, call, text);
}

/* Buffer k begins a block of its own (freed as one): 0, then POOL_FIRST, 2 POOL_FIRST,
 * 4 POOL_FIRST, ... since every block doubles the pool. */
static int block_start(int k) { return k == 0 || (k >= POOL_FIRST && (k & (k - 1)) == 0); }

/* Double the pool (POOL_FIRST buffers at first), every new buffer free. */
static int grow(mpi_end *x)
{
	if (x->cap > INT_MAX / 2)
		return lz_error(LZ_ENOMEM, "rank %d: %d messages in flight, the most a pool holds",
		                x->m.rank, x->cap);
	int cap = x->cap ? 2 * x->cap : POOL_FIRST;
	size_t more = (size_t)(cap - x->cap);
	MPI_Request *req = realloc(x->req, (size_t)cap * sizeof *req);
	if (req)
		x->req = req;
	unsigned char **buf = req ? realloc(x->buf, (size_t)cap * sizeof *buf) : NULL;
	if (buf)
		x->buf = buf;
	int *idle = buf ? realloc(x->idle, (size_t)cap * sizeof *idle) : NULL;
	if (idle)
		x->idle = idle;
	int *done = idle ? realloc(x->done, (size_t)cap * sizeof *done) : NULL;
	if (done)
		x->done = done;
	unsigned char *block = done ? malloc(more * LZ_MSG_MAX) : NULL;
	if (!block)  /* the arrays may be longer than cap now: harmless */
		return lz_error(LZ_ENOMEM, "rank %d: no memory for %d send buffers of %d bytes",
		                x->m.rank, cap, LZ_MSG_MAX);
	for (int k = x->cap; k < cap; k++) {
		x->req[k] = MPI_REQUEST_NULL;
		x->buf[k] = block + (size_t)(k - x->cap) * LZ_MSG_MAX;
		x->idle[x->nidle++] = k;
	}
	x->cap = cap;
	return LZ_OK;
}

/* The buffers whose sends have completed back on the idle stack. O(cap). */
static int reclaim(mpi_end *x)
{
	int out = 0;
	int rc = MPI_Testsome(x->cap, x->req, &out, x->done, MPI_STATUSES_IGNORE);
	if (rc != MPI_SUCCESS)
		return mpi_fail(x, rc, "MPI_Testsome of %d sends", x->cap);
	for (int k = 0; out != MPI_UNDEFINED && k < out; k++)
		x->idle[x->nidle++] = x->done[k];
	return LZ_OK;
}

static int mpi_send(lz_msg *m, int to, const void *data, size_t n)
{
	mpi_end *x = end_of(m);
	int st;
	if (x->nidle == 0 && (st = reclaim(x)) != LZ_OK)
		return st;
	if (x->nidle == 0 && (st = grow(x)) != LZ_OK)
		return st;
	int k = x->idle[--x->nidle];
	if (n > 0)
		memcpy(x->buf[k], data, n);
	int rc = MPI_Isend(x->buf[k], (int)n, MPI_BYTE, to, TAG, x->comm, &x->req[k]);
	if (rc != MPI_SUCCESS) {
		x->req[k] = MPI_REQUEST_NULL;
		x->idle[x->nidle++] = k;
		return mpi_fail(x, rc, "MPI_Isend of %zu bytes to rank %d", n, to);
	}
	return LZ_OK;
}

static int mpi_poll(lz_msg *m, int *from, void *buf, size_t cap, size_t *n)
{
	mpi_end *x = end_of(m);
	MPI_Status status;
	int flag = 0, count = 0;
	int rc = MPI_Iprobe(MPI_ANY_SOURCE, TAG, x->comm, &flag, &status);
	if (rc != MPI_SUCCESS)
		return mpi_fail(x, rc, "MPI_Iprobe");
	if (!flag)
		return 0;
	if ((rc = MPI_Get_count(&status, MPI_BYTE, &count)) != MPI_SUCCESS)
		return mpi_fail(x, rc, "MPI_Get_count of a message from rank %d", status.MPI_SOURCE);
	if ((size_t)count > cap)  /* probed, not received: it stays queued */
		return lz_error(LZ_EINVAL, "rank %d: a message of %d bytes from rank %d does not "
		                "fit the %zu bytes given", m->rank, count, status.MPI_SOURCE, cap);
	/* One thread: the first message from that source with our tag is the one probed. */
	rc = MPI_Recv(buf, count, MPI_BYTE, status.MPI_SOURCE, TAG, x->comm, MPI_STATUS_IGNORE);
	if (rc != MPI_SUCCESS)
		return mpi_fail(x, rc, "MPI_Recv of %d bytes from rank %d", count, status.MPI_SOURCE);
	*from = status.MPI_SOURCE;
	*n = (size_t)count;
	return 1;
}

static int mpi_reduce_start(lz_msg *m, lz_msg_op op, const double *in, size_t n)
{
	mpi_end *x = end_of(m);
	if (x->in_round)
		return lz_error(LZ_EINVAL, "rank %d started a reduction before the last one "
		                "completed", m->rank);
	MPI_Op o = op == LZ_MSG_MINIMUM ? MPI_MIN : op == LZ_MSG_MAXIMUM ? MPI_MAX : MPI_SUM;
	memcpy(x->rin, in, n * sizeof *in);
	int rc = MPI_Iallreduce(x->rin, x->rout, (int)n, MPI_DOUBLE, o, x->comm, &x->round);
	if (rc != MPI_SUCCESS)
		return mpi_fail(x, rc, "MPI_Iallreduce of %zu doubles", n);
	x->in_round = 1;
	x->nround = n;
	return LZ_OK;
}

static int mpi_reduce_test(lz_msg *m, double *out)
{
	mpi_end *x = end_of(m);
	int flag = 0;
	if (!x->in_round)
		return lz_error(LZ_EINVAL, "rank %d tested a reduction it did not start", m->rank);
	int rc = MPI_Test(&x->round, &flag, MPI_STATUS_IGNORE);
	if (rc != MPI_SUCCESS)
		return mpi_fail(x, rc, "MPI_Test of a reduction of %zu doubles", x->nround);
	if (!flag)
		return 0;
	memcpy(out, x->rout, x->nround * sizeof *out);
	x->in_round = 0;
	return 1;
}

static double mpi_clock(const lz_msg *m) { return MPI_Wtime(); }

static void mpi_charge(lz_msg *m, double events) {}

static const lz_msg_backend mpi_backend = {
	mpi_send, mpi_poll, mpi_reduce_start, mpi_reduce_test, mpi_clock, mpi_charge,
};

/* The pool's memory (no MPI left in it). */
static void release(mpi_end *x)
{
	for (int k = 0; k < x->cap; k++)
		if (block_start(k))
			free(x->buf[k]);
	free(x->req);
	free(x->buf);
	free(x->idle);
	free(x->done);
	free(x);
}

lz_msg *lz_msg_mpi_open(void)
{
	int init = 0, fin = 0;
	MPI_Initialized(&init);
	MPI_Finalized(&fin);
	if (!init || fin)
		return lz_error(LZ_EINVAL, "the MPI back-end needs MPI initialised (MPI_Init) and "
		                "not yet finalised"), NULL;
	mpi_end *x = calloc(1, sizeof *x);
	if (!x)
		return lz_error(LZ_ENOMEM, "no memory for the MPI back-end"), NULL;
	MPI_Comm_rank(MPI_COMM_WORLD, &x->m.rank);
	MPI_Comm_size(MPI_COMM_WORLD, &x->m.size);
	if (grow(x) != LZ_OK) {  /* before the collective: nothing to undo in MPI */
		release(x);
		return NULL;
	}
	int rc = MPI_Comm_dup(MPI_COMM_WORLD, &x->comm);
	if (rc == MPI_SUCCESS)
		rc = MPI_Comm_set_errhandler(x->comm, MPI_ERRORS_RETURN);
	if (rc != MPI_SUCCESS) {
		mpi_fail(x, rc, "MPI_Comm_dup of MPI_COMM_WORLD");
		release(x);
		return NULL;
	}
	x->m.b = &mpi_backend;
	x->m.impl = x;
	x->round = MPI_REQUEST_NULL;
	return &x->m;
}

void lz_msg_mpi_close(lz_msg *m)
{
	if (!m)
		return;
	mpi_end *x = end_of(m);
	MPI_Waitall(x->cap, x->req, MPI_STATUSES_IGNORE);
	if (x->in_round)  /* every rank has started it (a precondition of the protocol) */
		MPI_Wait(&x->round, MPI_STATUS_IGNORE);
	MPI_Comm_free(&x->comm);
	release(x);
}
