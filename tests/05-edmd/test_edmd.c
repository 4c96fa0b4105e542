/* test_edmd.c — stage 05, event-driven hard spheres (lz/edmd.h): when two spheres
 * touch, how they bounce, when a particle leaves its cell, the prediction of a
 * particle's next event and the event loop.
 *
 * The unit tests check each graded function against geometry rather than against
 * its own formula: a collision time is built backwards from a chosen contact, a
 * face time must put the particle on the face it names, a bounce must conserve what
 * physics conserves. The runs check what an exact event-driven simulation must do:
 * hand-computed collision times of two particles, a stale event skipped, energy and
 * momentum kept to round-off, no overlap at high density, free flight of one
 * particle, walls and gravity in closed form, the ideal-gas limit, and the pressure
 * of hard spheres at η = 0.3 against the reference equation of state
 * (datasets/reference/hard-spheres.csv, collision-identity.csv) with block error
 * bars. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>

#include "lz/edmd.h"
#include "lz/rng.h"
#include "lztest.h"



static double dot3(const double *a, const double *b)
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double norm3(const double *a) { return sqrt(dot3(a, a)); }

/* A random unit vector (z = 0 in 2D). */
static void unit_vector(gsl_rng *r, int dim, double k[3])
{
	if (dim == 3) {
		gsl_ran_dir_3d(r, &k[0], &k[1], &k[2]);
	} else {
		gsl_ran_dir_2d(r, &k[0], &k[1]);
		k[2] = 0;
	}
}

/* ---- pair time ---- */

LZ_TEST(pair_time_head_on_closed_form)
{
	/* centres d apart, closing at speed u along one axis: they touch when the gap
	 * d - 1 is closed, t = (d - 1)/u — on every axis, both ways round. The last two
	 * nearly touch: d = 1 + 2^-k has an exact square, so the data carry no error, but
	 * u is no power of two, so b = dr·dv is rounded and the textbook root (-b - √disc)/dv²
	 * cancels all but about 2^-k of it (relative errors 1e-10 and 1e-9). Reversing dv
	 * gives the same pair moving apart: it never meets. */
	static const double cases[][2] = {{2, 1}, {3, 0.5}, {1.5, 4}, {11, 2.5}, {1.25, 1e-3}, {101, 1e3},
	                                  {1 + 0x1p-20, 0.1}, {1 + 0x1p-24, 3.7}};
	for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
		for (int a = 0; a < 3; a++)
			for (int s = -1; s <= 1; s += 2) {
				double d = cases[c][0], u = cases[c][1];
				double dr[3] = {0, 0, 0}, dv[3] = {0, 0, 0};
				dr[a] = s * d;
				dv[a] = -s * u;
				double t = lz_edmd_pair_time(dr, dv), want = (d - 1) / u;
				LZ_REQUIRE(fabs(t - want) <= 1e-14 * want,
				      "head on along axis %d: centres %g apart closing at %g; they touch when "
				      "the gap %g is closed, at t = %.17g; lz_edmd_pair_time gave %.17g%s", a, d,
				      u, d - 1, want, t, t > want ? " (the later root? the spheres would be "
				      "inside each other)" : "");
				dv[a] = s * u;
				t = lz_edmd_pair_time(dr, dv);
				LZ_REQUIRE(isinf(t) && t > 0, "head on along axis %d: centres %g apart moving APART at "
				      "%g never meet, expected INFINITY; lz_edmd_pair_time gave %.17g — only a pair "
				      "with dr·dv < 0 approaches", a, d, u, t);
			}
	/* a moving frame changes nothing: only dv matters (both move, diagonal) */
	double dr[3] = {3 / sqrt(3.0), 3 / sqrt(3.0), 3 / sqrt(3.0)};
	double dv[3] = {-2 / sqrt(3.0), -2 / sqrt(3.0), -2 / sqrt(3.0)};
	double t = lz_edmd_pair_time(dr, dv);
	LZ_REQUIRE(fabs(t - 1.0) < 1e-14, "head on along the diagonal: 3 apart closing at 2, expected t "
	      "= 1, got %.17g", t);
}
END_TEST

