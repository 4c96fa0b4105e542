/* interrupt.h — a run stopped by SIGINT, SIGTERM or SIGHUP removes its partial
 * directory before it ends, so that an interrupted run leaves nothing behind, and the
 * previous run in its place, if any, as it was.
 *
 * While the guard is on, the signals are blocked and taken by a thread of its own
 * (sigwait), which may remove files safely — a signal handler may not. That thread
 * moves the partial directory out of the run's way, removes it, says so on stderr and
 * ends the process by the same signal with its default action (the shell sees "killed
 * by SIGINT", status 130). What the run does to its directory's name — lz_rundir_begin,
 * lz_rundir_commit, lz_rundir_abort — it does between hold and release, which the
 * thread waits for.
 */
#ifndef LZ_INTERRUPT_H
#define LZ_INTERRUPT_H

#include <pthread.h>
#include <signal.h>

#include "lz/output.h"

typedef struct {
	lz_rundir *dir;        /* the run directory (its tmp is removed when interrupted) */
	int committed;         /* set by the run once the directory is committed */
	int stop;              /* set by lz_guard_end: the thread is to end */
	pthread_t thread;      /* the thread that waits for the signals */
	pthread_mutex_t lock;  /* held by the run around begin, commit and abort, and by
	                          the thread from a signal on */
	sigset_t signals, old; /* the signals taken (and the thread's stop signal,
	                          SIGUSR2); the mask before lz_guard_begin */
	int active;            /* 1 while the thread runs */
} lz_guard;

/* Block the signals in the calling thread and start the thread that waits for them.
 * Without the resources for a thread the run goes on unguarded (hold and release do
 * nothing). dir's tmp must be empty or valid from now on. */
void lz_guard_begin(lz_guard *g, lz_rundir *dir);
/* No interruption between these two. */
void lz_guard_hold(lz_guard *g);
void lz_guard_release(lz_guard *g);
/* Stop the thread and restore the mask: a signal that comes later has its usual effect. */
void lz_guard_end(lz_guard *g);

#endif
