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
# exits 0. The parallel runs start with windows of some 8000 events a rank (window =
# 0.05 and 0.005) that grow by 2 % after a commit (grow = 1.02): against such windows
# a cut costs little and a rollback much (lesson 06 §11, §14).
#
# Then the model checked against the measurement: the stub's virtual-time policy run
# on 2 ranks of the same system (lz run ... schedule = virtual), its costs the measured
# ones — cost_event the time of one event on one rank (the P = 1 median), cost_message
# and latency the medians of what the P = 2 runs' ping-pong found (lz-mpi prints them)
# — and its modelled P = 2 / serial = committed events x the serial engine's time per
# event / the virtual time.
#
# Last, memory (Miller and Luding's fig. 9): what a process holds in the run (resident
# at its end) and at its peak, on 1, 2 and 4 processes, 10^6 disks — rank 0, which
# builds the start, and the largest of the others. Four processes may share fewer
# cores (Open MPI's --oversubscribe): these runs measure memory, not speed.
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
SHARE=()  # more processes than cores
if mpirun --version 2>&1 | grep -q "Open MPI"; then
	[ "$(id -u)" -ne 0 ] || MPIRUN+=(--allow-run-as-root)
	SHARE=(--oversubscribe)
fi
cores=$(nproc 2>/dev/null || echo 1)

# One lz-mpi run on $1 processes with the overrides that follow: committed events/s,
# the largest memory a process holds in the run (MiB, resident at its end), and on 2 or
# more processes the measured message cost and latency (seconds).
mpi_rate() {
	local np=$1
	shift
	"${MPIRUN[@]}" -np "$np" "$lzmpi" "$scene" check=no "$@" 2>/dev/null |
		awk '/committed events\/s/ {r = $3} /^run memory  / {m = $3}
		     /^run memory, others/ {if ($4 > m) m = $4} /^message cost/ {c = $3}
		     /^message latency/ {l = $3} END {print r, m, c, l}'
}

# The modelled P = 2 / serial of the virtual-time policy: $1 the serial engine's events
# per second, $2 one rank's, $3 the message cost, $4 the latency, then the overrides.
model_ratio() {
	local serial=$1 rank=$2 cost=$3 lat=$4
	shift 4
	"$lz" run "$scene" ranks=2 schedule=virtual check=no write_config=no \
		cost_event="$(awk -v r="$rank" 'BEGIN {printf "%.6g", 1 / r}')" cost_message="$cost" \
		latency="$lat" "$@" --quiet --out "$out/runs/mpi-model" >/dev/null 2>&1 &&
		awk -F'[:,]' -v s="$serial" '/"committed_events"/ {e = $2} /"virtual_s"/ {v = $2}
			END {if (v > 0 && s > 0) printf "%.4g\n", e / s / v}' "$out/runs/mpi-model/summary.json"
}

# The serial engine's events per CPU second on the same system. A run that fails
# stops the bench with lz's message (a key the serial engine does not know, say),
# rather than with an empty column.
serial_rate() {
	local log=$out/runs/mpi-serial.log
	if ! "$lz" run "$scene" method=edmd "$@" --quiet --out "$out/runs/mpi-serial" >"$log" 2>&1; then
		echo "bench-mpi: the serial run (lz run $scene method=edmd $*) failed:" >&2
		cat "$log" >&2
		exit 1
	fi
	awk -F'[:,]' '/"events_run"/ {e = $2} /"cpu_s"/ {c = $2} END {if (c > 0) printf "%.6g\n", e / c}' \
		"$out/runs/mpi-serial/summary.json"
}

median() { sort -g | awk '{v[NR] = $1} END {if (NR) print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2)}'; }

json="$out/06-mpi.json"
printf '{\n  "scene": "%s",\n  "cpu": "%s",\n  "cores": %s,\n  "repeats": %s,\n  "points": [' \
	"$scene" "$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: *//')" "$cores" \
	"$repeats" >"$json"
sep=""
printf '%-9s %14s %14s %14s %14s %12s %12s %14s %10s %10s\n' N "serial ev/s" "P=1 ev/s" \
	"P=2 ev/s" "P=2 / serial" "msg cost s" "latency s" "model P=2/ser" "P=1 MiB" "P=2 MiB"
