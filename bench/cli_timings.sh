#!/usr/bin/env bash
# Whole-process wall times of the CLI tasks that docs/speed.md quotes: median,
# min and max over RUNS runs (after one warm-up), as rows "task median min max runs cli".
# The two sweep targets of issue 26 (200 radii, pull-off over 100 eta) also get a CPU row
# (user + sys of the process, kind cli-cpu): the machine is shared, and wall time on a loaded
# machine says more about the load than about the code.
# Usage: bench/cli_timings.sh CLI [RUNS]
set -euo pipefail
cli="${1:?usage: bench/cli_timings.sh CLI [RUNS]}"
runs="${2:-7}"

time_task() {
  local task="$1"
  shift
  "$@" > /dev/null  # warm-up (page cache, FFTW)
  local times=()
  for ((i = 0; i < runs; i++)); do
    local start end
    start=$(date +%s%N)
    "$@" > /dev/null
    end=$(date +%s%N)
    times+=($(((end - start) / 1000)))
  done
  printf '%s\n' "${times[@]}" | sort -n | awk -v task="$task" -v n="$runs" '
    { t[NR] = $1 / 1000.0 }
    END { printf "%s\t%.4g\t%.4g\t%.4g\t%d\tcli\n", task, t[int((n + 1) / 2)], t[1], t[n], n }'
}

# time_task_cpu TASK ARGS...: as time_task, plus the row "TASK, CPU" of user + sys in ms.
time_task_cpu() {
  local task="$1"
  shift
  time_task "$task" "$@"
  local cpus=() TIMEFORMAT='%U %S'
  for ((i = 0; i < runs; i++)); do
    local t
    t=$( { time "$@" > /dev/null 2>&1; } 2>&1 )
    cpus+=($(awk -v t="$t" 'BEGIN { split(t, p, " "); printf "%d", (p[1] + p[2]) * 1e6 }'))
  done
  printf '%s\n' "${cpus[@]}" | sort -n | awk -v task="$task, CPU" -v n="$runs" '
    { t[NR] = $1 / 1000.0 }
    END { printf "%s\t%.4g\t%.4g\t%.4g\t%d\tcli-cpu\n", task, t[int((n + 1) / 2)], t[1], t[n], n }'
}

time_task "version (process start)" "$cli" --help
time_task "one radius (reduced, a/t = 1)" \
  "$cli" reduced --film 10,0.25 --substrate 1,0.25 --a-over-t 1
time_task_cpu "200 radii (reduced, a/t 1e-3..1e4)" \
  "$cli" reduced --film 10,0.25 --substrate 1,0.25 --a-over-t 0.001:10000:200
# the same radii each solved on its own (the path before the verified interpolant, issue 37)
time_task_cpu "200 radii (reduced --direct, a/t 1e-3..1e4)" \
  "$cli" reduced --film 10,0.25 --substrate 1,0.25 --a-over-t 0.001:10000:200 --direct
time_task_cpu "pulloff, 100 eta" \
  "$cli" pulloff --film 0.1,0.25 --substrate 1,0.25 --eta 0.01:100:100
# the same etas on the table of decades (the path before the pull-off sweep's table, issue 37)
time_task_cpu "pulloff --direct, 100 eta" \
  "$cli" pulloff --film 0.1,0.25 --substrate 1,0.25 --eta 0.01:100:100 --direct
time_task_cpu "pulloff, 1 eta" \
  "$cli" pulloff --film 0.1,0.25 --substrate 1,0.25 --eta 1

root="$(cd "$(dirname "$0")/.." && pwd)"
# fits with w and t free and no start values (global search included), 80 and 60 points
time_task "fit a,F, w,t free, no start (80 points, a/t to 5)" \
  "$cli" fit "$root/data/example_a_F.tsv" --columns a,F --radius 5mm --film 1MPa,0.49 \
  --substrate 70GPa,0.22 --free w,t
time_task "fit a,F, noise on a and F, w,t free, no start (60 points, a/t to 20)" \
  "$cli" fit "$root/data/example_both_a_F.tsv" --columns a,F --radius 2mm --film 1MPa,0.5 \
  --substrate 70GPa,0.22 --free w,t --sigma a=0.3%,F=10uN

