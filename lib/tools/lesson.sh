#!/usr/bin/env bash
# lesson.sh STAGE_NAME BUILD QUICK — run one lesson's experiments (make lesson STAGE=NN).
#
#   1. every experiment driver built from lessons/STAGE/*.c, alphabetically, as
#      BUILD/lessons/NN/bin/NAME OUTDIR [--quick], its output kept in OUTDIR/NAME.log;
#   2. every scene datasets/scenes/NN-*.scene, as lz run SCENE --out OUTDIR/runs/NAME;
#   3. every plot script lessons/STAGE/*.gp, with gnuplot running inside OUTDIR
#      (skipped with a note when gnuplot is not installed), so a plot may draw the
#      drivers' data and the scene runs' (runs/NAME/*.dat).
# OUTDIR is BUILD/lessons/NN. QUICK=1 runs the demo size. The data of a driver or a
# scene that fails (an exit status other than 0, a crash, a failed check) are moved
# to OUTDIR/failed/NAME/, so that no plot draws them: a plot that needs them is marked
# FAILED with the step it waited for. Exit status 1 when any step failed (the table at
# the end says which, and why).
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
need_args $# 2 3 'lesson.sh STAGE_NAME BUILD [QUICK]   e.g. lesson.sh 01-lozenge build 1'
stage=$1
build=$2
quick=${3:-}
nn=${stage%%-*}
lesson_dir=lessons/$stage
out=$build/lessons/$nn
bindir=$out/bin
lz=$build/bin/lz
root=$PWD

if [ ! -d "$lesson_dir" ]; then
	echo "lesson.sh: no lesson directory $lesson_dir" >&2
	exit 2
fi
quick_flag=()
size="full size"
if [ "$quick" = 1 ]; then
	quick_flag=(--quick)
	size="demo size"
fi

# Results of an earlier run must not pass for this run's (bin/ is make's).
mkdir -p "$out"
find "$out" -maxdepth 1 -type f \( -name '*.dat' -o -name '*.png' -o -name '*.json' \
	-o -name '*.log' -o -name '*.gp' \) -delete
rm -rf "$out/runs" "$out/failed"

rows=()    # "kind|name|status|seconds|made" for the table
failed=()  # names of failed steps
declare -A made_by  # a data file (relative to OUTDIR) -> "driver NAME" or "scene NAME"
declare -A broken   # a step that failed ("driver NAME") -> why, in one phrase

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
record() {
	rows+=("$1|$2|$3|$4|$5")
	case $3 in
		ok | skipped) ;;
		*) failed+=("$2") ;;
	esac
}

