#!/usr/bin/env bash
# Figure-pipeline test (label: figures). Runs gnuplot/figures.mk on the reduced parameter set
# tests/figures/figures-test.conf into a temporary folder, then checks:
#  1. every figure exists: PNG valid, of the size its script sets, not blank (check_png.py,
#     python3 standard library: zlib + struct); PDF starts with %PDF- and ends with %%EOF;
#     every dataset carries the CLI's self-describing header (a "# columns:" line);
#  2. a second run regenerates nothing (no data/plot lines, no file modified);
#  3. changing one parameter (ETA) regenerates exactly the datasets and figures that use it.
# usage: run_pipeline.sh <coatcontact binary> <source dir>
set -euo pipefail
cli=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
here="$src/tests/figures"
fail() { echo "FAIL: $*"; exit 1; }

run() {  # extra make arguments...
  make --no-print-directory -C "$src" -f gnuplot/figures.mk -j2 figures-only \
    CLI="$cli" FIGURES_CONF="$here/figures-test.conf" \
    DATA_DIR="$tmp/data" FIG_DIR="$tmp/figures" "$@"
}
snapshot() { (cd "$tmp" && find data figures -type f -printf '%p %T@\n' | sort); }

echo "== first run"
run > "$tmp/run1.log" 2>&1 || { cat "$tmp/run1.log"; fail "first run of the pipeline failed"; }
cat "$tmp/run1.log"

# Sizes in pixels set by each figure script (W, H at the top of gnuplot/figN.gp or its helper).
declare -A size=([fig1]=1000x900 [fig2]=1000x760 [fig3]=1400x620 [fig4]=1400x620
                 [fig5]=1000x720 [fig6]=1000x720 [fig7]=1000x720 [fig8]=1400x640 [fig9]=1000x960
                 [fig10]=1000x700 [fig11]=1400x640 [fig12]=1000x720 [fig13]=1000x720
                 [fig_md_lambda]=1400x640 [fig_stack]=1400x1100 [fig_kinetics]=1500x600)
specs=()
for f in fig1 fig2 fig3 fig4 fig5 fig6 fig7 fig8 fig9 fig10 fig11 fig12 fig13 fig_md_lambda fig_stack fig_kinetics; do
  specs+=("$tmp/figures/$f.png:${size[$f]}")
  pdf="$tmp/figures/$f.pdf"
  [ -s "$pdf" ] || fail "$pdf missing or empty"
  head -c 5 "$pdf" | grep -q '%PDF-' || fail "$pdf does not start with %PDF-"
  tail -c 64 "$pdf" | grep -q '%%EOF' || fail "$pdf does not end with %%EOF"
done
python3 "$here/check_png.py" "${specs[@]}" || fail "PNG check"
for d in "$tmp"/data/*.tsv; do
  grep -q '^# columns:' "$d" || fail "$d has no '# columns:' header line"
done
[ -z "$(find "$tmp" -name '*.tmp*')" ] || fail "temporary files left behind"

echo "== second run: nothing may be regenerated"
before=$(snapshot)
sleep 1.1   # make a rewrite visible in the modification times
run > "$tmp/run2.log" 2>&1 || { cat "$tmp/run2.log"; fail "second run failed"; }
if grep -E '^  (data|plot) ' "$tmp/run2.log"; then fail "second run regenerated files"; fi
[ "$before" = "$(snapshot)" ] || fail "second run modified files"

echo "== changed ETA: only the adhesive datasets and figures 5-7 may be regenerated"
run ETA=0.5,2 > "$tmp/run3.log" 2>&1 || { cat "$tmp/run3.log"; fail "third run failed"; }
got=$(grep -E '^  (data|plot) ' "$tmp/run3.log" | awk '{print $2}' | sed "s|$tmp/||" | sort | tr '\n' ' ')
want="data/adhesive_E0.1.tsv data/adhesive_E10.tsv data/pulloffeta_E0.1.tsv data/pulloffeta_E10.tsv \
figures/fig5.pdf figures/fig5.png figures/fig6.pdf figures/fig6.png figures/fig7.pdf figures/fig7.png "
[ "$got" = "$want" ] || fail "regenerated: [$got], expected: [$want]"
grep -q 'pull-off force' "$tmp/run3.log" || fail "no pull-off table printed"
echo "all figure checks passed"
