/* test_scene.c — scene files: every way a scene can be wrong has a message that points
 * at the line, and nothing a file contains can crash the reader or sneak in a NaN.
 *
 * The scenes are bound to a test method with one key of every type, so these tests
 * do not change when a real engine changes its keys. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "method.h"
#include "scene.h"
#include "lztest.h"
#include "support.h"

static int test_check(const lz_scene *s);

static const lz_key test_keys[] = {
	{.name = "potential", .type = LZ_KEY_ENUM, .choices = "harmonic|lj",
	 .help = "force law"},
	{.name = "dt", .type = LZ_KEY_REAL, .def = "0.01", .min = 0, .max = 1, .min_open = 1,
	 .unit = "τ", .help = "time step"},
	{.name = "steps", .type = LZ_KEY_INT, .def = "1000", .min = 1, .max = 1e9,
	 .help = "number of steps"},
	{.name = "dim", .type = LZ_KEY_INT, .def = "2", .min = 2, .max = 3,
	 .help = "dimension"},
	{.name = "packing", .type = LZ_KEY_REAL, .def = "0.5", .min = 0, .max = 0.9069,
	 .min_open = 1, .max_open = 1, .help = "packing fraction"},
	{.name = "omega", .type = LZ_KEY_REAL, .def = "1", .min = 0, .max = INFINITY,
	 .min_open = 1, .max_open = 1, .unit = "1/τ", .help = "angular frequency"},
	{.name = "seed", .type = LZ_KEY_SEED, .def = "auto", .help = "random seed"},
	{.name = "verbose", .type = LZ_KEY_BOOL, .def = "false", .help = "chatter"},
	{.name = "label", .type = LZ_KEY_TEXT, .def = "", .help = "a name for the plots"},
};

static const lz_method test_method = {
	LZ_METHOD_KEYS("test", test_keys),
	.help = "a method with a key of every type",
	.check = test_check,
};

/* Close packing is 0.9069 in 2D (the table's bound) but 0.7405 in 3D. */
static int test_check(const lz_scene *s)
{
	if (lz_scene_int(s, "dim") == 3 && lz_scene_real(s, "packing") >= 0.7405)
		return lz_scene_fail(s, "packing", "key 'packing' = %s is out of range (0, 0.7405) "
		                     "for dim=3", lz_scene_text(s, "packing"));
	return LZ_OK;
}

static const char *scene_dir;

/* Write n bytes as a scene file, return its path. */
static const char *scene_file(const char *content, size_t n)
{
	if (!scene_dir)
		scene_dir = lzt_tmpdir();
	const char *path = lzt_path(scene_dir, "t.scene");
	lzt_write(path, content, n);
	return path;
}

/* Read and bind; LZ_OK or the error code (from the return or the recorded one). */
static int read_and_bind(const char *path, lz_scene **out)
{
	lz_test_clear_error();
	lz_scene *s = lz_scene_read(path);
	int rc = s ? lz_method_bind(&test_method, s) : lz_test_last_error();
	if (out && rc == LZ_OK)
		*out = s;
	else
		lz_scene_free(s);
	return rc;
}

/* The scene (n bytes) must be refused with `code` and the message path + suffix
 * (exact), or, when suffix starts with '~', a message containing the rest. */
static void rejects_n(const char *content, size_t n, int code, const char *suffix)
{
	const char *path = scene_file(content, n);
	int rc = read_and_bind(path, NULL);
	const char *msg = lz_error_message();
	ck_assert_msg(rc == code, "the scene\n%.200s\nwas %s (code %d, expected %d): %s", content,
	              rc ? "refused with the wrong code" : "accepted", rc, code, msg);
	if (suffix[0] == '~') {
		ck_assert_msg(strncmp(msg, path, strlen(path)) == 0 && strstr(msg, suffix + 1),
		              "message '%s' should start with the file name and contain '%s'", msg,
		              suffix + 1);
	} else {
		char want[1024];
		snprintf(want, sizeof want, "%s%s", path, suffix);
		ck_assert_msg(strcmp(msg, want) == 0, "message is\n  %s\nexpected\n  %s", msg, want);
	}
	ck_assert_msg(!strchr(msg, '\n'), "the message should be one line: '%s'", msg);
}

