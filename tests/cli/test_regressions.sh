#!/usr/bin/env bash
# Regression tests of issue 17, one case per defect (label cli). Every case works in its own
# temporary folder and makes its own device node (mknod, skipped when not root), FIFO and
# symbolic links there; no case writes to the system's /dev entries.
# Usage: test_regressions.sh PATH/TO/coatcontact DATA_DIR CASE
CLI_TIMEOUT=120
source "$(dirname "$0")/cli_case_preamble.sh"
no_temporaries() {
  if compgen -G "$1/*.tmp.*" >/dev/null; then fail "temporary files left: $(ls "$1")"; fi
}

# One quick valid command line per subcommand that writes --output.
quick_commands=(
  "kernel --film 1GPa,0.3 --substrate 10GPa,0.25 --q 0.1,1"
  "reduced --film 0.1,0.25 --substrate 1,0.25 --a-over-t 1"
  "adhesive --film 1GPa,0.3 --substrate 10GPa,0.25 --eta 1 --a-bar 0.5,1"
  "pulloff --film 1GPa,0.3 --substrate 10GPa,0.25 --eta 1"
  "sphere --radius 5um --thickness 1um --film 1GPa,0.3 --substrate 10GPa,0.25 --work 50mJ/m2 --points 5"
  "fit $data/example_a_F.tsv --columns a,F --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um"
)
case "$case_name" in
output_replaces_device)
  # Defect 1: a character device at the --output path became a regular file.
  if [ "$(id -u)" -ne 0 ]; then echo "SKIP: mknod needs root"; exit 0; fi
  mknod -m 666 mynull c 1 3 || { echo "SKIP: mknod failed"; exit 0; }
  for line in "${quick_commands[@]}"; do
    read -r -a words <<<"$line"
    expect_error "--output" "${words[@]}" --output mynull
    grep -q "mynull" err || fail "${words[0]}: stderr does not name the path"
    [ "$(stat -c %F mynull)" = "character special file" ] || fail "${words[0]}: mynull is now $(stat -c %F mynull)"
  done
  mknod -m 666 mynull2 c 1 3
  read -r -a words <<<"${quick_commands[5]}"
  expect_error "--curve" "${words[@]}" --output fit.tsv --curve mynull2
  [ -e fit.tsv ] && fail "fit.tsv written although --curve was refused"
  no_temporaries .
  ;;
output_replaces_fifo)
  mkfifo fifo
  for line in "${quick_commands[@]}"; do
    read -r -a words <<<"$line"
    expect_error "--output" "${words[@]}" --output fifo
    [ -p fifo ] || fail "${words[0]}: fifo is no longer a FIFO"
  done
  no_temporaries .
  ;;
output_replaces_symlink)
  # A link to a regular file: the file is replaced, the link stays. A dangling link: refused.
  echo old >target.tsv
  ln -s target.tsv link.tsv
  read -r -a words <<<"${quick_commands[0]}"
  run 0 "${words[@]}" --output link.tsv && ok "output through a symlink"
  [ -L link.tsv ] || fail "link.tsv is no longer a symbolic link"
  grep -q "^# columns: q" target.tsv || fail "target.tsv was not written through the link"
  ln -s missing.tsv dangling.tsv
  expect_error "--output" "${words[@]}" --output dangling.tsv
  [ -L dangling.tsv ] && [ ! -e missing.tsv ] || fail "dangling link replaced or followed"
  no_temporaries .
  ;;
fit_output_overwrites_data)
  # Defect 2: fit d.tsv --output d.tsv destroyed the data; also through a symlink and a
  # second spelling; --output X --curve X lost one.
  cp "$data/example_a_F.tsv" d.tsv
  ln -s d.tsv alias.tsv
  for target in d.tsv ./d.tsv alias.tsv "$work/d.tsv"; do
    expect_error "--output" fit d.tsv "${FIT[@]}" --output "$target"
    cmp -s d.tsv "$data/example_a_F.tsv" || fail "data changed by --output $target"
    expect_error "--curve" fit d.tsv "${FIT[@]}" --curve "$target"
    cmp -s d.tsv "$data/example_a_F.tsv" || fail "data changed by --curve $target"
  done
  expect_error "--curve" fit d.tsv "${FIT[@]}" --output x.tsv --curve ./x.tsv
  [ -e x.tsv ] && fail "x.tsv written although the two outputs are one file"
  no_temporaries .
  ;;
