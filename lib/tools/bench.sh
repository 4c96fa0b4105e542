#!/usr/bin/env bash
# bench.sh BUILD — the speed suite (make bench; lib/README.md, "Benchmarks").
#
# Reads datasets/scenes/bench.list: one benchmark per line, `SCENE key=v1,v2,...
# [key=value ...]`; keys with comma lists are swept, every combination runs REPEATS
# times (default 3; a line's last word `repeats=N`, not passed to lz, overrides it for
# a run too big to repeat) as `lz run SCENE key=value ... --quiet`. From each run's
# summary.json it takes the speed figures (steps_per_s, atomsteps_per_s, and any
# other *_per_s), state_bytes_per_particle (or _per_site) and wall_s, and reports the median over the
# repeats: a table on stdout and BUILD/bench/NN-name.json per stage (the stage is the
# NN- prefix of the scene name), with the machine and the date; BUILD/bench/NN-name.tsv
# holds the same rows as a table, a column per key. A stage that has a plot script
# lib/tools/bench-NN-name.gp gets BUILD/bench/NN-name.png when gnuplot is installed:
# the script is given table, out (the PNG) and the cache sizes l2, l3 in bytes (0 when
# unknown). Benchmarks measure speed only; correctness is the tests' job.
set -euo pipefail

if [ $# != 1 ]; then
	echo "usage: bench.sh BUILD   e.g. bench.sh build" >&2
	exit 2
fi
build=$1
list=datasets/scenes/bench.list
lz=$build/bin/lz
repeats=${REPEATS:-3}
out=$build/bench

[ -x "$lz" ] || { echo "bench.sh: $lz is missing (run make first)" >&2; exit 2; }
[ -f "$list" ] || { echo "bench.sh: no benchmark list $list" >&2; exit 2; }
[[ $repeats =~ ^[1-9][0-9]*$ ]] || { echo "bench.sh: REPEATS=$repeats must be a positive integer" >&2; exit 2; }
rm -rf "$out"
mkdir -p "$out/runs"

cpu=$(grep -m1 -E '^(model name|Hardware|cpu model)' /proc/cpuinfo 2>/dev/null | sed 's/.*: *//')
cpu=${cpu:-unknown}
cores=$(nproc 2>/dev/null || echo 0)
when=$(date -u '+%Y-%m-%dT%H:%M:%SZ')

# The value of a numeric key in a flat JSON file ("" when absent or null).
json_num() {
	sed -n "s/^[[:space:]]*\"$2\"[[:space:]]*:[[:space:]]*\([-0-9.eE+]*\)[[:space:]]*,\{0,1\}[[:space:]]*$/\1/p" "$1" | head -1
}
# The *_per_s keys of a summary, in file order.
speed_keys() { sed -n 's/^[[:space:]]*"\([a-z_]*_per_s\)".*/\1/p' "$1"; }
# The memory figure of a summary: state_bytes_per_particle, _per_site, ...
bytes_keys() { sed -n 's/^[[:space:]]*"\(state_bytes_per_[a-z]*\)".*/\1/p' "$1"; }
# Bytes of the level-$1 data (or unified) cache of cpu0: sysfs, else getconf, else 0.
cache_bytes() {
	local d size
	for d in /sys/devices/system/cpu/cpu0/cache/index*; do
		[ -r "$d/level" ] || continue
		[ "$(cat "$d/level")" = "$1" ] || continue
		[ "$(cat "$d/type" 2>/dev/null)" != Instruction ] || continue
		size=$(cat "$d/size" 2>/dev/null)
		case $size in
		*K) echo $((${size%K} * 1024)) && return ;;
		*M) echo $((${size%M} * 1048576)) && return ;;
		[0-9]*) echo "$size" && return ;;
		esac
	done
	size=$(getconf "LEVEL${1}_CACHE_SIZE" 2>/dev/null || true)
	if [[ $size =~ ^[0-9]+$ ]]; then echo "$size"; else echo 0; fi
}
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print ""; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
json_str() { printf '"%s"' "$(printf '%s' "$1" | sed 's/\\/\\\\/g; s/"/\\"/g')"; }

