#!/usr/bin/env bash
# fixtures.sh — does the autograder score bad submissions as designed? (`make check`)
#
#   fixtures.sh BUILD [CASE ...]     (no CASE: all of them)
#
# Every tests/grade/fixtures/NAME/ is a fake student submission for stage 01, kept as
# a recipe (RECIPE, below) applied to the committed stubs, with an EXPECT file:
#
#   score MIN MAX     the total the grader must give (inclusive)
#   report TEXT       report.txt must contain TEXT (repeatable)
#   seconds S         grading it must take at most S seconds
#
# Each is built into BUILD/grade-fixtures/submissions/NAME/, graded by grade.sh into
# BUILD/grade-fixtures/NAME/, and then: the score is in range; report.txt,
# results.json, junit.xml and results.tap were written and are well-formed; nothing a
# fixture forged (files holding FORGED-BY-FIXTURE) survived; the scratch tree is gone;
# the whole test program never hit the grader's global timeout. Two more cases come
# from the tree itself: the stubs (no submission) must score 0 and the reference
# solutions full marks. Last, `--all` over a directory with the `half` fixture as a
# .tar.gz and a .tar.gz holding a symbolic link must write a gradebook with both rows,
# the same score for `half`, and 0 for the other.
# Prints `fixtures: N passed, M failed` and exits non-zero on any failure.
#
# A RECIPE starts from a copy of assignments/01-lozenge/ (the stubs; `make check` has
# already verified they are current) and applies one operation a line, in order.
# FILE is a path from the tree root, SNIPPET a file in the fixture's directory:
#
#   use OTHER                       apply tests/grade/fixtures/OTHER/RECIPE first
#   include FILE <HEADER>           put `#include <HEADER>` on FILE's first line
#   prepend FILE SNIPPET            put SNIPPET (top-level code) at the top of FILE
#   replace FILE FUNCTION SNIPPET   the `LZ_TODO();` line of FUNCTION's body becomes
#                                   SNIPPET, indented as that line was
#
# A FUNCTION that FILE does not define, or whose body has no `LZ_TODO();` line, fails
# the fixture: a renamed function breaks it loudly instead of grading plain stubs.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"
cd "$ROOT"
need_args $# 1 any "fixtures.sh BUILD [CASE ...]"
BUILD=$1
shift
ONLY=" $* "
OUTS=$BUILD/grade-fixtures
SUBS=$OUTS/submissions
STAGE=01
STAGE_DIR=assignments/01-lozenge
FIXTURES=tests/grade/fixtures
passed=0
failed=0
declare -A SCORE  # fixture name -> the score it got

make_tmp

# ---- checks on one graded output directory ----------------------------------------

problems=()
problem() { problems+=("$*"); }

check_files() {  # check_files OUT
	local out=$1 f n plan
	for f in report.txt results.json junit.xml results.tap; do
		[ -s "$out/$f" ] || problem "$f was not written"
	done
	[ -s "$out/results.json" ] && check_json "$out/results.json"
	if [ -s "$out/junit.xml" ]; then
		if command -v xmllint >/dev/null; then
			xmllint --noout "$out/junit.xml" 2>"$tmp/xml.err" ||
				problem "junit.xml is not well-formed: $(head -n 1 "$tmp/xml.err")"
		else
			grep -q '^<testsuites' "$out/junit.xml" || problem "junit.xml has no <testsuites>"
		fi
	fi
	if [ -s "$out/results.tap" ]; then
		[ "$(head -n 1 "$out/results.tap")" = "TAP version 13" ] || problem "results.tap: no TAP version 13 line"
		plan=$(sed -n 2p "$out/results.tap" | sed -n 's/^1\.\.\([0-9][0-9]*\)$/\1/p')
		n=$(grep -cE '^(not )?ok [0-9]+ ' "$out/results.tap" || true)
		[ -n "$plan" ] && [ "$plan" = "$n" ] || problem "results.tap: the plan says ${plan:-nothing}, $n test lines"
	fi
	[ ! -e "$out/scratch" ] || problem "the scratch tree $out/scratch was left behind"
	if grep -rlq FORGED-BY-FIXTURE "$out" 2>/dev/null; then
		problem "a forged file survived: $(grep -rl FORGED-BY-FIXTURE "$out" | head -n 3 | tr '\n' ' ')"
	fi
	if grep -q "the whole test program was stopped" "$out/report.txt" 2>/dev/null; then
		problem "the test program hit the grader's global timeout (a test's own timeout should have stopped it)"
	fi
}

