/* rsa_jam — lesson 03, experiment (§5): random sequential adsorption to exact jamming
 * on lattices of finer and finer resolution, and what the resolution costs (thesis
 * 2.5.1, figs. 2.17-2.20; the stage's trade of cost against accuracy).
 *
 * Disks (spheres) of radius R lattice units are dropped at uniformly random free
 * sites (lz_field_rsa with no target) until no site is free: jammed, known exactly
 * from the field's count of free sites, never guessed from failed tries. The coverage
 * θ = N · (continuum area πR², volume 4πR³/3) / (box area) is compared with the
 * continuum jamming coverage of disks, 0.547069 ± 5e-6, and spheres, 0.38413 ± 2e-5
 * (datasets/reference/rsa.csv: Wang 1994; Zhang & Torquato 2013).
 *
 * The lattice has its own jamming limit, and at small R it is a different problem:
 *   R = 1/2: σ = 1, the excluded shape d² < 1 is the centre site alone, so every site
 *     takes a particle: θ = π/4 = 0.7854 on the square lattice, π/(2√3) = 0.9069 on
 *     the triangular one (the triangular lattice of spacing σ IS the hexagonal close
 *     packing) and π/6 = 0.5236 on the cubic one, exactly, with no randomness left.
 *   R = 1 on the square lattice: d² < 4 is the 3×3 block, so two centres exclude each
 *     other iff |dx| <= 1 and |dy| <= 1 — RSA of 2×2 squares on the square lattice,
 *     whose jammed squares cover 0.74788 ± 2e-5 of the sites (datasets/reference/
 *     rsa.csv): θ = (π/4) · 0.74788 = 0.5874. R = 1.5 is the 5×5 block (3×3
 *     squares); R = 1 on the cubic lattice is the 3×3×3 block (2×2×2 cubes); on the
 *     triangular lattice R = 1 excludes the 19 sites at d² < 4.
 *   R >= 2: the shapes round off, and two lattice effects are left, both measured:
 *     (1) the shape. The lattice disk excludes |S| sites, not the area π(2R)²: the
 *     strict rule (lz/shape.h) leaves out the sites ON the circle, and the count of
 *     sites in a circle scatters about its area (Gauss's circle problem). The
 *     ratio |S|·cell / π(2R)² runs 0.96, 0.99, 0.996, 0.9986 at R = 4, 12, 24, 48 on
 *     the square lattice, erratically: θ inherits that scatter. A lattice disk
 *     behaves like a disk of a quarter of its excluded area: θ_eff = θ · ratio.
 *     (2) the gaps. A lattice centre may only sit on a site, a grid of spacing
 *     1/(2R) in units of σ; the last, smallest gaps of the packing hold a site or
 *     not, by chance, and θ_eff stays below the continuum by a smooth a/R (as k-mers
 *     on a line approach Rényi's parking constant like 1/k).
 * So θ_eff(R) is fitted (weighted least squares, GSL) as θ∞ + a/R over R >= RFIT, and
 * as θ∞ + a/R + b/R² to see whether the 1/R² term is needed (it is when the linear χ²
 * is improbable, Q < 0.01, and b is more than two error bars from 0). The error bar
 * of θ∞ includes the difference of the two fits: in 3D, with R <= 12, an unresolved
 * b/R² still moves the linear intercept by a few 1e-3. θ itself approaches the
 * continuum as the product of the two effects.
 *
 * Box sides: the smallest power of two holding nmin particles at jamming (and at
 * least lmin: small radii are cheap), up to lmax. Each radius runs until about ntot
 * particles are placed in all (at least smin, at most smax runs): mean and standard
 * error over the runs. The cost of a run, allocation included, is in CPU seconds (the
 * machine is shared: CPU time, not wall time) and per particle; the memory is the
 * field's L^dim bytes per particle. Both grow like R^dim: that is the trade
 * (rsa_trade.gp), the coverage error against CPU time and bytes per particle. (The
 * draws per particle grow alike: lz_field_rsa's final phase lists the free sites, a
 * sixteenth of the box, and draws each of them about once before it is jammed.)
 *
 * Checks: every run jammed (nfree == 0, and a full scan of the field agrees); R = 1/2
 * fills every site, θ exactly π/4, π/(2√3), π/6; R = 1 on the square lattice covers
 * the fraction of 2×2-square RSA within 3 standard errors; the extrapolation R → ∞
 * within 3 error bars of the continuum value on every lattice; and the largest R
 * alone, moved to R = ∞ by the fitted lattice term (θ_eff - a/R), on the continuum
 * within 3 error bars (its own, the slope's and the fit model's).
 *
 * Usage: rsa_jam OUTDIR [--quick]
 * Writes OUTDIR/rsa_jam.dat (one row per lattice and R), rsa_fit.dat (the fitted
 * lines) and rsa_jam.json.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/error.h"
#include "lz/field.h"
#include "lz/lattice.h"
#include "lz/lesson.h"
#include "lz/output.h"
#include "lz/reference.h"
#include "lz/rng.h"
#include "lz/timer.h"

#define SEED 2510u        /* fixed: the lesson quotes the numbers of this run */
#define NSIG 3.0          /* "within its error": 3 error bars */
#define RFIT 3.0          /* the fits use R >= RFIT */
#define MAXR 16           /* radii per lattice, at most */
#define MAXRUNS 64

