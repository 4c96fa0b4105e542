#!/usr/bin/env bash
# fixtures.sh — does the autograder score good and bad submissions as designed? (`make check`)
#
#   fixtures.sh BUILD [CASE ...]     (no CASE: all of them)
#
# Every tests/grade/fixtures/NAME/ is a fake student submission, kept as a recipe
# (RECIPE, format below) and an EXPECT file. Each is built into
# BUILD/grade-fixtures/submissions/NAME/ and graded by grade.sh — the instructor's
# command, under the grader's own limits — as a directory, as a .tar.gz, or both, or
# inside the class run below. Then: the reports were written and are well-formed;
# nothing a fixture forged (files holding FORGED-BY-FIXTURE) survived; the scratch
# tree is gone; no test program hit the grader's global timeout; and EXPECT holds:
#
#   stage NN          grade only stage NN (default: every stage)
#   form dir|tar|both|class   graded as a directory (default), as a tarball, both ways
#                     (the two must give every test the same result), or only as a
#                     tarball in the class run
#   score MIN MAX     the total (inclusive)
#   full NN ...|all   these stages score their whole rubric
#   partial NN ...|all   these stages score more than 0 and less than their rubric
#   stagescore NN MIN MAX   the score of one stage
#   status NN TEXT    the stage's status (its build test) starts with TEXT
#   report TEXT       report.txt contains TEXT (repeatable)
#   fails-as OTHER    exactly the tests that fail in fixture OTHER fail here
#   seconds S         grading it takes at most S seconds
#
# Two cases come from the tree itself: the stubs (no submission) score 0, and the
# reference as a student would hand it in scores full marks (the `reference`
# fixture). The class run grades the `form class` fixtures and the reference as
# tarballs with `--all` and checks the gradebook: a row per student with the same
# scores and statuses as each one's report.
# Prints `fixtures: N passed, M failed` and exits non-zero on any failure.
#
# A RECIPE starts from the committed stubs of every stage (assignments/), or from the
# reference solutions laid out as a student hands them in (`base reference`), and
# applies one operation a line, in order. FILE is assignments/NN-name/F.c, SNIPPET a
# file in the fixture's directory:
#
#   base stubs|reference            the starting point (first line; default stubs)
#   use OTHER                       apply tests/grade/fixtures/OTHER/RECIPE first
#   include FILE <HEADER>           put `#include <HEADER>` on FILE's first line
#   prepend FILE SNIPPET            put SNIPPET (top-level code) at the top of FILE
#   replace FILE FUNCTION SNIPPET   FUNCTION's body (the stub's `LZ_TODO();` line, or
#                                   the reference's body) becomes SNIPPET
#   stub FILE FUNCTION              FUNCTION's body becomes `LZ_TODO();`
#   symlink FILE TARGET             FILE becomes a symbolic link to TARGET
#   dotdot FILE                     in the tarball FILE is stored as
#                                   assignments/NN-name/../NN-name/F.c (never unpacked);
#                                   the directory form leaves it out
#
# A FUNCTION that FILE does not define, or whose body cannot be found, fails the
# fixture: a renamed function breaks it loudly instead of grading plain stubs.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"
cd "$ROOT"
need_args $# 1 any "fixtures.sh BUILD [CASE ...]"
BUILD=$1
shift
ONLY=" $* "
OUTS=$BUILD/grade-fixtures
SUBS=$OUTS/submissions
FIXTURES=tests/grade/fixtures
SOL_BEGIN="LZ_SOLUTION""_BEGIN"
SOL_END="LZ_SOLUTION""_END"
passed=0
failed=0
declare -A OUTDIR  # case name -> its graded output directory
declare -A DOTDOT  # fixture name -> the files its tarball stores behind '..'
CLASS=()           # the fixtures graded in the class run

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
		problem "a test program hit the grader's global timeout (a test's own timeout should have stopped it)"
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

# Every test of a graded output as "stage/test got max", from results.tap.
test_results() {  # test_results OUT
	sed -n 's/^\(not \)\{0,1\}ok [0-9]* - \([^ ]*\) (\([0-9.]*\)\/\([0-9.]*\) points)$/\2 \3 \4/p' \
		"$1/results.tap" | sort
}

# The tests that did not pass, one "stage/test" a line.
failing_tests() {  # failing_tests OUT
	sed -n 's/^not ok [0-9]* - \([^ ]*\) (.*points)$/\1/p' "$1/results.tap" | sort
}

