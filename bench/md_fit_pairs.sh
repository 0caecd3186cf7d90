#!/usr/bin/env bash
# Issue 37 item 2: the Maugis-Dugdale AFM retract fit on the real curves of data/afm, two CLI
# binaries (BEFORE, AFTER) run in alternation, CPU time (user + sys) of the whole process;
# rows "curve sample before_ms after_ms ratio" per pair and the median of the paired ratios.
# Usage: bench/md_fit_pairs.sh BEFORE_CLI AFTER_CLI [PAIRS]
# With BEFORE_CACHE and AFTER_CACHE set (two folders), each binary runs with its own solve cache
# (COATCONTACT_CACHE), warmed by one unmeasured run of each fit first: the cost of a sample whose
# tables' nodes an earlier process solved. Unset: no cache (every node solved).
set -euo pipefail
before="${1:?usage: bench/md_fit_pairs.sh BEFORE_CLI AFTER_CLI [PAIRS]}"
after="${2:?}"
pairs="${3:-3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
data="${COATCONTACT_AFM_DATA:-$root/../shared/data/afm}"
[ -d "$data" ] || data=/work/shared/data/afm
out=$(mktemp)
trap 'rm -f "$out"' EXIT
cpu_ms() {
  local TIMEFORMAT='%U %S' t cache="$1"
  shift
  if [ -n "$cache" ]; then export COATCONTACT_CACHE="$cache"; else unset COATCONTACT_CACHE; fi
  t=$( { time "$@" --output "$out" > /dev/null 2>&1; } 2>&1 )
  awk -v t="$t" 'BEGIN { split(t, p, " "); printf "%d", (p[1] + p[2]) * 1000 }'
}
printf '# columns: curve\tsample\tbefore_cpu_ms_median\tafter_cpu_ms_median\tratio_median (paired, %s pairs)\n' "$pairs"
for curve in fmt-igor-fd_U3_3_p10004.ibw fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force \
  fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force fmt-jpk-fd_spot3-0192.jpk-force; do
  for sample in "--halfspace 1kPa,0.5" "--film 10kPa,0.5 --substrate rigid --thickness 2um" \
    "--film 1kPa,0.5 --substrate 10kPa,0.25 --thickness 1um"; do
    args=(afm fit "$data/$curve" --model md --radius 10um $sample)
    a=() b=() r=()
    if [ -n "${BEFORE_CACHE:-}" ]; then
      cpu_ms "$BEFORE_CACHE" "$before" "${args[@]}" > /dev/null
      cpu_ms "$AFTER_CACHE" "$after" "${args[@]}" > /dev/null
    fi
    for ((i = 0; i < pairs; i++)); do
      x=$(cpu_ms "${BEFORE_CACHE:-}" "$before" "${args[@]}")
      y=$(cpu_ms "${AFTER_CACHE:-}" "$after" "${args[@]}")
      a+=("$x") b+=("$y") r+=("$(awk -v x="$x" -v y="$y" 'BEGIN { printf "%.4f", y / x }')")
    done
    med() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
    printf '%s\t%s\t%s\t%s\t%s\n' "$curve" "$sample" "$(med "${a[@]}")" "$(med "${b[@]}")" "$(med "${r[@]}")"
  done
done
