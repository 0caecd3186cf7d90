#!/usr/bin/env bash
# coatcontact afm show/export on the real files, and bad files made here from the good ones
# (truncated, corrupt entry, missing calibration, missing channel, empty segment): exit 2, a
# message naming the file and the reason, and no output file.
# Usage: test_afm_cli.sh COATCONTACT DATA_DIR WORK_DIR
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

# ---- good files: show lists every file, export gives the header's point count ----------
for f in "$data"/fmt-*; do
  "$cli" afm show "$f" --output "$work/show.tsv" 2>"$work/stderr" || fail "afm show $f: $(cat "$work/stderr")"
  grep -q '^# columns: curve	' "$work/show.tsv" || fail "afm show $f: no columns line"
  grep -q '^# command: coatcontact afm show' "$work/show.tsv" || fail "afm show $f: no command line"
done
spot="$data/fmt-jpk-fd_spot3-0192.jpk-force"
"$cli" afm export "$spot" --output "$work/spot.tsv" || fail "export spot3"
rows=$(grep -vc '^#' "$work/spot.tsv")
[ "$rows" -eq 4000 ] || fail "spot3 export has $rows rows, the header says 2 x 2000"
grep -q '^# columns: time_s	segment	height_piezo_m	height_measured_m	force_N	tip_position_m$' "$work/spot.tsv" || fail "spot3 columns line"
grep -q '^# spring constant \[N/m\]: 0.043493666407368466 (file)$' "$work/spot.tsv" || fail "spot3 spring constant in the header"
# A supplied value overrides the file's and is recorded; the force scales with it exactly.
"$cli" afm export "$spot" --spring-constant 0.1 --output "$work/spot_k.tsv" || fail "export with --spring-constant"
grep -q '^# spring constant \[N/m\]: 0.1 (user)$' "$work/spot_k.tsv" || fail "user spring constant not recorded"
# Map: --index picks the curve; its grid index is in the header (position-index 99 of a
# back-and-forth 10 x 10 grid: row 9 runs backwards, so column 0, at the smallest x).
"$cli" afm export "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" --index 3 --output "$work/map3.tsv" || fail "export map index 3"
grep -q '^# grid index x, y: 0, 9$' "$work/map3.tsv" || fail "map curve 3 grid index"
grep -q '^# curve index: 3 of 4$' "$work/map3.tsv" || fail "map curve index"
# Missing calibration supplied on the command line.
"$cli" afm export "$data/fmt-jpk-fd_single-modified_2023.jpk-force" --spring-constant 0.05 --output "$work/mod.tsv" \
  || fail "single-modified with --spring-constant"
"$cli" afm export "$data/fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt" \
  --spring-constant 0.1 --sensitivity 2e-7 --output "$work/ntmdt.tsv" || fail "NT-MDT with calibration"
grep -q '^# sensitivity \[m/V\]: 2e-07 (user)$' "$work/ntmdt.tsv" || fail "NT-MDT user sensitivity not recorded"

# Preprocessing: named steps with their parameters in the header, the corrected force column.
"$cli" afm export "$spot" --preprocess --contact-point deviation --output "$work/pre.tsv" || fail "export --preprocess"
for line in '^# step 1, tip position: height (measured) + force / spring constant$' '^# step 2, baseline: ' \
            '^# baseline slope \[N/m\]: ' '^# step 3, contact point: deviation (5 baseline sigmas)$' '^# contact point \[m\]: ' \
            '^# columns: .*	tip_position_m	force_corrected_N$'; do
  grep -q "$line" "$work/pre.tsv" || fail "preprocess header lacks $line"
done
expect_error 2 "--contact-point" "needs --preprocess" -- afm export "$spot" --contact-point deviation
expect_error 2 "--contact-point" "expected piecewise-fit or deviation" -- afm export "$spot" --preprocess --contact-point magic
expect_error 2 "--baseline-fraction" "(0, 1)" -- afm export "$spot" --preprocess --baseline-fraction 1.5

# ---- missing calibration -----------------------------------------------------------------
cal="$data/fmt-jpk-cl_calibration_force-save-2015.02.04-11.25.21.294.jpk-force"
expect_error 2 "$cal" "no spring constant and no sensitivity" "--spring-constant" "--sensitivity" -- afm export "$cal"
mod="$data/fmt-jpk-fd_single-modified_2023.jpk-force"
expect_error 2 "$mod" "no spring constant" "--spring-constant" -- afm export "$mod"
ws="$data/fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip"
expect_error 2 "$ws" "--spring-constant" "--sensitivity" -- afm export "$ws"
nt="$data/fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt"
expect_error 2 "$nt" "no spring constant and no sensitivity" -- afm export "$nt"
expect_error 2 "$nt" "no sensitivity" "--sensitivity" -- afm export "$nt" --spring-constant 0.1
expect_error 2 "--spring-constant" "must be > 0" -- afm export "$spot" --spring-constant -1
expect_error 2 "--index" "holds 4 curves" -- afm export "$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map" --index 4

