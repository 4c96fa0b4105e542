#!/usr/bin/env bash
# mutants.sh — do the graded tests catch the mistakes students make? (`make mutants`)
#
#   mutants.sh BUILD [STAGE ...] [--only NAME ...] [--sample]
#
# A mutant is a realistic student bug, kept as a patch against the reference solution
# of its stage: tests/NN-name/mutants/NAME.patch. The text before the patch says what
# it is:
#
#   Bug: the second half-kick uses the old force (kick, then compute the force)
#   Function: lz_step_velocity_verlet
#   Survives: lozenge_verlet_order: it reads the stencil table, not the step
#
# (`Survives:` is optional and repeatable: a test that calls the function but cannot
# see this bug, with the reason.) The patch itself is `diff -u a/FILE b/FILE` run in
# solutions/NN-name/, so it applies with `patch -p1` there.
#
# For every function the mutants name, the tests that lean on it are found by
# running the stage's suite with that one function stubbed (its body replaced by
# LZ_TODO()): the tests that fail then are the ones that call it. A mutant is
# *killed* when every one of those tests fails on it, except the ones it declares in
# `Survives:`. Anything else is a defect, reported with the test names: a test that
# calls the function and still passes on the bug (it pays for a wrong function), a
# declared survivor that fails after all (the declaration is stale), a mutant that no
# longer applies or compiles (the reference changed under it), or one that kills
# nothing.
#
# --sample takes one mutant per function (the first by name) and only applies the
# others (patch --dry-run), so that a reference they no longer fit is still a defect:
# what `make check` runs; `make mutants` runs them all.
#
# Each stage runs in BUILD/mutants/NN-name/, a scratch copy of the sources, with the
# grader's file limit, building with JOBS parallel jobs (default: the cores). Prints
# `mutants: N passed, M failed`; exits non-zero on a defect.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"
cd "$ROOT"
need_args $# 1 any "mutants.sh BUILD [STAGE ...] [--only NAME ...] [--sample]"
BUILD=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
shift
WANT_STAGES=()
ONLY=()
SAMPLE=0
while [ $# -gt 0 ]; do
	case $1 in
	--sample) SAMPLE=1; shift ;;
	--only) [ $# -ge 2 ] || need_args 0 1 1 "mutants.sh BUILD [STAGE ...] [--only NAME ...]"
		ONLY+=("$2"); shift 2 ;;
	*) WANT_STAGES+=("$1"); shift ;;
	esac
done
[ -d solutions ] || { echo "mutants: they patch the reference solutions, and this tree has none (a student handout)" >&2; exit 2; }
TREE=
ULIMIT_F=$((20 * 1024))  # KiB, as the grader
passed=0
failed=0
make_tmp

defect() {
	failed=$((failed + 1))
	echo "  DEFECT  $*"
}

