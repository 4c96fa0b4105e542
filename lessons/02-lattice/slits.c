/* slits — lesson 02, experiment (§6): hard disks in ever narrower slits, and how a new
 * layer forms in the middle (thesis 2.5.3, figs. 2.30-2.32).
 *
 * Disks of radius R = 6 lattice units (σ = 12) random-walk on the square lattice
 * between two hard walls across y, periodic along x (L = 256 = 21.3 σ). The width left
 * to the centres, w = H - σ, runs from a quarter of a diameter to four diameters, at a
 * fixed reduced density ρσ² = N σ² / (L H) = RHO_R. The profile is collected on the
 * lattice rows (lz/profile.h): the walls are parallel to them, so no lattice
 * correction is needed. Random placement jams in the narrow slits (a queue of disks
 * dropped at random along a line fills only 75 % of it), so the disks start on a
 * grid (lz_walk_place_grid) and melt during the first tenth of the sweeps.
 *
 * Checks (physics, not numbers of this run): every profile is mirror-symmetric within
 * its noise (the walls are identical); in the narrowest slit the disks can only queue
 * along x and the profile is flat; in every slit at least one centre-width wide the
 * wall rows are denser than the middle (the wall layer); and at w = 2σ a middle layer
 * stands between two troughs.
 *
 * Usage: slits OUTDIR [--quick]   (quick: 2e4 sweeps per width; full: 2e5)
 * Writes OUTDIR/slits.dat and slits.json.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/profile.h"
#include "lz/rng.h"
#include "lz/timer.h"
#include "lz/walk.h"

#define SEED 2530u   /* fixed: the lesson quotes this run */
#define RADIUS 6.0
#define SIDE 256
#define RHO_R 0.55   /* N σ² / (L H): η = 0.43 */
#define NW 10
#define SAMPLE 10    /* sweeps between samples */

/* Centre widths w/σ; H = (w + 1) σ. */
static const double widths[NW] = {0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0};

typedef struct {
	int rows;
	double z[256], rho[256];  /* z from the slit's middle in σ; ρσ² */
	double asym;              /* rms of ρ(z) - ρ(-z) over rms of ρ: mirror symmetry */
	double wall, mid, trough; /* wall rows, the middle row, the lowest row between */
	size_t n;
	double seconds, acceptance;
} slit;

/* The disks of one slit, walked and profiled. */
static int run_slit(double w_sigma, long sweeps, lz_rng *rng, slit *out)
{
	double sigma = 2 * RADIUS, H = (w_sigma + 1) * sigma;
	size_t n = (size_t)lround(RHO_R * SIDE * H / (sigma * sigma));
	lz_walk *w = lz_walk_alloc(LZ_LATTICE_SQUARE, SIDE, RADIUS, n, LZ_WALK_RANDOM);
	lz_profile *p = NULL;
	int status = w ? lz_walk_set_slit(w, H) : LZ_EINVAL;
	if (status == LZ_OK)
		status = lz_walk_place_grid(w, rng->gsl);
	if (status == LZ_OK && !(p = lz_profile_alloc(LZ_LATTICE_SQUARE, SIDE, w->lo, w->hi, n)))
		status = LZ_ENOMEM;
	for (long s = 0; status == LZ_OK && s < sweeps / 10; s++)  /* equilibrate */
		lz_walk_sweep(w, rng->gsl);
	uint64_t moves0 = w ? w->moves : 0, acc0 = w ? w->accepted : 0;
	double t0 = lz_wall_now();
	for (long s = 1; status == LZ_OK && s <= sweeps; s++) {
		lz_walk_sweep(w, rng->gsl);
		if (s % SAMPLE == 0)
			status = lz_profile_add_config(p, w->r);
	}
	out->seconds = lz_wall_now() - t0;
	if (status == LZ_OK)
		status = lz_profile_result(p, out->rho);
	if (status == LZ_OK) {
		out->rows = w->hi - w->lo + 1;
		out->n = n;
		out->acceptance = (double)(w->accepted - acc0) / (double)(w->moves - moves0);
		for (int c = 0; c < out->rows; c++) {
			out->z[c] = ((w->lo + c) - H / 2) / sigma;
			out->rho[c] *= sigma * sigma;
		}
	}
	lz_profile_free(p);
	lz_walk_free(w);
	return status;
}

