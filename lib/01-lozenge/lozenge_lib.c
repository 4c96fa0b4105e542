/* lozenge_lib.c — the library half of lz/lozenge.h (the truncation order itself is
 * graded, in solutions/01-lozenge/lozenge.c): exact rational arithmetic for the
 * weights, the built-in schemes as stencils, and the lozenge diagram.
 *
 * Rationals: every result is reduced, with den > 0 and |num|, den <= 2^62. Products
 * and sums are formed in __int128, where two such operands cannot overflow, then
 * reduced; a result still beyond 2^62 is reported as the invalid ratio {0, 0}, which
 * every operation passes on.
 *
 * The diagram (thesis fig. 1.1): columns r, v, a, b left to right, time running
 * down, the v and b columns shifted by half a step. The skeleton is small empty
 * circles; a sample a formula uses is a filled circle, or a filled square when it
 * sits at a whole step in a half-step column (velocity Verlet's v) or the other
 * way round; the target is ringed; an arrow runs from every term to its target,
 * labelled with the weight. Arrows along one column that would pass over another
 * node bend out to the left of the column instead.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lz/error.h"
#include "lz/lozenge.h"

/* ---- exact rationals ---- */

#define RATIO_MAX ((__int128)1 << 62)

static const lz_ratio invalid = {0, 0};

static unsigned __int128 gcd128(unsigned __int128 a, unsigned __int128 b)
{
	while (b != 0) {
		unsigned __int128 t = a % b;
		a = b;
		b = t;
	}
	return a;
}

/* num/den reduced; invalid when den == 0 or the reduced terms exceed 2^62. */
static lz_ratio reduce(__int128 num, __int128 den)
{
	if (den == 0)
		return invalid;
	if (den < 0) {
		num = -num;
		den = -den;
	}
	unsigned __int128 mag = num < 0 ? (unsigned __int128)-num : (unsigned __int128)num;
	unsigned __int128 g = gcd128(mag, (unsigned __int128)den);
	if (g > 1) {
		num /= (__int128)g;
		den /= (__int128)g;
	}
	if (num > RATIO_MAX || num < -RATIO_MAX || den > RATIO_MAX)
		return invalid;
	return (lz_ratio){(long long)num, (long long)den};
}

int lz_ratio_ok(lz_ratio a)
{
	return a.den > 0;
}

/* An operand the __int128 arithmetic below cannot overflow on (a hand-made ratio
 * may hold anything). */
static int operand(lz_ratio a)
{
	return a.den > 0 && a.den <= RATIO_MAX && a.num <= RATIO_MAX && a.num >= -RATIO_MAX;
}

int lz_ratio_is_zero(lz_ratio a)
{
	return lz_ratio_ok(a) && a.num == 0;
}

lz_ratio lz_ratio_make(long long num, long long den)
{
	return reduce(num, den);
}

lz_ratio lz_ratio_add(lz_ratio a, lz_ratio b)
{
	if (!operand(a) || !operand(b))
		return invalid;
	return reduce((__int128)a.num * b.den + (__int128)b.num * a.den, (__int128)a.den * b.den);
}

lz_ratio lz_ratio_sub(lz_ratio a, lz_ratio b)
{
	if (!operand(a) || !operand(b))
		return invalid;
	return reduce((__int128)a.num * b.den - (__int128)b.num * a.den, (__int128)a.den * b.den);
}

lz_ratio lz_ratio_mul(lz_ratio a, lz_ratio b)
{
	if (!operand(a) || !operand(b))
		return invalid;
	return reduce((__int128)a.num * b.num, (__int128)a.den * b.den);
}

const char *lz_ratio_str(lz_ratio a, char *buf, size_t size)
{
	if (!lz_ratio_ok(a))
		snprintf(buf, size, "invalid");
	else if (a.den == 1)
		snprintf(buf, size, "%lld", a.num);
	else
		snprintf(buf, size, "%lld/%lld", a.num, a.den);
	return buf;
}

/* ---- the schemes and the diagram ---- */

