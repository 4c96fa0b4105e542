/* config.h — particle configurations on file: config.dat, which every engine writes
 * after a run, and which the event-driven engine reads back (`config = FILE`).
 *
 * The file is whitespace columns under a '#' header that names them with units: on a
 * lattice x y [z] R in Cartesian lattice units (lz_lattice_cartesian); off it x y [z]
 * in σ and, after them, vx vy [vz] in σ/τ, every digit (%.17g) so that a run started
 * from the file continues bit for bit.
 */
#ifndef LZ_CONFIG_H
#define LZ_CONFIG_H

#include <stddef.h>
#include <stdint.h>

#include "lz/edmd.h"
#include "lz/lattice.h"
#include "method.h"

/* A configuration read from a file. */
typedef struct {
	size_t n;        /* particles (rows) */
	int velocities;  /* the rows have velocities */
	double *r, *v;   /* 3 per particle, z = 0 in 2D; v NULL without velocities */
} lz_config;

/* config.dat in the run directory: n particles of radius R (lattice units) centred on
 * the sites r (dim int32_t each, every coordinate in [0, L)) of a periodic box of side
 * L on lattice `kind`, one row per particle. LZ_EIO on a write error. O(n). */
int lz_config_write_lattice(const lz_run *run, lz_lattice_kind kind, int32_t side, size_t n,
                            const int32_t *r, double radius);

/* config.dat in the run directory: the positions (wrapped into [0, L) along the
 * periodic axes) and velocities of e's particles now; `about` goes into the header
 * (e.g. "packing 0.3, walls none"). LZ_EIO on a write error. O(n). */
int lz_config_write_edmd(const lz_run *run, const lz_edmd *e, const char *about);

/* Read the rows of `path` for dimension dim (2 or 3): dim numbers a row, or 2·dim
 * with velocities, the same count in every row; '#' starts a comment. LZ_EIO when
 * the file cannot be read, LZ_ESYNTAX naming the line when a row is malformed or
 * there is none, LZ_ENOMEM; on an error *c is empty. O(rows). */
int lz_config_read(const char *path, int dim, lz_config *c);
void lz_config_free(lz_config *c);

#endif