/* A lattice and the radii run on it, with its continuum jamming coverage. */
typedef struct {
	lz_lattice_kind kind;
	int nr;
	const double *radii;
	double cont, cont_err;   /* continuum θ_J and its error (datasets/reference/rsa.csv) */
	double full_limit;       /* θ at R = 1/2: every site taken */
} series;

static const double radii2[] = {0.5, 1, 1.5, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48};
static const double radii3[] = {0.5, 1, 1.5, 2, 3, 4, 6, 8, 12};
#define NSERIES 3
static series all[NSERIES] = {  /* cont, cont_err: read by read_references */
	{LZ_LATTICE_SQUARE, 13, radii2, NAN, NAN, M_PI / 4},
	{LZ_LATTICE_TRIANGULAR, 13, radii2, NAN, NAN, M_PI / (2 * 1.7320508075688772)},
	{LZ_LATTICE_CUBIC, 9, radii3, NAN, NAN, M_PI / 6},
};
static lz_ref squares_2x2;  /* RSA of 2×2 squares on the square lattice */

/* The literature values from datasets/reference/rsa.csv, and rsa_ref.gp, which hands
 * the continuum coverages to the plot scripts. */
static int read_references(lz_lesson *L)
{
	lz_ref disks, spheres;
	if (lz_reference("rsa.csv", "jamming coverage", "2", "disks continuum", &disks) ||
	    lz_reference("rsa.csv", "jamming coverage", "3", "spheres continuum", &spheres) ||
	    lz_reference("rsa.csv", "jamming coverage", "2", "square lattice 2x2 squares",
	                 &squares_2x2))
		return LZ_EIO;
	for (int k = 0; k < NSERIES; k++) {
		lz_ref r = all[k].kind == LZ_LATTICE_CUBIC ? spheres : disks;
		all[k].cont = r.value;
		all[k].cont_err = r.err;
	}
	FILE *f = fopen(lz_lesson_path(L, "rsa_ref.gp"), "w");
	if (!f)
		return lz_error(LZ_EIO, "cannot write %s", lz_lesson_path(L, "rsa_ref.gp"));
	fprintf(f, "# the continuum jamming coverages (datasets/reference/rsa.csv)\n"
	        "theta_disks = %.7g\ntheta_spheres = %.7g\n", disks.value, spheres.value);
	return fclose(f) == 0 ? LZ_OK : lz_error(LZ_EIO, "cannot write rsa_ref.gp");
}

/* How large and how many, per dimension: at least nmin particles per run (the box
 * side the smallest power of two in [lmin, lmax] that holds them), about ntot
 * particles per radius in all (runs between smin and smax), radii up to rmax. */
typedef struct {
	double nmin, ntot, rmax;
	int64_t lmin, lmax;
} dimsize;

typedef struct {
	dimsize d2, d3;
	int smin, smax;
} sizes;