/* A term: column, time offset in half steps, weight n/d (lz/lozenge.h). The rows
 * below read like the formulas, e.g. Verlet's r(+2) = 2 r(0) - 1 r(-2) + 1 a(0). */
#define TERM(c, h, n, d) {LZ_COL_##c, (h), {(n), (d)}}

static const lz_scheme schemes[] = {
	{"verlet", "Verlet (Störmer)", 1, {
		{LZ_COL_R, 2, 3, {TERM(R, 0, 2, 1), TERM(R, -2, -1, 1), TERM(A, 0, 1, 1)}},
	}},
	{"velocity", "central-difference velocity", 1, {
		{LZ_COL_V, 0, 2, {TERM(R, 2, 1, 2), TERM(R, -2, -1, 2)}},
	}},
	{"leapfrog", "leapfrog", 2, {
		{LZ_COL_V, 1, 2, {TERM(V, -1, 1, 1), TERM(A, 0, 1, 1)}},
		{LZ_COL_R, 2, 2, {TERM(R, 0, 1, 1), TERM(V, 1, 1, 1)}},
	}},
	{"velocity-verlet", "velocity Verlet", 2, {
		{LZ_COL_R, 2, 3, {TERM(R, 0, 1, 1), TERM(V, 0, 1, 1), TERM(A, 0, 1, 2)}},
		{LZ_COL_V, 2, 3, {TERM(V, 0, 1, 1), TERM(A, 0, 1, 2), TERM(A, 2, 1, 2)}},
	}},
	{"euler", "explicit Euler", 2, {
		{LZ_COL_R, 2, 2, {TERM(R, 0, 1, 1), TERM(V, 0, 1, 1)}},
		{LZ_COL_V, 2, 2, {TERM(V, 0, 1, 1), TERM(A, 0, 1, 1)}},
	}},
	{"symplectic-euler", "symplectic Euler", 2, {
		{LZ_COL_V, 2, 2, {TERM(V, 0, 1, 1), TERM(A, 0, 1, 1)}},
		{LZ_COL_R, 2, 2, {TERM(R, 0, 1, 1), TERM(V, 2, 1, 1)}},
	}},
};
#define NSCHEMES ((int)(sizeof schemes / sizeof schemes[0]))

const lz_scheme *lz_schemes(int *n)
{
	*n = NSCHEMES;
	return schemes;
}

const lz_scheme *lz_scheme_find(const char *name)
{
	for (int i = 0; name && i < NSCHEMES; i++)
		if (strcmp(schemes[i].name, name) == 0)
			return &schemes[i];
	return NULL;
}

/* ---- the diagram ---- */

#define NSCHEMES_MAX 6
static const unsigned colours[LZ_FORMULAS_MAX] = {0x1f5fa8, 0xc0392b, 0x2e8b57, 0x8e44ad};
static const char *const col_names[LZ_NCOLS] = {"r", "v", "a", "b"};

/* Picture coordinates: a column per unit across, a step per unit downwards. */
static double px(lz_column c) { return (double)c; }
static double py(int half) { return -0.5 * half; }

/* A column's own samples sit at whole steps (r, a) or half steps (v, b). */
static int on_skeleton(lz_column c, int half)
{
	return ((c + half) % 2 + 2) % 2 == 0;
}

static int scheme_ok(const lz_scheme *s)
{
	if (!s || s->nformulas < 1 || s->nformulas > LZ_FORMULAS_MAX)
		return 0;
	for (int i = 0; i < s->nformulas; i++) {
		const lz_formula *f = &s->f[i];
		if (f->nterms < 1 || f->nterms > LZ_TERMS_MAX || (unsigned)f->col >= LZ_NCOLS)
			return 0;
		for (int j = 0; j < f->nterms; j++)
			if ((unsigned)f->term[j].col >= LZ_NCOLS || f->term[j].w.den <= 0)
				return 0;
	}
	return 1;
}

/* Sample j of formula f: the target for j = -1, else term j. */
static lz_column sample_col(const lz_formula *f, int j)
{
	return j < 0 ? f->col : f->term[j].col;
}

