#!/usr/bin/env bash
# grade.sh — the autograder (DESIGN §6). `make grade` and `make grade-all` call it.
#
#   grade.sh --build BUILD [--submission DIR|X.tar.gz|X.tgz] [--stage NN] [--isolate 0|1]
#            [--out DIR]
#   grade.sh --build BUILD --all SUBS [--stage NN] [--isolate 0|1] [--out DIR]
#
# A submission is a directory or a .tar.gz; empty means this tree's own assignments/
# (the stubs in the instructor's tree, the student's work in a handout). For each
# stage the files its tests/NN-name/MANIFEST lists are looked up in the submission at
# <path>, NN-name/<file> or <file>, and copied onto a clean scratch copy of this tree
# (links, special files, files over 1 MiB and '..' are refused; a missing file keeps
# the stub). The stage's test binary is built there (--isolate 1 links the reference
# solutions for every other stage), and run under timeout and ulimit. Then every
# file the student's code could have written is deleted and lz-report, which links
# no student code, writes the reports from what this script captured itself:
# OUT/report.txt (and the table on stdout), results.json (Gradescope), junit.xml and
# results.tap. OUT defaults to BUILD/grade. --all grades every sub-directory and
# .tar.gz of SUBS into OUT/<student>/ and writes OUT/gradebook.csv.
#
# The graded objects may define only lz_ functions (static helpers are fine) and no
# code that runs before or after main: both would let a submission write the
# runner's results itself, so such a stage is rejected.
#
# Limits: the student's code runs as the user who grades. This script defends against
# crashes, endless loops, floods of output and naive forgery (files claiming full
# marks, fake result lines); a program written to attack the grader can still do
# anything that user can. Grade untrusted code in a throw-away container or account
# (Gradescope's autograder containers are such).
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"  # strict mode, LC_ALL=C, ROOT
MAX_FILE=$((1024 * 1024))           # bytes: a submitted file
MAX_CAPTURE=$((1024 * 1024))        # bytes: the runner's output we read
ULIMIT_F=$((20 * 1024))             # KiB: any file the tests write
ULIMIT_V=$((4 * 1024 * 1024))       # KiB: address space of each test process
SLACK=30                            # seconds on top of the rubric's timeouts
JOBS=$(nproc 2>/dev/null || echo 2)
[ "$JOBS" -le 8 ] || JOBS=8

die() {
	echo "grade: $*" >&2
	exit 2
}

usage() {
	cat >&2 <<'EOF'
usage: grade.sh --build BUILD [--submission DIR|X.tar.gz] [--stage NN] [--isolate 0|1] [--out DIR]
       grade.sh --build BUILD --all SUBS [--stage NN] [--isolate 0|1] [--out DIR]
EOF
	exit 2
}

