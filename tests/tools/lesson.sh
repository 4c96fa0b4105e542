#!/usr/bin/env bash
# tests/tools/lesson.sh — what `make lesson` (lib/tools/lesson.sh) says when a driver fails.
#
# A fake lesson, lessons/99-fake/ in a temporary tree, with three drivers (shell
# scripts in place of the compiled ones): `good` writes good.dat and exits 0,
# `crash` writes crash.dat and plot settings crash_axes.gp and aborts (SIGABRT), `stub`
# stops as a stub does. Its plots draw good.dat, crash.dat, both, and the settings.
# Checked: the run exits 1; each failed driver's row names its exit status, the reason
# and its log; its data moved to failed/NAME/;
# the plots that need them are FAILED, naming the driver, and have no PNG; the good
# plot is ok; no raw report of the shell ("line 71: ... Aborted") reaches the
# terminal. Then a run with the good driver alone exits 0. Prints "N passed, M failed".
# The drivers' bodies are single-quoted: they expand when the drivers run.
# shellcheck disable=SC2016
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"
need_args $# 0 0 "tests/tools/lesson.sh"
passed=0
failed=0
make_tmp

expect() {  # expect WHAT COMMAND...: one check
	if "${@:2}"; then
		passed=$((passed + 1))
	else
		failed=$((failed + 1))
		echo "  FAIL  $1"
	fi
}
has() { grep -qE -- "$1" "$tmp/out"; }
row() { grep -E "^$1 +$2 " "$tmp/out" | grep -qE -- "$3"; }  # row KIND NAME REGEX

tree=$tmp/tree
mkdir -p "$tree/lessons/99-fake" "$tree/build/lessons/99/bin"
driver() {  # driver NAME BODY: the source (never compiled) and its stand-in executable
	echo "/* $1: a stand-in */" >"$tree/lessons/99-fake/$1.c"
	printf '#!/usr/bin/env bash\nout=$1\n%s\n' "$2" >"$tree/build/lessons/99/bin/$1"
	chmod +x "$tree/build/lessons/99/bin/$1"
}
plot() {  # plot NAME DATA...: a script drawing column 1:2 of each data file
	local files
	files=$(printf "'%s' u 1:2 w l, " "${@:2}")
	printf 'set terminal pngcairo size 300,200\nset output "%s.png"\nplot %s\n' \
		"$1" "${files%, }" >"$tree/lessons/99-fake/$1.gp"
}
driver good 'printf "0 0\n1 1\n" >"$out/good.dat"; echo "good: done"'
driver crash 'printf "0 0\n1 2\n" >"$out/crash.dat"; echo "ymax = 2" >"$out/crash_axes.gp"
echo "crash: half way"; kill -ABRT $$'
driver stub 'echo "not implemented: lz_fake_step (assignments/99-fake/fake.c)" >&2; exit 1'
plot good good.dat
plot crash crash.dat
plot both good.dat crash.dat
printf 'load "crash_axes.gp"\n' >>"$tree/lessons/99-fake/both.gp"
printf 'set terminal pngcairo size 300,200\nset output "axes.png"\nload "crash_axes.gp"\nplot x\n' \
	>"$tree/lessons/99-fake/axes.gp"

status=0
(cd "$tree" && bash "$ROOT/lib/tools/lesson.sh" 99-fake build) >"$tmp/out" 2>&1 || status=$?
out=$tree/build/lessons/99
expect "a failed driver makes the run exit 1 (got $status)" [ "$status" = 1 ]
expect "the crashed driver's row: exit status, signal, log" \
	row driver crash "FAILED +[0-9.]+ +exit status 134, crashed \(signal 6, SIGABRT\); log .*/crash.log"
expect "the stub's row: exit status and the stub" \
	row driver stub "FAILED .*exit status 1, stub: not implemented: lz_fake_step"
expect "the good driver is ok" row driver good "ok +[0-9.]+ +1 data files"
expect "no raw report of the shell reaches the terminal" eval '! has "Aborted|line [0-9]+:"'
expect "the crashed driver's data are set aside" [ -f "$out/failed/crash/crash.dat" ]
expect "and are not where a plot finds them" [ ! -e "$out/crash.dat" ]
expect "the summary names the failed drivers and why" has "^  driver crash: exit status 134"
if command -v gnuplot >/dev/null 2>&1; then
	expect "the plot of the good data is ok" row plot good.png "ok "
	expect "the plot of the crashed driver's data is FAILED, naming it" \
		row plot crash.png "FAILED .*needs the data of the failed driver crash"
	expect "a plot that needs both is FAILED too" row plot both.png "FAILED .*driver crash"
	expect "a plot that loads settings the crashed driver wrote is FAILED, naming it" \
		row plot axes.png "FAILED .*needs the data of the failed driver crash"
	expect "no PNG stands for a failed plot" eval '[ ! -e "$out/crash.png" ] && [ ! -e "$out/both.png" ]'
fi

cp "$tmp/out" "$tmp/first"
rm "$tree/lessons/99-fake/"{crash,stub}.c "$tree/lessons/99-fake/"{crash,both,axes}.gp
status=0
(cd "$tree" && bash "$ROOT/lib/tools/lesson.sh" 99-fake build) >"$tmp/out" 2>&1 || status=$?
expect "a run whose steps all succeed exits 0 (got $status)" [ "$status" = 0 ]
expect "and leaves nothing set aside" [ ! -e "$out/failed" ]

[ "$failed" = 0 ] || { echo "  the first run's output:"; sed 's/^/    /' "$tmp/first"; }
echo "lesson tool: $passed passed, $failed failed"
[ "$failed" = 0 ]
