# Figure beyond the paper (THEORY.md section 14): rate-dependent adhesion through a spring.
# Left: the pull-off (most tensile load of the retract) against the reduced retract rate
# V = dZ/dtau, on the soft and stiff films and the homogeneous solid (eta, k_bar, n fixed), with
# the fast-limit slope n/(n+2) and each solid's quasi-static value (the slowest rate).
# Right: load against penetration P(D) on the soft film, approach - dwell - retract at three
# retract rates: the hysteresis loops.
# Inputs: ratios, sweeps (one `kinetics --retract-speeds` file per ratio), speeds, loops (one
# `kinetics` file per speed), n, k_bar, eta.

W = 1400; H = 640
load gpdir.'/style.gp'

f1 = word(sweeps, 1)
h = columns_of(f1)
eval need('c_v', h, 'V', f1)
eval need('c_p', h, 'P_pulloff', f1)
l1 = word(loops, 1)
hl = columns_of(l1)
eval need('c_d', hl, 'D', l1)
eval need('c_load', hl, 'P', l1)

beta = n / (n + 2.0)
set multiplot layout 1, 2 title figure_title(sprintf("Crack kinetics at the contact edge: G - w = w (|v|/v^*)^{%g},  η = %g,  k̄ = %g,  %s", n, eta, k_bar, nu_label)) font ',14' margins (paper ? 0.1 : 0.07), 0.97, 0.13, (paper ? 0.9 : 0.86) spacing 0.08, 0

# ---- left: pull-off against rate ----
set logscale xy
set format x '10^{%L}'
set xlabel 'retract rate  V = (dz/dt) L_a / (v^* L_D)'
set ylabel '|pull-off load|  |P| = |F| / (π w R)'
set key top left
stats f1 using (column(c_v)) nooutput
v_max = STATS_max
stats f1 using (-column(c_p)) nooutput
p_top = STATS_max
set title panel('pull-off against retract rate', 1)
name(r) = real(r) == 1 ? 'homogeneous' : ratio_text(real(r))
plot for [i = 1:words(sweeps)] word(sweeps, i) using (column(c_v)):(-column(c_p)) with linespoints ls (20 + i) \
         title name(word(ratios, i)), \
     p_top * (x / v_max)**beta ls 32 title sprintf('slope n/(n+2) = %.4f', beta)

# ---- right: hysteresis loops ----
unset logscale
set format x '%g'
set xlabel 'penetration  D = δ / L_D'
set ylabel 'load  P = F / (π w R)'
set key bottom left
set title panel(sprintf('P(D) on the soft film (%s): approach, dwell, retract', ratio_text(real(word(ratios, 1)))), 2)
plot 0 ls 32 notitle, \
     for [i = 1:words(loops)] word(loops, i) using (column(c_d)):(column(c_load)) with lines ls i \
         title sprintf('retract rate %g', real(word(speeds, i)))
unset multiplot
