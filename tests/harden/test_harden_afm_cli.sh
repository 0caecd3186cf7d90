#!/bin/bash
# Regressions of issue 40 (items 4 and 7) at the command line: a file-size limit (ulimit -f)
# is exit 2 naming the file, not death by SIGXFSZ with a temporary file left; a map fit to
# /dev/null makes no /dev/null.partial; OMP_NUM_THREADS beyond the limit is exit 2 naming the
# variable, not a segfault; one corrupt curve of a map does not stop afm show or afm export of
# another curve. Usage: test_harden_afm_cli.sh COATCONTACT DATA_DIR WORK_DIR
set -u
cli=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
map="$data/fmt-jpk-fd_map2x2_extracted.jpk-force-map"
model=(--radius 10e-6 --halfspace 1e4,0.5)

# regression: SIGXFSZ under ulimit -f (1 KiB: the map's table is larger).
(ulimit -f 1; exec "$cli" afm fit "$map" "${model[@]}" --output limited.tsv) 2> limited.err
rc=$?
[ "$rc" = 2 ] || fail "ulimit -f: exit $rc, expected 2 (153 is death by SIGXFSZ)"
grep -q "limited.tsv.*File too large" limited.err || fail "ulimit -f: the message names the file and EFBIG: $(cat limited.err)"
ls "$work" | grep -q '\.tmp\.' && fail "ulimit -f: a temporary file was left: $(ls "$work")"
(ulimit -f 1; exec "$cli" afm export "$map" --index 0 --output export.tsv) 2> export.err
rc=$?
[ "$rc" = 2 ] && grep -q "export.tsv" export.err || fail "ulimit -f, afm export: exit $rc: $(cat export.err)"
ls "$work" | grep -q '\.tmp\.' && fail "ulimit -f, afm export: a temporary file was left: $(ls "$work")"

# regression: afm fit MAP --output /dev/null tried to create /dev/null.partial.
rm -f /dev/null.partial 2>/dev/null
"$cli" afm fit "$map" "${model[@]}" --output /dev/null 2> devnull.err || fail "--output /dev/null: $(cat devnull.err)"
[ -e /dev/null.partial ] && fail "--output /dev/null made /dev/null.partial"
"$cli" afm fit "$map" "${model[@]}" --output /dev/stderr 2> stderr.out > /dev/null || fail "--output /dev/stderr: $(cat stderr.out)"
grep -q '^# flagged curves: 0 of 4' stderr.out || fail "--output /dev/stderr: the table went to standard error"
"$cli" afm fit "$map" "${model[@]}" --output /dev/null --resume 2> resume.err
[ $? = 2 ] && grep -q "regular file" resume.err || fail "--resume with /dev/null: $(cat resume.err)"

# regression: OMP_NUM_THREADS=100000 segfaulted any OpenMP command.
OMP_NUM_THREADS=100000 "$cli" reduced --film 1e6,0.3 --substrate 1e9,0.3 --a-over-t 0.1,1,10 --output omp.tsv 2> omp.err
rc=$?
[ "$rc" = 2 ] && grep -q "OMP_NUM_THREADS: 100000 is not allowed" omp.err || fail "OMP_NUM_THREADS=100000: exit $rc: $(cat omp.err)"
[ -e omp.tsv ] && fail "OMP_NUM_THREADS=100000: output written"
OMP_NUM_THREADS=3 "$cli" reduced --film 1e6,0.3 --substrate 1e9,0.3 --a-over-t 0.1,1,10 --output omp3.tsv || fail "OMP_NUM_THREADS=3"

# regression: one corrupt curve (curve 1's vDeflection of segment 0 cut to 3 bytes) made
# afm show and afm export --index 0 of the whole map fail.
python3 - "$map" "$work/one_bad.jpk-force-map" <<'PY' || fail "could not make the map with one corrupt curve"
import sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as src, zipfile.ZipFile(sys.argv[2], "w", zipfile.ZIP_DEFLATED) as dst:
    for info in src.infolist():
        data = src.read(info.filename)
        if info.filename == "index/1/segments/0/channels/vDeflection.dat":
            data = data[:3]
        dst.writestr(info.filename, data)
