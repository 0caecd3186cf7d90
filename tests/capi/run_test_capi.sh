#!/bin/sh
# Runs the C API test with the soft film's E_eq at a/t = 1 as printed by the C++ solver
# behind `coatcontact reduced` (round-trip digits), so the two are compared bit for bit.
set -eu
test_capi="$1"
cli="$2"
e_eq=$("$cli" reduced --film 0.1,0.25 --substrate 1,0.25 --a-over-t 1 | awk -F'\t' '!/^#/ { print $6 }')
[ -n "$e_eq" ] || { echo "FAIL no E_eq from $cli"; exit 1; }
exec "$test_capi" "$e_eq"
