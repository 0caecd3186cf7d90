#!/usr/bin/env bash
# The Speed table of docs/speed.md (moved there from the README) from a `make bench` results file (bench/run.sh): one row per task
# with its median, and the commit and machine the numbers come from.
# Usage: bench/readme_table.sh [build/bench/results.tsv]
set -euo pipefail
results="${1:-build/bench/results.tsv}"
awk -F'\t' '
  /^# commit:/  { commit = substr($0, 11) }
  /^# machine:/ { machine = substr($0, 12) }
  /^# date:/    { date = substr($0, 9) }
  /^#/ { next }
  NF >= 2 { rows[++n] = sprintf("| %s | %s | %s |", $1, $2, ($6 == "cli" ? "whole process" : $6 == "cli-cpu" ? "whole process, CPU (user + sys)" : "in process")) }
  END {
    printf "Medians from `make bench` (commit %s, %s, %s):\n\n", commit, machine, date
    print "| task | median [ms] | measured |"
    print "|---|---|---|"
    for (i = 1; i <= n; ++i) print rows[i]
  }' "$results"
