#!/usr/bin/env bash
# CLI tests of `coatcontact kernel` (label cli). Usage: test_kernel_cli.sh PATH/TO/coatcontact
set -u
cli="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_exit CODE PATTERN ARGS...: exit code CODE and PATTERN in stderr.
expect_exit() {
  local code="$1" pattern="$2"
  shift 2
  "$cli" kernel "$@" >"$work/out" 2>"$work/err"
  local got=$?
  [ "$got" -eq "$code" ] || fail "kernel $* exited $got, expected $code"
  grep -q -- "$pattern" "$work/err" || fail "kernel $*: stderr lacks '$pattern': $(cat "$work/err")"
  [ -s "$work/out" ] && fail "kernel $*: printed data despite the error"
  return 0
}

expect_exit 2 "film" --film -1,0.3 --substrate 1,0.3
expect_exit 2 "substrate" --film 1,0.3 --substrate 0,0.3
expect_exit 2 "0.6" --film 1,0.6 --substrate 1,0.3
expect_exit 2 "0.6" --film 1,0.3 --substrate 1,0.6
expect_exit 2 "--q" --film 1,0.3 --substrate 1,0.3 --q 1,,2
expect_exit 2 "--u" --film 1,0.3 --substrate 1,0.3 --u 1:0.5:x
expect_exit 2 "--film" --substrate 1,0.3
expect_exit 2 "--q" --film 1,0.3 --substrate rigid --q=-1

# --output into a missing folder: exit 2, a message naming the path, no file anywhere.
"$cli" kernel --film 1,0.3 --substrate rigid --output "$work/missing/table.tsv" 2>"$work/err"
[ $? -eq 2 ] || fail "--output to a missing folder did not exit 2"
grep -q "missing" "$work/err" || fail "--output message does not name the path: $(cat "$work/err")"
[ -e "$work/missing" ] && fail "--output created the missing folder"

# A normal run: header lines, the columns line and tab-separated rows with C(0) = E1*/E0*.
"$cli" kernel --film 0.1,0.25 --substrate 1,0.25 --q 0,1,100 --output "$work/c.tsv" || fail "normal run exit"
grep -q "^# E1\*/E0\*: 0.1$" "$work/c.tsv" || fail "ratio header missing"
grep -q "^# columns: q	C$" "$work/c.tsv" || fail "columns line missing"
[ "$(grep -vc '^#' "$work/c.tsv")" -eq 3 ] || fail "expected 3 data rows"
awk -F'\t' '!/^#/ && NF != 2 {bad=1} END {exit bad}' "$work/c.tsv" || fail "rows are not 2 tab-separated columns"
awk -F'\t' '!/^#/ && $1 == 0 {if (($2 - 0.1) > 1e-15 || ($2 - 0.1) < -1e-15) bad=1} END {exit bad}' "$work/c.tsv" \
  || fail "C(0) is not E1*/E0* = 0.1"
ls "$work" | grep -v '^c.tsv$' | grep -qv '^\(out\|err\)$' && fail "temporary file left behind"

# Both lists: two blocks, two blank lines between them, each with its own columns line.
"$cli" kernel --film 10,0.3 --substrate rigid --q 0.1:10:5 --u 0,1,2 >"$work/both.tsv" || fail "two-block run"
[ "$(grep -c '^# columns:' "$work/both.tsv")" -eq 2 ] || fail "two columns lines expected"
grep -q "^# columns: u	H$" "$work/both.tsv" || fail "H columns line missing"
grep -q "^# substrate: rigid$" "$work/both.tsv" || fail "rigid substrate header missing"
awk 'prev == "" && $0 == "" {n++} {prev = $0} END {exit !(n == 1)}' "$work/both.tsv" \
  || fail "blocks not separated by two blank lines"

# Default q list and --help.
[ "$("$cli" kernel --film 1,0.3 --substrate 2,0.3 | grep -vc '^#')" -eq 26 ] || fail "default q list"
"$cli" kernel --help | grep -q -- "--substrate" || fail "--help"

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all kernel CLI checks passed"
