#!/usr/bin/env bash
# Batch fits of synthetic JPK force maps (issue 25; tests/afm/make_afm_map writes them from the
# library's Hertz model): `afm fit MAP --radius 10um --halfspace 5kPa,0.5` on
#  - a 32 x 32 map (400 points per segment), --jobs 1 and --jobs 2: wall, user and system time,
#    the --jobs 2 speed-up (wall 1 / wall 2), curves per second;
#  - 64 x 64 and 256 x 256 maps (100 points per segment): peak RSS (GNU time's %M) of the batch
#    and of opening the archive and fitting one curve (--index 0): their difference is what the
#    batch itself holds beyond libzip's copy of the archive's central directory.
#  - a 32 x 32 map of adhesive retracts on a coating (make_afm_map --jkr: the library's JKR
#    spring model, film 100 kPa, t = 4 um on 1 MPa, w 8-14 mJ/m2, k = 1 N/m, noise, tilt, bad
#    curves) fitted with `--model jkr` (E1 from 250 kPa, w, contact point, baseline, tilt free),
#    --jobs 2: wall and CPU time, and the recovered E1 and w against the truth (mean and RMS of
#    the relative error, mean |z-score|) over the fitted curves, and the flags against the truth's.
#  - the approaches of the same map (the adhesionless coated model, make_afm_map --jkr) fitted
#    with the coated Hertz model (E1 from 250 kPa free on 1 MPa, t = 4 um; issue 37's 32 x 32
#    coated map, target 30 s on 2 cores): wall and CPU time, E1 against the truth.
#  - with ZIP_OPEN_RSS (bench/zip_open_rss.cpp): the heap libzip alone keeps for each opened
#    map (per entry of its central directory) and the peak RSS of a process that only opens it:
#    the memory budget of THEORY.md section 15, "Memory of a run".
# Rows "task value ... kind" like cli_timings.sh (kind: cli for times in ms, rss_kB, ratio).
# The machine is shared: compare user + system (CPU) time as well as wall time.
# Usage: bench/afm_maps.sh CLI MAKE_AFM_MAP [WORK_DIR [ZIP_OPEN_RSS]]
set -euo pipefail
cli="${1:?usage: bench/afm_maps.sh CLI MAKE_AFM_MAP [WORK_DIR [ZIP_OPEN_RSS]]}"
make_map="${2:?usage: bench/afm_maps.sh CLI MAKE_AFM_MAP [WORK_DIR [ZIP_OPEN_RSS]]}"
work="${3:-$(mktemp -d)}"
zip_open="${4:-}"
mkdir -p "$work"
model=(--radius 10um --halfspace 5kPa,0.5)

# run NAME ARGS...: prints "wall_s user_s sys_s maxrss_kB" of one run of the CLI.
run() {
  local name="$1"; shift
  rm -f "$work/$name.tsv" "$work/$name.tsv.partial"
  /usr/bin/time -f '%e %U %S %M' -o "$work/$name.time" "$cli" "$@" --output "$work/$name.tsv" 2>"$work/$name.err" >/dev/null
  cat "$work/$name.time"
}

"$make_map" "$work/map32.jpk-force-map" 32 32 --seed 3
read -r w1 u1 s1 m1 < <(run j1 afm fit "$work/map32.jpk-force-map" "${model[@]}" --jobs 1)
read -r w2 u2 s2 m2 < <(run j2 afm fit "$work/map32.jpk-force-map" "${model[@]}" --jobs 2)
cmp -s <(grep -v '^# command' "$work/j1.tsv") <(grep -v '^# command' "$work/j2.tsv") \
  || echo "afm_maps.sh: --jobs 2 table differs from --jobs 1" >&2
