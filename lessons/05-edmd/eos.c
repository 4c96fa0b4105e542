/* eos — lesson 05, experiment: the equation of state of hard spheres and hard disks,
 * measured twice over, against the best reference there is.
 *
 * Z = βP/ρ from the collision impulses (the virial, lz_edmd.virial), and, separately,
 * from the collision count alone through the identity of any hard-particle fluid in
 * equilibrium (datasets/reference/collision-identity.csv):
 *     Z = 1 + √(π/kT) Γ / (2·dim),   Γ = 2 · collisions / (N · time).
 * The two use different numbers from the same run — a sum of momentum transfers
 * against a count — so their agreement tests the whole engine; their agreement with
 * Z_ref (lz_edmd_z_reference: the Padé-resummed virial series of the course reference,
 * §1-2) tests the physics. Carnahan–Starling (3D) and Henderson (2D) are drawn beside:
 * CS is low by 0.3 % at η ≥ 0.3, Henderson high by 0.5-2 % at η ≥ 0.5.
 *
 * Each state point: N particles from the lattice (lz_edmd_place_lattice), melted, then
 * BLOCKS blocks of equal numbers of events (lz_edmd_blocks: block means, standard
 * errors, and the guards on energy, momentum and overlaps at every block end). Hard
 * spheres N = 4000 at η = 0.05 .. 0.49 (just below freezing, 0.494), hard disks N =
 * 4096 at η = 0.05 .. 0.65 (the fluid ends near 0.70: at 0.65 the relaxation is
 * slow, so it melts five times longer).
 *
 * Checks, at every state point: |Z - Z_ref| within 3 error bars plus the reference's
 * own uncertainty; |Z - Z_Γ| within 3 combined error bars (conservative: the two
 * block series are correlated, which the combined error ignores).
 *
 * Usage: eos OUTDIR [--quick]
 * Writes OUTDIR/eos.dat, eos_ref.dat and eos.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "lz/edmd.h"
#include "lz/edmd_obs.h"
#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/reference.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 5001u
#define BLOCKS 20
#define NSIGMA 3.0
#define NPOINT 15
#define DENSE_MELT 5.0  /* the 2D points from η = 0.6 on melt this many times longer */

/* The state points. Z_ref and its uncertainty come from datasets/reference/
 * hard-spheres.csv and hard-disks.csv at the tabulated packings; at η = 0.05, below
 * the table, lz_edmd_z_reference interpolates towards Z = 1 at η = 0, which is good
 * to about 2e-4 in 3D and 1e-5 in 2D (checked against the virial series). */
typedef struct {
	int dim;
	double eta;
} state;

static const state state_of[NPOINT] = {
	{3, 0.05}, {3, 0.10}, {3, 0.20}, {3, 0.30}, {3, 0.40}, {3, 0.45}, {3, 0.49},
	{2, 0.05}, {2, 0.10}, {2, 0.20}, {2, 0.30}, {2, 0.40}, {2, 0.50}, {2, 0.60}, {2, 0.65},
};

/* The uncertainty of Z_ref at s: the table's, or below it the interpolation's. */
static double zref_err(const state *s)
{
	lz_ref r;
	if (lz_reference_at(s->dim == 3 ? "hard-spheres.csv" : "hard-disks.csv", "Z",
	                    s->dim == 3 ? "3" : "2", "eta", s->eta, &r) == LZ_OK)
		return r.err;
	return s->dim == 3 ? 2e-4 : 1e-5;
}

typedef struct {
	double melt;     /* events per particle from the lattice */
	double produce;  /* events per particle measured, in BLOCKS blocks */
} sizes;

static const sizes full = {100, 2000};
static const sizes quick = {30, 150};

static size_t n_of(int dim) { return dim == 3 ? 4000 : 4096; }

