#!/usr/bin/env bash
# Regressions of the fit's data input (issue 29, defects 8, 9, 10, 13), one case per test:
#   stdin_unbounded       cat /dev/zero | coatcontact fit - ... read without limit (1 GB in 20 s)
#   bom_column_prescan    a UTF-8 byte-order mark made the column pre-scan miscount
#   semicolon_csv         a ';'-separated CSV was "expected 4 columns, found 1"
#   unit_in_header        headers a/um, a_um read silently as SI
#   units_recorded        the fit output did not record the units it detected
#   unit_mixup_explained  F in mN without units: "w ran to ..." with no word on units
#   error_names_line      "nulonly.tsv: 1 columns" and an F = 1e300 row named no line
#   long_path_shortened   a 131 kB path repeated in full in the error
# Usage: test_fit_input_regressions.sh CASE PATH/TO/coatcontact DATA_DIR
set -u
case_name="$1"
cli="$2"
data="$3"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
common=(--radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um)
fail() { echo "FAIL: $*"; exit 1; }
# expect_refusal CODE TEXT... : the last run's exit code and stderr
expect() {
  local want="$1"; shift
  [ "$status" -eq "$want" ] || fail "exit $status, want $want: $(head -c 400 "$work/err")"
  for text in "$@"; do
    grep -qF -- "$text" "$work/err" || fail "message lacks '$text': $(head -c 600 "$work/err")"
  done
}
# The example a,F data (um, mN) without comments: two columns of numbers.
numbers() { grep -v '^#' "$data/example_a_F.tsv"; }
reference_w() {
  "$cli" fit "$data/example_a_F.tsv" --columns a,F "${common[@]}" --output "$work/ref.tsv" >/dev/null 2>&1 ||
    fail "the example fit fails"
  sed -n 's|^# w \[J/m2\]: \([^ ]*\).*|\1|p' "$work/ref.tsv"
}
fitted_w() { sed -n 's|^# w \[J/m2\]: \([^ ]*\).*|\1|p' "$1"; }

case "$case_name" in
  stdin_unbounded)
    # Refused once 100 MB have been read (exit 2), long before memory runs out.
    timeout 120 bash -c "cat /dev/zero | '$cli' fit - --columns a,F ${common[*]} >/dev/null 2>'$work/err'"
    status=$?
    expect 2 "stdin: larger than 100 MB"
    ;;
  bom_column_prescan)
    { printf '\xef\xbb\xbfa (um),F (mN)\n'; numbers | tr '\t' ','; } >"$work/bom.csv"
    "$cli" fit "$work/bom.csv" --columns a,F "${common[@]}" --output "$work/fit.tsv" >/dev/null 2>"$work/err"
    status=$?
    expect 0
    [ "$(fitted_w "$work/fit.tsv")" = "$(reference_w)" ] || fail "w differs from the example's"
    ;;
  semicolon_csv)
    { echo "# units: um mN"; numbers | tr '\t' ';'; } >"$work/semi.csv"
    "$cli" fit "$work/semi.csv" --columns a,F "${common[@]}" --output "$work/fit.tsv" >/dev/null 2>"$work/err"
    status=$?
    expect 0
    [ "$(fitted_w "$work/fit.tsv")" = "$(reference_w)" ] || fail "w differs from the example's"
    ;;
  unit_in_header)
    ref="$(reference_w)"
    for header in 'a/um	F/mN' 'a_um	F_mN' 'a (um),F (mN)'; do
      { echo "$header"; numbers; } >"$work/h.tsv"
      "$cli" fit "$work/h.tsv" --columns a=a,F=F "${common[@]}" --output "$work/fit.tsv" >/dev/null 2>"$work/err"
      status=$?
      expect 0
      [ "$(fitted_w "$work/fit.tsv")" = "$ref" ] || fail "header '$header': w differs from the example's"
    done
    { printf 'a/furlong\tF/mN\n'; numbers; } >"$work/bad.tsv"
    "$cli" fit "$work/bad.tsv" --columns a=1,F=2 "${common[@]}" >/dev/null 2>"$work/err"
    status=$?
    expect 2 "unknown unit 'furlong'"
    ;;
  units_recorded)
    "$cli" fit "$data/example_a_F.tsv" --columns a,F "${common[@]}" --output "$work/fit.tsv" >/dev/null 2>"$work/err"
    status=$?
    expect 0
    grep -qF "# data units: a um, F mN (from the '# units:' line)" "$work/fit.tsv" || fail "no data units line"
    numbers | awk '{ printf "%.10g\t%.10g\n", $1 * 1e-6, $2 * 1e-3 }' >"$work/si.tsv"
    "$cli" fit "$work/si.tsv" --columns a,F "${common[@]}" --output "$work/fit.tsv" >/dev/null 2>"$work/err"
    status=$?
    expect 0
    grep -qF "# data units: none declared: read as SI (m, N)" "$work/fit.tsv" || fail "no SI data units line"
    ;;
  unit_mixup_explained)
    # a in m, F still in mN: the pull-off of -1.3 N needs w ~ 55 J/m2 on R = 5 mm.
    numbers | awk '{ printf "%.10g\t%s\n", $1 * 1e-6, $2 }' >"$work/mn.tsv"
    "$cli" fit "$work/mn.tsv" --columns a,F "${common[@]}" >/dev/null 2>"$work/err"
    status=$?
    [ "$status" -eq 2 ] || [ "$status" -eq 3 ] || fail "exit $status, want 2 or 3"
    expect "$status" "needs w = " "are the units of F and R right?"
    ;;
  error_names_line)
    printf '# one column only\n1e-4\n2e-4\n' >"$work/one.tsv"
    "$cli" fit "$work/one.tsv" --columns a,F "${common[@]}" >/dev/null 2>"$work/err"
    status=$?
    expect 2 "one.tsv:2: 1 columns"
    { echo "# units: um mN"; numbers | head -20; printf '100\t1e300\n'; } >"$work/huge.tsv"
    "$cli" fit "$work/huge.tsv" --columns a,F "${common[@]}" >/dev/null 2>"$work/err"
    status=$?
    expect 2 "line 22:" "outside the allowed range"
    ;;
  long_path_shortened)
    long="$work/$(head -c 131000 /dev/zero | tr '\0' 'x').tsv"
    "$cli" fit "$long" --columns a,F "${common[@]}" >/dev/null 2>"$work/err"
    status=$?
    [ "$status" -eq 2 ] || fail "exit $status, want 2"
    size=$(wc -c <"$work/err")
    [ "$size" -lt 2000 ] || fail "the error is $size bytes long"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo "ok   $case_name"
