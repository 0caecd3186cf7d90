#!/usr/bin/env bash
# The Maugis-Dugdale retract fit over a force map (issue 37; THEORY.md section 15, "A map of
# Maugis-Dugdale retracts"): synthetic N x N maps (tests/afm/make_afm_map --md [--rigid] --clean:
# the library's own MD spring model, a film E1 = 100 kPa +- 20 %, nu1 = 0.5, t = 4 um on
# E0 = 1 MPa, nu0 = 0.3, or on a rigid base; w 8-14 mJ/m2, z0 = 0.5 um, k = 1 N/m, noise)
# fitted with `afm fit MAP --model md` (E1 from 250 kPa, w, contact point, baseline, tilt free):
#  - one curve alone (--index 0, its own process: the first curve of a sample, every table it
#    reads built for it), the whole map with --jobs 1 and --jobs 2: wall and CPU (user + sys) of
#    the whole process;
#  - the cost of a FURTHER curve, once the sample's tables exist: (map --jobs 1 - curve 0 alone)
#    / (N^2 - 1), CPU and wall (the process start and the first curve's tables cancel);
#  - the --jobs 2 speed-up (wall 1 / wall 2); --jobs 2's table must equal --jobs 1's;
#  - peak RSS (GNU time's %M) of the one-curve run and of the map, --jobs 2: what the tables hold.
# The solve cache is off (COATCONTACT_CACHE unset): every node is solved in the process.
# Rows "task value ... kind" like cli_timings.sh (kind cli: ms; ratio). The machine is shared:
# read the CPU rows. Usage: bench/md_map.sh CLI MAKE_AFM_MAP [WORK_DIR [N]]
set -euo pipefail
cli="${1:?usage: bench/md_map.sh CLI MAKE_AFM_MAP [WORK_DIR [N]]}"
make_map="${2:?usage: bench/md_map.sh CLI MAKE_AFM_MAP [WORK_DIR [N]]}"
work="${3:-$(mktemp -d)}"
size="${4:-8}"
mkdir -p "$work"
unset COATCONTACT_CACHE
curves=$((size * size))

# run NAME ARGS...: prints "wall_s user_s sys_s maxrss_kB" of one run of the CLI.
run() {
  local name="$1"; shift
  rm -f "$work/$name.tsv" "$work/$name.tsv.partial"
  /usr/bin/time -f '%e %U %S %M' -o "$work/$name.time" "$cli" "$@" --output "$work/$name.tsv" 2>"$work/$name.err" >/dev/null
  cat "$work/$name.time"
}

for base in elastic rigid; do
  if [ "$base" = elastic ]; then substrate=1MPa,0.3 rigid=(); else substrate=rigid rigid=(--rigid); fi
  map="$work/md$size$base.jpk-force-map"
  "$make_map" "$map" "$size" "$size" --seed 7 --md "${rigid[@]}" --clean
  model=(--model md --radius 10um --film 250kPa,0.5 --substrate "$substrate" --thickness 4um --range 0.5um)
  read -r w0 u0 s0 m0 < <(run "${base}_one" afm fit "$map" "${model[@]}" --index 0)
  read -r w1 u1 s1 _ < <(run "${base}_j1" afm fit "$map" "${model[@]}" --jobs 1)
  read -r w2 u2 s2 m2 < <(run "${base}_j2" afm fit "$map" "${model[@]}" --jobs 2)
  cmp -s <(grep -v '^# command' "$work/${base}_j1.tsv") <(grep -v '^# command' "$work/${base}_j2.tsv") \
    || echo "md_map.sh: $base base: --jobs 2 table differs from --jobs 1" >&2
  flagged=$(grep -vc $'^#\|\t0\tfitted\t' "$work/${base}_j1.tsv" || true)
  [ "$flagged" -eq 0 ] || echo "md_map.sh: $base base: $flagged curves flagged" >&2
  awk -v b="$base" -v n="$curves" -v s="$size" -v m0="$m0" -v m2="$m2" -v w0="$w0" -v c0="$(awk -v u="$u0" -v s="$s0" 'BEGIN { print u + s }')" \
    -v w1="$w1" -v c1="$(awk -v u="$u1" -v s="$s1" 'BEGIN { print u + s }')" \
    -v w2="$w2" -v c2="$(awk -v u="$u2" -v s="$s2" 'BEGIN { print u + s }')" 'BEGIN {
    t = "afm fit --model md, E1 free, " b " base"
    printf "%s, one curve alone (--index 0; wall)\t%.4g\t\t\t1\tcli\n", t, w0 * 1000
    printf "%s, one curve alone (--index 0; user+sys CPU)\t%.4g\t\t\t1\tcli\n", t, c0 * 1000
    printf "%s, %dx%d map, --jobs 1 (wall)\t%.4g\t\t\t1\tcli\n", t, s, s, w1 * 1000
    printf "%s, %dx%d map, --jobs 1 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", t, s, s, c1 * 1000
    printf "%s, %dx%d map, --jobs 2 (wall)\t%.4g\t\t\t1\tcli\n", t, s, s, w2 * 1000
    printf "%s, %dx%d map, --jobs 2 (user+sys CPU)\t%.4g\t\t\t1\tcli\n", t, s, s, c2 * 1000
    printf "%s, further curve ((map --jobs 1 - curve 0 alone)/%d; user+sys CPU)\t%.4g\t\t\t1\tcli\n", t, n - 1, (c1 - c0) * 1000 / (n - 1)
    printf "%s, further curve ((map --jobs 1 - curve 0 alone)/%d; wall)\t%.4g\t\t\t1\tcli\n", t, n - 1, (w1 - w0) * 1000 / (n - 1)
    printf "%s, %dx%d map, --jobs 2 speed-up (wall 1 / wall 2)\t%.3g\t\t\t1\tratio\n", t, s, s, w1 / w2
    printf "%s, one curve alone (--index 0), peak RSS\t%d\t\t\t1\trss_kB\n", t, m0
    printf "%s, %dx%d map, --jobs 2, peak RSS\t%d\t\t\t1\trss_kB\n", t, s, s, m2
  }'
done
