#!/bin/sh
# `coatcontact kinetics` (THEORY.md section 14): the README run, a sweep, and bad input (exit 2
# naming the option, nothing written).
cli="$1"
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
fail=0
base="--film 1e6,0.49 --substrate 70e9,0.22 --radius 2e-3 --thickness 50e-6 --work 0.04 --v-star 1e-6 --n 0.6 --spring 500"
# The README run.
if ! "$cli" kinetics $base --protocol approach:1um/s:1mN,dwell:1s,retract:10um/s --output "$tmp/run.tsv"; then
  echo "FAIL: README run"; fail=1
fi
grep -q '^# pull-off (most tensile force of the last retract) \[N\]: -' "$tmp/run.tsv" || { echo "FAIL: no pull-off"; fail=1; }
grep -q '^# columns: t_s	z_m	delta_m	a_m	F_N	G_J_m2' "$tmp/run.tsv" || { echo "FAIL: columns"; fail=1; }
# The sweep's row at 10 um/s is the single run's pull-off.
"$cli" kinetics $base --protocol approach:1um/s:1mN,dwell:1s,retract:10um/s --retract-speeds 1um/s,10um/s \
  --output "$tmp/sweep.tsv" || { echo "FAIL: sweep"; fail=1; }
single=$(sed -n 's/^# pull-off (most tensile force of the last retract) \[N\]: //p' "$tmp/run.tsv")
swept=$(grep -v '^#' "$tmp/sweep.tsv" | sed -n 2p | cut -f2)
awk -v a="$single" -v b="$swept" 'BEGIN { d = a - b; if (d < 0) d = -d; s = a < 0 ? -a : a; exit !(a != "" && d <= 1e-15 * s) }' ||
  { echo "FAIL: sweep row $swept differs from the single run $single"; fail=1; }
# Bad input: exit 2, message naming the option, no output file.
expect2() {
  name="$1"; shift
  rm -f "$tmp/bad.tsv"
  "$cli" kinetics "$@" --output "$tmp/bad.tsv" 2>"$tmp/err"
  rc=$?
  if [ $rc -ne 2 ]; then echo "FAIL: $name: exit $rc, want 2"; cat "$tmp/err"; fail=1; fi
  if ! grep -q -- "$name" "$tmp/err"; then echo "FAIL: message does not name $name:"; cat "$tmp/err"; fail=1; fi
  if [ -e "$tmp/bad.tsv" ]; then echo "FAIL: $name: output written"; fail=1; fi
}
expect2 --protocol $base --protocol approach:-1um/s:1mN,retract:1um/s
expect2 --n --film 1e6,0.49 --substrate 70e9,0.22 --radius 2e-3 --thickness 50e-6 --work 0.04 --v-star 1e-6 --n 0 --spring 500 --protocol approach:1um/s:1mN,retract:1um/s
expect2 --v-star --film 1e6,0.49 --substrate 70e9,0.22 --radius 2e-3 --thickness 50e-6 --work 0.04 --v-star -1e-6 --n 0.6 --spring 500 --protocol approach:1um/s:1mN,retract:1um/s
expect2 --protocol $base --protocol retract:1um/s
expect2 --protocol $base --protocol approach:1um/s:1mN,retract:1um/s,dwell:1s
expect2 --protocol $base --protocol approach:1um/s:1mN,dwell:1s
expect2 --protocol $base --protocol approach:1um/s:1mN,hold:1s,retract:1um/s
expect2 --spring --film 1e6,0.49 --substrate 70e9,0.22 --radius 2e-3 --thickness 50e-6 --work 0.04 --v-star 1e-6 --n 0.6 --spring -5 --protocol approach:1um/s:1mN,retract:1um/s
expect2 --retract-speeds $base --protocol approach:1um/s:1mN,retract:1um/s --retract-speeds 1um/s,-2um/s
# Reduced runs (--eta): SI options refused, --k-bar needs --eta.
red="--eta 1 --film 0.1,0.25 --substrate 1,0.25 --n 0.6"
"$cli" kinetics $red --k-bar 1 --protocol approach:1:1,dwell:1,retract:1 --output "$tmp/red.tsv" ||
  { echo "FAIL: reduced run"; fail=1; }
grep -q '^# columns: tau	Z	D	a_bar	P	G_over_w	segment' "$tmp/red.tsv" || { echo "FAIL: reduced columns"; fail=1; }
expect2 --radius $red --k-bar 1 --radius 1mm --protocol approach:1:1,retract:1
expect2 --k-bar $base --k-bar 1 --protocol approach:1um/s:1mN,retract:1um/s
expect2 --k-bar $red --k-bar -1 --protocol approach:1:1,retract:1
exit $fail
