#!/bin/bash
# Issue 40 item 8, one case per message (label cli): a run given in SI units is answered in
# them. Each message names the value the user gave in its units and the allowed range in the
# same units, checked here against the scales computed in this script (THEORY.md section 5:
# L = (pi w R^2/E1*)^(1/3), eta = t/L in [1e-6, 1e6]; section 13: Maugis's
# lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3, in [1e-3, 1e4]); the reduced value
# comes only in parentheses.
# Usage: test_issue40_messages.sh PATH/TO/coatcontact DATA_DIR CASE
source "$(dirname "$0")/cli_case_preamble.sh"

# close A B: |A/B - 1| < 1e-4 (the messages print 6 significant digits).
close() { awk -v a="$1" -v b="$2" 'BEGIN { d = a / b - 1; exit !(b != 0 && d < 1e-4 && d > -1e-4) }'; }
# bracket NAME UNIT: the two numbers of "NAME in [LO, HI] UNIT" in err.
bracket() { sed -n "s|.*$1 in \[\([^,]*\), \([^]]*\)\] $2.*|\1 \2|p" err | head -n 1; }

R=1e-6 W=0.01 E1=1e9 NU1=0.3
STACK=(--radius 1um --film 1e9,0.3 --substrate 1e10,0.3 --work 0.01)
L=$(awk -v r=$R -v w=$W -v e=$E1 -v nu=$NU1 'BEGIN { printf "%.10g", exp(log(3.14159265358979 * w * r * r / (e / (1 - nu * nu))) / 3) }')

case "$case_name" in
values_quoted_in_reduced_units)
  # A film too thin for the model: t in m and its allowed range in m (was "eta = ... is outside").
  expect_error "film thickness t = 1e-15 m not allowed" sphere "${STACK[@]}" --thickness 1e-15
  read -r lo hi <<<"$(bracket "allowed: t" m)"
  close "$lo" "$(awk -v l="$L" 'BEGIN { print 1e-6 * l }')" && close "$hi" "$(awk -v l="$L" 'BEGIN { print 1e6 * l }')" &&
    ok "allowed t [$lo, $hi] m = [1e-6, 1e6] L, L = $L m" || fail "allowed t [$lo, $hi] m, L = $L m"
  grep -q "error: [^(]*eta = " err && fail "eta quoted before the thickness" || ok "eta only in parentheses"
  # sigma0 outside the lambda range: sigma0 and h0 in Pa and m with their allowed ranges.
  for given in "--cohesive-stress 1e15" "--range 1e-6"; do
    # shellcheck disable=SC2086
    expect_error "${given%% *}: sigma0 = " sphere "${STACK[@]}" --thickness 100nm $given
    read -r lo hi <<<"$(bracket "allowed: sigma0" Pa)"
    want=$(awk -v r=$R -v w=$W -v e=$E1 -v nu=$NU1 'BEGIN { k = 4 * e / (1 - nu * nu) / 3
             s = exp(log(3.14159265358979 * w * k * k / r) / 3) / 2; print 1e-3 * s, 1e4 * s }')
    close "$lo" "${want% *}" && close "$hi" "${want#* }" && ok "$given: allowed sigma0 [$lo, $hi] Pa = lambda [1e-3, 1e4]" ||
      fail "$given: allowed sigma0 [$lo, $hi] Pa, expected [$want]"
    grep -q "h0 in \[" err && ok "$given: h0's range too" || fail "$given: no h0 range"
    grep -q "error: [^(]*lambda [0-9]" err && fail "$given: lambda quoted before sigma0" || ok "$given: lambda only in parentheses"
  done
  ;;
