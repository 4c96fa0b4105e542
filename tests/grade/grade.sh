#!/usr/bin/env bash
# grade.sh — the autograder. `make grade` and `make grade-all` call it.
#
#   grade.sh --build BUILD [--submission DIR|X.tar.gz|X.tgz] [--stage NN] [--isolate 0|1]
#            [--out DIR]
#   grade.sh --build BUILD --all SUBS [--stage NN] [--isolate 0|1] [--out DIR]
#
# A submission is a directory or a .tar.gz; empty means this tree's own assignments/
# (the stubs in the instructor's tree, the student's work in a handout). For each
# stage the files its tests/NN-name/MANIFEST lists are looked up in the submission at
# <path>, NN-name/<file> or <file> and copied onto a clean scratch copy of this tree.
#
# Every stage is graded on its own build, so one stage's mistakes cost that stage
# only:
#   - A file that cannot be taken — a symbolic or hard link, a special file, a path
#     with '..' or an absolute one (in a tarball such entries are never unpacked),
#     a file outside the submission or over 1 MiB — is refused: its stub is graded
#     in its place, and the stage's status says why. A missing file keeps its stub.
#   - Each stage's files are compiled on their own. A stage that does not compile, or
#     whose objects define anything but lz_ functions or run code before or after
#     main, scores 0, with the compiler's errors in its visible NN-name/build test;
#     the other stages link the reference for it, and their reports say so.
#   - Each stage's test program is linked and run on its own, under timeout and
#     ulimit (the runner gives every test its own process: a crash, a loop or a flood
#     costs that test only). A stage that links only against the reference of the
#     other stages is graded that way, and says so. --isolate 1 does that for every
#     stage, so an early bug is never charged twice.
# Then every file the student's code could have written is deleted, and lz-report,
# which links no student code, writes the reports from what this script captured
# itself: OUT/report.txt (and the table on stdout), results.json (Gradescope),
# junit.xml and results.tap. OUT defaults to BUILD/grade. --all grades every
# sub-directory and .tar.gz of SUBS into OUT/<student>/ and writes OUT/gradebook.csv
# (a score and a status per stage); its OUT defaults to BUILD/grade-all.
#
# What no student code touches — the library, the tests, the reference and the stubs
# — is compiled once into BUILD/grade-cache (rebuilt when the sources change) and
# copied into every scratch tree, so grading a class compiles only the students'
# files.
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
SOURCES="Makefile lib tests datasets lessons assignments solutions"

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