static const char *scene_str(const char *content)
{
	return scene_file(content, strlen(content));
}

static void rejects(const char *content, int code, const char *suffix)
{
	rejects_n(content, strlen(content), code, suffix);
}

#define GOOD "method = test\npotential = harmonic\n"

LZ_TEST(scene_missing_file)
{
	lz_test_clear_error();
	ck_assert_msg(lz_scene_read("/nonexistent/water.scene") == NULL,
	              "a missing scene file was 'read'");
	ck_assert_msg(lz_test_last_error() == LZ_EINVAL, "a missing file is bad input (LZ_EINVAL), "
	              "got code %d", lz_test_last_error());
	ck_assert_msg(strstr(lz_error_message(), "/nonexistent/water.scene") &&
	              strstr(lz_error_message(), "No such file"),
	              "the message should name the file and the reason: '%s'", lz_error_message());
	ck_assert_msg(lz_scene_read("/tmp") == NULL && lz_test_last_error() == LZ_EINVAL,
	              "a directory was read as a scene");
}
END_TEST

LZ_TEST(scene_empty_file)
{
	rejects("", LZ_ESYNTAX, ": empty scene: no keys");
}
END_TEST

LZ_TEST(scene_only_comments)
{
	rejects("# a scene with nothing in it\n\n   # still nothing\n\t\n", LZ_ESYNTAX,
	        ": empty scene: no keys");
}
END_TEST

LZ_TEST(scene_nul_byte)
{
	rejects_n(GOOD "dt = 0.1\0\n", sizeof GOOD "dt = 0.1\0\n" - 1, LZ_ESYNTAX,
	          ":3: not a text line (binary data?)");
}
END_TEST

LZ_TEST(scene_control_characters)
{
	rejects(GOOD "label = \x1b[31mred\n", LZ_ESYNTAX, ":3: not a text line (binary data?)");
	rejects("method = test\x7f\n", LZ_ESYNTAX, ":1: not a text line (binary data?)");
	rejects("method = test\rpotential = lj\n", LZ_ESYNTAX,
	        ":1: not a text line (binary data?)");
}
END_TEST

LZ_TEST(scene_invalid_utf8)
{
	const char *bad[] = {"label = caf\xe9\n",          /* Latin-1 */
	                     "label = \xc0\xaf\n",          /* overlong '/' */
	                     "label = \xed\xa0\x80\n",      /* a UTF-16 surrogate */
	                     "label = \xf4\x90\x80\x80\n",  /* past U+10FFFF */
	                     "label = \xe2\x82\n",          /* truncated sequence */
	                     "label = \x80\n"};             /* lone continuation byte */
	char scene[128];
	for (int i = 0; i < 6; i++) {
		snprintf(scene, sizeof scene, GOOD "%s", bad[i]);
		rejects(scene, LZ_ESYNTAX, ":3: not a text line (binary data?)");
	}
	lz_scene *s = NULL;
	ck_assert_msg(read_and_bind(scene_str(GOOD "label = σ-€-𝄞\n"), &s)
	              == LZ_OK, "valid UTF-8 was refused: %s", lz_error_message());
	ck_assert_msg(strcmp(lz_scene_text(s, "label"), "σ-€-𝄞") == 0, "UTF-8 label changed");
	lz_scene_free(s);
}
END_TEST