fit_partial_results)
  # Defect 3: a failed fit left --curve behind. The write failure is injected by the test
  # hook (COATCONTACT_TEST_WRITE_FAILURE names the output whose write fails, as on a full disk).
  for failing in f.tsv c.tsv; do
    COATCONTACT_TEST_WRITE_FAILURE="$failing" run 2 fit "$data/example_a_F.tsv" "${FIT[@]}" --output f.tsv --curve c.tsv
    grep -q "No space left" err || fail "message does not say why: $(head -c 300 err)"
    [ -e f.tsv ] || [ -e c.tsv ] && fail "a result file was left after the write of $failing failed: $(ls)"
    no_temporaries .
  done
  echo keep >f.tsv
  COATCONTACT_TEST_WRITE_FAILURE=c.tsv run 2 fit "$data/example_a_F.tsv" "${FIT[@]}" --output f.tsv --curve c.tsv
  [ "$(cat f.tsv)" = keep ] || fail "an existing f.tsv was replaced although --curve failed"
  run 0 fit "$data/example_a_F.tsv" "${FIT[@]}" --output f.tsv --curve c.tsv && [ -s f.tsv ] && [ -s c.tsv ] &&
    ok "both outputs written when nothing fails"
  ;;
wrong_option_named)
  # Defect 4: subnormal and extreme values gave exit 3 or named the wrong thing.
  expect_error "--a-over-t" reduced --film 0.1,0.25 --substrate 1,0.25 --a-over-t 1e-320
  expect_error "--u" kernel --film 0.1,0.25 --substrate 1,0.25 --u 1e-320
  expect_error "--radius" fit "$data/example_a_F.tsv" --columns a,F --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um --radius 1e-320
  expect_error "--radius" fit "$data/example_a_F.tsv" --columns a,F --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um --radius 1e-90
  expect_error "--thickness" fit "$data/example_a_F.tsv" --columns a,F --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 1e-320
  expect_error "--thickness" fit "$data/example_a_F.tsv" --columns a,F --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 1e-90
  expect_error "--start w" fit "$data/example_a_F.tsv" "${FIT[@]}" --start w=1e-320
  expect_error "--start w" fit "$data/example_a_F.tsv" "${FIT[@]}" --start w=1e308
  expect_error "--start w" fit "$data/example_a_F.tsv" "${FIT[@]}" --start w=1e5
  expect_error "--start w" fit "$data/example_a_F.tsv" "${FIT[@]}" --start w=1e-12
  expect_error "--columns" fit "$data/example_a_F.tsv" --columns delta,F --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --thickness 50um
  expect_error "--film" kernel --film 1e308,0.25 --substrate 1e-308,0.25
  expect_error "--substrate" kernel --film 1,0.25 --substrate 1e-308,0.25
  # Zero stays allowed where it was: H(0).
  run 0 kernel --film 0.1,0.25 --substrate 1,0.25 --u 0,1e-300 && ok "--u 0 and 1e-300 still work"
  ;;
partial_stdout)
  # Defect 5: kernel printed its C(q) rows, then failed on H(u). Now nothing reaches stdout.
  expect_error "--film" kernel --film 1e308,0.25 --substrate 1,0.25 --q 0.001,1 --u 0,1
  run 3 kernel --film 1e99,0.25 --substrate 1e-99,0.25 --q 0.001,1 --u 0,1 &&
    { [ -s out ] && fail "stdout has $(wc -l <out) lines before the numerical failure" || ok "exit 3, stdout empty"; }
  COATCONTACT_TEST_WRITE_FAILURE=- run 2 kernel --film 1GPa,0.3 --substrate 10GPa,0.25 --q 0.1,1 &&
    { grep -q "standard output" err && ok "failed stdout write is exit 2" || fail "message: $(head -c 200 err)"; }
  ;;
