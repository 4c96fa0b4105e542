/* run_files.c — files the methods share (method.h): gnuplot scripts run inside the run
 * directory, and the picture of a configuration as circles, on a lattice or off it.
 * The configurations themselves are read and written by config.c. */
#include <stdio.h>

#include "lz/error.h"
#include "method.h"
#include "lz/walk.h"

FILE *lz_run_script(const lz_run *run, const char *name, const char *method,
                    const char *what, int width, int height)
{
	char file[256], path[4200];
	snprintf(file, sizeof file, "%s.gp", name);
	if (lz_rundir_file(run->dir, file, path, sizeof path) != LZ_OK)
		return NULL;
	FILE *f = fopen(path, "w");
	if (!f) {
		lz_error(LZ_EIO, "cannot write %s", path);
		return NULL;
	}
	fprintf(f, "# lz run, method %s: %s.\n"
	        "set terminal pngcairo size %d,%d enhanced font 'Sans,11'\n"
	        "set output '%s.png'\n", method, what, width, height, name);
	return f;
}

int lz_run_plot(const lz_run *run, FILE *f, const char *name)
{
	char file[256];
	snprintf(file, sizeof file, "%s.gp", name);
	int bad = ferror(f);
	if (fclose(f) != 0 || bad)
		return lz_error(LZ_EIO, "cannot write the plot script %s in %s", file,
		                run->dir->tmp);
	int status = lz_gnuplot(run->dir->tmp, file);
	return status == 1 ? LZ_OK : status;
}

/* The plot command of config.gp: circles of radius rcol centred on (xcol, ycol), all
 * three gnuplot expressions ("$1", "0.5"); in 3D only the circles in which the plane
 * z = mid (zcol) cuts the spheres. */
static void plot_circles(FILE *f, int dim, const char *xcol, const char *ycol,
                         const char *zcol, const char *rcol, double mid)
{
	if (dim == 2) {
		fprintf(f, "plot 'config.dat' u (%s):(%s):(%s) w circles fs transparent solid 0.5 "
		        "lc rgb '#3060c0'\n", xcol, ycol, rcol);
		return;
	}
	fprintf(f, "set label 1 'slice z = %g' at graph 0.02, graph 1.03\n"
	        "# the radius of the cut, sqrt(R² - dz²); spheres the plane misses get "
	        "x = NaN and are skipped\n"
	        "h(z, r) = abs(z - %g) < r ? sqrt(r * r - (z - %g)**2) : NaN\n"
	        "plot 'config.dat' u (h(%s, %s) == h(%s, %s) ? %s : NaN):(%s):(h(%s, %s)) "
	        "w circles fs transparent solid 0.5 lc rgb '#3060c0'\n", mid, mid, mid,
	        zcol, rcol, zcol, rcol, xcol, ycol, zcol, rcol);
}

int lz_run_plot_config(const lz_run *run, const char *method, lz_lattice_kind kind,
                       int32_t side, double window, const char *title)
{
	double top = window * lz_walk_row_spacing(kind), mid = side / 2.0;
	FILE *f = lz_run_script(run, "config", method, "the final configuration", 800,
	                        (int)(120 + 680 * top / window));
	if (!f)
		return LZ_EIO;
	fprintf(f, "set size ratio -1\nunset key\nset xrange [0:%g]\nset yrange [0:%g]\n"
	        "set xlabel 'x [lattice units]'\nset ylabel 'y [lattice units]'\n"
	        "set title \"%s\"\n", window, top, title);
	int dim = lz_lattice_dim(kind);
	plot_circles(f, dim, "$1", "$2", "$3", dim == 3 ? "$4" : "$3", mid);
	return lz_run_plot(run, f, "config");
}

int lz_run_plot_disks(const lz_run *run, const char *method, int dim, double L,
                      double window, int upright, const char *title)
{
	FILE *f = lz_run_script(run, "config", method, "the final configuration", 800, 800);
	if (!f)
		return LZ_EIO;
	fprintf(f, "set size ratio -1\nunset key\nset xrange [0:%g]\nset yrange [0:%g]\n"
	        "set xlabel '%s [σ]'\nset ylabel '%s [σ]'\nset title \"%s\" noenhanced\n",
	        window, window, upright ? "y" : "x", upright ? "x" : "y", title);
	plot_circles(f, dim, upright ? "$2" : "$1", upright ? "$1" : "$2", "$3", "0.5", L / 2);
	return lz_run_plot(run, f, "config");
}
