#!/usr/bin/env bash
# coatcontact afm fit over maps, several files and folders (issue 25; THEORY.md section 15, "Many curves"):
#  - a synthetic JPK force map (make_afm_map: the library's Hertz model, noise, tilted baseline,
#    bad curves) is read and fitted: one row per curve, the bad curves flagged with the right
#    reason, the count in the header and on stderr, exit 0; E, contact point and baseline of
#    the fitted curves recovered within 4 standard errors of the truth (b within the noise);
#  - --jobs 2 gives the table of --jobs 1 byte for byte (but the command line);
#  - --resume after a cut FILE.partial, and after a run killed by SIGTERM, gives the same table;
#  - the real maps in data/afm/ (JPK force map 2x2, JPK QI data, AFM Workshop zipped map with the
#    calibration supplied) and a folder of files are processed; a non-AFM file in a folder or a
#    list is one unreadable row and the run goes on, a single such FILE exits 2;
#  - --map-plot writes a PNG; bad options exit 2 naming the option, with no output;
#  - a synthetic map of adhesive retracts on a coating (make_afm_map --jkr: the library's JKR
#    spring model) fitted with --model jkr (E1, w, contact point, baseline, tilt free) at
#    --jobs 2: the flags of the truth, E1 and w within 3 standard errors of the truth.
# Usage: test_afm_map_cli.sh COATCONTACT MAKE_AFM_MAP DATA_DIR WORK_DIR
set -u
cli="$1"; make_map="$2"; data="$3"; work="$4"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
body() { grep -v '^# command:' "$1"; }   # a table without its command line

"$make_map" "$work/syn.jpk-force-map" 8 8 --points 300 --seed 5 --truth "$work/truth.tsv" || fail "make_afm_map"
model=(--radius 10um --halfspace 5kPa,0.5)

# ---- the synthetic map: rows, flags, recovery ------------------------------------------------
"$cli" afm fit "$work/syn.jpk-force-map" "${model[@]}" --jobs 1 --output "$work/j1.tsv" 2>"$work/j1.err" \
  || fail "afm fit synthetic map: $(cat "$work/j1.err")"
rows=$(grep -vc '^#' "$work/j1.tsv")
[ "$rows" -eq 64 ] || fail "64 rows expected, got $rows"
grep -q '^# flagged curves: 16 of 64 (no_contact 4, jump_in 4, empty_segment 4, calibration 4)$' "$work/j1.tsv" \
  || fail "flag count line: $(grep '^# flagged' "$work/j1.tsv")"
grep -q 'flagged: 16 of 64' "$work/j1.err" || fail "stderr lacks the flagged count: $(cat "$work/j1.err")"
grep -q $'^# columns: file\tcurve\tgrid_x\tgrid_y\tx\ty\tflag\treason\tE\tE_error\tcontact_point\tcontact_point_error\tbaseline\tbaseline_error\tchi2' "$work/j1.tsv" \
  || fail "columns: $(grep '^# columns' "$work/j1.tsv")"
# Each row's flag against the truth's expected flag (curve index in column 2 / column 1).
bad=$(awk -F'\t' 'FNR == NR { if ($0 !~ /^#/) want[$1] = $8; next } $0 !~ /^#/ && want[$2] != $7 { n++ } END { print n + 0 }' \
  "$work/truth.tsv" "$work/j1.tsv")
[ "$bad" -eq 0 ] || fail "$bad curves with another flag than the truth's"
# Recovery: |estimate - truth| / error for E, contact point, baseline (at the contact point).
awk -F'\t' 'FNR == NR { if ($0 !~ /^#/) { E[$1] = $4; zc[$1] = $5; b[$1] = $6 } next }
  $0 !~ /^#/ && $7 == 0 {
    z1 = ($9 - E[$2]) / $10; z2 = ($11 - zc[$2]) / $12; z3 = $13 - b[$2]
    for (k = 1; k <= 3; k++) { v = (k == 1 ? z1 : k == 2 ? z2 : z3); if (v < 0) v = -v; if (v > m[k]) m[k] = v }
    n++; s1 += ($9 - E[$2]) / E[$2]; q1 += (($9 - E[$2]) / E[$2])^2
  }
  END { printf "%d %.3f %.3f %.3g %.3g %.3g\n", n, m[1], m[2], m[3], s1 / n, sqrt(q1 / n - (s1 / n)^2) }' \
  "$work/truth.tsv" "$work/j1.tsv" >"$work/recovery"