awk -v w1="$w1" -v u1="$u1" -v s1="$s1" -v w2="$w2" -v u2="$u2" -v s2="$s2" 'BEGIN {
  printf "afm fit 32x32 map, Hertz, --jobs 1 (wall)\t%.4g\t\t\t1\tcli\n", w1 * 1000
  printf "afm fit 32x32 map, Hertz, --jobs 1 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", (u1 + s1) * 1000
  printf "afm fit 32x32 map, Hertz, --jobs 2 (wall)\t%.4g\t\t\t1\tcli\n", w2 * 1000
  printf "afm fit 32x32 map, Hertz, --jobs 2 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", (u2 + s2) * 1000
  printf "afm fit 32x32 map, --jobs 2 speed-up (wall 1 / wall 2)\t%.3g\t\t\t1\tratio\n", w1 / w2
  printf "afm fit 32x32 map, curves per second, --jobs 2\t%.4g\t\t\t1\tratio\n", 1024 / w2
}'

"$make_map" "$work/map32jkr.jpk-force-map" 32 32 --seed 5 --jkr --truth "$work/map32jkr.truth"
read -r wj uj sj mj < <(run jkr afm fit "$work/map32jkr.jpk-force-map" --model jkr --radius 10um --film 250kPa,0.5 \
  --substrate 1MPa,0.3 --thickness 4um --jobs 2)
