# numfmt.awk — numbers for people, as the demo page prints them (HTML markup).
#
# Alone (awk -f numfmt.awk) it reads lines "VALUE<TAB>ERROR" (ERROR may be empty) and
# prints one line each; with -v lib=1 it only lends its function numfmt(VALUE, ERROR)
# to the script given after it (demo_rows.awk). The text:
#   with an error bar, the value rounded to its error's precision, as a paper prints
#   it: the error to 2 significant digits, the value to the same decimal place
#   (4.09994 ± 0.003597 -> 4.0999 ± 0.0036; 12345.6 ± 678 -> 12,350 ± 680). Outside
#   1e-3 <= |x| < 1e6 both share one power of ten: (1.2346 ± 0.0036)×10<sup>-5</sup>;
#   an error below a millionth of the value (a round-off level, not a statistical
#   one) is printed beside the value, each on its own: 1 ± 4.1×10<sup>-15</sup>;
#   without one (empty, null, zero, not a number), the value alone: integers in full
#   with thousands commas, 1e3..1e6 rounded to an integer, 1e-3..1e3 to 4 significant
#   digits, anything else as 1.234×10<sup>n</sup>; a value that is no number is
#   printed as it is, null (the JSON writer's NaN) and empty as a dash.
# Checked by tests/lib/check_numfmt.sh.
BEGIN { FS = "\t" }

function isnum(s) { return s ~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/ }
function absv(x) { return x < 0 ? -x : x }
# floor(log10(a)) for a > 0, exact at powers of ten (log() alone may miss by one).
function decade(a,   p) {
	p = int(log(a) / log(10))
	if (log(a) < 0 && p != log(a) / log(10)) p--
	while (10 ^ p > a) p--
	while (10 ^ (p + 1) <= a) p++
	return p
}
# Thousands commas in the integer part of the fixed-point string s.
function commas(s,   sign, ip, fp, r, k) {
	sign = ""
	if (substr(s, 1, 1) == "-") { sign = "-"; s = substr(s, 2) }
	k = index(s, ".")
	ip = k ? substr(s, 1, k - 1) : s
	fp = k ? substr(s, k) : ""
	r = ""
	while (length(ip) > 3) { r = "," substr(ip, length(ip) - 2) r; ip = substr(ip, 1, length(ip) - 3) }
	return sign ip r fp
}
# "-0.00" and the like print as "0.00".
function unsign(s) { return s ~ /^-[0.]*$/ ? substr(s, 2) : s }
function sci(m, p) { return m "×10<sup>" p "</sup>" }

# A single value.
function plain(x,   v, a, p) {
	if (x == "" || x == "null") return "—"
	if (!isnum(x)) return x
	v = x + 0; a = absv(v)
	if (a == 0) return "0"
	if (v == int(v) && a < 1e15) return commas(sprintf("%.0f", v))
	if (a >= 1e3 && a < 1e6) return commas(sprintf("%.0f", v))
	if (a >= 1e-3 && a < 1e3) return sprintf("%.4g", v)
	p = decade(a)
	return sci(sprintf("%.3f", v / 10 ^ p), p)
}

# e > 0 to 2 significant digits.
function twodigits(e,   d) {
	d = decade(e) - 1
	if (int(e / 10 ^ d + 0.5) >= 100) d++
	if (e < 1e-3 || e >= 1e6) return sci(sprintf("%.1f", e / 10 ^ (d + 1)), d + 1)
	return commas(sprintf("%." (d < 0 ? -d : 0) "f", int(e / 10 ^ d + 0.5) * 10 ^ d))
}

# A value with its error bar e > 0.
function witherr(x, e,   v, d, r, p, scale, dec, vs, es) {
	v = x + 0
	if (e < 1e-6 * absv(v))
		return plain(x) " ± " twodigits(e)
	d = decade(e) - 1                 # the decimal place of the error's 2nd digit
	r = int(e / 10 ^ d + 0.5)
	if (r >= 100) d++                 # 0.0996 -> 0.10: the rounding carried a digit
	p = 0
	if (absv(v) >= e ? (absv(v) >= 1e6 || absv(v) < 1e-3) : (e >= 1e6 || e < 1e-3))
		p = decade(absv(v) >= e ? absv(v) : e)
	scale = 10 ^ p
	dec = p - d > 0 ? p - d : 0
	if (d > p) {                      # rounded to tens or more: whole multiples of 10^d
		vs = sprintf("%.0f", int(absv(v) / 10 ^ d + 0.5) * 10 ^ (d - p))
		if (v < 0) vs = "-" vs
		es = sprintf("%.0f", int(e / 10 ^ d + 0.5) * 10 ^ (d - p))
	} else {
		vs = sprintf("%." dec "f", v / scale)
		es = sprintf("%." dec "f", e / scale)
	}
	vs = unsign(vs)
	if (p == 0) return commas(vs) " ± " commas(es)
	return sci("(" vs " ± " es ")", p)
}

function numfmt(x, e) {
	if (isnum(x) && isnum(e) && e + 0 > 0 && e + 0 < 1e300) return witherr(x, e + 0)
	return plain(x)
}

lib == "" { print numfmt($1, $2) }
