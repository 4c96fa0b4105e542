/* interrupt.c — an interrupted run removes its partial directory (interrupt.h). */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "interrupt.h"

/* The signal lz_guard_end sends the thread to end it (a cancelled thread trips the
 * address sanitizer); one that comes from elsewhere while the guard is on is ignored. */
#define STOP SIGUSR2

/* The partial directory moved aside first, so that a file the run opens meanwhile
 * cannot land in it while it is being removed. */
static void remove_partial(lz_rundir *d)
{
	char doomed[sizeof d->tmp + 16];
	snprintf(doomed, sizeof doomed, "%s.removing", d->tmp);
	if (rename(d->tmp, doomed) == 0)
		lz_rmtree(doomed);
	else
		lz_rundir_abort(d);
	d->tmp[0] = '\0';
}

/* Wait for a signal, clean up, end by that signal; or end when lz_guard_end says so
 * (STOP, with the flag set). The lock is never given back after a signal: the run can
 * no longer commit, nor return and exit before the directory is gone. */
static void *guard_thread(void *arg)
{
	lz_guard *g = arg;
	int sig = 0;
	while (sigwait(&g->signals, &sig) == 0 && sig == STOP) {
		pthread_mutex_lock(&g->lock);
		int stop = g->stop;
		pthread_mutex_unlock(&g->lock);
		if (stop)
			return NULL;
	}
	pthread_mutex_lock(&g->lock);
	char msg[sizeof g->dir->final + 160];
	if (g->dir->tmp[0]) {
		remove_partial(g->dir);
		snprintf(msg, sizeof msg, "\nlz: interrupted (%s): the partial run is removed, "
		         "%s is as it was\n", strsignal(sig), g->dir->final);
	} else if (g->committed) {
		snprintf(msg, sizeof msg, "\nlz: interrupted (%s) after the run was complete: "
		         "results in %s/\n", strsignal(sig), g->dir->final);
	} else {
		snprintf(msg, sizeof msg, "\nlz: interrupted (%s): nothing was written\n",
		         strsignal(sig));
	}
	if (write(STDERR_FILENO, msg, strlen(msg)) < 0)
		msg[0] = '\0';  /* no one to tell: the process ends all the same */
	signal(sig, SIG_DFL);
	sigset_t one;
	sigemptyset(&one);
	sigaddset(&one, sig);
	pthread_sigmask(SIG_UNBLOCK, &one, NULL);
	raise(sig);
	_exit(128 + sig);  /* not reached: the default action ends the process */
}

void lz_guard_begin(lz_guard *g, lz_rundir *dir)
{
	g->dir = dir;
	g->committed = 0;
	g->stop = 0;
	g->active = 0;
	sigemptyset(&g->signals);
	sigaddset(&g->signals, STOP);
	sigaddset(&g->signals, SIGINT);
	sigaddset(&g->signals, SIGTERM);
	sigaddset(&g->signals, SIGHUP);
	if (pthread_mutex_init(&g->lock, NULL) != 0)
		return;
	pthread_sigmask(SIG_BLOCK, &g->signals, &g->old);
	if (pthread_create(&g->thread, NULL, guard_thread, g) != 0) {
		pthread_sigmask(SIG_SETMASK, &g->old, NULL);
		pthread_mutex_destroy(&g->lock);
		return;
	}
	g->active = 1;
}

void lz_guard_hold(lz_guard *g)
{
	if (g->active)
		pthread_mutex_lock(&g->lock);
}

void lz_guard_release(lz_guard *g)
{
	if (g->active)
		pthread_mutex_unlock(&g->lock);
}

void lz_guard_end(lz_guard *g)
{
	if (!g->active)
		return;
	/* A thread that took a signal first ends the process instead. */
	pthread_mutex_lock(&g->lock);
	g->stop = 1;
	pthread_mutex_unlock(&g->lock);
	pthread_kill(g->thread, STOP);
	pthread_join(g->thread, NULL);
	pthread_mutex_destroy(&g->lock);
	pthread_sigmask(SIG_SETMASK, &g->old, NULL);
	g->active = 0;
}
