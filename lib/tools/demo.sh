#!/usr/bin/env bash
# demo.sh BUILD "STAGES" — the demo page, BUILD/demo/index.html (make demo).
#
# Run after the lessons ran at demo size (lesson.sh STAGE BUILD 1). Per stage it shows
# the lesson's title (first '# ' line of its README), every plot with its caption (the
# '# caption:' line of its .gp script) in the order the lesson shows them, one a row
# at most at its own size, the headline figures of every experiment driver
# (OUTDIR/NAME.json) and a table of the scene runs (OUTDIR/runs/*/summary.json): the
# speed figures (keys ending in _per_s), wall_s and the keys the scene names in its
# '# demo: k1 k2' line. Every figure is labelled in words with its unit, and a value
# with an error bar rounded to the error's precision (demo_labels.tsv, demo_rows.awk,
# numfmt.awk). The page is one self-contained file plus img/ (inline CSS, images
# referenced relatively).
# Anything missing becomes a note on the page, never a failure.
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
need_args $# 2 2 'demo.sh BUILD "STAGES"   e.g. demo.sh build "01-lozenge"'
build=$1
stages=$2
tools=$(dirname "${BASH_SOURCE[0]}")
demo=$build/demo
page=$demo/index.html
rm -rf "$demo"
mkdir -p "$demo/img"

html_escape() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g'; }

# A flat JSON object as "key<TAB>value" lines, strings unquoted and unescaped.
json_pairs() {
	awk 'BEGIN { RS = "\0" } {
		s = $0; n = length(s); i = 1; depth = 0
		while (i <= n) {
			c = substr(s, i, 1)
			if (c == "\"") {                      # a string: key or value
				str = ""; i++
				while (i <= n && (c = substr(s, i, 1)) != "\"") {
					if (c == "\\") { i++; c = substr(s, i, 1); if (c == "n") c = " "; if (c == "t") c = " " }
					str = str c; i++
				}
				i++
				if (key == "") key = str; else { print key "\t" str; key = "" }
			} else if (c ~ /[-0-9.a-zA-Z+]/ && key != "") {   # number, true, false, null
				v = ""
				while (i <= n && (c = substr(s, i, 1)) ~ /[-0-9.eE+a-zA-Z]/) { v = v c; i++ }
				print key "\t" v; key = ""
			} else i++
		}
	}' "$1"
}

# The value of key in a flat JSON file ("" if absent).
json_get() { json_pairs "$1" | awk -F '\t' -v k="$2" '$1 == k { print $2; exit }'; }

