# demo_rows.awk — the demo page's lines of figures: a label, the value with its error
# bar on one line, and the unit. Run after numfmt.awk (awk -v lib=1 -f numfmt.awk -f
# demo_rows.awk ...) on two inputs: the label table (demo_labels.tsv) and the
# "key<TAB>value" pairs of one JSON file (demo.sh's json_pairs).
#   -v scope=NAME   the experiment driver, or "scene" (which rows of the table apply)
#   -v keys="k ..." only these keys, in this order (a scene's '# demo:' line);
#                   empty: every key but check, in the file's order
#   -v style=table  <tr><td>label</td><td>value unit</td></tr> per key (a card, the
#                   measured figures of a scene run);
#   -v style=after  value label<br> (speeds: 2.5×10<sup>6</sup> events per second);
#   -v style=value  the value and unit alone
# A key K_err goes on K's line when K is shown; a key without a row in the table is shown with its '_'
# as spaces.
BEGIN { FS = "\t" }

function html(s) {
	gsub(/&/, "\\&amp;", s); gsub(/</, "\\&lt;", s); gsub(/>/, "\\&gt;", s)
	return s
}
function spaced(s) { gsub(/_/, " ", s); return s }

# The label and unit of key k (into LABEL and UNIT).
function lookup(k,   i, pat, star, pre, suf, mid) {
	for (i = 1; i <= nrow; i++) {
		if (rscope[i] != scope && rscope[i] != "*")
			continue
		pat = rkey[i]
		star = index(pat, "*")
		if (!star) {
			if (pat != k) continue
			LABEL = rlabel[i]; UNIT = runit[i]
			return
		}
		pre = substr(pat, 1, star - 1); suf = substr(pat, star + 1)
		if (length(k) <= length(pre) + length(suf) || substr(k, 1, length(pre)) != pre ||
		    substr(k, length(k) - length(suf) + 1) != suf)
			continue
		mid = substr(k, length(pre) + 1, length(k) - length(pre) - length(suf))
		mid = (mid in word) ? word[mid] : spaced(html(mid))
		LABEL = rlabel[i]; UNIT = runit[i]
		sub(/\{\}/, mid, LABEL)
		return
	}
	LABEL = spaced(html(k)); UNIT = ""
}

function shown(v) {
	if (v == "true") return "yes"
	if (v == "false") return "no"
	return isnum(v) || v == "null" || v == "" ? v : html(v)
}

FNR == NR {
	if ($0 ~ /^#/ || NF < 3) next
	if ($1 == "word") { word[$2] = $3; next }
	nrow++; rscope[nrow] = $1; rkey[nrow] = $2; rlabel[nrow] = $3; runit[nrow] = $4
	next
}
{
	if (!($1 in value)) order[++nkey] = $1
	value[$1] = $2
}
END {
	if (keys != "")
		nkey = split(keys, order, " ")
	for (i = 1; i <= nkey; i++)
		listed[order[i]] = 1
	for (i = 1; i <= nkey; i++) {
		k = order[i]
		if ((keys == "" && k == "check") || (k ~ /_err$/ && substr(k, 1, length(k) - 4) in listed))
			continue
		lookup(k)
		v = (k in value) ? value[k] : ""
		if (UNIT == "#")
			text = html(v)
		else
			text = numfmt(shown(v), value[k "_err"])
		if (UNIT != "" && UNIT != "#" && text != "—") text = text " " UNIT
		cls = isnum(v) || v == "null" || v == "" ? "num" : "txt"
		if (style == "after")
			printf "%s %s<br>", text, LABEL
		else if (style == "value")
			printf "%s", text
		else
			printf "<tr><td>%s</td><td class=\"%s\">%s</td></tr>\n", LABEL, cls, text
	}
}
