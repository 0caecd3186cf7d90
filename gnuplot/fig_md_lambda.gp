# Figure beyond the paper (THEORY.md section 13): load-controlled pull-off force versus the
# Maugis-Dugdale parameter lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3, one curve
# per eta, on the soft film (left) and the stiff film (right). References: the homogeneous
# Maugis (1992) curve, DMT (-2, lambda -> 0), JKR of the homogeneous solid (-3/2) and each
# eta's JKR pull-off on the coating (short dashes at the right: lambda -> infinity).
# Inputs: ratios (two), etas, md (two `pulloff --lambda` files), jkr (two `pulloff` files),
# homogeneous (one `pulloff --lambda` file).

W = 1400; H = 640
load gpdir.'/style.gp'

f1 = word(md, 1)
h = columns_of(f1)
eval need('c_eta', h, 'eta', f1)
eval need('c_lambda', h, 'lambda', f1)
eval need('c_pl', h, 'P_load', f1)
hj = columns_of(word(jkr, 1))
eval need('j_eta', hj, 'eta', word(jkr, 1))
eval need('j_pl', hj, 'P_load', word(jkr, 1))

stats homogeneous using (column(c_lambda)) nooutput
l_min = STATS_min; l_max = STATS_max
near(a, b) = abs(a - b) <= 1e-9 * abs(b)

set multiplot layout 1, 2 title figure_title(sprintf("Maugis-Dugdale zone on a coating: pull-off force versus λ (load control),  %s", nu_label)) font ',14' margins (paper ? 0.1 : 0.07), 0.97, 0.13, (paper ? 0.9 : 0.86) spacing 0.08, 0
# The x axis is log10(lambda) on a linear scale, labelled as a log axis, so that the splines
# through the computed points are smooth in log(lambda) (gnuplot smooths in linear x).
lg(x) = log10(x)
set xrange [lg(l_min) : lg(l_max * 3)]
set xtics () 
do for [d = floor(lg(l_min)) : ceil(lg(l_max * 3))] {
    eval sprintf("set xtics add ('10^{%d}' %d)", d, d)
    do for [m = 2:9] { eval sprintf("set xtics add ('' %.12g 1)", d + lg(m)) }
}
set xlabel 'λ = 2σ_0 (R / (π w K^2))^{1/3},   K = 4E_1^*/3'
set ylabel 'pull-off force  P = F / (π w R)'
set key top left
# In print: short titles in two columns (the long key ran past the panel into the next one and
# over the JKR label); captions.txt says the rest.
if (paper) { set key maxrows 3 }
set yrange [-2.1 : *]
set offsets 0, 0, graph 0.45, 0   # headroom for the key above the curves

do for [side = 1:2] {
    r = real(word(ratios, side))
    file = word(md, side)
    jfile = word(jkr, side)
    set title panel(materials_label(r), side)
    set label 1 'DMT  -2' at graph 0.6, first -2 offset 0, -0.9 left tc ls 32 front
    # Above the line on the soft film; below it on the stiff one, whose thin films' curves pass above.
    set label 2 'JKR  -3/2' at graph 0.6, first -1.5 offset 0, (side == 1 ? 0.7 : -0.9) left tc ls 31 front
    # JKR pull-off of each eta on this coating, drawn beyond the largest lambda.
    jkr_values = ''
    do for [k = 1:words(etas)] {
        e = real(word(etas, k))
        stats jfile using (near(column(j_eta), e) ? column(j_pl) : NaN) nooutput
        jkr_values = jkr_values . sprintf(' %.12g', STATS_min)
    }
    plot -2 ls 32 notitle, -1.5 ls 31 notitle, \
         homogeneous using (lg(column(c_lambda))):(column(c_pl)) smooth mcsplines with lines ls 31 lw 2.4 \
             title (paper ? 'homogeneous' : 'homogeneous (Maugis 1992)'), \
         for [k = 1:words(etas)] file \
             using (near(column(c_eta), real(word(etas, k))) ? lg(column(c_lambda)) : NaN):(column(c_pl)) \
             smooth mcsplines with lines ls eta_ls(k) title sprintf('η = %s', word(etas, k)), \
         for [k = 1:words(etas)] file \
             using (near(column(c_eta), real(word(etas, k))) ? lg(column(c_lambda)) : NaN):(column(c_pl)) \
             with points ls eta_ls(k) pt 7 ps 0.6 notitle, \
         NaN with points lc rgb '#555555' pt 7 ps 0.6 title (paper ? 'computed λ' : 'computed λ (lines: monotone splines in log λ)'), \
         NaN with lines ls 31 lw 1.4 dt 2 title (paper ? 'λ → ∞ (JKR)' : 'JKR on the coating (λ → ∞)'), \
         for [k = 1:words(etas)] '+' using (x = l_max * (1.3 + 0.35 * $0 / 10.0), lg(x)):(real(word(jkr_values, k))) \
             every ::0::10 with lines ls eta_ls(k) dt 2 notitle
    unset label 1
    unset label 2
}
unset multiplot
unset output
