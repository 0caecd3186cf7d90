#!/usr/bin/env bash
# Regression (issue 29, defect 6): the validity warnings of the SI commands (a > 0.1 R, delta > t,
# mean pressure > 0.1 E*) were missing from `fit`, whose fitted model could run past the
# paraboloid's range silently. The example data reach a = 235.5 um: fitted with R = 1.5 mm
# (0.1 R = 150 um) the model must be flagged in the output header and on stderr; with the
# generator's R = 5 mm (0.1 R = 500 um) it must not.
# Usage: test_regression_fit_validity_warnings.sh PATH/TO/coatcontact PATH/TO/data/example_a_F.tsv
set -u
cli="$1"
data="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
model=(--columns a,F --film 1MPa,0.49 --substrate 70GPa,0.22 --free w,t --start t=40um)
if "$cli" fit "$data" "${model[@]}" --radius 1.5mm --output "$work/small.tsv" 2>"$work/err"; then
  grep -q '^# warning: fitted model: contact radius reaches .* above 0.1 R = 0.00015 m' "$work/small.tsv" ||
    fail "R = 1.5 mm: no a > 0.1 R warning in the output header"
  grep -q '^coatcontact fit: warning: fitted model: contact radius reaches' "$work/err" ||
    fail "R = 1.5 mm: no warning on stderr"
else
  fail "R = 1.5 mm: exit non-zero: $(head -c 300 "$work/err")"
fi
if "$cli" fit "$data" "${model[@]}" --radius 5mm --output "$work/valid.tsv" 2>"$work/err"; then
  ! grep -q '^# warning: fitted model' "$work/valid.tsv" || fail "R = 5 mm: a warning inside every limit"
  ! grep -q 'warning: fitted model' "$work/err" || fail "R = 5 mm: a warning on stderr inside every limit"
else
  fail "R = 5 mm: exit non-zero: $(head -c 300 "$work/err")"
fi
[ "$failures" -eq 0 ] && echo "ok   fit validity warnings" || exit 1
