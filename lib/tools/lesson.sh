#!/usr/bin/env bash
# lesson.sh STAGE_NAME BUILD QUICK — run one lesson's experiments (make lesson STAGE=NN).
#
#   1. every experiment driver built from lessons/STAGE/*.c, alphabetically, as
#      BUILD/lessons/NN/bin/NAME OUTDIR [--quick], its output kept in OUTDIR/NAME.log;
#   2. every scene datasets/scenes/NN-*.scene, as lz run SCENE --out OUTDIR/runs/NAME;
#   3. every plot script lessons/STAGE/*.gp, with gnuplot running inside OUTDIR
#      (skipped with a note when gnuplot is not installed), so a plot may draw the
#      drivers' data and the scene runs' (runs/NAME/*.dat).
# OUTDIR is BUILD/lessons/NN. QUICK=1 runs the demo size. Exit status 1 when any
# step failed (the table at the end says which).
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
rm -rf "$out/runs"

rows=()    # "kind|name|status|seconds|made" for the table
failed=()  # names of failed steps

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
# A plot without data is not counted: the experiment that failed to write it is.
record() {
	rows+=("$1|$2|$3|$4|$5")
	case $3 in
		ok | skipped | "no data") ;;
		*) failed+=("$2") ;;
	esac
}

# Why a driver failed, in one phrase, from its log.
diagnose() {
	local log=$1 rc=$2
	if grep -q "not implemented" "$log"; then
		echo "stub: $(grep -m1 -o 'not implemented: [^ ]*' "$log")"
	elif grep -q "CHECK FAILED" "$log"; then
		echo "a check against known values failed"
	elif [ "$rc" -ge 128 ]; then
		echo "crashed (signal $((rc - 128)))"
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
	"$exe" "$out" "${quick_flag[@]}" 2>&1 | tee "$out/$name.log" || rc=$?
	secs=$(elapsed "$t0" "$(now)")
	made=$(find "$out" -maxdepth 1 -type f -newer "$out/.start" \( -name '*.dat' -o -name '*.json' \) | wc -l)
	if [ "$rc" = 0 ]; then
		record driver "$name" ok "$secs" "$made data files"
	else
		record driver "$name" "FAILED" "$secs" "$(diagnose "$out/$name.log" "$rc")"
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
		"$lz" run "$scene" --out "$out/runs/$name" --quiet >"$out/$name.scene.log" 2>&1 || rc=$?
		secs=$(elapsed "$t0" "$(now)")
		if [ "$rc" = 0 ] && [ -f "$out/runs/$name/summary.json" ]; then
			record scene "$name" ok "$secs" "runs/$name/summary.json"
		else
			record scene "$name" FAILED "$secs" "$(head -c 120 "$out/$name.scene.log" | head -1)"
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
		(cd "$out" && gnuplot "$root/$gp") >"$out/$name.gp.log" 2>&1 || rc=$?
		secs=$(elapsed "$t0" "$(now)")
		if grep -q -e "Cannot find or open file" -e "Cannot load input from" "$out/$name.gp.log"; then
			# Empty axes would pass for a result: no plot without its data.
			rm -f "$out/$name.png"
			record plot "$name.png" "no data" "$secs" "its data is missing (an experiment above failed)"
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
	if printf '%s\n' "${rows[@]}" | grep -q "not implemented"; then
		echo "  Some steps stopped at a function that is still a stub (\"not implemented\"):" >&2
		echo "  that is expected until you have written it." >&2
	fi
	echo "  Run \`make test STAGE=$nn\` (add IMPL=assignments for your own code) first:" >&2
	echo "  the tests say what is wrong in physics words. Logs: $out/*.log" >&2
	exit 1
fi
