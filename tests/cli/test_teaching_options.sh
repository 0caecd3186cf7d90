#!/usr/bin/env bash
# Issue 39, teaching list: options a lecturer expects to find in every command.
#   contact_pyramid_is_equal_area_cone: `contact --shape pyramid:THETA` (as `afm fit` takes it)
#     is the cone of equal cross-section area, tan(beta) = 2 tan(theta)/sqrt(pi): its rows equal
#     those of `--shape cone:BETA` with BETA computed here, and the header names the pyramid;
#     a Vickers tip (68 deg) is the textbook 70.3 deg cone.
#   sphere_spring_matches_contact: `sphere --spring k` (as `contact --spring`, THEORY.md section 10)
#     gives the spring-controlled pull-off of `contact --shape sphere:R --spring k`, an independent
#     pipeline (direct shape solve against sphere's reduced-variable table): measured 2e-8
#     relative, allowed 1e-6 (both at --tol 1e-8, the pull-off located to ~1e-9 in a_bar); a
#     very soft spring gives the load-controlled pull-off, a very stiff one the displacement one.
set -u
cli=$1
case_name=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

case $case_name in
contact_pyramid_is_equal_area_cone)
  common=(--thickness 100nm --film 1GPa,0.3 --substrate 70GPa,0.22 --work 50mJ/m2 --points 20)
  "$cli" contact --shape pyramid:68deg "${common[@]}" --output "$tmp/pyramid.tsv" || fail "pyramid:68deg exit $?"
  beta=$(awk 'BEGIN { pi = atan2(0, -1); printf "%.17g", atan2(2 * sin(68 * pi / 180) / cos(68 * pi / 180), sqrt(pi)) }')
  awk -v b="$beta" 'BEGIN { d = b * 45 / atan2(1, 1); if (d < 70.25 || d > 70.35) { print "Vickers cone " d " deg, expected 70.3"; exit 1 } }' \
    || fail "equal-area cone of a Vickers pyramid"
  "$cli" contact --shape "cone:${beta}rad" "${common[@]}" --output "$tmp/cone.tsv" || fail "cone exit $?"
  grep -q '^# shape: four-sided pyramid, face half angle 68 deg' "$tmp/pyramid.tsv" || fail "header does not name the pyramid"
  # Same delta0(r) to the last bit up to tan(atan(x)) rounding: compare to 1e-12 relative.
  paste <(grep -v '^#' "$tmp/pyramid.tsv") <(grep -v '^#' "$tmp/cone.tsv") | awk -F'\t' '
    { n = NF / 2; for (i = 1; i <= n; i++) { a = $i; b = $(i + n); d = a - b; if (d < 0) d = -d
        s = (a < 0 ? -a : a); if (d > 1e-12 * s + 1e-300) { print "row " NR " column " i ": " a " vs " b; bad = 1 } } rows++ }
    END { if (rows < 20 || bad) exit 1 }' || fail "pyramid rows differ from the equal-area cone's"
  "$cli" contact --shape pyramid:95deg "${common[@]}" > /dev/null 2> "$tmp/err"; rc=$?
  [ $rc -eq 2 ] && grep -q -- '--shape' "$tmp/err" || fail "pyramid:95deg: exit $rc, $(cat "$tmp/err")"
  ;;
sphere_spring_matches_contact)
  mat=(--thickness 10um --film 1MPa,0.49 --substrate 70GPa,0.22 --work 40mJ/m2 --points 3)
  force() { sed -n "s/^# pull-off force, $1 \[N\]: \([^ ]*\).*/\1/p" "$2"; }
  close() { awk -v a="$1" -v b="$2" -v r="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; s = (a < 0 ? -a : a); exit !(a != "" && d <= r * s) }'; }
  for k in 50N/m 500N/m 5mN/um; do
    "$cli" sphere --radius 1mm "${mat[@]}" --spring "$k" --output "$tmp/s.tsv" 2> /dev/null || fail "sphere --spring $k exit $?"
    "$cli" contact --shape sphere:1mm "${mat[@]}" --spring "$k" --output "$tmp/c.tsv" 2> /dev/null || fail "contact --spring $k exit $?"
    a=$(force "spring control" "$tmp/s.tsv"); b=$(force "spring control" "$tmp/c.tsv")
    close "$a" "$b" 1e-6 || fail "k = $k: sphere $a, contact $b"
  done
  "$cli" sphere --radius 1mm "${mat[@]}" --spring 1e-6 --output "$tmp/soft.tsv" 2> /dev/null || fail "soft spring"
  close "$(force "spring control" "$tmp/soft.tsv")" "$(force "load control" "$tmp/soft.tsv")" 1e-4 \
    || fail "k -> 0 is not load control"
  "$cli" sphere --radius 1mm "${mat[@]}" --spring 1e9 --output "$tmp/stiff.tsv" 2> /dev/null || fail "stiff spring"
  close "$(force "spring control" "$tmp/stiff.tsv")" "$(force "displacement control" "$tmp/stiff.tsv")" 1e-3 \
    || fail "k -> inf is not displacement control"
  "$cli" sphere --radius 1mm "${mat[@]}" --spring 500N/m --cohesive-stress 1MPa > /dev/null 2> "$tmp/err"; rc=$?
  [ $rc -eq 2 ] && grep -q -- '--spring' "$tmp/err" || fail "--spring with --cohesive-stress: exit $rc"
  ;;
*) fail "unknown case $case_name" ;;
esac
echo "ok $case_name"
