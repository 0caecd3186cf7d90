#!/usr/bin/env bash
# Regression (issue 40, item 2; label cli): with concurrent writers the cache grew ~10x per
# round (each process that found 8 files merged everything it had loaded, duplicates included,
# into a new file): 206 KB -> 6.6 GB -> out of memory. Now records are kept once on reading and
# merging, one process at a time merges (a lock file), and the size is capped
# (docs/solver.md, "Solve cache").
# ROUNDS rounds of 10 `reduced` processes started together on one cache and one stack: each
# asks the same SHARED radii and 3 radii of its own. Checked after every round:
#  - every row is byte for byte that of a run without a cache;
#  - the records on disk are at most the distinct radii asked so far plus 9 extra copies of
#    the shared ones (the first round's writers all solve them before any file exists), and
#    the folder holds at most 8 + 10 + 1 files;
#  - each kernel table the stack needs is on disk once (the writers that need it while one
#    builds it wait for it: no copies);
#  - no writer refuses the folder: one that examined the fresh DIR while another wrote the
#    cache's tag and first entries took it for another program's cache (exit 2) about once in
#    ten rounds once the table entries were made early (fixed in root_state).
# and at the end a warm run asking every radius solves nothing (writes no file). The runs take
# `--direct`: a row is then a function of its radius alone, the cache's unit (a sweep of many
# radii otherwise reads an interpolant whose nodes depend on the sweep's range).
# usage: test_cache_concurrent_writers_bounded.sh <coatcontact binary> [ROUNDS, default 4]
set -uo pipefail
cli=$1
rounds=${2:-4}
writers=10
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*"
  exit 1
}
cache="$tmp/cache"
# shellcheck disable=SC2054  # commas inside an option value
stack=(--film 0.1,0.25 --substrate 1,0.25)
shared="0.05,0.2,1,4,15"
shared_count=5
# The radii of writer w in round r: three of its own, never asked by another command.
own() { echo "0.3$1$2,0.5$1$2,2.7$1$2"; }

# Records in one cache file: the count after its two text lines (an unsigned 64-bit integer).
records_in() {
  local offset
  offset=$(head -n 2 "$1" | wc -c)
  od -A n -t u8 -j "$offset" -N 8 "$1" | tr -d ' '
}

distinct=$shared_count
for r in $(seq 1 "$rounds"); do
  # The reference: one run without a cache asking every radius of the round (a row depends on
  # its radius alone).
  round_radii=$shared
  for w in $(seq 0 $((writers - 1))); do round_radii="$round_radii,$(own "$r" "$w")"; done
  env -u COATCONTACT_CACHE "$cli" reduced --direct "${stack[@]}" --a-over-t "$round_radii" | grep -v '^#' \
    > "$tmp/reference.$r" || fail "reference run of round $r"
  pids=()
  for w in $(seq 0 $((writers - 1))); do
    env -u COATCONTACT_CACHE "$cli" --cache "$cache" reduced --direct "${stack[@]}" --a-over-t "$shared,$(own "$r" "$w")" \
      > "$tmp/out.$r.$w" 2> "$tmp/err.$r.$w" &
    pids+=($!)
  done
  for i in "${!pids[@]}"; do
    wait "${pids[$i]}" || fail "round $r, writer $i: exit $? ($(head -c 300 "$tmp/err.$r.$i"))"
  done
  for w in $(seq 0 $((writers - 1))); do
    [ "$(grep -c -v '^#' "$tmp/out.$r.$w")" -eq 8 ] || fail "round $r, writer $w: not 8 rows"
    differing=$(grep -v '^#' "$tmp/out.$r.$w" | grep -F -x -v -f "$tmp/reference.$r")
    [ -z "$differing" ] || fail "round $r, writer $w: rows differ from no cache: $differing"
  done
  distinct=$((distinct + 3 * writers))
  files=0
  records=0
  while IFS= read -r f; do
    files=$((files + 1))
    records=$((records + $(records_in "$f")))
  done < <(find "$cache" -path '*/solve-*' -name '*.bin')
  table_folders=$(find "$cache" -mindepth 2 -maxdepth 2 -type d -name 'table-*' | wc -l)
  table_files=$(find "$cache" -path '*/table-*' -name '*.bin' | wc -l)
  [ "$table_folders" -ge 1 ] && [ "$table_files" -eq "$table_folders" ] ||
    fail "round $r: $table_files kernel-table entries for $table_folders tables (one each expected)"
  bytes=$(find "$cache" -path '*/solve-*' -type f -printf '%s\n' | awk '{s += $1} END {print s + 0}')
  echo "round $r: $files files, $records records ($distinct distinct radii), $bytes bytes; $table_files kernel tables"
  allowed=$((distinct + (writers - 1) * shared_count))
  [ "$records" -le "$allowed" ] || fail "round $r: $records records on disk for $distinct distinct radii (allowed $allowed)"
  [ "$files" -le $((8 + writers + 1)) ] || fail "round $r: $files files in the cache"
done

echo "== a warm run asking every radius solves nothing"
all="$shared"
for r in $(seq 1 "$rounds"); do
  for w in $(seq 0 $((writers - 1))); do all="$all,$(own "$r" "$w")"; done
done
before=$(find "$cache" -name '*.bin' | sort)
env -u COATCONTACT_CACHE "$cli" --cache "$cache" reduced --direct "${stack[@]}" --a-over-t "$all" > "$tmp/warm" || fail "warm run"
env -u COATCONTACT_CACHE "$cli" reduced --direct "${stack[@]}" --a-over-t "$all" > "$tmp/cold" || fail "no-cache run"
cmp -s "$tmp/warm" "$tmp/cold" || fail "warm run: output differs from no cache"
[ "$before" = "$(find "$cache" -name '*.bin' | sort)" ] || fail "the warm run wrote entries: a radius was lost"
echo "the cache stayed bounded"
