#!/bin/bash
# Issue 39 (ready for a paper and a lecture) and issue 40's kinetics items: one case per defect.
# Each case runs the command as a newcomer would and checks what it must say or write.
# shellcheck source=cli_case_preamble.sh
. "$(dirname "$0")/cli_case_preamble.sh"

MAT=(--film 1MPa,0.49 --substrate 70GPa,0.22)
KIN=(kinetics "${MAT[@]}" --radius 2mm --thickness 50um --work 40mJ/m2 --v-star 1um/s --n 0.6)
PROTOCOL=approach:1um/s:1mN,dwell:1s,retract:10um/s
# Value of a "# key: value" header line of file $1 whose key starts with $2.
header() { grep -m1 -F "# $2" "$1" | sed 's/^[^:]*: //'; }
# The rows (non-comment lines) of file $1.
rows() { grep -vc '^#' "$1"; }
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

case "$case_name" in
kinetics_spring_inf_displacement_control)
  # --help documents inf as displacement control: it must run, say so, and print no inf.
  if run 0 "${KIN[@]}" --spring inf --protocol "$PROTOCOL"; then
    grep -q '^# k_bar.*inf (displacement control)' out && ok "k_bar: $(header out 'k_bar')" || fail "no k_bar line"
    grep -q '^# drive: displacement control' out && ok "drive: displacement control" || fail "drive not named"
    [ "$(rows out)" -gt 10 ] && ok "$(rows out) rows" || fail "only $(rows out) rows"
    grep -v '^#' out | grep -qi 'nan\|inf' && fail "a row holds nan/inf" || ok "no nan/inf in the rows"
    # Displacement control is the stiff-spring limit: a 1e9 N/m spring gives the same pull-off.
    pulloff_inf=$(header out 'pull-off (most tensile')
    run 0 "${KIN[@]}" --spring 1e9 --protocol "$PROTOCOL" &&
      awk -v a="$pulloff_inf" -v b="$(header out 'pull-off (most tensile')" \
        'BEGIN { d = (a - b) / b; exit !(d < 1e-3 && d > -1e-3) }' &&
      ok "pull-off $pulloff_inf N as with k = 1e9 N/m" || fail "pull-off with inf ($pulloff_inf) differs from k = 1e9"
  fi
  ;;
bare_numbers_noted)
  # Bare numbers are SI: a modulus of 1 Pa, 20 m thick, radius 2 m, w = 40 J/m2 run, with a
  # note naming the unit the user likely meant (stderr and the header).
  if run 0 sphere --radius 2 --thickness 20 --film 1,0.49 --substrate 70e9,0.22 --work 40 --points 5; then
    for want in "--film 1 is read as 1 Pa" "1MPa" "--thickness 20" "20um" "--radius 2 " "2mm" "--work 40" \
                "40mJ/m2" "larger than the sphere radius"; do
      grep -q -F -- "$want" err && ok "stderr: $want" || fail "stderr lacks '$want': $(head -c 600 err)"
    done
    [ "$(grep -c '^# note:' out)" -eq 5 ] && ok "5 '# note:' header lines" || fail "$(grep -c '^# note:' out) notes"
  fi
  # With units, and values of a real experiment: no note.
  run 0 sphere --radius 2mm --thickness 20um "${MAT[@]}" --work 40mJ/m2 --points 5 &&
    { grep -q 'note' err out && fail "a note for plausible input: $(cat err)" || ok "no note with units"; }
  run 0 contact --shape sphere:2 --thickness 50um "${MAT[@]}" --work 0.04 --points 5 &&
    { grep -q -F 'sphere:2 ' err || grep -q -F -- '--shape 2 is read' err && ok "contact: radius in --shape noted" ||
      fail "contact: no note for sphere:2: $(cat err)"; }
  ;;
