#!/usr/bin/env bash
# check.sh — the MPI back-end in `make check` (and `make mpi-check`).
#
#   check.sh BUILD
#
# BUILD/bin/lz-mpi runs datasets/scenes/06-mpi-check.scene (check = yes) on P = 1, 2, 3
# and 4 processes: each must exit 0 and commit the serial run's final state bit for bit
# ("identical to the serial run: yes"). So must a falling sediment
# (06-sediment.scene) whose cuts move during the run (balance = dynamic: some moves)
# or come from a pilot run (balance = pilot: a smaller busiest share). Bad input — a
# key the scene cannot have, a scene that is not there, a `ranks` other than the
# processes — must exit 2 on every process with its message, and never hang (each run
# under `timeout`). Prints
# `mpi: N passed, M failed` and exits non-zero on any failure. Without mpicc or mpirun
# (or an lz-mpi built) the checks are skipped with a note: `mpi: 0 passed, 0 failed`.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/common.sh"
cd "$ROOT"
need_args $# 1 1 "check.sh BUILD"
LZ_MPI=$1/bin/lz-mpi
SCENE=datasets/scenes/06-mpi-check.scene
LIMIT=60  # seconds a run may take: a hang fails, it does not stall make check
passed=0
failed=0
make_tmp

skip() {
	echo "mpi: skipped: $1"
	echo "mpi: 0 passed, 0 failed"
	exit 0
}
command -v mpicc >/dev/null 2>&1 || skip "no mpicc (install Open MPI or MPICH to build lz-mpi)"
command -v mpirun >/dev/null 2>&1 || skip "no mpirun"
[ -x "$LZ_MPI" ] || skip "$LZ_MPI is not built (make all builds it where mpicc is)"

# Open MPI refuses root without --allow-run-as-root, and more processes than cores
# without --oversubscribe; other MPIs know neither flag.
MPIRUN=(mpirun)
if mpirun --version 2>&1 | grep -q "Open MPI"; then
	MPIRUN+=(--oversubscribe)
	[ "$(id -u)" -ne 0 ] || MPIRUN+=(--allow-run-as-root)
fi

# Open MPI's own allocations outlive MPI_Finalize: under the sanitizers (SANITIZE=1)
# LeakSanitizer would fail every run on them, so it is off here (ASan and UBSan stay on).
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0

pass() {
	passed=$((passed + 1))
	echo "  ok      $1"
}
fail() {  # fail NAME WHY: the run's output below
	failed=$((failed + 1))
	echo "  FAILED  $1: $2"
	sed 's/^/          /' "$tmp/out" | head -n 30
}

run() {  # run P ARGS...: lz-mpi on P processes, output in $tmp/out, status in $status
	local np=$1
	shift
	status=0
	timeout "$LIMIT" "${MPIRUN[@]}" -np "$np" "$LZ_MPI" "$@" >"$tmp/out" 2>&1 || status=$?
}

# The run's figures for the log: "(E events in W s)", or nothing.
figures() {
	awk '$1 == "committed" && $2 == "events" { e = $3 } $1 == "parallel" { w = $4 }
		END { if (e != "") printf " (%s events in %s s)", e, w }' "$tmp/out"
}

expect() {  # expect NAME STATUS LINES P ARGS...: exit STATUS, for each line of LINES a
	#            line of output matching it (grep -E), no hang
	local name=$1 want=$2 lines=$3 line missing=""
	shift 3
	run "$@"
	while IFS= read -r line; do
		grep -Eq "$line" "$tmp/out" || missing=${missing:-$line}
	done <<<"$lines"
	if [ "$status" -eq 124 ]; then
		fail "$name" "no end within $LIMIT s (a hang?)"
	elif [ "$status" -ne "$want" ]; then
		fail "$name" "exit status $status, not $want"
	elif [ -n "$missing" ]; then
		fail "$name" "no line '$missing'"
	else
		pass "$name$(figures)"
	fi
}

# The same bits as the serial run, on every number of processes.
for np in 1 2 3 4; do
	expect "P = $np: $SCENE equals the serial run" 0 "^identical to the serial run: yes$" \
		"$np" "$SCENE"
done

# Cuts that move: the sediment's load sinks to the floor, the ranks move their cuts
# after it (handing the particles over) or start from a pilot run's, and the run is
# still the serial run, bit for bit.
SEDIMENT=datasets/scenes/06-sediment.scene
for np in 2 3; do
	expect "P = $np: the sediment with moving cuts equals the serial run" 0 \
		$'^identical to the serial run: yes$\n^cut moves +[1-9]' \
		"$np" "$SEDIMENT" ranks="$np" balance=dynamic balance_every=4
done
expect "P = 2: the sediment on a pilot run's cuts equals the serial run" 0 \
	$'^identical to the serial run: yes$\n^pilot busiest share +0\\.' \
	2 "$SEDIMENT" ranks=2 balance=pilot

# The ping-pong before the run found a message's cost (what make bench feeds the
# virtual-time model): a positive time, not 0 or nothing.
expect "P = 2 measures a message's cost" 0 "^message cost +[1-9][0-9.]*(e-?[0-9]+)? s" 2 "$SCENE"

# Bad input: status 2 on every process, the message, no hang.
expect "a bad key exits 2 with its message" 2 "^lz-mpi: .*unknown key 'no_such_key'" \
	2 "$SCENE" no_such_key=1
expect "a missing scene exits 2 with its message" 2 "^lz-mpi: cannot open scene" \
	3 "$tmp/none.scene"
expect "ranks = 3 on 2 processes exits 2" 2 "^lz-mpi: .*ranks = 3, but lz-mpi runs on 2 processes" \
	2 "$SCENE" ranks=3

echo "mpi: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
