#!/usr/bin/env bash
# `coatcontact fit --shape`: a fit with any indenter of `contact --shape` (THEORY.md section 11).
#   recovery: w and t from noisy cone data made by `coatcontact contact --shape` (an
#     independent path: the curve at given radii, no fit code), within 3 standard errors;
#   bad input (exit 2, naming --shape, no output file): a bad spec, --shape with --radius.
# Usage: test_fit_shapes.sh COATCONTACT
set -u
cli=$1
source "$(dirname "$0")/fit_checks.sh"

# A blunt cone (beta = 80 deg) on a soft film, adhesion and the substrate both visible:
# 14 contact radii 1..20 um (a/t 0.2..4), Gaussian noise of 0.2 uN (fixed deviates) on F.
material=(--film 1MPa,0.49 --substrate 70GPa,0.22)
"$cli" contact --shape cone:80deg --thickness 5um "${material[@]}" --work 50mJ/m2 \
  --contact-radius 1e-6:20e-6:14 --output "$work/clean.tsv" || fail "contact --shape cone (data)"
noise="-0.256 0.511 -0.226 -0.315 -0.930 -0.213 1.112 0.424 1.037 0.249 0.395 0.185 -1.666 0.855"
grep -v '^#' "$work/clean.tsv" | awk -v n="$noise" 'BEGIN { split(n, z, " ") } { printf "%.12e\t%.12e\n", $1, $3 + 2e-7 * z[NR] }' \
  >"$work/cone.tsv"
start=$(date +%s)
expect "cone: w,t free" 0 "" -- "$cli" fit "$work/cone.tsv" --columns a,F --shape cone:80deg "${material[@]}" \
  --free w,t --sigma F=0.2uN
echo "     ($(( $(date +%s) - start )) s)"
grep -q "^# indenter shape: cone" "$work/out" || fail "cone: no indenter shape header line"
if grep -v '^#' "$work/out" | grep -Eiq 'nan|inf'; then fail "cone: NaN/inf in the output"; fi
within3 "cone w [J/m2]" "$(estimate "$work/out" "w [J/m2]")" "$(stderr_of "$work/out" "w [J/m2]")" 0.05
within3 "cone t [m]" "$(estimate "$work/out" "t [m]")" "$(stderr_of "$work/out" "t [m]")" 5e-6

# --- bad input: exit 2 naming --shape, nothing written ---
expect "unknown shape" 2 "--shape: unknown shape 'wedge'" -- "$cli" fit "$work/cone.tsv" --columns a,F \
  --shape wedge:3 "${material[@]}" --thickness 5um --output "$work/never.tsv"
expect "cone angle out of range" 2 "--shape: 'cone:95deg': half included angle" -- "$cli" fit "$work/cone.tsv" --columns a,F \
  --shape cone:95deg "${material[@]}" --thickness 5um --output "$work/never.tsv"
expect "shape without parameters" 2 "--shape: 'cone' has no parameters" -- "$cli" fit "$work/cone.tsv" --columns a,F \
  --shape cone "${material[@]}" --thickness 5um --output "$work/never.tsv"
expect "--shape with --radius" 2 "--shape and --radius" -- "$cli" fit "$work/cone.tsv" --columns a,F \
  --shape cone:80deg --radius 1mm "${material[@]}" --thickness 5um --output "$work/never.tsv"
expect "neither --shape nor --radius" 2 "--radius R \(or --shape SPEC\)" -- "$cli" fit "$work/cone.tsv" --columns a,F \
  "${material[@]}" --thickness 5um --output "$work/never.tsv"
[[ -e $work/never.tsv ]] && fail "an output file was left behind"

finish
