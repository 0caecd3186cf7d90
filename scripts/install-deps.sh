#!/usr/bin/env bash
# Installs the Debian packages coatcontact needs, only those that are missing.
# Uses apt-get, through sudo when not root. Does nothing when all are present.
set -euo pipefail

packages=(
  gfortran g++ cmake make pkg-config
  libgsl-dev liblapack-dev liblapacke-dev libblas-dev libfftw3-dev
  gnuplot-nox python3
  # the journal figures' test renders and reads the PDFs (pdftoppm, pdftotext)
  poppler-utils
  # the AFM readers (JPK archives, zipped AFM Workshop maps)
  libzip-dev
  # the NanoSuite .xls indentation reader (legacy Excel)
  libfreexl-dev
  # the Python package and its tests (python/, examples/python/)
  python3-dev python3-numpy pybind11-dev python3-pytest python3-matplotlib
  # the notebooks (examples/notebooks/, run headless by nbclient) and the explorer's Jupyter
  # widget (python -m coatcontact.explore; its window needs a GUI backend such as python3-tk)
  python3-nbclient python3-ipykernel python3-ipywidgets
  # coatcontact.afm.fit_map(..., client=) on a Dask cluster and its test (a LocalCluster)
  python3-distributed
)
# Optional extras for `make bench` and `make fuzz`; installed when asked for.
if [ "${COATCONTACT_EXTRAS:-0}" = 1 ]; then
  packages+=(libbenchmark-dev clang libclang-rt-14-dev)
fi

# One dpkg-query for all packages (`make figures` runs this check every time: one query per
# package cost ~0.2 s); a package that is unknown, removed or half-installed is missing.
declare -A installed=()
while read -r status name; do
  if [ "$status" = installed ]; then installed[$name]=1; fi
done < <(dpkg-query -W -f='${db:Status-Status} ${Package}\n' "${packages[@]}" 2>/dev/null || true)
missing=()
for p in "${packages[@]}"; do
  [ -n "${installed[$p]:-}" ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing missing Debian packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
