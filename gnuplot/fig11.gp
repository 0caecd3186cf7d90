# Figure 11 (beyond the paper): pull-off force versus eta for an elastic indenter
# (THEORY.md §9) of E2*/E1* = 0.3, 1, 3 and a rigid one, on the same film. Everything is
# normalized with E_r (1/E_r = 1/E1* + 1/E2*): eta = t/(pi w R^2/E_r)^(1/3), P = F/(pi w R);
# a homogeneous system stays at JKR's -3/2 and -5/6 whatever the indenter.
# Inputs: files (one `coatcontact pulloff --indenter` output per indenter), indenters
# ('rigid' or E2*/E1*, same order), ratio (film E1/E0).

W = 1400; H = 640
load gpdir.'/style.gp'

n = words(files)
f1 = word(files, 1)
h = columns_of(f1)
eval need('c_eta', h, 'eta', f1)
eval need('c_pl', h, 'P_load', f1)
eval need('c_pd', h, 'P_disp', f1)
indenter_text(s) = s eq 'rigid' ? 'rigid indenter' : sprintf("E_2^*/E_1^* = %s", s)
# The rigid indenter (the limit E2* -> oo) in dark grey, apart from the elastic ones, which take
# the sequential colours 1, 3, 5 (well separated) in their listed order.
rigid(k) = word(indenters, k) eq 'rigid'
n_elastic_before(k) = k <= 1 ? 0 : n_elastic_before(k - 1) + (rigid(k - 1) ? 0 : 1)
indenter_rgb(k) = rigid(k) ? 0x404040 : eta_rgb(1 + 2 * n_elastic_before(k))
indenter_lw(k) = rigid(k) ? 3.2 : 2.4

set multiplot layout 1, 2 title figure_title(sprintf("Fig. 11 — elastic indenters,  %s", materials_label(ratio))) font ',14' margins (paper ? 0.1 : 0.07), 0.97, (paper ? 0.16 : 0.13), (paper ? 0.9 : 0.86) spacing (paper ? 0.1 : 0.08), 0
set logscale x
set format x '10^{%L}'
set xlabel 'η = t / (π w R^2/E_r)^{1/3},   1/E_r = 1/E_1^* + 1/E_2^*'
set ylabel 'pull-off force  P = F / (π w R)'
set key bottom right

set title panel('load control', 1)
plot -1.5 ls 31 title 'JKR', \
     for [k = 1:n] word(files, k) using (column(c_eta)):(column(c_pl)) with lines \
         lc rgb indenter_rgb(k) lw indenter_lw(k) title indenter_text(word(indenters, k))
set title panel('displacement control', 2)
set key top right
plot -5.0/6 ls 31 title 'JKR', \
     for [k = 1:n] word(files, k) using (column(c_eta)):(column(c_pd)) with lines \
         lc rgb indenter_rgb(k) lw indenter_lw(k) title indenter_text(word(indenters, k))
unset multiplot
unset output
