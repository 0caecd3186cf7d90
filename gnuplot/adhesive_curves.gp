# Figures 5 and 7: normalized force P = F/(pi w R) versus normalized contact radius
# a_bar = a/(pi w R^2/E1*)^(1/3) for several eta = t/(pi w R^2/E1*)^(1/3) (paper section 6.2,
# [EqSolNormF]), with the JKR curve of a homogeneous film material and the two pull-off points.
# Inputs: adhesive, pulloff, ratio, fignum, film_word, effect; optional key_position.

W = 1000; H = 720
load gpdir.'/style.gp'
load gpdir.'/adhesive_data.gp'

stats adhesive using (column(c_abar)) nooutput
abar_max = STATS_max

set title figure_title(sprintf("Fig. %d — adhesive sphere on a %s: %s\n{/*0.85 %s}", fignum, film_word, materials_label(ratio), effect)) font ',14'
set xlabel axis_label('ā = a / (π w R^2/E_1^*)^{1/3}', 'normalized contact radius')
set ylabel axis_label('P = F / (π w R)', 'normalized force')
set xrange [0:abar_max]
set yrange [(P_low < -1.8 ? 1.15 * P_low : -2.1):3]
set xzeroaxis ls 32
# Where the key does not cover a curve: fig5.gp moves it (key_position).
if (!exists('key_position')) key_position = 'top left'
# In print the key goes under the plot, so no curve or marker is hidden at column width.
if (paper) key_position = 'outside below center horizontal maxrows 4 noopaque nobox'
eval 'set key '.key_position

# A curve within 3 % of the JKR curve over the drawn range (P <= 3; relative to JKR's pull-off
# 3/2) lies under the dashed JKR line drawn over it; its key entry says so and by how much
# (the thick film at eta = 10: 0.7 % on the soft film of fig 5, 2 % on the stiff one of fig 7).
array dev_jkr[n_eta]
do for [i = 1:n_eta] {
    stats adhesive index (i - 1) using (column(c_P) <= 3 ? abs(column(c_P) - jkr_P(column(c_abar))) / 1.5 : NaN) nooutput
    dev_jkr[i] = STATS_max
}
# In print the caption says it (captions.txt): the key under the plot has no room.
curve_title(i) = eta_title(i) . (!paper && dev_jkr[i] < 0.03 ? sprintf(', under the JKR line (within %.1g %%)', 100 * dev_jkr[i]) : '')

plot for [i = 1:n_eta] adhesive index (i - 1) using (column(c_abar)):(column(c_P)) \
         with lines ls eta_ls(i) title curve_title(i), \
     [a = 0.0001:abar_max] '+' using 1:(jkr_P($1)) with lines ls 31 title 'JKR, homogeneous (E_1^*)', \
     pulloff using (column(c_al)):(column(c_pl)):(eta_rgb(int($0) + 1)) with points ls 41 lc rgb variable title 'pull-off, load control (min P)', \
     pulloff using (column(c_ad)):(column(c_pd)):(eta_rgb(int($0) + 1)) with points ls 42 lc rgb variable title 'pull-off, displacement control (min D)'
unset output