LZ_TEST(scene_line_too_long)
{
	char *text = malloc(8192);
	ck_assert(text != NULL);
	/* 4096 bytes exactly is allowed, 4097 is not. */
	int head = snprintf(text, 8192, GOOD "label = ");
	memset(text + head, 'x', 4096 - 8);
	strcpy(text + head + 4096 - 8, "\n");
	lz_scene *s = NULL;
	ck_assert_msg(read_and_bind(scene_file(text, strlen(text)), &s) == LZ_OK,
	              "a line of exactly 4096 bytes was refused: %s", lz_error_message());
	lz_scene_free(s);
	strcpy(text + head + 4096 - 8, "x\n");
	rejects(text, LZ_ESYNTAX, ":3: line longer than 4096 bytes");
	free(text);
}
END_TEST

LZ_TEST(scene_file_too_large)
{
	size_t n = (1 << 20) + 1;
	char *text = malloc(n);
	ck_assert(text != NULL);
	memcpy(text, GOOD, strlen(GOOD));
	for (size_t i = strlen(GOOD); i < n; i += 64) {
		size_t len = n - i < 64 ? n - i : 64;
		memset(text + i, ' ', len);
		text[i] = '#';
		text[i + len - 1] = '\n';
	}
	rejects_n(text, n, LZ_ESYNTAX, ": larger than 1 MiB: not a scene file");
	free(text);
}
END_TEST

LZ_TEST(scene_line_without_equals)
{
	rejects(GOOD "dt 0.1\n", LZ_ESYNTAX, ":3: expected 'key = value', found 'dt 0.1'");
}
END_TEST

LZ_TEST(scene_empty_key)
{
	rejects(GOOD "  = 0.1\n", LZ_ESYNTAX, ":3: no key before '='");
}
END_TEST

LZ_TEST(scene_key_not_a_word)
{
	rejects(GOOD "Dt = 0.1\n", LZ_ESYNTAX, ":3: key 'Dt' must be one word of a-z, 0-9 and _");
	rejects(GOOD "time step = 1\n", LZ_ESYNTAX,
	        ":3: key 'time step' must be one word of a-z, 0-9 and _");
	rejects(GOOD "d-t = 1\n", LZ_ESYNTAX, ":3: key 'd-t' must be one word of a-z, 0-9 and _");
}
END_TEST

LZ_TEST(scene_empty_value)
{
	rejects(GOOD "dt =    # forgot it\n", LZ_ESYNTAX, ":3: key 'dt' has no value");
}
END_TEST

LZ_TEST(scene_duplicate_key)
{
	rejects(GOOD "# the time step\ndt = 0.1\n\n\n\n\ndt = 0.2\n", LZ_ESYNTAX,
	        ":9: key 'dt' given twice (first at line 4)");
}
END_TEST

LZ_TEST(scene_too_many_keys)
{
	size_t cap = 1100 * 16, len = 0;
	char *text = malloc(cap);
	ck_assert(text != NULL);
	for (int i = 0; i < 1100; i++)
		len += (size_t)snprintf(text + len, cap - len, "k%d = 1\n", i);
	rejects(text, LZ_ESYNTAX, ":1025: more than 1024 keys: not a scene");
	free(text);
}
END_TEST

LZ_TEST(scene_unknown_key)
{
	rejects(GOOD "dtt = 0.1\n", LZ_EINVAL, "~:3: unknown key 'dtt' for method test "
	        "(did you mean 'dt'?); its keys are: potential, dt, steps, dim, packing, omega, "
	        "seed, verbose, label");
	rejects(GOOD "zzzzzzzzz = 1\n", LZ_EINVAL, "~:3: unknown key 'zzzzzzzzz' for method "
	        "test; its keys are: potential");
}
END_TEST

LZ_TEST(scene_missing_required_key)
{
	rejects("method = test\ndt = 0.1\n", LZ_EINVAL, "~: missing key 'potential'");
}
END_TEST

LZ_TEST(scene_wrong_type)
{
	rejects(GOOD "steps = 1.5\n", LZ_EINVAL, ":3: key 'steps' = 1.5 must be an integer");
	rejects(GOOD "steps = ten\n", LZ_EINVAL, ":3: key 'steps' = ten must be an integer");
	rejects(GOOD "dt = fast\n", LZ_EINVAL, ":3: key 'dt' = fast must be a number");
	rejects(GOOD "dt = 0.1x\n", LZ_EINVAL, ":3: key 'dt' = 0.1x must be a number");
	rejects(GOOD "verbose = maybe\n", LZ_EINVAL,
	        ":3: key 'verbose' = maybe must be true or false (or yes/no, 1/0)");
}
END_TEST

