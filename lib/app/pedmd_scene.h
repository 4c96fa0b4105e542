/* pedmd_scene.h — the parallel run a `method = pedmd` scene describes (method_pedmd.c):
 * the system of the edmd keys, started and equilibrated serially, and how the ranks
 * run it. Shared by the `lz` program (every rank in one process, over the stub
 * back-end) and `lz-mpi` (one process per rank). */
#ifndef LZ_PEDMD_SCENE_H
#define LZ_PEDMD_SCENE_H

#include "lz/edmd.h"
#include "lz/msg.h"
#include "lz/pedmd.h"
#include "scene.h"

typedef struct {
	lz_edmd *system;          /* started, equilibrated, clock at 0, rebase_auto = 0 */
	lz_edmd *reference;       /* check: the same system made again (the same bits) */
	int kind;                 /* LZ_PEDMD_ROWS or LZ_PEDMD_MORTON */
	lz_stub_params stub;      /* ranks, schedule, seed, delays and costs */
	lz_pedmd_params params;
	double t_stop;            /* absolute: the scene's `time` */
	int check;                /* 1: compare with the serial run */
} lz_pedmd_scene;

/* The run of bound scene s (method pedmd); build = 0: all of it but the systems (a
 * process that takes its share from another, lz-mpi). LZ_OK, or an error at the key to
 * blame. O(n log n + equilibration). */
int lz_pedmd_scene_make(const lz_scene *s, int quiet, int build, lz_pedmd_scene *out);
void lz_pedmd_scene_free(lz_pedmd_scene *p);

/* balance = pilot: the cuts cut[0 .. P] from the committed events of a first run of
 * the same time over the stub (in one process; the load of a cell does not depend on
 * the schedule), *moved = 1 when they pay (lz_pedmd_rebalance), and in *ratio the
 * busiest rank's share under them over that under the even cuts. LZ_OK or an error.
 * O(the run). */
int lz_pedmd_scene_pilot(const lz_pedmd_scene *p, uint32_t *cut, int *moved, double *ratio);

/* The serial run of p's reference to p->t_stop, re-based where the ranks re-base
 * (lz_pedmd_serial): what the ranks must commit bit for bit. LZ_OK or an error.
 * O(events log n). */
int lz_pedmd_scene_serial(lz_pedmd_scene *p);

/* How many particles of a (the gathered parallel run) differ from b (the serial run)
 * in position, velocity or time, bit for bit. O(n). */
size_t lz_pedmd_scene_differ(const lz_edmd *a, const lz_edmd *b);

#endif