check_json() {  # check_json FILE: well-formed, and its score matches report.txt's
	local json=$1 score
	if command -v python3 >/dev/null; then
		python3 -m json.tool "$json" >/dev/null 2>"$tmp/json.err" ||
			{ problem "results.json is not valid JSON: $(tail -n 1 "$tmp/json.err")"; return; }
		score=$(python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); print("%g" % d["score"]); assert all(k in t for t in d["tests"] for k in ("name", "score", "max_score", "output", "visibility"))' "$json" 2>/dev/null) ||
			{ problem "results.json lacks Gradescope's keys"; return; }
	else
		grep -q '"tests": \[' "$json" || { problem "results.json has no tests array"; return; }
		score=$(sed -n 's/^  "score": \(.*\),$/\1/p' "$json")
	fi
	[ "$score" = "$(got_of "$(dirname "$json")")" ] ||
		problem "results.json says score $score, report.txt says $(got_of "$(dirname "$json")")"
}

got_of() { local s; s=$(score_of "$1/report.txt"); echo "${s%/*}"; }  # got_of OUT
max_of() { local s; s=$(score_of "$1/report.txt"); echo "${s#*/}"; }  # max_of OUT

in_range() {  # in_range X MIN MAX
	awk -v x="$1" -v lo="$2" -v hi="$3" 'BEGIN { exit !(x != "" && x >= lo && x <= hi) }'
}

# ---- building a fixture's submission (the RECIPE format is at the top) --------------

# Build fixture NAME's submission into DEST (DEST/assignments/01-lozenge/*.c); on a
# bad recipe, record the problem and return 1.
build_fixture() {  # build_fixture NAME DEST
	local dest=$2
	rm -rf "$dest"
	mkdir -p "$dest/$(dirname "$STAGE_DIR")"
	cp -R "$STAGE_DIR" "$dest/$STAGE_DIR"
	apply_recipe "$1" "$dest" ""
}

apply_recipe() {  # apply_recipe NAME DEST USED (USED: the recipes above this one)
	local dest=$2 used="$3 $1 " dir=$FIXTURES/$1 line op file arg snip extra n=0 at
	[ -f "$dir/RECIPE" ] || { problem "$dir/RECIPE is missing"; return 1; }
	while IFS= read -r line; do
		read -r op file arg snip extra <<<"$line"
		n=$((n + 1))
		at="$dir/RECIPE:$n"
		case $op in '' | '#'*) continue ;; esac
		if [ "$op" = use ]; then
			if [ -z "$file" ] || [ -n "$arg" ]; then
				problem "$at: use OTHER"
				return 1
			fi
			[[ $used != *" $file "* ]] || { problem "$at: $file uses itself"; return 1; }
			apply_recipe "$file" "$dest" "$used" || return 1
			continue
		fi
		case $file in
		"$STAGE_DIR"/*.c) [ -f "$dest/$file" ] || { problem "$at: no stub $file"; return 1; } ;;
		*) problem "$at: '$file' is not a file of $STAGE_DIR/"; return 1 ;;
		esac
		case $op:$arg:$snip:$extra in
		include:\<*\>:: | include:\"*\"::) printf '#include %s\n' "$arg" | put_first "$dest/$file" ;;
		prepend:?*::) snippet "$dir/$arg" "$at" && put_first "$dest/$file" <"$dir/$arg" ;;
		replace:?*:?*:)
			[[ $arg =~ ^[A-Za-z_][A-Za-z0-9_]*$ ]] || { problem "$at: '$arg' is not a function name"; return 1; }
			snippet "$dir/$snip" "$at" && replace_todo "$dest/$file" "$arg" "$dir/$snip" "$at" ;;
		*) problem "$at: not an operation: $line"; false ;;
		esac || return 1
	done <"$dir/RECIPE"
}

snippet() {  # snippet PATH WHERE: the snippet exists
	[ -f "$1" ] || { problem "$2: no snippet $1"; return 1; }
}

put_first() {  # put_first FILE: what comes on stdin goes before FILE's content
	cat - "$1" >"$1.new" && mv "$1.new" "$1"
}

# Replace the `LZ_TODO();` line in the body of FUNCTION, defined in FILE, with SNIPPET.
replace_todo() {  # replace_todo FILE FUNCTION SNIPPET WHERE
	local status=0
	awk -v fn="$2" -v snip="$3" '
	BEGIN { while ((getline line < snip) > 0) body[++nb] = line }
	# The definition: at column 0 (a type, then the name and "("), not a declaration.
	!in_fn && $0 ~ ("^[A-Za-z_].*[^A-Za-z0-9_]" fn "[ \t]*[(]") && $0 !~ /;[ \t]*$/ {
		in_fn = 1; defined++
	}
	in_fn && !replaced && /^[ \t]*LZ_TODO[(][)];[ \t]*$/ {
		indent = substr($0, 1, index($0, "L") - 1)
		for (i = 1; i <= nb; i++)
			print (body[i] == "" ? "" : indent body[i])
		replaced = 1
		next
	}
	in_fn && /^}/ { in_fn = 0 }
	{ print }
	END { exit defined != 1 ? 2 : !replaced ? 3 : 0 }' "$1" >"$1.new" || status=$?
	case $status in
	0) mv "$1.new" "$1"; return 0 ;;
	2) problem "$4: ${1##*/} does not define $2 (exactly once)" ;;
	3) problem "$4: $2 in ${1##*/} has no LZ_TODO(); line to replace" ;;
	*) problem "$4: replacing $2 in $1 failed" ;;
	esac
	rm -f "$1.new"
	return 1
}