LZ_TEST(scene_non_finite_number)
{
	const char *bad[] = {"nan", "NaN", "inf", "-inf", "infinity", "1e999", "-1e999"};
	char scene[128], suffix[128];
	for (int i = 0; i < 7; i++) {
		snprintf(scene, sizeof scene, GOOD "dt = %s\n", bad[i]);
		snprintf(suffix, sizeof suffix, ":3: key 'dt' = %s must be a finite number", bad[i]);
		rejects(scene, LZ_EINVAL, suffix);
	}
	rejects(GOOD "steps = 1e999\n", LZ_EINVAL, ":3: key 'steps' = 1e999 must be an integer");
}
END_TEST

LZ_TEST(scene_out_of_range)
{
	rejects(GOOD "packing = 0.95\n", LZ_EINVAL,
	        ":3: key 'packing' = 0.95 is out of range (0, 0.9069)");
	rejects(GOOD "dt = 0\n", LZ_EINVAL, ":3: key 'dt' = 0 is out of range (0, 1]");
	rejects(GOOD "dt = 1.0000001\n", LZ_EINVAL, ":3: key 'dt' = 1.0000001 is out of range (0, 1]");
	rejects(GOOD "steps = 0\n", LZ_EINVAL, ":3: key 'steps' = 0 is out of range [1, 1e+09]");
	rejects(GOOD "steps = 99999999999999999999\n", LZ_EINVAL,
	        ":3: key 'steps' = 99999999999999999999 is out of range [1, 1e+09]");
	rejects(GOOD "omega = -1\n", LZ_EINVAL, ":3: key 'omega' = -1 is out of range (0, inf)");
	rejects(GOOD "seed = 0\n", LZ_EINVAL, ":3: key 'seed' = 0 is out of range [1, 4294967295]");
	rejects(GOOD "seed = 4294967296\n", LZ_EINVAL,
	        ":3: key 'seed' = 4294967296 is out of range [1, 4294967295]");
	rejects(GOOD "seed = lucky\n", LZ_EINVAL,
	        ":3: key 'seed' = lucky must be 'auto' or an integer");
	lz_scene *s = NULL;
	ck_assert_msg(read_and_bind(scene_str(GOOD "dt = 1\nsteps = 1e9\n"), &s)
	              == LZ_OK, "values on a closed bound were refused: %s", lz_error_message());
	ck_assert_msg(lz_scene_int(s, "steps") == 1000000000, "steps = 1e9 read as %lld",
	              lz_scene_int(s, "steps"));
	lz_scene_free(s);
}
END_TEST

LZ_TEST(scene_bad_enum)
{
	rejects("method = test\npotential = coulomb\n", LZ_EINVAL,
	        ":2: key 'potential' = coulomb must be one of harmonic|lj");
	rejects("method = test\npotential = harm\n", LZ_EINVAL,
	        ":2: key 'potential' = harm must be one of harmonic|lj");
}
END_TEST

LZ_TEST(scene_cross_key_check)
{
	rejects(GOOD "dim = 3\npacking = 0.8\n", LZ_EINVAL,
	        ":4: key 'packing' = 0.8 is out of range (0, 0.7405) for dim=3");
}
END_TEST

LZ_TEST(scene_method_mismatch)
{
	rejects("method = verlet\npotential = lj\n", LZ_EINVAL,
	        ":1: method = verlet, but the scene is bound to method test");
}
END_TEST

