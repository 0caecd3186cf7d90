# Figure 9 (beyond the paper): exact flat-punch equivalent modulus E_eq(a/t) from
# `coatcontact reduced` against the Perriot-Barthel 2004 fit and the Gao-Chiu-Lee 1992 model
# (eeq_models.gp); lower panel: relative deviation of each model from the exact value.
# Inputs: files (one `coatcontact reduced` output per ratio), ratios (same order).

W = 1000; H = 960
load gpdir.'/style.gp'
load gpdir.'/eeq_models.gp'

n = words(files)
f1 = word(files, 1)
h = columns_of(f1)
eval need('c_at', h, 'a_over_t', f1)
eval need('c_eeq', h, 'E_eq', f1)
stats f1 using (column(c_at)) nooutput
at_min = STATS_min; at_max = STATS_max
r_of(k) = real(word(ratios, k))

set multiplot title figure_title(sprintf("Fig. 9 — equivalent modulus E_{eq}: exact versus published approximations,  %s", nu_label)) font ',14'
set logscale x
set xrange [at_min:at_max]
set format x '10^{%L}'
set lmargin at screen 0.11; set rmargin at screen 0.97

# ---- upper panel: E_eq ----
set tmargin at screen 0.84; set bmargin at screen 0.40
set logscale y
set format y '10^{%L}'
set ylabel axis_label('E_{eq} = S / (2 a E_1^*)', 'log scale')
set xlabel ''
set format x ''
set key at screen 0.54, 0.952 center top horizontal maxrows 2 width 1 samplen 4.5 noopaque nobox
# Markers by E1*/E0* (every 8th point) keep the
# eight model curves apart in greyscale print; dash types tell the models apart.
plot for [k = 1:n] word(files, k) using (column(c_at)):(column(c_eeq)) with linespoints \
         ls ratio_ls(r_of(k)) pt ratio_pt(r_of(k)) ps (paper ? 0.5 : 0.9) pi 8 title ratio_text(r_of(k)), \
     for [k = 1:n] word(files, k) using (column(c_at)):(pb_eeq(column(c_at), r_of(k))) with linespoints \
         ls ratio_ls(r_of(k)) dt 2 lw 1.6 pt ratio_pt(r_of(k)) ps (paper ? 0.5 : 0.9) pi 8 notitle, \
     for [k = 1:n] word(files, k) using (column(c_at)):(gao_eeq(column(c_at), r_of(k))) with linespoints \
         ls ratio_ls(r_of(k)) dt 4 lw 1.6 pt ratio_pt(r_of(k)) ps (paper ? 0.5 : 0.9) pi 8 notitle, \
     NaN with lines lc rgb '#555555' lw 2.4 title 'exact (coatcontact reduced)', \
     NaN with lines lc rgb '#555555' lw 1.6 dt 2 title 'Perriot–Barthel 2004 fit', \
     NaN with lines lc rgb '#555555' lw 1.6 dt 4 title 'Gao–Chiu–Lee 1992 model'

# ---- lower panel: relative deviation ----
set tmargin at screen 0.37; set bmargin at screen 0.08
unset logscale y
set format y '%g%%'
set yrange [-40:40]
set ytics 10
set format x '10^{%L}'
set xlabel axis_label('ã = a/t', 'contact radius / film thickness')
set ylabel 'model / exact - 1'
unset key
set label 1 'same line types;  clipped at ±40 %' at graph 0.5, graph 0.9 center front
plot 0 ls 32, \
     for [k = 1:n] word(files, k) using (column(c_at)):(100 * (pb_eeq(column(c_at), r_of(k)) / column(c_eeq) - 1)) \
         with linespoints ls ratio_ls(r_of(k)) dt 2 lw 1.8 pt ratio_pt(r_of(k)) ps (paper ? 0.5 : 0.9) pi 8, \
     for [k = 1:n] word(files, k) using (column(c_at)):(100 * (gao_eeq(column(c_at), r_of(k)) / column(c_eeq) - 1)) \
         with linespoints ls ratio_ls(r_of(k)) dt 4 lw 1.8 pt ratio_pt(r_of(k)) ps (paper ? 0.5 : 0.9) pi 8
unset multiplot
unset output
