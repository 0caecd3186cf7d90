#!/usr/bin/env bash
# CLI tests of `coatcontact fit`: a successful run on the example data, and the failures that
# must give a clear message and an exit code instead of a number:
#   bad input (exit 2): malformed data line (file:line), negative contact radius (file:line),
#     too few points (n <= free parameters), missing fixed value, unknown --free name;
#   numerical (exit 3): a fit of pure noise (no adhesive-contact signal in the data).
# Usage: test_fit_cli.sh COATCONTACT MAKE_SYNTHETIC_DATA DATA_DIR
set -u
cli=$1
generator=$2
data=$3
source "$(dirname "$0")/fit_checks.sh"
model=(--radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22)

# --- success: header with estimates and standard errors, a columns line, finite numbers ---
expect "fit a,F" 0 "" -- "$cli" fit "$data/example_a_F.tsv" --columns a,F "${model[@]}" --thickness 50um
for key in "w \[J/m2\]: [0-9.e+-]* +- [0-9.e+-]*$" "residual norm \[N\]" "iterations" "converged: yes" "columns: line"; do
  grep -q "^# $key" "$work/out" || fail "fit a,F: no '# $key' header line"
done
rows=$(grep -vc '^#' "$work/out")
[[ $rows -eq 80 ]] || fail "fit a,F: $rows data rows, expected 80"
if grep -v '^#' "$work/out" | grep -Eiq 'nan|inf'; then fail "fit a,F: NaN/inf in the output"; fi
expect "fit delta,F w,t to --output" 0 "" -- "$cli" fit "$data/example_delta_F.tsv" --columns delta,F \
  "${model[@]}" --free w,t --start t=45um --output "$work/fit.tsv" --curve "$work/curve.tsv"
[[ -n $(stderr_of "$work/fit.tsv" "t [m]") ]] || fail "fit delta,F: no standard error of t in the output file"
grep -q "^# columns: a_m	delta_m	F_N" "$work/curve.tsv" || fail "fit delta,F: curve file has no columns line"
grep -q "standard error" "$work/out" || fail "fit delta,F: no summary on stdout with --output"
expect "--help" 0 "" -- "$cli" fit --help

# --- bad input: exit 2 ---
printf '# units: um mN\n100\t1.0\n120\tabc\n140\t2.0\n' >"$work/malformed.tsv"
expect "malformed line" 2 "malformed.tsv:3:" -- "$cli" fit "$work/malformed.tsv" --columns a,F "${model[@]}" --thickness 50um
printf '100e-6\t1e-3\n-120e-6\t2e-3\n140e-6\t3e-3\n' >"$work/negative.tsv"
expect "negative contact radius" 2 "negative.tsv:2:" -- "$cli" fit "$work/negative.tsv" --columns a,F "${model[@]}" --thickness 50um
printf '100e-6\t1e-3\n0\t2e-3\n140e-6\t3e-3\n' >"$work/zero.tsv"
expect "zero contact radius" 2 "zero.tsv:2: contact radius must be > 0" -- "$cli" fit "$work/zero.tsv" --columns a,F "${model[@]}" --thickness 50um
printf '# one point\n200e-6\t1e-3\n' >"$work/one.tsv"
expect "too few points (1 for w)" 2 "1 data point for 1 free parameter" -- "$cli" fit "$work/one.tsv" --columns a,F "${model[@]}" --thickness 50um
printf '200e-6\t1e-3\n300e-6\t2e-3\n' >"$work/two.tsv"
expect "too few points (2 for w,t)" 2 "2 data points for 2 free parameters" -- "$cli" fit "$work/two.tsv" --columns a,F "${model[@]}" --free w,t --start t=50um
expect "fixed t without --thickness" 2 "--thickness" -- "$cli" fit "$data/example_a_F.tsv" --columns a,F "${model[@]}"
expect "unknown free parameter" 2 "--free: 'nu' is not a parameter" -- "$cli" fit "$data/example_a_F.tsv" --columns a,F "${model[@]}" --thickness 50um --free w,nu
expect "bad --columns" 2 "--columns" -- "$cli" fit "$data/example_a_F.tsv" --columns x,y "${model[@]}" --thickness 50um
expect "missing data file" 2 "nothere.tsv" -- "$cli" fit "$work/nothere.tsv" --columns a,F "${model[@]}" --thickness 50um
expect "unit of the wrong kind" 2 "" -- bash -c "printf '# units: mN um\n1\t100\n2\t200\n' >'$work/units.tsv'; '$cli' fit '$work/units.tsv' --columns a,F ${model[*]} --thickness 50um"

