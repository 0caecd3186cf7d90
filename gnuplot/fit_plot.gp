# The plot of one fit (`coatcontact fit ... --plot FILE.png|FILE.pdf`): data and fitted model
# with the predicted pull-offs (top), residuals in units of their sigma (bottom). The program
# sets the variables and reads the picture from stdout (it writes FILE atomically itself):
#   fitfile, curvefile   the fit table and the model curve (as --output and --curve write them)
#   xname                'a' or 'delta' (the data's abscissa: column 2 of both tables for a,
#                        column 2 of fitfile and 2 of curvefile for delta)
#   plottitle, fitlabel  title lines built from the user's parameters and estimates
#   term                 'png' or 'pdf'
#   lp_x, lp_F, dp_x, dp_F  pull-offs (load, displacement control) in SI; NaN when absent
if (term eq 'pdf') { set terminal pdfcairo size 7.5in,6in enhanced font 'Sans,9' } \
else { set terminal pngcairo size 1100,880 enhanced font 'Sans,11' }
set encoding utf8
xcol_curve = (xname eq 'a') ? 1 : 2
xlabel_text = (xname eq 'a') ? 'contact radius a (µm)' : 'penetration δ (µm)'
set style line 1 lc rgb '#1f77b4' pt 6 ps 0.8 lw 1.2   # data
set style line 2 lc rgb '#d62728' lw 2                 # model
set style line 3 lc rgb '#2ca02c' pt 7 ps 1.6          # load-controlled pull-off
set style line 4 lc rgb '#9467bd' pt 5 ps 1.4          # displacement-controlled pull-off
set style line 5 lc rgb '#555555' lw 1 dt 3            # zero
set grid lc rgb '#dddddd'
# a,F data span decades of a (and F): a log axis shows the adhesive end as well as the top.
if (xname eq 'a') { set logscale x; set autoscale xfix }
set multiplot title plottitle font ',12'
set lmargin at screen 0.11; set rmargin at screen 0.97
set tmargin at screen 0.88; set bmargin at screen 0.38
set format x ''
set ylabel 'force F (mN)'
set key top left box opaque
set title fitlabel font ',10'
plot curvefile u (column(xcol_curve)*1e6):($3*1e3) w l ls 2 t 'fitted model', \
     fitfile u ($2*1e6):($3*1e3) w p ls 1 t 'data', \
     '+' u (lp_x*1e6):(lp_F*1e3) every ::0::0 w p ls 3 t 'pull-off, load control', \
     '+' u (dp_x*1e6):(dp_F*1e3) every ::0::0 w p ls 4 t 'pull-off, displacement control', \
     0 w l ls 5 notitle
# The residual panel shares the x range of the panel above.
set xrange [GPVAL_X_MIN:GPVAL_X_MAX]
set tmargin at screen 0.36; set bmargin at screen 0.08
set format x '%g'
set xlabel xlabel_text
set ylabel 'residual / σ_{eff}'
set title ''
set key off
resid_col = (xname eq 'a') ? 5 : 6
sigma_col = (xname eq 'a') ? 6 : 8
plot fitfile u ($2*1e6):(column(resid_col)/column(sigma_col)) w p ls 1, 0 w l ls 5
unset multiplot
