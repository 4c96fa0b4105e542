#!/usr/bin/env bash
# make check — the test command: every suite against the reference must pass 100 %
# (and the demo page's number format, tests/lib/check_numfmt.sh),
# the committed assignments must be current, the stub audit and the grader
# fixtures must pass, a realistic bug in every graded function must fail the tests
# that call it (one mutant each, and every other one must still apply; `make mutants`
# runs them all), `make lesson` must report a failing driver and the plots it breaks
# (tests/tools/lesson.sh), the handout must work along the student's path (make
# test, make submit, make grade), and lz-mpi must equal the serial run on 1 to 4
# processes (skipped without MPI).
# Usage: check.sh BUILD "STAGES"
set -uo pipefail
build=$1
stages=$2
if [ ! -d solutions ]; then
	echo "make check runs the reference solutions, which the student handout leaves out;" >&2
	echo "students run 'make test STAGE=NN' and 'make grade'." >&2
	exit 2
fi
passed=0   # tests, summed over the steps' own "N passed, M failed" lines
failed=0
failures=()
log=$(mktemp)
trap 'rm -f "$log"' EXIT

# Under the sanitizers everything runs a few times slower.
if [[ "$build" == *sanitize* ]]; then
	export CK_TIMEOUT_MULTIPLIER=${CK_TIMEOUT_MULTIPLIER:-4}
fi

step() {  # step NAME COMMAND...: run it, count it
	local name=$1
	shift
	echo "== $name"
	local t0=$SECONDS status=0
	"$@" 2>&1 | tee "$log" || status=1
	local counts
	counts=$(grep -Eo '^([a-z]+: )?[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1 | grep -Eo '[0-9]+ passed, [0-9]+ failed')
	if [ -n "$counts" ]; then
		passed=$((passed + ${counts%% passed*}))
		local f=${counts##*, }
		failed=$((failed + ${f%% failed}))
	elif [ "$status" -eq 0 ]; then
		passed=$((passed + 1))
	fi
	if [ "$status" -eq 0 ]; then
		echo "== $name: ok ($((SECONDS - t0)) s)"
	else
		[ -n "$counts" ] && [ "${counts##*, }" != "0 failed" ] || failed=$((failed + 1))
		failures+=("$name")
		echo "== $name: FAILED ($((SECONDS - t0)) s)"
	fi
}

suite() {  # suite NAME: the Check suite tests/NAME with all its rubric files, in order
	local args=() r
	for r in $(bash -c '. lib/tools/common.sh && rubrics_of "$1"' suite "$1"); do
		args+=(--rubric "$r")
	done
	"$build/tests/$1" "${args[@]}"
}

step "suite lib" suite lib
step "the demo page's number format" bash tests/lib/check_numfmt.sh
for s in $stages; do
	step "suite $s (reference solutions)" suite "$s"
done
step "make lesson with a failing driver (a fake lesson)" bash tests/tools/lesson.sh
step "assignments/ is generated from solutions/" bash lib/tools/mkassign.sh solutions assignments --check
step "stub audit" bash tests/grade/audit.sh "$build" "$stages"
# The mutant sample and the fixtures are each mostly one process at a time (a test
# run, a build of one stage): on two cores they overlap, the mutants in the background
# into a log of their own that is shown, and counted, when the fixtures are done.
mutant_log=$(mktemp)
trap 'rm -f "$log" "$mutant_log"' EXIT
bash tests/grade/mutants.sh "$build" --sample >"$mutant_log" 2>&1 &
mutant_pid=$!
step "grader fixtures" bash tests/grade/fixtures.sh "$build"
mutant_status=0
wait "$mutant_pid" || mutant_status=$?
replay() {  # replay LOG STATUS: the background step's output, and its status
	cat "$1"
	return "$2"
}
step "mutants, one per graded function, the others applied (run beside the fixtures)" replay "$mutant_log" "$mutant_status"
step "handout and the student's path" bash lib/tools/handout.sh "$build"
step "MPI back-end (lz-mpi, P = 1..4)" bash tests/mpi/check.sh "$build"

echo
if [ ${#failures[@]} -ne 0 ]; then
	printf 'check FAILED: %s\n' "${failures[@]}"
fi
echo "check: $passed passed, $failed failed"
[ ${#failures[@]} -eq 0 ]