# A stage's score as "GOT MAX", summed from results.tap.
stage_score() {  # stage_score OUT NN
	test_results "$1" | awk -v nn="$2" 'index($1, nn "-") == 1 { g += $2; m += $3 } END { printf "%g %g", g, m }'
}

# A stage's status, from its build line in results.tap.
stage_status() {  # stage_status OUT NN
	sed -n "s/^\(not \)\{0,1\}ok [0-9]* - $2-[a-z0-9-]*\/build (\(.*\))\$/\2/p" "$1/results.tap" | head -n 1
}

# The stage numbers a `full` or `partial` line names (`all`: every stage).
stages_of() {  # stages_of "NN ..."|all
	if [ "$1" = all ]; then
		for d in assignments/[0-9][0-9]-*/; do basename "$d" | cut -d- -f1; done
	else
		echo "$1"
	fi
}

# The points of a stage's rubrics (visible and hidden), as this tree defines them.
rubric_total() {  # rubric_total NN
	local st r
	for st in assignments/"$1"-*/; do
		st=$(basename "$st")
		for r in $(rubrics_of "$st"); do
			cat "$r"
		done
	done | awk '{ sub(/#.*/, "") } NF >= 4 { s += $2 } END { printf "%g", s }'
}

# ---- building a fixture's submission (the RECIPE format is at the top) --------------

# Build fixture NAME's submission into DEST (DEST/assignments/NN-name/*.c); on a bad
# recipe, record the problem and return 1.
build_fixture() {  # build_fixture NAME DEST
	local dest=$2 base
	rm -rf "$dest"
	mkdir -p "$dest/assignments"
	base=$(awk '$1 == "base" { print $2; exit }' "$FIXTURES/$1/RECIPE")
	case ${base:-stubs} in
	stubs) cp -R assignments/[0-9][0-9]-* "$dest/assignments/" ;;
	reference) cp -R solutions/[0-9][0-9]-* "$dest/assignments/" ;;
	*) problem "$FIXTURES/$1/RECIPE: base is stubs or reference, not '$base'"; return 1 ;;
	esac
	DOTDOT[$1]=
	apply_recipe "$1" "$dest" "" "$1"
}

apply_recipe() {  # apply_recipe NAME DEST USED FIXTURE (USED: the recipes above this one)
	local dest=$2 used="$3 $1 " dir=$FIXTURES/$1 line op file arg snip extra n=0 at
	[ -f "$dir/RECIPE" ] || { problem "$dir/RECIPE is missing"; return 1; }
	while IFS= read -r line; do
		read -r op file arg snip extra <<<"$line"
		n=$((n + 1))
		at="$dir/RECIPE:$n"
		case $op in '' | '#'* | base) continue ;; esac
		if [ "$op" = use ]; then
			[ -n "$file" ] && [ -z "$arg" ] || { problem "$at: use OTHER"; return 1; }
			[[ $used != *" $file "* ]] || { problem "$at: $file uses itself"; return 1; }
			apply_recipe "$file" "$dest" "$used" "$4" || return 1
			continue
		fi
		case $file in
		assignments/[0-9][0-9]-*/*.c) [ -f "$dest/$file" ] || { problem "$at: no file $file"; return 1; } ;;
		*) problem "$at: '$file' is not a file assignments/NN-name/F.c"; return 1 ;;
		esac
		case $op:$arg:$snip:$extra in
		include:\<*\>:: | include:\"*\"::) printf '#include %s\n' "$arg" | put_first "$dest/$file" ;;
		prepend:?*::) snippet "$dir/$arg" "$at" && put_first "$dest/$file" <"$dir/$arg" ;;
		replace:?*:?*:) snippet "$dir/$snip" "$at" && replace_body "$dest/$file" "$arg" "$dir/$snip" "$at" ;;
		stub:?*::) echo "LZ_TODO();" >"$tmp/stub" && replace_body "$dest/$file" "$arg" "$tmp/stub" "$at" ;;
		symlink:?*::) rm -f "$dest/$file" && ln -s "$arg" "$dest/$file" ;;
		dotdot:::) DOTDOT[$4]="${DOTDOT[$4]} $file"; mv "$dest/$file" "$dest/$file.dotdot" ;;
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

# Replace the body of FUNCTION, defined in FILE, with SNIPPET: the `LZ_TODO();` line
# of a stub, or the lines between the reference's markers.
replace_body() {  # replace_body FILE FUNCTION SNIPPET WHERE
	local status=0
	awk -v fn="$2" -v snip="$3" -v sb="$SOL_BEGIN" -v se="$SOL_END" '
	BEGIN { while ((getline line < snip) > 0) body[++nb] = line }
	function put(indent,   i) {
		for (i = 1; i <= nb; i++)
			print (body[i] == "" ? "" : indent body[i])
		replaced = 1
	}
	# The definition: at column 0 (a type, then the name and "("), not a declaration.
	!in_fn && $0 ~ ("^[A-Za-z_].*[^A-Za-z0-9_]" fn "[ \t]*[(]") && $0 !~ /;[ \t]*$/ {
		in_fn = 1; defined++
	}
	in_fn && !replaced && /^[ \t]*LZ_TODO[(][)];[ \t]*$/ {
		put(substr($0, 1, index($0, "L") - 1))
		next
	}
	in_fn && !replaced && index($0, sb) { skip = 1; put(substr($0, 1, match($0, /[^ \t]/) - 1)); next }
	skip { if (index($0, se)) skip = 0; next }
	in_fn && /^}/ { in_fn = 0 }
	{ print }
	END { exit defined != 1 ? 2 : !replaced ? 3 : 0 }' "$1" >"$1.new" || status=$?
	case $status in
	0) mv "$1.new" "$1"; return 0 ;;
	2) problem "$4: ${1##*/} does not define $2 (exactly once)" ;;
	3) problem "$4: $2 in ${1##*/} has no body to replace" ;;
	*) problem "$4: replacing $2 in $1 failed" ;;
	esac
	rm -f "$1.new"
	return 1
}

