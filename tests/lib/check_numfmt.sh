#!/usr/bin/env bash
# check_numfmt.sh — the demo page's numbers (lib/tools/numfmt.awk): a value with an
# error bar is rounded to the error's precision (error to 2 significant digits, the
# value to the same decimal place), and a value alone to 4 significant digits.
# Run by make check (lib/tools/check.sh); prints "numfmt: N passed, M failed".
set -u
awk_script=$(dirname "${BASH_SOURCE[0]}")/../../lib/tools/numfmt.awk
passed=0
failed=0

# expect VALUE ERROR WANTED
expect() {
	local got
	got=$(printf '%s\t%s\n' "$1" "$2" | awk -f "$awk_script")
	if [ "$got" = "$3" ]; then
		passed=$((passed + 1))
	else
		failed=$((failed + 1))
		echo "FAIL  value '$1', error '$2': got '$got', want '$3'"
	fi
}

# the error's precision sets the value's
expect 4.09994 0.003597 "4.0999 ± 0.0036"
expect 3.99 0.003102 "3.9900 ± 0.0031"
expect 10.25338689318116 0.018819231586323575 "10.253 ± 0.019"
expect -3.14159 0.01 "-3.142 ± 0.010"
expect 9.5 0.96 "9.50 ± 0.96"
# rounding the error may carry a digit: 0.996 -> 1.0, 0.0996 -> 0.10
expect 9.5 0.996 "9.5 ± 1.0"
expect 0.0996 0.0996 "0.10 ± 0.10"
# an error larger than the value, and a value that rounds to zero
expect 0.0014 0.004 "0.0014 ± 0.0040"
expect -0.00001 0.0004 "(-0.1 ± 4.0)×10<sup>-4</sup>"
expect 0 1e-16 "(0.0 ± 1.0)×10<sup>-16</sup>"
# errors of tens and more: the value rounded to whole tens (hundreds...)
expect 12345.6 678 "12,350 ± 680"
expect 250 35 "250 ± 35"
# outside 1e-3 .. 1e6 one power of ten for both
expect 1.23456e-5 3.6e-8 "(1.2346 ± 0.0036)×10<sup>-5</sup>"
expect 2466345.98 12000 "(2.466 ± 0.012)×10<sup>6</sup>"
# an error at round-off level is printed beside the value
expect 1.0000000000000933 4.1e-15 "1 ± 4.1×10<sup>-15</sup>"
# no usable error: the value alone
expect 5 "" "5"
expect 0.5 null "0.5"
expect 0.123456 0 "0.1235"
expect 1234567 "" "1,234,567"
expect 4321.7 "" "4,322"
expect 6.02e23 "" "6.020×10<sup>23</sup>"
expect 2.5e-7 "" "2.500×10<sup>-7</sup>"
# not a number
expect null "" "—"
expect "" "" "—"
expect passed "" "passed"

echo "numfmt: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