static int sample_half(const lz_formula *f, int j)
{
	return j < 0 ? f->half : f->term[j].half;
}

/* The half-step range every panel shows: all samples, plus half a step. */
static void time_range(const lz_scheme *const *s, int ns, int *lo, int *hi)
{
	*lo = -3;
	*hi = 3;
	for (int i = 0; i < ns; i++)
		for (int k = 0; k < s[i]->nformulas; k++)
			for (int j = -1; j < s[i]->f[k].nterms; j++) {
				int h = sample_half(&s[i]->f[k], j);
				*lo = h - 1 < *lo ? h - 1 : *lo;
				*hi = h + 1 > *hi ? h + 1 : *hi;
			}
}

/* ---- text: times and formulas in gnuplot's enhanced syntax ---- */

/* "t", "t+δt", "t−2δt", "t+δt/2", "t−3δt/2". */
static const char *time_text(int half, char *buf, size_t size)
{
	int m = half < 0 ? -half : half, whole = m % 2 == 0, k = whole ? m / 2 : m;
	const char *sign = half < 0 ? "−" : "+";
	if (half == 0)
		snprintf(buf, size, "t");
	else if (k == 1)
		snprintf(buf, size, "t%sδt%s", sign, whole ? "" : "/2");
	else
		snprintf(buf, size, "t%s%dδt%s", sign, k, whole ? "" : "/2");
	return buf;
}

/* A weight times δt^power: "", "2 ", "1/2 δt^2 ", "1/(2δt) ". */
static void factor_text(lz_ratio w, int power, char *buf, size_t size)
{
	long long num = w.num < 0 ? -w.num : w.num, den = w.den;
	char dt[16] = "δt";
	if (power < -1 || power > 1)
		snprintf(dt, sizeof dt, "δt^%d", power < 0 ? -power : power);
	const char *dt_part = power > 0 ? dt : "", *gap = power > 0 ? " " : "";
	if (power < 0 && den == 1)
		snprintf(buf, size, "%lld/%s ", num, dt);
	else if (power < 0)
		snprintf(buf, size, "%lld/(%lld%s) ", num, den, dt);
	else if (den != 1)
		snprintf(buf, size, "%lld/%lld %s%s", num, den, dt_part, gap);
	else if (num != 1)
		snprintf(buf, size, "%lld %s%s", num, dt_part, gap);
	else
		snprintf(buf, size, "%s%s", dt_part, gap);
}

/* "r(t+δt) = 2 r(t) − r(t−δt) + δt^2 a(t)". */
static void formula_text(const lz_formula *f, char *buf, size_t size)
{
	char when[32];
	size_t used = (size_t)snprintf(buf, size, "%s(%s) =", col_names[f->col],
	                               time_text(f->half, when, sizeof when));
	for (int j = 0; j < f->nterms && used < size; j++) {
		const lz_term *t = &f->term[j];
		char w[64];
		factor_text(t->w, (int)t->col - (int)f->col, w, sizeof w);
		const char *sign = t->w.num < 0 ? " −" : j ? " +" : "";
		used += (size_t)snprintf(buf + used, size - used, "%s %s%s(%s)", sign, w,
		                         col_names[t->col], time_text(t->half, when, sizeof when));
	}
}

/* ---- the script ---- */

static void write_skeleton(FILE *out, int lo, int hi)
{
	fprintf(out, "$skeleton << EOD\n");
	for (int c = 0; c < LZ_NCOLS; c++)
		for (int h = lo; h <= hi; h++)
			if (on_skeleton((lz_column)c, h))
				fprintf(out, "%g %g\n", px((lz_column)c), py(h));
	fprintf(out, "EOD\n");
}

/* The samples scheme i uses, on (circles) or off (squares) their column's skeleton,
 * and its targets with the colour of their formula. */