LZ_TEST(scene_good_values)
{
	const char text[] = "\xef\xbb\xbf# a BOM, CRLF line ends, comments after values\r\n"
	                    "method=test\r\n"
	                    "  potential   =\tlj   # Lennard-Jones\r\n"
	                    "steps = 2e3\n"
	                    "dt = 0.005\n"
	                    "seed = 99\n"
	                    "verbose = yes\n"
	                    "label = run 1 = first";
	lz_scene *s = NULL;
	const char *path = scene_file(text, sizeof text - 1);
	ck_assert_msg(read_and_bind(path, &s) == LZ_OK, "a good scene was refused: %s",
	              lz_error_message());
	ck_assert_msg(strcmp(lz_scene_name(s), "t") == 0, "scene name is '%s', expected 't' "
	              "(the file name without .scene)", lz_scene_name(s));
	ck_assert_msg(strcmp(lz_scene_method(s), "test") == 0, "method is '%s'", lz_scene_method(s));
	ck_assert_msg(lz_scene_enum(s, "potential") == 1, "potential = lj should be choice 1, got %d",
	              lz_scene_enum(s, "potential"));
	ck_assert_msg(lz_scene_int(s, "steps") == 2000, "steps = 2e3 read as %lld",
	              lz_scene_int(s, "steps"));
	ck_assert_msg(lz_scene_real(s, "dt") == 0.005, "dt read as %g", lz_scene_real(s, "dt"));
	ck_assert_msg(lz_scene_real(s, "steps") == 2000, "an integer key read as real is %g",
	              lz_scene_real(s, "steps"));
	ck_assert_msg(lz_scene_seed(s, "seed") == 99, "seed read as %lu", lz_scene_seed(s, "seed"));
	ck_assert_msg(lz_scene_bool(s, "verbose") == 1, "verbose = yes should be true");
	ck_assert_msg(strcmp(lz_scene_text(s, "label"), "run 1 = first") == 0,
	              "label is '%s' (the value is everything after the first '=')",
	              lz_scene_text(s, "label"));
	ck_assert_msg(lz_scene_real(s, "packing") == 0.5 && lz_scene_int(s, "dim") == 2,
	              "defaults not filled in");
	ck_assert_msg(lz_scene_given(s, "dt") && !lz_scene_given(s, "packing"),
	              "lz_scene_given is wrong");
	ck_assert_msg(lz_scene_has(s, "packing") && lz_scene_has(s, "label"), "lz_scene_has wrong");
	lz_scene_free(s);
	s = NULL;
	ck_assert(read_and_bind(scene_str(GOOD), &s) == LZ_OK);
	ck_assert_msg(!lz_scene_has(s, "label") && strcmp(lz_scene_text(s, "label"), "") == 0,
	              "an optional key without default should have no value");
	lz_scene_free(s);
}
END_TEST

LZ_TEST(scene_undeclared_key_is_reported)
{
	lz_scene *s = NULL;
	ck_assert(read_and_bind(scene_str(GOOD), &s) == LZ_OK);
	lz_test_clear_error();
	ck_assert_msg(lz_scene_real(s, "temperature") == 0 && lz_test_last_error() == LZ_EINVAL,
	              "asking for an undeclared key should give 0 and LZ_EINVAL");
	ck_assert_msg(strstr(lz_error_message(), "'temperature'") != NULL, "message: '%s'",
	              lz_error_message());
	lz_test_clear_error();
	ck_assert_msg(lz_scene_bool(s, "dt") == 0 && lz_test_last_error() == LZ_EINVAL,
	              "asking for a real key as a bool should be reported");
	lz_scene_free(s);
}
END_TEST

