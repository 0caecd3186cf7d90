# Figure 6: normalized force P versus normalized penetration D = delta/(pi^2 w^2 R/E1*^2)^(1/3)
# for the same systems as figure 5 ([EqSolNormF], [EqSolNormD]), with the JKR curve and the
# two pull-off points (load control: lowest P; displacement control: lowest D).
# Inputs: adhesive, pulloff, ratio.

W = 1000; H = 720
load gpdir.'/style.gp'
load gpdir.'/adhesive_data.gp'

stats pulloff using (column(c_dd)) nooutput
D_low = STATS_min

set title figure_title(sprintf("Fig. 6 — force versus penetration, same systems as Fig. 5: %s", materials_label(ratio))) font ',14'
set xlabel axis_label('D = δ / (π^2 w^2 R/E_1^{*2})^{1/3}', 'normalized penetration')
set ylabel axis_label('P = F / (π w R)', 'normalized force')
set xrange [(D_low < -1.2 ? 1.15 * D_low : -1.4):2.5]
set yrange [(P_low < -1.8 ? 1.15 * P_low : -2.1):3]
set xzeroaxis ls 32
set yzeroaxis ls 32
set key top left
if (paper) { set key outside below center horizontal maxrows 4 noopaque nobox }

plot for [i = 1:n_eta] adhesive index (i - 1) using (column(c_D)):(column(c_P)) \
         with lines ls eta_ls(i) title eta_title(i), \
     [a = 0.0001:3] '+' using (jkr_D($1)):(jkr_P($1)) with lines ls 31 title 'JKR, homogeneous (E_1^*)', \
     pulloff using (column(c_dl)):(column(c_pl)):(eta_rgb(int($0) + 1)) with points ls 41 lc rgb variable title 'pull-off, load control (min P)', \
     pulloff using (column(c_dd)):(column(c_pd)):(eta_rgb(int($0) + 1)) with points ls 42 lc rgb variable title 'pull-off, displacement control (min D)'
unset output
