#!/usr/bin/env bash
# bench-mpi.sh BUILD — the parallel engine's real speed (make bench, after bench.sh).
#
# datasets/scenes/06-mpi-bench.scene at N = 10^5 (time 6) and 10^6 (time 0.5), each
# point REPEATS times (default 3), interleaved: the serial engine (`lz run SCENE
# method=edmd`: its events over its CPU seconds), then lz-mpi on 1 and on 2 processes
# (committed events over the parallel run's wall seconds). Never more processes than
# cores: on a machine with fewer than 2 cores the P = 2 runs are skipped. Prints, per
# N, the medians and the median over the rounds of each round's ratio P = 2 / serial
# (the machine is shared: a ratio of one round's runs is fairer than a ratio of
# medians), and writes BUILD/bench/06-mpi.json. Without mpirun or lz-mpi it says so and
# exits 0.
# shellcheck source=lib/tools/common.sh
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$ROOT"
need_args $# 1 1 "bench-mpi.sh BUILD"
build=$1
lz=$build/bin/lz
lzmpi=$build/bin/lz-mpi
scene=datasets/scenes/06-mpi-bench.scene
repeats=${REPEATS:-3}
out=$build/bench
mkdir -p "$out/runs"

if ! command -v mpirun >/dev/null 2>&1 || [ ! -x "$lzmpi" ]; then
	echo "bench-mpi: skipped (no mpirun, or $lzmpi not built)"
	exit 0
fi
MPIRUN=(mpirun)
if mpirun --version 2>&1 | grep -q "Open MPI"; then
	[ "$(id -u)" -ne 0 ] || MPIRUN+=(--allow-run-as-root)
fi
cores=$(nproc 2>/dev/null || echo 1)

# One lz-mpi run on $1 processes with the overrides that follow: committed events/s.
mpi_rate() {
	local np=$1
	shift
	"${MPIRUN[@]}" -np "$np" "$lzmpi" "$scene" check=no "$@" 2>/dev/null |
		awk '/committed events\/s/ {print $3}'
}

# The serial engine's events per CPU second on the same system.
serial_rate() {
	"$lz" run "$scene" method=edmd "$@" --quiet --out "$out/runs/mpi-serial" >/dev/null 2>&1 &&
		awk -F'[:,]' '/"events_run"/ {e = $2} /"cpu_s"/ {c = $2} END {if (c > 0) printf "%.6g\n", e / c}' \
			"$out/runs/mpi-serial/summary.json"
}

median() { sort -g | awk '{v[NR] = $1} END {if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2)}'; }

json="$out/06-mpi.json"
printf '{\n  "scene": "%s",\n  "cpu": "%s",\n  "cores": %s,\n  "repeats": %s,\n  "points": [' \
	"$scene" "$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: *//')" "$cores" \
	"$repeats" >"$json"
sep=""
printf '%-9s %14s %14s %14s %18s\n' N "serial ev/s" "P=1 ev/s" "P=2 ev/s" "P=2 / serial"
for point in "100000 6" "1000000 0.5"; do
	read -r n t <<<"$point"
	s=() p1=() p2=() ratio=()
	for ((k = 0; k < repeats; k++)); do
		s+=("$(serial_rate n="$n" time="$t")")
		p1+=("$(mpi_rate 1 n="$n" time="$t")")
		if [ "$cores" -ge 2 ]; then
			p2+=("$(mpi_rate 2 n="$n" time="$t")")
			ratio+=("$(awk -v a="${p2[k]}" -v b="${s[k]}" 'BEGIN {if (b > 0 && a > 0) print a / b}')")
		fi
	done
	ms=$(printf '%s\n' "${s[@]}" | median)
	m1=$(printf '%s\n' "${p1[@]}" | median)
	m2=$( ((${#p2[@]})) && printf '%s\n' "${p2[@]}" | median || echo "")
	mr=$( ((${#ratio[@]})) && printf '%s\n' "${ratio[@]}" | median || echo "")
	printf '%-9s %14s %14s %14s %18s\n' "$n" "$ms" "$m1" "${m2:-skipped}" "${mr:-skipped}"
	printf '%s\n    {"n": %s, "time": %s, "serial_events_per_s": %s, "p1_events_per_s": %s, "p2_events_per_s": %s, "p2_over_serial": %s}' \
		"$sep" "$n" "$t" "${ms:-null}" "${m1:-null}" "${m2:-null}" "${mr:-null}" >>"$json"
	sep=","
done
printf '\n  ]\n}\n' >>"$json"
echo "bench-mpi: $json"
