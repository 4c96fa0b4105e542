#!/usr/bin/env bash
# make check — the test command: every suite against the reference must pass 100 %,
# the committed assignments must be current, the stub audit and the grader
# fixtures must pass. Usage: check.sh BUILD "STAGES"
set -uo pipefail
build=$1
stages=$2
passed=0
failed=0
failures=()

# Under the sanitizers everything runs a few times slower.
if [[ "$build" == *sanitize* ]]; then
	export CK_TIMEOUT_MULTIPLIER=${CK_TIMEOUT_MULTIPLIER:-4}
fi

step() {  # step NAME COMMAND...: run it, count it
	local name=$1
	shift
	echo "== $name"
	local t0=$SECONDS
	if "$@"; then
		passed=$((passed + 1))
		echo "== $name: ok ($((SECONDS - t0)) s)"
	else
		failed=$((failed + 1))
		failures+=("$name")
		echo "== $name: FAILED ($((SECONDS - t0)) s)"
	fi
}

suite() {  # suite NAME: the Check suite tests/NAME with all its rubric files
	local args=()
	for r in tests/"$1"/rubric tests/"$1"/rubric-* tests/"$1"/hidden/rubric; do
		[ -f "$r" ] && args+=(--rubric "$r")
	done
	"$build/tests/$1" "${args[@]}"
}

step "suite lib" suite lib
for s in $stages; do
	step "suite $s (reference solutions)" suite "$s"
done
step "assignments/ is generated from solutions/" bash lib/tools/mkassign.sh solutions assignments --check
step "stub audit" bash tests/grade/audit.sh "$build" "$stages"
step "grader fixtures" bash tests/grade/fixtures.sh "$build"

echo
if [ "$failed" -ne 0 ]; then
	printf 'check FAILED: %s\n' "${failures[@]}"
fi
echo "check: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
