#!/usr/bin/env bash
# CPU seconds (user + sys) and wall seconds of each data command of `make figures`, one at a
# time, slowest first, then the totals: where the figures' time goes (issue 37).
# Usage: bench/figure_data_timings.sh CLI   (run from anywhere; no solve cache)
set -euo pipefail
cli="$(realpath "${1:?usage: bench/figure_data_timings.sh CLI}")"
root="$(cd "$(dirname "$0")/.." && pwd)"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# The data commands as make would run them (dry run), one a line.
make -s -n -C "$root" -f gnuplot/figures.mk figures-only CLI="$cli" DATA_DIR="$scratch/d" FIG_DIR="$scratch/f" 2>/dev/null |
  grep -o "$cli .*" > "$scratch/commands"
mkdir -p "$scratch/d"
while read -r -a command; do
  name=$(basename "${command[-1]}" .tsv)
  /usr/bin/time -f "%U %S %e" -o "$scratch/time" env OMP_WAIT_POLICY=PASSIVE "${command[@]}" > /dev/null 2>&1
  read -r user sys wall < "$scratch/time"
  awk -v u="$user" -v s="$sys" -v w="$wall" -v n="$name" 'BEGIN { printf "%.2f\t%.2f\t%s\n", u + s, w, n }'
done < "$scratch/commands" | sort -rn > "$scratch/rows"
printf 'cpu_s\twall_s\tdataset\n'
cat "$scratch/rows"
awk '{ c += $1; w += $2 } END { printf "%.2f\t%.2f\ttotal (%d commands)\n", c, w, NR }' "$scratch/rows"