kinetics_radii_quoted_in_metres)
  # An SI kinetics run whose contact radii leave the solver's a/t (was "kinetics: eta = 2e-06
  # puts the contact radii [0.01, 100] outside the table's range of a/t"): the radii in m,
  # 0.01 L to 100 L on a rigid substrate, and the allowed --thickness in m.
  E1=1e6 NU1=0.5 W=0.05 R=1e-3
  L=$(awk -v r=$R -v w=$W -v e=$E1 -v nu=$NU1 'BEGIN { printf "%.10g", exp(log(3.14159265358979 * w * r * r / (e / (1 - nu * nu))) / 3) }')
  expect_error "--thickness: thickness t = 1e-10 m puts the contact radii" kinetics --radius 1mm --film 1MPa,0.5 \
    --substrate rigid --work 50mJ/m2 --v-star 1um/s --n 0.5 --spring 1e3 --thickness 1e-10 \
    --protocol approach:1um/s:1mN,dwell:1s,retract:10um/s
  read -r a0 a1 <<<"$(sed -n 's|.*contact radii of the run (\([^ ]*\) to \([^ ]*\) m).*|\1 \2|p' err)"
  close "$a0" "$(awk -v l="$L" 'BEGIN { print 0.01 * l }')" && close "$a1" "$(awk -v l="$L" 'BEGIN { print 100 * l }')" &&
    ok "radii [$a0, $a1] m = [0.01, 100] L_a, L_a = $L m" || fail "radii [$a0, $a1] m, L_a = $L m"
  read -r lo hi <<<"$(bracket "allowed: t" m)"
  close "$lo" "$(awk -v a="$a1" 'BEGIN { print a / 1e6 }')" && close "$hi" "$(awk -v a="$a0" 'BEGIN { print a / 1e-6 }')" &&
    ok "allowed t [$lo, $hi] m keeps a/t in [1e-6, 1e6]" || fail "allowed t [$lo, $hi] m"
  grep -q "kinetics: eta = " err && fail "reduced eta message" || ok "no reduced eta message"
  ;;
pulloff_warnings_quoted_in_metres)
  # A stiff film on a soft substrate (eta = 0.01): two local minima of P and D. The sphere's
  # warnings gave a_bar ranges and values and "eta=0.01: "; now contact radii in m, a_bar in
  # parentheses, each radius = a_bar x the header's length scale.
  run 0 sphere --radius 1mm --thickness 13nm --film 70GPa,0.2 --substrate 1MPa,0.49 --work 0.05 || true
  L=$(sed -n 's|^# length scale (pi w R^2/E1\*)^(1/3) \[m\]: ||p' out)
  grep -q '^# warning: eta=' out && fail "a warning starts with eta=" || ok "no eta= prefix"
  line=$(grep -m 1 '^# warning: load control (minimum of P): 2 local minima in contact radii' out)
  [ -n "$line" ] && ok "load control warning in contact radii" || fail "no SI warning: $(grep '^# warning' out | head -2)"
  read -r lo hi blo bhi a ba <<<"$(echo "$line" | sed -n 's|.*radii \[\([^,]*\), \([^]]*\)\] m (a_bar \[\([^,]*\), \([^]]*\)\]).*(a = \([^ ]*\) m (a_bar=\([^)]*\))).*|\1 \2 \3 \4 \5 \6|p')"
  close "$lo" "$(awk -v b="$blo" -v l="$L" 'BEGIN { print b * l }')" && close "$hi" "$(awk -v b="$bhi" -v l="$L" 'BEGIN { print b * l }')" &&
    close "$a" "$(awk -v b="$ba" -v l="$L" 'BEGIN { print b * l }')" && ok "radii = a_bar x L ($lo, $hi, $a m; L = $L m)" ||
    fail "radii '$lo' '$hi' '$a' against a_bar '$blo' '$bhi' '$ba' x L = $L"
  pull=$(sed -n 's|^# pull-off contact radius, load control \[m\]: ||p' out)
  close "$a" "$pull" && ok "the reported minimum is the header's pull-off radius" || fail "a = $a, header $pull"
  ;;
*) unknown_case ;;
esac
finish_cases
