#!/usr/bin/env bash
# Regression tests of issue 25 item 6 (label cli): `reduced`, `adhesive`, `contact`, `sphere`
# (its --contact-radius list) and `pulloff` (its --eta list) used to fail the whole array (exit 3, or 2 from a probe, no output)
# when one point could not meet its tolerance. Each case forces one point to fail honestly (a tolerance the solver cannot meet
# at the largest radius: the rounding term eps cond(A) or the kernel table's accuracy exceeds
# it there, THEORY.md section 6) and checks: exit 0, the failed point as a '# not delivered'
# row in its place with its reason, the count in the header and on stderr, no NaN, every
# delivered row equal to the row of a call with that point alone; --strict keeps the whole
# run's failure (exit 3, or 2 where a probe refuses first) and no output; a run where no point
# can be delivered is exit 3.
# Usage: test_points_not_delivered.sh PATH/TO/coatcontact CASE
set -u
cli="$1"
case_name="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok   $*"; }

# run EXPECTED_EXIT OUT ARGS...: stdout -> OUT, stderr -> OUT.err.
run() {
  local want="$1" out="$2"
  shift 2
  timeout 250 "$cli" "$@" >"$out" 2>"$out.err"
  local rc=$?
  if [ "$rc" -ne "$want" ]; then
    fail "exit $rc (expected $want): coatcontact $*; stderr: $(head -c 300 "$out.err")"
    return 1
  fi
  return 0
}
data_rows() { grep -v '^#' "$1" | grep -v '^$'; }

# tolerant_checks OUT DELIVERED FAILED WHERE: the common checks of a run with one failed point.
tolerant_checks() {
  local out="$1" delivered="$2" failed="$3" where="$4"
  local total=$((delivered + failed))
  [ "$(data_rows "$out" | wc -l)" -eq "$delivered" ] && ok "$delivered rows delivered" ||
    fail "rows: $(data_rows "$out" | wc -l), expected $delivered"
  grep -q "^# not delivered: $where: " "$out" && ok "flagged row: $(grep '^# not delivered' "$out" | cut -c1-140)" ||
    fail "no '# not delivered: $where' row: $(grep '^#' "$out" | tail -3)"
  grep -q "^# points not delivered: $failed of $total " "$out" && ok "header counts $failed of $total" ||
    fail "header count missing: $(grep 'not delivered' "$out" | head -2)"
  grep -q "warning: $failed of $total points not delivered" "$out.err" && ok "stderr says so" ||
    fail "stderr: $(head -c 300 "$out.err")"
  grep -qi 'nan' <(data_rows "$out") && fail "a NaN was printed" || ok "no NaN printed"
}

# strict_checks EXIT ARGS...: --strict fails the whole run as before, with no output: exit 3,
# or 2 where the table's probe refuses an unreachable end of the range before any work.
strict_checks() {
  local want="$1"
  shift
  run "$want" strict "$@" --strict || return
  [ -s strict ] && fail "--strict wrote output" || ok "--strict: exit $want, no output ($(head -c 120 strict.err))"
}

case "$case_name" in
reduced)
  # PDMS on glass at tol 1e-12: a/t = 100 has eps cond(A) = 1.1e-12 (rounding alone above tol).
  M=(reduced --film 1MPa,0.49 --substrate 70GPa,0.22 --tol 1e-12)
  run 0 all "${M[@]}" --a-over-t 1,100,10 && tolerant_checks all 2 1 "a_over_t = 100"
  # In place: the flagged row sits between the rows of a/t = 1 and 10.
  order="$(grep -E '^([0-9]|# not delivered)' all | cut -f1 | cut -c1-15 | tr '\n' '|')"
  [ "$order" = "1|# not delivered|10|" ] && ok "row order kept: $order" || fail "row order: $order"
  for a in 1 10; do
    run 0 one "${M[@]}" --a-over-t "$a" &&
      { [ "$(data_rows one)" = "$(data_rows all | awk -v a="$a" '$1 == a')" ] && ok "a/t = $a equals its single-point call" ||
        fail "a/t = $a differs: $(data_rows one) vs $(data_rows all | awk -v a="$a" '$1 == a')"; }
  done
  strict_checks 3 "${M[@]}" --a-over-t 1,100,10
  run 3 none "${M[@]}" --a-over-t 100,1000 && { [ -s none ] && fail "output with no point delivered" ||
    ok "no point delivered: exit 3 ($(head -c 120 none.err))"; }
  ;;
