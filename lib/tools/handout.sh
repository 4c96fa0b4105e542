#!/usr/bin/env bash
# handout.sh — `make handout`: the student tarball, and a check of it along the student's path.
#
#   handout.sh BUILD
#
# Packs the files git tracks (their working-tree content) into
# BUILD/handout/lozenge-student.tar.gz under lozenge-student/, leaving out what only
# the instructor has: solutions/, hidden tests (tests/*/hidden/), the grader's
# fixtures and the mutants (both hold working code) and the scripts that need them
# (audit.sh, fixtures.sh, mutants.sh). Without solutions/ the Makefile defaults to
# IMPL=assignments. It adds tests/grade/hidden-points (the points of each stage's
# hidden tests), so that a student's `make grade` can say what it does not count.
# Then it checks the tarball along the student's path: none of those paths inside,
# no solution marker in any file; unpacked, it builds (`make all`); on the stubs
# `make test STAGE=NN` fails with 0 points for every stage and `make grade` scores 0;
# with the reference copied in (a student who finished), `make test STAGE=NN`
# passes every stage, `make submit` packs exactly the MANIFEST files, the student's
# `make grade` of that tarball gives every public point, and the instructor's
# `make grade` of it (this tree, hidden tests included) gives full marks.
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
for r in tests/[0-9][0-9]-*/hidden/rubric; do
	[ -f "$r" ] || continue
	awk -v s="$(basename "$(dirname "$(dirname "$r")")")" '{ sub(/#.*/, "") } NF >= 4 { p += $2 }
		END { print s, p + 0 }' "$r"
done >"$stage/tests/grade/hidden-points"

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
[ "$bad" -eq 0 ] && echo "  ok  no solutions/, hidden tests, fixtures, mutants or their scripts inside"

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
# IMPL=assignments is the student's default: no text of theirs may ask for it (the
# Makefile and the tools that set it are the mechanism, not advice).
advice=$( (grep -rlF "IMPL=assignments" "$tree" --include='*.md' --include='*.c' --include='*.h' \
	--include='*.gp' --include='*.scene' || true) | sed "s|$tree/||")
if [ -n "$advice" ] || student_make help 2>&1 | grep -qF "IMPL=assignments"; then
	fail "the handout advises IMPL=assignments, its default, in: ${advice:-make help}"
else
	echo "  ok  no lesson, slide, stub, README or make help advises IMPL=assignments"
fi
t0=$SECONDS
if student_make all >"$tmp/all.log" 2>&1; then
	echo "  ok  make all builds ($((SECONDS - t0)) s)"
else
	fail "make all does not build in the handout:"
	grep -v '^  \(CC\|LD\|AR\) ' "$tmp/all.log" | head -n 30
fi
stages=$(for d in "$tree"/assignments/[0-9][0-9]-*/; do basename "$d"; done)
public_points() {  # public_points STAGE: the points of the rubrics the handout has
	cat "$tree/tests/$1"/rubric* | awk '{ sub(/#.*/, "") } NF >= 4 { p += $2 } END { print p + 0 }'
}
test_stages() {  # test_stages stubs|done: make test STAGE=NN for every stage
	local st out status want
	for st in $stages; do
		status=0
		student_make test STAGE="${st%%-*}" >"$tmp/test.log" 2>&1 || status=$?
		out=$(grep '^Score:' "$tmp/test.log" | tail -n 1)
		if [ "$1" = stubs ]; then
			want="Score: 0/$(public_points "$st")"
			[ "$status" -ne 0 ] && [ "$out" = "$want" ] ||
				fail "make test STAGE=${st%%-*} on the stubs: exit $status, '$out' (want a failure and '$want')"
		else
			want="Score: $(public_points "$st")/$(public_points "$st")"
			[ "$status" -eq 0 ] && [ "$out" = "$want" ] ||
				{ fail "make test STAGE=${st%%-*} with the reference: exit $status, '$out' (want 0 and '$want')"; grep -A1 FAIL "$tmp/test.log" | head -n 10; }
		fi
	done
	echo "  ok  make test STAGE=NN on the $1 of every stage ($((SECONDS - t0)) s)"
}
t0=$SECONDS
test_stages stubs
t0=$SECONDS
student_make grade >"$tmp/grade.log" 2>&1 || true
score=$(score_of "$tmp/grade.log")
case $score in
0/0 | '') fail "make grade in the handout gave no score:"; tail -n 30 "$tmp/grade.log" ;;
0/*) echo "  ok  make grade scores the stubs $score ($((SECONDS - t0)) s)" ;;
*) fail "make grade in the handout scores the stubs $score, not 0" ;;
esac
if [ -s "$tree/tests/grade/hidden-points" ] && ! grep -q "adds hidden tests worth" "$tmp/grade.log"; then
	fail "make grade in the handout does not say that the instructor's grade adds hidden tests"
fi

# A student who finished: the reference in assignments/, tested, submitted, graded.
for st in $stages; do
	cp solutions/"$st"/*.c "$tree/assignments/$st/"
done
t0=$SECONDS
test_stages done
if student_make submit >"$tmp/submit.log" 2>&1; then
	sub=$tree/build/submit/lozenge-submission.tar.gz
	want=$(cat "$tree"/tests/[0-9][0-9]-*/MANIFEST | sed 's/#.*//' | tr -d ' \t' | grep . | sort)
	if [ "$(tar -tzf "$sub" | sort)" = "$want" ]; then
		echo "  ok  make submit packs exactly the $(echo "$want" | wc -l) files the MANIFESTs name"
	else
		fail "make submit packed other files than the MANIFESTs name: $(tar -tzf "$sub" | tr '\n' ' ')"
	fi
	total=0
	for st in $stages; do
		total=$((total + $(public_points "$st")))
	done
	t0=$SECONDS
	student_make grade SUBMISSION="$sub" >"$tmp/grade.log" 2>&1 || true
	score=$(score_of "$tmp/grade.log")
	if [ "$score" = "$total/$total" ]; then
		echo "  ok  the student's make grade of it: $score, every public point ($((SECONDS - t0)) s)"
	else
		fail "the student's make grade of the submitted tarball: ${score:-no score}, want $total/$total"
	fi
	t0=$SECONDS
	bash tests/grade/grade.sh --build "$BUILD" --submission "$sub" --out "$BUILD/handout/grade" \
		>"$tmp/grade.log" 2>&1 || true
	score=$(score_of "$tmp/grade.log")
	if [ -n "$score" ] && [ "${score%/*}" = "${score#*/}" ]; then
		echo "  ok  the instructor's make grade of it: $score, hidden tests included ($((SECONDS - t0)) s)"
	else
		fail "the instructor's make grade of the submitted tarball: ${score:-no score}, want full marks"
	fi
else
	fail "make submit failed in the handout:"
	tail -n 20 "$tmp/submit.log"
fi

if [ "$FAILED" -ne 0 ]; then
	rm -f "$OUT"
	echo "handout: the tarball failed its check and was removed"
	exit 1
fi
echo "handout: $OUT is ready"
