# Figure 10 (beyond the paper): pull-off force through a spring of normalized stiffness
# k_bar = k (pi^2 w^2 R/E1*^2)^(1/3) / (pi w R) (THEORY.md §10), one curve per modulus ratio
# at one eta, between its load-controlled (k_bar -> 0) and displacement-controlled
# (k_bar -> oo) limits (dashed).
# Inputs: files (one `coatcontact pulloff --spring-bar` output per ratio), ratios, eta.

W = 1000; H = 700
load gpdir.'/style.gp'

n = words(files)
f1 = word(files, 1)
h = columns_of(f1)
eval need('c_k', h, 'k_bar', f1)
eval need('c_ps', h, 'P_spring', f1)
eval need('c_pl', h, 'P_load', f1)
eval need('c_pd', h, 'P_disp', f1)

set title figure_title(sprintf("Fig. 10 — pull-off through a spring,  η = %g,  %s", eta, nu_label)) font ',14'
set logscale x
set format x '10^{%L}'
set xlabel 'spring stiffness  k̄ = k (π^2 w^2 R/E_1^{*2})^{1/3} / (π w R)'
set ylabel 'pull-off force  P = F / (π w R)'
set key at graph 0.97, graph 0.38 right center   # the free band between the two curves' limits
plot for [k = 1:n] word(files, k) using (column(c_k)):(column(c_pl)) with lines ls 32 notitle, \
     for [k = 1:n] word(files, k) using (column(c_k)):(column(c_pd)) with lines ls 32 notitle, \
     for [k = 1:n] word(files, k) using (column(c_k)):(column(c_ps)) with lines \
         ls ratio_ls(real(word(ratios, k))) title ratio_text(real(word(ratios, k))), \
     NaN ls 32 title (paper ? 'limits k̄ → 0, ∞' : 'limits k̄ → 0 (load control), k̄ → ∞ (displacement)')
unset output
