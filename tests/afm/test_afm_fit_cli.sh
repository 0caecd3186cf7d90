#!/usr/bin/env bash
# coatcontact afm fit on the real JPK curve: the estimates in the header, the table, the plot;
# range options; and the refusals: exit 2 naming the option, the value and what is allowed,
# exit 3 for a fit without contact; never an output file on failure.
# Usage: test_afm_fit_cli.sh COATCONTACT DATA_DIR WORK_DIR
set -u
cli="$1"; data="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
spot="$data/fmt-jpk-fd_spot3-0192.jpk-force"

expect_error() {  # CODE FRAGMENT... -- ARGS
  local code="$1"; shift
  local fragments=()
  while [ "$1" != "--" ]; do fragments+=("$1"); shift; done
  shift
  rm -f "$work/out.tsv" "$work/out.png"
  "$cli" "$@" --output "$work/out.tsv" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  [ "$rc" -eq "$code" ] || fail "exit $rc (wanted $code): $* :: $(cat "$work/stderr")"
  for f in "${fragments[@]}"; do
    grep -qF -- "$f" "$work/stderr" || fail "message lacks '$f': $* :: $(cat "$work/stderr")"
  done
  [ ! -e "$work/out.tsv" ] && [ ! -e "$work/out.png" ] || fail "an output file was written: $*"
  ls "$work" | grep -q '\.tmp\.' && fail "a temporary file was left: $*"
  return 0
}

# ---- a good fit: header, table, plot ---------------------------------------------------------
"$cli" afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --output "$work/fit.tsv" --plot "$work/fit.png" \
  2>"$work/stderr" || fail "afm fit spot3: $(cat "$work/stderr")"
grep -q '^# command: coatcontact afm fit ' "$work/fit.tsv" || fail "no command line"
for key in 'E \[Pa\]' 'contact point \[m\]' 'baseline \[N\]'; do
  grep -qE "^# $key: [-0-9.e+]+ \+- [0-9.e+-]+$" "$work/fit.tsv" || fail "header lacks '$key: value +- error'"
done
for key in 'chi2' 'residual sigma \[N\]' 'pull-off \(retract, measured\) \[N\]' 'fit range' 'tip'; do
  grep -qE "^# $key: " "$work/fit.tsv" || fail "header lacks '$key'"
done
grep -q '^# columns: point	tip_position_m	indentation_m	force_N	model_force_N	residual_N	fitted$' "$work/fit.tsv" \
  || fail "columns line"
rows=$(grep -vc '^#' "$work/fit.tsv")
[ "$rows" -eq 2000 ] || fail "the approach has 2000 points, the table $rows"
head -c 8 "$work/fit.png" | od -An -c | grep -q 'P   N   G' || fail "--plot did not write a PNG"
# The residual column is model - data, and the model is the baseline out of contact.
awk -F'\t' '!/^#/ { r = $5 - $4 - $6; if (r > 1e-20 || r < -1e-20) bad++ } END { exit bad > 0 }' "$work/fit.tsv" \
  || fail "residual_N is not model_force_N - force_N"
# Range options: fewer points fitted, recorded in the header.
"$cli" afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --max-indentation 50nm --indentation-range -1um,1um \
  --output "$work/range.tsv" 2>"$work/stderr" || fail "range options: $(cat "$work/stderr")"
grep -qE '^# fit range: indentation >= -1e-06 m; indentation <= 5e-08 m \([0-9]+ points fitted' "$work/range.tsv" \
  || fail "range not recorded: $(grep '^# fit range' "$work/range.tsv")"
fitted=$(awk -F'\t' '!/^#/ && $7 == 1' "$work/range.tsv" | wc -l)
[ "$fitted" -gt 100 ] && [ "$fitted" -lt 2000 ] || fail "range fitted $fitted points"
# A fixed contact point and E free: the cone and the pyramid run too.
"$cli" afm fit "$spot" --shape pyramid:35deg --halfspace 1kPa,0.5 --output "$work/pyr.tsv" 2>"$work/stderr" \
  || fail "pyramid: $(cat "$work/stderr")"
grep -q '^# tip: four-sided pyramid, face half angle 35 deg' "$work/pyr.tsv" || fail "pyramid description"
"$cli" afm fit "$spot" --shape blunted-cone:50nm,70deg --halfspace 1kPa,0.5 --output "$work/bc.tsv" 2>"$work/stderr" \
  || fail "blunted cone: $(cat "$work/stderr")"

# A coating with t free (E1 fixed): the estimate and its error in the header.
"$cli" afm fit "$spot" --radius 10um --film 5kPa,0.5 --substrate 1GPa,0.3 --thickness 2um --free t,contact_point,baseline \
  --max-indentation 100nm --output "$work/coat.tsv" 2>"$work/stderr" || fail "coating: $(cat "$work/stderr")"
