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
static int write_diagram(const char *out, const char *file, const char *png,
                         const char *const *names, int n)
{
	const lz_scheme *schemes[6];
	char path[4096];
	for (int i = 0; i < n; i++)
		if (!(schemes[i] = lz_scheme_find(names[i])))
			return lz_error(LZ_EINVAL, "no scheme named '%s'", names[i]);
	snprintf(path, sizeof path, "%s/%s", out, file);
	FILE *f = fopen(path, "w");
	if (!f)
		return lz_error(LZ_EIO, "cannot write %s", path);
	int status = lz_lozenge_gnuplot(f, schemes, n, png);
	if (fclose(f) != 0 && status == LZ_OK)
		status = lz_error(LZ_EIO, "cannot write %s", path);
	return status;
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
static int orders(lz_data *d, lz_json *j, int *ok)
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
			       lz_ratio_str(c, buf, sizeof buf), good ? "ok" : "CHECK FAILED");
			lz_data_row(d, (double[]){s, f, order, deriv, (double)c.num, (double)c.den});
			snprintf(key, sizeof key, "order_%s_%s", all[s].name, target);
			lz_json_int(j, key, order);
			*ok = *ok && good;
		}
	return LZ_OK;
}

int main(int argc, char **argv)
{
	if (argc < 2 || argc > 3 || (argc == 3 && strcmp(argv[2], "--quick") != 0)) {
		fprintf(stderr, "usage: %s OUTDIR [--quick]\n", argv[0]);
		return 2;
	}
	lz_set_error_handler(lz_error_quiet);  /* errors are reported once, by main */
	static const char *const verlet[] = {"verlet", "velocity", "leapfrog",
	                                     "velocity-verlet"};
	static const char *const euler[] = {"euler", "symplectic-euler"};
	static const char *names[] = {"scheme", "formula", "order", "deriv", "c_num", "c_den"};
	char path[4096], jpath[4096];
	int ok = 1;
	printf("lozenge: diagrams of verlet, velocity, leapfrog, velocity-verlet, euler, "
	       "symplectic-euler; truncation orders by exact Taylor expansion "
	       "(derivatives up to %d)\n", MAX_DERIV);
	snprintf(path, sizeof path, "%s/lozenge.dat", argv[1]);
	snprintf(jpath, sizeof jpath, "%s/lozenge.json", argv[1]);
	lz_data *d = lz_data_open(path, "local truncation error of every formula: "
	                          "c dt^order x^(deriv)", 6, names, NULL);
	lz_json *j = d ? lz_json_open(jpath) : NULL;
	int status = d && j ? LZ_OK : LZ_EIO;
	if (status == LZ_OK)
		status = write_diagram(argv[1], "diagram_verlet.gp", "lozenge.png", verlet, 4);
	if (status == LZ_OK)
		status = write_diagram(argv[1], "diagram_euler.gp", "lozenge_euler.png", euler, 2);
	if (status == LZ_OK)
		status = orders(d, j, &ok);
	if (j)
		lz_json_str(j, "check", ok ? "passed" : "FAILED");
	if ((d && lz_data_close(d) != LZ_OK) || (j && lz_json_end(j) != LZ_OK) ||
	    status != LZ_OK) {
		fprintf(stderr, "lozenge: %s\n", lz_error_message());
		return 2;
	}
	printf("check: Verlet order 4 (-1/12), velocity order 2 (1/6): %s\n",
	       ok ? "passed" : "FAILED (run `make test STAGE=01`)");
	return ok ? 0 : 1;
}
