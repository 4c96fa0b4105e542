/* cli.c — the `lz` command: run a scene, list the scenes, describe the methods.
 *
 * Every failure ends as one line "lz: message" on stderr and exit status 2 (bad
 * input) or 1 (a run that failed); a run validates everything before it creates a
 * directory, and a failed run leaves none behind.
 */
#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "interrupt.h"
#include "lz/error.h"
#include "method.h"
#include "lz/output.h"
#include "lz/rng.h"
#include "run_table.h"
#include "scene.h"
#include "lz/timer.h"

#ifndef LZ_SCENE_DIR
#define LZ_SCENE_DIR "datasets/scenes"
#endif

/* lz_cli_main's own status: the message is a usage error, show the usage too. */
enum { LZ_CLI_USAGE = -1 };

static const char lz_cli_usage_text[] =
	"usage: lz run SCENE [key=value ...] [--out DIR] [--quiet]\n"
	"       lz list\n"
	"       lz help [METHOD]\n";

/* The code of the last lz_error, for calls that report failure by returning NULL. */
static _Thread_local int lz_cli_code;

/* The CLI prints the message once, at the end; the handler only keeps the code. */
static void record(int code, const char *message)
{
	lz_cli_code = code;
}

const char *lz_scene_dir(void)
{
	const char *env = getenv("LZ_SCENES");
	return env && *env ? env : LZ_SCENE_DIR;
}