# The entries of a tarball that are never unpacked, as "NAME<TAB>why" lines into
# REFUSED; the entries that are, one per line, into ACCEPTED. Returns 1 when the file
# is not a readable .tar.gz.
read_tarball() {  # read_tarball FILE ACCEPTED REFUSED
	local listing=() names=() i why
	: >"$2"
	: >"$3"
	tar -tzf "$1" >/dev/null 2>&1 || return 1
	mapfile -t listing < <(tar -tvzf "$1" 2>/dev/null)
	mapfile -t names < <(tar -tzf "$1" 2>/dev/null)
	[ ${#listing[@]} -eq ${#names[@]} ] || return 1
	for i in "${!names[@]}"; do
		why=
		case ${listing[$i]:0:1} in
		- | d) ;;
		l) why="it is a symbolic link" ;;
		h) why="it is a hard link" ;;
		*) why="it is a special file" ;;
		esac
		case "/${names[$i]}/" in
		//*) why="it is an absolute path" ;;
		*/../*) why="its path has '..'" ;;
		esac
		if [ -n "$why" ]; then
			printf '%s\t%s\n' "${names[$i]}" "$why" >>"$3"
		elif [ "${listing[$i]:0:1}" = - ]; then
			printf '%s\n' "${names[$i]}" >>"$2"
		fi
	done
}

# Unpack the accepted regular files of FILE into DEST; print the directory that holds
# the submission (a tarball of one top-level directory is looked into).
unpack() {  # unpack FILE DEST ACCEPTED
	local dest=$2 only depth
	mkdir -p "$dest"
	if [ -s "$3" ]; then
		(ulimit -f $((100 * 1024)) && tar -xzf "$1" -C "$dest" --no-same-owner \
			--no-same-permissions --no-overwrite-dir --verbatim-files-from -T "$3") \
			>/dev/null 2>&1 || return 1
	fi
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

# Why the tarball entry that stands for a manifest path was not unpacked (empty when
# none does): an entry stands for assignments/NN-name/F.c when it ends in F.c and
# names no other stage.
entry_problem() {  # entry_problem STAGE PATH REFUSED
	local file=${2##*/} name why other st
	[ -s "$3" ] || return 0
	while IFS=$'\t' read -r name why; do
		[ "${name##*/}" = "$file" ] || continue
		other=0
		for st in $ALL_STAGES; do
			[ "$st" != "$1" ] && [[ /$name/ == */"$st"/* ]] && other=1
		done
		[ "$other" -eq 1 ] && continue
		echo "$why ($name)"
		return
	done <"$3"
}

# Copy every manifest file of every stage from the submission onto the scratch tree.
# For each stage PRIV/notes-STAGE gets the notes for its build test and
# PRIV/refused-STAGE the files that were refused.
copy_submission() {  # copy_submission SUB SCRATCH PRIV REFUSED_ENTRIES
	local sub=$1 scratch=$2 priv=$3 st p c why
	for st in $ALL_STAGES; do
		: >"$priv/notes-$st"
		: >"$priv/refused-$st"
		for p in $(manifest_of "$st"); do
			why=$(entry_problem "$st" "$p" "$4")
			c=
			[ -n "$why" ] || c=$(locate "$sub" "$st" "$p")
			[ -n "$why" ] || [ -z "$c" ] || why=$(file_problem "$sub" "$c")
			if [ -n "$why" ]; then
				echo "${p##*/}: $why" >>"$priv/refused-$st"
				echo "$p was refused ($why): its stub was graded instead" >>"$priv/notes-$st"
			elif [ -z "$c" ]; then
				echo "$p is not in the submission: its stub was graded" >>"$priv/notes-$st"
			else
				cat -- "$c" >"$scratch/$p"
			fi
		done
	done
}

# ---- the build cache ------------------------------------------------------------------

# What the cache depends on: the sources and the compiler.
source_key() {
	(
		cd "$ROOT"
		# shellcheck disable=SC2086
		find $SOURCES -path tests/grade/fixtures -prune -o -type f -print0 | sort -z |
			xargs -0 sha1sum
		cc --version 2>&1 | head -n 1
	) | sha1sum | cut -d' ' -f1
}

# BUILD/grade-cache/tree: a copy of the sources with every object that no student
# code affects, built for both implementations (stubs last, as a scratch tree starts).
prepare_cache() {
	local key new st targets=()
	key=$(source_key)
	[ "$(cat "$CACHE/key" 2>/dev/null)" = "$key" ] && return
	echo "grade: compiling the library, the tests, the reference and the stubs once into $CACHE" >&2
	new=$CACHE.new.$$
	rm -rf "$new"
	mkdir -p "$new/tree"
	# shellcheck disable=SC2086
	(cd "$ROOT" && cp -R $SOURCES "$new/tree/")
	rm -rf "$new/tree/tests/grade/fixtures"
	for st in $ALL_STAGES; do
		targets+=("build/grade/tests/$st")
	done
	{ [ ! -d "$ROOT/solutions" ] ||
		scratch_make "$new/tree" -j"$JOBS" BUILD=build/grade IMPL=solutions "${targets[@]}" \
			>"$new/build.log" 2>&1; } &&
		scratch_make "$new/tree" -j"$JOBS" BUILD=build/grade IMPL=assignments "${targets[@]}" \
			build/grade/bin/lz-report >>"$new/build.log" 2>&1 ||
		{ sed -E '/^  (CC|LD|AR) /d' "$new/build.log" | head -n 30 >&2; rm -rf "$new"; die "this tree does not build"; }
	echo "$key" >"$new/key"
	rm -rf "$CACHE"
	mv "$new" "$CACHE"
}