read -r n z_e z_c z_b mean_e scatter_e <"$work/recovery"
echo "synthetic 8x8: $n fitted; max |z| E $z_e, contact point $z_c; max |b - truth| $z_b N; E relative error mean $mean_e, scatter $scatter_e"
[ "$n" -eq 48 ] || fail "48 fitted curves expected, got $n"
# 4 standard errors: 48 curves x 3 estimates, a Gaussian |z| > 4 has probability 6e-5 each.
# The standard errors of z_c and b leave out the uncertainty of the tilt subtracted before the
# fit (THEORY.md section 15, "Many curves"; on a 64 x 64 map their RMS z-scores are 1.5 and 3.3,
# E's 1.07): z_c within 6 of its standard errors, b within the noise of one point, 0.1 nN.
awk -v a="$z_e" -v b="$z_c" -v c="$z_b" 'BEGIN { exit !(a < 4 && b < 6 && c < 1e-10) }' \
  || fail "an estimate off the truth: E $z_e (limit 4), z_c $z_c (limit 6) standard errors, |b - truth| $z_b N (limit 1e-10)"

# ---- --jobs 2 == --jobs 1 --------------------------------------------------------------------
"$cli" afm fit "$work/syn.jpk-force-map" "${model[@]}" --jobs 2 --output "$work/j2.tsv" 2>"$work/j2.err" \
  || fail "afm fit --jobs 2: $(cat "$work/j2.err")"
cmp -s <(body "$work/j1.tsv") <(body "$work/j2.tsv") || fail "--jobs 2 differs from --jobs 1"

# ---- --resume after a cut partial file -------------------------------------------------------
grep -v '^# flagged curves' "$work/j1.tsv" >"$work/full_partial"
head -c $(( $(wc -c <"$work/full_partial") * 2 / 3 )) "$work/full_partial" >"$work/r.tsv.partial"
"$cli" afm fit "$work/syn.jpk-force-map" "${model[@]}" --jobs 2 --resume --output "$work/r.tsv" 2>"$work/r.err" \
  || fail "--resume: $(cat "$work/r.err")"
grep -q 'resuming after' "$work/r.err" || fail "--resume did not resume: $(cat "$work/r.err")"
cmp -s <(body "$work/j1.tsv") <(body "$work/r.tsv") || fail "--resume after a cut file differs from the whole run"
[ ! -e "$work/r.tsv.partial" ] || fail "the partial file is left after the run"

