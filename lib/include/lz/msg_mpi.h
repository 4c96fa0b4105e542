/* lz/msg_mpi.h — the MPI back-end of lz/msg.h: one process per rank.
 *
 * lz_msg_mpi_open gives this process's end of a connection over a duplicate of
 * MPI_COMM_WORLD, a communicator of its own: nothing else the program sends (the
 * gathering of results, another library) can match its messages or its reductions.
 * The rank and the number of ranks are this process's in MPI_COMM_WORLD.
 *
 * Messages. A send copies the bytes into a buffer of a pool and starts MPI_Isend from
 * there; buffers whose sends have completed are reclaimed (MPI_Testsome) when the pool
 * runs out, and the pool doubles only when every buffer is still in flight: in a
 * steady state a message costs no allocation. A poll is MPI_Iprobe from any rank, then
 * MPI_Recv of what it found. MPI's non-overtaking rule gives the order that lz/msg.h
 * promises; nothing is delayed on purpose (the stub's job).
 * Reductions. MPI_Iallreduce of doubles (MPI_MIN, MPI_MAX or MPI_SUM), then MPI_Test:
 * no rank blocks while the others catch up.
 * Clock: MPI_Wtime, wall seconds. charge() does nothing.
 *
 * The counters (lz_msg_counters) are kept by the API's functions (msg.c), as for the
 * stub. MPI errors are returned, not fatal, on this communicator: they come back as
 * LZ_EIO with MPI's own message and the call that failed.
 *
 * This back-end is compiled with mpicc into build/bin/lz-mpi only, so that liblz.a
 * needs no MPI.
 */
#ifndef LZ_MSG_MPI_H
#define LZ_MSG_MPI_H

#include "lz/msg.h"

/* This process's end: rank and size of MPI_COMM_WORLD, over a duplicate of it.
 * Preconditions: MPI is initialised (MPI_Init) and not finalised; every process of
 * MPI_COMM_WORLD calls this together (MPI_Comm_dup is collective). NULL with lz_error
 * otherwise, or without memory. O(1) memory at first: 64 send buffers of LZ_MSG_MAX
 * bytes (256 KiB), doubling when all are in flight. */
lz_msg *lz_msg_mpi_open(void);

/* Wait for the sends still in flight (every one must be received: at the end of a
 * run, after its last cut, none is pending) and for a reduction still running (every
 * rank must have started it), free the communicator and the buffers. Collective, as
 * open (MPI_Comm_free). NULL: nothing. */
void lz_msg_mpi_close(lz_msg *m);

#endif
