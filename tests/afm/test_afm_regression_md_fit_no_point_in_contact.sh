#!/usr/bin/env bash
# Regression: "the MD fit leaves no point in contact" (exit 3) on the real flipsign retract, a film
# on an elastic base with E1 fixed near its free answer (1866, 1877, 1898 Pa on e3d14e0; whether it
# failed flipped with E1 in the 4th digit), and the same search's JKR (E1 1882 Pa) and DMT (rigid
# base, E free) fits. The contact-point profile's grid (40 points over the 24 um retract) is coarser
# than the contact (0.3 um): its no-contact end, the bare line b + m (z - z_c), was the lowest grid
# value, so every trial cost the line's sum and the search ended wherever its walk on that plateau
# stopped. THEORY.md section 15, "Search and errors": a trial holding no point in contact costs +inf.
# Each fit must succeed (exit 0, flag 0) with points in contact; a fixed contact point below every
# data point is still refused with exit 3, "no point in contact".
# Usage: test_afm_regression_md_fit_no_point_in_contact.sh COATCONTACT DATA_DIR WORK_DIR
set -u
cli="$1"; data="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
flipsign="$data/fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force"
elastic=(--film 1kPa,0.5 --substrate 10kPa,0.25 --thickness 1um)

fits() {  # NAME ARGS...: one fit that must succeed with points in contact
  local name="$1"; shift
  rm -f "$work/out.tsv"
  "$cli" afm fit "$flipsign" --radius 10um "$@" --output "$work/out.tsv" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  if [ "$rc" -ne 0 ]; then
    fail "$name: exit $rc :: $(cat "$work/stderr")"
    return
  fi
  grep -q '^# flag: 0 fitted$' "$work/out.tsv" || fail "$name: not flagged fitted: $(grep '^# flag' "$work/out.tsv")"
  local in_contact
  in_contact=$(sed -n 's/^# fit range: .*, \([0-9]*\) in contact)$/\1/p' "$work/out.tsv")
  [ -n "$in_contact" ] && [ "$in_contact" -ge 8 ] || fail "$name: '${in_contact}' points in contact (wanted >= 8)"
  echo "ok: $name ($in_contact points in contact; $(grep -E '^# w \[' "$work/out.tsv" | sed 's/^# //'))"
}

for e1 in 1866 1877 1898; do
  fits "md, E1 fixed at $e1 Pa on an elastic base" --model md --film "$e1,0.5" --substrate 10kPa,0.25 --thickness 1um \
    --free w,contact_point,baseline,tilt
done
fits "jkr, E1 fixed at 1882 Pa on an elastic base" --model jkr --film 1882,0.5 --substrate 10kPa,0.25 --thickness 1um \
  --free w,contact_point,baseline,tilt
fits "dmt, E1 free on a rigid base" --model dmt --film 10kPa,0.5 --substrate rigid --thickness 2um

# A fixed contact point below every data point: no trial holds a point in contact.
rm -f "$work/out.tsv"
"$cli" afm fit "$flipsign" --radius 10um --model md "${elastic[@]}" --free E1,w,baseline --contact-point 1e-6 \
  --output "$work/out.tsv" >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 3 ] || fail "fixed contact point below the data: exit $rc (wanted 3) :: $(cat "$work/stderr")"
grep -qF "no point in contact" "$work/stderr" || fail "fixed contact point below the data: message lacks 'no point in contact': $(cat "$work/stderr")"
[ ! -e "$work/out.tsv" ] || fail "fixed contact point below the data: an output file was written"

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all passed"
