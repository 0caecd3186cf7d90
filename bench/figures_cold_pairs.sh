#!/usr/bin/env bash
# `make figures` from a built tree with an empty solve cache, two trees paired (issue 37):
# the whole process tree of `make -f gnuplot/figures.mk figures-only -j2` into fresh data,
# figure and cache folders, A and B alternated, N pairs; CPU (user + sys of every process,
# /usr/bin/time on make) and wall, one line a run, then the medians and the paired CPU ratios.
# Usage: bench/figures_cold_pairs.sh TREE_A CLI_A TREE_B CLI_B [PAIRS]   (TREE: a source tree
# whose gnuplot/figures.mk and data/figures.conf are used). Prints the load before each run.
set -euo pipefail
tree_a=$(realpath "$1"); cli_a=$(realpath "$2"); tree_b=$(realpath "$3"); cli_b=$(realpath "$4"); pairs=${5:-4}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
run() {  # tree cli label
  rm -rf "$scratch/run" && mkdir -p "$scratch/run"
  local load; load=$(cut -d' ' -f1 /proc/loadavg)
  /usr/bin/time -f "%U %S %e" -o "$scratch/time" make -s -C "$1" -f gnuplot/figures.mk figures-only -j2 \
    CLI="$2" DATA_DIR="$scratch/run/d" FIG_DIR="$scratch/run/f" SOLVE_CACHE="$scratch/run/c" > /dev/null 2>&1
  read -r user sys wall < "$scratch/time"
  awk -v u="$user" -v s="$sys" -v w="$wall" -v l="$3" -v load="$load" \
    'BEGIN { printf "%s\t%.2f\t%.2f\tload %s\n", l, u + s, w, load }'
}
printf 'run\tcpu_s\twall_s\tload_before\n'
for ((i = 0; i < pairs; i++)); do
  run "$tree_a" "$cli_a" A
  run "$tree_b" "$cli_b" B
done | tee "$scratch/rows"
awk '$1 == "A" { a[++na] = $2; aw[na] = $3 } $1 == "B" { b[++nb] = $2; bw[nb] = $3 }
  function median(x, n,   i, j, t) { for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (x[j] < x[i]) { t = x[i]; x[i] = x[j]; x[j] = t }
    return n % 2 ? x[(n + 1) / 2] : (x[n / 2] + x[n / 2 + 1]) / 2 }
  END { for (i = 1; i <= na; i++) r[i] = b[i] / a[i]
    printf "median\tA cpu %.2f wall %.2f\tB cpu %.2f wall %.2f\tB/A cpu %.3f\n", median(a, na), median(aw, na), median(b, nb), median(bw, nb), median(r, na) }' "$scratch/rows"
