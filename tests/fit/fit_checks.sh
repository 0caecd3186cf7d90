# Shared checks of the fit's shell tests (sourced): a scratch folder, failure counting, exit
# status and message checks, the 3-standard-error recovery test, and the final verdict.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok   $*"; }
# expect NAME CODE PATTERN -- COMMAND...: COMMAND exits CODE and its stderr matches PATTERN
# (an extended regular expression; empty: not checked).
expect() {
  local name=$1 code=$2 pattern=$3
  shift 4
  "$@" >"$work/out" 2>"$work/err"
  local got=$?
  if [[ $got -ne $code ]]; then
    fail "$name: exit $got, expected $code; stderr: $(cat "$work/err")"
  elif [[ -n $pattern ]] && ! grep -Eq -- "$pattern" "$work/err"; then
    fail "$name: stderr does not match /$pattern/: $(cat "$work/err")"
  else
    ok "$name (exit $got${pattern:+, message: $(head -c 200 "$work/err")})"
  fi
}
# within3 NAME ESTIMATE ERROR TRUTH: |estimate - truth| < 3 error, error > 0.
within3() {
  awk -v e="$2" -v s="$3" -v t="$4" 'BEGIN { d = e - t; if (d < 0) d = -d; exit !(s > 0 && d < 3 * s) }' \
    && ok "$1 = $2 +- $3 (truth $4)" || fail "$1 = $2 +- $3, truth $4: not within 3 standard errors"
}
# Header values of a fit table (keys as written: "w [J/m2]", "pull-off force, load control [N]"):
# header_value FILE KEY (the whole value), estimate FILE KEY (its first number), stderr_of FILE
# KEY (the number after "+-"; empty for a fixed parameter).
header_value() { awk -v k="# $2: " 'index($0, k) == 1 { print substr($0, length(k) + 1); exit }' "$1"; }
estimate() { header_value "$1" "$2" | awk '{ print $1 }'; }
stderr_of() { header_value "$1" "$2" | sed -n 's/.* +- \([^ ]*\).*/\1/p'; }
# finish: the verdict; a non-zero exit status when any check failed.
finish() {
  if [[ $failures -ne 0 ]]; then
    echo "FAIL ($failures failures)"
    exit 1
  fi
  echo "PASS"
}