adhesive)
  # The table's decade 10 <= a/t < 100 cannot be built at 1e-12 (its node at a/t = 99.8 fails).
  M=(adhesive --film 1MPa,0.49 --substrate 70GPa,0.22 --eta 0.01 --tol 1e-12)
  run 0 all "${M[@]}" --a-bar 0.01,0.5,0.02 && tolerant_checks all 2 1 "eta = 0.01, a_bar = 0.5"
  run 0 one "${M[@]}" --a-bar 0.01,0.02 &&
    { [ "$(data_rows one)" = "$(data_rows all)" ] && ok "delivered rows equal the call without the failed point" ||
      fail "rows differ: $(data_rows one) vs $(data_rows all)"; }
  strict_checks 2 "${M[@]}" --a-bar 0.01,0.5,0.02
  ;;
contact)
  # At tol 1e-10 the shape solve of a/t = 2000 misses (2.9e-10); the pull-off scan reaches
  # a/t = 1497, which misses too: the header says the pull-off was not computed.
  M=(contact --shape sphere:5mm --thickness 1um --film 1MPa,0.49 --substrate 70GPa,0.22 --work 50mJ/m2 --tol 1e-10)
  run 0 all "${M[@]}" --contact-radius 1um,2mm,10um && tolerant_checks all 2 1 "a_m = 0.002"
  grep -q '^# pull-off: not computed' all && grep -q 'pull-off not computed' all.err && ok "pull-off left out, said so" ||
    fail "pull-off note missing: $(grep 'pull-off' all | head -2)"
  run 0 one "${M[@]}" --contact-radius 10um &&
    { [ "$(data_rows one)" = "$(data_rows all | tail -n 1)" ] && ok "a = 10um equals its single-point call" ||
      fail "a = 10um differs: $(data_rows one) vs $(data_rows all | tail -n 1)"; }
  strict_checks 3 "${M[@]}" --contact-radius 1um,2mm,10um
  ;;
pulloff)
  # At 1e-12 the table stops at a/t = 10 (its node at a/t = 99.8 fails): eta = 1 finds its
  # minima below, eta = 0.001 (a_bar = a/t eta) has none below a_bar = 0.01.
  M=(pulloff --film 1MPa,0.49 --substrate 70GPa,0.22 --tol 1e-12)
  run 0 all "${M[@]}" --eta 1,0.001 && tolerant_checks all 1 1 "eta = 0.001"
  run 0 one "${M[@]}" --eta 1 &&
    { [ "$(data_rows one)" = "$(data_rows all)" ] && ok "eta = 1 equals its single-eta call" ||
      fail "eta = 1 differs: $(data_rows one) vs $(data_rows all)"; }
  strict_checks 2 "${M[@]}" --eta 1,0.001
  run 3 none "${M[@]}" --eta 0.001,0.002 && { [ -s none ] && fail "output with no eta delivered" ||
    ok "no eta delivered: exit 3 ($(head -c 120 none.err))"; }
  ;;
sphere)
  # As contact's case: at tol 1e-10 a = 2 mm (a/t = 2000) misses (2.9e-10); the table's decade
  # cannot be built either, so the radii are solved alone and that one is not delivered.
  M=(sphere --radius 5mm --thickness 1um --film 1MPa,0.49 --substrate 70GPa,0.22 --work 50mJ/m2 --tol 1e-10)
  run 0 all "${M[@]}" --contact-radius 1um,2mm,10um && tolerant_checks all 2 1 "a_m = 0.002"
  order="$(grep -E '^([0-9]|# not delivered)' all | cut -f1 | cut -c1-15 | tr '\n' '|')"
  [ "$order" = "9.9999999999999|# not delivered|1.0000000000000|" ] && ok "row order kept" || fail "row order: $order"
  # Without the failing radius the table serves 1 um and 10 um: the same force and penetration
  # within 1e-9 relative (both within the tolerance 1e-10 of the exact reduced variables; the
  # table interpolates them, the solve-alone path does not).
  run 0 one "${M[@]}" --contact-radius 1um,10um &&
    { paste <(data_rows one) <(data_rows all) | awk -F'\t' '{ for (c = 1; c <= 3; c++) { d = $c - $(c + 3); if (d < 0) d = -d;
        m = $c < 0 ? -$c : $c; if (d > 1e-9 * m) bad++ } } END { exit bad > 0 || NR != 2 }' &&
      ok "delivered rows agree with the call without the failed radius (1e-9 relative)" ||
      fail "rows differ: $(data_rows one) vs $(data_rows all)"; }
  strict_checks 2 "${M[@]}" --contact-radius 1um,2mm,10um
  ;;
*)
  echo "unknown case $case_name"
  exit 1
  ;;
esac

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all passed"
