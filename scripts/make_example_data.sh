#!/usr/bin/env bash
# Regenerates the synthetic example data sets data/example_a_F.tsv and data/example_delta_F.tsv
# (described in data/README.md) with the make_synthetic_data tool built from tools/.
# Usage: scripts/make_example_data.sh [BUILD_DIR]   (default build; run `make build` first)
# Runs from the repository's top folder so that the command each file records is
# repository-relative (--output data/...), not a path of this machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
generator=$build/bin/make_synthetic_data
if [[ ! -x $generator ]]; then
  echo "make_example_data.sh: $generator not found (build the make_synthetic_data target first)" >&2
  exit 2
fi
cd "$root"
# PDMS-like soft film on glass; the truth the tests (tests/fit) check the fits against.
truth=(--radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um --work 40mJ/m2)
# 40 loading + 40 unloading rows, Gaussian force noise of 10 uN, fixed seeds.
"$generator" --kind a,F "${truth[@]}" --noise 10uN --points 40 --max-over-pulloff 1.5 --seed 1 --output data/example_a_F.tsv
"$generator" --kind delta,F "${truth[@]}" --noise 10uN --points 40 --max-over-pulloff 1.5 --seed 2 --output data/example_delta_F.tsv
echo "wrote data/example_a_F.tsv and data/example_delta_F.tsv"