static void write_samples(FILE *out, const lz_scheme *s, int i)
{
	for (int on = 1; on >= 0; on--) {
		fprintf(out, "$%s%d << EOD\n", on ? "circle" : "square", i);
		for (int k = 0; k < s->nformulas; k++)
			for (int j = -1; j < s->f[k].nterms; j++) {
				lz_column c = sample_col(&s->f[k], j);
				int h = sample_half(&s->f[k], j);
				if (on_skeleton(c, h) == on)
					fprintf(out, "%g %g\n", px(c), py(h));
			}
		/* A point far outside the picture keeps an otherwise empty block plottable. */
		fprintf(out, "1e9 1e9\nEOD\n");
	}
	fprintf(out, "$target%d << EOD\n", i);
	for (int k = 0; k < s->nformulas; k++)
		fprintf(out, "%g %g %u\n", px(s->f[k].col), py(s->f[k].half), colours[k]);
	fprintf(out, "EOD\n");
}

/* Where the weight labels of one panel went, so that the next one avoids them. */
typedef struct {
	int n;
	double x[LZ_FORMULAS_MAX * LZ_TERMS_MAX], y[LZ_FORMULAS_MAX * LZ_TERMS_MAX];
} label_spots;

/* How far a label at (x, y) is from the nearest node and the nearest earlier label.
 * Labels are wider than tall, so horizontal distance counts less. */
static double clearance(const label_spots *l, double x, double y)
{
	double best = 1e9;
	for (int c = 0; c < LZ_NCOLS; c++) {
		/* The nearest node of column c: r, a every step, v, b offset by half. */
		double row = c % 2 ? floor(y) + 0.5 : round(y);
		if (c % 2 && y - row > 0.5)
			row += 1.0;
		best = fmin(best, hypot(0.6 * (x - c), y - row));
	}
	for (int i = 0; i < l->n; i++)
		best = fmin(best, hypot(0.6 * (x - l->x[i]), y - l->y[i]));
	return best;
}

/* A spot beside the arrow (x0,y0) -> (x1,y1): a few places along it on either side,
 * the one clearest of nodes and earlier labels. */
static void place_label(label_spots *l, double x0, double y0, double x1, double y1,
                        double *lx, double *ly)
{
	static const double along[] = {0.4, 0.55, 0.25, 0.7};
	double dx = x1 - x0, dy = y1 - y0, len = hypot(dx, dy), best = -1.0;
	for (int i = 0; i < 4; i++)
		for (int side = 1; side >= -1; side -= 2) {
			double x = x0 + along[i] * dx + side * 0.14 * dy / len;
			double y = y0 + along[i] * dy - side * 0.14 * dx / len;
			double c = clearance(l, x, y);
			if (c > best + 0.02) {
				best = c;
				*lx = x;
				*ly = y;
			}
		}
	l->x[l->n] = *lx;
	l->y[l->n++] = *ly;
}

/* An arrow from a term to its target, shortened at both ends so that it stops at
 * the markers, with the weight written beside it. Along one column across more than
 * one step the arrow bends left of the column so it does not run over a node. */
static void write_arrow(FILE *out, const lz_term *t, const lz_formula *f, unsigned colour,
                        label_spots *spots)
{
	double x0 = px(t->col), y0 = py(t->half), x1 = px(f->col), y1 = py(f->half);
	char w[64];
	lz_ratio_str(t->w, w, sizeof w);
	const char *head = "head filled size 0.1,20 lw 1.6 lc rgb";
	if (t->col == f->col && (t->half - f->half > 2 || f->half - t->half > 2)) {
		double bx = x0 - 0.38, by = 0.5 * (y0 + y1), dir = y1 > y0 ? 1.0 : -1.0;
		fprintf(out, "set arrow from %g,%g to %g,%g nohead lw 1.6 lc rgb '#%06x'\n",
		        x0 - 0.09, y0 + 0.09 * dir, bx, by, colour);
		fprintf(out, "set arrow from %g,%g to %g,%g %s '#%06x'\n", bx, by, x1 - 0.09,
		        y1 - 0.09 * dir, head, colour);
		fprintf(out, "set label '%s' at %g,%g right tc rgb '#%06x'\n", w, bx - 0.05, by,
		        colour);
		spots->x[spots->n] = bx - 0.15;
		spots->y[spots->n++] = by;
		return;
	}
	double dx = x1 - x0, dy = y1 - y0, cut = 0.12 / hypot(dx, dy), lx = 0, ly = 0;
	fprintf(out, "set arrow from %g,%g to %g,%g %s '#%06x'\n", x0 + cut * dx,
	        y0 + cut * dy, x1 - cut * dx, y1 - cut * dy, head, colour);
	place_label(spots, x0, y0, x1, y1, &lx, &ly);
	fprintf(out, "set label '%s' at %g,%g center tc rgb '#%06x'\n", w, lx, ly, colour);
}

