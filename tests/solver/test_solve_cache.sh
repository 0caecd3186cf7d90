#!/usr/bin/env bash
# Solve cache (docs/solver.md, "Solve cache"; label cli): outputs of `reduced`, `pulloff` and
# `adhesive`, and of the Maugis-Dugdale table's `pulloff --lambda` and `adhesive --lambda`,
# byte-identical with no cache, a cold cache (COATCONTACT_CACHE) and a warm one
# (--cache DIR); a warm run solves nothing new (writes no entry); a corrupted entry is
# removed and solved again with the same outputs; an entry under another stack's key is
# ignored; another build's folder is removed; --cache without a directory is exit 2.
# usage: test_solve_cache.sh <coatcontact binary>
set -euo pipefail
cli=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cache="$tmp/cache"

film=(--film 0.1,0.25 --substrate 1,0.25)
other=(--film 10,0.3 --substrate 1,0.25)
commands=(
  "reduced ${film[*]} --a-over-t 0.05:20:9"
  "pulloff ${film[*]} --eta 0.3,1,3"
  "adhesive ${film[*]} --eta 1 --a-bar 0.05:2:7"
  "pulloff ${other[*]} --eta 1"
  "pulloff ${film[*]} --eta 1 --lambda 0.1,1"
  "adhesive ${film[*]} --eta 1 --lambda 0.3 --a-bar 0.05:2:5"
)
# run <label> <cache mode: none | env | option>: every command's stdout into $tmp/<label>.<i>
run() {
  local i=0
  for c in "${commands[@]}"; do
    # shellcheck disable=SC2086
    case $2 in
      none) env -u COATCONTACT_CACHE "$cli" $c > "$tmp/$1.$i" ;;
      env) COATCONTACT_CACHE="$cache" "$cli" $c > "$tmp/$1.$i" ;;
      option) env -u COATCONTACT_CACHE "$cli" --cache "$cache" $c > "$tmp/$1.$i" ;;
    esac
    i=$((i + 1))
  done
}
same() {  # <label a> <label b>: every output byte for byte
  local i
  for i in $(seq 0 $((${#commands[@]} - 1))); do
    cmp -s "$tmp/$1.$i" "$tmp/$2.$i" || fail "'${commands[$i]}': $2 output differs from $1"
  done
}
entries() { find "$cache" -type f -name '*.bin' | sort; }

echo "== no cache, cold cache, warm cache"
mkdir -p "$cache/0000000000000000/solve-0000000000000000"  # a folder of another build
run none none
run cold env
[ -n "$(entries)" ] || fail "the cold run wrote no cache entry"
[ ! -e "$cache/0000000000000000" ] || fail "another build's folder was not removed"
folders=$(find "$cache" -mindepth 2 -maxdepth 2 -type d -name 'solve-*' | wc -l)
[ "$folders" -eq 2 ] || fail "expected one folder per stack (2), found $folders"
zones=$(find "$cache" -mindepth 2 -maxdepth 2 -type d -name 'zone-*' | wc -l)
[ "$zones" -eq 1 ] || fail "expected one cohesive-zone table folder (the film's), found $zones"
before=$(entries)
run warm option
[ "$before" = "$(entries)" ] || fail "the warm run wrote entries: it solved radii the cache held"
same none cold
same none warm

echo "== corrupted entry: removed, solved again, same outputs"
victim=$(entries | head -n 1)
size=$(stat -c %s "$victim")
printf '\x01' | dd of="$victim" bs=1 seek=$((size / 2)) conv=notrunc status=none
cmp -s "$victim" <(printf '') && fail "corruption did not change the file"
run corrupt env
[ ! -e "$victim" ] || fail "the corrupted entry $victim is still there"
[ "$(entries | wc -l)" -ge 2 ] || fail "no entry written after the corrupted one was removed"
same none corrupt

echo "== truncated entry and an entry of another stack's key"
stack_dirs=($(find "$cache" -mindepth 2 -maxdepth 2 -type d -name 'solve-*' | sort))
# The second stack's own entries replaced by the first's: they hold the same radii (the table's
# nodes do not depend on the stack) with other values, so using them would change the outputs.
rm -f "${stack_dirs[1]}"/*.bin
for f in "${stack_dirs[0]}"/*.bin; do cp "$f" "${stack_dirs[1]}/foreign-$(basename "$f")"; done
victim=$(find "${stack_dirs[0]}" -name '*.bin' | head -n 1)
truncate -s 40 "$victim"
run mixed env
same none mixed
[ ! -e "$victim" ] || fail "the truncated entry $victim is still there"
[ -n "$(find "${stack_dirs[1]}" -name 'foreign-*')" ] || fail "an entry of another key was removed"

echo "== bad usage"
set +e
"$cli" --cache > "$tmp/usage.out" 2> "$tmp/usage.err"
code=$?
set -e
[ "$code" -eq 2 ] || fail "--cache without a directory: exit $code, expected 2"
grep -q -- '--cache' "$tmp/usage.err" || fail "--cache without a directory: message does not name the option"
[ ! -s "$tmp/usage.out" ] || fail "--cache without a directory wrote to stdout"
echo "all solve-cache checks passed"
