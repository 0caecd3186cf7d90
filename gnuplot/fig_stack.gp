# Figure beyond the paper (THEORY.md section 12): a stack of layers. Top row: a three-layer
# coating against its one-layer approximations (the top layer alone; one film of the
# thickness-weighted E and nu), E_eq(a/T) and the load-controlled pull-off versus eta. Bottom
# row: one film bonded versus sliding (frictionless) on its substrate. Everything is in the
# top layer's units: E_eq = E_equivalent/E_top*, eta = T/(pi w R^2/E_top*)^(1/3); the average
# film's curves are rescaled by avg_scale = E_avg*/E_top* (E_eq times it, eta divided by its
# cube root). Inputs: layers, base, film, film_base, avg, avg_scale, reduced and pulloff
# (stack, top, average), slip_reduced and slip_pulloff (bonded, sliding).

W = 1400; H = 1100
load gpdir.'/style.gp'

f1 = word(reduced, 1)
h = columns_of(f1)
eval need('c_a', h, 'a_over_t', f1)
eval need('c_e', h, 'E_eq', f1)
p1 = word(pulloff, 1)
hp = columns_of(p1)
eval need('c_eta', hp, 'eta', p1)
eval need('c_pl', hp, 'P_load', p1)

scale_e(k) = k == 3 ? avg_scale : 1.0
scale_eta(k) = k == 3 ? avg_scale**(1.0/3) : 1.0
# Legends in words: the layers' moduli top first, their relative thicknesses, the substrate.
pair(s, i) = word(system(sprintf("echo '%s' | tr ',' ' '", s)), i)
stack_words = system(sprintf("echo '%s' | awk '{ for (i = 1; i <= NF; i++) { split($i, a, \",\"); \
    e = e (i > 1 ? \", \" : \"\") a[2]; h = h (i > 1 ? \":\" : \"\") a[1] } \
    printf \"%%d layers E = %%s (top first), thicknesses %%s\", NF, e, h }'", layers))
stack_title(k) = k == 1 ? 'the stack' : \
                 (k == 2 ? sprintf('top layer alone (E = %s)', pair(word(layers, 1), 2)) : \
                  sprintf('weighted film (E = %.3g, ν = %.3g)', real(pair(avg, 1)), real(pair(avg, 2))))
slip_title(k) = k == 1 ? 'bonded' : 'sliding (frictionless interface)'

set multiplot layout 2, 2 title figure_title("Stacks of layers (moduli relative), normalized by the top layer's E^* and the total thickness T") font ',14' margins (paper ? 0.1 : 0.07), 0.97, 0.08, (paper ? 0.9 : 0.91) spacing 0.08, (paper ? 0.17 : 0.1)
set logscale x
set format x '10^{%L}'

set title panel(sprintf('%s on E_0 = %s, and one-layer approximations', stack_words, pair(base, 1)), 1)
set xlabel 'a/T'
set ylabel 'E_{eq} / E_{top}^*'
set logscale y
set yrange [*:40]   # headroom: the key sits above the curves
set key top left
plot for [k = 1:3] word(reduced, k) using (column(c_a)):(column(c_e) * scale_e(k)) with lines \
         ls eta_ls(k) dt k title stack_title(k)

set title panel('pull-off, load control', 2)
set xlabel 'η = T / (π w R^2/E_{top}^*)^{1/3}'
set ylabel 'P = F / (π w R)'
unset logscale y
set autoscale y
set offsets 0, 0, graph 0.5, 0   # headroom for the key above the curves
set key top right
plot -1.5 ls 31 title 'JKR, homogeneous', \
     for [k = 1:3] word(pulloff, k) using (column(c_eta) / scale_eta(k)):(column(c_pl)) with linespoints \
         ls eta_ls(k) dt k pt 7 ps 0.6 title stack_title(k)

set title panel(sprintf('film E = %s, ν = %s on a substrate E = %s, ν = %s: bonded vs sliding', \
                    pair(film, 1), pair(film, 2), pair(film_base, 1), pair(film_base, 2)), 3)
set xlabel 'a/T'
set ylabel 'E_{eq} / E_{film}^*'
set offsets 0, 0, 0, 0
set logscale y
set key top left
plot for [k = 1:2] word(slip_reduced, k) using (column(c_a)):(column(c_e)) with lines \
         ls (k == 1 ? 21 : 22) title slip_title(k)

set title panel('pull-off, load control', 4)
set xlabel 'η = T / (π w R^2/E_{film}^*)^{1/3}'
set ylabel 'P = F / (π w R)'
unset logscale y
set offsets 0, 0, graph 0.4, 0
set key top right
plot -1.5 ls 31 title 'JKR, homogeneous', \
     for [k = 1:2] word(slip_pulloff, k) using (column(c_eta)):(column(c_pl)) with linespoints \
         ls (k == 1 ? 21 : 22) pt 7 ps 0.6 title slip_title(k)
unset multiplot
unset output
