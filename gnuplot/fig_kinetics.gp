# Figure beyond the paper (THEORY.md section 14): rate-dependent adhesion through a spring.
# Left: the pull-off (most tensile load of the retract) against the reduced retract rate
# V = dZ/dtau, on the soft and stiff films and the homogeneous solid (eta, k_bar, n fixed), with
# the fast-limit slope n/(n+2) and each solid's quasi-static value (the slowest rate).
# Middle: load against penetration P(D) on the soft film, approach - dwell - retract at three
# retract rates: the hysteresis loops. Right: the same loads against time on a log axis, where
# approach and dwell are not crowded into a corner.
# Inputs: ratios, sweeps (one `kinetics --retract-speeds` file per ratio), speeds, loops (one
# `kinetics` file per speed), n, k_bar, eta.

W = 1500; H = 600
load gpdir.'/style.gp'

f1 = word(sweeps, 1)
h = columns_of(f1)
eval need('c_v', h, 'V', f1)
eval need('c_p', h, 'P_pulloff', f1)
l1 = word(loops, 1)
hl = columns_of(l1)
eval need('c_d', hl, 'D', l1)
eval need('c_load', hl, 'P', l1)
eval need('c_tau', hl, 'tau', l1)
eval need('c_seg', hl, 'segment', l1)

beta = n / (n + 2.0)
set multiplot layout 1, 3 title figure_title(sprintf("Crack kinetics at the contact edge: G - w = w (|v|/v^*)^{%g},  η = %g,  k̄ = %g,  %s", n, eta, k_bar, nu_label)) font ',14' margins (paper ? 0.085 : 0.06), 0.98, (paper ? 0.19 : 0.13), (paper ? 0.9 : 0.86) spacing 0.07, 0

# ---- left: pull-off against rate ----
set logscale xy
set format x '10^{%L}'
if (paper) { set xtics 100 }
set xlabel 'retract rate  V = (dz/dt) L_a / (v^* L_D)'
set ylabel '|pull-off load|  |P| = |F| / (π w R)'
set key top left
stats f1 using (column(c_v)) nooutput
v_max = STATS_max
stats f1 using (-column(c_p)) nooutput
p_top = STATS_max
set title panel('pull-off against retract rate', 1)
name(r) = real(r) == 1 ? 'homogeneous' : ratio_text(real(r))
# the shared colour of each E1*/E0* (style.gp ls 11-15), a marker each
plot for [i = 1:words(sweeps)] word(sweeps, i) using (column(c_v)):(-column(c_p)) with linespoints \
         ls ratio_ls(real(word(ratios, i))) pt (i == 1 ? 7 : (i == 2 ? 5 : 9)) ps (paper ? 0.4 : 0.7) \
         title name(word(ratios, i)), \
     p_top * (x / v_max)**beta ls 32 title sprintf('slope n/(n+2) = %.4f', beta)

# ---- right: hysteresis loops ----
unset logscale
set format x '%g'
set xtics autofreq
set xlabel 'penetration  D = δ / L_D'
set ylabel 'load  P = F / (π w R)'
unset key   # the same three runs as panel 3, keyed there
set title panel(sprintf('P(D) on the soft film (%s)', ratio_text(real(word(ratios, 1)))), 2)
plot 0 ls 32 notitle, \
     for [i = 1:words(loops)] word(loops, i) using (column(c_d)):(column(c_load)) with lines ls i \
         title sprintf('retract rate %g', real(word(speeds, i)))

# The same runs against time on a log axis: approach and dwell, short, get their own share of
# the axis. The segment ends (segments 1, 2) are read from the first run (the same protocol for all).
set title panel('the same runs against time', 3)
set logscale x
set format x '10^{%L}'
set xtics autofreq
set xlabel 'time  τ = t v^* / L_a'
set key right center title 'retract rate' # clear of the fast run's drop at the start of retract
stats l1 using (column(c_seg) == 1 ? column(c_tau) : NaN) nooutput
tau_approach = STATS_max
stats l1 using (column(c_seg) == 2 ? column(c_tau) : NaN) nooutput
tau_dwell = STATS_max
stats l1 using (column(c_tau) > 0 ? column(c_tau) : NaN) nooutput
tau_min = STATS_min
set xrange [tau_approach / 100 > tau_min ? tau_approach / 100 : tau_min:*]
set arrow 1 from tau_approach, graph 0 to tau_approach, graph 1 nohead ls 32
set arrow 2 from tau_dwell, graph 0 to tau_dwell, graph 1 nohead ls 32
set label 1 'approach' at tau_approach, graph 0.15 right offset -0.5, 0
set label 2 'dwell' at sqrt(tau_approach * tau_dwell), graph 0.45 center rotate by 90 front
set label 3 'retract' at tau_dwell, graph 0.15 left offset 0.5, 0
plot 0 ls 32 notitle, \
     for [i = 1:words(loops)] word(loops, i) using (column(c_tau)):(column(c_load)) with lines ls i \
         title sprintf('V = %g', real(word(speeds, i)))
unset multiplot