/* One state point: melted from the lattice, measured in blocks. */
static int measure(const state *s, const sizes *sz, lz_edmd_result *r, double *cpu_total)
{
	size_t n = n_of(s->dim);
	lz_edmd_params p = {s->dim, n, s->eta, 1.0, 0.0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	lz_rng *rng = lz_rng_alloc(NULL, SEED);
	double t0 = lz_cpu_now();
	int st = e && rng ? lz_edmd_place_lattice(e, rng) : LZ_EINVAL;
	double melt = sz->melt * (s->dim == 2 && s->eta >= 0.6 ? DENSE_MELT : 1);
	if (st == LZ_OK)
		st = lz_edmd_run(e, (uint64_t)(melt * (double)n), INFINITY);
	if (st == LZ_OK)
		st = lz_edmd_blocks(e, BLOCKS, (uint64_t)(sz->produce * (double)n / BLOCKS), r);
	*cpu_total = lz_cpu_now() - t0;
	lz_edmd_free(e);
	lz_rng_free(rng);
	return st;
}

/* Z_ref, CS and Henderson on a fine grid, for the plot's curves. */
static int write_reference(lz_lesson *L)
{
	static const char *names[] = {"eta", "Z_ref_3d", "Z_CS", "Z_ref_2d", "Z_Henderson"};
	lz_data *d = lz_lesson_data(L, "eos_ref.dat", "reference equations of state: Z_ref "
	                            "(lz_edmd_z_reference, within its table: 3D to 0.49, 2D to "
	                            "0.65 here), Carnahan-Starling, Henderson", 5, names, NULL);
	if (!d)
		return LZ_EIO;
	for (int k = 1; k <= 140; k++) {
		double eta = 0.005 * k;
		/* Z_ref only where it is tabulated (lz_edmd_z_reference: "table") */
		const char *s3, *s2;
		double z3 = lz_edmd_z_reference(3, eta, &s3), z2 = lz_edmd_z_reference(2, eta, &s2);
		double row[5] = {eta, s3[0] == 't' ? z3 : NAN, eta <= 0.5 ? lz_edmd_z_closed(3, eta) : NAN,
		                 s2[0] == 't' && eta <= 0.65 ? z2 : NAN, lz_edmd_z_closed(2, eta)};
		lz_data_row(d, row);
	}
	return lz_data_close(d);
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "05", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	printf("eos: hard spheres (N = %zu) and disks (N = %zu), melted %g events per particle "
	       "(2D η >= 0.6: %g), measured %g in %d blocks; seed %u\n", n_of(3), n_of(2),
	       sz->melt, sz->melt * DENSE_MELT, sz->produce, BLOCKS, SEED);
	static const char *names[] = {"dim", "eta", "Z", "Z_err", "Z_gamma", "Z_gamma_err",
	                              "Z_ref", "Z_ref_err", "Z_closed", "gamma", "gamma_err",
	                              "events_per_s", "max_overlap", "energy_drift"};
	static const char *units[] = {"", "", "", "", "", "", "", "", "CS (3D), Henderson (2D)",
	                              "collisions per particle per time", "", "per CPU s", "σ",
	                              "relative"};
	lz_data *d = lz_lesson_data(&L, "eos.dat", "hard spheres and disks: Z from the virial "
	                            "and from the collision rate against Z_ref", 14, names, units);
	if (!d)
		return lz_lesson_error(&L);
	printf("  dim   η       Z          ±        Z_Γ        ±       Z_ref       ±     "
	       "Z-Z_ref  Z-Z_Γ   events/s  CPU s\n");
	int ok_ref = 1, ok_id = 1;
	double worst_ref = 0, worst_id = 0, cpu_all = 0, ev_all = 0, over = 0, drift = 0;
	lz_edmd_result at03 = {0};
	for (int k = 0; k < NPOINT; k++) {
		const state *s = &state_of[k];
		lz_edmd_result r;
		double cpu;
		if (measure(s, sz, &r, &cpu) != LZ_OK) {
			lz_data_close(d);
			return lz_lesson_error(&L);
		}
		double zref = lz_edmd_z_reference(s->dim, s->eta, NULL);
		double dev_ref = (r.Z - zref) / (NSIGMA * r.Z_err + zref_err(s));
		double dev_id = (r.Z - r.Z_gamma) / (NSIGMA * hypot(r.Z_err, r.Z_gamma_err));
		ok_ref = ok_ref && fabs(dev_ref) <= 1;
		ok_id = ok_id && fabs(dev_id) <= 1;
		worst_ref = fmax(worst_ref, fabs(dev_ref));
		worst_id = fmax(worst_id, fabs(dev_id));
		cpu_all += cpu;
		ev_all += (double)r.events;
		over = fmax(over, r.max_overlap);
		drift = fmax(drift, r.energy_rel_drift);
		if (s->dim == 3 && s->eta == 0.30)
			at03 = r;
		printf("  %dD %5.2f %9.5f %9.5f %10.5f %9.5f %9.5f %8.5f %+7.2f %+7.2f %10.3g %6.2f  "
		       "%s\n", s->dim, s->eta, r.Z, r.Z_err, r.Z_gamma, r.Z_gamma_err, zref,
		       zref_err(s), dev_ref, dev_id, (double)r.events / r.cpu_s, cpu,
		       lz_lesson_check(&L, fabs(dev_ref) <= 1 && fabs(dev_id) <= 1));
		double row[14] = {s->dim, s->eta, r.Z, r.Z_err, r.Z_gamma, r.Z_gamma_err, zref,
		                  zref_err(s), lz_edmd_z_closed(s->dim, s->eta), r.gamma, r.gamma_err,
		                  (double)r.events / r.cpu_s, r.max_overlap, r.energy_rel_drift};
		lz_data_row(d, row);
	}
	if (lz_data_close(d) != LZ_OK || write_reference(&L) != LZ_OK)
		return lz_lesson_error(&L);
	printf("  (Z-Z_ref and Z-Z_Γ in units of what is allowed, 3 error bars plus the "
	       "reference's uncertainty, 3 combined error bars: a point passes within ±1)\n");
	printf("  every Z within 3 error bars (+ the reference's) of Z_ref, the worst at %.2f "
	       "of that: %s\n", worst_ref, lz_lesson_check(&L, ok_ref));
	printf("  every Z within 3 combined error bars of the collision-rate identity Z_Γ, "
	       "worst at %.2f of that: %s\n", worst_id, lz_lesson_check(&L, ok_id));
	printf("  guards: largest overlap %.2g σ, largest energy drift %.2g, %.3g events in "
	       "%.1f CPU s\n", over, drift, ev_all, cpu_all);

	lz_json *j = lz_lesson_json(&L, "eos.json");
	if (!j)
		return lz_lesson_error(&L);
	lz_json_int(j, "seed", SEED);
	lz_json_err(j, "Z_3d_eta_0.3", at03.Z, at03.Z_err);
	lz_json_err(j, "Z_gamma_3d_eta_0.3", at03.Z_gamma, at03.Z_gamma_err);
	lz_json_num(j, "Z_ref_3d_eta_0.3", lz_edmd_z_reference(3, 0.3, NULL));
	lz_json_num(j, "mean_free_time_3d_eta_0.3", at03.free_time);
	lz_json_num(j, "worst_deviation_from_Z_ref_in_3_sigma", worst_ref);
	lz_json_num(j, "worst_identity_deviation_in_3_sigma", worst_id);
	lz_json_num(j, "max_overlap", over);
	lz_json_num(j, "max_energy_drift", drift);
	lz_json_num(j, "events_per_s", ev_all / cpu_all);
	if (lz_json_end(j) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "Z(η) within error bars of Z_ref and of the collision-"
	                        "rate identity at %d state points", NPOINT);
}
