#!/usr/bin/env bash
# CPU (user + sys) and wall seconds of the two Maugis-Dugdale datasets of `make figures`
# (mdlambda_E0.1, mdlambda_E10: pulloff --eta 0.1,1,10 --lambda 0.01:100:17, no solve cache)
# and of the whole `figures-only -j2` into fresh data, figure and cache folders, for two CLI
# binaries run alternately, pair by pair (the machine is shared: the pairs' ratios are the
# reliable numbers; the 1-minute load is printed with each run). Used for docs/speed.md,
# "Maugis-Dugdale table for the figures (mdtable37)".
# Usage: bench/md_figures_pairs.sh BEFORE_CLI AFTER_CLI [PAIRS]   (run from anywhere)
set -euo pipefail
before="$(realpath "${1:?usage: bench/md_figures_pairs.sh BEFORE_CLI AFTER_CLI [PAIRS]}")"
after="$(realpath "${2:?usage: bench/md_figures_pairs.sh BEFORE_CLI AFTER_CLI [PAIRS]}")"
pairs="${3:-3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
load() { cut -d' ' -f1 /proc/loadavg; }
printf 'task\tbuild\tcpu_s\twall_s\tload\n'
for ratio in 0.1 10; do
  for ((k = 0; k < pairs; ++k)); do
    for build in before after; do
      cli=$before; [ "$build" = after ] && cli=$after
      /usr/bin/time -f "%U %S %e" -o "$scratch/time" env OMP_WAIT_POLICY=PASSIVE "$cli" pulloff \
        --film "$ratio,0.25" --substrate 1,0.25 --eta 0.1,1,10 --lambda 0.01:100:17 > /dev/null
      read -r user sys wall < "$scratch/time"
      awk -v u="$user" -v s="$sys" -v w="$wall" -v t="mdlambda_E$ratio" -v b="$build" -v l="$(load)" \
        'BEGIN { printf "%s\t%s\t%.2f\t%.2f\t%s\n", t, b, u + s, w, l }'
    done
  done
done
for ((k = 0; k < pairs; ++k)); do
  for build in before after; do
    cli=$before; [ "$build" = after ] && cli=$after
    run="$scratch/run"
    rm -rf "$run"
    /usr/bin/time -f "%U %S %e" -o "$scratch/time" make -s -C "$root" -f gnuplot/figures.mk figures-only -j2 \
      CLI="$cli" DATA_DIR="$run/data" FIG_DIR="$run/fig" SOLVE_CACHE="$run/cache" > /dev/null 2>&1
    read -r user sys wall < "$scratch/time"
    awk -v u="$user" -v s="$sys" -v w="$wall" -v b="$build" -v l="$(load)" \
      'BEGIN { printf "make figures-only -j2, cold cache\t%s\t%.2f\t%.2f\t%s\n", b, u + s, w, l }'
  done
done