for point in "100000 6 0.05" "1000000 0.5 0.005"; do
	read -r n t w <<<"$point"
	s=() p1=() p2=() ratio=() cost=() lat=() mb=() mb1=()
	for ((k = 0; k < repeats; k++)); do
		s+=("$(serial_rate n="$n" time="$t")") || exit 1
		read -r r m _ <<<"$(mpi_rate 1 n="$n" time="$t" window="$w" grow=1.02)"
		p1+=("$r") mb1+=("$m")
		if [ "$cores" -ge 2 ]; then
			read -r r m c l <<<"$(mpi_rate 2 n="$n" time="$t" window="$w" grow=1.02)"
			p2+=("$r") cost+=("$c") lat+=("$l") mb+=("$m")
			ratio+=("$(awk -v a="$r" -v b="${s[k]}" 'BEGIN {if (b > 0 && a > 0) print a / b}')")
		fi
	done
	ms=$(printf '%s\n' "${s[@]}" | median)
	m1=$(printf '%s\n' "${p1[@]}" | median)
	mp1=$(printf '%s\n' "${mb1[@]}" | median)
	m2="" mr="" mc="" ml="" mm="" mp=""
	if ((${#p2[@]})); then
		m2=$(printf '%s\n' "${p2[@]}" | median)
		mr=$(printf '%s\n' "${ratio[@]}" | median)
		mc=$(printf '%s\n' "${cost[@]}" | median)
		ml=$(printf '%s\n' "${lat[@]}" | median)
		mp=$(printf '%s\n' "${mb[@]}" | median)
		mm=$(model_ratio "$ms" "$m1" "$mc" "$ml" n="$n" time="$t" window="$w" grow=1.02)
	fi
	printf '%-9s %14s %14s %14s %14s %12s %12s %14s %10s %10s\n' "$n" "$ms" "$m1" \
		"${m2:-skipped}" "${mr:-skipped}" "${mc:--}" "${ml:--}" "${mm:--}" "${mp1:--}" "${mp:--}"
	printf '%s\n    {"n": %s, "time": %s, "serial_events_per_s": %s, "p1_events_per_s": %s, "p2_events_per_s": %s, "p2_over_serial": %s, "message_cost_s": %s, "latency_s": %s, "model_p2_over_serial": %s, "p1_run_mib": %s, "p2_run_mib": %s}' \
		"$sep" "$n" "$t" "${ms:-null}" "${m1:-null}" "${m2:-null}" "${mr:-null}" "${mc:-null}" \
		"${ml:-null}" "${mm:-null}" "${mp1:-null}" "${mp:-null}" >>"$json"
	sep=","
done
printf '\n  ],\n  "memory_n": 1000000,\n  "memory": [' >>"$json"
printf '\nmemory a process holds, 10^6 disks (MiB; in the run: resident at its end)\n'
printf '%-3s %14s %14s %14s %14s\n' P "run, rank 0" "run, others" "peak, rank 0" "peak, others"
sep=""
for np in 1 2 4; do
	read -r a b p q <<<"$("${MPIRUN[@]}" "${SHARE[@]}" -np "$np" "$lzmpi" "$scene" check=no \
		n=1000000 time=0.2 2>/dev/null | awk '/^run memory  / {a = $3} /^peak memory  / {p = $3}
		/^run memory, others/ {b = $4} /^peak memory, others/ {q = $4}
		END {print a, (b == "" ? "-" : b), p, (q == "" ? "-" : q)}')"
	printf '%-3s %14s %14s %14s %14s\n' "$np" "$a" "$b" "$p" "$q"
	printf '%s\n    {"processes": %s, "run_rank0_mib": %s, "run_others_mib": %s, "peak_rank0_mib": %s, "peak_others_mib": %s}' \
		"$sep" "$np" "${a:-null}" "$([ "$b" = - ] && echo null || echo "$b")" "${p:-null}" \
		"$([ "$q" = - ] && echo null || echo "$q")" >>"$json"
	sep=","
done
printf '\n  ]\n}\n' >>"$json"
echo "bench-mpi: $json"