one_unit_parser)
  # Rates with units in lists and in ranges, and stiffness units in every command.
  run 0 "${KIN[@]}" --spring 500N/m --protocol "$PROTOCOL" --retract-speeds 0.1um/s:10um/s:3 && cp out units.tsv
  run 0 "${KIN[@]}" --spring 500 --protocol "$PROTOCOL" --retract-speeds 1e-7:1e-5:3 && cp out si.tsv
  if cmp -s <(grep -v '^#' units.tsv) <(grep -v '^#' si.tsv); then ok "0.1um/s:10um/s:3 with 500N/m = SI rows"
  else fail "rows differ between units and SI"; fi
  [ "$(rows units.tsv)" -eq 3 ] && ok "3 speeds" || fail "$(rows units.tsv) rows"
  run 0 "${KIN[@]}" --spring 0.5mN/um --protocol "$PROTOCOL" && ok "kinetics --spring 0.5mN/um"
  C=(contact --shape sphere:2mm --thickness 50um "${MAT[@]}" --work 40mJ/m2 --points 5)
  run 0 "${C[@]}" --spring 500N/m && grep -v '^# command' out >a.tsv
  run 0 "${C[@]}" --spring 500 && grep -v '^# command' out >b.tsv
  cmp -s <(grep -v 'time' a.tsv) <(grep -v 'time' b.tsv) && ok "contact --spring 500N/m = 500" || fail "contact spring units"
  expect_error "unknown stiffness unit" contact "${C[@]:1}" --spring 500N/s
  ;;
did_you_mean)
  expect_error "did you mean --retract-speeds?" "${KIN[@]}" --spring 500 --protocol "$PROTOCOL" --retract-speed 1um/s
  expect_error "did you mean --thickness?" sphere --radius 2mm --thicknes 50um "${MAT[@]}" --work 0.04
  expect_error "did you mean --film?" fit x.tsv --flim 1MPa,0.49
  # Far from every option: no guess.
  run 2 sphere --radius 2mm --zzzzzzzzzz 1 && { grep -q 'did you mean' err && fail "a guess: $(cat err)" || ok "no guess"; }
  ;;
default_curves_inside_validity)
  # sphere and contact stop their default range at the model's limits: no validity warning, the
  # same default point count (200), and the curve still reaches the pull-off it reports.
  for cmd in "sphere --radius 2mm" "contact --shape sphere:2mm"; do
    # shellcheck disable=SC2086
    if run 0 $cmd --thickness 50um "${MAT[@]}" --work 40mJ/m2; then
      grep -q 'warning' err && fail "$cmd: $(grep warning err | head -2)" || ok "$cmd: no validity warning"
      [ "$(rows out)" -eq 200 ] && ok "$cmd: 200 points" || fail "$cmd: $(rows out) points"
      # The largest contact radius stays within 0.1 R (THEORY.md: the paraboloid).
      awk '!/^#/ && $1 > amax { amax = $1 } END { exit !(amax <= 2e-4 * (1 + 1e-12)) }' out &&
        ok "$cmd: a <= 0.1 R" || fail "$cmd: a past 0.1 R"
    fi
  done
  ;;
fit_correlation_warning)
  # w, E1 and t free on one a(F) curve: t and E1 are ~0.9996 correlated (the data fix mainly
  # E1/t); the fit must say so, in the header and in the summary.
  run 0 fit "$data/example_a_F.tsv" "${FIT[@]}" --free w,E1,t || exit 1
  r=$(header out 'correlation t, E1:')
  awk -v r="$r" 'BEGIN { exit !(r > 0.99 || r < -0.99) }' && ok "correlation t-E1 = $r" || fail "t-E1 correlation $r"
  grep -q '^# warning: correlation t, E1 = ' out && ok "header warns" || fail "no header warning"
  grep -q 'warning: correlation t, E1 = ' err && ok "the summary (stderr without --output) warns" || fail "no summary warning"
  grep -q '^# film nu1: 0.49$' out && ok "film nu1: 0.49 (shortest round trip, the key as every command writes it)" ||
    fail "$(grep 'nu1' out)"
  # One header style: no machine keys (name_unit) left in fit's header.
  bad=$(grep -E '^# [A-Za-z0-9]+_[A-Za-z0-9_]*: ' out) &&
    fail "machine-style keys in fit's header: $bad" || ok "fit's keys in words, units in brackets"
  # w alone: no warning; with --output the summary goes to stdout.
  run 0 fit "$data/example_a_F.tsv" "${FIT[@]}" --output fit.tsv &&
    { grep -q 'correlation' out err && fail "a correlation warning with one free parameter" || ok "one free: quiet"; }
  grep -q '^  w  = ' out && ok "summary on stdout with --output" || fail "no summary with --output: $(head -3 out)"
  ;;