# --- numerical: a fit of pure noise, exit 3 with a message, never a number ---
"$generator" --kind a,F --signal none --noise 1mN --seed 7 --output "$work/noise_a_F.tsv" || fail "generator (a,F noise)"
expect "pure noise a,F (w)" 3 "does not describe|not determine|not identifiable|did not converge" -- \
  "$cli" fit "$work/noise_a_F.tsv" --columns a,F "${model[@]}" --thickness 50um
[[ -s $work/out ]] && fail "pure noise a,F: something was written to stdout"
expect "pure noise a,F (w,t)" 3 "does not describe|not determine|not identifiable|did not converge" -- \
  "$cli" fit "$work/noise_a_F.tsv" --columns a,F "${model[@]}" --free w,t --start t=50um
"$generator" --kind delta,F --signal none --noise 1mN --seed 8 --output "$work/noise_delta_F.tsv" || fail "generator (delta,F noise)"
expect "pure noise delta,F (w)" 3 "does not describe|not determine|not identifiable|did not converge" -- \
  "$cli" fit "$work/noise_delta_F.tsv" --columns delta,F "${model[@]}" --thickness 50um
[[ -e $work/never.tsv ]] && fail "an output file was left behind"

# --- issue 15: errors in both variables, no start, instrument data ---
glass=(--radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22)
"$generator" --kind a,F --radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22 --thickness 20um --work 50mJ/m2 \
  --noise 10uN --noise-x 0.3% --a-range 60um,400um --points 30 --seed 5 --output "$work/both.tsv" || fail "generator (both)"
expect "both variables, no start" 0 "" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma a=0.3%,F=10uN
for key in "chi2/dof" "pull-off force, load control \[N\]" "global search" "weights: effective variance"; do
  grep -q "^# $key" "$work/out" || fail "both variables: no '# $key' header line"
done
w=$(estimate "$work/out" "w [J/m2]"); t=$(estimate "$work/out" "t [m]")
awk -v w="$w" -v t="$t" 'BEGIN { exit !(w > 0.048 && w < 0.052 && t > 19.8e-6 && t < 20.2e-6) }' \
  || fail "both variables: w = $w, t = $t (truth 0.05, 2e-05)"
expect "both variables, --start hint" 0 "" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --start w=0.01,t=50um --sigma a=0.3%,F=10uN
"$generator" --kind delta,F --radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22 --thickness 20um --work 50mJ/m2 \
  --noise 10uN --noise-x 0.3% --a-range 60um,400um --points 30 --seed 4 --output "$work/both_delta.tsv" || fail "generator (delta both)"
expect "delta,F both variables, no start" 0 "" -- "$cli" fit "$work/both_delta.tsv" --columns delta,F "${glass[@]}" --free w,t --sigma delta=0.3%,F=10uN
w=$(estimate "$work/out" "w [J/m2]"); t=$(estimate "$work/out" "t [m]")
awk -v w="$w" -v t="$t" 'BEGIN { exit !(w > 0.048 && w < 0.052 && t > 19.8e-6 && t < 20.2e-6) }' \
  || fail "delta,F both variables: w = $w, t = $t (truth 0.05, 2e-05)"