# make figures from a built tree, into a fresh folder each run (3 runs: ~14 s each)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Maugis-Dugdale through the reduced table of the cohesive zone (THEORY.md section 13), its
# tiles built in each run: 33 pull-offs, and fit --model md on 12 points of the sphere command.
md_lambdas=$(awk 'BEGIN { for (k = 0; k < 33; k++) printf "%s%.6g", (k ? "," : ""), 10 ^ (-2 + 4 * k / 32) }')
time_task "pulloff --lambda, 33 values (MD table included)" \
  "$cli" pulloff --film 0.1,0.25 --substrate 1,0.25 --eta 1 --lambda "$md_lambdas"
md_glass=(--radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22 --thickness 20um)
"$cli" sphere "${md_glass[@]}" --work 50mJ/m2 --cohesive-stress 30kPa --output "$scratch/md.tsv" 2>/dev/null
grep -v '^#' "$scratch/md.tsv" | awk '$1 >= 1e-5 && $1 <= 1.5e-4' |
  awk '{ r[n++] = $0 } END { for (i = 0; i < 12; i++) { split(r[int(i * (n - 1) / 11 + 0.5)], f, "\t"); print f[1] "\t" f[3] } }' \
  > "$scratch/md_a_F.tsv"
time_task "fit --model md, w,lambda free (12 points, MD table included)" \
  "$cli" fit "$scratch/md_a_F.tsv" --columns a,F "${md_glass[@]}" --model md --free w,lambda --sigma F=2uN
# The Maugis-Dugdale AFM retract fit on a real curve (issue 37 item 2: no direct work per trial),
# beside the JKR fit of the same curve: a half-space, and a film on a rigid base with E1 free.
afm_data="$root/../shared/data/afm"
[ -d "$afm_data" ] || afm_data=/work/shared/data/afm
gel="$afm_data/fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force"
if [ -f "$gel" ]; then
  for model in md jkr; do
    time_task_cpu "afm fit --model $model, half-space (pr14 polymer gel, real curve)" \
      "$cli" afm fit "$gel" --model "$model" --radius 10um --halfspace 1kPa,0.5 --output "$scratch/afm.tsv"
  done
  time_task_cpu "afm fit --model md, film on a rigid base, E1 free (pr14 polymer gel)" \
    "$cli" afm fit "$gel" --model md --radius 10um --film 10kPa,0.5 --substrate rigid --thickness 2um \
    --output "$scratch/afm.tsv"
fi
# make figures from a built tree, 2 jobs as the default runs: without the solve cache, with a
# cold one (emptied before each run) and a warm one (filled by the warm-up run); the CPU rows
# (all processes) say more than wall time on a shared machine.
figures() {  # figures <cache mode: none | cold | warm>
  rm -rf "$scratch/d" "$scratch/f"
  [ "$1" = cold ] && rm -rf "$scratch/cache"
  make -s -C "$root" -f gnuplot/figures.mk figures-only -j2 CLI="$(realpath "$cli")" \
    DATA_DIR="$scratch/d" FIG_DIR="$scratch/f" $([ "$1" = none ] || echo "SOLVE_CACHE=$scratch/cache") \
    > /dev/null 2>&1
}
runs=3 time_task_cpu "make figures (all data and plots, 2 jobs, no cache)" figures none
runs=3 time_task_cpu "make figures (2 jobs, cold solve cache)" figures cold
runs=3 time_task_cpu "make figures (2 jobs, warm solve cache)" figures warm
# `make figures` with nothing to do: the fixed part of every run (the Debian package check, the
# CLI's build check, the parameter stamps, the pull-off table), on the warm run's files.
build_dir=$(dirname "$(dirname "$(realpath "$cli")")")
if [ -f "$build_dir/CMakeCache.txt" ]; then
  figures_noop() {
    make -s -C "$root" figures BUILD="$build_dir" DATA_DIR="$scratch/d" FIG_DIR="$scratch/f" \
      SOLVE_CACHE="$scratch/cache" > /dev/null 2>&1
  }
  runs=5 time_task_cpu "make figures, nothing to do (2 jobs)" figures_noop
fi