static const sizes full = {{2000, 24000, 48, 1024, 8192}, {3000, 12000, 12, 64, 256}, 8, 32};
static const sizes quick = {{600, 3000, 48, 512, 2048}, {400, 2000, 8, 32, 128}, 8, 16};

/* One lattice and radius: several runs. */
typedef struct {
	double R;
	int64_t L;
	int runs;
	double n, theta, se;     /* particles per run, coverage mean and standard error */
	double ratio;            /* the lattice's excluded area over the continuum's */
	double theta_eff, se_eff;  /* θ · ratio: the coverage of disks of the lattice's area */
	double cpu;              /* CPU seconds per run (mean), allocation + RSA */
	double us_per_particle, bytes_per_particle, tries_per_particle;
	int jammed;              /* every run: nfree == 0 and the scan agrees */
	int filled;              /* every run: N = L^dim (every site taken) */
} point;

/* A fit of θ_eff: θ∞ + a/R, and θ∞ + a2/R + b/R², over R >= RFIT. */
typedef struct {
	int npts;
	double c;            /* the pooled spread of θ_eff times √N (fit_series) */
	double t_inf, t_err, a, a_err, chi2_dof, q;      /* linear in 1/R */
	double t2_inf, t2_err, a2, b, b_err, chi2_dof2;  /* with 1/R² (NaN: too few points) */
	int need_quadratic;
} fit;

static const dimsize *dim_sizes(const series *s, const sizes *sz)
{
	return lz_lattice_dim(s->kind) == 2 ? &sz->d2 : &sz->d3;
}

/* The particles at jamming in a box of side L at the continuum's coverage, for the
 * choice of sizes (a lattice jams within a few per cent of it from R = 1 on). */
static double expected_n(const series *s, double R, int64_t L)
{
	int dim = lz_lattice_dim(s->kind);
	double box = pow((double)L, dim) * lz_lattice_cell_volume(s->kind);
	double v = dim == 2 ? M_PI * R * R : 4.0 / 3.0 * M_PI * R * R * R;
	return s->cont * box / v;
}

/* The box side for radius R (header comment), at least 4R (lz/field.h); 0 when R is
 * beyond this size's rmax. */
static int64_t choose_side(const series *s, double R, const sizes *sz)
{
	const dimsize *d = dim_sizes(s, sz);
	int64_t L = d->lmin;
	while (L < d->lmax && (expected_n(s, R, L) < d->nmin || 4 * R > (double)L))
		L *= 2;
	return R > d->rmax || 4 * R > (double)L ? 0 : L;
}

/* One jammed configuration: its coverage, particles, CPU seconds and draws, and the
 * excluded shape's size. */
static int one_run(const series *s, double R, int64_t L, gsl_rng *rng, double *theta,
                   double *n, double *cpu, double *tries, int *jammed, size_t *shape)
{
	double t0 = lz_cpu_now();
	lz_field *f = lz_field_alloc(s->kind, L, R);
	if (!f)
		return LZ_EINVAL;
	int status = lz_field_rsa(f, rng, 0, jammed);
	*cpu = lz_cpu_now() - t0;
	*jammed = *jammed && f->nfree == 0 && lz_field_count_free(f) == 0;
	*theta = lz_field_coverage(f);
	*n = (double)f->n;
	*tries = (double)f->tries;
	*shape = f->excl->n;
	lz_field_free(f);
	return status;
}