static void write_axes(FILE *out, int lo, int hi)
{
	fprintf(out, "set border 0\nunset key\nunset xtics\nset x2tics scale 0 font ',13' (");
	for (int c = 0; c < LZ_NCOLS; c++)
		fprintf(out, "%s'%s' %g", c ? ", " : "", col_names[c], px((lz_column)c));
	fprintf(out, ")\nset ytics scale 0 (");
	int first = lo % 2 == 0 ? lo : lo + 1;
	for (int h = first; h <= hi; h += 2) {
		char buf[32];
		fprintf(out, "%s'%s' %g", h == first ? "" : ", ", time_text(h, buf, sizeof buf),
		        py(h));
	}
	fprintf(out, ")\nset grid ytics lt 0 lc rgb '#d0d0d0'\n"
	        "set xrange [-0.7:3.3]\nset yrange [%g:%g]\n"
	        "set lmargin 8\nset rmargin 1\nset bmargin 5\nset tmargin 4\n",
	        py(hi) - 0.3, py(lo) + 0.3);
}

/* The canvas: pixels per panel across, per half step down, per legend row. */
enum { PANEL_PX = 380, MIN_WIDTH_PX = 600, HALF_STEP_PX = 75, FRAME_PX = 200,
       LEGEND_ROW_PX = 26, CHAR_PX = 7 };

static void write_panel(FILE *out, const lz_scheme *s, int i, int ns, double bottom)
{
	double width = 1.0 / ns;
	fprintf(out, "set origin %g,%g\nset size %g,%g\n", width * i, bottom, width, 1 - bottom);
	fprintf(out, "unset arrow\nunset label\nset title \"%s\" font ',13'\n", s->title);
	fprintf(out, "set format y %s\n", i == 0 ? "" : "''");
	label_spots spots = {0};
	for (int k = 0; k < s->nformulas; k++) {
		char text[512];
		formula_text(&s->f[k], text, sizeof text);
		/* Centred on the panel, not on its plot area (which the y labels shift). */
		fprintf(out, "set label \"%s\" at screen %g, graph %g center font ',10' "
		        "tc rgb '#%06x'\n", text, width * (i + 0.5), -0.04 - 0.06 * k, colours[k]);
		for (int j = 0; j < s->f[k].nterms; j++)
			write_arrow(out, &s->f[k].term[j], &s->f[k], colours[k], &spots);
	}
	fprintf(out, "plot $skeleton w p pt 6 ps 0.8 lc rgb '#a0a0a0', "
	        "$target%d u 1:2:3 w p pt 6 ps 3.2 lw 2.5 lc rgb variable, "
	        "$circle%d w p pt 7 ps 1.4 lc rgb '#202020', "
	        "$square%d w p pt 5 ps 1.4 lc rgb '#202020'\n", i, i, i);
}

/* The key: each marker with its meaning, in rows under the panels. */
static const struct {
	const char *style, *text;
} legend[] = {
	{"pt 6 ps 0.8 lc rgb '#a0a0a0'", "skeleton (r, a at whole steps; v, b at half steps)"},
	{"pt 7 ps 1.4 lc rgb '#202020'", "sample used"},
	{"pt 5 ps 1.4 lc rgb '#202020'", "sample off its column's grid (v at a whole step)"},
	{"pt 6 ps 2.4 lw 2.5 lc rgb '#1f5fa8'", "target (the arrows carry the weights)"},
};
#define NLEGEND ((int)(sizeof legend / sizeof legend[0]))

