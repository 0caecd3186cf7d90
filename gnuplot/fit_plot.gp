# The plot of one fit (`coatcontact fit ... --plot FILE.png|FILE.pdf`): data and fitted model
# (top), the low-force region with the tensile points and the predicted pull-offs (middle),
# residuals in units of their sigma (bottom). The program sets the variables and reads the
# picture from stdout (it writes FILE atomically itself):
#   fitfile, curvefile   the fit table and the model curve (as --output and --curve write them)
#   xname                'a' or 'delta' (the data's abscissa: column 2 of both tables for a,
#                        column 2 of fitfile and 2 of curvefile for delta)
#   plottitle, fitlabel  title lines built from the user's parameters and estimates
#   term                 'png' or 'pdf'
#   lp_x, lp_F, dp_x, dp_F  pull-offs (load, displacement control) in SI; NaN when absent
#   spring_k             for xname 'z': the spring [N/m]; the model is drawn at z = delta + F/k
if (term eq 'pdf') { set terminal pdfcairo size 7.5in,7.5in enhanced font 'Sans,9' } \
else { set terminal pngcairo size 1100,1100 enhanced font 'Sans,11' }
set encoding utf8
xcol_curve = (xname eq 'a') ? 1 : 2
# The model's abscissa: a, delta, or the base displacement z = delta + F/k.
model_x(delta_or_a, F) = (xname eq 'z') ? delta_or_a + F / spring_k : delta_or_a
set style line 1 lc rgb '#1f77b4' pt 6 ps 0.8 lw 1.2   # data
set style line 2 lc rgb '#d62728' lw 2                 # model
set style line 3 lc rgb '#2ca02c' pt 7 ps 1.6          # load-controlled pull-off
set style line 4 lc rgb '#9467bd' pt 5 ps 1.4          # displacement-controlled pull-off
set style line 5 lc rgb '#555555' lw 1 dt 3            # zero
set grid lc rgb '#dddddd'

# SI prefixes chosen per quantity from its largest magnitude: 1 <= |value| < 1000.
si_exp(v) = (v > 0 && v < 1e300) ? 3 * floor(log10(v) / 3.0 + 1e-9) : 0
si_name(e) = e == -15 ? 'f' : e == -12 ? 'p' : e == -9 ? 'n' : e == -6 ? 'µ' : e == -3 ? 'm' : \
             e == 0 ? '' : e == 3 ? 'k' : e == 6 ? 'M' : sprintf('10^{%d} ', e)
stats fitfile using 2:3 nooutput
x_big = STATS_max_x; F_big = (abs(STATS_min_y) > abs(STATS_max_y)) ? abs(STATS_min_y) : abs(STATS_max_y)
F_data_min = STATS_min_y
stats curvefile using (model_x(column(xcol_curve), $3)) nooutput
x_lo = (xname eq 'a') ? STATS_min : 0; x_hi = STATS_max
if (xname eq 'a') { stats fitfile using 2 nooutput; if (STATS_min < x_lo) { x_lo = STATS_min } }
if (x_big > x_hi) { x_hi = x_big }
x_e = si_exp(x_hi); x_s = 10.0 ** -x_e
F_e = si_exp(F_big); F_s = 10.0 ** -F_e
xlabel_text = (xname eq 'a') ? sprintf('contact radius a (%sm)', si_name(x_e)) : \
              (xname eq 'z') ? sprintf('base displacement z = δ + F/k (%sm)', si_name(x_e)) : \
              sprintf('penetration δ (%sm)', si_name(x_e))
# The low-force panel: from below the most tensile of data and pull-offs to a few times its size.
F_neg = F_data_min
if (lp_F == lp_F && lp_F < F_neg) { F_neg = lp_F }
if (dp_F == dp_F && dp_F < F_neg) { F_neg = dp_F }
F_neg = F_neg < 0 ? -F_neg : (F_big > 0 ? 0.05 * F_big : 1)
L_e = si_exp(F_neg); L_s = 10.0 ** -L_e

# a,F data span decades of a (and F): a log axis, labelled at 1, 2, 5 per decade (and at
# every decade when the range is wide), shows the adhesive end as well as the top.
if (xname eq 'a') {
    set logscale x
    set xrange [x_lo * x_s : x_hi * x_s]
    # tics_bottom labels them (the residual panel), tics_blank only marks them (panels above).
    d_lo = floor(log10(x_lo * x_s)); d_hi = ceil(log10(x_hi * x_s))
    steps = (d_hi - d_lo > 3) ? '1' : '1 2 5'
    tics_bottom = 'set xtics ('; tics_blank = 'set xtics ('
    do for [d = d_lo : d_hi] {
        do for [m = 1:9] {
            v = m * 10.0 ** d
            sep = (d == d_lo && m == 1) ? '' : ', '
            labelled = strstrt(' '.steps.' ', sprintf(' %d ', m)) > 0
            tics_bottom = tics_bottom.sep.(labelled ? sprintf("'%g' %.12g 0", v, v) : sprintf("'' %.12g 1", v))
            tics_blank = tics_blank.sep.sprintf("'' %.12g %d", v, labelled ? 0 : 1)
        }
    }
    tics_bottom = tics_bottom.')'; tics_blank = tics_blank.')'
    eval tics_blank
} else {
    set autoscale xfix
}

set multiplot title plottitle font ',12'
set lmargin at screen 0.11; set rmargin at screen 0.97
set tmargin at screen 0.90; set bmargin at screen 0.60
set format x ''
set ylabel sprintf('force F (%sN)', si_name(F_e))
set key top left box opaque
set title fitlabel font ',10'
plot curvefile u (model_x(column(xcol_curve), $3)*x_s):($3*F_s) w l ls 2 t 'fitted model', \
     fitfile u ($2*x_s):($3*F_s) w p ls 1 t 'data', \
     '+' u (lp_x*x_s):(lp_F*F_s) every ::0::0 w p ls 3 t 'pull-off, load control', \
     '+' u (dp_x*x_s):(dp_F*F_s) every ::0::0 w p ls 4 t 'pull-off, displacement control', \
     0 w l ls 5 notitle
# The panels below share the x range of the one above.
set xrange [GPVAL_X_MIN:GPVAL_X_MAX]

set tmargin at screen 0.56; set bmargin at screen 0.33
set ylabel sprintf('force F (%sN)', si_name(L_e))
set yrange [-1.35 * F_neg * L_s : 3 * F_neg * L_s]
set title 'low-force region: tensile points and the predicted pull-offs' font ',10'
set key off
plot curvefile u (model_x(column(xcol_curve), $3)*x_s):($3*L_s) w l ls 2, \
     fitfile u ($2*x_s):($3*L_s) w p ls 1, \
     '+' u (lp_x*x_s):(lp_F*L_s) every ::0::0 w p ls 3, \
     '+' u (dp_x*x_s):(dp_F*L_s) every ::0::0 w p ls 4, \
     0 w l ls 5
set autoscale y

set tmargin at screen 0.29; set bmargin at screen 0.07
set format x '%g'
if (xname eq 'a') { eval tics_bottom }
set xlabel xlabel_text
set ylabel 'residual / σ_{eff}'
set title ''
resid_col = (xname eq 'a') ? 5 : 6
sigma_col = (xname eq 'a') ? 6 : 8
plot fitfile u ($2*x_s):(column(resid_col)/column(sigma_col)) w p ls 1, 0 w l ls 5
unset multiplot
