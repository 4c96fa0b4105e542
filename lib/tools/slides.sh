#!/usr/bin/env bash
# slides.sh BUILD "STAGES" — the slide decks, BUILD/slides/NN-name.html (make slides).
#
# For every stage with slides/NN-name.md: when BUILD/lessons/NN holds no plots yet,
# the lesson runs first at demo size (lesson.sh STAGE BUILD 1); then pandoc turns the
# Markdown into one self-contained dzslides HTML file, the plots embedded (they are
# found by bare name: --resource-path=BUILD/lessons/NN:slides).
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
need_args $# 2 2 'slides.sh BUILD "STAGES"   e.g. slides.sh build "01-lozenge"'
build=$1
stages=$2
if ! command -v pandoc >/dev/null 2>&1; then
	echo "slides.sh: pandoc is not installed (make deps installs it)" >&2
	exit 2
fi
mkdir -p "$build/slides"

# Images sized to the slide, and a quieter look than the dzslides default.
style=$(mktemp)
trap 'rm -f "$style"' EXIT
cat >"$style" <<'CSS'
<style>
  section { font-family: system-ui, "Segoe UI", Roboto, sans-serif; }
  section h2 { color: #1f4f8f; font-size: 32px; margin: 26px 0 14px; }
  section img { display: block; margin: 0 auto; max-width: 96%; max-height: 380px; }
  section p, section li { font-size: 21px; line-height: 1.35; margin: 8px 40px; }
  section li { margin: 5px 0; }
  section ul, section ol { margin: 8px 40px 8px 60px; }
  section code { font-size: 88%; }
  section table { margin: 0 auto; font-size: 18px; border-collapse: collapse; }
  section th, section td { padding: 3px 10px; border-bottom: 1px solid #ddd; }
  section.title h1 { color: #1f4f8f; font-size: 46px; margin: 170px 40px 20px; }
  section.title h1.subtitle { color: #666; font-size: 26px; margin-top: 10px; }
</style>
CSS

made=0
for stage in $stages; do
	md=slides/$stage.md
	[ -f "$md" ] || continue
	nn=${stage%%-*}
	out=$build/lessons/$nn
	if ! compgen -G "$out/*.png" >/dev/null; then
		echo "slides: no plots in $out yet; running the lesson at demo size first"
		bash lib/tools/lesson.sh "$stage" "$build" 1 ||
			echo "slides: the lesson had failures; the deck may miss some plots" >&2
	fi
	html=$build/slides/$stage.html
	pandoc -t dzslides --standalone --self-contained --mathml --include-in-header="$style" \
		--resource-path="$out:slides" -o "$html" "$md"
	echo "slides: wrote $html"
	made=$((made + 1))
done
[ "$made" -gt 0 ] || echo "slides: no slides/NN-name.md for the stages $stages"
