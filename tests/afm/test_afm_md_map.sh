#!/usr/bin/env bash
# The Maugis-Dugdale retract fit over a force map (issue 37; THEORY.md section 15, "Many curves"
# and "A map of Maugis-Dugdale retracts"): a synthetic 4 x 4 JPK map of a film on an elastic
# base (make_afm_map --md: the library's own MD spring model, E1 100 kPa +- 20 % over the map,
# w 8-14 mJ/m2, z0 = 0.5 um so Maugis's lambda ~0.7-1.2, t = 4 um on 1 MPa, k = 1 N/m, noise
# 5 nN, tilted baselines, bad curves) fitted with --model md, E1 (from 250 kPa), w, contact
# point, baseline and tilt free:
#  - the flags are the truth's;
#  - --jobs 2 gives the table of --jobs 1 byte for byte (but the command line);
#  - the AFM-service rule, one answer everywhere: curves fitted alone (`--index N`, each in its
#    own process, so its tables are built for it alone and in another order than in the map)
#    give the map's row bit for bit (every estimate and standard error, chi2, lambda, the
#    model's jump-off, read back as doubles): the cohesive-zone tables' values are a pure
#    function of the stack and the grid index (md_table.hpp), whichever curve built them;
#  - recovery: E1 and w of every fitted curve within 4 standard errors of the truth, their mean
#    z-score within 3/sqrt(n) of 0 (no bias) and their RMS z-score in [0.4, 2.5] (standard
#    errors neither too small nor inflated).
# Usage: test_afm_md_map.sh COATCONTACT MAKE_AFM_MAP WORK_DIR
set -u
cli="$1"; make_map="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
unset COATCONTACT_CACHE  # every table built in this process (no node from an earlier run)
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
body() { grep -v '^# command:' "$1"; }

map="$work/md.jpk-force-map"
"$make_map" "$map" 4 4 --seed 7 --md --truth "$work/truth.tsv" || fail "make_afm_map --md"
model=(--model md --radius 10um --film 250kPa,0.5 --substrate 1MPa,0.3 --thickness 4um --range 0.5um)

"$cli" afm fit "$map" "${model[@]}" --jobs 1 --output "$work/j1.tsv" 2>"$work/j1.err" || fail "the md map, --jobs 1: $(cat "$work/j1.err")"
"$cli" afm fit "$map" "${model[@]}" --jobs 2 --output "$work/j2.tsv" 2>"$work/j2.err" || fail "the md map, --jobs 2: $(cat "$work/j2.err")"
cmp -s <(body "$work/j1.tsv") <(body "$work/j2.tsv") || fail "--jobs 2 differs from --jobs 1"
grep -q '^# flagged curves: 3 of 16 (no_contact 1, empty_segment 1, calibration 1)$' "$work/j1.tsv" \
  || fail "flag count line: $(grep '^# flagged' "$work/j1.tsv")"
bad=$(awk -F'\t' 'FNR == NR { if ($0 !~ /^#/) want[$1] = $8; next } $0 !~ /^#/ && want[$2] != $7 { n++ } END { print n + 0 }' \
  "$work/truth.tsv" "$work/j1.tsv")
[ "$bad" -eq 0 ] || fail "$bad curves with another flag than the truth's"

# ---- the map's rows against single-curve fits, each in its own process -----------------------
# The one-curve header "name [unit]: value +- error" and the row's columns, compared as doubles
# (the row prints 17 digits, the header the shortest round trip: the same double either way).
for index in 0 7 14; do
  "$cli" afm fit "$map" "${model[@]}" --index "$index" --output "$work/one$index.tsv" 2>"$work/one$index.err" \
    || { fail "--index $index: $(cat "$work/one$index.err")"; continue; }
  awk -F'\t' -v index_="$index" '
    FNR == NR {
      if ($0 ~ /^# (E1 \[Pa\]|w \[J\/m2\]|tilt \[N\/m\]|contact point \[m\]|baseline \[N\]): /) {
        name = $0; sub(/^# /, "", name); sub(/ \[.*/, "", name); gsub(/ /, "_", name)
        split($0, p, ": "); split(p[2], v, " "); one[name] = v[1]; one[name "_error"] = v[3]
      } else if ($0 ~ /^# chi2: /) { split($0, v, " "); one["chi2"] = v[3] }
      else if ($0 ~ /^# Maugis lambda: /) { split($0, v, " "); one["maugis_lambda"] = v[4] }
      else if ($0 ~ /^# model jump-off: /) { split($0, v, " "); one["model_jump_off_force"] = v[4]; one["model_jump_off_indentation"] = v[11] }
      next
    }
    /^# columns:/ { sub(/^# columns: /, ""); for (k = 1; k <= NF; ++k) col[$k] = k; next }
    /^#/ || $2 != index_ { next }
    {
      for (name in one) {
        ++compared
        if (!(name in col)) { printf "no column %s in the map table\n", name; ++differ; continue }
        if ($col[name] + 0 != one[name] + 0) { printf "curve %d %s: map %s, alone %s\n", index_, name, $col[name], one[name]; ++differ }
      }
    }
    END { if (compared != 14) printf "curve %d: compared %d values, expected 14\n", index_, compared; exit (differ > 0 || compared != 14) }' \
    "$work/one$index.tsv" "$work/j1.tsv" || fail "curve $index: the map row differs from the single-curve fit"
done

# ---- recovery against the truth --------------------------------------------------------------
awk -F'\t' 'FNR == NR { if ($0 !~ /^#/) { E[$1] = $4; w[$1] = $9 } next }
  /^# columns:/ { sub(/^# columns: /, ""); for (k = 1; k <= NF; ++k) col[$k] = k; next }
  /^#/ || $col["flag"] != 0 { next }
  {
    n = $col["curve"]; ze = ($col["E1"] - E[n]) / $col["E1_error"]; zw = ($col["w"] - w[n]) / $col["w_error"]
    ++fitted; se += ze; sw += zw; qe += ze * ze; qw += zw * zw
    if (ze < 0) ze = -ze; if (zw < 0) zw = -zw
    if (ze > me) me = ze; if (zw > mw) mw = zw
  }
  END { printf "%d %.3f %.3f %.3f %.3f %.3f %.3f\n", fitted, me, mw, se / fitted, sw / fitted, sqrt(qe / fitted), sqrt(qw / fitted) }' \
  "$work/truth.tsv" "$work/j1.tsv" >"$work/recovery"
read -r n max_e max_w mean_e mean_w rms_e rms_w <"$work/recovery"
echo "md map 4x4: $n fitted; z-scores of E1: max |z| $max_e, mean $mean_e, RMS $rms_e; of w: max |z| $max_w, mean $mean_w, RMS $rms_w"
[ "$n" -eq 13 ] || fail "13 fitted curves expected, got $n"
awk -v n="$n" -v a="$max_e" -v b="$max_w" -v c="$mean_e" -v d="$mean_w" -v e="$rms_e" -v f="$rms_w" 'BEGIN {
  bias = 3 / sqrt(n)
  exit !(a < 4 && b < 4 && c < bias && -c < bias && d < bias && -d < bias && e > 0.4 && e < 2.5 && f > 0.4 && f < 2.5) }' \
  || fail "E1 or w off the truth: max |z| E1 $max_e, w $max_w (limit 4); mean z $mean_e, $mean_w (limit 3/sqrt($n)); RMS z $rms_e, $rms_w (allowed 0.4..2.5)"

if [ "$failures" -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "all passed"