# ---- bad files made from good ones ---------------------------------------------------------
size=$(stat -c %s "$spot")
head -c $((size / 2)) "$spot" > "$work/truncated.jpk-force"
expect_error 2 "$work/truncated.jpk-force" "not a readable zip archive" -- afm export "$work/truncated.jpk-force"
expect_error 2 "$work/truncated.jpk-force" "truncated or corrupt" -- afm show "$work/truncated.jpk-force"
ibw="$data/fmt-igor-fd_U3_3_p10004.ibw"
head -c 60000 "$ibw" > "$work/truncated.ibw"
expect_error 2 "$work/truncated.ibw" "truncated Igor binary wave" -- afm export "$work/truncated.ibw"
head -c 100 "$ibw" > "$work/stub.ibw"
expect_error 2 "$work/stub.ibw" "truncated Igor binary wave" -- afm show "$work/stub.ibw"
csv="$data/fmt-afm-workshop-fd_single_2021-10-22_14.16.csv"
head -n 11 "$csv" > "$work/header_only.csv"
expect_error 2 "$work/header_only.csv" "empty segment" -- afm export "$work/header_only.csv"
sed '5,$d' "$csv" > "$work/no_columns.csv"
expect_error 2 "$work/no_columns.csv" "no column line" -- afm export "$work/no_columns.csv"
sed 's/Extend Force(nN)/Extend Stuff(nN)/' "$csv" > "$work/no_force.csv"
expect_error 2 "$work/no_force.csv" "missing channel" -- afm export "$work/no_force.csv"
: > "$work/empty.jpk-force"
expect_error 2 "$work/empty.jpk-force" "empty file" -- afm export "$work/empty.jpk-force"
expect_error 2 "$work/none.jpk-force" "no such file" -- afm export "$work/none.jpk-force"

# JPK archives rewritten by Python's zipfile: without vDeflection, with an empty segment, with
# a corrupt entry (its CRC fails).
python3 - "$spot" "$work" <<'PY' || fail "could not make the bad JPK archives"
import sys, zipfile
src, work = sys.argv[1], sys.argv[2]
entries = [(i, zipfile.ZipFile(src).read(i.filename)) for i in zipfile.ZipFile(src).infolist()]
def write(name, change):
    with zipfile.ZipFile(f"{work}/{name}", "w", zipfile.ZIP_DEFLATED) as out:
        for info, data in entries:
            data = change(info.filename, data)
            if data is not None:
                out.writestr(info.filename, data)
write("no_deflection.jpk-force", lambda n, d: None if n == "segments/1/channels/vDeflection.dat" else d)
def empty(n, d):
    if n == "segments/1/segment-header.properties":
        return d.replace(b"force-segment-header.num-points=2000", b"force-segment-header.num-points=0")
    return d
write("empty_segment.jpk-force", empty)
def short(n, d):
    return d[:1000] if n == "segments/0/channels/height.dat" else d
write("short_channel.jpk-force", short)
def no_list(n, d):
    if n == "segments/0/segment-header.properties":
        return d.replace(b"channels.list=height vDeflection strainGaugeHeight", b"channels.list=height strainGaugeHeight")
    return d
write("unlisted_deflection.jpk-force", no_list)
with zipfile.ZipFile(f"{work}/corrupt.jpk-force", "w", zipfile.ZIP_STORED) as out:
    for info, data in entries:
        out.writestr(info.filename, data)
raw = bytearray(open(f"{work}/corrupt.jpk-force", "rb").read())
at = raw.find(b"channels/vDeflection.dat") + 200  # inside the first stored channel's data
raw[at] ^= 0xFF
open(f"{work}/corrupt.jpk-force", "wb").write(bytes(raw))
PY
expect_error 2 "$work/no_deflection.jpk-force" "segments/1/channels/vDeflection.dat" "missing" -- afm export "$work/no_deflection.jpk-force"
expect_error 2 "$work/empty_segment.jpk-force" "segments/1/segment-header.properties" "empty segment" -- afm export "$work/empty_segment.jpk-force"
expect_error 2 "$work/short_channel.jpk-force" "segments/0/channels/height.dat" "truncated channel" -- afm export "$work/short_channel.jpk-force"
expect_error 2 "$work/unlisted_deflection.jpk-force" "missing channel vDeflection" -- afm export "$work/unlisted_deflection.jpk-force"
expect_error 2 "$work/corrupt.jpk-force" "$work/corrupt.jpk-force" "corrupt" -- afm export "$work/corrupt.jpk-force"

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "afm cli: all checks passed"
