/* lztest.h — how a lozenge test suite is written (Check, with points).
 *
 * A test file includes this header and defines tests with LZ_TEST(name) ... END_TEST.
 * Tests register themselves; the runner (tests/grade/runner.c) builds one Check
 * test case per rubric line, in fork mode, with the rubric's timeout, so a crash,
 * an abort (LZ_TODO) or an endless loop costs that test only.
 *
 * A graded stage's rubric (tests/NN-name/rubric or rubric-*, plus
 * tests/NN-name/hidden/rubric for tests the handout leaves out) is a whitespace
 * table, '#' comments:
 *
 *     # test                        points  visibility  timeout_s
 *     kahan_exact_on_cancellation   3       visible     5
 *
 * visibility is Gradescope's: visible | hidden | after_due_date | after_published.
 * The tests run, and the reports list them, in the rubrics' order: the lesson's. A
 * rubric lists its tests in the order of the lesson's assignment table; a stage's
 * rubric-X files come in the order its MANIFEST names X.c (rubrics_of in
 * lib/tools/common.sh, which `make test` and the grader ask). In a graded suite every LZ_TEST must be in a rubric and every rubric line must name
 * an LZ_TEST: the runner refuses to run otherwise.
 *
 * Failure messages speak physics: say what was measured, what was expected and the
 * likely cause ("energy grew by 3e-2 over 1e4 steps; velocity Verlet stays below
 * 1e-4 at dt = 0.01 — is the second half-kick using the new force?").
 *
 * Runner command line:  SUITE [--rubric FILE ...] [--only TEST[,TEST...]]
 *                       [--machine [--log FILE]]
 * Only the graded stages have rubrics. Without one (the library's own suite) every
 * registered test runs, worth no points, with a timeout of 120 s, and the student
 * view prints no score.
 * Each test runs in a process of its own (the runner's child, in which Check forks
 * the test's own process), so a crash, an endless loop, a flood of output or a
 * resource limit costs that test only, and the message says which it was.
 * Student view (default): a line per test, its points and its message, then
 * "Score: X/Y" and "N passed, M failed"; exit 0 only when every test passed.
 * --machine (the grader's view): the children's stdout and stderr go to FILE
 * (default /dev/null); the parent then prints, on its own stdout,
 *     LZBEGIN
 *     LZRESULT <tab> test <tab> pass|fail|error|timeout <tab> message (one line)
 *     ...
 *     LZEND <tab> ran <tab> N
 * The runner installs handlers that turn a GSL error and an LZ_TODO() into a test
 * failure with a message, and a quiet lz_error handler that records the last code
 * (lz_test_last_error; tests of bad input read the message with lz_error_message()).
 *
 * Helpers every suite shares are declared below (defined in runner.c); the library's
 * own suite adds tests/lib/support.h (files, scenes, a JSON reader).
 */
#ifndef LZTEST_H
#define LZTEST_H

#include <check.h>
#include <gsl/gsl_rng.h>

#include "lz/error.h"
#include "lz/reference.h"

void lz_test_register(const char *name, const TTest *test);

#define LZ_TEST(tname)                                                         \
	static const TTest *tname;                                             \
	static void tname##_register(void) __attribute__((constructor));       \
	static void tname##_register(void) { lz_test_register(#tname, tname); } \
	START_TEST(tname)

/* A check inside a loop: silent while it holds, fails the test with the message the
 * first time it does not. Check's ck_assert_* record every assertion that passes
 * (about 40 bytes, through a temporary file in fork mode), so a loop of a million of
 * them writes 40 MB and runs into the grader's file limit; LZ_REQUIRE writes nothing
 * until it fails. Use ck_assert_* for the few checks outside loops. */
#define LZ_REQUIRE(cond, ...)                          \
	do {                                           \
		if (!(cond))                           \
			ck_abort_msg(__VA_ARGS__);     \
	} while (0)

/* The same for a condition that speaks for itself: "Assertion 'cond' failed". */
#define LZ_REQUIRE_TRUE(cond) LZ_REQUIRE(cond, "Assertion '%s' failed", #cond)

/* Relative difference |a - b| / max(|b|, tiny), for messages and tolerances. */
double lz_test_reldiff(double a, double b);

/* A Mersenne Twister (GSL's mt19937) started from `seed`: every test draws its own
 * reproducible numbers. Free it with gsl_rng_free. */
gsl_rng *lz_test_rng(unsigned long seed);

/* The code of the last lz_error reported since the test began or since
 * lz_test_clear_error() (0: none). The runner's handler records it quietly; tests of
 * bad input read the message with lz_error_message(). */
int lz_test_last_error(void);
void lz_test_clear_error(void);

/* The literature value of datasets/reference/FILE (lz/reference.h) that the test
 * compares with; the test fails, saying which, when the table has no such row. */
lz_ref lz_test_reference(const char *file, const char *quantity, const char *dim,
                         const char *state);

/* Fail unless a call was refused: `failed` (e.g. got == NULL, or status != LZ_OK)
 * with the code LZ_EINVAL and a message that says `says` (and `also`, unless NULL).
 * `call` names the call in the failure message. */
void lz_test_refused(int failed, const char *call, const char *says, const char *also);

#endif
