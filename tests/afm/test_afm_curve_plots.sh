#!/usr/bin/env bash
# afm fit's per-curve pictures (issue 36 items 3, 5 and --plot of a batch):
#  - --curve-plots FILE.pdf has one page per curve (pdfinfo), flagged curves included (a
#    synthetic 4x4 map with no_contact, jump_in, empty_segment and calibration curves), and the
#    real map2x2 gives 4 pages;
#  - --plot of a batch is --map-plot: the same picture;
#  - --depth-profile on the real spot3 curve: 10 depths, increasing, the last row's E the
#    whole-range fit's (the header's E line), and --plot draws a PNG;
#  - bad options exit 2 naming the option, with no output written.
# Usage: test_afm_curve_plots.sh COATCONTACT MAKE_AFM_MAP DATA_DIR WORK_DIR
set -u
cli="$1"; make_map="$2"; data="$3"; work="$4"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pages() { pdfinfo "$1" 2>/dev/null | awk '/^Pages:/ { print $2 }'; }

"$make_map" "$work/syn.jpk-force-map" 4 4 --points 200 --seed 2 || fail "make_afm_map 4x4"
"$cli" afm fit "$work/syn.jpk-force-map" --radius 10um --halfspace 5kPa,0.5 --output "$work/syn.tsv" \
  --curve-plots "$work/syn.pdf" 2>"$work/syn.err" || fail "syn: $(cat "$work/syn.err")"
[ "$(pages "$work/syn.pdf")" = 16 ] || fail "syn: 16 pages expected, got $(pages "$work/syn.pdf")"
flagged=$(awk -F'\t' '!/^#/ && $7 != 0' "$work/syn.tsv" | wc -l)
[ "$flagged" -ge 4 ] || fail "syn: the map should hold flagged curves (got $flagged)"
grep -q "16 control-plot pages" "$work/syn.err" || fail "syn: stderr names the pages: $(cat "$work/syn.err")"

map2="$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map"
"$cli" afm fit "$map2" --radius 5um --halfspace 1kPa,0.5 --curve-plots "$work/map2.pdf" >"$work/map2.tsv" 2>"$work/map2.err" \
  || fail "map2x2: $(cat "$work/map2.err")"
[ "$(pages "$work/map2.pdf")" = 4 ] || fail "map2x2: 4 pages expected"

# --plot of a batch is --map-plot.
"$cli" afm fit "$map2" --radius 5um --halfspace 1kPa,0.5 --plot "$work/plot.png" >/dev/null 2>&1 || fail "--plot of a batch"
"$cli" afm fit "$map2" --radius 5um --halfspace 1kPa,0.5 --map-plot "$work/mapplot.png" >/dev/null 2>&1 || fail "--map-plot"
cmp -s "$work/plot.png" "$work/mapplot.png" || fail "--plot of a batch differs from --map-plot"

# --depth-profile on one curve.
spot="$data/fmt-jpk-fd_spot3-0192.jpk-force"
"$cli" afm fit "$spot" --radius 5um --halfspace 1kPa,0.5 --depth-profile --plot "$work/dp.png" >"$work/dp.tsv" 2>"$work/dp.err" \
  || fail "depth profile: $(cat "$work/dp.err")"
[ "$(grep -vc '^#' "$work/dp.tsv")" = 10 ] || fail "depth profile: 10 rows expected"
awk -F'\t' '!/^#/ { if (NR0++ && $1 <= last) bad = 1; last = $1 } END { exit bad }' "$work/dp.tsv" || fail "depth profile: depths not increasing"
whole=$(awk -F': ' '/^# E \[Pa\]:/ { split($2, a, " "); print a[1] }' "$work/dp.tsv")
last=$(awk -F'\t' '!/^#/ { e = $3 } END { print e }' "$work/dp.tsv")
awk -v a="$whole" -v b="$last" 'BEGIN { exit !(a != "" && (a - b) ^ 2 <= (1e-12 * a) ^ 2) }' \
  || fail "depth profile: last depth E $last differs from the whole-range fit's $whole"
[ "$(head -c 4 "$work/dp.png" | od -An -tx1 | tr -d ' ')" = "89504e47" ] || fail "depth profile: no PNG"

# Bad options: exit 2, the option named, nothing written.
bad() {
  local name="$1" option="$2"; shift 2
  rm -f "$work/bad.out" "$work/bad.pdf" "$work/bad.png"
  "$cli" afm fit "$@" >"$work/bad.stdout" 2>"$work/bad.err"
  local rc=$?
  [ "$rc" = 2 ] || fail "$name: exit $rc, expected 2"
  grep -q -- "$option" "$work/bad.err" || fail "$name: the message does not name $option: $(cat "$work/bad.err")"
  [ ! -s "$work/bad.stdout" ] && [ ! -e "$work/bad.out" ] && [ ! -e "$work/bad.pdf" ] && [ ! -e "$work/bad.png" ] \
    || fail "$name: output written"
}
fit=(--radius 5um --halfspace 1kPa,0.5)
bad "curve plots not pdf" --curve-plots "$map2" "${fit[@]}" --curve-plots "$work/bad.png"
bad "curve plots over the input" --curve-plots "$map2" "${fit[@]}" --curve-plots "$map2"
bad "curve plots over the output" --curve-plots "$map2" "${fit[@]}" --output "$work/bad.pdf" --curve-plots "$work/bad.pdf"
bad "curve plots with --resume" --curve-plots "$map2" "${fit[@]}" --output "$work/bad.out" --resume --curve-plots "$work/bad.pdf"
bad "curve plots with --index" --index "$map2" "${fit[@]}" --index 0 --curve-plots "$work/bad.pdf"
bad "--plot and --map-plot" --plot "$map2" "${fit[@]}" --plot "$work/bad.png" --map-plot "$work/bad2.png"
bad "depth profile of a batch" --depth-profile "$map2" "${fit[@]}" --depth-profile
bad "depth profile of jkr" --depth-profile "$spot" --radius 5um --halfspace 1kPa,0.5 --model jkr --spring-constant 0.05 --depth-profile --output "$work/bad.out"
bad "depth profile, E fixed" --depth-profile "$spot" --radius 5um --halfspace 1kPa,0.5 --free contact_point,baseline --depth-profile --output "$work/bad.out"
bad "depth profile over the input" --plot "$spot" "${fit[@]}" --depth-profile --plot "$spot"

[ "$failures" = 0 ] && echo "afm curve plots: all checks passed"
exit $((failures > 0))