# The step that should have written a data file gnuplot could not open: a failed one
# by name, or the file itself when no step wrote it.
missing_data() {  # missing_data GNUPLOT_LOG: one phrase
	local f step steps=() files=()
	while IFS= read -r f; do
		step=${made_by[$f]:-}
		[ -n "$step" ] || [[ $f != runs/*/* ]] || step=${made_by[runs/$(echo "$f" | cut -d/ -f2)/]:-}
		if [ -n "$step" ] && [ -n "${broken[$step]:-}" ]; then
			[[ " ${steps[*]} " == *" $step "* ]] || steps+=("$step")
		else
			files+=("$f")
		fi
	done < <(sed -n -e 's/.*Cannot find or open file "\([^"]*\)".*/\1/p' \
		-e "s/.*Cannot load input from '\\([^']*\\)'.*/\\1/p" "$1" | sort -u)
	if [ ${#steps[@]} -gt 0 ]; then
		echo "needs the data of the failed $(printf '%s, ' "${steps[@]}" | sed 's/, $//')"
	elif [ ${#files[@]} -gt 0 ]; then
		echo "reads ${files[*]}, which no step wrote"
	else
		echo "its data is missing; see $1"
	fi
}

# A failed step's data files (and plot settings it wrote, *.gp) go to OUTDIR/failed/NAME/: kept for a look, drawn by no plot.
set_aside() {  # set_aside NAME FILE... (relative to OUTDIR)
	local f
	[ $# -gt 1 ] || return 0
	mkdir -p "$out/failed/$1"
	for f in "${@:2}"; do
		mkdir -p "$out/failed/$1/$(dirname "$f")"
		mv "$out/$f" "$out/failed/$1/$f"
	done
}

# The steps below run in a subshell whose own stderr is dropped: it is where the shell
# reports a program killed by a signal ("line 71: 1234 Aborted ..."), which the table
# says in words instead. Only the program's exit status comes out.
# A driver: its output (stderr too) to the terminal and to LOG.
run_driver() {  # run_driver EXE LOG
	(
		"$1" "$out" "${quick_flag[@]}" 2>&1
		exit $?
	) 2>/dev/null | tee "$2"
}
# A scene or a plot: CMD run in DIR, its output to LOG only.
run_logged() {  # run_logged DIR LOG CMD...
	local log
	log=$(realpath -m "$2")
	(
		cd "$1" && "${@:3}" >"$log" 2>&1
		exit $?
	) 2>/dev/null
}

# Why a driver failed, in one phrase, from its log and its exit status.
diagnose() {  # diagnose LOG STATUS
	local log=$1 rc=$2
	if grep -q "not implemented" "$log"; then
		echo "exit status $rc, stub: $(grep -m1 -o 'not implemented: [^ ]*' "$log")"
	elif grep -q "CHECK FAILED" "$log"; then
		echo "exit status $rc, a check against known values failed"
	elif [ "$rc" -gt 128 ]; then
		echo "exit status $rc, crashed (signal $((rc - 128)), SIG$(kill -l $((rc - 128)) 2>/dev/null || echo '?'))"
	else
		echo "exit status $rc"
	fi
}

echo "== lesson $stage ($size): experiments -> $out"
shopt -s nullglob
for src in "$lesson_dir"/*.c; do
	name=$(basename "$src" .c)
	exe=$bindir/$name
	if [ ! -x "$exe" ]; then
		record driver "$name" "not built" 0 "-"
		echo "-- $name: $exe is missing (run make first)"
		continue
	fi
	echo "-- $name"
	t0=$(now)
	touch "$out/.start"
	rc=0
	run_driver "$exe" "$out/$name.log" || rc=$?
	secs=$(elapsed "$t0" "$(now)")
	mapfile -t made < <(cd "$out" && find . -maxdepth 1 -type f -newer .start \
		\( -name '*.dat' -o -name '*.json' -o -name '*.gp' \) | sed 's|^\./||' | sort)
	for f in "${made[@]}"; do
		made_by[$f]="driver $name"
	done
	if [ "$rc" = 0 ]; then
		record driver "$name" ok "$secs" "${#made[@]} data files"
	else
		why=$(diagnose "$out/$name.log" "$rc")
		broken["driver $name"]=$why
		set_aside "$name" "${made[@]}"
		record driver "$name" "FAILED" "$secs" "$why; log $out/$name.log"
		echo "-- $name FAILED: $why (log: $out/$name.log)" >&2
	fi
done
rm -f "$out/.start"

echo "== scenes"
scenes=(datasets/scenes/"$nn"-*.scene)
if [ ${#scenes[@]} = 0 ]; then
	echo "-- no scenes datasets/scenes/$nn-*.scene"
elif [ ! -x "$lz" ]; then
	for scene in "${scenes[@]}"; do
		record scene "$(basename "$scene" .scene)" "not built" 0 "$lz is missing"
	done
else
	for scene in "${scenes[@]}"; do
		name=$(basename "$scene" .scene)
		echo "-- $name"
		t0=$(now)
		rc=0
		run_logged . "$out/$name.scene.log" "$lz" run "$scene" --out "$out/runs/$name" --quiet || rc=$?
		secs=$(elapsed "$t0" "$(now)")
		made_by["runs/$name/"]="scene $name"
		if [ "$rc" = 0 ] && [ -f "$out/runs/$name/summary.json" ]; then
			record scene "$name" ok "$secs" "runs/$name/summary.json"
		else
			why=$(head -c 120 "$out/$name.scene.log" | head -1)
			[ "$rc" != 0 ] || why="no summary.json written"
			why="exit status $rc${why:+: $why}"
			broken["scene $name"]=$why
			[ ! -d "$out/runs/$name" ] || set_aside "$name" "runs/$name"
			record scene "$name" FAILED "$secs" "$why; log $out/$name.scene.log"
			echo "-- $name FAILED (log: $out/$name.scene.log)" >&2
		fi
	done
fi

echo "== plots"
if ! command -v gnuplot >/dev/null 2>&1; then
	for gp in "$lesson_dir"/*.gp; do
		record plot "$(basename "$gp" .gp).png" skipped 0 "gnuplot is not installed"
	done
	echo "-- gnuplot is not installed: plots skipped (make deps installs it)"
else
	for gp in "$lesson_dir"/*.gp; do
		name=$(basename "$gp" .gp)
		t0=$(now)
		rm -f "$out/$name.png"
		rc=0
		run_logged "$out" "$out/$name.gp.log" gnuplot "$root/$gp" || rc=$?
		secs=$(elapsed "$t0" "$(now)")
		if grep -q -e "Cannot find or open file" -e "Cannot load input from" "$out/$name.gp.log"; then
			# Empty axes would pass for a result: no plot without its data.
			rm -f "$out/$name.png"
			record plot "$name.png" FAILED "$secs" "$(missing_data "$out/$name.gp.log")"
		elif [ "$rc" = 0 ] && [ -s "$out/$name.png" ]; then
			record plot "$name.png" ok "$secs" "$(du -k "$out/$name.png" | cut -f1) kB"
		else
			record plot "$name.png" FAILED "$secs" "see $out/$name.gp.log"
			sed 's/^/   /' "$out/$name.gp.log" | head -5
		fi
	done
fi

echo
echo "== lesson $stage ($size): what was made in $out"
printf '%-7s %-24s %-10s %8s  %s\n' step name status seconds result
for row in "${rows[@]}"; do
	IFS='|' read -r kind name status secs made <<<"$row"
	printf '%-7s %-24s %-10s %8s  %s\n' "$kind" "$name" "$status" "$secs" "$made"
done
if [ ${#failed[@]} -gt 0 ]; then
	echo
	echo "lesson $stage: ${#failed[@]} step(s) failed: ${failed[*]}" >&2
	for step in "${!broken[@]}"; do
		echo "  $step: ${broken[$step]}" >&2
	done | sort >&2
	if printf '%s\n' "${rows[@]}" | grep -q "not implemented"; then
		echo "  Some steps stopped at a function that is still a stub (\"not implemented\"):" >&2
		echo "  that is expected until you have written it." >&2
	fi
	# The tests of the code this lesson ran on: in the instructor's tree (solutions/
	# present) a lesson of the stubs was asked for with IMPL=assignments.
	impl_flag=
	[ -d solutions ] && [ "$(impl_of "$build" "$nn")" = assignments ] && impl_flag=" IMPL=assignments"
	echo "  Run \`make test STAGE=$nn$impl_flag\` first: the tests say what is wrong in physics" >&2
	echo "  words. Logs: $out/*.log; the failed steps' data: $out/failed/" >&2
	exit 1
fi
