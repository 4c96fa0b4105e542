/* lz/timer.h — clocks for measuring cost. Seconds, as double. */
#ifndef LZ_TIMER_H
#define LZ_TIMER_H

/* Wall-clock seconds from an arbitrary origin (monotonic; never jumps back). */
double lz_wall_now(void);

/* CPU seconds used by this process so far (user + system). */
double lz_cpu_now(void);

#endif
