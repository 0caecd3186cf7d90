#!/usr/bin/env bash
# Runs every benchmark executable bench_* in BUILD_DIR/bench (configure with
# -DCOATCONTACT_BUILD_BENCH=ON). Usage: bench/run.sh BUILD_DIR [extra benchmark flags]
set -euo pipefail
build="${1:?usage: bench/run.sh BUILD_DIR}"
shift
found=0
for exe in "$build"/bench/bench_*; do
  [ -x "$exe" ] && [ -f "$exe" ] || continue
  found=1
  echo "== $(basename "$exe")"
  "$exe" "$@"
done
if [ "$found" -eq 0 ]; then
  echo "bench/run.sh: no bench_* executables in $build/bench (configure with -DCOATCONTACT_BUILD_BENCH=ON)" >&2
  exit 1
fi