grep -qE '^# t \[m\]: [0-9.e+-]+ \+- [0-9.e+-]+$' "$work/coat.tsv" || fail "coating: no t +- error"
grep -q '^# E1 \[Pa\]: 5000 (fixed)$' "$work/coat.tsv" || fail "coating: E1 fixed"

# ---- the adhesive retract fit (--model jkr) ---------------------------------------------------
gel="$data/fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force"
"$cli" afm fit "$gel" --model jkr --radius 10um --halfspace 1kPa,0.5 --output "$work/jkr.tsv" --plot "$work/jkr.png" \
  2>"$work/stderr" || fail "afm fit --model jkr: $(cat "$work/stderr")"
for key in 'E \[Pa\]' 'w \[J/m2\]' 'contact point \[m\]' 'baseline \[N\]'; do
  grep -qE "^# $key: [-0-9.e+]+ \+- [0-9.e+-]+$" "$work/jkr.tsv" || fail "jkr header lacks '$key: value +- error'"
done
for key in 'tilt \[N/m\]' 'Tabor mu' 'Maugis lambda' 'model jump-off' 'spring constant \[N/m\]' 'chi2'; do
  grep -qE "^# $key: " "$work/jkr.tsv" || fail "jkr header lacks '$key'"
done
grep -q '^# segment: retract (3000 points)' "$work/jkr.tsv" || fail "jkr fits the retract by default"
head -c 8 "$work/jkr.png" | od -An -c | grep -q 'P   N   G' || fail "jkr --plot did not write a PNG"
grep -qE 'NaN|nan|inf' "$work/jkr.tsv" && fail "jkr output holds a NaN or inf"
# lambda scales as 1/z0: ten times the range, a tenth of lambda (same fit).
"$cli" afm fit "$gel" --model jkr --radius 10um --halfspace 1kPa,0.5 --range 3nm --output "$work/jkr3.tsv" 2>"$work/stderr" \
  || fail "jkr --range 3nm: $(cat "$work/stderr")"
l1=$(sed -n 's/^# Maugis lambda: \([0-9.e+-]*\) .*/\1/p' "$work/jkr.tsv")
l3=$(sed -n 's/^# Maugis lambda: \([0-9.e+-]*\) .*/\1/p' "$work/jkr3.tsv")
awk -v a="$l1" -v b="$l3" 'BEGIN { r = a / b; exit !(r > 9.999 && r < 10.001) }' || fail "lambda(0.3nm)/lambda(3nm) = $l1/$l3, not 10"
# The spot3 retract: a small adhesion on a stiff cantilever scale: lambda below 5 and a warning.
"$cli" afm fit "$spot" --model jkr --radius 10um --halfspace 10kPa,0.5 --output "$work/spotj.tsv" 2>"$work/stderr" \
  || fail "jkr spot3: $(cat "$work/stderr")"
grep -q "warning: Maugis's lambda = .* is below 5" "$work/stderr" || fail "jkr spot3: no lambda warning on stderr"
grep -q "^# warning: Maugis's lambda" "$work/spotj.tsv" || fail "jkr spot3: no lambda warning in the header"

# ---- the Maugis-Dugdale retract fit (--model md) ------------------------------------------------
# The flipsign retract (JKR's lambda 2.5, below JKR's range): the md fit runs with the file's spring
# constant, its header has the estimates, lambda against the table's range, the model line.
flip="$data/fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force"
"$cli" afm fit "$flip" --model md --radius 10um --halfspace 1kPa,0.5 --output "$work/md.tsv" --plot "$work/md.png" \
  2>"$work/stderr" || fail "afm fit --model md: $(cat "$work/stderr")"
for key in 'E \[Pa\]' 'w \[J/m2\]' 'contact point \[m\]' 'baseline \[N\]' 'tilt \[N/m\]'; do
  grep -qE "^# $key: [-0-9.e+]+ \+- [0-9.e+-]+" "$work/md.tsv" || fail "md header lacks '$key: value +- error'"
done
grep -q '^# model: F = b + m (z - z_c) + F_MD(z_c - z), F_MD: Maugis-Dugdale' "$work/md.tsv" || fail "md: model line"
grep -qE '^# Maugis lambda: [0-9.e+-]+ .*table holds lambda in \[0.001, 10000\]' "$work/md.tsv" || fail "md: lambda line"
head -c 8 "$work/md.png" | od -An -c | grep -q 'P   N   G' || fail "md --plot did not write a PNG"
grep -qE 'NaN|nan|inf' "$work/md.tsv" && fail "md output holds a NaN or inf"
# The spot3 retract has no adhesion to speak of: w runs toward 0, lambda below the table's 1e-3,
# and the spring holds the tip down to the curve's end: both warnings, on stderr and in the header.
"$cli" afm fit "$spot" --model md --radius 10um --halfspace 10kPa,0.5 --output "$work/spotmd.tsv" 2>"$work/stderr" \
  || fail "md spot3: $(cat "$work/stderr")"
