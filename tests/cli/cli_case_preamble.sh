# Shared start of the one-case-per-defect CLI scripts (sourced; label cli). Arguments of the
# sourcing script: PATH/TO/coatcontact DATA_DIR CASE. Sets cli, data, case_name, FIT; makes a
# temporary folder of the case's own and enters it; defines fail/ok, run, expect_error and the
# end of the script (unknown_case, finish_cases).
# CLI_TIMEOUT (seconds) bounds one run of the program.
set -u
cli="$1"
data="$2"
case_name="$3"
work="$(mktemp -d)"
cleanup() {
  chattr -i "$work"/* 2>/dev/null  # a case may make a file immutable; rm needs it back
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok   $*"; }

# run EXPECTED_EXIT ARGS...: runs the program (stdout -> out, stderr -> err), checks the exit.
run() {
  local want="$1"
  shift
  timeout "${CLI_TIMEOUT:-200}" "$cli" "$@" >out 2>err
  local rc=$?
  if [ "$rc" -ne "$want" ]; then
    fail "exit $rc (expected $want): coatcontact $(echo "$*" | cut -c1-200); stderr: $(head -c 400 err)"
    return 1
  fi
  return 0
}
# expect_error TEXT ARGS...: exit 2, stderr contains TEXT (an option's name or a phrase of the
# message), nothing on stdout.
expect_error() {
  local text="$1"
  shift
  run 2 "$@" || return 1
  if ! grep -q -F -- "$text" err; then
    fail "stderr does not say '$text': $(head -c 400 err)"
    return 1
  elif [ -s out ]; then
    fail "stdout not empty for coatcontact $*"
    return 1
  fi
  ok "$text: $(head -n 1 err | cut -c1-160)"
}

FIT=(--columns a,F --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um)

# The end of a case script: `*) unknown_case ;;` in its case statement, then finish_cases.
unknown_case() {
  echo "unknown case $case_name"
  exit 1
}
finish_cases() {
  if [ "$failures" -gt 0 ]; then
    echo "$failures failure(s)"
    exit 1
  fi
  echo "all passed"
}
