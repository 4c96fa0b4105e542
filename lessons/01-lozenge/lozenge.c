/* lozenge — lesson 01, experiment 6 (§4): the schemes as pictures and their orders.
 *
 * Writes the gnuplot scripts that draw the lozenge diagrams (lz_lozenge_gnuplot):
 * diagram_verlet.gp draws Verlet and the central-difference velocity as in the
 * thesis figure 1.1, plus leapfrog and velocity Verlet; diagram_euler.gp the two
 * Euler schemes. The lesson's plot scripts lozenge.gp and lozenge_euler.gp load
 * them, so the diagrams are drawn like every other plot.
 * Then every formula of every known scheme goes through lz_formula_order, and the
 * two formulas of the thesis are checked against their hand-derived expansions:
 *   Verlet    Σ terms - r(t+dt)  = -1/12 dt⁴ r''''(t) + ...   (order 4, derivative 4)
 *   velocity  Σ terms - v(t)     =  1/6  dt² v''(t)   + ...   (order 2, derivative 3)
 *
 * Usage: lozenge OUTDIR [--quick]   (the same either way)
 * Writes OUTDIR/diagram_verlet.gp, diagram_euler.gp, lozenge.dat, lozenge.json.
 */
#include <stdio.h>
#include <string.h>

#include "lz/error.h"
#include "lz/lesson.h"
#include "lz/lozenge.h"
#include "lz/output.h"

#define MAX_DERIV 12

static const char *const col_name = "rvab";

typedef struct {
	const char *scheme;
	int formula;
	int order, deriv;
	long long num, den;
} expectation;

/* Worked out by hand in §4 of the lesson. */
static const expectation expected[] = {
	{"verlet", 0, 4, 4, -1, 12},
	{"velocity", 0, 2, 3, 1, 6},
};

/* Write the diagram script for the named schemes into OUTDIR/file. */
static int write_diagram(lz_lesson *L, const char *file, const char *png,
                         const char *const *names, int n)
{
	const lz_scheme *schemes[6];
	for (int i = 0; i < n; i++)
		if (!(schemes[i] = lz_scheme_find(names[i])))
			return lz_error(LZ_EINVAL, "no scheme named '%s'", names[i]);
	FILE *f = lz_lesson_fopen(L, file);
	if (!f)
		return LZ_EIO;
	int status = lz_lozenge_gnuplot(f, schemes, n, png);
	if (status != LZ_OK) {
		fclose(f);
		return status;
	}
	return lz_lesson_fclose(L, f, file);
}

/* 1 when (scheme, formula) has no hand-derived expectation or meets it. */
static int meets_expectation(const char *scheme, int formula, int order, int deriv,
                             lz_ratio c)
{
	for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
		const expectation *e = &expected[i];
		if (strcmp(e->scheme, scheme) == 0 && e->formula == formula)
			return order == e->order && deriv == e->deriv && c.num == e->num &&
			       c.den == e->den;
	}
	return 1;
}

/* One row per formula of every scheme: print it, check it, store it. */
static int orders(lz_lesson *L, lz_data *d, lz_json *j)
{
	int n;
	const lz_scheme *all = lz_schemes(&n);
	printf("  %-17s %-8s %5s %6s %10s\n", "scheme", "target", "order", "deriv", "leading");
	for (int s = 0; s < n; s++)
		for (int f = 0; f < all[s].nformulas; f++) {
			const lz_formula *fm = &all[s].f[f];
			int order, deriv;
			lz_ratio c;
			char target[16], buf[32], key[96];
			int status = lz_formula_order(fm, MAX_DERIV, &order, &c, &deriv);
			if (status != LZ_OK)
				return status;
			int good = meets_expectation(all[s].name, f, order, deriv, c);
			snprintf(target, sizeof target, "%c(%+d/2)", col_name[fm->col], fm->half);
			printf("  %-17s %-8s %5d %6d %10s  %s\n", all[s].name, target, order, deriv,
			       lz_ratio_str(c, buf, sizeof buf), lz_lesson_check(L, good));
			lz_data_row(d, (double[]){s, f, order, deriv, (double)c.num, (double)c.den});
			snprintf(key, sizeof key, "order_%s_%s", all[s].name, target);
			lz_json_int(j, key, order);
		}
	return LZ_OK;
}

int main(int argc, char **argv)
{
	lz_lesson L;
	if (lz_lesson_args(argc, argv, "01", &L) != LZ_OK)
		return 2;
	static const char *const verlet[] = {"verlet", "velocity", "leapfrog",
	                                     "velocity-verlet"};
	static const char *const euler[] = {"euler", "symplectic-euler"};
	static const char *names[] = {"scheme", "formula", "order", "deriv", "c_num", "c_den"};
	printf("lozenge: diagrams of verlet, velocity, leapfrog, velocity-verlet, euler, "
	       "symplectic-euler; truncation orders by exact Taylor expansion "
	       "(derivatives up to %d)\n", MAX_DERIV);
	lz_data *d = lz_lesson_data(&L, "lozenge.dat", "local truncation error of every "
	                            "formula: c dt^order x^(deriv)", 6, names, NULL);
	/* Opened before the checks, which run as the orders are written: its "check"
	 * member comes last. */
	const char *jpath = d ? lz_lesson_path(&L, "lozenge.json") : NULL;
	lz_json *j = jpath ? lz_json_open(jpath) : NULL;
	int status = d && j ? LZ_OK : LZ_EIO;
	if (status == LZ_OK)
		status = write_diagram(&L, "diagram_verlet.gp", "lozenge.png", verlet, 4);
	if (status == LZ_OK)
		status = write_diagram(&L, "diagram_euler.gp", "lozenge_euler.png", euler, 2);
	if (status == LZ_OK)
		status = orders(&L, d, j);
	if (j)
		lz_json_str(j, "check", lz_lesson_verdict(&L));
	if ((d && lz_data_close(d) != LZ_OK) || (j && lz_json_end(j) != LZ_OK) ||
	    status != LZ_OK)
		return lz_lesson_error(&L);
	return lz_lesson_finish(&L, "Verlet order 4 (-1/12), velocity order 2 (1/6)");
}
