# Figure beyond the paper (THEORY.md section 13): normalized force P versus contact radius
# a_bar at one eta for several Maugis-Dugdale parameters lambda, on the soft film, with the
# JKR curve on the same coating (lambda -> infinity). Small lambda: the interaction zone is
# wide, the curve flattens and reaches a = 0 at a finite tensile force (DMT-like).
# Inputs: ratio, eta, lambdas (space-separated), md (`adhesive --lambda` file, one block per
# lambda), jkr (`adhesive` file, one block).

W = 1000; H = 720
load gpdir.'/style.gp'

h = columns_of(md)
eval need('c_abar', h, 'a_bar', md)
eval need('c_P', h, 'P', md)
hj = columns_of(jkr)
eval need('j_abar', hj, 'a_bar', jkr)
eval need('j_P', hj, 'P', jkr)
n_lambda = words(lambdas)

set title figure_title(sprintf("Fig. 13 — Maugis-Dugdale zone on a coating, η = %g: %s", eta, materials_label(ratio))) font ',14'
set xlabel axis_label('ā = a / (π w R^2/E_1^*)^{1/3}', 'normalized contact radius')
set ylabel axis_label('P = F / (π w R)', 'normalized force')
set xrange [0:*]
set yrange [-2.1:3]
set xzeroaxis ls 32
set key top left

# Load-controlled pull-off: the lowest P of each curve (circles in the curve's colour).
array PA[n_lambda + 1]
array PP[n_lambda + 1]
do for [i = 1:n_lambda] {
    stats md index (i - 1) using (column(c_P)) nooutput
    PP[i] = STATS_min
    stats md index (i - 1) every ::(int(STATS_index_min))::(int(STATS_index_min)) using (column(c_abar)) nooutput
    PA[i] = STATS_min
}
stats jkr using (column(j_P)) nooutput
PP[n_lambda + 1] = STATS_min
stats jkr every ::(int(STATS_index_min))::(int(STATS_index_min)) using (column(j_abar)) nooutput
PA[n_lambda + 1] = STATS_min
marker_rgb(i) = i <= n_lambda ? eta_rgb(i) : 0

plot for [i = 1:n_lambda] md index (i - 1) using (column(c_abar)):(column(c_P)) \
         with lines ls eta_ls(i) title sprintf('λ = %s', word(lambdas, i)), \
     jkr using (column(j_abar)):(column(j_P)) with lines ls 31 title 'JKR on the coating (λ → ∞)', \
     PA using (PA[int($1)]):(PP[int($1)]):(marker_rgb(int($1))) with points ls 41 lc rgb variable notitle, \
     NaN with points ls 41 title 'pull-off (load control): lowest P'
unset output
