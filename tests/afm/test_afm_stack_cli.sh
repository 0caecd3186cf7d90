#!/usr/bin/env bash
# coatcontact afm fit on a stack of layers (--layer h,E,nu[,slip] repeated, --substrate; issue 35)
# on the real spot3 curve: the header lists the stack as other commands do and names the free
# layer; the estimates of E fixed agree with the one-film fit's within their errors where the
# stack is two identical layers; refusals exit 2 naming the option, the value and what is
# allowed, with no output written.
# Usage: test_afm_stack_cli.sh COATCONTACT DATA_DIR WORK_DIR
set -u
cli="$1"; data="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
spot="$data/fmt-jpk-fd_spot3-0192.jpk-force"
stack=(--radius 10um --layer 1um,5kPa,0.5 --layer 4um,20kPa,0.5 --substrate rigid)

expect_error() {  # CODE FRAGMENT... -- ARGS
  local code="$1"; shift
  local fragments=()
  while [ "$1" != "--" ]; do fragments+=("$1"); shift; done
  shift
  rm -f "$work/out.tsv"
  "$cli" "$@" --output "$work/out.tsv" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  [ "$rc" -eq "$code" ] || fail "exit $rc (wanted $code): $* :: $(cat "$work/stderr")"
  for f in "${fragments[@]}"; do
    grep -qF -- "$f" "$work/stderr" || fail "message lacks '$f': $* :: $(cat "$work/stderr")"
  done
  [ ! -e "$work/out.tsv" ] || fail "an output file was written: $*"
  return 0
}

# ---- a stack, E fixed (cheap: the table's stencil at one modulus) -------------------------------
"$cli" afm fit "$spot" "${stack[@]}" --free contact_point,baseline --output "$work/stack.tsv" 2>"$work/stderr" \
  || fail "stack fit: $(cat "$work/stderr")"
grep -q '^# sample: stack of 2 layers on a rigid substrate' "$work/stack.tsv" || fail "no stack sample line"
grep -q '^# layer 2 (h, E \[Pa\], nu, E\* \[Pa\], interface below): 4e-06, 20000, 0.5, 26666.666666666668, bonded$' \
  "$work/stack.tsv" || fail "layer 2 line: $(grep '^# layer 2' "$work/stack.tsv")"
grep -q '^# free layer: 1 ' "$work/stack.tsv" || fail "free layer line"
grep -q '^# E1 \[Pa\]: 5000 (fixed)$' "$work/stack.tsv" || fail "E1 fixed"
grep -qE '^# contact point \[m\]: [0-9.e+-]+ \+- [0-9.e+-]+$' "$work/stack.tsv" || fail "no contact point +- error"

# Two identical layers (0.7 + 1.3 um) are one film of 2 um: the same z_c and b within 1/100 of
# their errors (the two tables differ by ~1e-6 relative, the noise's errors are ~1e-3).
"$cli" afm fit "$spot" --radius 10um --layer 0.7um,5kPa,0.5 --layer 1.3um,5kPa,0.5 --substrate 1MPa,0.3 \
  --free contact_point,baseline --output "$work/two.tsv" 2>"$work/stderr" || fail "two layers: $(cat "$work/stderr")"
"$cli" afm fit "$spot" --radius 10um --film 5kPa,0.5 --thickness 2um --substrate 1MPa,0.3 \
  --free contact_point,baseline --output "$work/one.tsv" 2>"$work/stderr" || fail "one film: $(cat "$work/stderr")"
for key in 'contact point \[m\]' 'baseline \[N\]'; do
  a=$(sed -nE "s/^# $key: ([^ ]+) \+- ([^ ]+)$/\1 \2/p" "$work/two.tsv")
  b=$(sed -nE "s/^# $key: ([^ ]+) \+- ([^ ]+)$/\1 \2/p" "$work/one.tsv")
  awk -v a="$a" -v b="$b" 'BEGIN { split(a, x, " "); split(b, y, " "); d = x[1] - y[1]; if (d < 0) d = -d;
    printf "identical layers vs one film: %s %s +- %s (difference %.3g SE)\n", "'"$key"'", y[1], y[2], d / y[2];
    exit !(d <= 0.01 * y[2]) }' || fail "identical layers: $key differs by more than SE/100"
done

# One --layer is the one-film shorthand's sample: the same output, line for line (E1 free).
"$cli" afm fit "$spot" --radius 10um --layer 2um,5kPa,0.5 --substrate rigid --output "$work/l1.tsv" 2>"$work/stderr" \
  || fail "one layer: $(cat "$work/stderr")"
"$cli" afm fit "$spot" --radius 10um --film 5kPa,0.5 --thickness 2um --substrate rigid --output "$work/f1.tsv" \
  2>"$work/stderr" || fail "one film: $(cat "$work/stderr")"
