#!/usr/bin/env bash
# coatcontact indent show on the real files: the header's calibration as the files state it,
# the rows against the files' own lines (decoded here with awk), --test/--index; bad options
# and bad files: exit 2, a message naming the option or the file and line, no output file.
# Usage: test_indent_cli.sh COATCONTACT DATA_DIR WORK_DIR
set -u
cli="$1"; data="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_error CODE FRAGMENT... -- ARGS: exit CODE, stderr holding every fragment, no $work/out.tsv
expect_error() {
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
  ls "$work" | grep -q '\.tmp\.' && fail "a temporary file was left: $*"
  return 0
}

# ---- every file reads; the header has the command and the columns ----------------------
for f in FS_Calibration.xls RobinSteel0000LC.txt Exp-50mN_0000.hld multipleIndentations.zip FS1.txt; do
  "$cli" indent show "$data/$f" --output "$work/show.tsv" 2>"$work/stderr" || fail "indent show $f: $(cat "$work/stderr")"
  grep -q '^# command: coatcontact indent show' "$work/show.tsv" || fail "$f: no command line"
  grep -q '^# columns: depth_m	load_N	time_s' "$work/show.tsv" || fail "$f: columns line"
done

# ---- NanoSuite: --test picks the sheet; the calibration as the sheets state it -----------
xls="$data/FS_Calibration.xls"
"$cli" indent show "$xls" --test "Test 009" --output "$work/t9.tsv" || fail "show --test 'Test 009'"
grep -q '^# test: Test 009 (index 8 of 16)$' "$work/t9.tsv" || fail "Test 009 header"
grep -qF '# area coefficients (A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + ..., h_c [nm]): 27.3136 152.6988585 -494.1823171' "$work/t9.tsv" || fail "area coefficients"
grep -q '^# poisson (sample): 0.18$' "$work/t9.tsv" || fail "poisson"
grep -q '^# tip: Berk40_20210907_MarilaineSP$' "$work/t9.tsv" || fail "tip"
grep -q '^# vendor E_mean \[Pa\]: 7.3579e+10$' "$work/t9.tsv" || fail "Test 009 E_mean 73.579 GPa: $(grep E_mean "$work/t9.tsv")"
grep -q '^# columns: depth_m	load_N	time_s	stiffness_N_per_m	hardness_Pa	modulus_Pa	segment$' "$work/t9.tsv" || fail "NanoSuite columns"
# --index 8 is the same test.
"$cli" indent show "$xls" --index 8 --output "$work/i8.tsv" || fail "show --index 8"
diff <(grep -v '^# command' "$work/t9.tsv") <(grep -v '^# command' "$work/i8.tsv") >/dev/null || fail "--index 8 differs from --test 'Test 009'"
# "-" where the software wrote 1.797e308 (hardness before contact); no "nan" anywhere.
grep -v '^#' "$work/t9.tsv" | head -1 | cut -f5 | grep -qx -- '-' || fail "missing hardness not written as -"
grep -v '^#' "$work/t9.tsv" | grep -qi 'nan\|inf' && fail "a nan or inf in the rows"

# ---- Hysitron text: each row equals the file's line (nm -> m, µN -> N), segments ----------
robin="$data/RobinSteel0000LC.txt"
"$cli" indent show "$robin" --output "$work/robin.tsv" || fail "show robin"
awk -F'\t' 'NR > 4 && NF == 5 { printf "%.15g\t%.15g\t%.15g\n", $1 * 1e-9, $2 * 1e-6, $3 }' "$robin" >"$work/robin_want.tsv"
grep -v '^#' "$work/robin.tsv" | awk -F'\t' '{ printf "%.15g\t%.15g\t%.15g\n", $1, $2, $3 }' >"$work/robin_got.tsv"
cmp -s "$work/robin_want.tsv" "$work/robin_got.tsv" || fail "Hysitron rows differ from the file's lines (15 digits)"
[ "$(grep -vc '^#' "$work/robin.tsv")" -eq 5304 ] || fail "Hysitron: 5304 rows"
grep -q '^# columns: depth_m	load_N	time_s	segment	Depth_V	Load_V$' "$work/robin.tsv" || fail "Hysitron columns"

# ---- FischerScope: decimal commas; the test's epsilon -------------------------------------
"$cli" indent show "$data/FS1.txt" --test "Block 1 Value 3" --output "$work/fs3.tsv" || fail "show FS1 value 3"
grep -q '^# epsilon: 0.75$' "$work/fs3.tsv" || fail "FischerScope epsilon"
grep -q '^# vendor HM \[Pa\]: 3753300000$' "$work/fs3.tsv" || fail "FischerScope HM 3753.3 N/mm2"

# ---- bad options and files: exit 2, named, nothing written ---------------------------------
expect_error 2 "--index" "16 tests (indices 0..15)" -- indent show "$xls" --index 16
expect_error 2 "--test" "'Test 099' is not a test" "'Test 001'" -- indent show "$xls" --test "Test 099"
expect_error 2 "--test and --index" -- indent show "$xls" --test "Test 001" --index 0
expect_error 2 "no such file" -- indent show "$work/none.txt"
head -c 100000 "$robin" >"$work/cut.txt"
expect_error 2 "cut.txt" "line" -- indent show "$work/cut.txt"
sed 's/^0,438949/0.438949/' "$data/FS1.txt" >"$work/point.txt"
expect_error 2 "point.txt" "Block 1 Value 1" "line 87" -- indent show "$work/point.txt"
expect_error 2 "unknown indentation file format" -- indent show "$data/README.md"
"$cli" indent frobnicate "$xls" >/dev/null 2>"$work/stderr"
[ $? -eq 2 ] && grep -q "unknown indent command 'frobnicate' (expected show" "$work/stderr" || fail "unknown indent command"
"$cli" indent --help | grep -q '^  show ' || fail "indent --help lists show"

[ "$failures" -eq 0 ] && echo "indent cli: all checks passed"
exit $((failures > 0))