LZ_TEST(scene_overrides)
{
	lz_scene *s = NULL;
	ck_assert(read_and_bind(scene_str(GOOD "dt = 0.1\n"), &s) == LZ_OK);
	ck_assert(lz_scene_set(s, "dt=0.5", NULL) == LZ_OK);
	ck_assert(lz_scene_set(s, "steps = 7", "command line") == LZ_OK);
	ck_assert_msg(lz_method_bind(&test_method, s) == LZ_OK, "rebinding failed: %s",
	              lz_error_message());
	ck_assert_msg(lz_scene_real(s, "dt") == 0.5 && lz_scene_int(s, "steps") == 7,
	              "overrides not applied: dt %g, steps %lld", lz_scene_real(s, "dt"),
	              lz_scene_int(s, "steps"));
	lz_scene_fail(s, "dt", "too big");
	ck_assert_msg(strcmp(lz_error_message(), "command line: too big") == 0,
	              "an error about an overridden key should point at the command line: '%s'",
	              lz_error_message());
	ck_assert(lz_scene_set(s, "dt=nan", NULL) == LZ_OK);
	ck_assert(lz_method_bind(&test_method, s) == LZ_EINVAL);
	ck_assert_msg(strcmp(lz_error_message(), "command line: key 'dt' = nan must be a finite "
	                     "number") == 0, "message: '%s'", lz_error_message());
	ck_assert_msg(lz_scene_set(s, "dt", NULL) == LZ_ESYNTAX &&
	              strcmp(lz_error_message(), "command line: expected 'key = value', found 'dt'")
	              == 0, "an override without '=': '%s'", lz_error_message());
	ck_assert_msg(lz_scene_set(s, "", NULL) == LZ_ESYNTAX, "an empty override was accepted");
	ck_assert_msg(lz_scene_set(s, "label=\x01", NULL) == LZ_ESYNTAX,
	              "a control character in an override was accepted");
	lz_scene_free(s);
}
END_TEST

LZ_TEST(scene_seed_auto)
{
	lz_scene *s = NULL;
	ck_assert(read_and_bind(scene_str(GOOD), &s) == LZ_OK);
	unsigned long a = lz_scene_seed(s, "seed");
	ck_assert_msg(strcmp(lz_scene_text(s, "seed"), "auto") == 0, "seed text is '%s'",
	              lz_scene_text(s, "seed"));
	ck_assert_msg(a >= 1 && a <= 4294967295UL, "auto seed %lu out of range", a);
	ck_assert(lz_method_bind(&test_method, s) == LZ_OK);
	ck_assert_msg(lz_scene_seed(s, "seed") != a, "two binds drew the same auto seed %lu", a);
	lz_scene_free(s);
}
END_TEST

LZ_TEST(scene_json_lists_every_key)
{
	lz_scene *s = NULL;
	ck_assert(read_and_bind(scene_str(GOOD "seed = 5\ndt = 0.1\n"), &s)
	          == LZ_OK);
	char *buf = NULL, err[128];
	size_t n = 0;
	FILE *f = open_memstream(&buf, &n);
	lz_json *j = lz_json_begin(f);
	lz_scene_json(s, j);
	ck_assert(lz_json_end(j) == LZ_OK);
	fclose(f);
	lzt_json *p = lzt_json_parse(buf, err, sizeof err);
	ck_assert_msg(p != NULL, "lz_scene_json wrote invalid JSON (%s):\n%s", err, buf);
	const char *order[] = {"method", "potential", "dt", "steps", "dim", "packing", "omega",
	                       "seed", "verbose", "label"};
	ck_assert_msg(p->n == 10, "expected method + 9 keys, got %d members:\n%s", p->n, buf);
	for (int i = 0; i < 10; i++)
		ck_assert_msg(strcmp(p->m[i].key, order[i]) == 0, "member %d is '%s', expected '%s' "
		              "(method first, then the table order)", i, p->m[i].key, order[i]);
	ck_assert_msg(p->m[0].kind == LZT_STR && strcmp(p->m[0].text, "test") == 0, "method");
	ck_assert_msg(p->m[1].kind == LZT_STR && strcmp(p->m[1].text, "harmonic") == 0, "enum");
	ck_assert_msg(p->m[2].kind == LZT_NUM && p->m[2].num == 0.1, "dt is %s", p->m[2].text);
	ck_assert_msg(strcmp(p->m[3].text, "1000") == 0, "steps is %s", p->m[3].text);
	ck_assert_msg(strcmp(p->m[7].text, "5") == 0, "seed is %s", p->m[7].text);
	ck_assert_msg(p->m[8].kind == LZT_FALSE, "verbose should be false");
	ck_assert_msg(p->m[9].kind == LZT_NULL, "an unset optional key should be null");
	free(p);
	free(buf);
	lz_scene_free(s);
}
END_TEST

