/* integrate_lib.c — the lz_md state: allocation, force evaluation, start-up, the checked step,
 * energies. The step functions themselves are graded (solutions/01-lozenge). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lz/error.h"
#include "lz/integrate.h"
#include "lz/vec.h"

/* The arrays every state carries: r, v, a, r_prev, scratch. */
enum { NARRAYS = 5 };

lz_md *lz_md_alloc(size_t n, int dim, lz_force_fn *f, void *params)
{
	if (n < 1 || dim < 1 || dim > 3 || !f) {
		lz_error(LZ_EINVAL, "lz_md_alloc: n = %zu must be >= 1, dim = %d in 1..3, and "
		         "a force law must be given", n, dim);
		return NULL;
	}
	size_t len = n * (size_t)dim;
	if (len > (SIZE_MAX - sizeof(lz_md)) / (NARRAYS * sizeof(double))) {
		lz_error(LZ_ENOMEM, "lz_md_alloc: n = %zu particles do not fit in memory", n);
		return NULL;
	}
	/* One block: the struct, then the arrays. A step may swap the array pointers
	 * (r_prev and scratch, say) and lz_md_free still frees everything. sizeof(lz_md)
	 * is a multiple of the alignment of double because the struct holds doubles. */
	lz_md *s = calloc(1, sizeof(lz_md) + NARRAYS * len * sizeof(double));
	if (!s) {
		lz_error(LZ_ENOMEM, "lz_md_alloc: no memory for n = %zu particles", n);
		return NULL;
	}
	double *base = (double *)(s + 1);
	s->n = n;
	s->dim = dim;
	s->r = base;
	s->v = base + len;
	s->a = base + 2 * len;
	s->r_prev = base + 3 * len;
	s->scratch = base + 4 * len;
	s->force = f;
	s->force_params = params;
	return s;
}

void lz_md_free(lz_md *s)
{
	free(s);
}

int lz_md_force(lz_md *s)
{
	size_t len = s->n * (size_t)s->dim;
	s->u_prev = s->u;
	s->force_evals++;
	int status = s->force(s->n, s->dim, s->r, s->a, &s->u, s->force_params);
	if (status != LZ_OK)
		return status;
	/* One non-finite entry makes the sum non-finite; so does an overflow, which is
	 * just as fatal for the next step. */
	double sum = s->u;
	for (size_t i = 0; i < len; i++)
		sum += s->a[i];
	if (!isfinite(sum))
		return lz_error(LZ_EPHYS, "the force or the potential energy at t = %g is not "
		                "finite (u = %g): the positions blew up", s->t, s->u);
	return LZ_OK;
}

static int check_dt(double dt)
{
	if (!isfinite(dt) || dt <= 0.0)
		return lz_error(LZ_EINVAL, "time step dt = %g must be finite and > 0", dt);
	return LZ_OK;
}

static int check_integrator(lz_integrator m)
{
	if ((int)m < 0 || m >= LZ_NINTEGRATORS)
		return lz_error(LZ_EINVAL, "integrator %d is not one of the %d known ones",
		                (int)m, (int)LZ_NINTEGRATORS);
	return LZ_OK;
}

int lz_md_start(lz_md *s, lz_integrator m, double dt)
{
	int status = check_dt(dt);
	if (status == LZ_OK)
		status = check_integrator(m);
	if (status == LZ_OK)
		status = lz_md_force(s);
	if (status != LZ_OK)
		return status;
	s->u_prev = s->u;
	s->dt = dt;
	s->t0 = s->t;
	s->nsteps = 0;
	s->v_lags = 0;
	size_t len = s->n * (size_t)s->dim;
	if (m == LZ_VERLET) {
		/* r(t - dt) to second order. Then Verlet's first central-difference velocity
		 * is exactly v(t) again: the run is the velocity-Verlet trajectory. */
		for (size_t i = 0; i < len; i++)
			s->r_prev[i] = s->r[i] - dt * s->v[i] + 0.5 * dt * dt * s->a[i];
	} else if (m == LZ_LEAPFROG) {
		lz_axpy(s->v, -0.5 * dt, s->a, len);
	}
	return LZ_OK;
}

