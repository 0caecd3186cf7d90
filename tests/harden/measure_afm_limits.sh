#!/bin/bash
# Measures issue 40 item 3 (unbounded AFM reads): time and peak memory (/usr/bin/time -v) of
# `afm show` / `afm export` on crafted files, for each binary given. The files (up to ~30 MB)
# are made in WORK_DIR from data/afm; not a test (timings), run by hand for the closing note.
# Usage: measure_afm_limits.sh DATA_DIR WORK_DIR MAKE_AFM_MAP COATCONTACT...
set -u
data=$1 work=$2 make_map=$3
shift 3
mkdir -p "$work" && cd "$work" || exit 1
spot="$data/fmt-jpk-fd_spot3-0192.jpk-force"
single="$data/fmt-jpk-fd_single-modified_2023.jpk-force"
python3 - "$spot" "$single" <<'PY'
import sys, zipfile, struct
spot, single = sys.argv[1], sys.argv[2]
def rewrite(src, dst, change):
    with zipfile.ZipFile(src) as s, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as d:
        for info in s.infolist():
            d.writestr(info.filename, change(info.filename, s.read(info.filename)))
# zip bomb: 1 GiB of blanks in header.properties (~1 MB compressed)
rewrite(spot, "zip_bomb.jpk-force", lambda n, b: b + b" " * (1 << 30) if n == "header.properties" else b)
# properties bomb: 2000 shared settings referenced by 1000 keys of a segment header
def bomb(n, b):
    if n == "shared-data/header.properties":
        return b + b"".join(b"lcd-info.77.bomb%d=1\n" % k for k in range(2000))
    if n == "segments/0/segment-header.properties":
        return b + b"".join(b"bomb%d.lcd-info.*=77\n" % r for r in range(1000))
    return b
rewrite(single, "properties_bomb.jpk-force", bomb)
# lying entry size: header.properties declared 1 GiB in the central directory
data = bytearray(open(spot, "rb").read())
at = data.find(b"PK\x01\x02")
while at >= 0:
    length = struct.unpack_from("<H", data, at + 28)[0]
    if data[at + 46:at + 46 + length] == b"header.properties":
        struct.pack_into("<I", data, at + 24, 1 << 30)
    at = data.find(b"PK\x01\x02", at + 4)
open("lying_size.jpk-force", "wb").write(data)
head = ("Force-Distance Curve\nFile Format:\t3\n\nX, um:\t0.5\nY, um:\t0.5\n\n"
        "Extend Z-Sense(nm),Extend Force(nN),Retract Z-Sense(nm),Retract Force(nN)")
# rows x columns: 50 000 extra columns, 20 000 rows
with open("wide.csv", "w") as f:
    f.write(head + ",x" * 50000 + "\n")
    for i in range(20000):
        f.write("%d.5,0.05,%d.5,0.07\n" % (4000 + i, 5000 - i))
# one long row: 4 Mi fields (8 MB)
with open("long_row.csv", "w") as f:
    f.write(head + "\n" + "1," * (1 << 22) + "1\n")
PY
"$make_map" map.jpk-force-map 32 32 --points 2000 --clean > /dev/null
run() {  # label, command...
  local label=$1
  shift
  /usr/bin/time -v "$@" > /dev/null 2> time.log
  local rc=$?
  printf '%-22s rc %3s  %8s s  %9s KB  %s\n' "$label" "$rc" "$(grep 'Elapsed (wall' time.log | awk '{print $NF}')" \
    "$(grep 'Maximum resident' time.log | awk '{print $NF}')" "$(grep -m1 'error' time.log | cut -c1-110)"
}
for cli in "$@"; do
  echo "== $cli"
  run zip_bomb "$cli" afm show zip_bomb.jpk-force
  run properties_bomb "$cli" afm show properties_bomb.jpk-force
  run lying_size "$cli" afm show lying_size.jpk-force
  run wide_csv "$cli" afm show wide.csv --spring-constant 0.1
  run long_row "$cli" afm show long_row.csv
  run "map show" "$cli" afm show map.jpk-force-map
  run "map export --index 5" "$cli" afm export map.jpk-force-map --index 5
done