PY
"$cli" afm show "$work/one_bad.jpk-force-map" --output show.tsv 2> show.err || fail "afm show with one corrupt curve: $(cat show.err)"
grep -q '^# unreadable curves: 1 (.*index/1/segments/0/channels/vDeflection.dat: truncated channel' show.tsv || fail "afm show: the unreadable curve is not named"
awk -F'\t' '$1 == 1 && $7 == "unreadable"' show.tsv | grep -q . || fail "afm show: no 'unreadable' row for curve 1"
[ "$(awk -F'\t' '$1 == 2' show.tsv | wc -l)" = 2 ] || fail "afm show: curve 2 lost its segments"
"$cli" afm export "$work/one_bad.jpk-force-map" --index 0 --output export0.tsv || fail "afm export --index 0 with curve 1 corrupt"
"$cli" afm export "$work/one_bad.jpk-force-map" --index 1 --output export1.tsv 2> export1.err
[ $? = 2 ] && grep -q "truncated channel" export1.err || fail "afm export --index 1 (the corrupt curve): $(cat export1.err)"

# regression: a read I/O error was an "internal error" without the file name (/proc/self/mem
# is a regular file whose read at offset 0 fails with EIO).
if [ -r /proc/self/mem ]; then
  "$cli" afm show /proc/self/mem 2> eio.err
  rc=$?
  [ "$rc" = 2 ] && grep -q "/proc/self/mem: read error (Input/output error)" eio.err || fail "read I/O error: exit $rc: $(cat eio.err)"
fi

# ---- item 5: --resume on one FILE.partial ----
# The partial file of a run is its table without the flagged count; rows are checked against
# the run's curve list (map2x2 then spot3: 5 rows).
spot="$data/fmt-jpk-fd_spot3-0192.jpk-force"
"$cli" afm fit "$map" "$spot" "${model[@]}" --output whole.tsv 2> /dev/null || fail "the reference run"
body() { grep -v '^#' "$1"; }
make_partial() {  # NAME, then the rows (sed program on the body)
  { grep '^#' whole.tsv | grep -v '^# flagged curves'; body whole.tsv | sed -n "$2"; } > "$1.partial"
}
# regression: --resume accepted duplicate, missing or foreign rows.
for case in "duplicate 1p;1p" "missing 1p;3p" "foreign 1p;s/^[^\t]*/other.jpk-force/;2p"; do
  name=${case%% *} program=${case#* }
  make_partial "res_$name.tsv" "$program"
  "$cli" afm fit "$map" "$spot" "${model[@]}" --resume --output "res_$name.tsv" 2> "res_$name.err"
  rc=$?
  [ "$rc" = 2 ] && grep -q "row 2 of .*(a duplicate, missing or foreign row" "res_$name.err" \
    || fail "--resume with a $name row: exit $rc: $(cat "res_$name.err")"
  [ -e "res_$name.tsv" ] && fail "--resume with a $name row wrote the table"
done
make_partial res_good.tsv "1,2p"
"$cli" afm fit "$map" "$spot" "${model[@]}" --resume --output res_good.tsv 2> res_good.err || fail "--resume of 2 good rows: $(cat res_good.err)"
cmp -s <(body whole.tsv) <(body res_good.tsv) || fail "--resume of 2 good rows differs from the whole run"
# regression: two concurrent --resume runs on one .partial (368 rows for 256 curves). The
# lock is held here by flock(1) as a concurrent run would hold it.
make_partial res_held.tsv "1,2p"
flock -x res_held.tsv.partial -c "\"$cli\" afm fit \"$map\" \"$spot\" ${model[*]} --resume --output res_held.tsv 2> held.err; echo \$? > held.rc"
[ "$(cat held.rc)" = 2 ] && grep -q "in use by another run on the same FILE (locked)" held.err \
  || fail "--resume while another process holds FILE.partial: exit $(cat held.rc): $(cat held.err)"
[ "$(body res_held.tsv.partial | wc -l)" = 2 ] || fail "the locked partial file was changed"
# regression: a file name starting with '#' made rows that read as comments.
cp "$spot" "#hash.jpk-force"
"$cli" afm fit "#hash.jpk-force" "$spot" "${model[@]}" --output hash.tsv 2> hash.err || fail "a file named #...: $(cat hash.err)"
[ "$(body hash.tsv | wc -l)" = 2 ] && body hash.tsv | grep -q '^\./#hash.jpk-force	0	' || fail "the row of #hash.jpk-force: $(body hash.tsv)"

[ "$failures" = 0 ] && echo "all checks passed" || echo "$failures failure(s)"
[ "$failures" = 0 ]