/* Symmetry, the wall layer, the middle and the lowest point between wall and middle. */
static void shape(slit *s)
{
	int R = s->rows;
	double d2 = 0, r2 = 0;
	for (int c = 0; c < R; c++) {
		d2 += (s->rho[c] - s->rho[R - 1 - c]) * (s->rho[c] - s->rho[R - 1 - c]);
		r2 += s->rho[c] * s->rho[c];
	}
	s->asym = sqrt(d2 / r2);
	s->wall = (s->rho[0] + s->rho[R - 1]) / 2;
	s->mid = (s->rho[(R - 1) / 2] + s->rho[R / 2]) / 2;
	s->trough = s->wall;
	for (int c = 1; c < R / 2; c++)
		if (s->rho[c] < s->trough)
			s->trough = s->rho[c];
}

static int write_out(lz_lesson *L, const slit *s, long sweeps)
{
	static const char *names[] = {"width", "w_over_sigma", "z_over_sigma", "rho_reduced"};
	static const char *units[] = {"index", "centre width / σ", "from the middle, σ", "ρσ²"};
	lz_data *d = lz_lesson_data(L, "slits.dat", "density profiles of hard disks (R = 6, "
	                            "square lattice) across slits of centre width w, at "
	                            "reduced density 0.55", 4, names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < NW; k++)
		for (int c = 0; c < s[k].rows; c++) {
			double row[4] = {k, widths[k], s[k].z[c], s[k].rho[c]};
			lz_data_row(d, row);
		}
	if (lz_data_close(d) != LZ_OK)
		return LZ_EIO;
	lz_json *j = lz_lesson_json(L, "slits.json");
	if (!j)
		return LZ_EIO;
	lz_json_num(j, "radius", RADIUS);
	lz_json_num(j, "reduced_density", RHO_R);
	lz_json_int(j, "sweeps_per_width", sweeps);
	lz_json_num(j, "wall_over_middle_w4", s[NW - 1].wall / s[NW - 1].mid);
	lz_json_num(j, "middle_over_trough_w2", s[6].mid / s[6].trough);
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	static slit s[NW];
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "02", &L) != LZ_OK)
		return 2;
	long sweeps = L.quick ? 20000 : 200000;
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	if (!rng)
		return lz_lesson_error(&L);
	printf("slits: hard disks R = %g on the square lattice, L = %d, reduced density %.2f, "
	       "%ld sweeps per width (profile every %d), mt19937 seed %u\n", RADIUS, SIDE, RHO_R,
	       sweeps, SAMPLE, SEED);
	printf("  %6s %5s %5s %10s %8s %8s %8s %8s %8s\n", "w/σ", "N", "rows", "acceptance",
	       "wall", "trough", "middle", "asym", "seconds");
	for (int k = 0; k < NW; k++) {
		if (run_slit(widths[k], sweeps, rng, &s[k]) != LZ_OK) {
			lz_rng_free(rng);
			return lz_lesson_error(&L);
		}
		shape(&s[k]);
		printf("  %6.2f %5zu %5d %10.3f %8.3f %8.3f %8.3f %8.3f %8.2f\n", widths[k], s[k].n,
		       s[k].rows, s[k].acceptance, s[k].wall, s[k].trough, s[k].mid, s[k].asym,
		       s[k].seconds);
	}
	lz_rng_free(rng);

	double worst = 0;
	for (int k = 0; k < NW; k++)
		worst = fmax(worst, s[k].asym);
	double tol = L.quick ? 0.25 : 0.1;
	printf("  every profile mirror-symmetric (rms asymmetry %.3f < %.2f): %s\n", worst, tol,
	       lz_lesson_check(&L, worst < tol));
	printf("  w = σ/4: a queue along x, flat across (wall/middle = %.2f within 0.2 of 1): %s\n",
	       s[0].wall / s[0].mid, lz_lesson_check(&L, fabs(s[0].wall / s[0].mid - 1) < 0.2));
	int layered = 1;
	for (int k = 3; k < NW; k++)
		layered = layered && s[k].wall > 1.3 * s[k].mid;
	printf("  w >= σ: the walls hold a layer (wall rows > 1.3 × middle in every slit): %s\n",
	       lz_lesson_check(&L, layered));
	printf("  w = 2σ: a middle layer between two troughs (middle/trough = %.2f > 1.3): %s\n",
	       s[6].mid / s[6].trough, lz_lesson_check(&L, s[6].mid > 1.3 * s[6].trough));
	if (write_out(&L, s, sweeps) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "slit profiles symmetric, flat when narrow, layered when wide");
}
