#!/usr/bin/env bash
# Journal figures (make figures-paper; label: figures). Runs gnuplot/figures.mk's
# figures-paper-only on tests/figures/figures-test.conf into a temporary folder, then checks:
#  1. every figure is a PDF one journal column (8.5 cm = 241 pt) or two (17.8 cm = 505 pt) wide;
#  2. its text is 8-9 pt (pdftotext -bbox: the height of the axis tic labels), no "Fig. N" title,
#     and multi-panel figures carry panel letters (a), (b);
#  3. captions.txt lies beside them and defines the symbols the figures use;
#  4. a second run redraws nothing.
# usage: run_paper_figures.sh <coatcontact binary> <source dir>
set -euo pipefail
cli=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
run() {
  make --no-print-directory -C "$src" -f gnuplot/figures.mk -j2 figures-paper-only \
    CLI="$cli" FIGURES_CONF="$src/tests/figures/figures-test.conf" DATA_DIR="$tmp/data" FIG_DIR="$tmp/figures"
}
run >"$tmp/run1.log" 2>&1 || { cat "$tmp/run1.log"; fail "figures-paper-only failed"; }
paper="$tmp/figures/paper"
[ -s "$paper/captions.txt" ] || fail "no captions.txt beside the figures"
for symbol in eta a_bar '  P ' '  D ' lambda p_H 'g(a)'; do
  grep -q -F -- "$symbol" "$paper/captions.txt" || fail "captions.txt does not define '$symbol'"
done
for pdf in "$paper"/*.pdf; do
  name=$(basename "$pdf" .pdf)
  # MediaBox width in points (pdfcairo writes it as "/MediaBox [ 0 0 W H ]").
  width=$(grep -a -m1 -o '/MediaBox \[ *0 0 [0-9.]*' "$pdf" | awk '{ print $NF }')
  awk -v w="$width" 'BEGIN { exit !((w > 239 && w < 243) || (w > 503 && w < 507)) }' ||
    fail "$name: $width pt wide (need 241 or 505: 8.5 or 17.8 cm)"
  if command -v pdftotext >/dev/null; then
    text=$(pdftotext "$pdf" -)
    echo "$text" | grep -q 'Fig\. [0-9]' && fail "$name: a 'Fig. N' title in print"
    # The tallest single-digit word (a tic label) is the font's line height, ~1.16 em.
    size=$(pdftotext -bbox "$pdf" - | awk -F'"' '/<word/ && />-?[0-9][0-9.]*</ { h = $8 - $4; if (h > m) m = h } END { print m / 1.164 }')
    awk -v s="$size" 'BEGIN { exit !(s >= 7.5 && s <= 9.5) }' || fail "$name: text of ${size} pt (need 8-9)"
    case "$name" in
      fig3|fig4|fig8|fig11|fig_md_lambda|fig_stack|fig_kinetics)
        echo "$text" | grep -q '(a)' && echo "$text" | grep -q '(b)' || fail "$name: no panel letters" ;;
    esac
    echo "ok   $name: $width pt wide, ${size} pt text"
  else
    echo "ok   $name: $width pt wide (pdftotext missing: text not checked)"
  fi
done
run >"$tmp/run2.log" 2>&1 || fail "second run failed"
grep -q '  paper ' "$tmp/run2.log" && fail "a second run redrew: $(grep '  paper ' "$tmp/run2.log" | head -3)"
echo "ok   a second run redraws nothing"
echo "all passed"