grep -q "warning: Maugis's lambda = .* is below 0.001: outside the cohesive-zone table" "$work/stderr" \
  || fail "md spot3: no lambda warning on stderr"
grep -q "^# warning: Maugis's lambda = .*the spring holds the tip down to the curve's end" "$work/spotmd.tsv" \
  || fail "md spot3: no curve's-end warning in the header"

# ---- refusals ----------------------------------------------------------------------------------
expect_error 2 "--model" "'lj'" "allowed: hertz, jkr, md, dmt" -- afm fit "$spot" --model lj --radius 10um --halfspace 1kPa,0.5
expect_error 2 "--model" "dmt takes a sphere" -- afm fit "$spot" --model dmt --shape cone:70deg --halfspace 1kPa,0.5
expect_error 2 "--model" "md takes a sphere" -- afm fit "$spot" --model md --shape cone:70deg --halfspace 1kPa,0.5
expect_error 2 "--work" "needs --model jkr" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --work 1mJ/m2
expect_error 2 "--range" "needs --model jkr" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --range 1nm
expect_error 2 "--model" "jkr takes a sphere" -- afm fit "$spot" --model jkr --shape cone:70deg --halfspace 1kPa,0.5
expect_error 2 "--free" "a fixed w needs --work W" -- afm fit "$spot" --model jkr --radius 10um --halfspace 1kPa,0.5 --free E,contact_point,baseline
expect_error 2 "--tilt" "the tilt is free" -- afm fit "$spot" --model jkr --radius 10um --halfspace 1kPa,0.5 --tilt 0
expect_error 2 "--range" "'-1nm'" -- afm fit "$spot" --model jkr --radius 10um --halfspace 1kPa,0.5 --range -1nm
expect_error 2 "--free" "'t'" "allowed: E, contact_point, baseline, w, tilt" -- afm fit "$spot" --model jkr --radius 10um --halfspace 1kPa,0.5 --free E,t
expect_error 3 "no point in contact" -- afm fit "$spot" --model jkr --radius 10um --halfspace 1kPa,0.5 --free E,w,baseline --contact-point 1e-6
expect_error 2 "--model" "'foo'" "allowed: hertz" -- afm fit "$spot" --model foo --radius 10um --halfspace 1kPa,0.5
expect_error 2 "a coating needs" "--thickness is missing" -- afm fit "$spot" --radius 10um --film 1kPa,0.5 --substrate rigid
expect_error 2 "--halfspace" "one sample" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --film 1kPa,0.5 --substrate rigid --thickness 1um
expect_error 2 "--free" "'E'" "allowed: E1, t, contact_point, baseline" -- afm fit "$spot" --radius 10um --film 1kPa,0.5 --substrate rigid --thickness 1um --free E
expect_error 2 "a coating takes a sphere" -- afm fit "$spot" --shape punch:1um --film 1kPa,0.5 --substrate rigid --thickness 1um
expect_error 2 "--halfspace E,nu" -- afm fit "$spot" --radius 10um
expect_error 2 "--radius R" "--shape SPEC" -- afm fit "$spot" --halfspace 1kPa,0.5
expect_error 2 "--radius and --shape" -- afm fit "$spot" --radius 10um --shape cone:70deg --halfspace 1kPa,0.5
expect_error 2 "--free" "'w'" "allowed: E, contact_point, baseline" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --free E,w
expect_error 2 "--free" "--contact-point Z" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --free E,baseline
expect_error 2 "--segment" "'side'" "approach or retract" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --segment side
expect_error 2 "--tip-range" "MIN must be below MAX" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --tip-range 2e-5,1e-5
expect_error 2 "range options leave 0 points" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --tip-range 1,2
expect_error 2 "--index" "holds 1 curve" -- afm fit "$spot" --index 3 --radius 10um --halfspace 1kPa,0.5
expect_error 2 "--plot" ".png or .pdf" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --plot "$work/out.gif"
expect_error 2 "--shape" "pyramid:THETA" -- afm fit "$spot" --shape pyramid: --halfspace 1kPa,0.5
expect_error 2 "--spring-constant" -- afm fit "$data/fmt-jpk-cl_calibration_force-save-2015.02.04-11.25.21.294.jpk-force" --radius 10um --halfspace 1kPa,0.5
# No point in contact (a fixed contact point below every tip position): numerical failure, exit 3.
expect_error 3 "no contact" -- afm fit "$spot" --radius 10um --halfspace 1kPa,0.5 --free E,baseline --contact-point 1e-6 --plot "$work/out.png"

[ "$failures" -eq 0 ] && echo "afm fit CLI: all checks passed"
exit $((failures > 0))