/* Bytes that make interesting scenes: syntax characters, digits, control bytes,
 * UTF-8 lead and continuation bytes. */
static char fuzz_byte(gsl_rng *r)
{
	static const char pick[] = "=#\n \tmethodtspe._0123456789-+enaif";
	if (gsl_rng_uniform(r) < 0.7)
		return pick[gsl_rng_uniform_int(r, sizeof pick - 1)];
	return (char)gsl_rng_uniform_int(r, 256);
}

static void mutate(gsl_rng *r, char *text, size_t *n, size_t cap)
{
	for (int k = 1 + (int)gsl_rng_uniform_int(r, 4); k > 0; k--) {
		size_t at = *n ? gsl_rng_uniform_int(r, *n) : 0;
		switch (gsl_rng_uniform_int(r, 4)) {
		case 0:  /* replace a byte */
			if (*n)
				text[at] = fuzz_byte(r);
			break;
		case 1:  /* insert a byte */
			if (*n + 1 < cap) {
				memmove(text + at + 1, text + at, *n - at);
				text[at] = fuzz_byte(r);
				(*n)++;
			}
			break;
		case 2:  /* delete a byte */
			if (*n) {
				memmove(text + at, text + at + 1, *n - at - 1);
				(*n)--;
			}
			break;
		default:  /* truncate, as a half-written file would be */
			*n = at;
		}
	}
}

/* Whatever the bytes, the reader returns a scene or an error with a message; an
 * accepted scene never carries a NaN or an out-of-range value. */
static void fuzz_one(const char *text, size_t n)
{
	lz_scene *s = NULL;
	int rc = read_and_bind(scene_file(text, n), &s);
	const char *msg = lz_error_message();
	/* Plain ifs: Check writes to a pipe for every passing ck_assert. */
	if (rc != LZ_OK) {
		if (rc < 0 || msg[0] == '\0' || strchr(msg, '\n'))
			ck_abort_msg("a refused scene gave code %d and message '%s' (it should be one "
			             "non-empty line)", rc, msg);
		return;
	}
	for (size_t i = 0; i < test_method.keys.n; i++) {
		const lz_key *k = &test_keys[i];
		if (k->type != LZ_KEY_REAL && k->type != LZ_KEY_INT)
			continue;
		double v = lz_scene_real(s, k->name);
		int in = (k->min_open ? v > k->min : v >= k->min) &&
		         (k->max_open ? v < k->max : v <= k->max);
		if (!isfinite(v) || !in)
			ck_abort_msg("accepted %s = %g, outside its range or not finite", k->name, v);
	}
	lz_scene_free(s);
}

LZ_TEST(scene_fuzz)
{
	static const char valid[] = "# fuzz seed scene\nmethod = test\npotential = harmonic\n"
	                            "dt = 0.01\nsteps = 100\npacking = 0.3\nomega = 2.5\n"
	                            "seed = 7\nverbose = no\nlabel = hello σ\n";
	enum { CAP = 512 };
	char text[CAP];
	gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(r, 20240601);
	for (int i = 0; i < 300; i++) {
		size_t n = gsl_rng_uniform_int(r, 200);
		for (size_t k = 0; k < n; k++)
			text[k] = fuzz_byte(r);
		fuzz_one(text, n);
	}
	for (int i = 0; i < 300; i++) {
		size_t n = sizeof valid - 1;
		memcpy(text, valid, n);
		mutate(r, text, &n, CAP);
		fuzz_one(text, n);
	}
	gsl_rng_free(r);
	ck_assert(lz_rmtree(scene_dir) == LZ_OK);
}
END_TEST
