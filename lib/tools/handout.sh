#!/usr/bin/env bash
# handout.sh — `make handout`: the student tarball, and a check of it (DESIGN §4).
#
#   handout.sh BUILD
#
# Packs the files git tracks (their working-tree content) into
# BUILD/handout/lozenge-student.tar.gz under lozenge-student/, leaving out what only
# the instructor has: solutions/, hidden tests (tests/*/hidden/), the grader's
# fixtures and the mutants (both hold working code) and the scripts that need them
# (audit.sh, fixtures.sh, mutants.sh). Without solutions/ the Makefile defaults to IMPL=assignments.
# Then it checks the tarball: none of those paths inside, no solution marker in any
# file, and unpacked into a temporary directory it builds (`make all`) and
# `make grade` there scores 0.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$ROOT"
need_args $# 1 1 "handout.sh BUILD"
BUILD=$1
OUT=$BUILD/handout/lozenge-student.tar.gz
NAME=lozenge-student
# The markers, assembled so that this file (which is in the handout) has none.
MARKERS=("LZ_SOLUTION""_BEGIN" "LZ_SOLUTION""_END" "LZ_HELPERS""_BEGIN" "LZ_HELPERS""_END")
FAILED=0

fail() {
	echo "handout: FAILED: $*"
	FAILED=1
}

# Paths the student must not get (one pattern per line, as `case` patterns).
instructor_only() {  # instructor_only PATH: true when PATH stays out of the handout
	case $1 in
	solutions/* | tests/*/hidden/* | tests/*/mutants/* | tests/grade/fixtures/* | tests/grade/audit.sh | \
	tests/grade/fixtures.sh | tests/grade/mutants.sh)
		return 0 ;;
	esac
	return 1
}

if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
	echo "handout: $ROOT is not a git checkout: the handout is made of the files git tracks" >&2
	exit 1
fi

make_tmp
stage=$tmp/pack/$NAME
mkdir -p "$stage"

# ---- pack ------------------------------------------------------------------------------

n=0
left=0
while IFS= read -r -d '' f; do
	if instructor_only "$f"; then
		left=$((left + 1))
		continue
	fi
	if [ ! -e "$f" ] && [ ! -L "$f" ]; then
		echo "handout: $f is tracked but not in the working tree: left out"
		continue
	fi
	mkdir -p "$stage/$(dirname "$f")"
	cp -P --preserve=mode "$f" "$stage/$f"
	n=$((n + 1))
done < <(git ls-files -z)
[ "$n" -gt 0 ] || { echo "handout: git tracks no files here yet (git add them first)" >&2; exit 1; }

mtime=$(git log -1 --format=%ct 2>/dev/null || echo 0)
mkdir -p "$(dirname "$OUT")"
tar --sort=name --owner=0 --group=0 --numeric-owner --mtime="@$mtime" \
	-C "$tmp/pack" -cf - "$NAME" | gzip -n -9 >"$OUT.tmp"
mv "$OUT.tmp" "$OUT"
echo "handout: $OUT: $n files ($left instructor-only files left out)"

# ---- check -------------------------------------------------------------------------------

echo "handout: checking it"
bad=0
while IFS= read -r p; do
	instructor_only "${p#"$NAME"/}" && { fail "$p is instructor-only"; bad=1; }
done < <(tar -tzf "$OUT")
[ "$bad" -eq 0 ] && echo "  ok  no solutions/, hidden tests, fixtures, audit.sh or fixtures.sh inside"

check=$tmp/check
mkdir -p "$check"
tar -xzf "$OUT" -C "$check"
tree=$check/$NAME
hits=$(grep -rlF "${MARKERS[@]/#/-e}" "$tree" 2>/dev/null || true)
if [ -n "$hits" ]; then
	fail "solution markers in: $(echo "$hits" | sed "s|$tree/||" | tr '\n' ' ')"
else
	echo "  ok  no solution marker in any file"
fi

# The handout is built and graded as a student would, with nothing from this make.
student_make() {
	env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u IMPL -u SANITIZE -u BUILD \
		make -C "$tree" --no-print-directory "$@"
}
if student_make help 2>&1 | grep -q 'now:.*=solutions'; then
	fail "the handout does not default to IMPL=assignments: $(student_make help 2>&1 | tail -n 1)"
else
	echo "  ok  IMPL defaults to assignments"
fi
t0=$SECONDS
if student_make all >"$tmp/all.log" 2>&1; then
	echo "  ok  make all builds ($((SECONDS - t0)) s)"
else
	fail "make all does not build in the handout:"
	grep -v '^  \(CC\|LD\|AR\) ' "$tmp/all.log" | head -n 30
fi
t0=$SECONDS
student_make grade >"$tmp/grade.log" 2>&1 || true
score=$(score_of "$tmp/grade.log")
case $score in
0/0 | '') fail "make grade in the handout gave no score:"; tail -n 30 "$tmp/grade.log" ;;
0/*) echo "  ok  make grade scores the stubs $score ($((SECONDS - t0)) s)" ;;
*) fail "make grade in the handout scores the stubs $score, not 0" ;;
esac

if [ "$FAILED" -ne 0 ]; then
	rm -f "$OUT"
	echo "handout: the tarball failed its check and was removed"
	exit 1
fi
echo "handout: $OUT is ready"
