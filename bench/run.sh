#!/usr/bin/env bash
# `make bench`: every bench_* executable in BUILD_DIR/bench (configure with
# -DCOATCONTACT_BUILD_BENCH=ON), then whole-process timings of the CLI (bench/cli_timings.sh),
# the batch AFM fits of synthetic force maps (bench/afm_maps.sh; the Maugis-Dugdale maps:
# bench/md_map.sh), the explorer's slider
# updates (bench/explore_sliders.py) and afm.fit_map threaded and on a Dask LocalCluster
# (bench/dask_map.py).
# Results: BUILD_DIR/bench/results.tsv (one row per task: median, min, max over the runs, with
# the machine and the commit) and BUILD_DIR/bench/<name>.json (the benchmark library's own
# report, medians of 5 repetitions). Usage: bench/run.sh BUILD_DIR [extra benchmark flags]
set -euo pipefail
build="${1:?usage: bench/run.sh BUILD_DIR}"
shift
out="$build/bench"
mkdir -p "$out"
results="$out/results.tsv"
tmp="$results.tmp.$$"
trap 'rm -f "$tmp"' EXIT

commit=$(git -C "$(dirname "$0")/.." describe --always --dirty 2>/dev/null || echo unknown)
cpu=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //' || echo unknown)
{
  echo "# coatcontact benchmarks (make bench)"
  echo "# commit: $commit"
  echo "# machine: $(nproc) cores, $cpu"
  echo "# date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "# columns: task	median_ms	min_ms	max_ms	runs	kind"
} > "$tmp"

found=0
for exe in "$build"/bench/bench_*; do
  [ -x "$exe" ] && [ -f "$exe" ] || continue
  found=1
  name=$(basename "$exe")
  echo "== $name"
  "$exe" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_out="$out/$name.json" --benchmark_out_format=json "$@"
  # median rows of the library's report, in ms of real time
  python3 - "$out/$name.json" >> "$tmp" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
unit = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
rows = {}
for b in report["benchmarks"]:
    if b.get("run_type") != "aggregate":
        continue
    name = b["run_name"]
    rows.setdefault(name, {})[b["aggregate_name"]] = b["real_time"] * unit[b["time_unit"]]
    rows[name]["runs"] = b.get("repetitions", 0)
    # Benchmarks that measure the process's CPU time (all threads) get a second row with it.
    if "process_time" in name:
        rows[name].setdefault("cpu", {})[b["aggregate_name"]] = b["cpu_time"] * unit[b["time_unit"]]
for name, r in rows.items():
    print(f"{name}\t{r.get('median', 0):.4g}\t\t\t{r['runs']}\tlibrary")
    if "cpu" in r:
        print(f"{name} (CPU)\t{r['cpu'].get('median', 0):.4g}\t\t\t{r['runs']}\tlibrary-cpu")
PY
done
if [ "$found" -eq 0 ]; then
  echo "bench/run.sh: no bench_* executables in $build/bench (configure with -DCOATCONTACT_BUILD_BENCH=ON)" >&2
  exit 1
fi

echo "== CLI, whole process"
bash "$(dirname "$0")/cli_timings.sh" "$build/bin/coatcontact" >> "$tmp"

echo "== afm fit over synthetic force maps (time, scaling, peak RSS)"
scratch_maps=$(mktemp -d)
bash "$(dirname "$0")/afm_maps.sh" "$build/bin/coatcontact" "$build/tests/afm/make_afm_map" "$scratch_maps" \
  "$build/bench/zip_open_rss" >> "$tmp"
rm -rf "$scratch_maps"

echo "== afm fit --model md over synthetic force maps (first curve, further curves, --jobs 1 and 2)"
scratch_md=$(mktemp -d)
bash "$(dirname "$0")/md_map.sh" "$build/bin/coatcontact" "$build/tests/afm/make_afm_map" "$scratch_md" >> "$tmp"
rm -rf "$scratch_md"

# The interpreter the Python module was built for.
python=$(sed -n 's/^Python3_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt" 2>/dev/null)
python="${python:-python3}"
if [ -d "$build/python/coatcontact" ] && "$python" -c "import matplotlib, numpy" 2>/dev/null; then
  echo "== Python explorer, slider updates"
  PYTHONPATH="$build/python" "$python" "$(dirname "$0")/explore_sliders.py" --tsv >> "$tmp"
else
  echo "bench/run.sh: no Python module in $build/python or no matplotlib: explorer timings left out" >&2
fi
if [ -d "$build/python/coatcontact" ] && "$python" -c "import distributed, numpy" 2>/dev/null; then
  echo "== Python afm.fit_map: jobs=1, jobs=2 and a Dask LocalCluster of 2 workers"
  PYTHONPATH="$build/python" "$python" "$(dirname "$0")/dask_map.py" "$build/tests/afm/make_afm_map" --tsv >> "$tmp"
else
  echo "bench/run.sh: no Python module in $build/python or no python3-distributed: Dask timings left out" >&2
fi
mv "$tmp" "$results"
trap - EXIT
echo "wrote $results"
cat "$results"
