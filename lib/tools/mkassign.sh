#!/usr/bin/env bash
# mkassign.sh — generate the student stubs from the reference solutions (lib/README.md, "Assignments").
#
#   mkassign.sh SRC_ROOT DST_ROOT [--check]
#
# For every SRC_ROOT/NN-name/*.c it writes DST_ROOT/NN-name/*.c: the text outside the
# markers verbatim; each reference body (from the line with the solution-begin marker
# to the line with the solution-end marker) replaced by one `LZ_TODO();` line at the
# begin marker's indentation; each block of private helpers (helpers-begin to
# helpers-end) dropped; and a first comment that tells the student what the file is.
# Stale DST .c files without a source are removed. Files are only rewritten when
# their content changes, so `make` rebuilds nothing after a no-op run.
# --check writes nothing: it generates into a temporary directory and compares.
#
# The marker names are assembled here rather than spelled out, so that this script
# (which is in the student handout) never contains them: the handout's self-check
# greps the whole tarball for them.
set -euo pipefail

SOL_BEGIN="LZ_SOLUTION""_BEGIN"
SOL_END="LZ_SOLUTION""_END"
HLP_BEGIN="LZ_HELPERS""_BEGIN"
HLP_END="LZ_HELPERS""_END"

usage() {
	echo "usage: mkassign.sh SRC_ROOT DST_ROOT [--check]" >&2
	exit 2
}

die() {
	echo "mkassign: $*" >&2
	exit 1
}

# The generated first comment. It names the stage's lesson and test command.
banner() {  # banner NN-name
	local stage=$1 nn=${1%%-*}
	cat <<BANNER
/* YOUR FILE — this is the file you fill in for stage $stage.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/$stage/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with \`make test STAGE=$nn\`; see your own code at work with
 * \`make lesson STAGE=$nn\`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

BANNER
}

# Transform one file to stdout; on a marker error print "file:line: why" and exit 1.
strip_file() {  # strip_file SRC DISPLAY_NAME
	awk -v name="$2" -v sb="$SOL_BEGIN" -v se="$SOL_END" -v hb="$HLP_BEGIN" -v he="$HLP_END" '
	function fail(msg, line) { printf "%s:%d: %s\n", name, line ? line : FNR, msg > "/dev/stderr"; bad = 1; exit 1 }
	function count(s,   n) { n = 0; if (index($0, sb)) n++; if (index($0, se)) n++;
	                         if (index($0, hb)) n++; if (index($0, he)) n++; return n }
	{
		n = count()
		if (n > 1) fail("two markers on one line")
		if (index($0, sb)) {
			if (state != "") fail(sb " inside an open " state " block (opened at line " opened ")")
			state = sb; opened = FNR; nsol++
			match($0, /^[ \t]*/)
			print substr($0, 1, RLENGTH) "LZ_TODO();"
			next
		}
		if (index($0, hb)) {
			if (state != "") fail(hb " inside an open " state " block (opened at line " opened ")")
			state = hb; opened = FNR
			next
		}
		if (index($0, se)) {
			if (state != sb) fail(se " without a matching " sb)
			state = ""; next
		}
		if (index($0, he)) {
			if (state != hb) fail(he " without a matching " hb)
			state = ""; next
		}
		if (state == "") print
	}
	END {
		if (bad) exit 1
		if (state != "") fail(state " is never closed", opened)
		if (nsol == 0) fail("no " sb " marker: a graded file would be copied with its reference bodies", 1)
	}' "$1"
}

# Generate every stub of SRC into the (empty) directory OUT.
generate() {  # generate SRC OUT
	local src=$1 out=$2 f stage base found=0
	for f in "$src"/[0-9][0-9]-*/*.c; do
		[ -e "$f" ] || continue
		found=1
		stage=$(basename "$(dirname "$f")")
		base=$(basename "$f")
		mkdir -p "$out/$stage"
		{ banner "$stage"; strip_file "$f" "$f"; } >"$out/$stage/$base.tmp" || exit 1
		mv "$out/$stage/$base.tmp" "$out/$stage/$base"
	done
	[ "$found" -eq 1 ] || die "no $src/NN-name/*.c files: nothing to generate from"
}

# The stage-relative paths (NN-name/file.c) of the generated files in a root.
list_c() {  # list_c ROOT
	[ -d "$1" ] || return 0
	(cd "$1" && for f in [0-9][0-9]-*/*.c; do [ -e "$f" ] && echo "$f"; done) | LC_ALL=C sort
}

check() {  # check GENERATED DST
	local gen=$1 dst=$2 f bad=0
	while read -r f; do
		if [ ! -f "$dst/$f" ]; then
			echo "mkassign: $dst/$f is missing"; bad=1
		elif ! cmp -s "$gen/$f" "$dst/$f"; then
			echo "mkassign: $dst/$f differs from what $SRC/$f generates:"
			diff -u --label "$dst/$f" --label "generated" "$dst/$f" "$gen/$f" | head -n 20
			bad=1
		fi
	done < <(list_c "$gen")
	while read -r f; do
		[ -f "$gen/$f" ] || { echo "mkassign: $dst/$f has no source $SRC/$f (stale)"; bad=1; }
	done < <(list_c "$dst")
	if [ "$bad" -ne 0 ]; then
		echo "mkassign: $dst/ is out of date: run \`make assignments\` (and commit the result)"
		exit 1
	fi
	echo "mkassign: $dst/ is up to date with $SRC/ ($(list_c "$gen" | wc -l) files)"
}

install_into() {  # install_into GENERATED DST
	local gen=$1 dst=$2 f changed=0 removed=0
	while read -r f; do
		if ! cmp -s "$gen/$f" "$dst/$f" 2>/dev/null; then
			mkdir -p "$dst/$(dirname "$f")"
			cp "$gen/$f" "$dst/$f"
			echo "  GEN     $dst/$f"
			changed=$((changed + 1))
		fi
	done < <(list_c "$gen")
	while read -r f; do
		if [ ! -f "$gen/$f" ]; then
			rm -f "$dst/$f"
			echo "  RM      $dst/$f (no source)"
			removed=$((removed + 1))
			rmdir "$dst/$(dirname "$f")" 2>/dev/null || true
		fi
	done < <(list_c "$dst")
	echo "mkassign: $dst/ up to date ($changed written, $removed removed)"
}

[ $# -eq 2 ] || [ $# -eq 3 ] || usage
SRC=${1%/}
DST=${2%/}
MODE=${3:-write}
[ "$MODE" = write ] || [ "$MODE" = --check ] || usage
# A student tree has no solutions/: never wipe the student's own work from there.
[ -d "$SRC" ] || die "$SRC/ is not here (a student tree has only the assignments, which are yours to edit): nothing to generate"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
generate "$SRC" "$tmp"
if [ "$MODE" = --check ]; then
	check "$tmp" "$DST"
else
	mkdir -p "$DST"
	install_into "$tmp" "$DST"
fi
