#!/usr/bin/env bash
# `--output` never leaves a partial file, also when the process is interrupted (issue 7, label
# cli): a long `pulloff` sweep writing to --output gets SIGINT (then SIGTERM) once its
# temporary file "out.tsv.tmp.*" exists; it must die by that signal and leave neither out.tsv
# nor a temporary file, and an out.tsv that existed before must be left untouched.
# Usage: test_output_interrupt.sh PATH/TO/coatcontact
set -u
cli="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# run_and_signal SIGNAL DIR: starts the sweep with DIR/out.tsv as output, waits (up to 60 s)
# for its temporary file, sends SIGNAL and prints "EXIT_STATUS SAW_TEMPORARY_FILE(0/1)".
# env --default-signal: a background job of a non-interactive shell starts with SIGINT
# ignored, and coatcontact (rightly) keeps an ignored signal ignored.
run_and_signal() {
  local signal="$1" dir="$2"
  env --default-signal=INT,TERM "$cli" pulloff --film 1GPa,0.3 --substrate 10GPa,0.25 \
    --eta 0.001:1000:400 --output "$dir/out.tsv" 2>"$dir/stderr" &
  local pid=$! i
  for ((i = 0; i < 6000; i++)); do
    compgen -G "$dir/out.tsv.tmp.*" >/dev/null && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.01
  done
  local saw=0
  compgen -G "$dir/out.tsv.tmp.*" >/dev/null && saw=1
  kill -s "$signal" "$pid" 2>/dev/null
  wait "$pid"
  echo "$? $saw"
}

for signal in INT TERM; do
  number=$(kill -l "$signal")
  want=$((128 + number))

  # 1. No file before: none after, no temporary file.
  dir="$work/fresh_$signal"
  mkdir -p "$dir"
  read -r status saw < <(run_and_signal "$signal" "$dir")
  [ "$saw" -eq 1 ] || fail "SIG$signal: no temporary file out.tsv.tmp.* appeared while the sweep ran"
  if [ "$status" -eq 0 ]; then
    fail "SIG$signal: the sweep finished before the signal arrived (make the workload larger)"
  elif [ "$status" -ne "$want" ]; then
    fail "SIG$signal: exit status $status, expected $want (killed by SIG$signal); stderr: $(head -c 300 "$dir/stderr")"
  fi
  [ -e "$dir/out.tsv" ] && fail "SIG$signal: a partial out.tsv was left"
  leftovers=$(ls -A "$dir" | grep -v '^stderr$')
  [ -n "$leftovers" ] && fail "SIG$signal: files left behind: $leftovers"
  echo "SIG$signal, no previous file: exit status $status (want $want), files after: ${leftovers:-none}"

  # 2. An existing out.tsv is left untouched (same bytes, same modification time).
  dir="$work/existing_$signal"
  mkdir -p "$dir"
  printf '# an earlier result\n1\t2\n' >"$dir/out.tsv"
  cp -p "$dir/out.tsv" "$work/reference_$signal.tsv"
  touch -d '2001-02-03 04:05:06' "$dir/out.tsv"
  before=$(stat -c '%Y %i' "$dir/out.tsv")
  read -r status saw < <(run_and_signal "$signal" "$dir")
  [ "$saw" -eq 1 ] || fail "SIG$signal (existing file): no temporary file appeared while the sweep ran"
  if [ "$status" -eq 0 ]; then
    fail "SIG$signal (existing file): the sweep finished before the signal arrived"
  elif [ "$status" -ne "$want" ]; then
    fail "SIG$signal (existing file): exit status $status, expected $want; stderr: $(head -c 300 "$dir/stderr")"
  fi
  cmp -s "$dir/out.tsv" "$work/reference_$signal.tsv" || fail "SIG$signal: the existing out.tsv was changed"
  [ "$(stat -c '%Y %i' "$dir/out.tsv")" = "$before" ] || fail "SIG$signal: the existing out.tsv was replaced"
  leftovers=$(ls -A "$dir" | grep -v -e '^stderr$' -e '^out.tsv$')
  [ -n "$leftovers" ] && fail "SIG$signal (existing file): files left behind: $leftovers"
  echo "SIG$signal, existing file: exit status $status, out.tsv unchanged, other files: ${leftovers:-none}"
done

# Control: the same sweep uninterrupted writes a complete out.tsv and nothing else, so the
# interrupted runs above really were cut short.
dir="$work/complete"
mkdir -p "$dir"
"$cli" pulloff --film 1GPa,0.3 --substrate 10GPa,0.25 --eta 0.001:1000:400 --output "$dir/out.tsv" \
  2>"$dir/stderr" || fail "the uninterrupted sweep failed: $(head -c 300 "$dir/stderr")"
rows=$(grep -vc '^#' "$dir/out.tsv" 2>/dev/null)
[ "${rows:-0}" -eq 400 ] || fail "the uninterrupted sweep wrote ${rows:-no} rows, expected 400"
[ "$(ls -A "$dir" | grep -v -e '^stderr$' -e '^out.tsv$')" = "" ] || fail "the uninterrupted sweep left other files"

if [ $failures -ne 0 ]; then
  echo "test_output_interrupt: $failures failure(s)"
  exit 1
fi
echo "test_output_interrupt: all checks passed"