long_silent_run)
  # Defect 6: 323 s of silence, then exit 3. Now refused up front.
  start=$(date +%s)
  expect_error "--tol" adhesive --film 0.1,0.25 --substrate 1,0.25 --eta 1e-6 --tol 1e-13
  grep -q "allowed" err || fail "message does not say what is allowed: $(head -c 300 err)"
  elapsed=$(($(date +%s) - start))
  [ "$elapsed" -le 60 ] && ok "refused after $elapsed s" || fail "took $elapsed s to refuse"
  expect_error "--tol" pulloff --film 0.1,0.25 --substrate 1,0.25 --eta 1e-6 --tol 1e-13
  ;;
stdout_full)
  # Defect 7a: a full stdout ended in exit 0 for fit and --help.
  if [ "$(id -u)" -eq 0 ] && mknod -m 666 full c 1 7 2>/dev/null; then
    for args in "--help" "kernel --help" "--version"; do
      read -r -a words <<<"$args"
      timeout 60 "$cli" "${words[@]}" >full 2>err
      rc=$?
      [ $rc -eq 2 ] && ok "$args > full: exit 2" || fail "$args > full: exit $rc"
    done
    timeout 120 "$cli" fit "$data/example_a_F.tsv" "${FIT[@]}" >full 2>err
    rc=$?
    [ $rc -eq 2 ] && ok "fit > full: exit 2" || fail "fit > full: exit $rc"
    timeout 120 "$cli" fit "$data/example_a_F.tsv" "${FIT[@]}" --output f.tsv >full 2>err
    rc=$?
    [ $rc -eq 2 ] && ok "fit --output f.tsv > full (summary): exit 2" || fail "fit summary > full: exit $rc"
  else
    echo "SKIP: mknod full needs root"
  fi
  COATCONTACT_TEST_WRITE_FAILURE=- run 2 fit "$data/example_a_F.tsv" "${FIT[@]}" && ok "fit with failing stdout: exit 2"
  ;;
long_option_echo)
  # Defect 7b: an unknown option of 100 000 characters was echoed whole.
  long="--$(head -c 100000 /dev/zero | tr '\0' x)"
  run 2 kernel "$long" 1 && {
    size=$(wc -c <err)
    [ "$size" -lt 400 ] && ok "message of $size bytes" || fail "message of $size bytes"
    grep -q "100002 characters" err || fail "message does not give the length"
  }
  ;;
sphere_physics_warnings)
  S=(sphere --radius 1mm --thickness 50um --film 1MPa,0.49 --substrate 10MPa,0.49 --work 50mJ/m2)
  run 0 "${S[@]}" --points 50 && {
    grep -q "^# warning" out && fail "default curve has warnings: $(grep '^# warning' out)"
    amax=$(grep -v '^#' out | awk 'BEGIN { m = 0 } $1 > m { m = $1 } END { print m }')
    awk -v a="$amax" 'BEGIN { exit !(a <= 1e-4 * 1.000001) }' && ok "default curve ends at a = $amax <= 0.1 R" ||
      fail "default curve reaches a = $amax > 0.1 R"
  }
  run 0 "${S[@]}" --contact-radius 1e-5:5e-4:20 && {
    grep -q "^# warning: contact radius" out || fail "no header warning for a > 0.1 R"
    grep -q "^# warning: penetration" out || fail "no header warning for delta > t"
    grep -q "warning: contact radius" err || fail "no stderr warning"
    [ "$(grep -vc '^#' out)" -eq 20 ] || fail "--contact-radius MIN:MAX:20 did not give 20 rows"
    ok "warnings beyond the limits"
  }
  run 0 sphere --radius 1mm --thickness 1um --film 1MPa,0.49 --substrate 1GPa,0.3 --work 50mJ/m2 --contact-radius 1e-5,5e-5 &&
    { grep -q "^# warning: mean pressure" out && ok "pressure warning" || fail "no pressure warning: $(grep '^#' out | tail -3)"; }
  expect_error "--contact-radius" "${S[@]}" --contact-radius 1e-30
  expect_error "--points" "${S[@]}" --contact-radius 1e-5 --points 5
  ;;