awk -v wj="$wj" -v uj="$uj" -v sj="$sj" 'BEGIN { FS = "\t" }
  FNR == NR { if ($0 !~ /^#/) { e[$1] = $4; w[$1] = $9; flag[$1] = $8 }; next }
  /^# columns:/ { sub(/^# columns: /, ""); for (k = 1; k <= NF; ++k) col[$k] = k; next }
  /^#/ { next }
  {
    n = $col["curve"]; ++curves
    if ($col["flag"] != flag[n]) ++wrong_flags
    if ($col["flag"] != 0) next
    de = $col["E1"] / e[n] - 1; dw = $col["w"] / w[n] - 1
    ze = ($col["E1"] - e[n]) / $col["E1_error"]; zw = ($col["w"] - w[n]) / $col["w_error"]
    ++fitted; se += de; see += de * de; sw += dw; sww += dw * dw; aze += (ze < 0 ? -ze : ze); azw += (zw < 0 ? -zw : zw)
  }
  END {
    printf "afm fit 32x32 JKR coating map, --jobs 2 (wall)\t%.4g\t\t\t1\tcli\n", wj * 1000
    printf "afm fit 32x32 JKR coating map, --jobs 2 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", (uj + sj) * 1000
    printf "afm fit 32x32 JKR coating map, fitted curves (of %d; flags unlike the truth: %d)\t%d\t\t\t1\tratio\n", curves, wrong_flags, fitted
    printf "afm fit 32x32 JKR coating map, E1 mean relative error\t%.3g\t\t\t1\tratio\n", se / fitted
    printf "afm fit 32x32 JKR coating map, E1 RMS relative error\t%.3g\t\t\t1\tratio\n", sqrt(see / fitted)
    printf "afm fit 32x32 JKR coating map, w mean relative error\t%.3g\t\t\t1\tratio\n", sw / fitted
    printf "afm fit 32x32 JKR coating map, w RMS relative error\t%.3g\t\t\t1\tratio\n", sqrt(sww / fitted)
    printf "afm fit 32x32 JKR coating map, E1 mean |z-score|\t%.3g\t\t\t1\tratio\n", aze / fitted
    printf "afm fit 32x32 JKR coating map, w mean |z-score|\t%.3g\t\t\t1\tratio\n", azw / fitted
  }' "$work/map32jkr.truth" "$work/jkr.tsv"
read -r wh uh sh mh < <(run hertzcoat afm fit "$work/map32jkr.jpk-force-map" --segment approach --radius 10um \
  --film 250kPa,0.5 --substrate 1MPa,0.3 --thickness 4um --jobs 2)
awk -v wh="$wh" -v uh="$uh" -v sh="$sh" 'BEGIN { FS = "\t" }
  FNR == NR { if ($0 !~ /^#/) e[$1] = $4; next }
  /^# columns:/ { sub(/^# columns: /, ""); for (k = 1; k <= NF; ++k) col[$k] = k; next }
  /^#/ { next }
  $col["flag"] == 0 { de = $col["E1"] / e[$col["curve"]] - 1; ++fitted; see += de * de }
  END {
    printf "afm fit 32x32 coated map, Hertz approach, --jobs 2 (wall)\t%.4g\t\t\t1\tcli\n", wh * 1000
    printf "afm fit 32x32 coated map, Hertz approach, --jobs 2 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", (uh + sh) * 1000
    printf "afm fit 32x32 coated map, Hertz approach, fitted curves\t%d\t\t\t1\tratio\n", fitted
    printf "afm fit 32x32 coated map, Hertz approach, E1 RMS relative error\t%.3g\t\t\t1\tratio\n", sqrt(see / fitted)
  }' "$work/map32jkr.truth" "$work/hertzcoat.tsv"

"$make_map" "$work/map64.jpk-force-map" 64 64 --points 100 --seed 4 --clean
"$make_map" "$work/map256.jpk-force-map" 256 256 --points 100 --seed 6 --clean
# The archive alone: one curve fitted (--index 0) after libzip has read the central directory
# (~3 entries per segment and curve), which the batch cannot avoid.
read -r _ _ _ oa < <(run o64 afm fit "$work/map64.jpk-force-map" "${model[@]}" --index 0)
read -r _ _ _ ob < <(run o256 afm fit "$work/map256.jpk-force-map" "${model[@]}" --index 0)
read -r wa ua sa ma < <(run m64 afm fit "$work/map64.jpk-force-map" "${model[@]}" --jobs 2)
read -r wb ub sb mb < <(run m256 afm fit "$work/map256.jpk-force-map" "${model[@]}" --jobs 2)
awk -v oa="$oa" -v ob="$ob" -v wa="$wa" -v ma="$ma" -v wb="$wb" -v mb="$mb" -v ua="$ua" -v sa="$sa" -v ub="$ub" -v sb="$sb" 'BEGIN {
  printf "afm fit 64x64 map (100 points), --jobs 2 (wall)\t%.4g\t\t\t1\tcli\n", wa * 1000
  printf "afm fit 64x64 map (100 points), --jobs 2 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", (ua + sa) * 1000
  printf "afm fit 256x256 map (100 points), --jobs 2 (wall)\t%.4g\t\t\t1\tcli\n", wb * 1000
  printf "afm fit 256x256 map (100 points), --jobs 2 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", (ub + sb) * 1000
  printf "afm fit 64x64 map, peak RSS\t%d\t\t\t1\trss_kB\n", ma
  printf "afm fit 256x256 map, peak RSS\t%d\t\t\t1\trss_kB\n", mb
  printf "afm fit peak RSS 256x256 / 64x64\t%.3g\t\t\t1\tratio\n", mb / ma
  printf "afm fit --index 0 (archive opened, one curve) 64x64, peak RSS\t%d\t\t\t1\trss_kB\n", oa
  printf "afm fit --index 0 (archive opened, one curve) 256x256, peak RSS\t%d\t\t\t1\trss_kB\n", ob
  printf "afm fit 256x256 map, peak RSS beyond the opened archive\t%d\t\t\t1\trss_kB\n", mb - ob
}'

if [ -n "$zip_open" ]; then
  for size in 64 256; do
    # "rdonly entries rss_kB heap_kB heap_bytes_per_entry" and the process's peak RSS.
    /usr/bin/time -f '%M' -o "$work/zip$size.time" "$zip_open" "$work/map$size.jpk-force-map" rdonly >"$work/zip$size.out"
    read -r _ entries _ heap per_entry <"$work/zip$size.out"
    awk -v size="$size" -v entries="$entries" -v heap="$heap" -v per="$per_entry" -v peak="$(cat "$work/zip$size.time")" 'BEGIN {
      printf "zip_open (libzip alone, ZIP_RDONLY) %dx%d map: entries\t%d\t\t\t1\tcount\n", size, size, entries
      printf "zip_open (libzip alone, ZIP_RDONLY) %dx%d map: heap kept\t%d\t\t\t1\trss_kB\n", size, size, heap
      printf "zip_open (libzip alone, ZIP_RDONLY) %dx%d map: heap bytes per entry\t%.4g\t\t\t1\tbytes\n", size, size, per
      printf "zip_open (libzip alone, ZIP_RDONLY) %dx%d map: process peak RSS\t%d\t\t\t1\trss_kB\n", size, size, peak
    }'
  done
fi