# Every combination of the swept keys: one line of key=value words per run.
expand() {
	local combos=("") word key values v c next
	for word in "$@"; do
		key=${word%%=*}
		values=${word#*=}
		next=()
		IFS=',' read -r -a vs <<<"$values"
		for c in "${combos[@]}"; do
			for v in "${vs[@]}"; do
				next+=("${c:+$c }$key=$v")
			done
		done
		combos=("${next[@]}")
	done
	printf '%s\n' "${combos[@]}"
}

results=$out/results.tsv  # stage, scene, params, then key=value figures
: >"$results"
failed=0
# The table shows each method's headline speed (lib/README.md, "Benchmarks"): atom-steps, site updates or
# events per second when the method reports one, else steps per second.
printf '%-14s %-46s %11s %-19s %13s %8s\n' scene parameters speed unit bytes wall_s
lineno=0
while IFS= read -r line || [ -n "$line" ]; do
	lineno=$((lineno + 1))
	line=${line%%#*}
	read -r -a words <<<"$line"
	[ ${#words[@]} = 0 ] && continue
	scene=${words[0]}
	times=$repeats
	if [[ ${words[-1]} =~ ^repeats=([1-9][0-9]*)$ ]]; then
		times=${BASH_REMATCH[1]}
		unset 'words[-1]'
	fi
	stage_nn=${scene%%-*}
	if ! [[ $stage_nn =~ ^[0-9][0-9]$ ]]; then
		echo "bench.sh: $list:$lineno: scene '$scene' should be named NN-..." >&2
		failed=1
		continue
	fi
	while IFS= read -r params; do
		read -r -a kv <<<"$params"
		tag=$(printf '%s' "$scene-$params" | tr ' =,/' '_-__')
		figures=()
		for ((r = 1; r <= times; r++)); do
			dir=$out/runs/$tag-$r
			if ! "$lz" run "$scene" "${kv[@]}" --out "$dir" --quiet >"$dir.log" 2>&1; then
				echo "bench.sh: $scene $params failed: $(head -1 "$dir.log")" >&2
				failed=1
				continue 2
			fi
			figures+=("$dir/summary.json")
		done
		row="$stage_nn	$scene	$params"
		for key in $(speed_keys "${figures[0]}") $(bytes_keys "${figures[0]}") wall_s; do
			m=$(for f in "${figures[@]}"; do json_num "$f" "$key"; done | median)
			row="$row	$key=$m"
		done
		printf '%s\n' "$row" >>"$results"
		printf '%s\n' "$row" | awk -F '\t' '{
			bytes = ""
			for (i = 4; i <= NF; i++) {
				split($i, kv, "="); f[kv[1]] = kv[2]
				if (kv[1] ~ /^state_bytes_per_/) bytes = sprintf("%.0f", kv[2]) "/" substr(kv[1], 17)
			}
			n = split("atomsteps_per_s site_updates_per_s events_per_s placed_per_s steps_per_s", order, " ")
			for (k = 1; k <= n && !(order[k] in f); k++) ;
			key = k <= n ? order[k] : "steps_per_s"
			printf "%-14s %-46s %11.4g %-19s %13s %8.3f\n", $2, $3, f[key], key, bytes, f["wall_s"] }'
	done < <(expand "${words[@]:1}")
done <"$list"

# One JSON file per stage.
cut -f1 "$results" | sort -u | while read -r nn; do
	name=$nn
	for dir in lessons/"$nn"-*; do
		[ -d "$dir" ] && name=$(basename "$dir") && break
	done
	file=$out/$name.json
	{
		printf '{\n  "stage": %s,\n  "date": %s,\n  "cpu": %s,\n  "nproc": %s,\n  "repeats": %s,\n  "statistic": "median",\n  "results": [\n' \
			"$(json_str "$name")" "$(json_str "$when")" "$(json_str "$cpu")" "$cores" "$repeats"
		awk -F '\t' -v nn="$nn" '$1 == nn {
			line = sprintf("    {\"scene\": \"%s\", \"params\": \"%s\"", $2, $3)
			for (i = 4; i <= NF; i++) {
				split($i, kv, "="); v = kv[2] == "" ? "null" : kv[2]
				line = line sprintf(", \"%s\": %s", kv[1], v)
			}
			rows[++n] = line "}"
		} END { for (i = 1; i <= n; i++) print rows[i] (i < n ? "," : "") }' "$results"
		printf '  ]\n}\n'
	} >"$file"
	echo "bench: wrote $file"
	# the same rows as a table: scene, then a column per key (NaN where a row has none)
	awk -F '\t' -v nn="$nn" '
		function put(word,   eq, k) {
			eq = index(word, "="); k = substr(word, 1, eq - 1)
			if (!(k in seen)) { seen[k] = 1; cols[++nc] = k }
			val[rows, k] = substr(word, eq + 1)
		}
		$1 == nn {
			scene[++rows] = $2
			nw = split($3, w, " ")
			for (i = 1; i <= nw; i++) put(w[i])
			for (i = 4; i <= NF; i++) put($i)
		}
		END {
			printf "scene"; for (c = 1; c <= nc; c++) printf "\t%s", cols[c]; print ""
			for (r = 1; r <= rows; r++) {
				printf "%s", scene[r]
				for (c = 1; c <= nc; c++) printf "\t%s", (r, cols[c]) in val && val[r, cols[c]] != "" ? val[r, cols[c]] : "NaN"
				print ""
			}
		}' "$results" >"$out/$name.tsv"
	plot=lib/tools/bench-$name.gp
	if [ -f "$plot" ] && command -v gnuplot >/dev/null 2>&1; then
		if gnuplot -e "table='$out/$name.tsv'; out='$out/$name.png'; l2=$(cache_bytes 2); l3=$(cache_bytes 3)" "$plot" </dev/null 2>"$out/$name.plot.log"; then
			echo "bench: wrote $out/$name.png"
		else
			echo "bench.sh: $plot failed: $(head -3 "$out/$name.plot.log")" >&2
		fi
	fi
done
echo "machine: $cpu, $cores cores; $when; median of $repeats runs each"
if [ "$failed" != 0 ]; then
	echo "bench.sh: some benchmarks failed (see $out/runs/*.log)" >&2
	exit 1
fi