static int run_point(const series *s, double R, const sizes *sz, gsl_rng *rng, point *p)
{
	double theta[MAXRUNS], n = 0, cpu = 0, tries = 0;
	int dim = lz_lattice_dim(s->kind);
	double sites = pow((double)p->L, dim);
	double runs = ceil(dim_sizes(s, sz)->ntot / expected_n(s, R, p->L));
	size_t shape = 0;
	p->runs = (int)fmin(sz->smax, fmax(sz->smin, runs));
	p->jammed = p->filled = 1;
	for (int k = 0; k < p->runs; k++) {
		double nk, ck, tk;
		int jammed;
		int status = one_run(s, R, p->L, rng, &theta[k], &nk, &ck, &tk, &jammed, &shape);
		if (status != LZ_OK)
			return status;
		p->jammed = p->jammed && jammed;
		p->filled = p->filled && nk == sites;
		n += nk;
		cpu += ck;
		tries += tk;
	}
	p->theta = gsl_stats_mean(theta, 1, (size_t)p->runs);
	p->se = gsl_stats_sd_m(theta, 1, (size_t)p->runs, p->theta) / sqrt(p->runs);
	double sigma = 2 * R;
	double area = dim == 2 ? M_PI * sigma * sigma : 4.0 / 3.0 * M_PI * sigma * sigma * sigma;
	p->ratio = (double)shape * lz_lattice_cell_volume(s->kind) / area;
	p->theta_eff = p->theta * p->ratio;
	p->se_eff = p->se * p->ratio;
	p->n = n / p->runs;
	p->cpu = cpu / p->runs;
	p->us_per_particle = 1e6 * cpu / n;
	p->bytes_per_particle = sites / p->n;
	p->tries_per_particle = tries / n;
	return LZ_OK;
}

/* θ∞ + a2/R + b/R² by weighted least squares (gsl_multifit_wlinear). */
static void fit_quadratic(const double *x, const double *y, const double *w, int m, fit *F)
{
	F->t2_inf = F->t2_err = F->a2 = F->b = F->b_err = F->chi2_dof2 = NAN;
	if (m < 4)
		return;
	gsl_matrix *X = gsl_matrix_alloc((size_t)m, 3), *cov = gsl_matrix_alloc(3, 3);
	gsl_vector *Y = gsl_vector_alloc((size_t)m), *W = gsl_vector_alloc((size_t)m);
	gsl_vector *c = gsl_vector_alloc(3);
	gsl_multifit_linear_workspace *ws = gsl_multifit_linear_alloc((size_t)m, 3);
	for (int i = 0; i < m; i++) {
		gsl_matrix_set(X, (size_t)i, 0, 1);
		gsl_matrix_set(X, (size_t)i, 1, x[i]);
		gsl_matrix_set(X, (size_t)i, 2, x[i] * x[i]);
		gsl_vector_set(Y, (size_t)i, y[i]);
		gsl_vector_set(W, (size_t)i, w[i]);
	}
	double chi2;
	gsl_multifit_wlinear(X, W, Y, c, cov, &chi2, ws);
	double scale = fmax(1, chi2 / (m - 3));
	F->t2_inf = gsl_vector_get(c, 0);
	F->t2_err = sqrt(gsl_matrix_get(cov, 0, 0) * scale);
	F->a2 = gsl_vector_get(c, 1);
	F->b = gsl_vector_get(c, 2);
	F->b_err = sqrt(gsl_matrix_get(cov, 2, 2) * scale);
	F->chi2_dof2 = chi2 / (m - 3);
	gsl_multifit_linear_free(ws);
	gsl_vector_free(c);
	gsl_vector_free(W);
	gsl_vector_free(Y);
	gsl_matrix_free(cov);
	gsl_matrix_free(X);
}

/* Weighted least squares of θ_eff against x = 1/R over R >= RFIT. The standard error
 * of one point, from 8 to 32 runs, is itself uncertain by some 25 %, and a point whose
 * error came out small by chance would pull the fit. The weights use the pooled
 * variance instead: the coverage of a jammed packing of N particles varies like
 * c²/N (its number fluctuations, S(0) of the packing), at every R alike, so each point
 * gets c²/(runs · N) with c² averaged over the fitted points. Error bars of the
 * parameters are scaled up by √(χ²/dof) when the scatter is larger than that. */
