#!/usr/bin/env bash
# afm_map_plot_color_range_covers_values (issue 36: the plot limits were the outer cell edges, so
# gnuplot left the edge cells out of its colour autoscale; map2x2's E bar read 1.65-1.685 kPa for
# values 1.67-6.41 kPa). For the real JPK map2x2, a synthetic 8x8 map with flagged curves and a
# synthetic one-row map (drawn as profiles), the range gnuplot actually used for every panel
# (GPVAL_CB_MIN/MAX, or GPVAL_Y_MIN/MAX of a profile, which the script appends to the file named
# by COATCONTACT_MAP_PLOT_RANGES) is compared with the minimum and maximum of that column of the
# fit table, computed here:
#  - a heat map's colour range is the values' [min, max] (relative 1e-8: the file has 10 digits);
#  - a profile's y range covers [min, max] and is at most 20 % wider than their span;
#  - --color-range 1kPa,10kPa sets E's colour range to [1000, 10000] Pa, the other panels keep
#    theirs; --color-log keeps E's range covering its values;
#  - several files: one image per map file, each with its own file's ranges;
#  - a bad --color-range or --color-log exits 2 naming the option, with no output.
# Usage: test_afm_map_plot.sh COATCONTACT MAKE_AFM_MAP DATA_DIR WORK_DIR
set -u
cli="$1"; make_map="$2"; data="$3"; work="$4"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$make_map" "$work/syn.jpk-force-map" 8 8 --points 300 --seed 5 || fail "make_afm_map 8x8"
"$make_map" "$work/line.jpk-force-map" 6 1 --points 300 --seed 3 || fail "make_afm_map 6x1"

# run NAME MAP MODULUS [OPTIONS...]: fit with --map-plot NAME.png, the ranges in NAME.ranges
run() {
  local name="$1" map="$2" modulus="$3"; shift 3
  rm -f "$work/$name.ranges"
  COATCONTACT_MAP_PLOT_RANGES="$work/$name.ranges" "$cli" afm fit "$map" --radius 10um --halfspace "$modulus,0.5" \
    --output "$work/$name.tsv" --map-plot "$work/$name.png" "$@" 2>"$work/$name.err" || fail "$name: $(cat "$work/$name.err")"
  [ "$(head -c 4 "$work/$name.png" | od -An -tx1 | tr -d ' ')" = "89504e47" ] || fail "$name: no PNG"
  [ "$(wc -l <"$work/$name.ranges")" -eq 5 ] || fail "$name: 5 panel ranges expected: $(cat "$work/$name.ranges")"
}

# check NAME MODE: every panel's range against the table's values (MODE exact: heat map; cover:
# profile). Prints one line per panel; fails on the first panel that breaks the rule.
check() {
  local name="$1" mode="$2"
  awk -F'\t' -v mode="$mode" -v name="$name" '
    FNR == NR { lo[$1] = $2; hi[$1] = $3; next }
    /^# columns: / { sub(/^# columns: /, ""); n = split($0, c, "\t"); for (i = 1; i <= n; i++) col[c[i]] = i; next }
    /^#/ { next }
    { for (k in lo) { v = $(col[k]); if (v == "-") continue; v += 0
        if (!(k in mn) || v < mn[k]) mn[k] = v; if (!(k in mx) || v > mx[k]) mx[k] = v } }
    END {
      bad = 0
      for (k in lo) {
        if (!(k in col)) { print "FAIL: " name ": no column " k; bad = 1; continue }
        tol = 1e-8 * (mx[k] - mn[k] > 0 ? (mx[k] > -mn[k] ? (mx[k] > 0 ? mx[k] : -mx[k]) : -mn[k]) : 1)
        if (tol < 0) tol = -tol
        printf "%s %s: values [%.10g, %.10g], range [%.10g, %.10g]\n", name, k, mn[k], mx[k], lo[k], hi[k]
        if (lo[k] > mn[k] + tol || hi[k] < mx[k] - tol) { print "FAIL: " name " " k ": the range leaves values out"; bad = 1 }
        if (mode == "exact" && (lo[k] < mn[k] - tol || hi[k] > mx[k] + tol)) { print "FAIL: " name " " k ": range is not [min, max]"; bad = 1 }
        if (mode == "cover" && hi[k] - lo[k] > 1.2 * (mx[k] - mn[k]) + tol) { print "FAIL: " name " " k ": range too wide"; bad = 1 }
      }
      exit bad
    }' "$work/$name.ranges" "$work/$name.tsv" || fail "$name: ranges against values"
}

