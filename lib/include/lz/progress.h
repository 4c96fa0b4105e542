/* lz/progress.h — a one-line progress report on stderr for long runs.
 *
 * Prints only when stderr is a terminal, at most five times a second, so it costs
 * nothing in tests, pipes and CI logs. Call lz_progress_update from the outer loop
 * (it reads the clock only every 1024 calls).
 */
#ifndef LZ_PROGRESS_H
#define LZ_PROGRESS_H

typedef struct {
	const char *label;  /* what is running, e.g. "verlet" */
	double total;       /* the amount of work at 100 % (steps, events, ...) */
	double start;       /* wall time at lz_progress_begin */
	double last;        /* wall time of the last print */
	unsigned calls;     /* updates since the last clock read */
	int active;         /* stderr is a terminal */
} lz_progress;

void lz_progress_begin(lz_progress *p, const char *label, double total);
void lz_progress_update(lz_progress *p, double done);
/* Erases the line. */
void lz_progress_end(lz_progress *p);

#endif
