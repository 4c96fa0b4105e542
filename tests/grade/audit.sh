#!/usr/bin/env bash
# audit.sh — the stub audit of `make check`.
#
#   audit.sh BUILD ["STAGES"]
#
# Built in BUILD/audit with IMPL=assignments (the committed stubs), every stage's
# test binary runs in machine mode: every graded test must fail (a test that passes
# on a stub cannot fail, and is a defect), none may time out, the runner must finish
# within the rubric's budget, the rubric and the suite must agree (the runner refuses
# otherwise: its message is shown) and lz-report must grade the stage 0. Built with
# IMPL=solutions, every test must pass and the grade must be 100%. Both run under the
# grader's file limit, so a test that floods Check's channel fails here first. The
# tests must come in the lesson's order (audit_order).
# Prints `audit: N passed, M failed` (one count per test and per stage-wide check)
# and exits non-zero on any failure.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"
cd "$ROOT"
need_args $# 1 2 "audit.sh BUILD [\"STAGES\"]"
BUILD=$1
AUDIT=$BUILD/audit
STAGES=${2:-$(for d in assignments/[0-9][0-9]-*/; do [ -d "$d" ] && basename "$d"; done | tr "\n" " ")}
REPORT=$AUDIT/bin/lz-report
MULT=${CK_TIMEOUT_MULTIPLIER:-1}
ULIMIT_F=$((20 * 1024))  # KiB: the grader's file limit, under which every run happens
passed=0
failed=0
make_tmp

ok() { passed=$((passed + 1)); }
defect() {
	failed=$((failed + 1))
	echo "  DEFECT  $*"
}

rubric_args() {  # rubric_args STAGE: the Makefile's rubric files, as --rubric options
	local r
	for r in $(rubrics_of "$1"); do
		printf -- '--rubric\n%s\n' "$r"
	done
}

rubric_tests() {  # rubric_tests STAGE: the test names its rubrics list
	local r
	for r in $(rubrics_of "$1"); do
		awk '{ sub(/#.*/, "") } NF { print $1 }' "$r"
	done
}

budget_of() {  # budget_of STAGE: seconds, the rubric timeouts summed plus slack
	awk -v s="$(rubric_seconds "$1")" -v m="$MULT" 'BEGIN { printf "%d", s * m + 30 }'
}

# Build every stage's tests and the report writer with one implementation for all.
build() {  # build solutions|assignments
	local vars=("BUILD=$AUDIT" "IMPL=$1") targets=("$REPORT") st
	for st in $STAGES; do
		vars+=("IMPL_${st%%-*}=$1")
		targets+=("$AUDIT/tests/$st")
	done
	echo "audit: building the tests against $1/"
	if ! make --no-print-directory "${vars[@]}" "${targets[@]}" >"$tmp/build.log" 2>&1; then
		sed -E '/^  (CC|LD|AR) /d' "$tmp/build.log" | head -n 40
		defect "the tests do not build against $1/"
		return 1
	fi
}

# Run one stage; leaves its stdout in $tmp/out, stderr in $tmp/err, and checks that
# it finished, reported, and ran every rubric test. Returns 1 when it did not report.
run() {  # run STAGE IMPL
	local st=$1 impl=$2 budget status=0 ran want
	budget=$(budget_of "$st")
	mapfile -t args < <(rubric_args "$st")
	(
		ulimit -f "$ULIMIT_F"
		exec env CK_FORK=yes timeout -k 5 "$budget" "$AUDIT/tests/$st" "${args[@]}" --machine \
			--log "$AUDIT/$st-$impl.log"
	) >"$tmp/out" 2>"$tmp/err" </dev/null || status=$?
	if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
		defect "$st ($impl): the test program did not finish within $budget s"
		return 1
	fi
	if ! grep -q '^LZEND' "$tmp/out"; then
		defect "$st ($impl): the runner did not report (exit status $status):"
		sed 's/^/            /' "$tmp/err" | head -n 20
		return 1
	fi
	ran=$(awk -F'\t' '$1 == "LZEND" { print $3 }' "$tmp/out")
	want=$(rubric_tests "$st" | wc -l)
	if [ "$ran" -ne "$want" ]; then
		defect "$st ($impl): $ran tests ran, the rubric lists $want"
		return 1
	fi
	ok
}

# lz-report's grade of the last run: prints "GOT MAX".
grade() {  # grade STAGE
	{
		echo "stage $1"
		rubrics_of "$1" | sed 's/^/rubric /'
		echo "build ok"
		echo "results $tmp/out"
		echo "exit 0"
	} >"$tmp/spec"
	"$REPORT" --quiet --out "$tmp/report" --spec "$tmp/spec"
	score_of "$tmp/report/report.txt" | tr / ' '
}

# The tests come in the lesson's order: every rubric-X belongs to a file X.c that the
# MANIFEST names (rubrics_of orders the rubrics by it), and the runner reports the
# tests in the rubrics' order (the last run's output).
audit_order() {  # audit_order STAGE
	local st=$1 r x
	for r in tests/"$st"/rubric-*; do
		[ -f "$r" ] || continue
		x=${r##*/rubric-}
		if manifest_of "$st" | grep -q "/$x\.c\$"; then
			ok
		else
			defect "$r: tests/$st/MANIFEST names no $x.c, so its tests have no place in the lesson's order"
		fi
	done
	if [ "$(grep '^LZRESULT' "$tmp/out" | cut -f2)" = "$(rubric_tests "$st")" ]; then
		ok
	else
		defect "$st: the runner did not report the tests in the rubrics' order"
	fi
}

audit_stubs() {  # audit_stubs STAGE
	local st=$1 name word msg got max
	echo "audit: $st against the stubs"
	run "$st" assignments || return 0
	audit_order "$st"
	while IFS=$'\t' read -r _ name word msg; do
		case $word in
		pass) defect "test $name passes on the stub: it cannot fail" ;;
		timeout) defect "test $name timed out on the stub (a stub stops at once: the test itself hangs)" ;;
		*) ok ;;
		esac
	done < <(grep '^LZRESULT' "$tmp/out")
	got='?' max='?'
	read -r got max < <(grade "$st") || true
	if [ "$got" = 0 ] && [ "$max" != 0 ]; then
		ok
	else
		defect "$st: the stubs grade $got/$max; they must grade 0 (of more than 0)"
	fi
}

audit_reference() {  # audit_reference STAGE
	local st=$1 name word msg got max
	echo "audit: $st against the reference solutions"
	run "$st" solutions || return 0
	while IFS=$'\t' read -r _ name word msg; do
		if [ "$word" = pass ]; then
			ok
		else
			defect "test $name fails on the reference ($word): $msg"
		fi
	done < <(grep '^LZRESULT' "$tmp/out")
	got='?' max='?'
	read -r got max < <(grade "$st") || true
	if [ "$got" = "$max" ] && [ "$max" != 0 ]; then
		ok
	else
		defect "$st: the reference grades $got/$max; it must grade 100%"
	fi
}

t0=$SECONDS
if build assignments; then
	for st in $STAGES; do
		audit_stubs "$st"
	done
fi
if [ -d solutions ]; then
	if build solutions; then
		for st in $STAGES; do
			audit_reference "$st"
		done
	fi
else
	echo "audit: no solutions/ here (a student tree): the reference is not audited"
fi
echo "audit: $((SECONDS - t0)) s"
echo "audit: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