# Plot names (without .png) of a lesson: first in the order its README shows them,
# then any others alphabetically.
plot_order() {
	local lesson=$1 readme=$1/README.md
	{
		[ -f "$readme" ] && grep -o '!\[[^]]*\]([^)]*\.png)' "$readme" |
			sed 's/.*(\(.*\)\.png)/\1/' | xargs -r -n1 basename
		for gp in "$lesson"/*.gp; do [ -f "$gp" ] && basename "$gp" .gp; done
	} | awk '!seen[$0]++' | while read -r name; do
		[ -f "$lesson/$name.gp" ] && echo "$name"
	done
}

stage_title() {
	local readme=lessons/$1/README.md
	if [ -f "$readme" ]; then
		grep -m1 '^# ' "$readme" | sed 's/^# *//' | html_escape
	else
		echo "$1" | html_escape
	fi
}

emit_plots() {
	local stage=$1 nn=$2 out=$3 shown=0 name caption
	echo '<div class="plots">'
	while read -r name; do
		caption=$(grep -m1 '^# caption:' "lessons/$stage/$name.gp" 2>/dev/null |
			sed 's/^# caption: *//' | html_escape)
		if [ -f "$out/$name.png" ]; then
			cp "$out/$name.png" "$demo/img/$nn-$name.png"
			printf '<figure><a href="img/%s-%s.png"><img src="img/%s-%s.png" alt="%s"></a>' \
				"$nn" "$name" "$nn" "$name" "$name"
		else
			printf '<figure><div class="missing">%s.png was not made: its experiment failed or gnuplot is missing (see %s/%s.gp.log)</div>' \
				"$name" "$out" "$name"
		fi
		printf '<figcaption><b>%s</b> — %s</figcaption></figure>\n' "$name" "${caption:-no caption}"
		shown=$((shown + 1))
	done < <(plot_order "lessons/$stage")
	[ "$shown" = 0 ] && echo '<p class="note">This lesson has no plots.</p>'
	echo '</div>'
}

# Lines of figures from a flat JSON file: rows VALUES FILE SCOPE STYLE [KEYS]
# (lib/tools/demo_rows.awk: labels and units from demo_labels.tsv, each value with
# its error bar on one line).
rows() {
	json_pairs "$1" | awk -v lib=1 -v scope="$2" -v style="$3" -v keys="${4:-}" \
		-f "$tools/numfmt.awk" -f "$tools/demo_rows.awk" "$tools/demo_labels.tsv" -
}

# One card per experiment driver: its headline figures.
emit_headlines() {
	local stage=$1 out=$2 src name json check
	echo '<h3>Headline figures of the experiments</h3><div class="cards">'
	for src in "lessons/$stage"/*.c; do
		[ -f "$src" ] || continue
		name=$(basename "$src" .c)
		json=$out/$name.json
		if [ ! -f "$json" ]; then
			printf '<div class="card"><h4>%s</h4><p class="note">no %s.json (the driver did not run or failed; see %s.log)</p></div>\n' \
				"$name" "$name" "$name"
			continue
		fi
		check=$(json_get "$json" check)
		printf '<div class="card"><h4>driver <code>%s</code> <span class="badge %s">%s</span></h4><table>\n' "$name" \
			"$([ "$check" = passed ] && echo ok || echo bad)" "$(echo "${check:-unchecked}" | html_escape)"
		rows "$json" "$name" table
		echo '</table></div>'
	done
	echo '</div>'
}

# The keys a scene asks the demo to show: its '# demo: k1 k2' line.
demo_keys() { grep -m1 '^# *demo:' "$1" 2>/dev/null | sed 's/^# *demo: *//'; }

emit_runs() {
	local nn=$1 out=$2 scene name summary speed
	local scenes=(datasets/scenes/"$nn"-*.scene)
	echo '<h3>Scene runs</h3>'
	if [ ! -e "${scenes[0]}" ]; then
		echo '<p class="note">This stage ships no scenes.</p>'
		return
	fi
	echo '<table class="runs"><tr><th class="w-scene">scene</th><th class="w-what">what it is</th><th class="w-speed">speed</th><th class="w-wall">wall time</th><th>measured</th></tr>'
	for scene in "${scenes[@]}"; do
		name=$(basename "$scene" .scene)
		summary=$out/runs/$name/summary.json
		printf '<tr><td><code>%s</code></td><td>%s</td>' "$name" \
			"$(grep -m1 '^#' "$scene" | sed 's/^# *//' | html_escape)"
		if [ ! -f "$summary" ]; then
			echo '<td colspan="3" class="note">not run or failed (see the lesson log)</td></tr>'
			continue
		fi
		speed=$(rows "$summary" scene after \
			"$(json_pairs "$summary" | awk -F '\t' '$1 ~ /_per_s$/ { printf "%s ", $1 }')")
		printf '<td class="num">%s</td><td class="num">%s</td><td>' "${speed:-—}" \
			"$(rows "$summary" scene value wall_s)"
		echo '<table class="kv">'
		rows "$summary" scene table "$(demo_keys "$scene")"
		echo '</table>'
		echo '</td></tr>'
	done
	echo '</table>'
}

emit_stage() {
	local stage=$1 nn=${1%%-*} out=$build/lessons/${1%%-*}
	printf '<section id="s%s"><h2><span class="nn">%s</span> %s</h2>\n' "$nn" "$nn" "$(stage_title "$stage")"
	if [ ! -d "$out" ]; then
		printf '<p class="note">Not run yet: <code>make lesson STAGE=%s QUICK=1</code>.</p></section>\n' "$nn"
		return
	fi
	printf '<p class="meta">Lesson text: <code>lessons/%s/README.md</code> · implementation: <code>%s</code> · data and logs: <code>%s</code></p>\n' \
		"$stage" "$(impl_of "$build" "$nn")" "$out"
	emit_plots "$stage" "$nn" "$out"
	emit_headlines "$stage" "$out"
	emit_runs "$nn" "$out"
	echo '</section>'
}

machine() {
	local cpu
	cpu=$(grep -m1 -E '^(model name|Hardware|cpu model)' /proc/cpuinfo 2>/dev/null | sed 's/.*: *//')
	printf '%s · %s cores · %s · %s · %s' "${cpu:-unknown CPU}" "$(nproc 2>/dev/null || echo '?')" \
		"$(uname -sm)" "$(${CC:-cc} --version 2>/dev/null | head -1)" "$(date -u '+%Y-%m-%d %H:%M UTC')" | html_escape
}

style() {
	cat <<'EOF'
<style>
:root { --ink: #1d2330; --muted: #5b6475; --line: #e3e6ec; --accent: #1f5fa8; --bg: #f6f7f9; }
* { box-sizing: border-box; }
body { margin: 0; font: 15px/1.55 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: var(--ink); background: var(--bg); }
header { background: linear-gradient(120deg, #17345f, #1f5fa8); color: #fff; padding: 34px 0 28px; }
.wrap { max-width: 1180px; margin: 0 auto; padding: 0 24px; }
header h1 { margin: 0 0 6px; font-size: 30px; letter-spacing: .5px; }
header p { margin: 4px 0; max-width: 900px; color: #dfe8f6; }
header code { color: #fff; background: rgba(255,255,255,.12); padding: 1px 5px; border-radius: 4px; }
nav { margin-top: 14px; }
nav ul { margin: 0; padding-left: 20px; }
nav li { margin: 3px 0; }
nav a { color: #fff; text-decoration: none; border-bottom: 1px solid rgba(255,255,255,.4); }
section { background: #fff; margin: 26px 0; padding: 22px 26px; border-radius: 10px; box-shadow: 0 1px 3px rgba(0,0,0,.06); }
h2 { margin: 0 0 4px; font-size: 23px; }
h2 .nn { display: inline-block; background: var(--accent); color: #fff; border-radius: 6px; padding: 0 9px; margin-right: 6px; font-size: 19px; }
h3 { margin: 26px 0 10px; font-size: 17px; color: var(--accent); border-bottom: 1px solid var(--line); padding-bottom: 4px; }
.meta { color: var(--muted); font-size: 13px; margin: 0 0 12px; }
.plots { display: grid; grid-template-columns: 1fr; gap: 18px; }
figure { margin: 0; border: 1px solid var(--line); border-radius: 8px; overflow: hidden; background: #fff; }
figure img { display: block; max-width: 100%; margin: 0 auto; }
figcaption { padding: 10px 12px; font-size: 13.5px; color: #333; border-top: 1px solid var(--line); background: #fbfbfc; }
.cards { display: grid; grid-template-columns: repeat(auto-fill, minmax(330px, 1fr)); gap: 14px; }
.card { border: 1px solid var(--line); border-radius: 8px; padding: 10px 12px; }
.card h4 { margin: 0 0 6px; font-size: 15px; }
.card table { width: 100%; border-collapse: collapse; font-size: 13px; }
.card td { padding: 2px 4px; border-bottom: 1px solid #f0f1f4; vertical-align: top; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.txt { text-align: right; color: var(--muted); }
.badge { font-size: 11px; font-weight: 600; padding: 1px 7px; border-radius: 9px; vertical-align: middle; }
.badge.ok { background: #dcf3e3; color: #17663a; }
.badge.bad { background: #fde2e1; color: #a3201b; }
table.runs { width: 100%; border-collapse: collapse; font-size: 13.5px; }
table.runs th { text-align: left; background: #f0f3f8; padding: 6px 8px; }
table.runs td { padding: 6px 8px; border-bottom: 1px solid var(--line); vertical-align: top; }
table.runs td code { white-space: nowrap; }
.w-scene { width: 10%; } .w-what { width: 27%; } .w-speed { width: 14%; } .w-wall { width: 6%; }
table.kv { width: 100%; border-collapse: collapse; font-size: 13px; }
table.kv td { padding: 1px 4px; border-bottom: 1px solid #f0f1f4; vertical-align: top; }
.note, .missing { color: #8a5a00; background: #fff7e0; padding: 6px 10px; border-radius: 6px; }
.missing { margin: 12px; }
footer { color: var(--muted); font-size: 13px; padding: 8px 0 40px; }
code { font-size: 90%; }
</style>
EOF
}

{
	echo '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
	echo '<meta name="viewport" content="width=device-width, initial-scale=1">'
	echo '<title>lozenge — demo</title>'
	style
	echo '</head><body><header><div class="wrap">'
	echo '<h1>lozenge</h1>'
	echo '<p>Fast simulation of hard particles: a course in C. Each stage is a lesson with a graded assignment;'
	echo 'students build a small library stage by stage and run every experiment on their own code.</p>'
	echo '<p>This page shows the experiments of every lesson at demo size, as measured on this machine by'
	echo '<code>make demo</code>: the plots, the headline figures each experiment checked against known values,'
	echo 'and the speed and accuracy of the ready-made scenes. Each caption says what the plot shows at demo size and,'
	echo 'where it differs, at full size (<code>make lesson STAGE=NN</code>). &ldquo;The thesis&rdquo; is T. F. Nagy,'
	echo '<i>Computational methods to simulate large classical particle systems</i>, PhD thesis, Michigan State University (2000),'
	echo 'on which the course is built; &ldquo;lesson NN &sect;k&rdquo; is a section of <code>lessons/NN-*/README.md</code>.</p><nav><ul>'
	for stage in $stages; do
		printf '<li><a href="#s%s">%s</a></li>\n' "${stage%%-*}" "$(stage_title "$stage")"
	done
	echo '</ul></nav></div></header><main class="wrap">'
	[ -z "$stages" ] && echo '<section><p class="note">No stages were given.</p></section>'
	for stage in $stages; do
		emit_stage "$stage"
	done
	printf '</main><footer class="wrap">Measured on: %s.<br>Run it yourself: <code>make demo</code>; one lesson at full size: <code>make lesson STAGE=01</code>.</footer>\n' "$(machine)"
	echo '</body></html>'
} >"$page"

shopt -s nullglob
images=("$demo"/img/*.png)
echo "demo: wrote $page (${#images[@]} plots)"
