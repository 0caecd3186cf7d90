# Figure 8 (beyond the paper): pull-off force versus eta = t/(pi w R^2/E1*)^(1/3) for several
# film/substrate modulus ratios, under load control (left) and displacement control (right).
# JKR limits of a homogeneous solid: -3/2 and -5/6 (THEORY.md §6); an elastic substrate
# recovers them for eta -> 0 (substrate-dominated) and eta -> oo (film-dominated).
# Inputs: files (one `coatcontact pulloff` output per ratio), ratios (same order).

W = 1400; H = 640
load gpdir.'/style.gp'

n = words(files)
f1 = word(files, 1)
h = columns_of(f1)
eval need('c_eta', h, 'eta', f1)
eval need('c_pl', h, 'P_load', f1)
eval need('c_pd', h, 'P_disp', f1)
eval need('c_al', h, 'a_bar_load', f1)
eval need('c_ad', h, 'a_bar_disp', f1)

P_low = -1.5; P_high = -5.0/6
eta_min = 1e300; eta_max = 0
do for [k = 1:n] {
    stats word(files, k) using (column(c_eta)):(column(c_pl)) nooutput
    if (STATS_min_y < P_low) { P_low = STATS_min_y }
    if (STATS_min_x < eta_min) { eta_min = STATS_min_x }
    if (STATS_max_x > eta_max) { eta_max = STATS_max_x }
    stats word(files, k) using (column(c_pd)) nooutput
    if (STATS_max > P_high) { P_high = STATS_max }
}
P_span = P_high - P_low

set multiplot layout 1, 2 title figure_title(sprintf("Fig. 8 — pull-off force versus film thickness,  %s", nu_label)) font ',14' margins (paper ? 0.1 : 0.07), 0.97, (paper ? 0.16 : 0.13), (paper ? 0.9 : 0.86) spacing 0.08, 0
set logscale x
set xrange [eta_min:eta_max]
set format x '10^{%L}'
set xlabel axis_label('η = t / (π w R^2/E_1^*)^{1/3}', 'film thickness / adhesive length')
set ylabel 'pull-off force  P = F / (π w R)'
set yrange [P_low - 0.08 * P_span : P_high + 0.08 * P_span]
# One key, in panel (a)'s empty upper left (both panels share the colours): in (b) it would
# cover the curves.
set key top left
if (paper) { set key maxrows 3 title 'E_1^*/E_0^*' }
# In print the key's title carries 'E1*/E0*', the entries just its value.
key_text(r) = paper ? sprintf('%g', star_ratio(r)) : ratio_text(r)

# Kinks: where two minima of the curve exchange the lowest, the pull-off radius jumps (by more
# than 30 % from one eta to the next: on a smooth stretch it changes by ~1 % per step) and the
# pull-off force has a corner. A square marks the sampled point at the corner (the higher of
# the two beside the jump). ca, cp: columns of the pull-off radius and force.
jump(ca) = ($0 == 0) ? 0 : (column(ca) / k_a > 1.3 || column(ca) / k_a < 1 / 1.3)
kink_x(ca, cp) = (k_j = jump(ca), k_x = (k_j ? (column(cp) > k_p ? column(c_eta) : k_e) : NaN), \
                  k_y = (column(cp) > k_p ? column(cp) : k_p), \
                  k_a = column(ca), k_e = column(c_eta), k_p = column(cp), k_x)
k_a = 1; k_e = 1; k_p = 0; k_y = 0

set title panel('load control (lowest P on the P(ā) curve)', 1)
set label 1 'JKR  -3/2' at graph 0.98, first -1.5 offset 0, 0.7 right tc ls 31 front
plot -1.5 ls 31 notitle, \
     for [k = 1:n] word(files, k) using (column(c_eta)):(column(c_pl)) with lines \
         ls ratio_ls(real(word(ratios, k))) title key_text(real(word(ratios, k))), \
     for [k = 1:n] word(files, k) using (kink_x(c_al, c_pl)):(k_y) with points \
         ls ratio_ls(real(word(ratios, k))) pt 4 ps (paper ? 0.9 : 1.5) lw 1.5 notitle, \
     NaN with points lc rgb '#000000' pt 4 ps (paper ? 0.9 : 1.5) lw 1.5 title (paper ? 'kink (minima swap)' : 'kink: two minima swap')
unset label 1

set title panel('displacement control (lowest D on the P(D) curve)', 2)
unset key
# Below the line at the far left, where no curve lies more than 0.012 below -5/6.
set label 1 'JKR  -5/6' at graph 0.02, first -5.0/6 offset 0, -1.1 left tc ls 31 front
plot -5.0/6 ls 31 notitle, \
     for [k = 1:n] word(files, k) using (column(c_eta)):(column(c_pd)) with lines \
         ls ratio_ls(real(word(ratios, k))) title key_text(real(word(ratios, k))), \
     for [k = 1:n] word(files, k) using (kink_x(c_ad, c_pd)):(k_y) with points \
         ls ratio_ls(real(word(ratios, k))) pt 4 ps (paper ? 0.9 : 1.5) lw 1.5 notitle, \
     NaN with points lc rgb '#000000' pt 4 ps (paper ? 0.9 : 1.5) lw 1.5 title (paper ? 'kink (minima swap)' : 'kink: two minima swap')
unset multiplot
unset output