# ---- grading a case ------------------------------------------------------------------

verdict() {  # verdict NAME SECONDS: count the case, print its problems
	local name=$1 took=$2 out=$OUTS/$1 p
	if [ ${#problems[@]} -eq 0 ]; then
		passed=$((passed + 1))
		if [ -s "$out/report.txt" ]; then
			echo "fixture $name: ok (score $(got_of "$out")/$(max_of "$out"), $took s)"
		else
			echo "fixture $name: ok ($took s)"
		fi
	else
		failed=$((failed + 1))
		echo "fixture $name: FAILED ($took s)"
		for p in "${problems[@]}"; do
			echo "    $p"
		done
		if [ -s "$out/report.txt" ]; then
			echo "    the grader's table ($out/report.txt):"
			sed 's/^/      /' "$out/report.txt" | head -n 40
		fi
	fi
	problems=()
}

# Grade SUBMISSION as case NAME; the grader's output goes to OUTS/NAME.log.
grade_case() {  # grade_case NAME SUBMISSION
	local name=$1 sub=$2 status=0
	bash tests/grade/grade.sh --build "$BUILD" --submission "$sub" --stage "$STAGE" \
		--out "$OUTS/$name" >"$OUTS/$name.log" 2>&1 || status=$?
	[ "$status" -eq 0 ] || problem "grade.sh exited with $status (see $OUTS/$name.log)"
	check_files "$OUTS/$name"
	SCORE[$name]=$(got_of "$OUTS/$name")
}

check_expect() {  # check_expect NAME EXPECT SECONDS
	local name=$1 expect=$2 took=$3 key a b got
	got=${SCORE[$name]}
	while read -r key a b; do
		case $key in
		score) in_range "$got" "$a" "$b" || problem "score ${got:-none}, expected $a..$b" ;;
		report) grep -qF -- "$a${b:+ $b}" "$OUTS/$name/report.txt" 2>/dev/null ||
			problem "report.txt does not say \"$a${b:+ $b}\"" ;;
		seconds) [ "$took" -le "$a" ] || problem "grading took $took s, more than $a s" ;;
		'' | '#'*) ;;
		*) problem "EXPECT: unknown line '$key'" ;;
		esac
	done < <(sed -E 's/^[[:space:]]+//' "$expect")
}

fixture() {  # fixture NAME
	local name=$1 t0=$SECONDS
	if build_fixture "$name" "$SUBS/$name"; then
		grade_case "$name" "$SUBS/$name"
		check_expect "$name" "$FIXTURES/$name/EXPECT" $((SECONDS - t0))
	fi
	verdict "$name" $((SECONDS - t0))
}

stubs_case() {
	local t0=$SECONDS
	grade_case stubs ""
	in_range "${SCORE[stubs]}" 0 0 || problem "the stubs score ${SCORE[stubs]:-none}, expected 0"
	verdict stubs $((SECONDS - t0))
}

reference_case() {
	local t0=$SECONDS max
	grade_case reference solutions
	max=$(max_of "$OUTS/reference")
	[ -n "$max" ] && [ "${SCORE[reference]}" = "$max" ] && [ "$max" != 0 ] ||
		problem "the reference scores ${SCORE[reference]:-none}/${max:-none}, expected full marks"
	verdict reference $((SECONDS - t0))
}

