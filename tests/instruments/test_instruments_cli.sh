#!/usr/bin/env bash
# CLI of the real-instrument options (THEORY.md sections 9-11): --indenter on every command
# that takes materials, pulloff --spring-bar, and the contact command. Bad values get exit 2,
# a message naming the option and value, nothing on stdout and no output file.
# Usage: test_instruments_cli.sh PATH/TO/coatcontact
set -u
cli="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# The contact command without --shape (each row adds its own) and without a radius option.
contact=(contact --thickness=1um --film=1GPa,0.3 --substrate=10GPa,0.25 --work=50mJ/m2)

# Good lines run and print what they should.
"$cli" kernel --film=1GPa,0.25 --substrate=10GPa,0.25 --indenter=1GPa,0.25 --q=0 >"$work/k" || fail "kernel --indenter"
grep -q "^0	0.55000000000000004$" "$work/k" || fail "kernel C'(0) with rho = 1: $(tail -1 "$work/k")"
grep -q "^# reference modulus E_r" "$work/k" || fail "kernel header without E_r"
for cmd in "reduced --a-over-t=1" "adhesive --eta=1 --a-bar=1" "pulloff --eta=1" \
           "sphere --radius=5um --thickness=1um --work=50mJ/m2 --points=5"; do
  # shellcheck disable=SC2086
  "$cli" $cmd --film=1GPa,0.3 --substrate=10GPa,0.25 --indenter=2GPa,0.2 >"$work/o" 2>"$work/e" ||
    fail "$cmd --indenter: $(cat "$work/e")"
  grep -q "^# indenter E2\* \[Pa\]" "$work/o" || fail "$cmd: no indenter header"
done
"$cli" pulloff --film=1GPa,0.3 --substrate=10GPa,0.25 --eta=1 --spring-bar=0,1,inf >"$work/p" || fail "pulloff --spring-bar"
[ "$(grep -vc '^#' "$work/p")" = 3 ] || fail "pulloff --spring-bar: 3 rows expected"
# The spring columns follow the six pull-off values; the error estimates of the six come after them.
grep -q "D_disp	k_bar	P_spring	a_bar_spring	D_spring	P_load_err	" "$work/p" || fail "pulloff --spring-bar columns"
for shape in sphere:5um cone:70deg punch:1um power:3,5um blunted-cone:50nm,70deg; do
  # A flat punch has one contact radius, its own: --points is refused for it (issue 29, defect 5).
  points=(--points=10)
  [ "${shape%%:*}" = punch ] && points=()
  "$cli" contact --shape=$shape --thickness=1um --film=1GPa,0.3 --substrate=10GPa,0.25 --work=50mJ/m2 \
    "${points[@]}" --spring=1 >"$work/c" 2>"$work/e" || fail "contact --shape=$shape: $(cat "$work/e")"
  grep -q "^# pull-off force, spring control \[N\]" "$work/c" || fail "contact $shape: no spring line"
  grep -q "^# columns: a_m	delta_m	F_N	delta_H_m	F_H_N$" "$work/c" || fail "contact $shape: columns"
done
# A sampled sphere cap (units in um) as a profile.
{
  echo "# units: um um"
  for i in $(seq 0 40); do awk -v i="$i" 'BEGIN { r = i * 0.1; printf "%.10g %.10g\n", r, 10 - sqrt(100 - r * r) }'; done
} >"$work/tip.txt"
"$cli" contact --shape=profile:"$work/tip.txt" --thickness=1um --film=1GPa,0.3 --substrate=10GPa,0.25 \
  --work=50mJ/m2 --contact-radius=0.5um,1um,3um >"$work/c" 2>"$work/e" || fail "contact profile: $(cat "$work/e")"
grep -q "^# profile interpolation error estimate" "$work/c" || fail "contact profile: no error estimate"

# bad CMD_AND_ARGS... : expect exit 2, EXPECT in stderr, no stdout, no --output file.
bad() {
  local expect="$1"
  shift
  rm -f "$work/out.tsv"
  "$cli" "$@" --output="$work/out.tsv" >"$work/o" 2>"$work/e"
  local rc=$?
  [ $rc -eq 2 ] || fail "$* -> exit $rc (expected 2)"
  grep -qF -- "$expect" "$work/e" || fail "$* -> message without '$expect': $(cat "$work/e")"
  [ -s "$work/o" ] && fail "$* -> stdout not empty"
  [ -e "$work/out.tsv" ] && fail "$* -> output file written"
}
for value in 1GPa,0.6 1GPa,-1 -1GPa,0.3 0,0.3 abc 1GPa; do
  bad "--indenter" kernel --film=1GPa,0.3 --substrate=rigid --indenter=$value --q=1
  bad "--indenter" pulloff --film=1GPa,0.3 --substrate=rigid --indenter=$value --eta=1
done
for value in -1 abc nan -inf 1,,2 0:1:3; do
  bad "--spring-bar" pulloff --film=1GPa,0.3 --substrate=rigid --eta=1 --spring-bar=$value
done
for shape in sphere:0 sphere:-1um cone:0deg cone:90deg cone:95deg cone:-5deg power:0,1um power:-2,1um \
             power:2 blunted-cone:1um,0deg blunted-cone:0,70deg punch:-1 ellipse:1um sphere; do
  bad "--shape" "${contact[@]}" --points=20 --shape=$shape
done
for value in 0 -1 abc nan; do
  bad "--spring" "${contact[@]}" --shape=sphere:5um --spring=$value
done
bad "--indenter" "${contact[@]}" --shape=sphere:5um --indenter=1GPa,0.7
bad "--contact-radius" "${contact[@]}" --shape=sphere:5um --contact-radius=-1um
bad "--points" "${contact[@]}" --shape=sphere:5um --points=1
bad "exclude" "${contact[@]}" --shape=sphere:5um --points=20 --contact-radius=1um
# Profiles: not at r = 0, unsorted, non-monotonic, malformed, too short for the radii.
printf '0.1 0\n0.2 0.1\n0.3 0.2\n0.4 0.3\n0.5 0.4\n' >"$work/p1.txt"
bad "p1.txt:1" "${contact[@]}" --points=20 --shape=profile:"$work/p1.txt"
printf '0 0\n0.2 0.1\n0.1 0.2\n0.4 0.3\n0.5 0.4\n' >"$work/p2.txt"
bad "p2.txt:3" "${contact[@]}" --points=20 --shape=profile:"$work/p2.txt"
printf '0 0\n0.1 0.1\n0.2 0.05\n0.4 0.3\n0.5 0.4\n' >"$work/p3.txt"
bad "p3.txt:3" "${contact[@]}" --points=20 --shape=profile:"$work/p3.txt"
printf '0 0\n0.1 abc\n' >"$work/p4.txt"
bad "p4.txt:2" "${contact[@]}" --points=20 --shape=profile:"$work/p4.txt"
printf '0 0\n1e-7 1e-9\n2e-7 4e-9\n3e-7 9e-9\n4e-7 1.6e-8\n' >"$work/p5.txt"
bad "exceeds" "${contact[@]}" --shape=profile:"$work/p5.txt" --contact-radius=1um
bad "missing.txt" "${contact[@]}" --shape=profile:"$work/missing.txt"

if [ $failures -ne 0 ]; then
  echo "test_instruments_cli: $failures failure(s)"
  exit 1
fi
echo "test_instruments_cli: all checks passed"