LZ_TEST(pair_time_oblique_built_from_the_contact)
{
	/* Work backwards: pick the contact direction k (|k| = 1), a relative velocity dv
	 * that closes along k (dv·k < 0) and a time t*; then dr = k - dv t* touches at
	 * t* while approaching, so t* is the FIRST contact. 2D and 3D. */
	gsl_rng *r = lz_test_rng(511);
	for (int trial = 0; trial < 200000; trial++) {
		int dim = 2 + trial % 2;
		double k[3], dv[3];
		unit_vector(r, dim, k);
		do {
			unit_vector(r, dim, dv);
		} while (dot3(dv, k) > -0.02);
		double speed = exp(gsl_ran_flat(r, log(1e-2), log(1e2)));
		for (int a = 0; a < 3; a++)
			dv[a] *= speed;
		double tstar = exp(gsl_ran_flat(r, log(1e-6), log(1e2)));
		double dr[3];
		for (int a = 0; a < 3; a++)
			dr[a] = k[a] - dv[a] * tstar;
		double t = lz_edmd_pair_time(dr, dv);
		/* dr = k - dv t* carries a round-off of about (1 + |dv| t*) ulp, which moves
		 * the contact by that over the normal closing speed |dv·k|; and any formula
		 * forms the discriminant b² - dv² c, whose relative round-off grows as
		 * b²/(dv·k)² for a long, nearly grazing approach: allow for both */
		double un = fabs(dot3(dv, k)), b = fabs(dot3(dr, dv));
		double tol = 1e-13 * tstar + 1e-15 * (1 + speed * tstar + b * tstar) / un;
		double err = fabs(t - tstar);
		LZ_REQUIRE(err <= tol,
		      "%dD, dr = (%.6g, %.6g, %.6g), dv = (%.6g, %.6g, %.6g): built to touch at t = %.15g "
		      "(contact normal (%.3f, %.3f, %.3f), approaching), lz_edmd_pair_time gave %.15g%s",
		      dim, dr[0], dr[1], dr[2], dv[0], dv[1], dv[2], tstar, k[0], k[1], k[2], t,
		      isinf(t) ? ": the pair approaches and meets, it is not a miss" : "");
		/* time reversed (dv -> -dv): the pair touched t* ago and now recedes */
		double back[3] = {-dv[0], -dv[1], -dv[2]};
		t = lz_edmd_pair_time(dr, back);
		LZ_REQUIRE(isinf(t) && t > 0, "%dD, dr = (%.6g, %.6g, %.6g), dv = (%.6g, %.6g, %.6g): this pair "
		      "touched %.6g ago and is moving apart (dr·dv > 0), expected INFINITY, got %.17g", dim,
		      dr[0], dr[1], dr[2], back[0], back[1], back[2], tstar, t);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(pair_time_never_when_receding_sideways_missing_or_grazing)
{
	struct {
		double dr[3], dv[3];
		const char *what;
	} never[] = {
	    {{2, 0, 0}, {1, 0, 0}, "receding head on"},
	    {{2, 0.5, 0}, {0.3, 1, 0}, "receding obliquely"},
	    {{-3, 1, 2}, {-1, 0.2, 0.1}, "receding (negative dr)"},
	    {{2, 0, 0}, {0, 1, 0}, "moving sideways (dr·dv = 0)"},
	    {{0, 0, 1.5}, {3, -2, 0}, "moving sideways in z (dr·dv = 0)"},
	    {{5, 1.5, 0}, {-1, 0, 0}, "missing: impact parameter 1.5 > 1"},
	    {{5, 0, 1.0000001}, {-1, 0, 0}, "missing by 1e-7"},
	    {{5, 1, 0}, {-1, 0, 0}, "grazing: impact parameter exactly 1 (disc = 0)"},
	    {{-4, 0, 1}, {2, 0, 0}, "grazing along -x: impact parameter exactly 1"},
	    {{3, 0, 0}, {0, 0, 0}, "at rest relative to each other"},
	    {{1, 0, 0}, {1, 0, 0}, "touching and receding"},
	    {{0, 1, 0}, {1, 0, 0}, "touching and moving sideways"},
	    {{1 - 1e-13, 0, 0}, {0, 1, 0}, "overlapping by round-off and moving sideways"},
	    {{0.6, 0.8, 0}, {0.8, -0.6, 0}, "touching, tangential velocity only"},
	};
	for (size_t c = 0; c < sizeof never / sizeof never[0]; c++) {
		double t = lz_edmd_pair_time(never[c].dr, never[c].dv);
		LZ_REQUIRE(isinf(t) && t > 0,
		      "%s: dr = (%g, %g, %g), dv = (%g, %g, %g) never touch (or only graze), expected "
		      "INFINITY; lz_edmd_pair_time gave %.17g%s", never[c].what, never[c].dr[0],
		      never[c].dr[1], never[c].dr[2], never[c].dv[0], never[c].dv[1], never[c].dv[2], t,
		      isnan(t) ? " (NaN: a square root of a negative discriminant?)" : "");
	}
	/* random receding and missing pairs */
	gsl_rng *r = lz_test_rng(512);
	for (int trial = 0; trial < 100000; trial++) {
		double dr[3], dv[3], k[3];
		unit_vector(r, 3, k);
		unit_vector(r, 3, dv);
		double d = 1 + exp(gsl_ran_flat(r, log(1e-6), log(10)));
		for (int a = 0; a < 3; a++)
			dr[a] = d * k[a];
		if (dot3(dr, dv) < 0) {
			/* turn it into a miss: move dr sideways so the closest approach is > 1 */
			double b = dot3(dr, dv);
			double perp[3], pn;
			for (int a = 0; a < 3; a++)
				perp[a] = dr[a] - b * dv[a];
			pn = norm3(perp);
			if (pn < 1e-3)
				continue;
			for (int a = 0; a < 3; a++)
				dr[a] = perp[a] / pn * (1.001 + gsl_rng_uniform(r)) - 3 * dv[a];
		}
		double t = lz_edmd_pair_time(dr, dv);
		LZ_REQUIRE(isinf(t), "dr = (%.6g, %.6g, %.6g), dv = (%.6g, %.6g, %.6g): receding or passing "
		      "at a closest distance above 1, expected INFINITY, got %.17g", dr[0], dr[1], dr[2],
		      dv[0], dv[1], dv[2], t);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(pair_time_touching_and_approaching_is_now)
{
	struct {
		double dr[3], dv[3];
		const char *what;
	} now[] = {
	    {{1, 0, 0}, {-1, 0, 0}, "touching exactly, head on"},
	    {{0, 0, -1}, {0, 0.5, 2}, "touching exactly, approaching obliquely"},
	    {{0.6, 0.8, 0}, {-1, 0, 0}, "touching exactly (0.6, 0.8), approaching"},
	    {{1 - 1e-13, 0, 0}, {-1, 0, 0}, "overlapping by 1e-13 (round-off), approaching"},
	    {{0, 1 - 3e-16, 0}, {0.2, -1e-3, 0}, "overlapping by 3e-16, approaching slowly"},
	    {{0.6 - 1e-12, 0.8, 0}, {-0.1, -0.1, 0}, "overlapping by round-off, approaching obliquely"},
	};
	for (size_t c = 0; c < sizeof now / sizeof now[0]; c++) {
		double t = lz_edmd_pair_time(now[c].dr, now[c].dv);
		/* "exactly" touching pairs like (0.6, 0.8) have |dr|² = 1 + 1 ulp in floating
		 * point: a time of 1e-16 is now to round-off */
		LZ_REQUIRE(t >= 0 && t <= 1e-15, "%s: dr = (%.17g, %g, %g), dv = (%g, %g, %g) collide at once: expected t "
		      "= 0 (to round-off), got %.17g%s", now[c].what, now[c].dr[0], now[c].dr[1], now[c].dr[2],
		      now[c].dv[0], now[c].dv[1], now[c].dv[2], t,
		      t < 0 ? " (a negative time: the event would be in the past)"
		            : isinf(t) ? " (they would pass through each other)" : "");
		/* the same contact with the velocity reversed: moving apart, never again */
		double apart[3] = {-now[c].dv[0], -now[c].dv[1], -now[c].dv[2]};
		t = lz_edmd_pair_time(now[c].dr, apart);
		LZ_REQUIRE(isinf(t) && t > 0, "%s, but moving apart (dv = (%g, %g, %g)): a pair that touches "
		      "and recedes never collides, expected INFINITY, got %.17g — test the approach "
		      "(dr·dv < 0) before anything else", now[c].what, apart[0], apart[1], apart[2], t);
	}
}
END_TEST

/* The first contact time by Newton's method in long double from t = 0, where f(t)
 * = dv² t² + 2 b t + c > 0 is convex and falling: the iterates climb monotonically
 * to the smaller root. An independent way to the answer, in more digits. */
static long double newton_contact(const double dr[3], const double dv[3])
{
	long double b = 0, dv2 = 0, dr2 = 0;
	for (int a = 0; a < 3; a++) {
		b += (long double)dr[a] * dv[a];
		dv2 += (long double)dv[a] * dv[a];
		dr2 += (long double)dr[a] * dr[a];
	}
	long double c = dr2 - 1, t = 0;
	for (int it = 0; it < 200; it++) {
		long double f = (dv2 * t + 2 * b) * t + c, fp = 2 * (dv2 * t + b);
		long double next = t - f / fp;
		if (next == t)
			break;
		t = next;
	}
	return t;
}

LZ_TEST(pair_time_root_is_numerically_stable)
{
	/* A near-touching pair closing fast: c = dr² - 1 is tiny and b² >> dv² c. The
	 * textbook root (-b - √(b² - dv² c))/dv² subtracts two nearly equal numbers and
	 * keeps only about |c|/ulp digits; c/(-b + √disc) keeps them all. dr = 1 + 2^-k
	 * makes c exact in double (no error from the data), dv is any direction. */
	gsl_rng *r = lz_test_rng(513);
	for (int trial = 0; trial < 20000; trial++) {
		int k = 14 + trial % 12;  /* gaps 2^-14 .. 2^-25 */
		double dr[3] = {1 + ldexp(1.0, -k), 0, 0}, dv[3];
		do {
			unit_vector(r, 3, dv);
		} while (dv[0] > -0.3);
		double speed = gsl_ran_flat(r, 0.5, 3);
		for (int a = 0; a < 3; a++)
			dv[a] *= speed;
		double t = lz_edmd_pair_time(dr, dv);
		long double want = newton_contact(dr, dv);
		double rel = (double)fabsl((t - want) / want);
		LZ_REQUIRE(rel < 1e-13,
		      "a pair 2^-%d = %.3g apart closing at %.3g (dr·dv = %.6g): the first contact is "
		      "at t = %.17Lg (Newton, long double), lz_edmd_pair_time gave %.17g — relative "
		      "error %.2g; the root -b - √disc cancels digits here: use c / (-b + √disc)",
		      k, ldexp(1.0, -k), speed, dr[0] * dv[0], want, t, rel);
		for (int a = 0; a < 3; a++)
			dv[a] = -dv[a];
		t = lz_edmd_pair_time(dr, dv);
		LZ_REQUIRE(isinf(t) && t > 0, "a pair 2^-%d apart moving apart at %.3g never meets, expected "
		      "INFINITY, got %.17g", k, speed, t);
	}
	gsl_rng_free(r);
}
END_TEST

/* ---- bounce ---- */

static lz_edmd_particle particle_with(const double v[3])
{
	lz_edmd_particle p;
	memset(&p, 0, sizeof p);
	for (int a = 0; a < 3; a++)
		p.v[a] = v[a];
	return p;
}

LZ_TEST(bounce_head_on_swaps_the_velocities)
{
	/* equal masses, elastic, head on: the velocities are exchanged */
	double va[3] = {1.5, 0, 0}, vb[3] = {-0.5, 0, 0};
	lz_edmd_particle a = particle_with(va), b = particle_with(vb);
	double dr[3] = {1, 0, 0};
	double w = lz_edmd_bounce(&a, &b, dr, 1.0);
	LZ_REQUIRE(fabs(a.v[0] + 0.5) < 1e-15 && fabs(b.v[0] - 1.5) < 1e-15 && a.v[1] == 0 &&
	              b.v[1] == 0 && a.v[2] == 0 && b.v[2] == 0,
	      "head on along +x, elastic, v_a = 1.5, v_b = -0.5: equal masses exchange velocities; "
	      "got v_a = (%g, %g, %g), v_b = (%g, %g, %g)", a.v[0], a.v[1], a.v[2], b.v[0], b.v[1],
	      b.v[2]);
	LZ_REQUIRE(fabs(w - 2.0) < 1e-15, "head on, elastic, closing speed 2: each particle's momentum "
	      "changes by 2, so the virial |r_ab|·|Δp| = 2; got %.17g%s", w,
	      w < 0 ? " (negative: the virial r_ab·Δp_a of a repulsion is positive)" : "");
	/* along -y with dr the other way round */
	double vc[3] = {0.3, -1, 0.2}, vd[3] = {0.3, 1, 0.2};
	lz_edmd_particle c = particle_with(vc), d = particle_with(vd);
	double dr2[3] = {0, -1, 0};
	w = lz_edmd_bounce(&c, &d, dr2, 1.0);
	LZ_REQUIRE(fabs(c.v[1] - 1) < 1e-15 && fabs(d.v[1] + 1) < 1e-15 && c.v[0] == 0.3 && d.v[2] == 0.2,
	      "head on along -y (dr = (0, -1, 0)), v_a = (0.3, -1, 0.2), v_b = (0.3, 1, 0.2): "
	      "expected v_a = (0.3, 1, 0.2), v_b = (0.3, -1, 0.2); got v_a = (%g, %g, %g), v_b = "
	      "(%g, %g, %g)", c.v[0], c.v[1], c.v[2], d.v[0], d.v[1], d.v[2]);
	LZ_REQUIRE(fabs(w - 2) < 1e-15, "head on along -y, closing speed 2: virial 2 expected, got %g", w);
	/* inelastic head on, e = 1/2: the closing speed 2 becomes an opening speed 1 */
	double ve[3] = {1, 0, 0}, vf[3] = {-1, 0, 0};
	lz_edmd_particle e = particle_with(ve), f = particle_with(vf);
	w = lz_edmd_bounce(&e, &f, dr, 0.5);
	LZ_REQUIRE(fabs(e.v[0] + 0.5) < 1e-15 && fabs(f.v[0] - 0.5) < 1e-15 && fabs(w - 1.5) < 1e-15,
	      "head on, restitution 1/2, v = ±1: after the bounce v_a = -0.5, v_b = 0.5 and the "
	      "virial |Δp| = 1.5; got v_a = %g, v_b = %g, virial %g", e.v[0], f.v[0], w);
}
END_TEST

/* One random bounce in dim dimensions with restitution er: every law checked. */
static void check_random_bounce(gsl_rng *r, int dim, double er, double dr_len)
{
	double k[3], va[3], vb[3], dr[3];
	unit_vector(r, dim, k);
	for (int a = 0; a < 3; a++) {
		va[a] = a < dim ? gsl_ran_gaussian(r, 1.0) : 0;
		vb[a] = a < dim ? gsl_ran_gaussian(r, 1.0) : 0;
		dr[a] = dr_len * k[a];
	}
	double u0 = (vb[0] - va[0]) * k[0] + (vb[1] - va[1]) * k[1] + (vb[2] - va[2]) * k[2];
	if (u0 > 0) { /* make it approach: swap the two velocities */
		for (int a = 0; a < 3; a++) {
			double x = va[a];
			va[a] = vb[a];
			vb[a] = x;
		}
		u0 = -u0;
	}
	lz_edmd_particle pa = particle_with(va), pb = particle_with(vb);
	double w = lz_edmd_bounce(&pa, &pb, dr, er);
	double scale = fabs(va[0]) + fabs(va[1]) + fabs(va[2]) + fabs(vb[0]) + fabs(vb[1]) + fabs(vb[2]);
	double tol = 1e-14 * scale;
	const char *D = dim == 3 ? "3D" : "2D";
	for (int a = 0; a < 3; a++) {
		double before = va[a] + vb[a], after = pa.v[a] + pb.v[a];
		LZ_REQUIRE(fabs(after - before) <= tol,
		      "%s bounce, restitution %g: momentum %c changed from %.17g to %.17g — the "
		      "impulses on a and b must be equal and opposite", D, er, "xyz"[a], before, after);
	}
	if (dim == 2)
		LZ_REQUIRE(pa.v[2] == 0 && pb.v[2] == 0, "2D bounce: the z velocities became %g and %g, they "
		      "must stay 0", pa.v[2], pb.v[2]);
	/* only the normal components change */
	double dva[3], dvb[3];
	for (int a = 0; a < 3; a++) {
		dva[a] = pa.v[a] - va[a];
		dvb[a] = pb.v[a] - vb[a];
	}
	double na = dot3(dva, k), nb = dot3(dvb, k);
	for (int a = 0; a < 3; a++) {
		LZ_REQUIRE(fabs(dva[a] - na * k[a]) <= tol && fabs(dvb[a] - nb * k[a]) <= tol,
		      "%s bounce, restitution %g, normal k = (%.4f, %.4f, %.4f): the change of velocity "
		      "of a is (%.6g, %.6g, %.6g), of b (%.6g, %.6g, %.6g); it must be along k — the "
		      "tangential components do not change (normalise dr?)", D, er, k[0], k[1], k[2],
		      dva[0], dva[1], dva[2], dvb[0], dvb[1], dvb[2]);
	}
	double u1 = (pb.v[0] - pa.v[0]) * k[0] + (pb.v[1] - pa.v[1]) * k[1] + (pb.v[2] - pa.v[2]) * k[2];
	LZ_REQUIRE(fabs(u1 + er * u0) <= tol,
	      "%s bounce, restitution %g: the normal relative velocity (v_b - v_a)·k was %.12g "
	      "before, %.12g after; expected %.12g (reversed and scaled by the restitution)", D, er,
	      u0, u1, -er * u0);
	double ke0 = 0.5 * (dot3(va, va) + dot3(vb, vb)), ke1 = 0.5 * (dot3(pa.v, pa.v) + dot3(pb.v, pb.v));
	double loss = (1 - er * er) / 4 * u0 * u0;
	LZ_REQUIRE(fabs((ke0 - ke1) - loss) <= 1e-14 * scale * scale,
	      "%s bounce, restitution %g, normal closing speed %.6g: the kinetic energy dropped by "
	      "%.12g, expected (1 - e²)/4 · u² = %.12g", D, er, -u0, ke0 - ke1, loss);
	double dp = norm3(dva);
	LZ_REQUIRE(fabs(w - dr_len * dp) <= 1e-14 * (1 + dr_len * dp),
	      "%s bounce, restitution %g, |dr| = %.15g: the momentum of a changed by |Δp| = %.12g, "
	      "so the virial r_ab·Δp_a = |dr|·|Δp| = %.12g; lz_edmd_bounce returned %.12g", D, er,
	      dr_len, dp, dr_len * dp, w);
}

LZ_TEST(bounce_elastic_conserves_momentum_and_energy)
{
	gsl_rng *r = lz_test_rng(514);
	for (int trial = 0; trial < 100000; trial++)
		check_random_bounce(r, 2 + trial % 2, 1.0, trial % 3 == 0 ? 1 + 1e-10 : 1.0);
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(bounce_inelastic_loses_exactly_the_normal_energy)
{
	gsl_rng *r = lz_test_rng(515);
	for (int trial = 0; trial < 100000; trial++) {
		/* also the nearly perfectly inelastic limit: the normal motion is destroyed */
		double er = trial % 5 == 0 ? 0.1 : trial % 7 == 0 ? 1e-9 : gsl_ran_flat(r, 0.05, 1.0);
		check_random_bounce(r, 2 + trial % 2, er, trial % 3 == 0 ? 1 - 1e-12 : 1.0);
	}
	gsl_rng_free(r);
}
END_TEST

/* ---- the cell's faces ---- */

/* A box by hand, just what lz_edmd_cell_time reads: dim, L, m cells per side, walls
 * per axis (bit a), gravity. */
static lz_edmd *hand_box(int dim, double L, int m, int walls, double g)
{
	lz_edmd *e = calloc(1, sizeof *e);
	LZ_REQUIRE(e, "out of memory for a hand-made box");
	e->dim = dim;
	e->L = L;
	e->g = g;
	e->restitution = 1;
	for (int a = 0; a < 3; a++) {
		e->m[a] = a < dim ? m : 1;
		e->w[a] = L / e->m[a];
		e->wall[a] = a < dim && (walls >> a & 1);
	}
	e->ncells = (size_t)e->m[0] * e->m[1] * e->m[2];
	return e;
}

static uint32_t hand_cell(const lz_edmd *e, const int cc[3])
{
	return (uint32_t)(cc[0] + e->m[0] * (cc[1] + e->m[1] * cc[2]));
}

/* The span [lo, hi] on axis a of cell coordinate c: the cell, or the wall contact. */
static void span_of(const lz_edmd *e, int a, int c, double *lo, double *hi)
{
	*lo = c * e->w[a];
	*hi = (c + 1) * e->w[a];
	if (e->wall[a] && c == 0)
		*lo = 0.5;
	if (e->wall[a] && c == e->m[a] - 1)
		*hi = e->L - 0.5;
}

LZ_TEST(cell_time_reaches_the_face_it_names)
{
	/* A particle anywhere in a cell, any velocity: at the returned time it must be ON
	 * the face it names (that coordinate equal to the face's) and inside the cell on
	 * every other axis — and it must not have left earlier (half way it is inside). */
	gsl_rng *r = lz_test_rng(516);
	for (int trial = 0; trial < 200000; trial++) {
		int dim = 2 + trial % 2;
		int walls = trial % 7 == 0 ? 7 : trial % 7 == 1 ? 1 : 0;
		int m = 3 + (int)gsl_rng_uniform_int(r, 6);
		lz_edmd *e = hand_box(dim, m * gsl_ran_flat(r, 1.0, 2.5), m, walls, 0);
		int cc[3] = {0, 0, 0};
		double x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
		for (int a = 0; a < dim; a++) {
			cc[a] = (int)gsl_rng_uniform_int(r, (unsigned long)m);
			double lo, hi;
			span_of(e, a, cc[a], &lo, &hi);
			x[a] = lo + (hi - lo) * gsl_rng_uniform(r);
			v[a] = gsl_rng_uniform(r) < 0.1 ? 0 : gsl_ran_gaussian(r, 1.0);
		}
		if (v[0] == 0 && v[1] == 0 && v[2] == 0)
			v[0] = 0.5;
		uint32_t c = hand_cell(e, cc);
		int face = -1;
		double t = lz_edmd_cell_time(e, x, v, c, &face);
		LZ_REQUIRE(t >= 0 && isfinite(t), "%dD, cell (%d, %d, %d) of %d per side, r = (%.6g, %.6g, "
		      "%.6g), v = (%.6g, %.6g, %.6g): a moving particle leaves its cell in a finite time "
		      ">= 0, got %g", dim, cc[0], cc[1], cc[2], m, x[0], x[1], x[2], v[0], v[1], v[2], t);
		LZ_REQUIRE(face >= 0 && face < 2 * dim, "%dD: face %d is not one of the 2·dim faces (2·axis + "
		      "up)", dim, face);
		int fa = face / 2, up = face % 2;
		double lo, hi;
		span_of(e, fa, cc[fa], &lo, &hi);
		double at = x[fa] + v[fa] * t, want = up ? hi : lo;
		LZ_REQUIRE(fabs(at - want) <= 1e-12 * e->L,
		      "%dD, cell (%d, %d, %d) of side %.4g%s, r = (%.6g, %.6g, %.6g), v = (%.6g, %.6g, "
		      "%.6g): lz_edmd_cell_time says face %d (axis %d, %s) at t = %.12g, but then %c = "
		      "%.12g, not the face's %.12g", dim, cc[0], cc[1], cc[2], e->w[0],
		      walls ? " with walls" : "", x[0], x[1], x[2], v[0], v[1], v[2], face, fa,
		      up ? "up" : "down", t, "xyz"[fa], at, want);
		LZ_REQUIRE(v[fa] != 0 && (v[fa] > 0) == (up == 1), "%dD: face %d (axis %d, %s) named for a "
		      "velocity %g along that axis", dim, face, fa, up ? "up" : "down", v[fa]);
		for (int a = 0; a < dim; a++) {
			double l2, h2;
			span_of(e, a, cc[a], &l2, &h2);
			double y = x[a] + v[a] * t, tol = 1e-12 * e->L;
			LZ_REQUIRE(y >= l2 - tol && y <= h2 + tol,
			      "%dD, cell (%d, %d, %d), r = (%.6g, %.6g, %.6g), v = (%.6g, %.6g, %.6g): at the "
			      "face time %.12g (face %d) %c = %.12g is already outside [%.12g, %.12g] — "
			      "another face comes first (take the earliest axis)", dim, cc[0], cc[1], cc[2],
			      x[0], x[1], x[2], v[0], v[1], v[2], t, face, "xyz"[a], y, l2, h2);
		}
		free(e);
	}
	gsl_rng_free(r);
}
END_TEST

LZ_TEST(cell_time_at_rest_on_an_axis_and_by_round_off)
{
	lz_edmd *e = hand_box(3, 12, 4, 0, 0);  /* cells of 3 */
	int face = -7;
	double r0[3] = {4, 5, 7}, still[3] = {0, 0, 0};
	double t = lz_edmd_cell_time(e, r0, still, hand_cell(e, (int[3]){1, 1, 2}), &face);
	LZ_REQUIRE(isinf(t) && t > 0, "a particle at rest never leaves its cell: expected INFINITY, got "
	      "%g", t);
	/* one axis at a time, both ways: r = (4, 5, 7) in cell (1, 1, 2) = [3,6]x[3,6]x[6,9] */
	struct {
		double v[3], t;
		int face;
	} one[] = {{{2, 0, 0}, 1.0, 1},   {{-0.5, 0, 0}, 2.0, 0}, {{0, 4, 0}, 0.25, 3},
	           {{0, -1, 0}, 2.0, 2}, {{0, 0, 1}, 2.0, 5},    {{0, 0, -0.25}, 4.0, 4},
	           {{2, -3, 0}, 2.0 / 3, 2}, {{-1, 0, 3}, 2.0 / 3, 5}};
	for (size_t c = 0; c < sizeof one / sizeof one[0]; c++) {
		face = -1;
		t = lz_edmd_cell_time(e, r0, one[c].v, hand_cell(e, (int[3]){1, 1, 2}), &face);
		LZ_REQUIRE(fabs(t - one[c].t) < 1e-15 && face == one[c].face,
		      "r = (4, 5, 7) in the cell [3,6]x[3,6]x[6,9], v = (%g, %g, %g): expected face %d "
		      "at t = %.15g, got face %d at t = %.15g", one[c].v[0], one[c].v[1], one[c].v[2],
		      one[c].face, one[c].t, face, t);
	}
	/* exactly on a face: on the upper one moving up it leaves now, moving down it has
	 * the whole cell to cross; the same on the lower face */
	struct {
		double x, v, t;
		int face;
	} on[] = {{6, 1, 0, 1}, {6, -1, 3, 0}, {3, 0.5, 6, 1}, {3, -2, 0, 0}};
	for (size_t c = 0; c < sizeof on / sizeof on[0]; c++) {
		double ro[3] = {on[c].x, 5, 7}, vo[3] = {on[c].v, 0, 0};
		face = -1;
		t = lz_edmd_cell_time(e, ro, vo, hand_cell(e, (int[3]){1, 1, 2}), &face);
		LZ_REQUIRE(t == on[c].t && face == on[c].face, "x = %g exactly on a face of the cell [3, 6] "
		      "(on x), v_x = %g: expected face %d at t = %g, got face %d at t = %.17g", on[c].x,
		      on[c].v, on[c].face, on[c].t, face, t);
	}
	/* round-off put the particle a hair beyond its upper face, still moving up: it
	 * leaves now (t = 0), never in the past */
	double hair[3] = {6 + 1e-14, 5, 7}, up[3] = {1, 0, 0};
	t = lz_edmd_cell_time(e, hair, up, hand_cell(e, (int[3]){1, 1, 2}), &face);
	LZ_REQUIRE(t == 0 && face == 1, "x = 6 + 1e-14 in a cell that ends at 6, moving up: the face is "
	      "already reached, expected t = 0 at face 1, got t = %.17g at face %d%s", t, face,
	      t < 0 ? " (a time in the past)" : "");
	double hair2[3] = {4, 3 - 1e-14, 7}, down[3] = {0.1, -1, 0.2};
	t = lz_edmd_cell_time(e, hair2, down, hand_cell(e, (int[3]){1, 1, 2}), &face);
	LZ_REQUIRE(t == 0 && face == 2, "y = 3 - 1e-14 in a cell that starts at 3, moving down: expected "
	      "t = 0 at face 2, got t = %.17g at face %d", t, face);
	/* a hair beyond but moving back in: the far face */
	double back[3] = {-2, 0, 0};
	t = lz_edmd_cell_time(e, hair, back, hand_cell(e, (int[3]){1, 1, 2}), &face);
	LZ_REQUIRE(fabs(t - 1.5) < 1e-14 && face == 0, "x = 6 + 1e-14 moving down at 2 in [3, 6]: the "
	      "lower face at t = 1.5, got face %d at t = %.17g", face, t);
	free(e);
	/* 2D: the z axis is not there, even with a z velocity of 0 */
	lz_edmd *f = hand_box(2, 9, 3, 0, 0);
	double r2[3] = {1, 1, 0}, v2[3] = {0, 0, 0};
	t = lz_edmd_cell_time(f, r2, v2, 0, &face);
	LZ_REQUIRE(isinf(t), "2D at rest: expected INFINITY, got %g", t);
	double v3[3] = {0, -0.5, 0};
	t = lz_edmd_cell_time(f, r2, v3, 0, &face);
	LZ_REQUIRE(fabs(t - 2) < 1e-15 && face == 2, "2D, (1, 1) in the cell [0,3]x[0,3] moving -y at "
	      "0.5: expected face 2 at t = 2, got face %d at t = %g", face, t);
	free(f);
}
END_TEST

LZ_TEST(cell_time_walls_at_the_contact)
{
	/* walls: the centre of a sphere of diameter 1 stops at 1/2 from the wall, so in
	 * an edge cell the wall-side face is replaced by the contact 1/2 (or L - 1/2) */
	lz_edmd *e = hand_box(3, 12, 4, 7, 0);  /* cells of 3, walls on every axis */
	int face;
	struct {
		int cc[3];
		double r[3], v[3], t;
		int face;
		const char *what;
	} w[] = {
	    {{0, 1, 1}, {2.5, 4, 4}, {-1, 0, 0}, 2.0, 0, "x = 2.5 towards the wall at x = 0"},
	    {{3, 1, 1}, {10, 4, 4}, {0.5, 0, 0}, 3.0, 1, "x = 10 towards the wall at x = 12"},
	    {{1, 0, 1}, {4, 1.5, 4}, {0, -2, 0}, 0.5, 2, "y = 1.5 towards the wall at y = 0"},
	    {{1, 1, 3}, {4, 4, 11}, {0, 0, 1}, 0.5, 5, "z = 11 towards the wall at z = 12"},
	    {{0, 1, 1}, {0.5, 4, 4}, {-1, 0, 0}, 0.0, 0, "touching the wall at x = 0, moving in"},
	    {{0, 1, 1}, {1, 4, 4}, {1, 0, 0}, 2.0, 1, "x = 1 in the edge cell, moving away from the wall"},
	    {{1, 1, 1}, {4, 4, 4}, {-1, 0, 0}, 1.0, 0, "an inner cell: no wall"},
	    {{0, 1, 1}, {1.5, 4, 4}, {-1, 0.25, 0}, 1.0, 0,
	     "towards the wall at x = 0 and slowly along y (its face at t = 8): the wall first"},
	    {{1, 3, 1}, {4, 11, 4.5}, {0, 0.25, -0.5}, 2.0, 3,
	     "towards the wall at y = 12 (contact 11.5 at t = 2) and down z (face at t = 3)"},
	};
	for (size_t c = 0; c < sizeof w / sizeof w[0]; c++) {
		face = -1;
		double t = lz_edmd_cell_time(e, w[c].r, w[c].v, hand_cell(e, w[c].cc), &face);
		LZ_REQUIRE(fabs(t - w[c].t) < 1e-14 && face == w[c].face,
		      "box of 12 with walls, cells of 3, %s: r = (%g, %g, %g), v = (%g, %g, %g); "
		      "expected face %d at t = %g, got face %d at t = %.15g", w[c].what, w[c].r[0],
		      w[c].r[1], w[c].r[2], w[c].v[0], w[c].v[1], w[c].v[2], w[c].face, w[c].t, face, t);
	}
	free(e);
	/* walls on x only: y and z stay periodic, their edge faces are plain faces */
	lz_edmd *f = hand_box(3, 12, 4, 1, 0);
	double r[3] = {4, 1, 4}, v[3] = {0, -1, 0};
	double t = lz_edmd_cell_time(f, r, v, hand_cell(f, (int[3]){1, 0, 1}), &face);
	LZ_REQUIRE(fabs(t - 1) < 1e-15 && face == 2, "walls on x only, y = 1 moving down in the first "
	      "y cell: y is periodic, the face is y = 0 at t = 1 (not a contact at 1/2); got face %d "
	      "at t = %g", face, t);
	free(f);
}
END_TEST

LZ_TEST(cell_time_under_gravity_follows_the_parabola)
{
	/* gravity g along -x: x(t) = x + v t - g t²/2. The time is the first root of
	 * reaching the top of the cell (if the particle gets that high) or else its
	 * bottom, found here with GSL's quadratic solver. Random cells, heights,
	 * velocities; with walls on x, the bottom of the first cell is the contact 1/2 */
	gsl_rng *r = lz_test_rng(517);
	for (int trial = 0; trial < 100000; trial++) {
		double g = exp(gsl_ran_flat(r, log(0.01), log(100)));
		lz_edmd *e = hand_box(3, 15, 5, 1, g);  /* cells of 3 */
		int cc[3] = {(int)gsl_rng_uniform_int(r, 5), 2, 2};
		double lo, hi;
		span_of(e, 0, cc[0], &lo, &hi);
		double x[3] = {lo + (hi - lo) * gsl_rng_uniform(r), 7.5, 7.5};
		double v[3] = {gsl_ran_gaussian(r, 2.0), 0, 0};
		if (trial % 3 == 0) { /* moving sideways too: the side faces may come first */
			v[1] = gsl_ran_gaussian(r, 1.0);
			v[2] = gsl_ran_gaussian(r, 1.0);
		}
		int face = -1;
		double t = lz_edmd_cell_time(e, x, v, hand_cell(e, cc), &face);
		/* the reference: roots of -g/2 t² + v t + (x - level) = 0 */
		double t_up = INFINITY, t_down, r1, r2;
		if (gsl_poly_solve_quadratic(-0.5 * g, v[0], x[0] - hi, &r1, &r2) == 2)
			t_up = fmin(r1, r2) >= 0 ? fmin(r1, r2) : INFINITY;
		int nd = gsl_poly_solve_quadratic(-0.5 * g, v[0], x[0] - lo, &r1, &r2);
		t_down = nd == 2 ? fmax(r1, r2) : nd == 1 ? r1 : 0;
		double want = fmin(t_up, t_down);
		int want_face = t_up <= t_down ? 1 : 0;
		for (int a = 1; a < 3; a++)
			if (v[a] != 0) {
				double l2, h2;
				span_of(e, a, cc[a], &l2, &h2);
				double ta = v[a] > 0 ? (h2 - x[a]) / v[a] : (l2 - x[a]) / v[a];
				if (ta < want) {
					want = ta;
					want_face = 2 * a + (v[a] > 0);
				}
			}
		LZ_REQUIRE(fabs(t - want) <= 1e-9 * (1 + want) && face == want_face,
		      "gravity g = %.4g along -x, cell x in [%.4g, %.4g], x = %.10g, v = (%.6g, %.6g, "
		      "%.6g): the parabola %s first at t = %.12g (face %d); lz_edmd_cell_time gave face "
		      "%d at t = %.12g%s", g, lo, hi, x[0], v[0], v[1], v[2],
		      want_face == 1 ? "reaches the top" : want_face == 0 ? "falls to the bottom"
		                                                          : "leaves sideways",
		      want, want_face, face, t,
		      fabs(t - (v[0] > 0 ? (hi - x[0]) / v[0] : (lo - x[0]) / v[0])) < 1e-12
		          ? " — that is the straight-line time: gravity bends the path (lz_edmd_fall_time)"
		          : "");
		free(e);
	}
	gsl_rng_free(r);
}
END_TEST

/* ---- systems for the runs ---- */

static double particle_volume(int dim) { return dim == 3 ? M_PI / 6 : M_PI / 4; }

/* A system of n particles in a box of side L (the packing that gives it). */
static lz_edmd *box_of_side(int dim, size_t n, double L, int walls, double g, double er)
{
	lz_edmd_params p = {dim, n, n * particle_volume(dim) / pow(L, dim), er, g, walls, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	LZ_REQUIRE(e != NULL, "lz_edmd_alloc(dim %d, n %zu, L %g): %s", dim, n, L,
	              lz_error_message());
	return e;
}

/* Set the hand-placed state (positions and velocities, 3 per particle). */
static void place(lz_edmd *e, const double *r, const double *v)
{
	int st = lz_edmd_set(e, r, v);
	LZ_REQUIRE(st == LZ_OK, "lz_edmd_set refused the test's state: %s", lz_error_message());
}

/* n particles at packing eta on a lattice (lz_edmd_place_lattice), kT = 1. */
static lz_edmd *lattice_system(int dim, size_t n, double eta, double er, int walls, double g,
                               unsigned long seed)
{
	lz_edmd_params p = {dim, n, eta, er, g, walls, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	LZ_REQUIRE(e != NULL, "lz_edmd_alloc(dim %d, n %zu, packing %g): %s", dim, n, eta,
	              lz_error_message());
	lz_rng *rng = lz_rng_alloc(NULL, seed);
	LZ_REQUIRE(rng, "lz_rng_alloc(seed %lu): %s", seed, lz_error_message());
	int st = lz_edmd_place_lattice(e, rng);
	lz_rng_free(rng);
	LZ_REQUIRE(st == LZ_OK, "lz_edmd_place_lattice(dim %d, n %zu, packing %g): %s", dim, n,
	              eta, lz_error_message());
	return e;
}

/* A dilute gas at random positions (no two closer than 1) and Maxwell velocities of
 * zero total momentum, kT = 1. */
static lz_edmd *random_gas(int dim, size_t n, double eta, unsigned long seed)
{
	lz_edmd_params p = {dim, n, eta, 1.0, 0, LZ_EDMD_WALLS_NONE, 0, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	LZ_REQUIRE(e != NULL, "lz_edmd_alloc(dim %d, n %zu, packing %g): %s", dim, n, eta,
	              lz_error_message());
	gsl_rng *r = lz_test_rng(seed);
	double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v), P[3] = {0, 0, 0};
	LZ_REQUIRE(x && v, "out of memory for %zu particles", n);
	for (size_t i = 0; i < n; i++) {
		int ok;
		do {
			for (int a = 0; a < dim; a++)
				x[3 * i + a] = e->L * gsl_rng_uniform(r);
			ok = 1;
			for (size_t j = 0; j < i && ok; j++) {
				double d2 = 0;
				for (int a = 0; a < dim; a++) {
					double d = x[3 * i + a] - x[3 * j + a];
					d -= e->L * rint(d / e->L);
					d2 += d * d;
				}
				ok = d2 > 1.0001;
			}
		} while (!ok);
		for (int a = 0; a < dim; a++) {
			v[3 * i + a] = gsl_ran_gaussian(r, 1.0);
			P[a] += v[3 * i + a];
		}
	}
	double ke = 0;
	for (size_t i = 0; i < n; i++)
		for (int a = 0; a < dim; a++) {
			v[3 * i + a] -= P[a] / n;
			ke += 0.5 * v[3 * i + a] * v[3 * i + a];
		}
	double s = sqrt(0.5 * dim * n / ke);
	for (size_t i = 0; i < 3 * n; i++)
		v[i] *= s;
	place(e, x, v);
	free(x);
	free(v);
	gsl_rng_free(r);
	return e;
}

/* Position of particle i now. */
static void where(const lz_edmd *e, uint32_t i, double r[3], double v[3])
{
	lz_edmd_state(e, &e->p[i], e->now, r, v);
}

/* The nearest-image distance of i and j now. */
static double distance(const lz_edmd *e, uint32_t i, uint32_t j)
{
	double ri[3], rj[3], v[3], d2 = 0;
	where(e, i, ri, v);
	where(e, j, rj, v);
	for (int a = 0; a < e->dim; a++) {
		double d = rj[a] - ri[a];
		if (!e->wall[a])
			d -= e->L * rint(d / e->L);
		d2 += d * d;
	}
	return sqrt(d2);
}

/* ---- the contract of one event (lz/edmd.h, lz_edmd_step) ---- */

/* The heap's top as the loop is about to carry it out, and the counters then. */
typedef struct {
	uint32_t i, ci, cj;  /* the particle, its count and its partner's */
	double t, vi[3];     /* the event's time, i's velocity then */
	lz_edmd_event ev;
	int stale;           /* a collision whose partner has collided since */
	uint64_t events, collisions, stale_n, faces;
	unsigned rebases;
} next_event;

static next_event peek(const lz_edmd *e)
{
	next_event x;
	memset(&x, 0, sizeof x);
	x.i = lz_heap_top(e->heap);
	x.t = lz_heap_top_t(e->heap);
	x.ev = e->ev[x.i];
	x.ci = e->p[x.i].count;
	if (x.ev.partner >= 0) {
		x.cj = e->p[x.ev.partner].count;
		x.stale = x.cj != x.ev.pcount;
	}
	if (isfinite(x.t)) {
		double r[3];
		lz_edmd_state(e, &e->p[x.i], x.t, r, x.vi);
	}
	x.events = e->events;
	x.collisions = e->collisions;
	x.stale_n = e->stale;
	x.faces = e->crossings + e->bounces;
	x.rebases = e->rebases;
	return x;
}

/* Particle k was just predicted: its event is not in the past, and one with a partner
 * stores the partner's count as it is now. */
static void check_fresh(const lz_edmd *e, uint32_t k, const char *what)
{
	double t = e->heap->node[e->heap->pos[k]].t;
	LZ_REQUIRE(t >= e->now, "%s: particle %u was just predicted an event at %.17g, before now = %.17g",
	      what, k, t, e->now);
	int32_t j = e->ev[k].partner;
	LZ_REQUIRE(j < 0 || e->ev[k].pcount == e->p[j].count, "%s: particle %u was just predicted a "
	      "collision with %d and stored the count %u, but %d's count is %u: the event must "
	      "store the PARTNER's count, the one the stale check compares", what, k, j,
	      e->ev[k].pcount, j, e->p[j].count);
}

/* Particle k's position now lies in the span of its cell (to 1e-9), which on an axis
 * with walls ends at the contacts 1/2 and L - 1/2. */
static void check_in_cell(const lz_edmd *e, uint32_t k, const char *what)
{
	double r[3], v[3];
	where(e, k, r, v);
	uint32_t c = e->p[k].cell, m0 = (uint32_t)e->m[0], m1 = (uint32_t)e->m[1];
	uint32_t cc[3] = {c % m0, c / m0 % m1, c / (m0 * m1)};
	for (int a = 0; a < e->dim; a++) {
		double lo = cc[a] * e->w[a], hi = (cc[a] + 1) * e->w[a];
		if (e->wall[a]) {
			lo = fmax(lo, 0.5);
			hi = fmin(hi, e->L - 0.5);
		}
		LZ_REQUIRE(r[a] >= lo - 1e-9 && r[a] <= hi + 1e-9, "%s: after its face event particle %u is "
		      "at %c = %.12g, outside the span [%.12g, %.12g] of its cell %u — a crossing moves "
		      "it to the cell across (wrapping r on a periodic axis), a wall reverses v", what,
		      k, "xyz"[a], r[a], lo, hi, c);
	}
}

/* What the event x, just carried out, must have done (lz_edmd_step): set the clock
 * to its time; if stale, count it and change nothing else; if a collision, bounce
 * the pair at contact and add 1 to both counts; if a face, count a crossing or a
 * bounce and leave the particle in the span of its cell; and predict again. */
static void check_event(const lz_edmd *e, const next_event *x, const char *what)
{
	uint32_t i = x->i;
	int32_t j = x->ev.partner;
	LZ_REQUIRE(e->events == x->events + 1, "%s: one step counted %llu events", what,
	      (unsigned long long)(e->events - x->events));
	if (e->rebases == x->rebases)
		LZ_REQUIRE(e->now == x->t, "%s: the event of particle %u was at t = %.17g, but after it "
		      "now = %.17g: step sets the clock to the event's time", what, i, x->t, e->now);
	if (j >= 0 && x->stale) {
		double r[3], v[3];
		where(e, i, r, v);
		double dv = fabs(v[0] - x->vi[0]) + fabs(v[1] - x->vi[1]) + fabs(v[2] - x->vi[2]);
		LZ_REQUIRE(e->stale == x->stale_n + 1 && e->collisions == x->collisions &&
		              e->p[i].count == x->ci && e->p[j].count == x->cj &&
		              dv <= 1e-12 * (1 + fabs(x->vi[0]) + fabs(x->vi[1]) + fabs(x->vi[2])),
		      "%s: particle %u's event with %d was stale (%d's count is %u, the event stored "
		      "%u), so step must only count it stale and predict %u again; stale %llu -> %llu, "
		      "collisions %llu -> %llu, v_x %.6g -> %.6g", what, i, j, j, x->cj, x->ev.pcount, i,
		      (unsigned long long)x->stale_n, (unsigned long long)e->stale,
		      (unsigned long long)x->collisions, (unsigned long long)e->collisions, x->vi[0],
		      v[0]);
	} else if (j >= 0) {
		double d = distance(e, i, (uint32_t)j);
		LZ_REQUIRE(e->collisions == x->collisions + 1 && e->stale == x->stale_n &&
		              e->p[i].count == x->ci + 1 && e->p[j].count == x->cj + 1,
		      "%s: the collision of %u and %d must count one collision and add 1 to BOTH "
		      "counts (so that the events others predicted with either become stale): "
		      "collisions +%llu, counts %u -> %u and %u -> %u", what, i, j,
		      (unsigned long long)(e->collisions - x->collisions), x->ci, e->p[i].count, x->cj,
		      e->p[j].count);
		LZ_REQUIRE(fabs(d - 1) < 1e-9, "%s: particles %u and %d collided with their centres %.12g "
		      "apart: hard spheres collide at contact, 1 — a stale event carried out, or a "
		      "partner not brought to the collision time?", what, i, j, d);
		check_fresh(e, (uint32_t)j, what);
	} else {
		LZ_REQUIRE(e->crossings + e->bounces == x->faces + 1 && e->collisions == x->collisions &&
		              e->stale == x->stale_n,
		      "%s: particle %u's face event must count one crossing or one wall bounce and "
		      "nothing else", what, i);
		check_in_cell(e, i, what);
	}
	check_fresh(e, i, what);
}

/* lz_edmd_run, one event at a time (the same trajectory: the run re-bases and
 * guards at the top of its loop), each event checked against the contract above;
 * until `events` have run or the clock reaches t_stop. lz_edmd_run's status. */
static int run_checked(lz_edmd *e, uint64_t events, double t_stop, const char *what)
{
	for (uint64_t k = 0; k < events; k++) {
		next_event x = peek(e);
		int st = lz_edmd_run(e, 1, t_stop);
		if (st != LZ_OK || e->events == x.events)  /* an error, or t_stop reached */
			return st;
		check_event(e, &x, what);
	}
	return LZ_OK;
}

/* What every run must leave behind, whatever else a test measures: a clock that
 * moved, the invariants of the event loop (lz_edmd_audit: the heap and its index,
 * every particle in its cell, clocks in order — without them the cell-based overlap
 * search below is blind), no overlap, the energy of an elastic system and the momentum
 * of a periodic one without gravity, and a positive virial once there were
 * collisions. Round-off moves the energy and the momentum by a few ulp per event, so
 * over the 10^6 events of the longest run they drift by about 1e-13: 1e-10 (relative
 * energy) and 1e-9 (absolute momentum of up to 4096 unit velocities) leave room. */
typedef struct {
	double t, E, P[3];
} before_t;

static before_t before(const lz_edmd *e)
{
	before_t b = {lz_edmd_time(e), lz_edmd_energy(e), {0, 0, 0}};
	lz_edmd_momentum(e, b.P);
	return b;
}

static void healthy(const lz_edmd *e, const before_t *b, const char *what)
{
	LZ_REQUIRE(lz_edmd_time(e) > b->t, "%s: after %llu events the clock still reads %.17g — events "
	      "at one instant for ever: is a face time 0 every time (the faces swapped?), or the "
	      "clock not advanced in step?", what, (unsigned long long)e->events, lz_edmd_time(e));
	LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%s, after %llu events (%llu collisions, %llu crossings): "
	      "%s", what, (unsigned long long)e->events, (unsigned long long)e->collisions,
	      (unsigned long long)e->crossings, lz_error_message());
	uint32_t i = 0, j = 0;
	double over = lz_edmd_max_overlap(e, &i, &j);
	LZ_REQUIRE(over < 1e-10, "%s: particles %u and %u overlap by %.3g after %llu events — a "
	      "collision was missed or carried out at the wrong place", what, i, j, over,
	      (unsigned long long)e->events);
	double E = lz_edmd_energy(e);
	if (e->restitution == 1)
		LZ_REQUIRE(fabs(E / b->E - 1) < 1e-10, "%s, elastic: the energy went from %.15g to %.15g "
		      "(relative %.2g) — elastic bounces and free flight keep it to round-off", what,
		      b->E, E, E / b->E - 1);
	if (!e->wall[0] && !e->wall[1] && !e->wall[2] && e->g == 0) {
		double P[3];
		lz_edmd_momentum(e, P);
		for (int a = 0; a < 3; a++)
			LZ_REQUIRE(fabs(P[a] - b->P[a]) < 1e-9, "%s, periodic box: the momentum %c went from "
			      "%.3g to %.3g — the impulses on the two partners must be equal and "
			      "opposite", what, "xyz"[a], b->P[a], P[a]);
	}
	LZ_REQUIRE(e->virial >= 0 && (e->collisions == 0 || e->virial > 0), "%s: the virial sum is "
	      "%.6g after %llu collisions; each collision adds r_ab·Δp_a = |dr|·|Δp| > 0 (is "
	      "the bounce returning a signed impulse?)", what, e->virial,
	      (unsigned long long)e->collisions);
}

/* `events` events, every one checked (run_checked), which must succeed, keep the
 * clock moving to the end (not all of the second half at one instant) and leave a
 * healthy system. */
static void run(lz_edmd *e, uint64_t events, const char *what)
{
	before_t b = before(e);
	int st = run_checked(e, events / 2, INFINITY, what);
	double t_mid = lz_edmd_time(e);
	if (st == LZ_OK)
		st = run_checked(e, events - events / 2, INFINITY, what);
	LZ_REQUIRE(st == LZ_OK, "%s: lz_edmd_run stopped after %llu events at t = %g: %s", what,
	      (unsigned long long)e->events, lz_edmd_time(e), lz_error_message());
	LZ_REQUIRE(lz_edmd_time(e) > t_mid, "%s: the last %llu events all happened at one instant, t = "
	      "%.17g — the same event again and again (a stale event not predicted again? a "
	      "valid collision taken for stale?)", what, (unsigned long long)(events - events / 2),
	      t_mid);
	healthy(e, &b, what);
}

/* Step until the collision counter reaches `want` (at most `most` events), checking
 * each event and auditing the loop after it; the time of that event. */
static double step_to_collision(lz_edmd *e, uint64_t want, int most, const char *what)
{
	for (int k = 0; k < most && e->collisions < want; k++) {
		next_event x = peek(e);
		LZ_REQUIRE(lz_edmd_step(e) == 0, "%s: lz_edmd_step says nothing will ever happen (after %d "
		      "events, %llu collisions), but collision %llu is still to come", what, k,
		      (unsigned long long)e->collisions, (unsigned long long)want);
		check_event(e, &x, what);
		/* a few particles: the invariants are cheap to check after every event */
		LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%s, after event %d (now = %.12g): %s", what, k + 1,
		      e->now, lz_error_message());
	}
	LZ_REQUIRE(e->collisions == want, "%s: no collision number %llu within %d events (%llu "
	      "collisions, %llu crossings, now = %g)", what, (unsigned long long)want, most,
	      (unsigned long long)e->collisions, (unsigned long long)e->crossings, e->now);
	return e->now;
}

/* ---- two and three particles by hand ---- */

LZ_TEST(two_particles_meet_on_time_and_again_across_the_boundary)
{
	/* 3D box of side 10: a at x = 0.7 moving +0.7, b at x = 4.7 moving -0.3. The gap
	 * 3 closes at 1 per unit time: contact at t = 3 (a at 2.8, b at 3.8), velocities
	 * exchanged. Then they separate at 1, and the gap L - 2 = 8 through the periodic
	 * boundary closes at t = 11 with a at 0.4 and b at 9.4: they touch across the
	 * boundary, each on its own side of it. Both drift along z at 0.25, which changes
	 * nothing (Galilean invariance) but makes two axes compete for the next face.
	 * Each collision reverses a closing speed of 1: |Δp| = 1, the virial adds 1. */
	lz_edmd *e = box_of_side(3, 2, 10, LZ_EDMD_WALLS_NONE, 0, 1);
	double L = e->L, w = 0.25;
	double r[6] = {0.7, 5, 5, 4.7, 5, 5}, v[6] = {0.7, 0, w, -0.3, 0, w};
	place(e, r, v);
	before_t b0 = before(e);
	double t1 = step_to_collision(e, 1, 1000, "two particles head on");
	LZ_REQUIRE(fabs(t1 - 3) < 1e-12, "a at x = 0.7 (v = +0.7), b at x = 4.7 (v = -0.3): the gap of "
	      "3 closes at relative speed 1, the collision is at t = 3; it happened at t = %.15g", t1);
	LZ_REQUIRE(fabs(distance(e, 0, 1) - 1) < 1e-12, "at the collision the centres are %.15g apart, "
	      "expected 1 (touching)", distance(e, 0, 1));
	double ra[3], va[3], rb[3], vb[3];
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	LZ_REQUIRE(fabs(va[0] + 0.3) < 1e-14 && fabs(vb[0] - 0.7) < 1e-14,
	      "after the head-on collision the velocities must be exchanged: v_a = %g (want -0.3), "
	      "v_b = %g (want 0.7)", va[0], vb[0]);
	double t2 = step_to_collision(e, 2, 1000, "two particles, second collision");
	double want2 = 3 + (L - 2);
	LZ_REQUIRE(fabs(t2 - want2) < 1e-11, "after the first collision the two separate at relative "
	      "speed 1; through the periodic boundary the gap L - 2 = %.10g closes at t = %.12g "
	      "(a at x = 0.4, b at x = L - 0.6). The second collision happened at t = %.12g%s",
	      L - 2, want2, t2,
	      t2 > want2 + 1e-6 ? " — late: is the periodic image (shift) used in predict?" : "");
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	LZ_REQUIRE(fabs(ra[0] - 0.4) < 1e-11 && fabs(rb[0] - (L - 0.6)) < 1e-11, "at the collision "
	      "across the boundary a should be at x = 0.4 and b at x = L - 0.6 = %.12g; they are at "
	      "%.12g and %.12g", L - 0.6, ra[0], rb[0]);
	LZ_REQUIRE(fabs(va[0] - 0.7) < 1e-14 && fabs(vb[0] + 0.3) < 1e-14 && va[2] == w && vb[2] == w,
	      "after the collision across the boundary the velocities must be exchanged back: v_a = "
	      "(%g, %g, %g) (want (0.7, 0, %g)), v_b = (%g, %g, %g) (want (-0.3, 0, %g))", va[0],
	      va[1], va[2], w, vb[0], vb[1], vb[2], w);
	LZ_REQUIRE(fabs(e->virial - 2) < 1e-12, "two head-on collisions at closing speed 1: each "
	      "changes a momentum by |Δp| = 1 at |dr| = 1, so the virial sum is 2; it is %.15g",
	      e->virial);
	healthy(e, &b0, "two particles after two collisions");
	LZ_REQUIRE(e->p[0].count == 2 && e->p[1].count == 2, "after two collisions each particle's count "
	      "must be 2, got %u and %u", e->p[0].count, e->p[1].count);
	lz_edmd_free(e);

	/* 2D, oblique: a at (3, 3) moving +x, b at (6, 3.6) moving -x, impact parameter
	 * 0.6: contact when dx = 0.8, at t = 1.1, normal k = (0.8, 0.6); the normal
	 * relative velocity -1.6 is reversed: v_a = (-0.28, -0.96), v_b = (0.28, 0.96).
	 * They start in neighbouring cells. The virial is |Δp| = 1.6. */
	e = box_of_side(2, 2, 10, LZ_EDMD_WALLS_NONE, 0, 1);
	double r2[6] = {3, 3, 0, 6, 3.6, 0}, v2[6] = {1, 0, 0, -1, 0, 0};
	place(e, r2, v2);
	b0 = before(e);
	LZ_REQUIRE(e->p[0].cell != e->p[1].cell, "the test meant a and b to start in different cells");
	double t = step_to_collision(e, 1, 1000, "2D oblique pair");
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	LZ_REQUIRE(fabs(t - 1.1) < 1e-12 && fabs(va[0] + 0.28) < 1e-12 && fabs(va[1] + 0.96) < 1e-12 &&
	              fabs(vb[0] - 0.28) < 1e-12 && fabs(vb[1] - 0.96) < 1e-12 && va[2] == 0,
	      "2D oblique: a at (3, 3) v = (1, 0), b at (6, 3.6) v = (-1, 0) touch at t = 1.1 with "
	      "normal (0.8, 0.6) and leave with v_a = (-0.28, -0.96), v_b = (0.28, 0.96); got t = "
	      "%.15g, v_a = (%.12g, %.12g, %g), v_b = (%.12g, %.12g)", t, va[0], va[1], va[2], vb[0],
	      vb[1]);
	LZ_REQUIRE(fabs(e->virial - 1.6) < 1e-12, "2D oblique: the normal closing speed 1.6 is reversed, "
	      "|Δp| = 1.6 at |dr| = 1: the virial is 1.6, it is %.15g", e->virial);
	healthy(e, &b0, "2D oblique pair after the collision");
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(two_particles_first_meet_through_the_wrap)
{
	/* a at (0.8, 5) moving -x, b at (L - 0.8, 5.6) moving +x: 1.6 apart on x through
	 * the periodic boundary (L - 1.6 inside the box), 0.6 on y. They touch when dx =
	 * 0.8, at t = 0.8, with a at x = 0.4 and b at L - 0.4, the normal k = (-0.8, 0.6)
	 * from a to b through the boundary. The normal relative velocity -0.8 is
	 * reversed: v_a = (0.14, -0.48), v_b = (-0.14, 0.48). */
	lz_edmd *e = box_of_side(3, 2, 10, LZ_EDMD_WALLS_NONE, 0, 1);
	double L = e->L;
	double r[6] = {0.8, 5, 5, L - 0.8, 5.6, 5}, v[6] = {-0.5, 0, 0, 0.5, 0, 0};
	place(e, r, v);
	before_t b0 = before(e);
	double t = step_to_collision(e, 1, 1000, "a pair through the wrap");
	LZ_REQUIRE(fabs(t - 0.8) < 1e-12, "a at (0.8, 5) moving -0.5, b at (L - 0.8, 5.6) moving +0.5 are "
	      "(1.6, 0.6) apart through the periodic boundary: contact at t = 0.8; it happened at t = "
	      "%.15g%s", t, t > 1 ? " — is the periodic image (the block's shift) used in predict?" : "");
	double ra[3], va[3], rb[3], vb[3];
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	LZ_REQUIRE(fabs(va[0] - 0.14) < 1e-12 && fabs(va[1] + 0.48) < 1e-12 && fabs(vb[0] + 0.14) < 1e-12 &&
	              fabs(vb[1] - 0.48) < 1e-12,
	      "after the collision through the wrap (normal (-0.8, 0.6) from a to b): expected v_a = "
	      "(0.14, -0.48), v_b = (-0.14, 0.48); got v_a = (%.12g, %.12g), v_b = (%.12g, %.12g) — "
	      "the separation given to the bounce must be the nearest image", va[0], va[1], vb[0],
	      vb[1]);
	LZ_REQUIRE(fabs(e->virial - 0.8) < 1e-12, "through the wrap the normal closing speed 0.8 is "
	      "reversed: |Δp| = 0.8 at |dr| = 1, the virial is 0.8; it is %.15g", e->virial);
	healthy(e, &b0, "a pair after its collision through the wrap");
	lz_edmd_free(e);
	/* through a corner: 0.8 apart on x and on y through both boundaries, closing
	 * along the diagonal at relative speed √2: contact when 0.8√2 - √2 t = 1 */
	e = box_of_side(3, 2, 10, LZ_EDMD_WALLS_NONE, 0, 1);
	L = e->L;
	double rc[6] = {0.5, 0.5, 5, L - 0.3, L - 0.3, 5}, vc[6] = {-0.5, -0.5, 0, 0.5, 0.5, 0};
	place(e, rc, vc);
	b0 = before(e);
	t = step_to_collision(e, 1, 1000, "a pair through the corner");
	double want = 0.8 - 1 / sqrt(2.0);
	LZ_REQUIRE(fabs(t - want) < 1e-12, "a at (0.5, 0.5), b at (L - 0.3, L - 0.3), closing along the "
	      "diagonal: they touch through the corner of the box at t = %.15g; it happened at %.15g",
	      want, t);
	where(e, 0, ra, va);
	LZ_REQUIRE(fabs(va[0] - 0.5) < 1e-12 && fabs(va[1] - 0.5) < 1e-12, "after the collision through "
	      "the corner, v_a = (%g, %g), expected (0.5, 0.5)", va[0], va[1]);
	LZ_REQUIRE(fabs(e->virial - sqrt(2.0)) < 1e-12, "through the corner the closing speed √2 is "
	      "reversed: |Δp| = √2, the virial is %.15g, expected √2", e->virial);
	healthy(e, &b0, "a pair after its collision through the corner");
	lz_edmd_free(e);
}
END_TEST

/* Two particles in a periodic 3D box of side L with m cells per side (faces at
 * multiples of L/m). */
static lz_edmd *box_with_cells(size_t n, double L, int m)
{
	lz_edmd_params p = {3, n, n * particle_volume(3) / (L * L * L), 1, 0, LZ_EDMD_WALLS_NONE, m, LZ_EDMD_CELLS, 0, 0};
	lz_edmd *e = lz_edmd_alloc(&p);
	LZ_REQUIRE(e != NULL, "lz_edmd_alloc(n %zu, L %g, %d cells per side): %s", n, L, m,
	      lz_error_message());
	return e;
}

LZ_TEST(two_particles_collide_exactly_on_a_cell_face)
{
	/* Box of 12, cells of 4: a at x = 2 moving +1, b at x = 7 moving -1 touch at t =
	 * 2 with a at x = 4, exactly on the face between its cell and the next: its
	 * crossing and its collision fall on the same instant. Whichever the loop takes
	 * first, there is ONE collision at t = 2, the velocities are exchanged, and the
	 * pair next meets through the periodic boundary when the gap L - 2 has closed at
	 * relative speed 2, at t = 2 + (L - 2)/2 = 7, with a at x = -1 + L and b at 10.
	 * A common drift along z changes nothing but gives each particle two axes to
	 * leave its cell by. */
	lz_edmd *e = box_with_cells(2, 12, 3);
	double L = e->L, w = 0.2;
	LZ_REQUIRE(fabs(e->w[0] - 4) < 1e-12, "the test wants cells of 4, the box has %.15g", e->w[0]);
	double r[6] = {2, 6, 6, 7, 6, 6}, v[6] = {1, 0, w, -1, 0, w};
	place(e, r, v);
	before_t b0 = before(e);
	double t1 = step_to_collision(e, 1, 100, "a collision on a cell face");
	double ra[3], va[3], rb[3], vb[3];
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	LZ_REQUIRE(fabs(t1 - 2) < 1e-12 && fabs(ra[0] - 4) < 1e-12 && va[0] == -1 && vb[0] == 1,
	      "a (x = 2, v = +1) and b (x = 7, v = -1) touch at t = 2 with a on the cell face x = 4: "
	      "expected the collision then, v_a = -1, v_b = +1; got t = %.15g, x_a = %.15g, v_a = %g, "
	      "v_b = %g", t1, ra[0], va[0], vb[0]);
	double t2 = step_to_collision(e, 2, 100, "after a collision on a cell face");
	double want = 2 + (L - 2) / 2;
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	LZ_REQUIRE(fabs(t2 - want) < 1e-11 && fabs(ra[0] - (L - 1)) < 1e-11 && fabs(rb[0] - 10) < 1e-11,
	      "after the collision on the face the pair recedes at 2 and meets again through the "
	      "periodic boundary at t = %.12g, a at x = %.12g and b at 10; the second collision was "
	      "at t = %.12g with a at %.12g and b at %.12g%s", want, L - 1, t2, ra[0], rb[0],
	      t2 < 2 + 1e-9 ? " — a second collision at the face: was the pair bounced twice?" : "");
	healthy(e, &b0, "two collisions, the first on a cell face");
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(two_particles_touching_at_the_start)
{
	/* Centres exactly 1 apart at t = 0, along x, in a box of side L ≈ 10, both
	 * drifting along z at w (which changes nothing but the faces they cross): */
	static const struct {
		double va, vb, vy;
		const char *what;
	} c[3] = {{-0.5, 0.5, 0, "moving apart"}, {0.5, -0.5, 0, "approaching"},
	          {0, 0, 0.8, "sliding past (relative velocity along y, across the contact)"}};
	for (int k = 0; k < 3; k++) {
		lz_edmd *e = box_of_side(3, 2, 10, LZ_EDMD_WALLS_NONE, 0, 1);
		double L = e->L;
		const double w = 0.1;
		double r[6] = {3, 5, 5, 4, 5, 5}, v[6] = {c[k].va, 0, w, c[k].vb, c[k].vy, w};
		place(e, r, v);
		before_t b0 = before(e);
		double ra[3], va[3], rb[3], vb[3];
		if (k == 2) {
			/* b slides off a sideways: they never touch again within the 5 time units
			 * the run lasts (b needs 12.5 to come back through the wrap in y) */
			int st = run_checked(e, 10000, 5, "touching, sliding past");
			where(e, 1, rb, vb);
			LZ_REQUIRE(st == LZ_OK && e->collisions == 0 && vb[1] == 0.8 && fabs(rb[1] - 9) < 1e-12,
			      "touching, %s: no collision (dr·dv = 0 is no approach), b flies on to y = "
			      "9 by t = 5; got %llu collisions, v_b = (%g, %g, %g), y_b = %.15g (%s)",
			      c[k].what, (unsigned long long)e->collisions, vb[0], vb[1], vb[2], rb[1],
			      st == LZ_OK ? "ok" : lz_error_message());
			healthy(e, &b0, "touching, sliding past");
			lz_edmd_free(e);
			continue;
		}
		/* moving apart: no collision now, the first one when the gap L - 2 through the
		 * boundary has closed at relative speed 1. Approaching: the collision at t = 0,
		 * then the same. */
		double t1 = step_to_collision(e, 1, 1000, c[k].what);
		where(e, 0, ra, va);
		double want1 = k == 0 ? L - 2 : 0;
		LZ_REQUIRE(fabs(t1 - want1) < 1e-11 && va[0] == (k == 0 ? 0.5 : -0.5),
		      "touching at t = 0 and %s (v_a = %g, v_b = %g): the first collision is at t = "
		      "%.12g%s; it happened at t = %.12g with v_a = %g after it", c[k].what, c[k].va,
		      c[k].vb, want1, k == 0 ? " through the periodic boundary, not at the contact "
		      "they are leaving" : ", at once", t1, va[0]);
		if (k == 1) {
			double t2 = step_to_collision(e, 2, 1000, "touching and approaching, then");
			LZ_REQUIRE(fabs(t2 - (L - 2)) < 1e-11, "touching and approaching: after the collision "
			      "at t = 0 the pair recedes at 1 and meets again through the boundary at t = "
			      "%.12g; it did at %.12g", L - 2, t2);
		}
		healthy(e, &b0, c[k].what);
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(stale_partner_event_is_skipped)
{
	/* a at (3.5, 4.8) moving +x would hit b, at rest at (5, 5), at t = 1.5 - √0.96.
	 * But c at (5, 6.5) comes down at 4 and hits b first, at t = 0.125: b takes c's
	 * velocity and leaves downwards, c stops. a's event with b is now stale (b's
	 * count changed): at its time the loop must count it stale and predict a again,
	 * and a flies on untouched. All three drift along z at w, which changes nothing
	 * (Galilean invariance) but gives every particle two axes to leave its cell by. */
	lz_edmd *e = box_of_side(3, 3, 10, LZ_EDMD_WALLS_NONE, 0, 1);
	const double w = 0.3;
	double r[9] = {3.5, 4.8, 5, 5, 5, 5, 5, 6.5, 5}, v[9] = {1, 0, w, 0, 0, w, 0, -4, w};
	place(e, r, v);
	before_t b0 = before(e);
	double t_ab = 1.5 - sqrt(0.96);
	LZ_REQUIRE(e->ev[0].partner == 1 && e->ev[0].pcount == 0 &&
	              fabs(e->heap->node[e->heap->pos[0]].t - t_ab) < 1e-12,
	      "after the start, particle a (0) should have predicted its collision with b (1) at t "
	      "= %.12g with b's count 0; its event is partner %d, pcount %u, at t = %.12g", t_ab,
	      e->ev[0].partner, e->ev[0].pcount, e->heap->node[e->heap->pos[0]].t);
	LZ_REQUIRE(e->ev[2].partner == 1 && fabs(e->heap->node[e->heap->pos[2]].t - 0.125) < 1e-12,
	      "after the start, particle c (2) should have predicted its collision with b (1) at t "
	      "= 0.125; its event is partner %d at t = %.12g", e->ev[2].partner,
	      e->heap->node[e->heap->pos[2]].t);
	int st = run_checked(e, 10000, 0.7, "three particles and a stale event");
	LZ_REQUIRE(st == LZ_OK, "lz_edmd_run to t = 0.7: %s", lz_error_message());
	/* by t = 0.7: the collision of b and c, a's stale event, b's crossing of a face or
	 * two on its way down (cells of 10/3) — a handful of events, not thousands */
	LZ_REQUIRE(fabs(lz_edmd_time(e) - 0.7) < 1e-12 && e->events < 20,
	      "the run to t = 0.7 stopped at t = %.15g after %llu events: a handful of events "
	      "happen by then. If the same stale event comes up again and again, the particle "
	      "was not predicted again after it", lz_edmd_time(e), (unsigned long long)e->events);
	LZ_REQUIRE(e->collisions == 1, "by t = 0.7 exactly one collision happens (b with c at t = "
	      "0.125); the loop counted %llu — a's event with b (t = %.6f) was predicted before b "
	      "collided with c and must be found stale (b's count != the stored pcount)",
	      (unsigned long long)e->collisions, t_ab);
	LZ_REQUIRE(e->stale >= 1, "a's event with b must be counted stale when it comes up; stale = %llu",
	      (unsigned long long)e->stale);
	double ra[3], va[3], rb[3], vb[3], rc[3], vc[3];
	where(e, 0, ra, va);
	where(e, 1, rb, vb);
	where(e, 2, rc, vc);
	LZ_REQUIRE(va[0] == 1 && va[1] == 0 && va[2] == w, "a must fly on untouched, v_a = (%g, %g, %g)",
	      va[0], va[1], va[2]);
	LZ_REQUIRE(fabs(vb[1] + 4) < 1e-14 && fabs(vc[1]) < 1e-14 && vb[2] == w && vc[2] == w,
	      "b and c collided head on along y: b must leave at (0, -4, %g) and c stop but for the "
	      "drift; v_b = (%g, %g, %g), v_c = (%g, %g, %g)", w, vb[0], vb[1], vb[2], vc[0], vc[1],
	      vc[2]);
	LZ_REQUIRE(fabs(e->virial - 4) < 1e-12, "one head-on collision at closing speed 4: |Δp| = 4 at "
	      "|dr| = 1, so the virial is 4; it is %.15g (a phantom collision adds to it)", e->virial);
	LZ_REQUIRE(e->p[0].count == 0 && e->p[1].count == 1 && e->p[2].count == 1,
	      "collision counts must be (0, 1, 1) for a, b, c; got (%u, %u, %u)", e->p[0].count,
	      e->p[1].count, e->p[2].count);
	healthy(e, &b0, "three particles after the stale event");
	lz_edmd_free(e);
}
END_TEST

/* ---- many particles ---- */

LZ_TEST(cells_stay_consistent_over_many_events)
{
	/* after every few hundred events: every particle in the list of its cell and
	 * inside it, clocks in order, the heap valid (lz_edmd_audit) */
	for (int dim = 2; dim <= 3; dim++) {
		lz_edmd *e = lattice_system(dim, dim == 3 ? 500 : 400, 0.3, 1, LZ_EDMD_WALLS_NONE, 0,
		                            520 + dim);
		for (int k = 0; k < 300; k++) {
			run(e, 333, "cells kept over many events");
			LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%dD, η = 0.3, after %d events (%llu crossings, "
			      "%llu collisions): %s", dim, 333 * (k + 1), (unsigned long long)e->crossings,
			      (unsigned long long)e->collisions, lz_error_message());
		}
		LZ_REQUIRE(e->crossings > 1000 && e->collisions > 1000, "%dD, η = 0.3, 10^5 events: %llu "
		      "crossings and %llu collisions — both should be in the thousands", dim,
		      (unsigned long long)e->crossings, (unsigned long long)e->collisions);
		for (uint32_t i = 0; i < e->n; i++)
			for (int a = 0; a < dim; a++)
				LZ_REQUIRE(e->p[i].r[a] >= -1e-9 && e->p[i].r[a] <= e->L + 1e-9,
				      "%dD: particle %u has %c = %g, outside the box [0, %g]: a crossing of the "
				      "periodic boundary must wrap the position", dim, i, "xyz"[a],
				      e->p[i].r[a], e->L);
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(energy_and_momentum_conserved)
{
	for (int dim = 2; dim <= 3; dim++) {
		lz_edmd *e = lattice_system(dim, 500, dim == 3 ? 0.4 : 0.6, 1, LZ_EDMD_WALLS_NONE, 0,
		                            530 + dim);
		double E0 = lz_edmd_energy(e), P0[3], P[3];
		lz_edmd_momentum(e, P0);
		for (int k = 0; k < 10; k++) {
			run(e, 10000, "energy and momentum");
			double E = lz_edmd_energy(e);
			lz_edmd_momentum(e, P);
			LZ_REQUIRE(fabs(E / E0 - 1) < 1e-11, "%dD, η = %g, elastic: after %d events (%llu "
			      "collisions) the energy is %.15g, it started at %.15g (relative change %.2g): "
			      "an elastic bounce keeps the energy to round-off", dim, dim == 3 ? 0.4 : 0.6,
			      10000 * (k + 1), (unsigned long long)e->collisions, E, E0, E / E0 - 1);
			for (int a = 0; a < 3; a++)
				LZ_REQUIRE(fabs(P[a] - P0[a]) < 1e-10, "%dD: after %d events the momentum %c is %.3g, "
				      "it started at %.3g: equal and opposite impulses keep it", dim,
				      10000 * (k + 1), "xyz"[a], P[a], P0[a]);
		}
		LZ_REQUIRE(lz_edmd_max_overlap(e, NULL, NULL) < 1e-10, "%dD: overlap %.3g after 10^5 events",
		      dim, lz_edmd_max_overlap(e, NULL, NULL));
		lz_edmd_free(e);
	}
}
END_TEST

/* Block averages of Z, of the identity side Z_Γ, of their difference, and of Γ over
 * `blocks` blocks of `events` events. */
typedef struct {
	double Z, Z_err, Zg, Zg_err, diff, diff_err, gamma, gamma_err, T;
} blocks_t;

static blocks_t measure(lz_edmd *e, int blocks, uint64_t events, int momentum_fix)
{
	double *Z = malloc(blocks * sizeof *Z), *Zg = malloc(blocks * sizeof *Zg);
	double *D = malloc(blocks * sizeof *D), *G = malloc(blocks * sizeof *G);
	LZ_REQUIRE(Z && Zg && D && G, "out of memory for %d blocks", blocks);
	int dim = e->dim;
	double n = (double)e->n, T = 0;
	/* With the total momentum fixed at 0, the relative velocity of two particles has
	 * variance 2T·n/(n-1) rather than 2T, which puts a factor √(n/(n-1)) into the
	 * mean impulse of a collision: Z - 1 exceeds the canonical identity by (Z-1)/(2n),
	 * 0.0015 at η = 0.4 and n = 2048, half the error bar of the difference. */
	double fix = momentum_fix ? sqrt(n / (n - 1)) : 1;
	for (int b = 0; b < blocks; b++) {
		lz_edmd_reset_counts(e);
		run(e, events, "a measurement block");
		T = lz_edmd_temperature(e);
		double t = lz_edmd_time(e) - e->t_reset;
		Z[b] = 1 + e->virial / (dim * n * T * t);
		G[b] = 2.0 * e->collisions / (n * t);
		Zg[b] = 1 + sqrt(M_PI / T) * fix * G[b] / (2 * dim);
		D[b] = Z[b] - Zg[b];
	}
	blocks_t out;
	out.Z = gsl_stats_mean(Z, 1, blocks);
	out.Z_err = gsl_stats_sd(Z, 1, blocks) / sqrt(blocks);
	out.Zg = gsl_stats_mean(Zg, 1, blocks);
	out.Zg_err = gsl_stats_sd(Zg, 1, blocks) / sqrt(blocks);
	out.diff = gsl_stats_mean(D, 1, blocks);
	out.diff_err = gsl_stats_sd(D, 1, blocks) / sqrt(blocks);
	out.gamma = gsl_stats_mean(G, 1, blocks);
	out.gamma_err = gsl_stats_sd(G, 1, blocks) / sqrt(blocks);
	out.T = T;
	free(Z);
	free(Zg);
	free(D);
	free(G);
	return out;
}

LZ_TEST(ideal_gas_limit_at_packing_1e_4)
{
	/* At η = 1e-4 the gas is ideal to 4e-4: Z - 1 = 4η g(σ) (3D), 2η g(σ) (2D), with
	 * g(σ) = 1 + O(η), and the collision rate is Γ = 4√π n √T (3D), 2√π n √T (2D)
	 * (datasets/reference/collision-identity.csv). A mean free time is ~750 (3D) and ~2200 (2D) time units here;
	 * the runs last 20 (3D) and 50 (2D) of them, about 10^4 and 2.4·10^4 collisions:
	 * Z - 1 and Γ to about 1 %. The blocks are only 2 free times long, so their means are
	 * correlated and the block error is low by up to a quarter (measured over 40
	 * starts): the tolerance is 4 block errors, about 3 true standard errors. */
	for (int dim = 2; dim <= 3; dim++) {
		double eta = 1e-4;
		lz_edmd *e = random_gas(dim, 1000, eta, 540 + dim);
		double nd = e->n / pow(e->L, dim);
		blocks_t m = dim == 3 ? measure(e, 10, 400000, 0) : measure(e, 20, 120000, 0);
		double zexp = (dim == 3 ? 4 : 2) * eta, gexp = (dim == 3 ? 4 : 2) * sqrt(M_PI) * nd * sqrt(m.T);
		LZ_REQUIRE(fabs(m.Z - 1) < 0.01, "%dD ideal gas (η = 1e-4): Z = %.6f, expected 1 + %.1e: is "
		      "the virial (r_ab·Δp) or its sum right?", dim, m.Z, zexp);
		LZ_REQUIRE(fabs(m.Z - 1 - zexp) <= 4 * m.Z_err,
		      "%dD, η = 1e-4: Z - 1 = %.4e ± %.1e (block error), the dilute gas has Z - 1 = "
		      "%dη = %.4e: the virial per collision is off (bounce: |dr|·|Δp|?)", dim, m.Z - 1,
		      m.Z_err, dim == 3 ? 4 : 2, zexp);
		LZ_REQUIRE(fabs(m.gamma - gexp) <= 4 * m.gamma_err,
		      "%dD, η = 1e-4: collision rate per particle Γ = %.5e ± %.1e, kinetic theory gives "
		      "%s√π n √T = %.5e — collisions are missed (or counted twice)", dim, m.gamma,
		      m.gamma_err, dim == 3 ? "4" : "2", gexp);
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(pressure_at_packing_0_3_matches_the_reference)
{
	/* Hard spheres at η = 0.3: Z_ref = 3.9840 ± 0.0005 (datasets/reference/
	 * hard-spheres.csv: the resummed virial series). N = 4000 keeps the finite-size shift (~(Z-1)/N) well below the error
	 * bar. 20 blocks of 2·10^5 events (about 25 collisions per particle each). */
	lz_edmd *e = lattice_system(3, 4000, 0.3, 1, LZ_EDMD_WALLS_NONE, 0, 551);
	run(e, 150000, "equilibration at η = 0.3");
	blocks_t m = measure(e, 20, 200000, 0);
	lz_ref z = lz_test_reference("hard-spheres.csv", "Z", "3", "eta=0.30");
	double ref = z.value, ref_err = z.err, tol = 3 * m.Z_err + ref_err;
	LZ_REQUIRE(m.Z_err < 0.01, "η = 0.3: the block error of Z is %.3g, far too large for 4·10^6 "
	      "events — the pressure jumps from block to block", m.Z_err);
	LZ_REQUIRE(fabs(m.Z - ref) <= tol,
	      "hard spheres at η = 0.3 (N = 4000, 4·10^6 events): Z = βP/ρ = %.4f ± %.4f, the "
	      "reference is %.4f ± %.4f (Carnahan-Starling 3.9738); tolerance 3 block errors + the "
	      "reference's. %s", m.Z, m.Z_err, ref, ref_err,
	      m.Z < ref ? "Too low: collisions missed, or too little impulse per bounce."
	                : "Too high: phantom collisions (stale events?), or too much impulse.");
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(pressure_identity_with_the_collision_rate)
{
	/* For any hard-sphere fluid in equilibrium Z = 1 + √(π/T) Γ/6 (3D), exactly
	 * (datasets/reference/collision-identity.csv): the impulses on one side, a count of collisions on the other.
	 * Checked on the block means of the difference, to 3 standard errors, with the
	 * factor √(n/(n-1)) of a fixed total momentum (see measure). */
	lz_edmd *e = lattice_system(3, 2048, 0.4, 1, LZ_EDMD_WALLS_NONE, 0, 561);
	run(e, 80000, "equilibration at η = 0.4");
	blocks_t m = measure(e, 20, 100000, 1);
	LZ_REQUIRE(fabs(m.diff) <= 3 * m.diff_err,
	      "η = 0.4 (N = 2048): the virial gives Z = %.5f ± %.5f, the collision rate Γ = %.4f "
	      "gives 1 + √(π/T)Γ/6 = %.5f ± %.5f; the difference %.5f ± %.5f must vanish within 3 "
	      "errors — %s", m.Z, m.Z_err, m.gamma, m.Zg, m.Zg_err, m.diff, m.diff_err,
	      m.diff > 0 ? "too much impulse per collision (the bounce) or collisions not counted"
	                 : "too little impulse per collision, or phantom collisions counted");
	LZ_REQUIRE(m.Z > 6.0 && m.Z < 7.9, "η = 0.4: Z = %.4f, hard spheres have 6.947 (datasets/reference/hard-spheres.csv)",
	      m.Z);
	lz_edmd_free(e);
}
END_TEST

static void dense_no_overlap(int dim, size_t n, double eta)
{
	lz_edmd *e = lattice_system(dim, n, eta, 1, LZ_EDMD_WALLS_NONE, 0, 570 + dim);
	double E0 = lz_edmd_energy(e);
	for (int k = 0; k < 10; k++) {
		run(e, 100000, "a dense fluid");
		uint32_t i = 0, j = 0;
		double over = lz_edmd_max_overlap(e, &i, &j);
		LZ_REQUIRE(over < 1e-10, "%dD, η = %g, N = %zu: after %d events particles %u and %u overlap "
		      "by %.3g (their centres are %.12g apart) — a collision was missed: look at the "
		      "block of cells in predict, the periodic images, and the stale check", dim, eta,
		      n, 100000 * (k + 1), i, j, over, 1 - over);
	}
	LZ_REQUIRE(fabs(lz_edmd_energy(e) / E0 - 1) < 1e-10, "%dD, η = %g: the energy changed by %.2g "
	      "(relative) over 10^6 events", dim, eta, lz_edmd_energy(e) / E0 - 1);
	LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%dD, η = %g, after 10^6 events: %s", dim, eta,
	      lz_error_message());
	LZ_REQUIRE(e->collisions > 500000, "%dD, η = %g: only %llu collisions in 10^6 events — a dense "
	      "fluid has mostly collisions", dim, eta, (unsigned long long)e->collisions);
	lz_edmd_free(e);
}

LZ_TEST(no_overlap_dense_spheres_eta_0_49)
{
	dense_no_overlap(3, 4096, 0.49);
}
END_TEST

LZ_TEST(no_overlap_dense_disks_eta_0_69)
{
	dense_no_overlap(2, 4096, 0.69);
}
END_TEST

/* ---- extremes ---- */

LZ_TEST(one_particle_flies_free)
{
	/* N = 1: nothing to collide with. After time t it is at r0 + v t, wrapped into
	 * the box; the only events are cell crossings, one per cell boundary the
	 * unwrapped path passes. Long enough for several re-bases. */
	lz_edmd *e = box_of_side(3, 1, 10, LZ_EDMD_WALLS_NONE, 0, 1);
	double L = e->L;
	double r0[3] = {1.234, 5.678, 9.5}, v0[3] = {0.37, -1.21, 2.9};
	place(e, r0, v0);
	double T = 1234.5;
	int st = run_checked(e, 100000000, T, "one particle in free flight");
	LZ_REQUIRE(st == LZ_OK, "one particle, run to t = %g: %s", T, lz_error_message());
	LZ_REQUIRE(fabs(lz_edmd_time(e) - T) < 1e-9, "the run was to stop at t = %g, the clock reads %.12g",
	      T, lz_edmd_time(e));
	uint64_t want = 0;
	for (int a = 0; a < 3; a++) {
		double x = r0[a] + v0[a] * T, w = e->w[a];
		want += (uint64_t)llabs((long long)floor(x / w) - (long long)floor(r0[a] / w));
		double wrapped = x - L * floor(x / L), got[3], vv[3];
		where(e, 0, got, vv);
		double d = fabs(got[a] - wrapped);
		d = fmin(d, L - d);
		LZ_REQUIRE(d < 1e-8 && got[a] >= 0 && got[a] < L,
		      "one particle from %c = %g at v = %g: at t = %g it must be at %.10g (wrapped into "
		      "[0, %g)), it is at %.10g", "xyz"[a], r0[a], v0[a], T, wrapped, L, got[a]);
		LZ_REQUIRE(vv[a] == v0[a], "a lone particle keeps its velocity: v%c = %g, was %g", "xyz"[a],
		      vv[a], v0[a]);
	}
	LZ_REQUIRE(e->collisions == 0 && e->bounces == 0 && e->stale == 0,
	      "one particle: no collisions, bounces or stale events possible; got %llu, %llu, %llu",
	      (unsigned long long)e->collisions, (unsigned long long)e->bounces,
	      (unsigned long long)e->stale);
	LZ_REQUIRE(e->crossings == want && e->events == want,
	      "one particle flying for t = %g crosses %llu cell boundaries (cells of %.6g); the loop "
	      "counted %llu crossings in %llu events", T, (unsigned long long)want, e->w[0],
	      (unsigned long long)e->crossings, (unsigned long long)e->events);
	LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "one particle after t = %g: %s", T, lz_error_message());
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(absolute_time_of_1e12)
{
	/* The clock set to 10^12 (resolution 1e-4 there) must not change the physics:
	 * the engine works with `now`, kept small by the re-bases. The same start
	 * without the offset must give the same trajectory, event for event. */
	lz_edmd *a = lattice_system(3, 500, 0.35, 1, LZ_EDMD_WALLS_NONE, 0, 581);
	lz_edmd *b = lattice_system(3, 500, 0.35, 1, LZ_EDMD_WALLS_NONE, 0, 581);
	lz_edmd_set_time(b, 1e12);
	double E0 = lz_edmd_energy(b);
	run(a, 200000, "the reference run");
	run(b, 200000, "a run at t = 1e12");
	double elapsed = lz_edmd_time(a);
	LZ_REQUIRE(fabs(lz_edmd_time(b) - (1e12 + elapsed)) < 1e-3,
	      "the clock started at 1e12 and %.10g time units were run: it reads %.17g, expected "
	      "%.17g", elapsed, lz_edmd_time(b), 1e12 + elapsed);
	LZ_REQUIRE(fabs(lz_edmd_energy(b) / E0 - 1) < 1e-11, "at t = 1e12 the energy drifted by %.2g",
	      lz_edmd_energy(b) / E0 - 1);
	double over = lz_edmd_max_overlap(b, NULL, NULL);
	LZ_REQUIRE(over < 1e-10, "at t = 1e12: an overlap of %.3g — absolute times lose digits: "
	      "predict and step must work with now, not t_base + now", over);
	LZ_REQUIRE(a->collisions == b->collisions && a->crossings == b->crossings,
	      "the same start with the clock at 0 and at 1e12 must run the same events: %llu and "
	      "%llu collisions, %llu and %llu crossings", (unsigned long long)a->collisions,
	      (unsigned long long)b->collisions, (unsigned long long)a->crossings,
	      (unsigned long long)b->crossings);
	LZ_REQUIRE(lz_edmd_audit(b) == LZ_OK, "at t = 1e12: %s", lz_error_message());
	lz_edmd_free(a);
	lz_edmd_free(b);
}
END_TEST

LZ_TEST(inelastic_collapse_is_reported)
{
	/* restitution 0.1 in a small dense system: the particles of a cluster collide
	 * ever faster (inelastic collapse). The run must stop with LZ_EPHYS instead of
	 * spinning for ever at one instant. */
	lz_edmd *e = lattice_system(2, 64, 0.5, 0.1, LZ_EDMD_WALLS_NONE, 0, 591);
	double E0 = lz_edmd_energy(e), P0[3], P[3];
	lz_edmd_momentum(e, P0);
	int st = run_checked(e, 3000000, INFINITY, "inelastic collapse");
	LZ_REQUIRE(st == LZ_EPHYS, "2D, 64 disks at η = 0.5 with restitution 0.1: the run should stop "
	      "with LZ_EPHYS (inelastic collapse); it returned %d after %llu events (%llu "
	      "collisions), kinetic energy %.3g of %.3g%s", st, (unsigned long long)e->events,
	      (unsigned long long)e->collisions, lz_edmd_energy(e), E0,
	      fabs(lz_edmd_energy(e) / E0 - 1) < 1e-6 ? " — no energy was lost: is the restitution "
	                                                  "used in the bounce?" : "");
	LZ_REQUIRE(strstr(lz_error_message(), "collapse") != NULL, "the error should name the inelastic "
	      "collapse: \"%s\"", lz_error_message());
	LZ_REQUIRE(lz_edmd_energy(e) < 0.95 * E0, "before the collapse the kinetic energy should have "
	      "dropped, it is %.3g of %.3g", lz_edmd_energy(e), E0);
	/* an inelastic bounce loses energy but never momentum (equal and opposite impulses,
	 * round-off of a few ulp per collision over ~10^6 of them); the loop stopped between
	 * events, with its invariants intact */
	lz_edmd_momentum(e, P);
	for (int a = 0; a < 2; a++)
		LZ_REQUIRE(fabs(P[a] - P0[a]) < 1e-9, "restitution 0.1: the momentum %c went from %.3g to "
		      "%.3g — an inelastic bounce must still give the partners equal and opposite "
		      "impulses", "xy"[a], P0[a], P[a]);
	LZ_REQUIRE(e->virial > 0, "after %llu collisions the virial sum is %.6g; each adds |dr|·|Δp| > 0",
	      (unsigned long long)e->collisions, e->virial);
	LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "at the inelastic collapse: %s", lz_error_message());
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(walls_keep_the_particles_in)
{
	/* a box with walls on every side: no centre beyond the contacts 1/2 and L - 1/2,
	 * the energy kept, the bounces counted */
	for (int dim = 2; dim <= 3; dim++) {
		lz_edmd *e = lattice_system(dim, 400, 0.3, 1, LZ_EDMD_WALLS_BOX, 0, 600 + dim);
		double E0 = lz_edmd_energy(e);
		for (int k = 0; k < 10; k++) {
			run(e, 20000, "a box with walls");
			for (uint32_t i = 0; i < e->n; i++) {
				double r[3], v[3];
				where(e, i, r, v);
				for (int a = 0; a < dim; a++)
					LZ_REQUIRE(r[a] >= 0.5 - 1e-9 && r[a] <= e->L - 0.5 + 1e-9,
					      "%dD box with walls (L = %.6g): particle %u has %c = %.12g, beyond the "
					      "wall contact [0.5, %.12g]: a face of an edge cell on a wall is a "
					      "bounce, not a crossing", dim, e->L, i, "xyz"[a], r[a], e->L - 0.5);
			}
			LZ_REQUIRE(lz_edmd_audit(e) == LZ_OK, "%dD box with walls: %s", dim, lz_error_message());
		}
		LZ_REQUIRE(fabs(lz_edmd_energy(e) / E0 - 1) < 1e-11, "%dD box with walls: the energy changed "
		      "by %.2g (relative) over 2·10^5 events; a wall bounce reverses one component and "
		      "keeps the energy", dim, lz_edmd_energy(e) / E0 - 1);
		LZ_REQUIRE(e->bounces > 1000 && e->collisions > 1000, "%dD box with walls: %llu wall bounces "
		      "and %llu collisions in 2·10^5 events — both should be in the thousands", dim,
		      (unsigned long long)e->bounces, (unsigned long long)e->collisions);
		LZ_REQUIRE(lz_edmd_max_overlap(e, NULL, NULL) < 1e-10, "%dD box with walls: overlap %.3g",
		      dim, lz_edmd_max_overlap(e, NULL, NULL));
		lz_edmd_free(e);
	}
}
END_TEST

LZ_TEST(one_particle_between_two_walls)
{
	/* walls on x at 0 and L: the centre goes back and forth between 1/2 and L - 1/2,
	 * a triangle wave; y and z are periodic. Each bounce reverses v_x and adds 1 to
	 * the particle's count. */
	lz_edmd *e = box_of_side(3, 1, 10, LZ_EDMD_WALLS_X, 0, 1);
	double L = e->L, span = L - 1;
	double r0[3] = {3.3, 2, 7}, v0[3] = {2.1, 0.45, -0.2};
	place(e, r0, v0);
	double T = 500.25;
	int st = run_checked(e, 100000000, T, "one particle between walls");
	LZ_REQUIRE(st == LZ_OK, "one particle between walls, run to t = %g: %s", T, lz_error_message());
	double s = (r0[0] - 0.5) + v0[0] * T;  /* unfolded distance from the lower contact */
	uint64_t bounces = (uint64_t)floor(s / span);
	double f = fmod(s, 2 * span), want_x = f < span ? 0.5 + f : 0.5 + 2 * span - f;
	double want_v = f < span ? v0[0] : -v0[0];
	double r[3], v[3];
	where(e, 0, r, v);
	LZ_REQUIRE(fabs(r[0] - want_x) < 1e-8 && v[0] == want_v,
	      "one particle between walls at x = 0.5 and %.6g (contacts), from x = %g at v = %g: "
	      "after t = %g it must be at x = %.10g moving %g (a triangle wave); it is at x = %.10g "
	      "moving %g", L - 0.5, r0[0], v0[0], T, want_x, want_v, r[0], v[0]);
	LZ_REQUIRE(e->bounces == bounces, "one particle between walls: %llu bounces expected in t = %g, "
	      "counted %llu", (unsigned long long)bounces, T, (unsigned long long)e->bounces);
	LZ_REQUIRE(e->p[0].count == bounces, "every wall bounce changes the velocity, so it must add 1 "
	      "to the particle's count: count = %u after %llu bounces", e->p[0].count,
	      (unsigned long long)bounces);
	double wy = r0[1] + v0[1] * T, wz = r0[2] + v0[2] * T;
	wy -= L * floor(wy / L);
	wz -= L * floor(wz / L);
	LZ_REQUIRE(fabs(r[1] - wy) < 1e-8 && fabs(r[2] - wz) < 1e-8, "walls on x only: y and z are "
	      "periodic, expected (y, z) = (%.10g, %.10g), got (%.10g, %.10g)", wy, wz, r[1], r[2]);
	LZ_REQUIRE(e->collisions == 0, "one particle: %llu collisions", (unsigned long long)e->collisions);
	lz_edmd_free(e);
}
END_TEST

LZ_TEST(gravity_bouncing_ball_and_energy)
{
	/* One ball dropped from rest at x = 5 under g = 1 onto the wall contact x = 1/2:
	 * it lands at t = 3 at speed 3 and, bouncing elastically, lands again every 6.
	 * At t = 100 (1 after the 17th landing at 99) it is at x = 0.5 + 3 - 1/2 = 3
	 * rising at 2. */
	lz_edmd *e = box_of_side(3, 1, 10, LZ_EDMD_WALLS_X, 1.0, 1);
	double r0[3] = {5, 5, 5}, v0[3] = {0, 0.3, 0};
	place(e, r0, v0);
	int st = run_checked(e, 100000000, 100, "the bouncing ball");
	LZ_REQUIRE(st == LZ_OK, "the bouncing ball, run to t = 100: %s", lz_error_message());
	double r[3], v[3];
	where(e, 0, r, v);
	LZ_REQUIRE(fabs(r[0] - 3) < 1e-8 && fabs(v[0] - 2) < 1e-8,
	      "a ball dropped from x = 5 at rest, g = 1, elastic floor contact at 0.5: at t = 100 it "
	      "is at x = 3 rising at 2; it is at x = %.12g with v_x = %.12g — with gravity the face "
	      "and wall times come from the parabola", r[0], v[0]);
	LZ_REQUIRE(e->bounces == 17, "the ball lands at t = 3, 9, ..., 99: 17 bounces by t = 100, "
	      "counted %llu", (unsigned long long)e->bounces);
	lz_edmd_free(e);

	/* a gas under gravity with walls on x: E = KE + Σ g x is conserved */
	for (int dim = 2; dim <= 3; dim++) {
		lz_edmd *q = lattice_system(dim, 400, 0.2, 1, LZ_EDMD_WALLS_X, 0.2, 610 + dim);
		double E0 = lz_edmd_energy(q);
		for (int k = 0; k < 10; k++) {
			run(q, 10000, "a gas under gravity");
			double E = lz_edmd_energy(q);
			LZ_REQUIRE(fabs(E / E0 - 1) < 1e-10, "%dD gas under gravity g = 0.2: after %d events the "
			      "energy KE + Σ g x is %.15g, it started at %.15g (relative %.2g)", dim,
			      10000 * (k + 1), E, E0, E / E0 - 1);
			LZ_REQUIRE(lz_edmd_audit(q) == LZ_OK, "%dD under gravity: %s", dim, lz_error_message());
		}
		LZ_REQUIRE(q->bounces > 100 && q->collisions > 1000, "%dD under gravity: %llu bounces, %llu "
		      "collisions", dim, (unsigned long long)q->bounces, (unsigned long long)q->collisions);
		LZ_REQUIRE(lz_edmd_max_overlap(q, NULL, NULL) < 1e-10, "%dD under gravity: overlap %.3g", dim,
		      lz_edmd_max_overlap(q, NULL, NULL));
		lz_edmd_free(q);
	}
}
END_TEST
