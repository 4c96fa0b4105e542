/* config.c — particle configurations on file (config.h): the lattice engines' and the
 * event-driven engine's config.dat, and reading one back. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "lz/error.h"

/* ---- on a lattice ---- */

int lz_config_write_lattice(const lz_run *run, lz_lattice_kind kind, int32_t side, size_t n,
                            const int32_t *r, double radius)
{
	static const char *const names[] = {"x", "y", "z", "R"};
	static const char *const names2[] = {"x", "y", "R"};
	static const char *const units[] = {"lattice units", "lattice units", "lattice units",
	                                    "lattice units"};
	char path[4200];
	int status = lz_rundir_file(run->dir, "config.dat", path, sizeof path);
	if (status != LZ_OK)
		return status;
	int dim = lz_lattice_dim(kind);
	char title[240];
	snprintf(title, sizeof title, "configuration, %zu particles of radius %g on the %s "
	         "lattice, periodic box of side %d (Cartesian coordinates%s)", n, radius,
	         lz_lattice_name(kind), (int)side, kind == LZ_LATTICE_TRIANGULAR ?
	         ": the sheared box drawn as the rectangle L × L·√3/2" : "");
	lz_data *d = lz_data_open(path, title, dim + 1, dim == 3 ? names : names2, units);
	if (!d)
		return LZ_EIO;
	for (size_t i = 0; i < n; i++) {
		double c[3], row[4];
		lz_lattice_cartesian(kind, side, r + i * (size_t)dim, c);
		for (int k = 0; k < dim; k++)
			row[k] = c[k];
		row[dim] = radius;
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

/* ---- off the lattice ---- */

int lz_config_write_edmd(const lz_run *run, const lz_edmd *e, const char *about)
{
	static const char *const names[] = {"x", "y", "z", "vx", "vy", "vz"};
	char path[4200];
	int status = lz_rundir_file(run->dir, "config.dat", path, sizeof path);
	if (status != LZ_OK)
		return status;
	FILE *f = fopen(path, "w");
	if (!f)
		return lz_error(LZ_EIO, "cannot write %s: %s", path, strerror(errno));
	fprintf(f, "# the state of %zu hard %s at t = %.17g τ, box side L = %.17g σ (%s); "
	        "read it back with config = config.dat\n#", e->n,
	        e->dim == 3 ? "spheres" : "disks", lz_edmd_time(e), e->L, about);
	for (int k = 0; k < 2 * e->dim; k++) {
		int a = k % e->dim;
		fprintf(f, " %s [%s]", names[(k / e->dim) * 3 + a], k < e->dim ? "σ" : "σ/τ");
	}
	fputc('\n', f);
	for (size_t i = 0; i < e->n; i++) {
		double r[3], v[3];
		lz_edmd_state(e, &e->p[i], e->now, r, v);
		for (int a = 0; a < e->dim; a++) {
			if (!e->wall[a]) {  /* round-off may leave a hair outside [0, L) */
				r[a] -= e->L * floor(r[a] / e->L);
				r[a] = r[a] < e->L ? r[a] : 0;
			}
			fprintf(f, "%.17g ", r[a]);
		}
		for (int a = 0; a < e->dim; a++)
			fprintf(f, a + 1 < e->dim ? "%.17g " : "%.17g\n", v[a]);
	}
	int bad = ferror(f);
	if (fclose(f) != 0 || bad)
		return lz_error(LZ_EIO, "cannot write %s", path);
	return LZ_OK;
}

void lz_config_free(lz_config *c)
{
	free(c->r);
	free(c->v);
	*c = (lz_config){0};
}

/* The numbers of one line (a '#' starts a comment) into x[0 .. 6]; their count, or -1
 * with lz_error. */
static int config_line(const char *path, long lineno, char *line, double x[7])
{
	char *hash = strchr(line, '#');
	if (hash)
		*hash = '\0';
	int k = 0;
	for (char *c = line;;) {
		while (*c == ' ' || *c == '\t' || *c == '\r' || *c == '\n')
			c++;
		if (!*c)
			return k;
		char *end;
		errno = 0;
		double v = strtod(c, &end);
		if (end == c || !isfinite(v) || errno == ERANGE || (*end && !strchr(" \t\r\n", *end)))
			return lz_error(LZ_ESYNTAX, "config file '%s', line %ld: '%.*s' is not a "
			                "finite number", path, lineno, (int)fmin(20, strcspn(c, " \t\r\n")),
			                c), -1;
		if (k == 7)
			return lz_error(LZ_ESYNTAX, "config file '%s', line %ld: more than 6 numbers",
			                path, lineno), -1;
		x[k++] = v;
		c = end;
	}
}

int lz_config_read(const char *path, int dim, lz_config *c)
{
	*c = (lz_config){0};
	FILE *f = fopen(path, "r");
	if (!f)
		return lz_error(LZ_EIO, "config file '%s' cannot be read: %s", path, strerror(errno));
	char *line = NULL;
	size_t cap = 0, room = 0;
	long lineno = 0;
	int cols = 0, status = LZ_OK;
	while (status == LZ_OK && getline(&line, &cap, f) >= 0) {
		double x[7];
		int k = config_line(path, ++lineno, line, x);
		if (k < 0) {
			status = LZ_ESYNTAX;
			break;
		}
		if (k == 0)
			continue;
		if (cols == 0) {
			if (k != dim && k != 2 * dim) {
				status = lz_error(LZ_ESYNTAX, "config file '%s', line %ld: %d numbers; "
				                  "a row in %dD is x y%s (%d) or with velocities (%d)", path,
				                  lineno, k, dim, dim == 3 ? " z" : "", dim, 2 * dim);
				break;
			}
			cols = k;
			c->velocities = k == 2 * dim;
		} else if (k != cols) {
			status = lz_error(LZ_ESYNTAX, "config file '%s', line %ld: %d numbers where the "
			                  "first row had %d", path, lineno, k, cols);
			break;
		}
		if (c->n == room) {
			room = room ? 2 * room : 1024;
			double *r = realloc(c->r, 3 * room * sizeof *r), *v = c->v;
			if (r)
				c->r = r;
			if (r && c->velocities && (v = realloc(c->v, 3 * room * sizeof *v)))
				c->v = v;
			if (!r || (c->velocities && !v)) {
				status = lz_error(LZ_ENOMEM, "config file '%s': no memory for %zu rows",
				                  path, room);
				break;
			}
		}
		for (int a = 0; a < 3; a++) {
			c->r[3 * c->n + a] = a < dim ? x[a] : 0;
			if (c->velocities)
				c->v[3 * c->n + a] = a < dim ? x[dim + a] : 0;
		}
		c->n++;
	}
	if (status == LZ_OK && ferror(f))
		status = lz_error(LZ_EIO, "config file '%s': read error", path);
	if (status == LZ_OK && c->n == 0)
		status = lz_error(LZ_ESYNTAX, "config file '%s' has no particle rows", path);
	free(line);
	fclose(f);
	if (status != LZ_OK)
		lz_config_free(c);
	return status;
}
