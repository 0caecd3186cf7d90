#!/bin/sh
# Runs the kinetics C API test with the CLI's pull-off, loss of contact and state count for the
# README's run (sphere) and a 70-degree cone on the same stack (header digits round-trip), so the
# C API and the C++ library behind `coatcontact kinetics` are compared.
set -eu
test_capi="$1"
cli="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=""
for shape in sphere:2mm cone:70deg; do
  "$cli" kinetics --film 1e6,0.49 --substrate 70e9,0.22 --shape "$shape" --thickness 50um --work 0.04 \
    --v-star 1um/s --n 0.6 --spring 500 --protocol approach:1um/s:1mN,dwell:1s,retract:10um/s --output "$tmp/run.tsv"
  value() { sed -n "s|^# $1: ||p" "$tmp/run.tsv"; }
  f=$(value 'pull-off (most tensile force of the last retract) \[N\]')
  t=$(value 'pull-off time \[s\]')
  a=$(value 'pull-off contact radius \[m\]')
  tl=$(value 'loss of contact time \[s\]')
  n=$(grep -vc '^#' "$tmp/run.tsv")
  [ -n "$f" ] && [ -n "$t" ] && [ -n "$a" ] && [ -n "$tl" ] || { echo "FAIL header values of $shape"; exit 1; }
  args="$args $f $t $a $tl $n"
done
exec "$test_capi" $args
