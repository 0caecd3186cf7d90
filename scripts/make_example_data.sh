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
# Issue 15: an experiment-like a,F set, noise on both variables (0.3 % on a, 10 uN on F): a 2 mm
# sphere on a 20 um incompressible film on glass, a from 60 to 400 um (a/t 3-20).
"$generator" --kind a,F --radius 2mm --film 1MPa,0.5 --substrate 70GPa,0.22 --thickness 20um --work 50mJ/m2 \
  --noise 10uN --noise-x 0.3% --a-range 60um,400um --points 30 --seed 3 --output data/example_both_a_F.tsv
# A coating of two layers (a 20 um soft skin on a 30 um stiffer layer) on glass, for fits of a
# layer's thickness or modulus (--layer, --free w,h2).
"$generator" --kind a,F --radius 5mm --layer 20um,1MPa,0.49 --layer 30um,5MPa,0.45 --substrate 70GPa,0.22 \
  --work 40mJ/m2 --noise 10uN --points 40 --max-over-pulloff 1.5 --seed 3 --output data/example_layers_a_F.tsv
# JKR hysteresis: w = 20 mJ/m2 while loading, 60 mJ/m2 while unloading, with a branch column
# (1 loading, 0 unloading), for fits of w_load and w_unload.
"$generator" --kind a,F --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um --work 20mJ/m2 --work-unload 60mJ/m2 --branch-column yes \
  --noise 10uN --points 40 --max-over-pulloff 1.5 --seed 11 --output data/example_hysteresis_a_F.tsv
echo "wrote data/example_a_F.tsv, data/example_delta_F.tsv, data/example_both_a_F.tsv, data/example_layers_a_F.tsv and data/example_hysteresis_a_F.tsv"
