#!/bin/sh
# Maugis-Dugdale options of `adhesive`, `pulloff` and `sphere` (THEORY.md section 13):
# bad input (lambda <= 0 or out of range, both --cohesive-stress and --range, a range above
# 1e6 film thicknesses) -> exit 2, a message naming the option, no output file; `--lambda inf`
# gives exactly the JKR output. Usage: cli_md_bad_input.sh COATCONTACT
bin="$1"
fail=0
tmp="${TMPDIR:-/tmp}/cc_md_bad_$$"
out="${TMPDIR:-/tmp}/cc_md_out_$$.tsv"
trap 'rm -f "$tmp" "$tmp.a" "$tmp.b" "$out"' EXIT

# expect_bad NAME_IN_MESSAGE ARGS...: exit 2, NAME_IN_MESSAGE in stderr, no --output file.
expect_bad() {
  want="$1"
  shift
  rm -f "$out"
  "$bin" "$@" --output "$out" >/dev/null 2>"$tmp"
  rc=$?
  if [ "$rc" -ne 2 ] || ! grep -q -F -- "$want" "$tmp" || [ -e "$out" ]; then
    echo "FAIL: coatcontact $* -> exit $rc, stderr: $(cat "$tmp") (wanted exit 2 naming $want, no file)"
    fail=1
  else
    echo "ok   coatcontact $* -> exit 2: $(head -n 1 "$tmp")"
  fi
}

F="--film 1GPa,0.25"
S="--substrate 10GPa,0.25"
for cmd in adhesive pulloff; do
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda 0
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda=-1
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda 1,-0.5
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda abc
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda 1,,2
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda 1,
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda 1e-5
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda 1e9
  expect_bad --lambda: $cmd $F $S --eta 1 --lambda nan
done
G="--radius 5um --thickness 1um $F $S --work 50mJ/m2"
expect_bad "--cohesive-stress and --range" sphere $G --cohesive-stress 10MPa --range 5nm
expect_bad --range: sphere $G --range 2m
expect_bad --range: sphere $G --range 0
expect_bad --range: sphere $G --range abc
expect_bad --cohesive-stress: sphere $G --cohesive-stress 0
expect_bad --cohesive-stress: sphere $G --cohesive-stress=-1MPa
expect_bad --cohesive-stress: sphere $G --cohesive-stress 1e-30

# --lambda inf (alone) is JKR: byte-identical to the output without --lambda, but for the
# "# command:" line, which echoes the command as typed.
no_command() { grep -v '^# command:' "$1" > "$1.body"; mv "$1.body" "$1"; }
"$bin" adhesive $F $S --eta 1 --a-bar 0.5,1 >"$tmp.a"
"$bin" adhesive $F $S --eta 1 --a-bar 0.5,1 --lambda inf >"$tmp.b"
no_command "$tmp.a"; no_command "$tmp.b"
if cmp -s "$tmp.a" "$tmp.b" && [ -s "$tmp.a" ]; then echo "ok   adhesive --lambda inf is the JKR output"
else echo "FAIL: adhesive --lambda inf differs from the output without --lambda"; fail=1; fi
"$bin" pulloff $F $S --eta 1 >"$tmp.a"
"$bin" pulloff $F $S --eta 1 --lambda inf >"$tmp.b"
no_command "$tmp.a"; no_command "$tmp.b"
if cmp -s "$tmp.a" "$tmp.b" && [ -s "$tmp.a" ]; then echo "ok   pulloff --lambda inf is the JKR output"
else echo "FAIL: pulloff --lambda inf differs from the output without --lambda"; fail=1; fi
exit $fail