static void fit_series(const point *p, int np, fit *F)
{
	double x[MAXR], y[MAXR], w[MAXR], c2 = 0;
	int m = 0;
	for (int i = 0; i < np; i++)
		if (p[i].R >= RFIT) {
			x[m] = 1 / p[i].R;
			y[m] = p[i].theta_eff;
			w[m] = p[i].runs * p[i].n;
			c2 += p[i].se_eff * p[i].se_eff * w[m];
			m++;
		}
	c2 /= m;
	for (int i = 0; i < m; i++)
		w[i] /= c2;
	F->c = sqrt(c2);
	F->npts = m;
	double c0, c1, c00, c01, c11, chi2;
	gsl_fit_wlinear(x, 1, w, 1, y, 1, (size_t)m, &c0, &c1, &c00, &c01, &c11, &chi2);
	double scale = fmax(1, chi2 / (m - 2));
	F->t_inf = c0;
	F->t_err = sqrt(c00 * scale);
	F->a = c1;
	F->a_err = sqrt(c11 * scale);
	F->chi2_dof = chi2 / (m - 2);
	F->q = gsl_cdf_chisq_Q(chi2, m - 2);
	fit_quadratic(x, y, w, m, F);
	F->need_quadratic = F->q < 0.01 && fabs(F->b) > 2 * F->b_err;
}

/* The extrapolation quoted: linear in 1/R unless the 1/R² term is needed; its error
 * bar takes in the model's, how far the other fit lands (a term in 1/R² that the data
 * cannot resolve still moves θ∞: by about b/(R_min R_max) in the linear fit). */
static double f_inf(const fit *F) { return F->need_quadratic ? F->t2_inf : F->t_inf; }
static double model_err(const fit *F)
{
	return isfinite(F->t2_inf) ? fabs(F->t2_inf - F->t_inf) : 0;
}
static double f_err(const fit *F)
{
	return hypot(F->need_quadratic ? F->t2_err : F->t_err, model_err(F));
}

static void print_series(const series *s, const point *p, int np, const fit *F)
{
	printf("  %s lattice (continuum %.6f):\n", lz_lattice_name(s->kind), s->cont);
	printf("  %5s %5s %4s %8s %9s %8s %9s %7s %9s %8s %8s %10s %10s %8s\n", "R", "L", "runs",
	       "N/run", "theta", "+-", "-cont", "ratio", "theta_eff", "+-", "s/run",
	       "us/particle", "bytes/part", "tries/N");
	for (int i = 0; i < np; i++)
		printf("  %5.1f %5lld %4d %8.0f %9.6f %8.6f %+9.6f %7.4f %9.6f %8.6f %8.3f %10.3f "
		       "%10.1f %8.1f\n", p[i].R, (long long)p[i].L, p[i].runs, p[i].n, p[i].theta,
		       p[i].se, p[i].theta - s->cont, p[i].ratio, p[i].theta_eff, p[i].se_eff,
		       p[i].cpu, p[i].us_per_particle, p[i].bytes_per_particle,
		       p[i].tries_per_particle);
	printf("  theta_eff fitted over R >= %g (%d points, pooled spread %.3f/sqrt(N)): %.5f "
	       "+- %.5f %+.4f(+- %.4f)/R, chi2/dof %.2f (Q = %.2g); with 1/R^2: theta_inf = "
	       "%.5f +- %.5f, b = %+.3f +- %.3f, chi2/dof %.2f -> 1/R^2 %s\n", RFIT, F->npts, F->c, F->t_inf, F->t_err, F->a,
	       F->a_err, F->chi2_dof, F->q, F->t2_inf, F->t2_err, F->b, F->b_err, F->chi2_dof2,
	       F->need_quadratic ? "needed" : "not needed");
}