/* Report a usage error: the message, then the usage lines. */
static int print_usage(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int print_usage(const char *fmt, ...)
{
	char msg[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	lz_error(LZ_EINVAL, "%s", msg);
	return LZ_CLI_USAGE;
}

/* "verlet, walk, ..." */
static void method_names(char *buf, size_t size)
{
	size_t n, len = 0;
	const lz_method *const *m = lz_methods(&n);
	buf[0] = '\0';
	for (size_t i = 0; i < n && len < size; i++)
		len += (size_t)snprintf(buf + len, size - len, "%s%s", i ? ", " : "", m[i]->name);
}

/* ---- lz run ---- */

typedef struct {
	const char *scene;      /* SCENE as given */
	const char *out;        /* --out, or NULL for build/runs/<name> */
	int quiet;
	char **overrides;       /* key=value arguments, in order */
	int noverrides;
} lz_cli_args;

static int run_parse(int argc, char **argv, lz_cli_args *a)
{
	for (int i = 0; i < argc; i++) {
		const char *arg = argv[i];
		if (strcmp(arg, "--out") == 0) {
			if (i + 1 == argc)
				return print_usage("--out needs a directory");
			a->out = argv[++i];
		} else if (strncmp(arg, "--out=", 6) == 0) {
			a->out = arg + 6;
		} else if (strcmp(arg, "--quiet") == 0 || strcmp(arg, "-q") == 0) {
			a->quiet = 1;
		} else if (arg[0] == '-' && arg[1]) {
			return print_usage("unknown option '%s'", arg);
		} else if (!a->scene) {
			a->scene = arg;
		} else if (strchr(arg, '=')) {
			a->overrides[a->noverrides++] = argv[i];
		} else {
			return print_usage("unexpected argument '%s' (after SCENE come "
			                    "key=value overrides)", arg);
		}
	}
	if (!a->scene)
		return print_usage("lz run needs a scene");
	return LZ_OK;
}

/* SCENE as a path if it names a file, else as a name in the scene directory. */
static int scene_path(const char *arg, char *path, size_t size)
{
	struct stat st;
	if (strlen(arg) >= size)
		return lz_error(LZ_EINVAL, "scene path too long (%zu bytes)", strlen(arg));
	if (stat(arg, &st) == 0 || strchr(arg, '/')) {
		snprintf(path, size, "%s", arg);
		return LZ_OK;
	}
	const char *dir = lz_scene_dir();
	snprintf(path, size, "%s/%s.scene", dir, arg);
	if (stat(path, &st) == 0)
		return LZ_OK;
	snprintf(path, size, "%s/%s", dir, arg);
	if (stat(path, &st) == 0)
		return LZ_OK;
	return lz_error(LZ_EINVAL, "no scene '%s': not a file, and no %s.scene in %s "
	                "(`lz list` shows the scenes)", arg, arg, dir);
}

/* Read SCENE, apply the overrides, find its method and bind: every check a run
 * needs, done before anything is written. */
static int run_load(const lz_cli_args *a, lz_scene **sp, const lz_method **mp)
{
	char path[4096], names[512];
	int rc = scene_path(a->scene, path, sizeof path);
	if (rc != LZ_OK)
		return rc;
	lz_scene *s = *sp = lz_scene_read(path);
	if (!s)
		return lz_cli_code;
	for (int i = 0; i < a->noverrides; i++)
		if ((rc = lz_scene_set(s, a->overrides[i], "command line")) != LZ_OK)
			return rc;
	method_names(names, sizeof names);
	const char *method = lz_scene_method(s);
	if (!method)
		return lz_error(LZ_EINVAL, "%s: no 'method' key; say which engine runs the scene "
		                "(method = %s)", path, names);
	const lz_method *m = *mp = lz_method_find(method);
	if (!m)
		return lz_scene_fail(s, "method", "unknown method '%s'; the methods are: %s",
		                     method, names);
	return lz_method_bind(m, s);
}

/* An automatic seed is logged so that seed=N repeats the run. */
static void log_seeds(const lz_scene *s, const lz_method *m)
{
	for (size_t i = 0; i < m->keys.n; i++) {
		const char *key = m->keys.key[i].name;
		if (m->keys.key[i].type == LZ_KEY_SEED && strcmp(lz_scene_text(s, key), "auto") == 0)
			fprintf(stderr, "lz: %s = %lu (auto); pass %s=%lu to repeat this run\n", key,
			        lz_scene_seed(s, key), key, lz_scene_seed(s, key));
	}
}

/* Remove the partial directory, keeping the message of the failure itself (removing
 * may report errors of its own). */
static int run_fail(lz_guard *g, int rc)
{
	char msg[2048];
	if (lz_cli_code == LZ_OK)  /* a method that failed without saying why */
		lz_error(rc, "the run failed (%s)", lz_strerror(rc));
	snprintf(msg, sizeof msg, "%s", lz_error_message());
	lz_guard_hold(g);
	lz_rundir_abort(g->dir);
	lz_guard_release(g);
	return lz_error(rc, "%s", msg);
}

/* The run directory, or LZ_EINVAL: an --out that cannot be made is bad input, and
 * nothing is created. */
static int run_begin(lz_guard *g, const char *out)
{
	lz_guard_hold(g);
	int rc = lz_rundir_begin(g->dir, out);
	lz_guard_release(g);
	if (rc == LZ_OK || rc == LZ_EINVAL)
		return rc;
	char msg[2048];
	snprintf(msg, sizeof msg, "%s", lz_error_message());
	return lz_error(LZ_EINVAL, "cannot make the run directory '%s': %s (choose another "
	                "--out)", out, msg);
}

/* The parameters, the method's results and wall_s into summary.json, written as
 * summary.json.partial and renamed when complete: a summary.json is never cut short. */
static int run_method(const lz_scene *s, const lz_method *m, lz_rundir *d, int quiet)
{
	char part[4200], path[4200];
	int rc = lz_rundir_file(d, "summary.json.partial", part, sizeof part);
	if (rc == LZ_OK)
		rc = lz_rundir_file(d, "summary.json", path, sizeof path);
	lz_json *j = rc == LZ_OK ? lz_json_open(part) : NULL;
	if (!j)
		return rc != LZ_OK ? rc : lz_cli_code;
	lz_scene_json(s, j);
	lz_run run = {d, j, quiet};
	lz_cli_code = LZ_OK;
	double t0 = lz_wall_now();
	rc = m->run(s, &run);
	lz_json_num(j, "wall_s", lz_wall_now() - t0);
	int rc_json = lz_json_end(j);
	rc = rc != LZ_OK ? rc : rc_json;
	if (rc == LZ_OK && rename(part, path) != 0)
		rc = lz_error(LZ_EIO, "cannot rename '%s' to '%s'", part, path);
	return rc;
}

/* Run a bound scene into its directory; then, unless quiet, the directory on stderr
 * and the table of results on stdout. */
static int run_execute(const lz_scene *s, const lz_method *m, const char *out,
                       int quiet)
{
	lz_rundir d;
	lz_guard g;
	d.final[0] = d.tmp[0] = '\0';
	lz_guard_begin(&g, &d);
	int rc = run_begin(&g, out);
	if (rc == LZ_OK && (rc = run_method(s, m, &d, quiet)) == LZ_OK) {
		lz_guard_hold(&g);
		rc = lz_rundir_commit(&d);
		g.committed = rc == LZ_OK;
		lz_guard_release(&g);
	}
	if (rc != LZ_OK && d.tmp[0])
		rc = run_fail(&g, rc);
	lz_guard_end(&g);
	if (rc != LZ_OK || quiet)
		return rc;
	char path[4200];
	fprintf(stderr, "lz: results in %s/\n", d.final);
	fflush(stderr);
	snprintf(path, sizeof path, "%s/summary.json", d.final);
	return lz_run_table(stdout, m, lz_scene_name(s), path);
}

static int cmd_run(int argc, char **argv)
{
	lz_cli_args a = {0};
	a.overrides = malloc((size_t)(argc + 1) * sizeof *a.overrides);
	if (!a.overrides)
		return lz_error(LZ_ENOMEM, "no memory for the arguments");
	lz_scene *s = NULL;
	const lz_method *m = NULL;
	int rc = run_parse(argc, argv, &a);
	if (rc == LZ_OK)
		rc = run_load(&a, &s, &m);
	if (rc == LZ_OK) {
		char out[4096];
		snprintf(out, sizeof out, "build/runs/%s", lz_scene_name(s));
		if (!a.quiet)
			log_seeds(s, m);
		rc = run_execute(s, m, a.out ? a.out : out, a.quiet);
	}
	lz_scene_free(s);
	free(a.overrides);
	return rc;
}

/* ---- lz list ---- */

static int is_scene_file(const struct dirent *e)
{
	size_t n = strlen(e->d_name);
	return n > 6 && e->d_name[0] != '.' && strcmp(e->d_name + n - 6, ".scene") == 0;
}

/* The first '#' comment of a scene file, without the '#': its description. */
static void scene_description(const char *path, char *buf, size_t size)
{
	FILE *f = fopen(path, "r");
	buf[0] = '\0';
	char line[512];
	while (f && fgets(line, sizeof line, f)) {
		char *p = line + strspn(line, " \t");
		if (*p != '#')
			continue;
		p += strspn(p, "# \t");
		p[strcspn(p, "\r\n")] = '\0';
		snprintf(buf, size, "%s", p);
		break;
	}
	if (f)
		fclose(f);
}

static int cmd_list(void)
{
	const char *dir = lz_scene_dir();
	struct dirent **files;
	int n = scandir(dir, &files, is_scene_file, alphasort);
	if (n < 0)
		return lz_error(LZ_EIO, "cannot list the scenes in '%s' (set LZ_SCENES to the "
		                "scene directory)", dir);
	int width = 8;
	for (int i = 0; i < n; i++)
		if ((int)strlen(files[i]->d_name) - 6 > width)
			width = (int)strlen(files[i]->d_name) - 6;
	if (n == 0)
		printf("no scenes in %s\n", dir);
	for (int i = 0; i < n; i++) {
		char path[4096], about[512];
		snprintf(path, sizeof path, "%s/%s", dir, files[i]->d_name);
		lz_scene *s = lz_scene_read(path);
		if (s)
			scene_description(path, about, sizeof about);
		else
			snprintf(about, sizeof about, "(broken: %s)", lz_error_message());
		const char *method = s ? lz_scene_method(s) : NULL;
		printf("%-*.*s  %-12s  %s\n", width, (int)strlen(files[i]->d_name) - 6,
		       files[i]->d_name, method ? method : "?", about);
		lz_scene_free(s);
		free(files[i]);
	}
	free(files);
	return LZ_OK;
}

/* ---- lz help ---- */

/* Every line of `lz help` fits a terminal of HELP_WIDTH columns: long cells wrap. */
enum { HELP_WIDTH = 100, RANGE_MAX = 20, CELL = 512, LINES_MAX = 16 };

/* Columns of `lz help METHOD`, a Markdown table that also reads well in a terminal; a
 * key's long cells go on in the rows below it, whose other cells are empty. */
enum { COL_KEY, COL_TYPE, COL_DEFAULT, COL_RANGE, COL_HELP, NCOLS };
static const char *const lz_cli_help_heads[NCOLS] = {"key", "type", "default", "range",
                                                     "meaning"};

/* The first line of t, at most width characters, broken at a space when one fits (a
 * longer word is cut), into line (CELL bytes); the rest of t, or NULL when done. */
static const char *wrap_next(const char *t, int width, char *line)
{
	t += strspn(t, " ");
	const char *p = t, *space = NULL;
	for (int w = 0; *p && w < width; w++) {
		if (*p == ' ')
			space = p;
		for (p++; ((unsigned char)*p & 0xc0) == 0x80; p++)
			;
	}
	const char *end = !*p || *p == ' ' || !space ? p : space;
	size_t n = (size_t)(end - t) < CELL - 1 ? (size_t)(end - t) : CELL - 1;
	memcpy(line, t, n);
	while (n > 0 && line[n - 1] == ' ')
		n--;
	line[n] = '\0';
	end += strspn(end, " ");
	return *end ? end : NULL;
}

/* text after lead, wrapped to HELP_WIDTH; the lines after the first indented. */
static void print_wrapped(const char *lead, int indent, const char *text)
{
	char line[CELL];
	int width = HELP_WIDTH - lz_text_width(lead);
	printf("%s", lead);
	for (const char *t = text; t; width = HELP_WIDTH - indent) {
		t = wrap_next(t, width, line);
		printf("%s\n", line);
		if (t)
			printf("%*s", indent, "");
	}
}

/* The cells of one key's row (each CELL bytes). */
static void help_row(const lz_key *k, char cell[NCOLS][CELL])
{
	static const char *const types[] = {"int", "real", "enum", "seed", "bool", "text",
	                                    "path"};
	const char *unit = k->unit && *k->unit ? k->unit : NULL;
	snprintf(cell[COL_KEY], CELL, "%s", k->name);
	snprintf(cell[COL_TYPE], CELL, "%s", (unsigned)k->type < 7 ? types[k->type] : "?");
	snprintf(cell[COL_DEFAULT], CELL, "%s", !k->def ? "required" : *k->def ? k->def : "none");
	switch (k->type) {
	case LZ_KEY_INT:
	case LZ_KEY_REAL:
		snprintf(cell[COL_RANGE], CELL, "%c%g, %g%c%s%s", k->min_open ? '(' : '[', k->min,
		         k->max, k->max_open ? ')' : ']', unit ? " " : "", unit ? unit : "");
		break;
	case LZ_KEY_ENUM: {
		/* Markdown tables split cells at '|': list the choices with commas. */
		char *w = cell[COL_RANGE], *end = w + CELL - 6;
		for (const char *c = k->choices ? k->choices : ""; *c && w < end; c++) {
			if (*c == '|')
				*w++ = ',', *w++ = ' ';
			else
				*w++ = *c;
		}
		*w = '\0';
		break;
	}
	case LZ_KEY_SEED:
		snprintf(cell[COL_RANGE], CELL, "auto or [1, %lu]", LZ_SEED_MAX);
		break;
	case LZ_KEY_BOOL:
		snprintf(cell[COL_RANGE], CELL, "true, false");
		break;
	case LZ_KEY_PATH:
		snprintf(cell[COL_RANGE], CELL, "a file");
		break;
	default:
		snprintf(cell[COL_RANGE], CELL, "text");
		break;
	}
	snprintf(cell[COL_HELP], CELL, "%s", k->help ? k->help : "");
}

static void help_line(char cell[NCOLS][CELL], const int *width)
{
	for (int c = 0; c < NCOLS; c++)
		printf("| %s%*s ", cell[c], width[c] - lz_text_width(cell[c]), "");
	printf("|\n");
}

/* One key's row, its range and meaning wrapped into the rows below. */
static void help_key(char cell[NCOLS][CELL], const int *width)
{
	char line[NCOLS][CELL];
	const char *rest[NCOLS] = {NULL};
	for (int c = 0; c < NCOLS; c++)
		rest[c] = cell[c];
	for (int k = 0; k < LINES_MAX && (rest[COL_RANGE] || rest[COL_HELP]); k++) {
		for (int c = 0; c < NCOLS; c++) {
			line[c][0] = '\0';
			if (rest[c])
				rest[c] = wrap_next(rest[c], width[c], line[c]);
		}
		help_line(line, width);
	}
}

static void help_method(const lz_method *m)
{
	char (*rows)[NCOLS][CELL] = calloc(m->keys.n + 2, sizeof *rows);
	if (!rows) {
		lz_error(LZ_ENOMEM, "no memory for the key table");
		return;
	}
	int width[NCOLS] = {0}, used = 1;
	for (int c = 0; c < NCOLS; c++)
		snprintf(rows[0][c], CELL, "%s", lz_cli_help_heads[c]);
	for (size_t i = 0; i < m->keys.n; i++)
		help_row(&m->keys.key[i], rows[i + 2]);
	for (size_t i = 0; i < m->keys.n + 2; i++)
		for (int c = 0; c < COL_HELP; c++)
			if (lz_text_width(rows[i][c]) > width[c])
				width[c] = lz_text_width(rows[i][c]);
	if (width[COL_RANGE] > RANGE_MAX)
		width[COL_RANGE] = RANGE_MAX;
	for (int c = 0; c < COL_HELP; c++)
		used += width[c] + 3;
	width[COL_HELP] = HELP_WIDTH - used - 3;
	for (int c = 0; c < NCOLS; c++)
		memset(rows[1][c], '-', (size_t)width[c]);
	char lead[64];
	snprintf(lead, sizeof lead, "method %s: ", m->name);
	print_wrapped(lead, 2, m->help);
	printf("\nkey = value lines; `method = %s` picks this method.\n\n", m->name);
	help_line(rows[0], width);
	help_line(rows[1], width);
	for (size_t i = 2; i < m->keys.n + 2; i++)
		help_key(rows[i], width);
	free(rows);
}

/* What `lz help` says besides the usage: how a run reads its scene, where its output
 * goes, how it ends. Lines of at most HELP_WIDTH columns. */
static const char lz_cli_help_text[] =
	"\n"
	"lz run SCENE  SCENE is a scene file, or the name of one in the scene directory.\n"
	"  key=value   The command line wins over the scene: key=value replaces the scene's\n"
	"              value; key= (nothing after '=') unsets it, so that its default applies;\n"
	"              a key of a group of alternatives (steps or time, events or time, n or\n"
	"              packing) unsets the others the scene gives: `lz run S time=10` on a\n"
	"              scene with events = 100 runs for the time.\n"
	"              A relative file name in the scene (config = x.dat) is read from the\n"
	"              scene's directory; on the command line, from the current one.\n"
	"  --out DIR   the run directory (default build/runs/<scene name>). The run is written\n"
	"              into DIR.partial-<pid>, which replaces DIR only when the run succeeded;\n"
	"              a run that fails or is interrupted (Ctrl-C, SIGTERM, SIGHUP) removes it\n"
	"              and leaves DIR as it was. The summary is DIR/summary.json.\n"
	"  --quiet     no progress line, seed log, warning, \"results in\" line or table.\n"
	"  output      on stderr the progress, the seed of seed = auto, warnings and the line\n"
	"              `lz: results in DIR/`; then on stdout the table of results: the\n"
	"              headline observables of summary.json with their error bars (the error\n"
	"              to 2 significant digits, the value to the same place) and references,\n"
	"              the speed and the seed.\n"
	"  exit status 0 done; 1 the run failed (a physics guard, an I/O error); 2 bad input\n"
	"              (usage, scene file, key, value, an --out that cannot be made), with\n"
	"              nothing written; 128 + N when killed by signal N (130: Ctrl-C).\n";

static int cmd_help(int argc, char **argv)
{
	if (argc > 1)
		return print_usage("lz help takes at most one method");
	if (argc == 1) {
		const lz_method *m = lz_method_find(argv[0]);
		char names[512];
		method_names(names, sizeof names);
		if (!m)
			return lz_error(LZ_EINVAL, "unknown method '%s'; the methods are: %s", argv[0],
			                names);
		help_method(m);
		return LZ_OK;
	}
	size_t n;
	const lz_method *const *m = lz_methods(&n);
	fputs(lz_cli_usage_text, stdout);
	fputs(lz_cli_help_text, stdout);
	printf("\nmethods (`lz help METHOD` lists a method's keys):\n");
	for (size_t i = 0; i < n; i++) {
		char lead[64];
		snprintf(lead, sizeof lead, "  %-12s ", m[i]->name);
		print_wrapped(lead, 15, m[i]->help);
	}
	char where[4200];
	snprintf(where, sizeof where, "%s (`lz list`)", lz_scene_dir());
	printf("\n");
	print_wrapped("scenes are looked up in ", 2, where);
	return LZ_OK;
}

/* ---- main ---- */

static int dispatch(int argc, char **argv)
{
	if (argc < 2)
		return print_usage("say what to do");
	const char *cmd = argv[1];
	if (strcmp(cmd, "run") == 0)
		return cmd_run(argc - 2, argv + 2);
	if (strcmp(cmd, "list") == 0)
		return argc == 2 ? cmd_list() : print_usage("lz list takes no arguments");
	if (strcmp(cmd, "help") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0)
		return cmd_help(argc - 2, argv + 2);
	return print_usage("unknown command '%s'", cmd);
}

int lz_cli_main(int argc, char **argv)
{
	lz_error_handler *previous = lz_set_error_handler(record);
	lz_cli_code = LZ_OK;
	int rc = dispatch(argc, argv);
	lz_set_error_handler(previous);
	if (rc == LZ_OK)
		return 0;
	fprintf(stderr, "lz: %s\n", lz_error_message());
	if (rc == LZ_CLI_USAGE)
		fputs(lz_cli_usage_text, stderr);
	return rc == LZ_CLI_USAGE || rc == LZ_EINVAL || rc == LZ_ESYNTAX ? 2 : 1;
}
