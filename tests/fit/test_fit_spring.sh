#!/usr/bin/env bash
# `coatcontact fit --columns z,F`: data against the base (piezo) displacement z = delta + F/k of
# a sphere on a spring k; k free (--free w,k).
#   recovery: w and k from 14 noisy points (delta,F of make_synthetic_data, an independent
#     path through ReducedSolver, shifted by F/k with k = 2e5 N/m), within 3 standard errors;
#   bad input (exit 2, naming the option, no output file): z,F without --spring, k free with
#     delta,F data, a bad --start k, z,F with --shape.
# Usage: test_fit_spring.sh COATCONTACT MAKE_SYNTHETIC_DATA
set -u
cli=$1
generator=$2
source "$(dirname "$0")/fit_checks.sh"

glass=(--radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22)
common=(--kind delta,F "${glass[@]}" --thickness 20um --work 50mJ/m2 --a-range 60um,250um --points 14 --seed 4)
# The same rows twice: exact forces (for z) and forces with 10 uN of noise (the measured F).
"$generator" "${common[@]}" --noise 1e-20N --output "$work/clean.tsv" || fail "generator (clean)"
"$generator" "${common[@]}" --noise 10uN --output "$work/noisy.tsv" || fail "generator (noisy)"
grep -q '^# units: um mN' "$work/clean.tsv" || fail "generator: units are no longer um mN"
# z = delta + F/k in um, F in mN: F/k = F[mN] 1e-3 / 2e5 m = F[mN] 5e-3 um.
{ echo "# units: um mN"
  paste <(grep -v '^#' "$work/clean.tsv") <(grep -v '^#' "$work/noisy.tsv") | head -14 |
    awk '{ printf "%.12g\t%.12g\n", $1 + $2 * 5e-3, $4 }'; } >"$work/z.tsv"
start=$(date +%s)
expect "z,F: w,k free" 0 "" -- "$cli" fit "$work/z.tsv" --columns z,F "${glass[@]}" --thickness 20um \
  --spring 1e5 --free w,k --sigma F=10uN
echo "     ($(( $(date +%s) - start )) s)"
if grep -v '^#' "$work/out" | grep -Eiq 'nan|inf'; then fail "z,F: NaN/inf in the output"; fi
within3 "w [J/m2]" "$(estimate "$work/out" "w [J/m2]")" "$(stderr_of "$work/out" "w [J/m2]")" 0.05
within3 "k [N/m]" "$(estimate "$work/out" "k [N/m]")" "$(stderr_of "$work/out" "k [N/m]")" 2e5
hint=$(header_value "$work/out" "k, start of the search [N/m]")
# The header's shortest round-trip text of 1e5 (as every header's numbers): the value, not its spelling.
awk -v h="$hint" 'BEGIN { exit !(h != "" && h + 0 == 100000) }' ||
  fail "z,F: k hint is '$hint', expected the --spring value 100000"
grep -q '^# pull-off force, spring control \[N\]: -' "$work/out" || fail "z,F: no spring pull-off of the fitted k"
# k fixed at its true value: w alone
expect "z,F: k fixed" 0 "" -- "$cli" fit "$work/z.tsv" --columns z,F "${glass[@]}" --thickness 20um --spring 2e5 --sigma F=10uN
within3 "w (k fixed) [J/m2]" "$(estimate "$work/out" "w [J/m2]")" "$(stderr_of "$work/out" "w [J/m2]")" 0.05

# --- bad input: exit 2 ---
expect "z,F without --spring" 2 "--columns z,F: give the spring stiffness with --spring k" -- "$cli" fit "$work/z.tsv" \
  --columns z,F "${glass[@]}" --thickness 20um --free w,k --output "$work/never.tsv"
expect "k free with delta,F data" 2 "--free: 'k' \(the spring stiffness\) is a parameter only of base-displacement data" -- \
  "$cli" fit "$work/z.tsv" --columns delta,F "${glass[@]}" --thickness 20um --spring 1e5 --free w,k --output "$work/never.tsv"
expect "bad --start k" 2 "--start k: 'abc' is not a stiffness" -- "$cli" fit "$work/z.tsv" --columns z,F "${glass[@]}" \
  --thickness 20um --spring 1e5 --free w,k --start k=abc --output "$work/never.tsv"
expect "bad --spring with z,F" 2 "--spring: the stiffness must be > 0" -- "$cli" fit "$work/z.tsv" --columns z,F "${glass[@]}" \
  --thickness 20um --spring -5 --free w,k --output "$work/never.tsv"
expect "z,F with --shape" 2 "--columns z,F: .*not --shape" -- "$cli" fit "$work/z.tsv" --columns z,F --shape cone:80deg \
  --film 1MPa,0.5 --substrate 70GPa,0.22 --thickness 20um --spring 1e5 --output "$work/never.tsv"
expect "sigma delta on z,F data" 2 "--sigma: 'delta' is not a column of these data \(allowed: z, F\)" -- "$cli" fit "$work/z.tsv" \
  --columns z,F "${glass[@]}" --thickness 20um --spring 1e5 --sigma delta=1nm --output "$work/never.tsv"
[[ -e $work/never.tsv ]] && fail "an output file was left behind"

finish
