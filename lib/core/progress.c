/* progress.c — a '\r' progress line on stderr, only for a terminal, <= 5 per second. */
#include <stdio.h>
#include <unistd.h>

#include "lz/progress.h"
#include "lz/timer.h"

#define LZ_PROGRESS_EVERY 1024  /* updates between clock reads */
#define LZ_PROGRESS_GAP 0.2     /* seconds between prints */

void lz_progress_begin(lz_progress *p, const char *label, double total)
{
	p->label = label ? label : "";
	p->total = total;
	p->start = lz_wall_now();
	p->last = p->start;
	p->calls = 0;
	p->active = isatty(STDERR_FILENO);
}

/* "12.3 s", "4 min 05 s", "2 h 07 min": short enough to keep the line on one row. */
static void progress_time(double s, char *buf, size_t size)
{
	if (!(s >= 0) || s > 1e8)
		snprintf(buf, size, "?");
	else if (s < 60)
		snprintf(buf, size, "%.1f s", s);
	else if (s < 3600)
		snprintf(buf, size, "%d min %02d s", (int)s / 60, (int)s % 60);
	else
		snprintf(buf, size, "%d h %02d min", (int)s / 3600, (int)s % 3600 / 60);
}

void lz_progress_update(lz_progress *p, double done)
{
	if (!p->active || ++p->calls < LZ_PROGRESS_EVERY)
		return;
	p->calls = 0;
	double now = lz_wall_now();
	if (now - p->last < LZ_PROGRESS_GAP)
		return;
	p->last = now;
	double frac = p->total > 0 ? done / p->total : 0;
	frac = frac < 0 ? 0 : frac > 1 ? 1 : frac;
	double elapsed = now - p->start;
	char el[32], eta[32];
	progress_time(elapsed, el, sizeof el);
	progress_time(frac > 0 ? elapsed * (1 - frac) / frac : -1, eta, sizeof eta);
	/* ESC[K (erase to the end of the line) clears what a longer line left. */
	fprintf(stderr, "\r\033[K%s %5.1f%%  %s elapsed, ETA %s", p->label, 100 * frac, el, eta);
	fflush(stderr);
}

void lz_progress_end(lz_progress *p)
{
	/* Nothing was printed unless last moved past start. */
	if (p->active && p->last > p->start) {
		fputs("\r\033[K", stderr);
		fflush(stderr);
	}
}
