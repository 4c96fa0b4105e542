/* timer.c — wall and CPU clocks in seconds. */
#include <time.h>

#include "lz/timer.h"

static double clock_seconds(clockid_t id)
{
	struct timespec ts;
	clock_gettime(id, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double lz_wall_now(void)
{
	return clock_seconds(CLOCK_MONOTONIC);
}

double lz_cpu_now(void)
{
	return clock_seconds(CLOCK_PROCESS_CPUTIME_ID);
}
