#!/bin/sh
# Bad input to `adhesive`, `pulloff` and `sphere`: exit code 2 and a message naming the
# option, one case per option (cli_support conventions). Usage: cli_bad_input.sh COATCONTACT
bin="$1"
fail=0
tmp="${TMPDIR:-/tmp}/cc_adhesive_bad_$$"
trap 'rm -f "$tmp"' EXIT

# expect_bad NAME_IN_MESSAGE ARGS...: exit 2 and NAME_IN_MESSAGE in stderr.
expect_bad() {
  want="$1"
  shift
  "$bin" "$@" >/dev/null 2>"$tmp"
  rc=$?
  if [ "$rc" -ne 2 ] || ! grep -q -F -- "$want" "$tmp"; then
    echo "FAIL: coatcontact $* -> exit $rc, stderr: $(cat "$tmp") (wanted exit 2 naming $want)"
    fail=1
  else
    echo "ok   coatcontact $* -> exit 2: $(head -n 1 "$tmp")"
  fi
}

F="--film 1GPa,0.25"
S="--substrate 10GPa,0.25"
for cmd in adhesive pulloff; do
  expect_bad --film $cmd --film abc $S --eta 1
  expect_bad --film $cmd --film 1e9,0.7 $S --eta 1
  expect_bad --film $cmd --film -1e9,0.2 $S --eta 1
  expect_bad --film $cmd $S --eta 1
  expect_bad --substrate $cmd $F --substrate soft --eta 1
  expect_bad --substrate $cmd $F --substrate 0,0.3 --eta 1
  expect_bad --eta $cmd $F $S --eta=
  expect_bad --eta $cmd $F $S --eta 1,,2
  expect_bad --eta $cmd $F $S --eta 0
  expect_bad --eta $cmd $F $S --eta=-1
  expect_bad --eta $cmd $F $S --eta abc
  expect_bad --eta $cmd $F $S
  expect_bad --tol $cmd $F $S --eta 1 --tol 0
  expect_bad --tol $cmd $F $S --eta 1 --tol 1
  expect_bad --tol $cmd $F $S --eta 1 --tol x
  expect_bad /nonexistent-dir/out.tsv $cmd $F $S --eta 1 --output /nonexistent-dir/out.tsv
  expect_bad --bogus $cmd $F $S --eta 1 --bogus 3
done
expect_bad --a-bar adhesive $F $S --eta 1 --a-bar 0,1
expect_bad --a-bar adhesive $F $S --eta 1 --a-bar=-0.5
expect_bad --a-bar adhesive $F $S --eta 1 --a-bar 1:0.1:5
expect_bad --a-bar adhesive $F $S --eta 1 --a-bar nan

G="--radius 5um --thickness 1um $F $S --work 50mJ/m2"
expect_bad --radius sphere --radius 0 --thickness 1um $F $S --work 0.05
expect_bad --radius sphere --radius -5um --thickness 1um $F $S --work 0.05
expect_bad --radius sphere --radius 5parsec --thickness 1um $F $S --work 0.05
expect_bad --radius sphere --thickness 1um $F $S --work 0.05
expect_bad --thickness sphere --radius 5um --thickness 0 $F $S --work 0.05
expect_bad --thickness sphere --radius 5um --thickness=-1nm $F $S --work 0.05
expect_bad --work sphere --radius 5um --thickness 1um $F $S --work 0
expect_bad --work sphere --radius 5um --thickness 1um $F $S --work=-0.05
expect_bad --work sphere --radius 5um --thickness 1um $F $S --work 5GPa
expect_bad --work sphere --radius 5um --thickness 1um $F $S
expect_bad --film sphere --radius 5um --thickness 1um --film 1e9 $S --work 0.05
expect_bad --substrate sphere --radius 5um --thickness 1um $F --substrate rigidd --work 0.05
expect_bad --points sphere $G --points 1
expect_bad --points sphere $G --points 2.5
expect_bad --points sphere $G --points many
expect_bad --tol sphere $G --tol 1e-20
expect_bad /nonexistent-dir/s.tsv sphere $G --output /nonexistent-dir/s.tsv

# --help: exit 0 and a usage line
for cmd in adhesive pulloff sphere; do
  if ! "$bin" $cmd --help | grep -q "usage: coatcontact $cmd"; then
    echo "FAIL: coatcontact $cmd --help"
    fail=1
  fi
done
[ "$fail" -eq 0 ] && echo "cli_bad_input: all checks passed"
exit $fail