abspath() {
	case $1 in
	/*) printf '%s\n' "$1" ;;
	*) printf '%s\n' "$PWD/$1" ;;
	esac
}

# ---- the stages --------------------------------------------------------------

# All stages of this tree (as the Makefile sees them), or the one --stage names.
select_stages() {  # select_stages NN|NN-name|''
	local all=() s
	for s in "$ROOT"/assignments/[0-9][0-9]-*/; do
		[ -d "$s" ] && all+=("$(basename "$s")")
	done
	[ ${#all[@]} -gt 0 ] || die "no stages: $ROOT/assignments/NN-name/ is empty"
	if [ -z "$1" ]; then
		printf '%s\n' "${all[@]}"
		return
	fi
	for s in "${all[@]}"; do
		if [ "$s" = "$1" ] || [ "${s%%-*}" = "$1" ]; then
			echo "$s"
			return
		fi
	done
	die "no stage '$1'; the stages here are: ${all[*]}"
}

# The paths a stage's MANIFEST lists, checked: relative, under assignments/, no '..'.
manifest_of() {  # manifest_of STAGE
	local m="$ROOT/tests/$1/MANIFEST" p
	[ -f "$m" ] || die "$m is missing: it lists the files a student hands in for $1"
	while read -r p; do
		p=${p%%#*}
		p=$(printf '%s' "$p" | tr -d ' \t\r')
		[ -n "$p" ] || continue
		case "/$p/" in
		*/../* | */./* | //*) die "$m: '$p' must be a plain path relative to the tree root" ;;
		esac
		case $p in
		assignments/*) echo "$p" ;;
		*) die "$m: '$p' is not under assignments/" ;;
		esac
	done <"$m"
}

budget_of() {  # budget_of STAGE: the rubric timeouts summed, plus slack, in seconds
	echo $(($(rubric_seconds "$1") + SLACK))
}

# ---- the submission ------------------------------------------------------------

# Refuse a tarball with links, special files, absolute paths or '..'; print why.
tarball_problem() {  # tarball_problem FILE
	local listing=() names=() i
	mapfile -t listing < <(tar -tvzf "$1" 2>/dev/null) || true
	mapfile -t names < <(tar -tzf "$1" 2>/dev/null) || true
	if ! tar -tzf "$1" >/dev/null 2>&1 || [ ${#listing[@]} -ne ${#names[@]} ]; then
		echo "it is not a readable .tar.gz"
		return
	fi
	for i in "${!names[@]}"; do
		case ${listing[$i]:0:1} in
		- | d) ;;
		l) echo "it contains a symbolic link: ${names[$i]}"; return ;;
		h) echo "it contains a hard link: ${names[$i]}"; return ;;
		*) echo "it contains a special file: ${names[$i]}"; return ;;
		esac
		case "/${names[$i]}/" in
		//*) echo "it contains an absolute path: ${names[$i]}"; return ;;
		*/../*) echo "it contains a path with '..': ${names[$i]}"; return ;;
		esac
	done
}

# Unpack a checked tarball into DEST; print the directory that holds the submission
# (a tarball of one top-level directory is looked into).
unpack() {  # unpack FILE DEST
	local dest=$2 only depth
	mkdir -p "$dest"
	(ulimit -f $((100 * 1024)) && tar -xzf "$1" -C "$dest" --no-same-owner \
		--no-same-permissions --no-overwrite-dir) >/dev/null 2>&1 || return 1
	for depth in 1 2 3; do
		only=$(only_entry "$dest")
		if [ -z "$only" ] || [ ! -d "$only" ] || [ -L "$only" ]; then
			break
		fi
		dest=$only
		: "$depth"
	done
	echo "$dest"
}

# The single entry of a directory, or nothing when it has none or several.
only_entry() {  # only_entry DIR
	local e found='' n=0
	for e in "$1"/* "$1"/.[!.]*; do
		[ -e "$e" ] || [ -L "$e" ] || continue
		found=$e
		n=$((n + 1))
	done
	[ "$n" -eq 1 ] && echo "$found"
	return 0
}

# Where a manifest path is in the submission (empty when it is not there).
locate() {  # locate SUB STAGE PATH
	local c
	for c in "$1/$3" "$1/$2/${3##*/}" "$1/${3##*/}"; do
		if [ -L "$c" ] || [ -e "$c" ]; then
			echo "$c"
			return
		fi
	done
}

# Why a submitted file is refused (empty when it is fine).
file_problem() {  # file_problem SUB FILE
	local real sub size
	if [ -L "$2" ]; then
		echo "it is a symbolic link"
	elif [ ! -f "$2" ]; then
		echo "it is not a regular file"
	else
		size=$(stat -c %s -- "$2")
		real=$(realpath -- "$2")
		sub=$(realpath -- "$1")
		if [ "$size" -gt "$MAX_FILE" ]; then
			echo "it is larger than 1 MiB ($size bytes)"
		elif [ "${real#"$sub"/}" = "$real" ]; then
			echo "it lies outside the submission"
		fi
	fi
}

# Copy every manifest file of every stage from the submission onto the scratch tree,
# writing the notes for each stage into PRIV/notes-STAGE.
copy_submission() {  # copy_submission SUB SCRATCH PRIV
	local sub=$1 scratch=$2 priv=$3 st p c why
	for st in $ALL_STAGES; do
		: >"$priv/notes-$st"
		for p in $(manifest_of "$st"); do
			c=$(locate "$sub" "$st" "$p")
			if [ -z "$c" ]; then
				echo "$p: not in the submission, the stub was kept" >>"$priv/notes-$st"
				continue
			fi
			why=$(file_problem "$sub" "$c")
			if [ -n "$why" ]; then
				echo "$p: refused, $why; the stub was kept" >>"$priv/notes-$st"
				continue
			fi
			mkdir -p "$scratch/$(dirname "$p")"
			cat -- "$c" >"$scratch/$p"
			[ "${c#"$sub"/}" = "$p" ] || echo "$p: taken from ${c#"$sub"/}" >>"$priv/notes-$st"
		done
	done
}

# A clean copy of the tree: sources only, no build/ and no .git.
make_scratch() {  # make_scratch SCRATCH
	local d
	[ ! -e "$1" ] || chmod -R u+rwX "$1" 2>/dev/null || true
	rm -rf "$1"
	mkdir -p "$1"
	for d in Makefile lib tests datasets lessons assignments solutions; do
		[ -e "$ROOT/$d" ] && cp -R "$ROOT/$d" "$1/"
	done
	rm -rf "$1/tests/grade/fixtures"
}

# ---- build and run -----------------------------------------------------------------

# make in the scratch tree with a clean environment: nothing from the caller's
# make (MAKEFLAGS carries command-line variables such as IMPL or SANITIZE), no
# CFLAGS or CC from the shell. Grading is never sanitized.
scratch_make() {  # scratch_make SCRATCH ARGS...
	local scratch=$1
	shift
	env -i PATH="$PATH" HOME="${HOME:-/tmp}" LC_ALL=C TERM=dumb \
		make -C "$scratch" --no-print-directory SANITIZE=0 "$@"
}

# The build variables for a stage: every stage the student's, or (isolate) only this
# one and the reference for the others. Printed one per line.
build_vars() {  # build_vars STAGE
	local nn=${1%%-*}
	if [ "$ISOLATE" = 1 ]; then
		printf '%s\n' "BUILD=build/grade-$nn" IMPL=solutions "IMPL_$nn=assignments"
	else
		printf '%s\n' BUILD=build/grade IMPL=assignments
	fi
}

# Build the stage's test binary; the compiler's output (without make's progress
# lines) goes to LOG. A failed parallel build is redone serially with -k, so the log
# lists every error in a stable order.
build_stage() {  # build_stage SCRATCH STAGE LOG
	local scratch=$1 st=$2 log=$3 vars bdir
	mapfile -t vars < <(build_vars "$st")
	bdir=${vars[0]#BUILD=}
	if scratch_make "$scratch" -j"$JOBS" "${vars[@]}" "$bdir/tests/$st" >"$log.raw" 2>&1; then
		: >"$log"
		return 0
	fi
	scratch_make "$scratch" -k "${vars[@]}" "$bdir/tests/$st" >"$log.raw" 2>&1 || true
	sed -E '/^  (CC|LD|AR) /d' "$log.raw" >"$log"
	return 1
}

# The graded objects may define only lz_ symbols and must not run code outside the
# calls the tests make (constructors, destructors). Prints the problems.
object_problems() {  # object_problems SCRATCH STAGE
	local dir o base src st
	dir=$1/$(build_vars "$2" | head -n 1 | cut -d= -f2)/obj/assignments
	for o in "$dir"/*.o; do
		[ -e "$o" ] || continue
		base=$(basename "$o" .o)
		src=$base
		for st in $ALL_STAGES; do
			[ "${base#"$st"-}" = "$base" ] || src="assignments/$st/${base#"$st"-}.c"
		done
		nm -g --defined-only "$o" | awk -v f="$src" '$NF !~ /^lz_/ {
			printf "%s defines the global symbol %s: a graded file may define only lz_ functions (make helpers static)\n", f, $NF }'
		if objdump -h "$o" | grep -Eq '\.(init_array|fini_array|preinit_array|ctors|dtors)'; then
			echo "$src has code that runs before or after main (a constructor or destructor): not allowed"
		fi
	done
}

# Run the stage's tests in machine mode under timeout and ulimit, from the scratch
# root, with the environment reset (CK_FORK=yes: a crash costs one test). The runner's
# stdout and stderr go to CAPTURE; the tests' own output to the log in the scratch
# tree, which is never read. Prints the exit status.
run_stage() {  # run_stage SCRATCH STAGE BUDGET CAPTURE
	local scratch=$1 st=$2 budget=$3 cap=$4 bdir args=() r status=0
	bdir=$(build_vars "$st" | head -n 1 | cut -d= -f2)
	for r in $(rubrics_of "$st"); do
		args+=(--rubric "$r")
	done
	(
		cd "$scratch" || exit 2
		ulimit -c 0 || true
		ulimit -f "$ULIMIT_F" || true
		ulimit -v "$ULIMIT_V" || true
		ulimit -t $((budget + 10)) || true
		exec env -i PATH="$PATH" HOME="${HOME:-/tmp}" LC_ALL=C CK_FORK=yes \
			timeout -k 5 "$budget" "$bdir/tests/$st" "${args[@]}" \
			--machine --log "$bdir/test-output.log"
	) >"$cap" 2>&1 </dev/null || status=$?
	echo "$status"
}

# ---- one submission ----------------------------------------------------------------

# Grade SUB (a directory, or '' after a refused tarball with REFUSED set) into a spec
# for lz-report in PRIV. Everything the student's code can touch is under SCRATCH.
grade_submission() {  # grade_submission SUB LABEL SCRATCH PRIV REFUSED
	local sub=$1 label=$2 scratch=$3 priv=$4 refused=$5 st spec=$4/spec
	echo "title $label" >"$spec"
	if [ -n "$refused" ]; then
		for st in $STAGES; do
			echo "the submission was refused: $refused" >"$priv/build-$st.log"
			{
				echo "stage $st"
				rubric_lines "$st"
				echo "build rejected $priv/build-$st.log"
			} >>"$spec"
		done
		return
	fi
	make_scratch "$scratch"
	copy_submission "$sub" "$scratch" "$priv"
	for st in $STAGES; do
		grade_stage "$scratch" "$st" "$priv" >>"$spec"
	done
	chmod -R u+rwX "$scratch" 2>/dev/null || true
	rm -rf "$scratch"
}

rubric_lines() {  # rubric_lines STAGE
	local r
	for r in $(rubrics_of "$1"); do
		echo "rubric $ROOT/$r"
	done
}

# Build, check and run one stage; print its part of the spec.
grade_stage() {  # grade_stage SCRATCH STAGE PRIV
	local scratch=$1 st=$2 priv=$3 log=$3/build-$2.log budget problems status n
	budget=$(budget_of "$st")
	echo "stage $st"
	rubric_lines "$st"
	while IFS= read -r n; do
		echo "note $n"
	done <"$priv/notes-$st"
	echo "grade: building $st" >&2
	if ! build_stage "$scratch" "$st" "$log"; then
		echo "build failed $log"
		return
	fi
	problems=$(object_problems "$scratch" "$st")
	if [ -n "$problems" ]; then
		echo "$problems" >"$log"
		echo "build rejected $log"
		return
	fi
	echo "build ok"
	echo "grade: running the tests of $st (at most $budget s)" >&2
	status=$(run_stage "$scratch" "$st" "$budget" "$priv/capture-$st")
	head -c "$MAX_CAPTURE" "$priv/capture-$st" >"$priv/results-$st"
	rm -f "$priv/capture-$st"
	printf 'results %s\nexit %s\nbudget %s\n' "$priv/results-$st" "$status" "$budget"
}

# ---- the output directory ------------------------------------------------------------

# Empty OUT: everything in it may have been written by a student's code. Only a
# directory this script made (it holds .lz-grade) or an empty one is cleared.
clear_out() {  # clear_out OUT
	local out=$1
	mkdir -p "$out"
	if [ ! -e "$out/.lz-grade" ] && [ -n "$(ls -A "$out")" ]; then
		die "refusing to clear $out: it was not made by the grader (no .lz-grade in it)"
	fi
	chmod -R u+rwX "$out" 2>/dev/null || true
	find "$out" -mindepth 1 -delete
	echo "lozenge grader output: cleared and rewritten on every grade" >"$out/.lz-grade"
}

# Resolve a submission into a directory; sets SUB_DIR and SUB_REFUSED.
resolve() {  # resolve PATH PRIV
	SUB_REFUSED=
	if [ -z "$1" ]; then
		SUB_DIR=$ROOT
	elif [ -d "$1" ]; then
		SUB_DIR=$(abspath "$1")
	elif [ -f "$1" ] && [[ $1 == *.tar.gz || $1 == *.tgz ]]; then
		SUB_DIR=
		SUB_REFUSED=$(tarball_problem "$1")
		[ -n "$SUB_REFUSED" ] && return
		SUB_DIR=$(unpack "$1" "$2/unpacked") || SUB_REFUSED="it could not be unpacked (too large, or damaged)"
	else
		die "submission '$1' is neither a directory nor a .tar.gz/.tgz file"
	fi
}

grade_one() {  # grade_one SUBMISSION
	local label=${1:-"this tree's assignments/"}
	resolve "$1" "$PRIV"
	grade_submission "$SUB_DIR" "$label" "$OUT/scratch" "$PRIV" "$SUB_REFUSED"
	clear_out "$OUT"
	"$REPORT" --out "$OUT" --spec "$PRIV/spec"
	echo "reports: $OUT/report.txt results.json junit.xml results.tap"
}

# The students of SUBS: sub-directories and tarballs, by name.
students_in() {  # students_in SUBS
	local e
	for e in "$1"/*; do
		if [ -d "$e" ] || [[ -f $e && ($e == *.tar.gz || $e == *.tgz) ]]; then
			echo "$e"
		fi
	done
}

student_name() {  # student_name ENTRY
	local n
	n=$(basename "$1")
	n=${n%.tar.gz}
	n=${n%.tgz}
	echo "$n"
}

grade_all() {  # grade_all SUBS
	local subs=$1 e name priv n=0
	[ -d "$subs" ] || die "--all $subs: not a directory"
	mkdir -p "$PRIV/reports"
	while IFS= read -r e; do
		name=$(student_name "$e")
		case $name in .* | *[!A-Za-z0-9._@+-]*) name=$(printf '%s' "$name" | tr -c 'A-Za-z0-9._@+-' '_') ;; esac
		[ ! -e "$PRIV/reports/$name" ] || die "two submissions are both named $name"
		priv=$PRIV/students/$name
		mkdir -p "$priv"
		echo "grade: == $name" >&2
		resolve "$e" "$priv"
		grade_submission "$SUB_DIR" "$name" "$OUT/scratch" "$priv" "$SUB_REFUSED"
		"$REPORT" --quiet --out "$PRIV/reports/$name" --spec "$priv/spec" \
			--gradebook "$PRIV/gradebook.csv" --student "$name"
		grep '^Score:' "$PRIV/reports/$name/report.txt" | sed "s/^/$name: /"
		n=$((n + 1))
	done < <(students_in "$subs" | sort)
	[ "$n" -gt 0 ] || die "--all $subs: no sub-directory or .tar.gz in it"
	clear_out "$OUT"
	mv "$PRIV/reports"/* "$OUT/"
	mv "$PRIV/gradebook.csv" "$OUT/gradebook.csv"
	echo
	cat "$OUT/gradebook.csv"
	echo "reports: $OUT/<student>/ and $OUT/gradebook.csv ($n students)"
}

# ---- main ------------------------------------------------------------------------------

BUILD_DIR='' SUBMISSION='' STAGE='' ISOLATE='' OUT='' ALL=''
while [ $# -gt 0 ]; do
	[ $# -ge 2 ] || usage
	case $1 in
	--build) BUILD_DIR=$2 ;;
	--submission) SUBMISSION=$2 ;;
	--stage) STAGE=$2 ;;
	--isolate) ISOLATE=$2 ;;
	--out) OUT=$2 ;;
	--all) ALL=$2 ;;
	*) usage ;;
	esac
	shift 2
done
[ -n "$BUILD_DIR" ] || usage
[ -z "$ALL" ] || [ -z "$SUBMISSION" ] || die "give --submission or --all, not both"
ISOLATE=${ISOLATE:-0}
case $ISOLATE in 0 | 1) ;; *) die "--isolate is 0 or 1, not '$ISOLATE'" ;; esac
if [ "$ISOLATE" = 1 ] && [ ! -d "$ROOT/solutions" ]; then
	die "ISOLATE=1 links the reference solutions for the stages not graded, and this tree has no solutions/ (a student handout): grade without ISOLATE"
fi
for tool in timeout tar nm objdump make; do
	command -v "$tool" >/dev/null || die "'$tool' is needed and not installed"
done

BUILD_DIR=$(abspath "$BUILD_DIR")
OUT=$(abspath "${OUT:-$BUILD_DIR/grade}")
[ -z "$SUBMISSION" ] || SUBMISSION=$(abspath "$SUBMISSION")
[ -z "$ALL" ] || ALL=$(abspath "$ALL")
REPORT=$BUILD_DIR/bin/lz-report
(cd "$ROOT" && make --no-print-directory BUILD="$BUILD_DIR" "$REPORT" >&2) ||
	die "cannot build $REPORT"
ALL_STAGES=$(select_stages "")
STAGES=$(select_stages "$STAGE")
# OUT is emptied: never the tree, a directory holding it, or one of its sources.
case $ROOT/ in "$OUT"/*) die "--out $OUT holds the source tree" ;; esac
case $OUT in "$ROOT"/build*) ;; "$ROOT"/*) die "--out $OUT: inside the sources (use a directory under build/)" ;; esac

# Private working files (specs, captured output, reports before they are moved): not
# under OUT, where the student's code runs.
PRIV=$(mktemp -d "${TMPDIR:-/tmp}/lz-grade.XXXXXX")
trap 'rm -rf "$PRIV" "$OUT/scratch"' EXIT
clear_out "$OUT"

if [ -n "$ALL" ]; then
	grade_all "$ALL"
else
	grade_one "$SUBMISSION"
fi