# ---- --resume after SIGTERM ------------------------------------------------------------------
"$make_map" "$work/big.jpk-force-map" 12 12 --points 300 --seed 9 || fail "make_afm_map big"
"$cli" afm fit "$work/big.jpk-force-map" "${model[@]}" --jobs 1 --output "$work/big_ref.tsv" 2>/dev/null || fail "big reference run"
env --default-signal=INT,TERM "$cli" afm fit "$work/big.jpk-force-map" "${model[@]}" --jobs 1 --output "$work/k.tsv" 2>/dev/null &
pid=$!
for ((i = 0; i < 3000; i++)); do
  [ -e "$work/k.tsv.partial" ] && [ "$(grep -vc '^#' "$work/k.tsv.partial")" -ge 20 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
kill -TERM "$pid" 2>/dev/null; wait "$pid"
if [ -e "$work/k.tsv" ]; then
  echo "note: the run ended before it was killed; the resume check is on a finished table"
else
  [ -e "$work/k.tsv.partial" ] || fail "no partial table after SIGTERM"
  grep -q '^# columns:' "$work/k.tsv.partial" || fail "the partial table has no header"
  "$cli" afm fit "$work/big.jpk-force-map" "${model[@]}" --jobs 2 --resume --output "$work/k.tsv" 2>"$work/k.err" \
    || fail "--resume after SIGTERM: $(cat "$work/k.err")"
fi
cmp -s <(body "$work/big_ref.tsv") <(body "$work/k.tsv") || fail "--resume after SIGTERM differs from the whole run"

# ---- real maps -------------------------------------------------------------------------------
"$cli" afm fit "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" --radius 10um --halfspace 1kPa,0.5 \
  --output "$work/jpkmap.tsv" --map-plot "$work/jpkmap.png" 2>"$work/jpkmap.err" || fail "JPK map: $(cat "$work/jpkmap.err")"
[ "$(grep -vc '^#' "$work/jpkmap.tsv")" -eq 4 ] || fail "JPK map: 4 rows expected"
[ "$(head -c 4 "$work/jpkmap.png" | od -An -tx1 | tr -d ' ')" = "89504e47" ] || fail "--map-plot wrote no PNG"
"$cli" afm fit "$data/fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data" --radius 10um --halfspace 1kPa,0.5 \
  --output "$work/qi.tsv" 2>"$work/qi.err" || fail "JPK QI: $(cat "$work/qi.err")"
[ "$(grep -vc '^#' "$work/qi.tsv")" -ge 1 ] || fail "JPK QI: no rows"
"$cli" afm fit "$data/fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip" --radius 10um --halfspace 1kPa,0.5 \
  --spring-constant 0.1 --sensitivity 5e-8 --output "$work/aw.tsv" 2>"$work/aw.err" || fail "AFM Workshop map: $(cat "$work/aw.err")"
[ "$(grep -vc '^#' "$work/aw.tsv")" -ge 2 ] || fail "AFM Workshop map: rows"
grep -q '^# spring constant \[N/m\]: 0.1 (user' "$work/aw.tsv" || fail "AFM Workshop map: the supplied calibration is not in the header"
mkdir -p "$work/folder"
cp "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" "$data/fmt-jpk-fd_spot3-0192.jpk-force" "$work/folder/"
"$cli" afm fit "$work/folder" --radius 10um --halfspace 1kPa,0.5 --output "$work/folder.tsv" 2>"$work/folder.err" \
  || fail "folder: $(cat "$work/folder.err")"
[ "$(grep -vc '^#' "$work/folder.tsv")" -eq 5 ] || fail "folder: 5 rows expected"
"$cli" afm fit "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" "$data/fmt-jpk-fd_spot3-0192.jpk-force" \
  --radius 10um --halfspace 1kPa,0.5 >"$work/stdout.tsv" 2>"$work/stdout.err" || fail "two files to stdout"
[ "$(grep -vc '^#' "$work/stdout.tsv")" -eq 5 ] || fail "two files to stdout: 5 rows expected"
tail -1 "$work/stdout.tsv" | grep -q '^# flagged curves: ' || fail "stdout table does not end with the flagged count"

# A non-AFM file with an AFM extension in a folder or a list of files is one flagged row
# (unreadable; the header and stderr name it and why) and the run goes on, exit 0 (issue 25 item 1).
mkdir -p "$work/mixed"
cp "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" "$work/mixed/"
echo "not a force curve" >"$work/mixed/notes.jpk-force"
"$cli" afm fit "$work/mixed" --radius 10um --halfspace 1kPa,0.5 --output "$work/mixed.tsv" 2>"$work/mixed.err" \
  || fail "folder with a non-AFM file: exit $? :: $(cat "$work/mixed.err")"
[ "$(grep -vc '^#' "$work/mixed.tsv")" -eq 5 ] || fail "folder with a non-AFM file: 5 rows expected"
[ "$(awk -F'\t' '$0 !~ /^#/ && $1 ~ /notes.jpk-force$/ && $2 == 0 && $7 == 8 && $8 == "unreadable"' "$work/mixed.tsv" | wc -l)" -eq 1 ] \
  || fail "folder with a non-AFM file: no unreadable row for it"
[ "$(awk -F'\t' '$0 !~ /^#/ && $7 == 0' "$work/mixed.tsv" | wc -l)" -eq 4 ] || fail "folder with a non-AFM file: the map's 4 curves not fitted"
grep -q '^# flagged curves: 1 of 5 (unreadable 1)$' "$work/mixed.tsv" || fail "folder with a non-AFM file: header count"
grep -q '^# file 1: .*notes.jpk-force (unreadable, one flagged row: not a zip archive' "$work/mixed.tsv" \
  || fail "folder with a non-AFM file: the header does not say why: $(grep '^# file' "$work/mixed.tsv")"
grep -q 'flagged: 1 of 5 (unreadable 1)' "$work/mixed.err" && grep -q 'unreadable file: .*notes.jpk-force: not a zip archive' "$work/mixed.err" \
  || fail "folder with a non-AFM file: stderr: $(cat "$work/mixed.err")"
"$cli" afm fit "$work/mixed/notes.jpk-force" "$data/fmt-jpk-fd_spot3-0192.jpk-force" --radius 10um --halfspace 1kPa,0.5 \
  >"$work/mixed_list.tsv" 2>"$work/mixed_list.err" || fail "list with a non-AFM file: exit $? :: $(cat "$work/mixed_list.err")"
[ "$(grep -vc '^#' "$work/mixed_list.tsv")" -eq 2 ] && tail -1 "$work/mixed_list.tsv" | grep -q '^# flagged curves: 1 of 2 (unreadable 1)$' \
  || fail "list with a non-AFM file: rows or count"

# ---- bad options: exit 2, the option named, no output ----------------------------------------
expect_error() {  # FRAGMENT... -- ARGS
  local fragments=()
  while [ "$1" != "--" ]; do fragments+=("$1"); shift; done
  shift
  rm -f "$work/bad.tsv" "$work/bad.tsv.partial" "$work/bad.png"
  "$cli" "$@" >"$work/bad.out" 2>"$work/bad.err"
  local rc=$?
  [ "$rc" -eq 2 ] || fail "exit $rc (wanted 2): $* :: $(cat "$work/bad.err")"
  for f in "${fragments[@]}"; do grep -qF -- "$f" "$work/bad.err" || fail "message lacks '$f': $(cat "$work/bad.err")"; done
  [ ! -e "$work/bad.tsv" ] && [ ! -e "$work/bad.tsv.partial" ] && [ ! -e "$work/bad.png" ] || fail "output written: $*"
  [ ! -s "$work/bad.out" ] || fail "stdout written: $*"
}
map="$work/syn.jpk-force-map"
expect_error "--jobs" "'0'" "1 to 1024" -- afm fit "$map" "${model[@]}" --jobs 0 --output "$work/bad.tsv"
expect_error "--jobs" "'2.5'" -- afm fit "$map" "${model[@]}" --jobs 2.5 --output "$work/bad.tsv"
expect_error "--resume" "--output" -- afm fit "$map" "${model[@]}" --resume
expect_error "--map-plot" ".png or .pdf" -- afm fit "$map" "${model[@]}" --map-plot "$work/bad.gif" --output "$work/bad.tsv"
# --plot of a batch is --map-plot (test_afm_curve_plots.sh); both at once are refused.
expect_error "--plot" "--map-plot" -- afm fit "$map" "${model[@]}" --plot "$work/bad.png" --map-plot "$work/bad2.png" --output "$work/bad.tsv"
expect_error "--index" "one FILE" -- afm fit "$map" "$map" "${model[@]}" --index 1 --output "$work/bad.tsv"
expect_error "given twice" -- afm fit "$map" "$map" "${model[@]}" --output "$work/bad.tsv"
expect_error "no such file" -- afm fit "$map" "$work/none.jpk-force" "${model[@]}" --output "$work/bad.tsv"
# A single FILE named that cannot be read is the run's input: exit 2, no output (with or without
# the batch options).
expect_error "notes.jpk-force" "not a zip archive" -- afm fit "$work/mixed/notes.jpk-force" "${model[@]}" --output "$work/bad.tsv"
expect_error "notes.jpk-force" "not a zip archive" -- afm fit "$work/mixed/notes.jpk-force" "${model[@]}" --jobs 2 --output "$work/bad.tsv"
echo "not a table" >"$work/bad.tsv.partial.src"
cp "$work/full_partial" "$work/other.partial"
sed -i 's/^# sample: .*/# sample: another/' "$work/other.partial"
cp "$work/other.partial" "$work/bad.tsv.partial"
"$cli" afm fit "$map" "${model[@]}" --resume --output "$work/bad.tsv" >/dev/null 2>"$work/bad.err"
[ $? -eq 2 ] && grep -q 'another run' "$work/bad.err" || fail "--resume on another run's partial file: $(cat "$work/bad.err")"
rm -f "$work/bad.tsv.partial"
# One curve with --index keeps the one-curve fit (its table of points).
"$cli" afm fit "$map" "${model[@]}" --index 0 --output "$work/one.tsv" 2>/dev/null || fail "--index 0 of the map"
grep -q '^# columns: point' "$work/one.tsv" || fail "--index: not the one-curve table"

# Adhesive retracts on a coating: E1 starts 2.5 times off, the nodes shared by the curves.
"$make_map" "$work/jkr.jpk-force-map" 4 4 --seed 5 --jkr --truth "$work/jkr_truth.tsv" || fail "make_afm_map --jkr"
"$cli" afm fit "$work/jkr.jpk-force-map" --model jkr --radius 10um --film 250kPa,0.5 --substrate 1MPa,0.3 --thickness 4um \
  --jobs 2 --output "$work/jkr.tsv" 2>"$work/jkr.err" || fail "the jkr map fit: $(cat "$work/jkr.err")"
awk 'BEGIN { FS = "\t" }
  FNR == NR { if ($0 !~ /^#/) { e[$1] = $4; w[$1] = $9; flag[$1] = $8 }; next }
  /^# columns:/ { sub(/^# columns: /, ""); for (k = 1; k <= NF; ++k) col[$k] = k; next }
  /^#/ { next }
  {
    n = $col["curve"]; ++rows
    if ($col["flag"] != flag[n]) { print "curve " n ": flag " $col["flag"] ", truth " flag[n]; bad = 1 }
    if ($col["flag"] != 0) next
    ++fitted
    ze = ($col["E1"] - e[n]) / $col["E1_error"]; zw = ($col["w"] - w[n]) / $col["w_error"]
    if (ze > 3 || ze < -3 || zw > 3 || zw < -3) { print "curve " n ": E1 " ze " SE, w " zw " SE"; bad = 1 }
  }
  END { if (rows != 16 || fitted != 13) { print rows " rows, " fitted " fitted (16, 13 expected)"; bad = 1 }; exit bad }' \
  "$work/jkr_truth.tsv" "$work/jkr.tsv" || fail "the jkr map against its truth"

# ---- issue 36: the rating, tabor_mu, maugis_lambda and warnings columns; --sort-by rating ------
grep -q $'\tpoints\trating\ttabor_mu\tmaugis_lambda\twarnings$' "$work/j1.tsv" \
  || fail "the rating, mu, lambda, warnings columns: $(grep '^# columns' "$work/j1.tsv")"
"$cli" afm fit "$work/syn.jpk-force-map" "${model[@]}" --jobs 1 --sort-by rating --output "$work/sorted.tsv" 2>/dev/null \
  || fail "--sort-by rating"
# The same rows, by rating highest first, equal ratings in curve order; flagged-unfit rows rate 0.
awk -F'\t' '/^# columns:/ { sub(/^# columns: /, ""); for (k = 1; k <= NF; ++k) col[$k] = k; next } /^#/ { next }
  { r = $col["rating"]; c = $col["curve"] + 0
    if (NR > 1 && seen && (r > last || (r == last && c < lastc))) bad = 1
    if ($col["flag"] != 0 && $col["flag"] != 10 && $col["flag"] != 11 && r != 0) bad = 1
    if ($col["tabor_mu"] != "-" || $col["maugis_lambda"] != "-") bad = 1
    last = r; lastc = c; seen = 1; ++n }
  END { exit bad || n != 64 }' "$work/sorted.tsv" || fail "--sort-by rating: rows not sorted, or a Hertz row with mu/lambda"
[ "$(grep -v '^#' "$work/sorted.tsv" | sort)" = "$(grep -v '^#' "$work/j1.tsv" | sort)" ] || fail "--sort-by changed the rows"
out=$("$cli" afm fit "$work/syn.jpk-force-map" "${model[@]}" --sort-by chi2 2>&1 >/dev/null); rc=$?
[ "$rc" -eq 2 ] && [[ "$out" == *"--sort-by: 'chi2' is not allowed; expected rating"* ]] || fail "--sort-by chi2: rc $rc, $out"

[ "$failures" -eq 0 ] && echo "afm fit over maps: all checks passed"
[ "$failures" -eq 0 ]
