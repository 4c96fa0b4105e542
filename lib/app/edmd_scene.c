/* edmd_scene.c — the system of an event-driven scene (edmd_scene.h): its size and box
 * from the keys, its start from a config file or a lattice, its equilibration. */
#include <math.h>
#include <stdlib.h>

#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/progress.h"
#include "lz/reference.h"
#include "config.h"
#include "edmd_scene.h"

#define PROGRESS_EVENTS 256  /* events between progress updates (on a terminal) */

int lz_edmd_scene_particles(const lz_scene *s, const lz_config *c, size_t *n)
{
	if (!lz_scene_has(s, "config")) {
		*n = (size_t)lz_scene_int(s, "n");
		return LZ_OK;
	}
	if (lz_scene_given(s, "n") && (size_t)lz_scene_int(s, "n") != c->n)
		return lz_scene_fail(s, "n", "n = %lld but the config file '%s' has %zu rows: leave "
		                     "n out, the file sets it", lz_scene_int(s, "n"),
		                     lz_scene_text(s, "config"), c->n);
	*n = c->n;
	return LZ_OK;
}

static lz_edmd_params scene_params(const lz_scene *s, size_t n, const lz_edmd_params *engine)
{
	static const int walls[] = {LZ_EDMD_WALLS_NONE, LZ_EDMD_WALLS_X, LZ_EDMD_WALLS_BOX};
	lz_edmd_params p = {
		.dim = (int)lz_scene_int(s, "dim"),
		.n = n,
		.packing = lz_scene_real(s, "packing"),
		.restitution = lz_scene_real(s, "restitution"),
		.gravity = lz_scene_real(s, "gravity"),
		.walls = walls[lz_scene_enum(s, "walls")],
		.cells = (int)lz_scene_int(s, "cells"),
	};
	if (engine) {
		p.neighbours = engine->neighbours;
		p.shell = engine->shell;
		p.queue = engine->queue;
	}
	return p;
}

/* The system of the scene (not yet placed), or NULL with the library's message at the
 * key to blame. */
lz_edmd *lz_edmd_scene_system(const lz_scene *s, size_t n, const lz_edmd_params *engine)
{
	lz_edmd_params p = scene_params(s, n, engine);
	lz_edmd *e = lz_edmd_alloc(&p);
	if (e)
		return e;
	double close = p.dim == 3 ? LZ_EDMD_CLOSE_3D : LZ_EDMD_CLOSE_2D;
	const char *key = p.packing >= close ? "packing"
	                  : p.gravity > 0 && p.walls == LZ_EDMD_WALLS_NONE ? "gravity"
	                  : lz_scene_given(s, "cells") ? "cells"
	                  : engine && lz_scene_given(s, "shell") ? "shell"
	                  : engine && lz_scene_given(s, "queue") ? "queue"
	                  : engine && lz_scene_given(s, "neighbours") ? "neighbours"
	                  : lz_scene_has(s, "config") ? "config" : "n";
	lz_scene_fail(s, key, "%s", lz_error_message());
	return NULL;
}

/* Place the config file's particles (velocities from the file or Maxwell's);
 * lz_edmd_set checks the box, the walls, the numbers and the overlaps. */
int lz_edmd_scene_place_config(const lz_scene *s, lz_edmd *e, const lz_config *c, lz_rng *rng)
{
	double *v = c->v;
	if (!c->velocities) {
		v = malloc(3 * c->n * sizeof *v);
		if (!v)
			return lz_error(LZ_ENOMEM, "no memory for %zu velocities", c->n);
		lz_edmd_maxwell(e, rng, v);
	}
	int status = lz_edmd_set(e, c->r, v);
	if (v != c->v)
		free(v);
	if (status != LZ_OK)
		return lz_scene_fail(s, "config", "config file '%s' (particle k is its row k, "
		                     "from 0; the box side is L = %.10g σ): %s",
		                     lz_scene_text(s, "config"), e->L, lz_error_message());
	return LZ_OK;
}

/* The system placed: from the config file or a lattice. */
int lz_edmd_scene_start(const lz_scene *s, lz_edmd *e, lz_rng *rng)
{
	if (lz_scene_has(s, "config")) {
		lz_config c;
		int status = lz_config_read(lz_scene_text(s, "config"), e->dim, &c);
		if (status == LZ_OK)
			status = lz_edmd_scene_place_config(s, e, &c, rng);
		lz_config_free(&c);
		return status;
	}
	if (lz_edmd_place_lattice(e, rng) != LZ_OK)
		return lz_scene_fail(s, lz_scene_given(s, "n") ? "n" : "packing", "%s",
		                     lz_error_message());
	return LZ_OK;
}

/* Where the fluid ends (*end) and the other phase begins (*next), from the tables. */
static int fluid_limits(int dim, lz_ref *end, lz_ref *next)
{
	if (dim == 3)
		return lz_reference("hard-spheres.csv", "freezing packing fraction", "3",
		                    "coexistence", end) ||
		       lz_reference("hard-spheres.csv", "melting packing fraction", "3",
		                    "coexistence", next);
	return lz_reference("hard-disks.csv", "liquid stability limit", "2", "packing fraction",
	                    end) ||
	       lz_reference("hard-disks.csv", "hexatic phase begins", "2", "packing fraction",
	                    next);
}

void lz_edmd_scene_warn_phase(const lz_edmd *e, double packing, int quiet)
{
	lz_ref end, next;
	if (quiet || e->wall[0] || e->g > 0 || e->restitution < 1 ||
	    fluid_limits(e->dim, &end, &next) != LZ_OK || packing <= end.value)
		return;
	const char *source = "";
	double z = lz_edmd_z_reference(e->dim, packing, &source);
	if (e->dim == 3)
		fprintf(stderr, "lz: warning: packing = %g is beyond the hard-sphere fluid, stable "
		        "up to its freezing packing %.4f (the crystal from %.4f on; "
		        "datasets/reference/hard-spheres.csv): Z_ref = %.4g is the fluid's "
		        "equation of state (%s) carried past %s, not this system's; a lattice "
		        "start does not melt\n", packing, end.value, next.value, z, source, "freezing");
	else
		fprintf(stderr, "lz: warning: packing = %g is beyond the hard-disk liquid, stable "
		        "up to %.3f (the hexatic phase from %.3f on; "
		        "datasets/reference/hard-disks.csv): Z_ref = %.4g is the fluid's "
		        "equation of state (%s) carried past %s, not this system's; a lattice "
		        "start does not melt\n", packing, end.value, next.value, z, source, "its stability limit");
}

/* Equilibration: elastic, in pieces for the progress line on a terminal; then the clock
 * reads 0. */
int lz_edmd_scene_equilibrate(const lz_scene *s, lz_edmd *e, int quiet)
{
	double restitution = e->restitution;
	uint64_t total = (uint64_t)llround(lz_scene_real(s, "equilibrate") * (double)e->n);
	uint64_t piece = quiet ? total : PROGRESS_EVENTS, done = 0;
	lz_progress bar;
	if (!quiet)
		lz_progress_begin(&bar, "edmd equilibrate", (double)total);
	e->restitution = 1;
	int status = LZ_OK;
	while (status == LZ_OK && done < total) {
		uint64_t k = total - done < piece ? total - done : piece;
		status = lz_edmd_run(e, k, INFINITY);
		done += k;
		if (!quiet)
			lz_progress_update(&bar, (double)done);
	}
	if (!quiet)
		lz_progress_end(&bar);
	e->restitution = restitution;
	lz_edmd_set_time(e, 0);
	return status;
}