run map2x2 "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" 1kPa
check map2x2 exact
run syn "$work/syn.jpk-force-map" 5kPa
grep -q 'flagged: 16 of 64' "$work/syn.err" || fail "syn: the flagged curves are missing: $(cat "$work/syn.err")"
check syn exact
run line "$work/line.jpk-force-map" 5kPa
check line cover

# --color-range: E (a modulus) gets the range given, the other panels keep their own.
run fixed "$work/syn.jpk-force-map" 5kPa --color-range 1kPa,10kPa
awk -F'\t' '$1 == "E" { exit !($2 == 1000 && $3 == 10000) }' "$work/fixed.ranges" || fail "--color-range: E range $(grep '^E' "$work/fixed.ranges")"
grep -v '^E' "$work/fixed.ranges" | cmp -s - <(grep -v '^E' "$work/syn.ranges") || fail "--color-range changed the other panels"
run logscale "$work/syn.jpk-force-map" 5kPa --color-log
awk -F'\t' '$1 == "E"' "$work/logscale.ranges" >"$work/logscale.E"
awk -F'\t' '$1 == "E"' "$work/syn.ranges" >"$work/syn.E"
paste "$work/logscale.E" "$work/syn.E" | awk -F'\t' '{ exit !($2 <= $5 && $3 >= $6 && $2 > 0) }' \
  || fail "--color-log: E range $(cat "$work/logscale.E") does not cover $(cat "$work/syn.E")"

# Several files: one image per map file (NAME-K.png, K its place in the run), none for a single
# curve; each image's ranges are its own file's.
rm -f "$work/multi"*
COATCONTACT_MAP_PLOT_RANGES="$work/multi.ranges" "$cli" afm fit "$work/syn.jpk-force-map" "$data/fmt-jpk-fd_spot3-0192.jpk-force" \
  "$work/line.jpk-force-map" --radius 10um --halfspace 5kPa,0.5 --output "$work/multi.tsv" --map-plot "$work/multi.png" \
  2>"$work/multi.err" || fail "several files: $(cat "$work/multi.err")"
[ -s "$work/multi-1.png" ] && [ -s "$work/multi-3.png" ] && [ ! -e "$work/multi-2.png" ] && [ ! -e "$work/multi.png" ] \
  || fail "several files: images $(ls "$work"/multi*.png)"
head -5 "$work/multi.ranges" | cmp -s - "$work/syn.ranges" || fail "several files: the first image's ranges are not the map's own"
[ "$(tail -n +6 "$work/multi.ranges" | cut -f1 | tr '\n' ' ')" = "E contact_point baseline chi2_per_dof pulloff " ] \
  || fail "several files: second image's panels $(cat "$work/multi.ranges")"

expect_error() {  # FRAGMENT... -- ARGS
  local fragments=()
  while [ "$1" != "--" ]; do fragments+=("$1"); shift; done
  shift
  rm -f "$work/bad.tsv" "$work/bad.png"
  "$cli" "$@" >"$work/bad.out" 2>"$work/bad.err"
  local rc=$?
  [ "$rc" -eq 2 ] || fail "exit $rc (wanted 2): $* :: $(cat "$work/bad.err")"
  for f in "${fragments[@]}"; do grep -qF -- "$f" "$work/bad.err" || fail "message lacks '$f': $(cat "$work/bad.err")"; done
  [ ! -e "$work/bad.tsv" ] && [ ! -e "$work/bad.png" ] || fail "output written: $*"
}
fitargs=(afm fit "$work/syn.jpk-force-map" --radius 10um --halfspace 5kPa,0.5 --output "$work/bad.tsv")
expect_error "--color-range" "MIN must be below MAX" -- "${fitargs[@]}" --map-plot "$work/bad.png" --color-range 10kPa,1kPa
expect_error "--color-range" "MIN,MAX" -- "${fitargs[@]}" --map-plot "$work/bad.png" --color-range 10kPa
expect_error "--color-range" "--map-plot" -- "${fitargs[@]}" --color-range 1kPa,10kPa
expect_error "--color-log" "--map-plot" -- "${fitargs[@]}" --color-log

if [ "$failures" -ne 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "afm_map_plot_color_range_covers_values: all checks passed"
