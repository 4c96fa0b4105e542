# shellcheck shell=bash
# common.sh — the preamble and helpers shared by the shell tools: the lesson, demo,
# slides and handout tools (lib/tools/*.sh) and the grader (tests/grade/*.sh).
# Sourced, first thing, as
#
#   . "$(dirname "${BASH_SOURCE[0]}")/common.sh"                    (from lib/tools)
#   . "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"   (from tests/grade)
#
# It sets strict mode and the C locale (stable sort order and messages) and ROOT, the
# tree root. It does not change directory: grade.sh resolves its arguments against
# the caller's directory first; the others `cd "$ROOT"` themselves.
set -euo pipefail
export LC_ALL=C

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

# Exit 2 with the usage line unless the script got MIN to MAX arguments (MAX: a
# number, or `any`).
need_args() {  # need_args NARGS MIN MAX USAGE
	[ "$1" -ge "$2" ] && { [ "$3" = any ] || [ "$1" -le "$3" ]; } && return 0
	echo "usage: $4" >&2
	exit 2
}

# A private temporary directory in $tmp, removed when the script exits.
make_tmp() {
	tmp=$(mktemp -d)
	trap 'rm -rf "$tmp"' EXIT
}

# The files a stage's MANIFEST names, in its order (comments and blanks dropped).
manifest_of() {  # manifest_of STAGE
	sed 's/#.*//' "$ROOT/tests/$1/MANIFEST" 2>/dev/null | tr -d ' \t' | grep . || true
}

# The rubric files of a stage, relative to the tree root, in the order the lesson
# assigns the work, which is the order `make test` and the grade report show them in:
# tests/STAGE/rubric; then each rubric-X in the order the MANIFEST lists X.c (the
# lesson's order: heap.c before edmd.c); a rubric-X the MANIFEST does not name after
# them (audit.sh calls that a defect); hidden/rubric last. The Makefile asks this too.
rubrics_of() {  # rubrics_of STAGE
	local r f named=" "
	[ ! -f "$ROOT/tests/$1/rubric" ] || echo "tests/$1/rubric"
	for f in $(manifest_of "$1"); do
		r=tests/$1/rubric-$(basename "$f" .c)
		[ -f "$ROOT/$r" ] || continue
		echo "$r"
		named+="$r "
	done
	for r in "$ROOT/tests/$1"/rubric-*; do
		r=${r#"$ROOT/"}
		[ ! -f "$ROOT/$r" ] || [[ $named == *" $r "* ]] || echo "$r"
	done
	[ ! -f "$ROOT/tests/$1/hidden/rubric" ] || echo "tests/$1/hidden/rubric"
	return 0
}

# Seconds: the timeouts of a stage's rubrics summed (before any slack or multiplier).
rubric_seconds() {  # rubric_seconds STAGE
	local r
	for r in $(rubrics_of "$1"); do
		cat "$ROOT/$r"
	done | awk '{ sub(/#.*/, "") } NF >= 4 { s += $4 } END { printf "%d", s + 0.999 }'
}

# The implementation a build links for stage NN ("solutions", "assignments"), from the
# Makefile's BUILD/impl.stamp ("01=solutions 02=assignments ..."); "?" when unknown.
impl_of() {  # impl_of BUILD NN
	local stamp=$1/impl.stamp
	if [ -f "$stamp" ]; then
		tr ' ' '\n' <"$stamp" | awk -F= -v nn="$2" '$1 == nn { print $2; f = 1 } END { if (!f) print "?" }'
	else
		echo "?"
	fi
}

# The total of a report.txt that lz-report wrote, as "GOT/MAX" (empty when none).
score_of() {  # score_of REPORT_TXT
	sed -n 's/^Score: \([0-9.]*\/[0-9.]*\)$/\1/p' "$1" 2>/dev/null | tail -n 1
}