diff <(grep -v '^# command\|^# fit time' "$work/l1.tsv") <(grep -v '^# command\|^# fit time' "$work/f1.tsv") >/dev/null \
  || fail "one --layer differs from --film"

# ---- JKR and DMT on a stack (THEORY.md section 15, "JKR and DMT on a stack") -----------------------
# The deeper layer's modulus free: the header names E2 and the estimates carry errors.
"$cli" afm fit "$spot" --radius 10um --layer 1um,5kPa,0.5 --layer 4um,20kPa,0.5 --substrate 1MPa,0.3 --model jkr --free E2,w,contact_point,baseline,tilt \
  --output "$work/jkr.tsv" 2>"$work/stderr" || fail "jkr on a stack: $(cat "$work/stderr")"
grep -qE '^# E2 \[Pa\]: [0-9.e+-]+ \+- [0-9.e+-]+$' "$work/jkr.tsv" || fail "jkr stack: no E2 +- error: $(grep '^# E' "$work/jkr.tsv")"
grep -qE '^# w \[J/m2\]: [0-9.e+-]+ \+- [0-9.e+-]+$' "$work/jkr.tsv" || fail "jkr stack: no w +- error"
# Two identical layers with E fixed are one film: the same JKR header, line for line, but the sample's lines.
"$cli" afm fit "$spot" --radius 10um --layer 0.7um,5kPa,0.5 --layer 1.3um,5kPa,0.5 --substrate 1MPa,0.3 --model dmt \
  --free w,contact_point,baseline,tilt --output "$work/dmt2.tsv" 2>"$work/stderr" || fail "dmt two layers: $(cat "$work/stderr")"
"$cli" afm fit "$spot" --radius 10um --film 5kPa,0.5 --thickness 2um --substrate 1MPa,0.3 --model dmt \
  --free w,contact_point,baseline,tilt --output "$work/dmt1.tsv" 2>"$work/stderr" || fail "dmt one film: $(cat "$work/stderr")"
for key in 'w \[J.m2\]' 'contact point \[m\]' 'baseline \[N\]'; do
  a=$(sed -nE "s/^# $key: ([^ ]+) \+- ([^ ]+)$/\1 \2/p" "$work/dmt2.tsv")
  b=$(sed -nE "s/^# $key: ([^ ]+) \+- ([^ ]+)$/\1 \2/p" "$work/dmt1.tsv")
  awk -v a="$a" -v b="$b" 'BEGIN { split(a, x, " "); split(b, y, " "); d = x[1] - y[1]; if (d < 0) d = -d;
    printf "dmt, identical layers vs one film: %s %s +- %s (difference %.3g SE)\n", "'"$key"'", y[1], y[2], d / y[2];
    exit !(y[2] > 0 && d <= 1e-3 * y[2]) }' || fail "dmt identical layers: $key differs by more than SE/1000"
done

# ---- refusals ------------------------------------------------------------------------------------
expect_error 2 "--free" "'E3'" "allowed with 2 --layer: E1..E2" -- afm fit "$spot" "${stack[@]}" --free E3,contact_point,baseline
expect_error 2 "--free" "one layer's modulus is free at a time" -- afm fit "$spot" "${stack[@]}" --free E1,E2,contact_point
expect_error 2 "--layer" "'5kPa,0.5' has 2 items" "expected h,E,nu" -- afm fit "$spot" --radius 10um --layer 5kPa,0.5 --substrate rigid
expect_error 2 "--thickness" "not with --layer" -- afm fit "$spot" "${stack[@]}" --thickness 2um
expect_error 2 "--layer" "cannot be combined with --film" -- afm fit "$spot" "${stack[@]}" --film 5kPa,0.5
expect_error 2 "--substrate" -- afm fit "$spot" --radius 10um --layer 1um,5kPa,0.5 --layer 4um,20kPa,0.5
expect_error 2 "t is free on one film only" "E1..E2" -- afm fit "$spot" "${stack[@]}" --free t,contact_point,baseline
expect_error 2 "--model md takes one bonded film" "--model hertz, jkr or dmt" -- afm fit "$spot" "${stack[@]}" --model md --work 1mJ/m2
expect_error 2 "--model md takes one bonded film" "a sliding film" -- afm fit "$spot" --radius 10um --layer 2um,5kPa,0.5,slip --substrate rigid --model md --work 1mJ/m2
expect_error 2 "--depth-profile" "takes a half-space or one film" -- afm fit "$spot" "${stack[@]}" --depth-profile
# A free layer started far from what the curve holds: the failure names that layer's modulus.
expect_error 3 "E2 runs out of its search range" -- afm fit "$spot" --radius 10um --layer 1um,5kPa,0.5 \
  --layer 4um,1Pa,0.5 --substrate 1MPa,0.3 --free E2,contact_point,baseline

[ "$failures" -eq 0 ] && echo "all afm stack CLI checks passed"
exit $((failures > 0))