plots_for_every_command)
  run 0 sphere --radius 2mm --thickness 50um "${MAT[@]}" --work 40mJ/m2 --plot s.png && is_png s.png &&
    ok "sphere --plot" || fail "sphere --plot"
  grep -q '^# JKR reference pull-off' out && ok "sphere: JKR reference in the header" || fail "sphere: no JKR reference"
  run 0 contact --shape sphere:2mm --thickness 50um "${MAT[@]}" --work 40mJ/m2 --plot c.pdf &&
    [ "$(head -c 4 c.pdf)" = "%PDF" ] && ok "contact --plot (pdf)" || fail "contact --plot"
  run 0 pulloff "${MAT[@]}" --eta 0.1:10:5 --plot p.png && is_png p.png && ok "pulloff --plot" || fail "pulloff --plot"
  grep -q '^# JKR reference' out && ok "pulloff: JKR reference in the header" || fail "pulloff: no JKR reference"
  run 0 "${KIN[@]}" --spring 500N/m --protocol "$PROTOCOL" --plot k.png && is_png k.png && ok "kinetics --plot" ||
    fail "kinetics --plot"
  run 0 "${KIN[@]}" --spring 500N/m --protocol "$PROTOCOL" --retract-speeds 1um/s,10um/s --plot k2.png &&
    is_png k2.png && ok "kinetics sweep --plot" || fail "kinetics sweep --plot"
  expect_error "--plot" sphere --radius 2mm --thickness 50um "${MAT[@]}" --work 0.04 --plot s.svg
  [ ! -e s.svg ] && ok "nothing written for a refused --plot" || fail "s.svg written"
  ;;
kinetics_sweep_estimated)
  # Issue 40 item 4: a sweep of 1e6 speeds is refused up front with its estimate.
  expect_error "estimated run time" "${KIN[@]}" --spring 500 --protocol "$PROTOCOL" \
    --retract-speeds 0.1um/s:10um/s:1000000
  ;;
kinetics_messages_name_options)
  # Issue 40 item 8: the run time is named as such; --fit - reads stdin as `fit -` does.
  run 0 "${KIN[@]}" --spring 500 --protocol "$PROTOCOL" &&
    { grep -q '^# run time (wall clock' out && ok "run time named" || fail "no run-time line"; }
  grep -q '^# time \[s\]' out && fail "a bare 'time [s]' line beside simulated times" || ok "no bare time [s]"
  # Curves made by kinetics itself (every third state, w = 0.04), w fitted back from stdin.
  for c in 1 2; do
    v=$([ $c = 1 ] && echo 1um/s || echo 10um/s)
    run 0 "${KIN[@]}" --spring 500 --protocol "approach:1um/s:1mN,dwell:1s,retract:$v" &&
      grep -v '^#' out | awk -v c=$c 'NR > 1 && NR % 3 == 0 { print c "\t" $1 "\t" $5 }' >>curves.tsv
  done
  K2=("${KIN[@]}")
  K2[10]=0.05  # the value after --work: the start value
  timeout 600 "$cli" "${K2[@]}" --spring 500 --protocol "$PROTOCOL" --retract-speeds 1um/s,10um/s --free w --fit - \
    <curves.tsv >out 2>err && ok "kinetics --fit - reads stdin" || fail "kinetics --fit -: $(head -c 300 err)"
  w=$(sed -n 's|^# w \[J/m2\]: \([^ ]*\) +- .*|\1|p' out)
  awk -v w="$w" 'BEGIN { d = (w - 0.04) / 0.04; exit !(w != "" && d < 1e-3 && d > -1e-3) }' &&
    ok "w = $w from stdin (made with 0.04)" || fail "w = '$w' from stdin"
  ;;
*) unknown_case ;;
esac
finish_cases