/* Lays the key out in character cells across a canvas `cols` wide: the x of each
 * entry and its row. Returns the number of rows. */
static int legend_layout(int cols, double *x, int *row)
{
	int rows = 1;
	double at = 2.0;
	for (int k = 0; k < NLEGEND; k++) {
		double need = 3.0 + (double)strlen(legend[k].text);
		if (at + need > cols && at > 2.0) {
			rows++;
			at = 2.0;
		}
		x[k] = at;
		row[k] = rows - 1;
		at += need + 4.0;
	}
	return rows;
}

static void write_legend(FILE *out, int cols, double height)
{
	double x[NLEGEND];
	int row[NLEGEND], rows = legend_layout(cols, x, row);
	fprintf(out, "set origin 0,0\nset size 1,%g\nunset title\nunset arrow\nunset label\n"
	        "unset x2tics\nunset ytics\nunset grid\nset margins 0,0,0,0\n"
	        "set xrange [0:%d]\nset yrange [0:%d]\nplot ", height, cols, rows);
	for (int k = 0; k < NLEGEND; k++) {
		double y = rows - row[k] - 0.5;
		fprintf(out, "%s'+' u (%g):(%g) every ::0::0 w p %s", k ? ", " : "", x[k], y,
		        legend[k].style);
		fprintf(out, ", '+' u (%g):(%g):(\"%s\") every ::0::0 w labels left font ',11' "
		        "tc rgb '#303030'", x[k] + 1.8, y, legend[k].text);
	}
	fprintf(out, "\n");
}

int lz_lozenge_gnuplot(FILE *out, const lz_scheme *const *s, int ns, const char *png)
{
	if (!out || !s || ns < 1 || ns > NSCHEMES_MAX)
		return lz_error(LZ_EINVAL, "lozenge diagram: nschemes = %d must be in 1..%d", ns,
		                NSCHEMES_MAX);
	if (!png || strpbrk(png, "'\n"))
		return lz_error(LZ_EINVAL, "lozenge diagram: the PNG name must be given and hold "
		                "no quote or newline");
	for (int i = 0; i < ns; i++)
		if (!scheme_ok(s[i]))
			return lz_error(LZ_EINVAL, "lozenge diagram: scheme %d is malformed (formulas "
			                "1..%d, terms 1..%d, columns r v a b, weights with den > 0)",
			                i, LZ_FORMULAS_MAX, LZ_TERMS_MAX);
	int lo, hi;
	time_range(s, ns, &lo, &hi);
	int width = PANEL_PX * ns > MIN_WIDTH_PX ? PANEL_PX * ns : MIN_WIDTH_PX;
	double x[NLEGEND];
	int row[NLEGEND], rows = legend_layout(width / CHAR_PX, x, row);
	int height = FRAME_PX + HALF_STEP_PX * (hi - lo) + LEGEND_ROW_PX * rows;
	double bottom = (double)(LEGEND_ROW_PX * rows + 8) / height;
	fprintf(out, "# The lozenge diagram (thesis fig. 1.1), written by lz_lozenge_gnuplot.\n"
	        "set terminal pngcairo size %d,%d enhanced font 'Sans,11'\n"
	        "set output '%s'\nset multiplot\n", width, height, png);
	write_skeleton(out, lo, hi);
	for (int i = 0; i < ns; i++)
		write_samples(out, s[i], i);
	write_axes(out, lo, hi);
	for (int i = 0; i < ns; i++)
		write_panel(out, s[i], i, ns, bottom);
	write_legend(out, width / CHAR_PX, bottom);
	fprintf(out, "unset multiplot\n");
	return ferror(out) ? lz_error(LZ_EIO, "lozenge diagram: writing the script failed")
	                   : LZ_OK;
}
