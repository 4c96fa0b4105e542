#!/usr/bin/env bash
# submit.sh — `make submit`: the student's submission, exactly what the grader reads.
#
#   submit.sh BUILD
#
# Packs the files the stages' tests/NN-name/MANIFEST list — and nothing else: no
# build output, no notes, no editor backups — into BUILD/submit/lozenge-submission.tar.gz
# as assignments/NN-name/F.c, and lists them, each with the functions still left as
# stubs and whether it compiles. A file the grader would refuse (a symbolic link, not
# a regular file, over 1 MiB) stops it with the reason, so that what is uploaded is
# what is graded. `make grade SUBMISSION=<the tarball>` grades it as the instructor
# will (with the public tests only, in a student's tree).
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$ROOT"
need_args $# 1 1 "submit.sh BUILD"
BUILD=$1
OUT=$BUILD/submit/lozenge-submission.tar.gz
MAX_FILE=$((1024 * 1024))  # bytes, as the grader
make_tmp

files=()
bad=0
for m in tests/[0-9][0-9]-*/MANIFEST; do
	while read -r p; do
		p=${p%%#*}
		p=$(printf '%s' "$p" | tr -d ' \t\r')
		[ -n "$p" ] || continue
		if [ -L "$p" ]; then
			echo "submit: $p is a symbolic link; the grader refuses links: put the file itself there" >&2
			bad=1
		elif [ ! -f "$p" ]; then
			echo "submit: $p is missing (or not a regular file): restore it (its stub scores 0, but it must be there)" >&2
			bad=1
		elif [ "$(stat -c %s -- "$p")" -gt "$MAX_FILE" ]; then
			echo "submit: $p is larger than 1 MiB; the grader refuses it" >&2
			bad=1
		else
			files+=("$p")
		fi
	done <"$m"
done
[ "$bad" -eq 0 ] || { echo "submit: nothing was packed" >&2; exit 1; }
[ ${#files[@]} -gt 0 ] || { echo "submit: no MANIFEST names a file" >&2; exit 1; }

# Does each stage's code compile? (Objects in a build directory of its own.)
declare -A COMPILES
for st in $(printf '%s\n' "${files[@]}" | cut -d/ -f2 | sort -u); do
	objs=()
	for f in "${files[@]}"; do
		[[ $f == assignments/$st/* ]] && objs+=("$BUILD/submit/obj/obj/assignments/$st-$(basename "$f" .c).o")
	done
	if make --no-print-directory BUILD="$BUILD/submit/obj" IMPL=assignments "${objs[@]}" \
		>"$tmp/$st.log" 2>&1; then
		COMPILES[$st]=yes
	else
		COMPILES[$st]=no
		grep -m 3 'error' "$tmp/$st.log" | sed 's/^/            /' >"$tmp/$st.errors" || true
	fi
done

mkdir -p "$(dirname "$OUT")"
tar --sort=name --owner=0 --group=0 --numeric-owner --mtime=@0 -cf - "${files[@]}" |
	gzip -n -9 >"$OUT.tmp"
mv "$OUT.tmp" "$OUT"

echo "submit: $OUT holds these ${#files[@]} files, and nothing else:"
last=
for f in "${files[@]}"; do
	st=$(echo "$f" | cut -d/ -f2)
	if [ "$st" != "$last" ] && [ "${COMPILES[$st]}" = no ]; then
		echo "  $st DOES NOT COMPILE: the grader will score it 0. The first errors:"
		cat "$tmp/$st.errors"
	fi
	last=$st
	left=$(grep -c '^[[:space:]]*LZ_TODO();' "$f" || true)
	if [ "$left" -eq 0 ]; then
		echo "  $f"
	else
		echo "  $f ($left function(s) still LZ_TODO())"
	fi
done
echo "submit: upload that file. To see the grade it gets: make grade SUBMISSION=$OUT"
