#!/usr/bin/env bash
# --layer (THEORY.md section 12) on the command line: the issue's commands run; bad input
# (mixing --film and --layer, h <= 0, more than 1000 layers, a bad slip word, --thickness with
# --layer in an SI command) exits 2 naming the option, with nothing on stdout and no file.
# Usage: test_stack_cli.sh PATH/TO/coatcontact
set -u
cli="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0

stack=(--layer 1,10,0.3 --layer 2,1,0.45 --substrate 100,0.2)
good() {
  if ! timeout 300 "$cli" "$@" >"$work/out" 2>"$work/err"; then
    echo "FAIL: '$*' exits $?: $(head -c 300 "$work/err")"
    failures=$((failures + 1))
  fi
}
bad() {  # bad OPTION ARGS...: exit 2, OPTION named on stderr, no stdout, no output file
  local option="$1"
  shift
  rm -f "$work/file"
  timeout 120 "$cli" "$@" --output "$work/file" >"$work/out" 2>"$work/err"
  local rc=$?
  if [ "$rc" -ne 2 ] || ! grep -q -- "$option" "$work/err" || [ -s "$work/out" ] || [ -e "$work/file" ]; then
    echo "FAIL: '$*': exit $rc (want 2), stderr: $(head -c 300 "$work/err")"
    failures=$((failures + 1))
  fi
}

good kernel "${stack[@]}" --q 0.001:30:16
grep -q "total thickness T" "$work/out" && grep -q "reference modulus" "$work/out" &&
  grep -q "layer 2 (h, E" "$work/out" || { echo "FAIL: kernel header lacks the stack"; failures=$((failures + 1)); }
[ "$(grep -vc '^#' "$work/out")" -eq 16 ] || { echo "FAIL: kernel: not 16 rows"; failures=$((failures + 1)); }
good reduced "${stack[@]}" --a-over-t 0.1,1,10
good kernel --layer 1,1,0.5,slip --substrate rigid --q 0.5 --u 0.5
good sphere --radius 5um --layer 1um,1GPa,0.3 --layer 2um,100MPa,0.45,slip --substrate 10GPa,0.25 --work 50mJ/m2 --points 10 --tol 1e-6
grep -q "total thickness T" "$work/out" || { echo "FAIL: sphere header lacks T"; failures=$((failures + 1)); }

bad --layer kernel --film 1,0.3 "${stack[@]}" --q 1
bad --layer kernel --layer 0,1,0.3 --substrate 1,0.3 --q 1
bad --layer kernel --layer -1,1,0.3 --substrate 1,0.3 --q 1
bad --layer kernel --layer 1,1,0.3,glue --substrate 1,0.3 --q 1
bad --layer kernel --layer 1,1 --substrate 1,0.3 --q 1
bad --layer reduced --layer 1,-5,0.3 --layer 1,1,0.3 --substrate 1,0.3 --a-over-t 1
many=()
for _ in $(seq 1001); do many+=(--layer 1,1,0.3); done
bad --layer kernel "${many[@]}" --substrate 1,0.3 --q 1
bad --thickness sphere --radius 5um --thickness 1um --layer 1um,1GPa,0.3 --substrate 10GPa,0.25 --work 50mJ/m2
bad --film kernel --substrate 1,0.3 --q 1
# A top layer thinner than T/32 cannot have a kernel table: refused before any work.
bad --layer reduced --layer 0.03,10,0.3 --layer 1,1,0.45 --substrate 100,0.2 --a-over-t 1
bad --layer pulloff --layer 1,10,0.3 --layer 40,1,0.45 --substrate 100,0.2 --eta 1

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "stack CLI: all passed"