# Pack a fixture's submission as a student's tarball: assignments/NN-name/*.c, the
# dotdot files behind a '..'.
pack_fixture() {  # pack_fixture NAME SRC TARBALL
	local name=$1 src=$2 f st
	rm -rf "$tmp/pack"
	mkdir -p "$tmp/pack"
	cp -a "$src/assignments" "$tmp/pack/"
	find "$tmp/pack" -name '*.dotdot' -delete
	tar -cf "$tmp/pack.tar" -C "$tmp/pack" assignments
	for f in ${DOTDOT[$name]}; do
		st=$(basename "$(dirname "$f")")
		mkdir -p "$tmp/pack/$(dirname "$f")"
		cp "$src/$f.dotdot" "$tmp/pack/$f"
		tar -rPf "$tmp/pack.tar" -C "$tmp/pack" \
			--transform "s|^assignments/$st/|assignments/$st/../$st/|" "$f"
	done
	gzip -c "$tmp/pack.tar" >"$3"
}

# ---- grading a case ------------------------------------------------------------------

verdict() {  # verdict NAME SECONDS
	local name=$1 took=$2 out=${OUTDIR[$1]:-} p
	if [ ${#problems[@]} -eq 0 ]; then
		passed=$((passed + 1))
		if [ -n "$out" ] && [ -s "$out/report.txt" ]; then
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
		if [ -n "$out" ] && [ -s "$out/report.txt" ]; then
			echo "    the grader's table ($out/report.txt):"
			grep -v ' pass$\| pass (' "$out/report.txt" | sed 's/^/      /' | head -n 40
		fi
	fi
	problems=()
}

expect() {  # expect NAME KEY: the EXPECT values of KEY, one line each
	sed -E 's/^[[:space:]]+//' "$FIXTURES/$1/EXPECT" | awk -v k="$2" '$1 == k { $1 = ""; sub(/^ /, ""); print }'
}

# Grade SUBMISSION into OUTS/CASE; the grader's output goes to OUTS/CASE.log.
grade_case() {  # grade_case CASE SUBMISSION [STAGE]
	local name=$1 status=0 args=()
	[ -z "${3:-}" ] || args+=(--stage "$3")
	bash tests/grade/grade.sh --build "$BUILD" --submission "$2" "${args[@]}" \
		--out "$OUTS/$name" >"$OUTS/$name.log" 2>&1 || status=$?
	[ "$status" -eq 0 ] || problem "grade.sh exited with $status (see $OUTS/$name.log)"
	OUTDIR[$name]=$OUTS/$name
	check_files "$OUTS/$name"
}

# Check EXPECT of fixture NAME against the graded output OUT (fails-as waits for the end).
check_expect() {  # check_expect NAME OUT SECONDS
	local name=$1 out=$2 took=$3 line a b c got nn
	while read -r a b c; do
		in_range "$(got_of "$out")" "$a" "$b" || problem "score $(got_of "$out"), expected $a..$b"
	done < <(expect "$name" score)
	while read -r line; do
		for nn in $(stages_of "$line"); do
			got=$(stage_score "$out" "$nn")
			[ "${got% *}" = "$(rubric_total "$nn")" ] ||
				problem "stage $nn scores ${got% *}/${got#* }, expected full marks ($(rubric_total "$nn"))"
		done
	done < <(expect "$name" full)
	while read -r line; do
		for nn in $(stages_of "$line"); do
			got=$(stage_score "$out" "$nn")
			in_range "${got% *}" 0.5 "$(awk -v m="$(rubric_total "$nn")" 'BEGIN { print m - 0.5 }')" ||
				problem "stage $nn scores ${got% *}/${got#* }: expected more than 0 and less than full marks"
		done
	done < <(expect "$name" partial)
	while read -r nn a b; do
		got=$(stage_score "$out" "$nn")
		in_range "${got% *}" "$a" "$b" || problem "stage $nn scores ${got% *}, expected $a..$b"
	done < <(expect "$name" stagescore)
	while read -r nn line; do
		got=$(stage_status "$out" "$nn")
		[[ $got == "$line"* ]] || problem "stage $nn has status '$got', expected '$line…'"
	done < <(expect "$name" status)
	while IFS= read -r line; do
		grep -qF -- "$line" "$out/report.txt" 2>/dev/null || problem "report.txt does not say \"$line\""
	done < <(expect "$name" report)
	while read -r a; do
		[ "$took" -le "$a" ] || problem "grading took $took s, more than $a s"
	done < <(expect "$name" seconds)
}

# Grade fixture NAME (not a class one) as its EXPECT says.
fixture() {  # fixture NAME
	local name=$1 t0=$SECONDS form stage sub=$SUBS/$1
	form=$(expect "$name" form | head -n 1)
	stage=$(expect "$name" stage | head -n 1)
	if ! build_fixture "$name" "$sub"; then
		verdict "$name" 0
		return
	fi
	if [ "${form:-dir}" = class ]; then
		pack_fixture "$name" "$sub" "$tmp/class/$name.tar.gz"
		CLASS+=("$name")
		return
	fi
	if [ "${form:-dir}" != tar ]; then
		grade_case "$name" "$sub" "$stage"
	fi
	if [ "${form:-dir}" != dir ]; then
		pack_fixture "$name" "$sub" "$SUBS/$name.tar.gz"
		grade_case "$name.tar.gz" "$SUBS/$name.tar.gz" "$stage"
		[ "${form:-dir}" = tar ] && OUTDIR[$name]=$OUTS/$name.tar.gz
	fi
	if [ "${form:-dir}" = both ]; then
		cmp -s <(test_results "$OUTS/$name") <(test_results "$OUTS/$name.tar.gz") ||
			problem "as a directory and as a tarball it scores differently:" \
				"$(diff <(test_results "$OUTS/$name") <(test_results "$OUTS/$name.tar.gz") | head -n 6 | tr '\n' ' ')"
		check_expect "$name" "$OUTS/$name.tar.gz" $((SECONDS - t0))
	fi
	check_expect "$name" "${OUTDIR[$name]}" $((SECONDS - t0))
	verdict "$name" $((SECONDS - t0))
}

# Every fixture that names another in fails-as: the same tests fail in both.
fails_as_cases() {
	local d name other
	for d in "$FIXTURES"/*/; do
		name=$(basename "$d")
		wanted "$name" || continue
		other=$(expect "$name" fails-as | head -n 1)
		[ -n "$other" ] || continue
		if [ -z "${OUTDIR[$name]:-}" ] || [ -z "${OUTDIR[$other]:-}" ]; then
			problem "$name and $other must both be graded to compare them"
		elif ! cmp -s <(failing_tests "${OUTDIR[$name]}") <(failing_tests "${OUTDIR[$other]}"); then
			problem "$name does not fail exactly the tests $other fails (< only in $name, > only in $other):" \
				"$(diff <(failing_tests "${OUTDIR[$name]}") <(failing_tests "${OUTDIR[$other]}") | grep '^[<>]' | head -n 8 | tr '\n' ' ')"
		fi
		verdict "$name = $other" 0
	done
}

stubs_case() {
	local t0=$SECONDS
	grade_case stubs ""
	in_range "$(got_of "$OUTS/stubs")" 0 0 || problem "the stubs score $(got_of "$OUTS/stubs"), expected 0"
	verdict stubs $((SECONDS - t0))
}

# --all over the class fixtures (as tarballs), the reference, and an unreadable
# tarball: one gradebook row each, with the scores and statuses of their reports.
class_case() {
	local t0=$SECONDS status=0 book name nn col got want
	[ -d "$SUBS/reference" ] || { problem "the reference fixture was not built"; verdict class 0; return; }
	pack_fixture reference "$SUBS/reference" "$tmp/class/reference.tar.gz"
	printf 'not a tarball\n' | gzip -c | head -c 12 >"$tmp/class/garbled.tgz"
	bash tests/grade/grade.sh --build "$BUILD" --all "$tmp/class" \
		--out "$OUTS/class" >"$OUTS/class.log" 2>&1 || status=$?
	[ "$status" -eq 0 ] || problem "grade.sh --all exited with $status (see $OUTS/class.log)"
	book=$OUTS/class/gradebook.csv
	want=student
	for nn in $(for d in assignments/[0-9][0-9]-*/; do basename "$d"; done); do
		want="$want,$nn,$nn status"
	done
	[ "$(head -n 1 "$book" 2>/dev/null)" = "$want,total,max" ] ||
		problem "gradebook.csv: the header is not $want,total,max"
	for name in "${CLASS[@]}" reference garbled; do
		OUTDIR[$name]=$OUTS/class/$name
		check_files "$OUTS/class/$name"
		got=$(grep "^$name," "$book" 2>/dev/null | awk -F, '{ print $(NF - 1) }')
		[ "$got" = "$(got_of "$OUTS/class/$name")" ] && [ -n "$got" ] ||
			problem "gradebook.csv gives $name ${got:-no row}, its report $(got_of "$OUTS/class/$name")"
		col=2
		for nn in $(for d in assignments/[0-9][0-9]-*/; do basename "$d" | cut -d- -f1; done); do
			got=$(grep "^$name," "$book" 2>/dev/null | cut -d, -f$((col + 1)))
			[ "$got" = "$(stage_status "$OUTS/class/$name" "$nn")" ] ||
				problem "gradebook.csv gives $name the status '$got' in $nn, its report '$(stage_status "$OUTS/class/$name" "$nn")'"
			col=$((col + 2))
		done
	done
	grep -q '^garbled,0,unreadable' "$book" || problem "the unreadable tarball is not graded 0, unreadable"
	[ "$(test_results "$OUTS/class/reference")" = "$(test_results "$OUTS/reference")" ] ||
		problem "the reference tarball in the class run scores differently from the reference directory"
	verdict class $((SECONDS - t0))
	for name in "${CLASS[@]}"; do
		check_expect "$name" "$OUTS/class/$name" 0
		verdict "$name (in the class run)" 0
	done
}

# lz-report alone, on a crafted runner output: a fake block before the runner's own
# (glued to half a line) does not count, nor lines after LZEND; the last line for a
# test wins, unknown tests are ignored, and bytes that are not text come out as valid
# JSON, XML and TAP. Expected: first 2 + third 4 of stage 01, nothing of stage 02 (it
# did not compile), stage 03's refused file in its status.
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
	printf 'stage 03-z\nrubric %s\nrefused z.c: it is a symbolic link (03-z/z.c)\nbuild ok\nresults %s\nexit 0\n' \
		"$d/rubric" "$d/out" >>"$d/spec"
	mkdir -p "$OUTS/report"
	OUTDIR[report]=$OUTS/report
	"$BUILD/bin/lz-report" --quiet --out "$OUTS/report" --spec "$d/spec" || problem "lz-report failed"
	check_files "$OUTS/report"
	[ "$(got_of "$OUTS/report")/$(max_of "$OUTS/report")" = 12/30 ] ||
		problem "lz-report scored $(got_of "$OUTS/report")/$(max_of "$OUTS/report"), expected 12/30"
	grep -q "did not compile" "$OUTS/report/report.txt" || problem "report.txt does not say 'did not compile'"
	[ "$(stage_status "$OUTS/report" 03)" = "refused: z.c: it is a symbolic link (03-z/z.c)" ] ||
		problem "stage 03's status is '$(stage_status "$OUTS/report" 03)', not the refused file"
	verdict report $((SECONDS - t0))
}

wanted() { [ "$ONLY" = "  " ] || [[ $ONLY == *" $1 "* ]]; }

t0=$SECONDS
rm -rf "$OUTS"
mkdir -p "$OUTS" "$tmp/class"
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
fails_as_cases
wanted stubs && stubs_case
wanted class && class_case
echo "fixtures: $((SECONDS - t0)) s, outputs in $OUTS/"
echo "fixtures: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
