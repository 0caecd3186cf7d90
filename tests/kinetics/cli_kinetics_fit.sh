#!/bin/sh
# `coatcontact kinetics --fit` (THEORY.md section 14, fitting): curves made by `kinetics` itself at
# three retract speeds (every third state, no noise) are fitted back from a start 1.5x, 3x, 0.75x
# off, with the film thickness free from 70 um, and with the film modulus free from 1.15 MPa; bad input exits 2 naming the option and
# writes nothing.
cli="$1"
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
fail=0
materials="--film 1e6,0.49 --substrate 70e9,0.22 --radius 2mm --spring 500"
t50="--thickness 50um"
prefix="approach:1um/s:1mN,dwell:1s"
curve=1
: >"$tmp/curves.tsv"
printf 'curve\tt\tF\n' >"$tmp/curves.tsv"
for speed in 1um/s 10um/s 100um/s; do
  "$cli" kinetics $materials $t50 --work 0.04 --v-star 1um/s --n 0.6 --protocol "$prefix,retract:$speed" \
    --output "$tmp/run$curve.tsv" || { echo "FAIL: simulating curve $curve"; fail=1; }
  grep -v '^#' "$tmp/run$curve.tsv" | awk -v c="$curve" 'NR > 1 && NR % 3 == 0 { printf "%d\t%s\t%s\n", c, $1, $5 }' \
    >>"$tmp/curves.tsv"
  curve=$((curve + 1))
done
"$cli" kinetics $materials $t50 --work 0.06 --v-star 3um/s --n 0.45 --protocol "$prefix,retract:1um/s" \
  --retract-speeds 1um/s,10um/s,100um/s --fit "$tmp/curves.tsv" --output "$tmp/fit.tsv" ||
  { echo "FAIL: fit"; fail=1; }
# Noise-free data: the fit returns the parameters that made them. Bound 1e-3 relative: the model
# interpolates between its own ODE states (rtol 1e-9), the data sit on the states of the true
# run, and the trust region stops at relative steps ~1e-7; 1e-3 leaves room for a flat n-v* valley.
check() {
  value=$(sed -n "s|^# $1: \([^ ]*\) +- .*|\1|p" "$tmp/fit.tsv")
  awk -v a="$value" -v b="$2" 'BEGIN { d = (a - b) / b; if (d < 0) d = -d; exit !(a != "" && d <= 1e-3) }' ||
    { echo "FAIL: $1 = '$value', want $2"; fail=1; }
}
check 'w \[J/m2\]' 0.04
check 'v_star \[m/s\]' 1e-06
check 'n' 0.6
# The film thickness too (t enters through eta = t/L_a, the table stays): from 70 um.
"$cli" kinetics $materials --work 0.05 --v-star 2um/s --n 0.5 --protocol "$prefix,retract:1um/s" \
  --retract-speeds 1um/s,10um/s,100um/s --fit "$tmp/curves.tsv" --free w,v_star,n,t --thickness 70um \
  --output "$tmp/fit.tsv" 2>"$tmp/err" || { echo "FAIL: fit with t free"; cat "$tmp/err"; fail=1; }
check 't \[m\]' 5e-05
check 'n' 0.6
# The film modulus (each trial E1 builds its own table): from 1.15 MPa, with w, v*, n.
"$cli" kinetics --film 1.15e6,0.49 --substrate 70e9,0.22 --radius 2mm --spring 500 $t50 --work 0.045 \
  --v-star 1.5um/s --n 0.55 --protocol "$prefix,retract:1um/s" --retract-speeds 1um/s,10um/s,100um/s --fit "$tmp/curves.tsv" \
  --free w,v_star,n,E1 --output "$tmp/fit.tsv" 2>"$tmp/err" || { echo "FAIL: fit with E1 free"; cat "$tmp/err"; fail=1; }
check 'E1 \[Pa\]' 1e+06
check 'w \[J/m2\]' 0.04
grep -q '^# columns: curve	t_s	F_N	F_model_N	residual_N	fitted' "$tmp/fit.tsv" || { echo "FAIL: fit columns"; fail=1; }
# Bad input: exit 2, message naming the option, no output file.
expect2() {
  name="$1"; shift
  rm -f "$tmp/bad.tsv"
  "$cli" kinetics $materials $t50 --work 0.04 --v-star 1um/s --n 0.6 "$@" --output "$tmp/bad.tsv" 2>"$tmp/err"
  rc=$?
  if [ $rc -ne 2 ]; then echo "FAIL: $name: exit $rc, want 2"; cat "$tmp/err"; fail=1; fi
  if ! grep -q -- "$name" "$tmp/err"; then echo "FAIL: message does not name $name:"; cat "$tmp/err"; fail=1; fi
  if [ -e "$tmp/bad.tsv" ]; then echo "FAIL: $name: output written"; fail=1; fi
}
expect2 --fit --protocol "$prefix,retract:1um/s" --fit "$tmp/missing.tsv"
expect2 --free --protocol "$prefix,retract:1um/s" --retract-speeds 1um/s,10um/s,100um/s --fit "$tmp/curves.tsv" --free w,E0
expect2 --free --protocol "$prefix,retract:1um/s" --free w
expect2 --retract-speeds --protocol "$prefix,retract:1um/s" --retract-speeds 1um/s,10um/s --fit "$tmp/curves.tsv"
# One retract speed for every curve with v_star and n free: refused (one speed fixes only (v/v*)^n).
expect2 --retract-speeds --protocol "$prefix,retract:1um/s" --retract-speeds 1um/s,1um/s,1um/s --fit "$tmp/curves.tsv"
printf '1\t0\t0.001\n0\t1\t0.002\n' >"$tmp/zero.tsv"
expect2 --fit --protocol "$prefix,retract:1um/s" --fit "$tmp/zero.tsv"
printf '1\t0\n' >"$tmp/two.tsv"
expect2 --fit --protocol "$prefix,retract:1um/s" --fit "$tmp/two.tsv"
exit $fail
