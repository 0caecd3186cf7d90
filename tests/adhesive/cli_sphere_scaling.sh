#!/bin/sh
# THEORY.md section 5 normalization [EqSolNormF, EqSolNormD]: `sphere` (SI units) agrees with
# `adhesive` and `pulloff` (normalized) after scaling, and its header scales match the
# formulas l = (pi w R^2/E1*)^(1/3), delta scale l^2/R, force scale pi w R, eta = t/l
# (computed here independently with awk). Usage: cli_sphere_scaling.sh COATCONTACT
set -u
bin="$1"
dir="${TMPDIR:-/tmp}/cc_adhesive_scaling_$$"
mkdir -p "$dir"
trap 'rm -rf "$dir"' EXIT
fail=0
# Both paths use the same interpolation segments (nodes fixed per decade of a/t), so they
# agree to rounding; 1e-10 relative leaves a wide margin over the ~1e-15 expected.
tier=1e-10

R=5e-6; T=2e-7; W=0.05; E1=1e9; NU1=0.3; E0=1e10; NU0=0.25
"$bin" sphere --radius 5um --thickness 200nm --film 1GPa,0.3 --substrate 10GPa,0.25 --work 50mJ/m2 \
  --points 41 --output "$dir/sphere.tsv" || { echo "FAIL: sphere exited $?"; exit 1; }
header() { grep "^# $1:" "$dir/sphere.tsv" | head -n 1 | sed 's/^[^:]*: //'; }
L=$(header "length scale (pi w R^2\/E1\*)^(1\/3) \[m\]")
ETA=$(header "eta = t\/length scale")
FL=$(header "pull-off force, load control \[N\]")
FD=$(header "pull-off force, displacement control \[N\]")
echo "length scale $L, eta $ETA, pull-off forces $FL (load) $FD (displacement)"
[ -n "$L" ] && [ -n "$ETA" ] && [ -n "$FL" ] && [ -n "$FD" ] || { echo "FAIL: missing header lines"; exit 1; }

# close A B WHAT: |A-B| <= tier max(|B|, tiny)
close() {
  if awk -v a="$1" -v b="$2" -v t="$tier" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b;
        exit !(d <= t * m + 1e-300) }'; then
    echo "ok   $3: $1 vs $2"
  else
    echo "FAIL $3: $1 vs $2"
    fail=1
  fi
}
close "$L" "$(awk -v w=$W -v r=$R -v e=$E1 -v nu=$NU1 'BEGIN { printf "%.17g", exp(log(3.14159265358979324 * w * r * r / (e / (1 - nu * nu))) / 3) }')" "length scale"
close "$ETA" "$(awk -v t=$T -v l="$L" 'BEGIN { printf "%.17g", t / l }')" "eta"

"$bin" pulloff --film 1GPa,0.3 --substrate 10GPa,0.25 --eta "$ETA" --output "$dir/pulloff.tsv" || { echo "FAIL: pulloff"; exit 1; }
row=$(grep -v '^#' "$dir/pulloff.tsv" | head -n 1)
PL=$(echo "$row" | cut -f2); PD=$(echo "$row" | cut -f5)
close "$FL" "$(awk -v p="$PL" -v w=$W -v r=$R 'BEGIN { printf "%.17g", p * 3.14159265358979324 * w * r }')" "load-control pull-off force = P_load pi w R"
close "$FD" "$(awk -v p="$PD" -v w=$W -v r=$R 'BEGIN { printf "%.17g", p * 3.14159265358979324 * w * r }')" "disp-control pull-off force = P_disp pi w R"

# Curves: a_bar = a/l for every sphere row, then F = P pi w R, delta = D l^2/R.
abar=$(grep -v '^#' "$dir/sphere.tsv" | awk -v l="$L" '{ printf "%s%.17g", (NR > 1 ? "," : ""), $1 / l }')
"$bin" adhesive --film 1GPa,0.3 --substrate 10GPa,0.25 --eta "$ETA" --a-bar "$abar" --output "$dir/adhesive.tsv" ||
  { echo "FAIL: adhesive"; exit 1; }
grep -v '^#' "$dir/sphere.tsv" > "$dir/s.rows"
grep -v '^#' "$dir/adhesive.tsv" | grep -v '^$' > "$dir/a.rows"
n_s=$(wc -l < "$dir/s.rows"); n_a=$(wc -l < "$dir/a.rows")
[ "$n_s" -eq 41 ] && [ "$n_a" -eq 41 ] || { echo "FAIL: row counts $n_s $n_a (want 41)"; exit 1; }
# Compared in normalized units, relative to max(1, |value|) (P and D cross zero).
worst=$(paste "$dir/s.rows" "$dir/a.rows" | awk -v w=$W -v r=$R -v l="$L" '
  function rel(a, b,   d, s) { d = a - b; if (d < 0) d = -d; s = b < 0 ? -b : b; if (s < 1) s = 1; return d / s }
  { p = $3 / (3.14159265358979324 * w * r); dd = $2 * r / (l * l);
    e1 = rel(p, $7); e2 = rel(dd, $8); if (e1 > worst) worst = e1; if (e2 > worst) worst = e2 }
  END { printf "%.3g", worst }')
if awk -v x="$worst" -v t=$tier 'BEGIN { exit !(x <= t) }'; then
  echo "ok   worst relative difference, sphere vs scaled adhesive curve (41 rows): $worst"
else
  echo "FAIL worst relative difference, sphere vs scaled adhesive curve (41 rows): $worst > $tier"
  fail=1
fi
[ "$fail" -eq 0 ] && echo "cli_sphere_scaling: all checks passed"
exit $fail