version_and_headers)
  run 0 --version && { grep -qE '^coatcontact [0-9]+\.[0-9]+\.[0-9]+' out && ok "version: $(cat out)" || fail "version: $(cat out)"; }
  for line in "${quick_commands[@]}"; do
    read -r -a words <<<"$line"
    run 0 "${words[@]}" || continue
    first=$(head -n 1 out)
    case "$first" in "# command: coatcontact ${words[0]} "*) ;; *) fail "${words[0]}: first line '$first'" ;; esac
  done
  for line in "${quick_commands[4]}" "${quick_commands[5]}"; do
    read -r -a words <<<"$line"
    run 0 "${words[@]}" && { grep -q "^# sign convention: F compressive positive" out ||
      fail "${words[0]}: no sign convention line"; }
  done
  # Units: mN/m and mJ/m^2 are mJ/m2, cm is 10 mm.
  run 0 sphere --radius 1cm --thickness 1um --film 1GPa,0.3 --substrate 10GPa,0.25 --work 50mN/m --points 5 && grep -v '^# command' out >a
  run 0 sphere --radius 10mm --thickness 1um --film 1GPa,0.3 --substrate 10GPa,0.25 --work 50mJ/m^2 --points 5 && grep -v '^# command' out >b
  run 0 sphere --radius 0.01 --thickness 1um --film 1GPa,0.3 --substrate 10GPa,0.25 --work 0.05 --points 5 && grep -v '^# command' out >c
  cmp -s a b && cmp -s a c && ok "cm, mN/m and mJ/m^2 accepted" || fail "unit spellings give different results"
  ;;
progress_line)
  # The progress line appears only on a terminal (script gives one), never in a pipe.
  if ! command -v script >/dev/null; then echo "SKIP: no script(1)"; exit 0; fi
  cmd="$cli pulloff --film 1GPa,0.3 --substrate 10GPa,0.25 --eta 0.001:1000:60 --output p.tsv"
  script -qec "$cmd" typescript >/dev/null 2>&1
  if grep -q "working" typescript; then ok "progress line on a terminal"; else
    echo "note: run finished before the progress line (2 s) or no terminal: $(head -c 200 typescript)"; fi
  $cmd 2>err >/dev/null
  grep -q "working" err && fail "progress line written to a non-terminal stderr"
  grep -q $'\r' err && fail "carriage return in a non-terminal stderr"
  ok "no progress line off a terminal"
  ;;
md_sphere_ignores_contact_radius)
  # `sphere --cohesive-stress` wrote its 400 default radii whatever --contact-radius asked for.
  md=(sphere --radius 5mm --thickness 50um --film 1MPa,0.49 --substrate 70GPa,0.22 --work 50mJ/m2
      --cohesive-stress 30kPa)
  run 0 "${md[@]}" --contact-radius 2e-5,5e-5,1e-4 && grep -v '^#' out | cut -f1 >radii
  printf '2.0000000000000002e-05\n5.0000000000000002e-05\n0.0001\n' >want
  cmp -s radii want && ok "the three requested radii, in order" || fail "rows: $(tr '\n' ' ' <radii | cut -c1-200)"
  expect_error "--points" "${md[@]}" --contact-radius 2e-5 --points 3
  expect_error "--contact-radius" "${md[@]}" --contact-radius 1e-12
  ;;
*)
  echo "unknown case '$case_name'"
  exit 1
  ;;
esac

if [ $failures -ne 0 ]; then
  echo "$case_name: $failures failure(s)"
  exit 1
fi
echo "$case_name: passed"