typedef int step_fn(lz_md *s, double dt);
static step_fn *const steps[LZ_NINTEGRATORS] = {
	[LZ_EULER] = lz_step_euler,
	[LZ_SYMPLECTIC_EULER] = lz_step_symplectic_euler,
	[LZ_VERLET] = lz_step_verlet,
	[LZ_VELOCITY_VERLET] = lz_step_velocity_verlet,
	[LZ_LEAPFROG] = lz_step_leapfrog,
};

int lz_md_step(lz_md *s, lz_integrator m, double dt)
{
	int status = check_dt(dt);
	if (status == LZ_OK)
		status = check_integrator(m);
	if (status != LZ_OK)
		return status;
	/* Verlet's r_prev and leapfrog's half-step v were set up for one dt: another dt
	 * would silently mix two step sizes into a first-order error. */
	if ((m == LZ_VERLET || m == LZ_LEAPFROG) && dt != s->dt)
		return lz_error(LZ_EINVAL, "%s was started with dt = %.17g and cannot step with "
		                "dt = %.17g; call lz_md_start again to change the step",
		                lz_integrator_name(m), s->dt, dt);
	if (dt != s->dt) {
		s->t0 = s->t;
		s->nsteps = 0;
		s->dt = dt;
	}
	status = steps[m](s, dt);
	if (status != LZ_OK)
		return status;
	s->nsteps++;
	s->t = s->t0 + (double)s->nsteps * dt;
	if (m == LZ_VERLET)
		s->v_lags = 1;
	return LZ_OK;
}

double lz_md_kinetic(const lz_md *s, lz_integrator m)
{
	size_t len = s->n * (size_t)s->dim;
	if (m != LZ_LEAPFROG)
		return 0.5 * lz_norm2(s->v, len);
	double k = 0.0;
	for (size_t i = 0; i < len; i++) {
		double v = s->v[i] + 0.5 * s->dt * s->a[i];
		k += v * v;
	}
	return 0.5 * k;
}

double lz_md_energy(const lz_md *s, lz_integrator m, double *when)
{
	int lagging = m == LZ_VERLET && s->v_lags;
	if (when)
		*when = lagging ? s->t - s->dt : s->t;
	return lz_md_kinetic(s, m) + (lagging ? s->u_prev : s->u);
}

static const char *const names[LZ_NINTEGRATORS] = {
	[LZ_EULER] = "euler",
	[LZ_SYMPLECTIC_EULER] = "symplectic-euler",
	[LZ_VERLET] = "verlet",
	[LZ_VELOCITY_VERLET] = "velocity-verlet",
	[LZ_LEAPFROG] = "leapfrog",
};

const char *lz_integrator_name(lz_integrator m)
{
	return (int)m >= 0 && m < LZ_NINTEGRATORS ? names[m] : "unknown";
}

int lz_integrator_parse(const char *name, lz_integrator *m)
{
	for (int i = 0; i < LZ_NINTEGRATORS; i++)
		if (name && strcmp(name, names[i]) == 0) {
			*m = (lz_integrator)i;
			return LZ_OK;
		}
	return lz_error(LZ_EINVAL, "unknown integrator '%s': the choices are euler, "
	                "symplectic-euler, verlet, velocity-verlet, leapfrog",
	                name ? name : "(null)");
}

static void round_array(double *x, size_t len)
{
	for (size_t i = 0; i < len; i++)
		x[i] = (float)x[i];
}

void lz_md_round_float(lz_md *s)
{
	size_t len = s->n * (size_t)s->dim;
	round_array(s->r, len);
	round_array(s->v, len);
	round_array(s->a, len);
	round_array(s->r_prev, len);
}