# the spring pull-off lies between the load- and displacement-controlled ones
expect "spring pull-off" 0 "" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma a=0.3%,F=10uN --spring 500N/m
fs=$(header_value "$work/out" "pull-off force, spring control [N]"); fl=$(header_value "$work/out" "pull-off force, load control [N]")
fd=$(header_value "$work/out" "pull-off force, displacement control [N]")
awk -v s="$fs" -v l="$fl" -v d="$fd" 'BEGIN { exit !(s != "" && s > l && s < d) }' || fail "spring pull-off $fs not between $fl and $fd"
expect "bad --spring" 2 "--spring" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --thickness 20um --spring abc
expect "unweighted says exact a" 0 "" -- "$cli" fit "$data/example_a_F.tsv" --columns a,F "${model[@]}" --thickness 50um
grep -q "^# weights: none.*assume exact a" "$work/out" || fail "unweighted fit does not say the errors assume exact a"
expect "bootstrap" 0 "" -- "$cli" fit "$data/example_a_F.tsv" --columns a,F "${model[@]}" --thickness 50um --bootstrap 20 --seed 3
grep -q "^# w, bootstrap 68% interval \[J/m2\]: " "$work/out" || fail "bootstrap: no interval in the header"
# multi-column export with units in the column names, columns by name and position, stdin
{ echo "time (s),a (um),load (mN),sF (mN)"; grep -v '^#' "$work/both.tsv" | awk '{ print NR "," $1 "," $2 ",0.01" }'; } >"$work/export.csv"
expect "columns by name, units from names" 0 "" -- "$cli" fit "$work/export.csv" --columns a=a,F=load,sigma_F=sF "${glass[@]}" --free w,t --sigma a=0.3%
expect "columns by position from stdin" 0 "" -- bash -c "'$cli' fit - --columns a=2,F=3 ${glass[*]} --free w,t --sigma a=0.3%,F=10uN <'$work/export.csv'"
# bad values: exit 2 naming the option or file:line
expect "bad --sigma name" 2 "--sigma: 'x'" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma x=1%
expect "bad --sigma percent" 2 "--sigma a" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma a=abc%
expect "bad --sigma unit" 2 "--sigma F" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma F=10um
expect "delta sigma on a,F data" 2 "--sigma: 'delta'" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --sigma delta=1nm --thickness 20um
expect "bad --bootstrap" 2 "--bootstrap" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --thickness 20um --bootstrap 3
expect "bad --plot extension" 2 "--plot" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --thickness 20um --plot fit.gif
expect "bad --columns position" 2 "--columns: a=9" -- "$cli" fit "$work/export.csv" --columns a=9,F=3 "${glass[@]}" --thickness 20um
expect "bad --columns name" 2 "no column named 'radius'" -- "$cli" fit "$work/export.csv" --columns a=radius,F=3 "${glass[@]}" --thickness 20um
expect "elastic indenter" 0 "" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma a=0.3%,F=10uN --indenter 70GPa,0.2
grep -q "^# indenter E2 \[Pa\]: 7e+10$" "$work/out" && grep -q "^# indenter nu2: 0.2$" "$work/out" || fail "elastic indenter: not in the header"
expect "bad --indenter" 2 "--indenter" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --thickness 20um --indenter 1GPa
grep -v '^# units' "$work/both.tsv" >"$work/nounits.tsv"
expect "forgotten units" 2 "nounits.tsv:[0-9]+: contact radius .* not below the sphere radius.*# units: um mN" -- \
  "$cli" fit "$work/nounits.tsv" --columns a,F "${glass[@]}" --free w,t
expect "a > R" 2 "both.tsv:[0-9]+: contact radius .* not below the sphere radius" -- \
  "$cli" fit "$work/both.tsv" --columns a,F --radius 0.2mm --film 1MPa,0.5 --substrate 70GPa,0.22 --free w,t
printf '# units: um mN\n60,1\t-0,69\n70,2\t-0,6\n80,3\t-0,3\n' >"$work/comma.tsv"
expect "decimal commas" 2 "comma.tsv:2: .*decimal commas" -- "$cli" fit "$work/comma.tsv" --columns a,F "${glass[@]}" --thickness 20um
# --plot: PNG or PDF by extension, written atomically (nothing left behind on failure)
if command -v gnuplot >/dev/null; then
  expect "plot png" 0 "" -- "$cli" fit "$work/both.tsv" --columns a,F "${glass[@]}" --free w,t --sigma a=0.3%,F=10uN --plot "$work/fit.png"
  [[ $(head -c 4 "$work/fit.png" | tail -c 3) == PNG ]] || fail "plot png: not a PNG file"
  expect "plot pdf (delta,F)" 0 "" -- "$cli" fit "$data/example_delta_F.tsv" --columns delta,F "${model[@]}" --free w,t --plot "$work/fit.pdf"
  [[ $(head -c 4 "$work/fit.pdf") == %PDF ]] || fail "plot pdf: not a PDF file"
  ls "$work" | grep -q '\.tmp\.' && fail "plot: a temporary file was left behind"
fi
# w runs out of its range on unweighted data without adhesion (w = 1e-9 J/m2, noisy a): the
# message hints that noise on a may dominate and names --sigma
"$generator" --kind a,F --radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22 --thickness 20um --work 1e-9 \
  --noise 10uN --noise-x 3% --a-range 60um,400um --points 20 --seed 5 --output "$work/no_adhesion.tsv" || fail "generator (no adhesion)"
expect "w runaway, no --sigma: hint" 3 "do not determine w\. No uncertainties were given.*--sigma a=" -- \
  "$cli" fit "$work/no_adhesion.tsv" --columns a,F "${glass[@]}" --thickness 20um --output "$work/never.tsv"
[[ -e $work/never.tsv ]] && fail "w runaway: an output file was left behind"
# undetermined parameter: exit 3 saying which
expect "undetermined t" 3 "do not determine t" -- \
  "$cli" fit "$data/example_a_F.tsv" --columns a,F --radius 5mm --film 1MPa,0.49 --substrate 1MPa,0.49 --free w,t

finish