# A clean copy of the tree for one submission: the cached sources and objects, their
# times kept, so that only the files copied in afterwards are compiled again.
make_scratch() {  # make_scratch SCRATCH
	[ ! -e "$1" ] || chmod -R u+rwX "$1" 2>/dev/null || true
	rm -rf "$1"
	mkdir -p "$(dirname "$1")"
	cp -a "$CACHE/tree" "$1"
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

# The compiler's output of a make run, without make's progress lines.
compiler_output() {  # compiler_output RAW LOG
	sed -E '/^  (CC|LD|AR) /d; /^make(\[[0-9]+\])?: /d' "$1" >"$2"
}

# Compile the student's files of one stage, alone. Failures leave the compiler's
# errors in LOG (a serial -k rerun, so every error shows, in a stable order).
compile_stage() {  # compile_stage SCRATCH STAGE LOG
	local scratch=$1 st=$2 log=$3 objs=() f
	for f in "$scratch/assignments/$st"/*.c; do
		objs+=("build/grade/obj/assignments/$st-$(basename "$f" .c).o")
	done
	if scratch_make "$scratch" -j"$JOBS" BUILD=build/grade IMPL=assignments "${objs[@]}" \
		>"$log.raw" 2>&1; then
		return 0
	fi
	scratch_make "$scratch" -k BUILD=build/grade IMPL=assignments "${objs[@]}" >"$log.raw" 2>&1 || true
	compiler_output "$log.raw" "$log"
	return 1
}

# The graded objects may define only lz_ symbols and must not run code outside the
# calls the tests make (constructors, destructors). Prints the problems.
object_problems() {  # object_problems SCRATCH STAGE
	local o src
	for o in "$1/build/grade/obj/assignments/$2"-*.o; do
		[ -e "$o" ] || continue
		src=assignments/$2/$(basename "$o" .o | sed "s/^$2-//").c
		nm -g --defined-only "$o" | awk -v f="$src" '$NF !~ /^lz_/ {
			printf "%s defines the global symbol %s: a graded file may define only lz_ functions (make helpers static)\n", f, $NF }'
		if objdump -h "$o" | grep -Eq '\.(init_array|fini_array|preinit_array|ctors|dtors)'; then
			echo "$src has code that runs before or after main (a constructor or destructor): not allowed"
		fi
	done
}

# The implementation choice for one stage's test program: the student's code for
# the stages that compiled, the reference for the others; with ISOLATE (or ALONE)
# the reference for every stage but this one.
stage_vars() {  # stage_vars STAGE ALONE
	local st
	if [ "$ISOLATE" = 1 ] || [ "$2" = 1 ]; then
		printf '%s\n' IMPL=solutions "IMPL_${1%%-*}=assignments"
		return
	fi
	echo IMPL=assignments
	[ -d "$ROOT/solutions" ] || return 0
	for st in $BROKEN; do
		echo "IMPL_${st%%-*}=solutions"
	done
}

# Link the stage's test program; print how (student, alone) or fail with the errors
# in LOG. When the student's other stages do not link with it, try it alone.
link_stage() {  # link_stage SCRATCH STAGE LOG
	local scratch=$1 st=$2 log=$3 vars alone
	for alone in 0 1; do
		[ "$alone" = 1 ] && [ "$ISOLATE" = 1 ] && break
		mapfile -t vars < <(stage_vars "$st" "$alone")
		if scratch_make "$scratch" -j"$JOBS" BUILD=build/grade "${vars[@]}" \
			"build/grade/tests/$st" >"$log.raw" 2>&1; then
			cp "$scratch/build/grade/tests/$st" "$scratch/build/grade/tests/$st.graded"
			echo "$alone"
			return 0
		fi
	done
	compiler_output "$log.raw" "$log"
	return 1
}

# Run the stage's tests in machine mode under timeout and ulimit, from the scratch
# root, with the environment reset (CK_FORK=yes). The runner's stdout and stderr go
# to CAPTURE; the tests' own output to a log in the scratch tree, which is never
# read; the literature tables are the scratch tree's. The exit status goes to STATUS.
run_stage() {  # run_stage SCRATCH STAGE BUDGET CAPTURE STATUS
	local scratch=$1 st=$2 budget=$3 args=() r status=0
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
			LZ_REFERENCE_DIR="$scratch/datasets/reference" \
			timeout -k 5 "$budget" "build/grade/tests/$st.graded" "${args[@]}" \
			--machine --log "build/grade/$st-output.log"
	) >"$4" 2>&1 </dev/null || status=$?
	echo "$status" >"$5"
}

# ---- one submission ----------------------------------------------------------------

# Grade SUB (a directory, or '' for an unreadable tarball, with UNREADABLE saying why)
# into a spec for lz-report in PRIV. Everything the student's code can touch is under
# SCRATCH.
grade_submission() {  # grade_submission SUB LABEL SCRATCH PRIV UNREADABLE REFUSED_ENTRIES
	local sub=$1 label=$2 scratch=$3 priv=$4 st
	echo "title $label" >"$priv/spec"
	if [ -n "$5" ]; then
		for st in $STAGES; do
			echo "the submission could not be read: $5" >"$priv/build-$st.log"
			{ stage_head "$st" "$priv"; echo "build unreadable $priv/build-$st.log"; } >>"$priv/spec"
		done
		return
	fi
	make_scratch "$scratch"
	copy_submission "$sub" "$scratch" "$priv" "$6"
	compile_all "$scratch" "$priv"
	for st in $STAGES; do
		case " $BROKEN " in *" $st "*) continue ;; esac
		echo "grade: linking the tests of $st" >&2
		if link_stage "$scratch" "$st" "$priv/build-$st.log" >"$priv/alone-$st"; then
			echo linked >"$priv/state-$st"
		else
			echo nolink >"$priv/state-$st"
		fi
	done
	run_all "$scratch" "$priv"
	for st in $STAGES; do
		stage_spec "$st" "$priv" >>"$priv/spec"
	done
	chmod -R u+rwX "$scratch" 2>/dev/null || true
	rm -rf "$scratch"
}

# Compile every stage's files on its own; BROKEN lists the stages that did not
# compile or whose objects were refused. In a tree without the reference (a
# student's handout) a broken stage's files go back to the stubs, so that the other
# stages can still link.
compile_all() {  # compile_all SCRATCH PRIV
	local scratch=$1 priv=$2 st problems
	BROKEN=
	for st in $ALL_STAGES; do
		echo "grade: compiling $st" >&2
		if ! compile_stage "$scratch" "$st" "$priv/build-$st.log"; then
			echo failed >"$priv/state-$st"
			BROKEN="$BROKEN $st"
		else
			problems=$(object_problems "$scratch" "$st")
			[ -z "$problems" ] && continue
			echo "$problems" >"$priv/build-$st.log"
			echo rejected >"$priv/state-$st"
			BROKEN="$BROKEN $st"
		fi
		if [ ! -d "$ROOT/solutions" ]; then
			cp -a "$CACHE/tree/assignments/$st/." "$scratch/assignments/$st/"
			rm -f "$scratch/build/grade/obj/assignments/$st"-*.o
			cp -a "$CACHE/tree/build/grade/obj/assignments/$st"-*.o "$scratch/build/grade/obj/assignments/"
		fi
	done
}

# Run the linked stages, JOBS at a time.
run_all() {  # run_all SCRATCH PRIV
	local scratch=$1 priv=$2 st
	for st in $STAGES; do
		[ "$(cat "$priv/state-$st")" = linked ] || continue
		while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do
			wait -n || true
		done
		echo "grade: running the tests of $st (at most $(budget_of "$st") s)" >&2
		run_stage "$scratch" "$st" "$(budget_of "$st")" "$priv/capture-$st" "$priv/exit-$st" &
	done
	wait
	for st in $STAGES; do
		[ -e "$priv/capture-$st" ] || continue
		head -c "$MAX_CAPTURE" "$priv/capture-$st" >"$priv/results-$st"
		rm -f "$priv/capture-$st"
	done
}

stage_head() {  # stage_head STAGE PRIV: the spec lines every stage starts with
	local r n
	echo "stage $1"
	for r in $(rubrics_of "$1"); do
		echo "rubric $ROOT/$r"
	done
	if [ -f "$ROOT/tests/grade/hidden-points" ]; then
		awk -v s="$1" '$1 == s { print "hidden-elsewhere " $2 }' "$ROOT/tests/grade/hidden-points"
	fi
	while IFS= read -r n; do
		echo "note $n"
	done < <(cat "$2/notes-$1" 2>/dev/null)
	while IFS= read -r n; do
		echo "refused $n"
	done < <(cat "$2/refused-$1" 2>/dev/null)
}

# The spec of one stage, from what compile_all, link_stage and run_all left in PRIV.
stage_spec() {  # stage_spec STAGE PRIV
	local st=$1 priv=$2 b
	stage_head "$st" "$priv"
	case $(cat "$priv/state-$st") in
	failed) echo "build failed $priv/build-$st.log"; return ;;
	rejected) echo "build rejected $priv/build-$st.log"; return ;;
	nolink) echo "note its test program did not link (the linker's errors are below)"
		echo "build failed $priv/build-$st.log"; return ;;
	esac
	if [ "$(cat "$priv/alone-$st")" = 1 ]; then
		echo "note the code of the other stages did not link with this stage's tests: it was graded against the reference for every other stage"
	elif [ "$ISOLATE" = 1 ]; then
		echo "note graded on its own (ISOLATE=1): the reference was linked for every other stage"
	else
		for b in $BROKEN; do
			[[ $b < $st ]] || continue
			if [ -d "$ROOT/solutions" ]; then
				echo "note $b did not compile: its reference was linked so that this stage could be graded"
			else
				echo "note $b did not compile: its stubs were linked, so the tests here that use it fail"
			fi
		done
	fi
	echo "build ok"
	printf 'results %s\nexit %s\nbudget %s\n' "$priv/results-$st" "$(cat "$priv/exit-$st")" \
		"$(budget_of "$st")"
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

# Resolve a submission into a directory: sets SUB_DIR, SUB_UNREADABLE and, for a
# tarball, PRIV/refused-entries.
resolve() {  # resolve PATH PRIV
	SUB_UNREADABLE=
	: >"$2/refused-entries"
	if [ -z "$1" ]; then
		SUB_DIR=$ROOT
	elif [ -d "$1" ]; then
		SUB_DIR=$(abspath "$1")
	elif [ -f "$1" ] && [[ $1 == *.tar.gz || $1 == *.tgz ]]; then
		SUB_DIR=
		if ! read_tarball "$1" "$2/accepted-entries" "$2/refused-entries"; then
			SUB_UNREADABLE="it is not a readable .tar.gz"
			return
		fi
		SUB_DIR=$(unpack "$1" "$2/unpacked" "$2/accepted-entries") ||
			SUB_UNREADABLE="it could not be unpacked (too large, or damaged)"
	else
		die "submission '$1' is neither a directory nor a .tar.gz/.tgz file"
	fi
}

grade_one() {  # grade_one SUBMISSION
	local label=${1:-"this tree's assignments/"}
	resolve "$1" "$PRIV"
	grade_submission "$SUB_DIR" "$label" "$OUT/scratch" "$PRIV" "$SUB_UNREADABLE" \
		"$PRIV/refused-entries"
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
		grade_submission "$SUB_DIR" "$name" "$OUT/scratch" "$priv" "$SUB_UNREADABLE" \
			"$priv/refused-entries"
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
for tool in timeout tar nm objdump make sha1sum; do
	command -v "$tool" >/dev/null || die "'$tool' is needed and not installed"
done
if [ ! -d "$ROOT/solutions" ]; then
	SOURCES="Makefile lib tests datasets lessons assignments"
fi

BUILD_DIR=$(abspath "$BUILD_DIR")
if [ -n "$ALL" ]; then
	OUT=$(abspath "${OUT:-$BUILD_DIR/grade-all}")
else
	OUT=$(abspath "${OUT:-$BUILD_DIR/grade}")
fi
[ -z "$SUBMISSION" ] || SUBMISSION=$(abspath "$SUBMISSION")
[ -z "$ALL" ] || ALL=$(abspath "$ALL")
CACHE=$BUILD_DIR/grade-cache
ALL_STAGES=$(select_stages "")
STAGES=$(select_stages "$STAGE")
# OUT is emptied: never the tree, a directory holding it, or one of its sources.
case $ROOT/ in "$OUT"/*) die "--out $OUT holds the source tree" ;; esac
case $OUT in "$ROOT"/build*) ;; "$ROOT"/*) die "--out $OUT: inside the sources (use a directory under build/)" ;; esac
prepare_cache
REPORT=$CACHE/tree/build/grade/bin/lz-report

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