static void checks(lz_lesson *L, const series *s, const point *p, int np, const fit *F)
{
	const char *name = lz_lattice_name(s->kind);
	int jammed = 1;
	for (int i = 0; i < np; i++)
		jammed = jammed && p[i].jammed;
	printf("  %s: every run jammed (nfree = 0, a full scan agrees): %s\n", name,
	       lz_lesson_check(L, jammed));
	printf("  %s: R = 1/2 takes every site, theta = %.6f = %.6f exactly: %s\n", name,
	       p[0].theta, s->full_limit, lz_lesson_check(L, p[0].filled && p[0].se == 0 &&
	                                                 fabs(p[0].theta - s->full_limit) < 1e-12));
	if (s->kind == LZ_LATTICE_SQUARE) {
		double frac = p[1].theta * 4 / M_PI, err = p[1].se * 4 / M_PI;
		printf("  square, R = 1: RSA of 2x2 squares, sites covered %.5f +- %.5f against "
		       "%.5f: %s\n", frac, err, squares_2x2.value, lz_lesson_check(L, fabs(frac -
		       squares_2x2.value) < NSIG * hypot(err, squares_2x2.err)));
	}
	double e = hypot(f_err(F), s->cont_err);
	printf("  %s: theta_eff(R -> inf) = %.5f +- %.5f within %.0f error bars of the "
	       "continuum %.6f (%+.1f): %s\n", name, f_inf(F), f_err(F), NSIG, s->cont,
	       (f_inf(F) - s->cont) / e, lz_lesson_check(L, fabs(f_inf(F) - s->cont) < NSIG * e));
	const point *big = &p[np - 1];
	double se = F->c / sqrt(big->runs * big->n);  /* pooled, as in the fit */
	double moved = big->theta_eff - F->a / big->R;
	double tol = NSIG * sqrt(se * se + pow(F->a_err / big->R, 2) + pow(model_err(F), 2));
	printf("  %s: R = %g alone, moved to R = inf by the fitted -a/R: %.5f on the continuum "
	       "within %.0f error bars (%.5f): %s\n", name, big->R, moved, NSIG, tol / NSIG,
	       lz_lesson_check(L, fabs(moved - s->cont) < tol));
}

static int write_data(lz_lesson *L, const point p[NSERIES][MAXR], const int *np,
                      const fit *F)
{
	static const char *names[] = {"lattice", "dim", "R", "L", "runs", "N", "theta",
	                              "theta_se", "theta_minus_cont", "ratio", "theta_eff",
	                              "theta_eff_se", "cpu_per_run", "us_per_particle",
	                              "bytes_per_particle", "tries_per_particle"};
	static const char *units[] = {"0 square 1 triangular 2 cubic", "", "lattice", "sites",
	                              "", "per run", "", "", "", "", "", "", "s", "us", "bytes",
	                              ""};
	lz_data *d = lz_lesson_data(L, "rsa_jam.dat", "RSA coverage at exact jamming against "
	                            "the radius R in lattice units (mean and standard error over "
	                            "runs), the lattice's excluded area over the continuum's "
	                            "(ratio), and the CPU time and field memory per particle", 16,
	                            names, units);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < NSERIES; k++)
		for (int i = 0; i < np[k]; i++) {
			const point *q = &p[k][i];
			double row[16] = {k, lz_lattice_dim(all[k].kind), q->R, (double)q->L, q->runs,
			                  q->n, q->theta, q->se, q->theta - all[k].cont, q->ratio,
			                  q->theta_eff, q->se_eff, q->cpu, q->us_per_particle,
			                  q->bytes_per_particle, q->tries_per_particle};
			lz_data_row(d, row);
		}
	if (lz_data_close(d) != LZ_OK)
		return LZ_EIO;
	static const char *fnames[] = {"lattice", "inv_R", "theta_eff_linear",
	                               "theta_eff_quadratic"};
	static const char *funits[] = {"", "1/lattice", "", ""};
	d = lz_lesson_data(L, "rsa_fit.dat", "the fits of theta_eff = theta_inf + a/R (+ b/R^2) "
	                   "over R >= 3, from 1/R = 0.5 to 0", 4, fnames, funits);
	if (!d)
		return LZ_EIO;
	for (int k = 0; k < NSERIES; k++)
		for (int j = 0; j <= 50; j++) {
			const fit *f = &F[k];
			double x = 0.01 * j;
			double row[4] = {k, x, f->t_inf + f->a * x, f->t2_inf + (f->a2 + f->b * x) * x};
			lz_data_row(d, row);
		}
	return lz_data_close(d);
}

