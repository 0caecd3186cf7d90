#!/usr/bin/env bash
# coatcontact indent analyse|calibrate|film on the shared fused-silica file (THEORY.md section
# 16): analyse --all against the vendor's per-test averages (E within 0.5 %, H within 1 %); a
# homogeneous "film" (film = substrate) gives back the Oliver-Pharr modulus at every depth; the
# calibration's table; --plot writes a picture; bad options: exit 2, the option named, no output.
# Usage: test_indent_analysis_cli.sh COATCONTACT DATA_DIR WORK_DIR
set -u
cli="$1"; data="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
xls="$data/FS_Calibration.xls"

expect_error() {  # CODE FRAGMENT... -- ARGS
  local code="$1"; shift
  local fragments=()
  while [ "$1" != "--" ]; do fragments+=("$1"); shift; done
  shift
  rm -f "$work/out.tsv"
  "$cli" "$@" --output "$work/out.tsv" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  [ "$rc" -eq "$code" ] || fail "exit $rc (wanted $code): $* :: $(cat "$work/stderr")"
  for f in "${fragments[@]}"; do
    grep -qF -- "$f" "$work/stderr" || fail "message lacks '$f': $* :: $(cat "$work/stderr")"
  done
  [ ! -e "$work/out.tsv" ] || fail "an output file was written: $*"
}

# ---- analyse --all: our E and H against the vendor's, test by test ------------------------
"$cli" indent analyse "$xls" --all --output "$work/all.tsv" 2>"$work/stderr" || fail "analyse --all: $(cat "$work/stderr")"
grep -q '^# columns: test	E_mean_Pa	E_sd_Pa	H_mean_Pa	H_sd_Pa	points	vendor_E_mean_Pa	vendor_H_mean_Pa$' "$work/all.tsv" || fail "analyse --all columns"
rows=$(grep -vc '^#' "$work/all.tsv")
[ "$rows" -eq 16 ] || fail "analyse --all: $rows rows, wanted 16"
bad=$(awk -F'\t' '!/^#/ { de = $2/$7 - 1; dh = $4/$8 - 1; if (de < 0) de = -de; if (dh < 0) dh = -dh;
                          if (de > 0.005 || dh > 0.01) print $1, de, dh }' "$work/all.tsv")
[ -z "$bad" ] || fail "tests off the vendor's averages: $bad"

# ---- analyse one test: per-point columns, the header's means, a plot ----------------------
"$cli" indent analyse "$xls" --test "Test 004" --range 100nm:200nm --output "$work/t4.tsv" || fail "analyse --test"
grep -q '^# columns: depth_m	load_N	stiffness_N_per_m	contact_depth_m	area_m2	contact_radius_m	reduced_modulus_Pa	modulus_Pa	hardness_Pa	in_range$' "$work/t4.tsv" || fail "analyse columns"
mean=$(awk -F'\t' '!/^#/ && $10 == 1 { s += $8; n++ } END { printf "%.9e", s/n }' "$work/t4.tsv")
header=$(sed -n 's/^# E mean \[Pa\]: //p' "$work/t4.tsv")
awk -v a="$mean" -v b="$header" 'BEGIN { d = a/b - 1; exit !(d < 1e-9 && d > -1e-9) }' || fail "E mean $header is not the rows' mean $mean"
if command -v gnuplot >/dev/null; then
  "$cli" indent analyse "$xls" --index 0 --plot "$work/a.png" --output "$work/a.tsv" || fail "analyse --plot"
  [ -s "$work/a.png" ] && head -c 8 "$work/a.png" | grep -q PNG || fail "analyse --plot wrote no PNG"
fi

# ---- film: a film far thicker than the contact (a/t < 1e-5) is all the tip sees: its modulus
# is the Oliver-Pharr modulus at every depth (E_eq - 1 ~ a/t; bound 1e-4) --------------------
"$cli" indent film "$xls" --thickness 1m --film-poisson 0.18 --substrate 162GPa,0.22 --max-points 15 \
  --output "$work/film.tsv" 2>"$work/stderr" || fail "film: $(cat "$work/stderr")"
bad=$(awk -F'\t' '!/^#/ && $9 != "-" { d = $9/$7 - 1; if (d < 0) d = -d; if (d > 1e-4) print $1, $7, $9 }' "$work/film.tsv")
[ -z "$bad" ] || fail "a thick film differs from the Oliver-Pharr modulus: $bad"
[ "$(grep -vc '^#' "$work/film.tsv")" -eq 15 ] || fail "film --max-points 15: not 15 rows"
grep -q '^# exact: fitted E_film \[Pa\]: ' "$work/film.tsv" || fail "film header lacks the fit"
"$cli" indent film "$xls" --thickness 1um --film-poisson 0.18 --substrate 162GPa,0.22 --model all --max-points 12 \
  --output "$work/all_models.tsv" 2>"$work/stderr" || fail "film --model all: $(cat "$work/stderr")"
for m in exact doerner_nix king gao hay_crawford bec perriot_barthel; do
  grep -q "	E_film_${m}_Pa	" "$work/all_models.tsv" || fail "film --model all lacks $m"
done

# ---- calibrate ------------------------------------------------------------------------------
"$cli" indent calibrate "$xls" --range 50nm:1800nm --output "$work/cal.tsv" || fail "calibrate"
grep -q '^C0	' "$work/cal.tsv" && grep -q '^frame_compliance_m_per_N	' "$work/cal.tsv" || fail "calibrate rows"

# ---- bad input --------------------------------------------------------------------------------
expect_error 2 "--film-poisson" -- indent film "$xls" --thickness 500nm --substrate 75GPa,0.18
expect_error 2 "--model" "doerner-nix" -- indent film "$xls" --thickness 500nm --film-poisson 0.18 --substrate 75GPa,0.18 --model nix
expect_error 2 "--range" -- indent analyse "$xls" --range 200nm:100nm
expect_error 2 "beta" -- indent analyse "$xls" --beta -1
expect_error 2 "--stiffness" -- indent analyse "$xls" --stiffness magic
expect_error 2 "coated" -- indent film "$xls" --thickness 500nm --film-poisson 0.18 --substrate 75GPa,0.18 --model bec --contact-depth coated

[ "$failures" -eq 0 ] && echo "all indent analysis CLI checks passed"
exit $((failures > 0))