# --all over a class of two: half as a tarball, and a tarball with a symbolic link.
class_case() {
	local t0=$SECONDS subs=$tmp/class status=0 book row
	mkdir -p "$subs" "$tmp/evil/01-lozenge"
	build_fixture half "$tmp/half" || { verdict class $((SECONDS - t0)); return; }
	tar -czf "$subs/half.tar.gz" -C "$tmp/half" assignments
	ln -s /etc/passwd "$tmp/evil/01-lozenge/fpsum.c"
	tar -czf "$subs/evil.tgz" -C "$tmp/evil" 01-lozenge
	bash tests/grade/grade.sh --build "$BUILD" --all "$subs" --stage "$STAGE" \
		--out "$OUTS/class" >"$OUTS/class.log" 2>&1 || status=$?
	[ "$status" -eq 0 ] || problem "grade.sh --all exited with $status (see $OUTS/class.log)"
	book=$OUTS/class/gradebook.csv
	[ "$(head -n 1 "$book" 2>/dev/null)" = "student,01-lozenge,total,max" ] ||
		problem "gradebook.csv: no header student,01-lozenge,total,max"
	row=$(grep '^half,' "$book" 2>/dev/null | cut -d, -f3)
	[ "$row" = "${SCORE[half]:-}" ] || problem "half.tar.gz scores ${row:-nothing}, the half directory ${SCORE[half]:-nothing}"
	row=$(grep '^evil,' "$book" 2>/dev/null | cut -d, -f3)
	[ "$row" = 0 ] || problem "evil.tgz (a symbolic link) scores ${row:-nothing}, expected 0"
	grep -q "symbolic link" "$OUTS/class/evil/report.txt" 2>/dev/null ||
		problem "evil/report.txt does not say the symbolic link was refused"
	check_files "$OUTS/class/half"
	verdict class $((SECONDS - t0))
}

# lz-report alone, on a crafted runner output: a fake block before the runner's own
# (glued to half a line) does not count, nor lines after LZEND; the last line for a
# test wins, unknown tests are ignored, and bytes that
# are not text come out as valid JSON, XML and TAP. Expected: first 2 + third 4 of
# stage 01, nothing of stage 02 (it did not compile).
report_case() {
	local t0=$SECONDS d=$tmp/report
	mkdir -p "$d"
	printf '# test points visibility timeout_s\nfirst 2 visible 5\nsecond 3 hidden 5\nthird 4 visible 5\nfourth 1 visible 5\n' >"$d/rubric"
	{
		printf 'LZBEGIN\nLZRESULT\tfirst\tpass\t\nLZRESULT\tsecond\tpass\t\nLZRESULT\tthird\tpass\t\n'
		printf 'LZRESULT\tfourth\tpass\t\nLZEND\tran\t4\nhalf a line, then the real block: '
		printf 'LZBEGIN\nLZRESULT\tfirst\tpass\t\nLZRESULT\tsecond\tpass\t\n'
		printf 'LZRESULT\tsecond\tfail\tbad \001\377\376 bytes <&> "q" \047s \302\n'
		printf 'LZRESULT\tthird\tfail\tx\nLZRESULT\tthird\tpass\t\nLZRESULT\tbogus\tpass\t\nLZEND\tran\t3\nLZRESULT\tfourth\tpass\t\n'
	} >"$d/out"
	printf 'x.c:1:1: error: \033[31mred\033[0m \377\n' >"$d/cc.log"
	printf 'stage 01-x\nrubric %s\nbuild ok\nresults %s\nexit 1\nstage 02-y\nrubric %s\nbuild failed %s\n' \
		"$d/rubric" "$d/out" "$d/rubric" "$d/cc.log" >"$d/spec"
	mkdir -p "$OUTS/report"
	"$BUILD/bin/lz-report" --quiet --out "$OUTS/report" --spec "$d/spec" || problem "lz-report failed"
	check_files "$OUTS/report"
	SCORE[report]=$(got_of "$OUTS/report")
	[ "${SCORE[report]}/$(max_of "$OUTS/report")" = 6/20 ] ||
		problem "lz-report scored ${SCORE[report]:-nothing}/$(max_of "$OUTS/report"), expected 6/20"
	grep -q "did not compile" "$OUTS/report/report.txt" || problem "report.txt does not say 'did not compile'"
	verdict report $((SECONDS - t0))
}

wanted() { [ "$ONLY" = "  " ] || [[ $ONLY == *" $1 "* ]]; }

t0=$SECONDS
rm -rf "$OUTS"
mkdir -p "$OUTS"
make --no-print-directory BUILD="$BUILD" "$BUILD/bin/lz-report" >/dev/null
wanted report && report_case
for d in "$FIXTURES"/*/; do
	name=$(basename "$d")
	wanted "$name" || continue
	if [ -f "$d/EXPECT" ]; then
		fixture "$name"
	else
		failed=$((failed + 1))
		echo "fixture $name: FAILED (no EXPECT file)"
	fi
done
wanted stubs && stubs_case
if [ -d solutions ] && wanted reference; then
	reference_case
fi
wanted class && class_case
echo "fixtures: $((SECONDS - t0)) s, outputs in $OUTS/"
echo "fixtures: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