static int write_json(lz_lesson *L, const point p[NSERIES][MAXR], const int *np,
                      const fit *F, double seconds)
{
	lz_json *j = lz_lesson_json(L, "rsa_jam.json");
	if (!j)
		return LZ_EIO;
	lz_json_int(j, "seed", SEED);
	lz_json_num(j, "fit_from_R", RFIT);
	for (int k = 0; k < NSERIES; k++) {
		const char *name = lz_lattice_name(all[k].kind);
		const point *big = &p[k][np[k] - 1];
		char key[80];
		snprintf(key, sizeof key, "theta_inf_%s", name);
		lz_json_err(j, key, f_inf(&F[k]), f_err(&F[k]));
		snprintf(key, sizeof key, "theta_continuum_%s", name);
		lz_json_num(j, key, all[k].cont);
		snprintf(key, sizeof key, "theta_inf_linear_%s", name);
		lz_json_err(j, key, F[k].t_inf, F[k].t_err);
		snprintf(key, sizeof key, "theta_inf_quadratic_%s", name);
		lz_json_err(j, key, F[k].t2_inf, F[k].t2_err);
		snprintf(key, sizeof key, "a_over_R_%s", name);
		lz_json_err(j, key, F[k].a, F[k].a_err);
		snprintf(key, sizeof key, "chi2_dof_linear_%s", name);
		lz_json_num(j, key, F[k].chi2_dof);
		snprintf(key, sizeof key, "b_over_R2_%s", name);
		lz_json_err(j, key, F[k].b, F[k].b_err);
		snprintf(key, sizeof key, "need_1_over_R2_%s", name);
		lz_json_bool(j, key, F[k].need_quadratic);
		snprintf(key, sizeof key, "theta_R%g_%s", big->R, name);
		lz_json_err(j, key, big->theta, big->se);
		snprintf(key, sizeof key, "us_per_particle_R%g_%s", big->R, name);
		lz_json_num(j, key, big->us_per_particle);
	}
	lz_json_num(j, "cpu_s", seconds);
	return lz_json_end(j);
}

int main(int argc, char **argv)
{
	static point p[NSERIES][MAXR];
	fit F[NSERIES];
	int np[NSERIES];
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "03", &L) != LZ_OK)
		return 2;
	const sizes *sz = L.quick ? &quick : &full;
	if (read_references(&L) != LZ_OK)
		return lz_lesson_error(&L);
	lz_rng *rng = lz_rng_alloc("mt19937", SEED);
	if (!rng)
		return lz_lesson_error(&L);
	printf("rsa_jam: RSA to exact jamming; 2D: radii up to %g, sides %lld..%lld, %.0f+ "
	       "particles a run, about %.0f a radius; 3D: radii up to %g, sides %lld..%lld, "
	       "%.0f+ a run, about %.0f a radius; %d..%d runs a radius; mt19937 seed %u\n",
	       sz->d2.rmax, (long long)sz->d2.lmin, (long long)sz->d2.lmax, sz->d2.nmin,
	       sz->d2.ntot, sz->d3.rmax, (long long)sz->d3.lmin, (long long)sz->d3.lmax,
	       sz->d3.nmin, sz->d3.ntot, sz->smin, sz->smax, SEED);
	double t0 = lz_cpu_now();
	for (int k = 0; k < NSERIES; k++) {
		np[k] = 0;
		for (int i = 0; i < all[k].nr; i++) {
			point *q = &p[k][np[k]];
			q->R = all[k].radii[i];
			if ((q->L = choose_side(&all[k], q->R, sz)) == 0)
				continue;
			if (run_point(&all[k], q->R, sz, rng->gsl, q) != LZ_OK) {
				lz_rng_free(rng);
				return lz_lesson_error(&L);
			}
			np[k]++;
		}
		fit_series(p[k], np[k], &F[k]);
		print_series(&all[k], p[k], np[k], &F[k]);
	}
	double seconds = lz_cpu_now() - t0;
	lz_rng_free(rng);
	for (int k = 0; k < NSERIES; k++)
		checks(&L, &all[k], p[k], np[k], &F[k]);
	if (write_data(&L, p, np, F) != LZ_OK || write_json(&L, p, np, F, seconds) != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "every run jammed exactly, lattice limits at R = 1/2 and 1, "
	                        "R -> infinity on the continuum jamming coverage");
}