stages() {
	local d st want
	for d in tests/[0-9][0-9]-*/mutants/; do
		[ -d "$d" ] || continue
		st=$(basename "$(dirname "$d")")
		if [ ${#WANT_STAGES[@]} -eq 0 ]; then
			echo "$st"
			continue
		fi
		for want in "${WANT_STAGES[@]}"; do
			[ "$want" = "$st" ] || [ "$want" = "${st%%-*}" ] && echo "$st"
		done
	done
	return 0
}

field() {  # field PATCH KEY: the values of `KEY: value` lines before the diff
	sed -n '/^--- /q; s/^'"$2"': *//p' "$1"
}

# The file a patch changes (relative to solutions/STAGE).
patched_file() {  # patched_file PATCH
	sed -n 's/^+++ b\/\([^[:space:]]*\).*/\1/p' "$1" | head -n 1
}

# A scratch copy of the sources, built with the reference for every stage.
make_tree() {
	local d
	rm -rf "$TREE"
	mkdir -p "$TREE"
	for d in Makefile lib tests datasets lessons assignments solutions; do
		cp -R "$d" "$TREE/"
	done
	rm -rf "$TREE/tests/grade/fixtures"
}

tree_make() {  # tree_make TARGET...: quiet, in the scratch tree, reference everywhere
	env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -C "$TREE" --no-print-directory \
		-j"${JOBS:-$(nproc 2>/dev/null || echo 2)}" BUILD=build IMPL=solutions SANITIZE=0 "$@"
}

# Run STAGE's tests (all, or the --only list) in machine mode under the grader's
# file limit; prints the names of the tests that did not pass.
failing() {  # failing STAGE [ONLY]
	local st=$1 args=() r
	for r in $(rubrics_of "$st"); do
		args+=(--rubric "$TREE/$r")
	done
	[ -z "${2:-}" ] || args+=(--only "$2")
	(
		cd "$TREE" && ulimit -f "$ULIMIT_F" &&
			CK_FORK=yes build/tests/"$st" "${args[@]}" --machine --log build/mutant.log
	) >"$tmp/out" 2>&1 </dev/null || true
	grep -q '^LZEND' "$tmp/out" || { echo "__NO_REPORT__"; return; }
	awk -F'\t' '$1 == "LZRESULT" && $3 != "pass" { print $2 }' "$tmp/out" | sort
}

# SOLUTION with FUNCTION's reference body replaced by LZ_TODO(), to stdout.
stub_one() {  # stub_one SOLUTION FUNCTION
	local sb="LZ_SOLUTION""_BEGIN" se="LZ_SOLUTION""_END"
	echo '#include "lz/error.h"'
	# a static helper that only this function called is left unused; that is fine here
	echo '#pragma GCC diagnostic ignored "-Wunused-function"'
	awk -v fn="$2" -v sb="$sb" -v se="$se" '
	!in_fn && $0 ~ ("^[A-Za-z_].*[^A-Za-z0-9_]" fn "[ \t]*[(]") && $0 !~ /;[ \t]*$/ { in_fn = 1 }
	in_fn && index($0, sb) { match($0, /^[ \t]*/); print substr($0, 1, RLENGTH) "LZ_TODO();"; skip = 1; next }
	skip && index($0, se) { skip = 0; in_fn = 0; done = 1; next }
	skip { next }
	in_fn && /^}/ { in_fn = 0 }
	{ print }
	END { exit done ? 0 : 1 }' "$1"
}

# The tests of STAGE that call FUNCTION (defined in FILE): they fail when it is a stub.
leaning_on() {  # leaning_on STAGE FILE FUNCTION -> $tmp/lean-FUNCTION
	local st=$1 file=$2 fn=$3 src=$TREE/solutions/$1/$2
	[ -s "$tmp/lean-$fn" ] && return 0
	cp "$src" "$tmp/pristine"
	if ! stub_one "$tmp/pristine" "$fn" >"$src"; then
		cp "$tmp/pristine" "$src"
		echo "__NO_FUNCTION__" >"$tmp/lean-$fn"
		return 0
	fi
	if tree_make "build/tests/$st" >"$tmp/build.log" 2>&1; then
		failing "$st" >"$tmp/lean-$fn"
	else
		echo "__NO_BUILD__" >"$tmp/lean-$fn"
	fi
	cp "$tmp/pristine" "$src"
}

outgrown() {  # outgrown STAGE PATCH: the defect of a patch that no longer applies
	defect "$1/$(basename "$2" .patch): the patch no longer applies to solutions/$1/$(patched_file "$2"): $(head -n 1 "$tmp/patch.log")"
}

mutant() {  # mutant STAGE PATCH
	local st=$1 patch=$2 name fn file lean killed survivors declared stale t
	name=$(basename "$patch" .patch)
	fn=$(field "$patch" Function | head -n 1)
	file=$(patched_file "$patch")
	if [ -z "$fn" ] || [ -z "$file" ] || [ -z "$(field "$patch" Bug)" ]; then
		defect "$st/$name: the patch needs Bug: and Function: lines and a diff of one file"
		return
	fi
	leaning_on "$st" "$file" "$fn"
	case $(head -n 1 "$tmp/lean-$fn") in
	__NO_FUNCTION__) defect "$st/$name: $file defines no graded function $fn"; return ;;
	__NO_BUILD__ | __NO_REPORT__) defect "$st/$name: the suite does not build or run with $fn stubbed"; return ;;
	"") defect "$st/$name: no test fails when $fn is a stub: nothing pays for it"; return ;;
	esac
	cp "$TREE/solutions/$st/$file" "$tmp/pristine"
	if ! patch -s -p1 -d "$TREE/solutions/$st" <"$patch" >"$tmp/patch.log" 2>&1; then
		cp "$tmp/pristine" "$TREE/solutions/$st/$file"
		outgrown "$st" "$patch"
		return
	fi
	rm -f "$TREE/solutions/$st/$file.orig"
	if ! tree_make "build/tests/$st" >"$tmp/build.log" 2>&1; then
		cp "$tmp/pristine" "$TREE/solutions/$st/$file"
		defect "$st/$name: the mutant does not compile: $(grep -m1 'error' "$tmp/build.log")"
		return
	fi
	lean=$(tr '\n' ',' <"$tmp/lean-$fn")
	failing "$st" "${lean%,}" >"$tmp/killed"
	cp "$tmp/pristine" "$TREE/solutions/$st/$file"
	field "$patch" Survives | sed 's/[:[:space:]].*//' | sort >"$tmp/declared"
	survivors=$(comm -23 "$tmp/lean-$fn" "$tmp/killed" | comm -23 - "$tmp/declared" | tr '\n' ' ')
	stale=$(comm -12 "$tmp/declared" "$tmp/killed" | tr '\n' ' ')
	killed=$(wc -l <"$tmp/killed")
	t=$(wc -l <"$tmp/lean-$fn")
	if grep -q __NO_REPORT__ "$tmp/killed"; then
		defect "$st/$name: the test program did not report"
	elif [ "$killed" -eq 0 ]; then
		defect "$st/$name: no test fails on it ($(field "$patch" Bug))"
	elif [ -n "$survivors" ]; then
		defect "$st/$name: passes ${survivors% } although they call $fn ($(field "$patch" Bug))"
	elif [ -n "$stale" ]; then
		defect "$st/$name: declared to survive ${stale% }, but they fail: drop the Survives: lines"
	else
		passed=$((passed + 1))
		echo "  ok      $st/$name: $killed of the $t tests that call $fn fail"
	fi
}

wanted() {  # wanted NAME
	local o
	[ ${#ONLY[@]} -eq 0 ] && return 0
	for o in "${ONLY[@]}"; do
		[ "$o" = "$1" ] && return 0
	done
	return 1
}

t0=$SECONDS
for st in $(stages); do
	TREE=$BUILD/mutants/$st
	echo "mutants: $st (building the reference in $TREE)"
	make_tree
	tree_make "build/tests/$st" >"$tmp/build.log" 2>&1 ||
		{ defect "$st: the reference does not build"; continue; }
	rm -f "$tmp"/lean-*
	sampled=" "
	for p in tests/"$st"/mutants/*.patch; do
		[ -e "$p" ] || continue
		wanted "$(basename "$p" .patch)" || continue
		if [ "$SAMPLE" = 1 ]; then
			fn=$(field "$p" Function | head -n 1)
			if [[ $sampled == *" $fn "* ]]; then
				patch --dry-run -s -p1 -d "$TREE/solutions/$st" <"$p" >"$tmp/patch.log" 2>&1 ||
					outgrown "$st" "$p"
				continue
			fi
			sampled="$sampled$fn "
		fi
		mutant "$st" "$p"
	done
done
echo "mutants: $((SECONDS - t0)) s"
echo "mutants: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
