# The plot of one AFM curve fit (`coatcontact afm fit FILE ... --plot FILE.png|FILE.pdf`): the
# segment's force against tip position with the fitted points, the model, the contact point and
# the retract's pull-off (top: whole segment; middle: the contact region), and the residuals of
# the fitted points in the contact region (bottom). The program
# sets the variables and reads the picture from stdout (it writes FILE atomically itself):
#   fitfile              the table of `afm fit` (columns point, tip_position_m, indentation_m,
#                        force_N, model_force_N, residual_N, fitted)
#   term                 'png' or 'pdf'
#   plottitle, fitlabel  title lines
#   zs, zunit, fs, funit scale and unit of the tip position and of the force axes
#   zc, base             fitted contact point [m] and baseline [N]
#   zlo, zhi             tip positions [m] of the zoomed contact region (middle and bottom)
#   po_z, po_F           the retract's pull-off (tip position [m], force [N]); NaN when absent
if (term eq 'pdf') { set terminal pdfcairo size 7.5in,8in enhanced font 'Sans,9' } \
else { set terminal pngcairo size 1100,1150 enhanced font 'Sans,11' }
set encoding utf8
set style line 1 lc rgb '#1f77b4' pt 7 ps 0.35        # fitted data
set style line 6 lc rgb '#bbbbbb' pt 7 ps 0.3         # data outside the fit range
set style line 2 lc rgb '#d62728' lw 2                # model
set style line 3 lc rgb '#2ca02c' pt 9 ps 2.0         # pull-off
set style line 4 lc rgb '#9467bd' lw 1.5 dt 2         # contact point
set style line 5 lc rgb '#555555' lw 1 dt 3           # baseline / zero
set grid lc rgb '#dddddd'

set multiplot title plottitle font ',12'
set lmargin at screen 0.11; set rmargin at screen 0.97
# Top: the whole segment.
set tmargin at screen 0.90; set bmargin at screen 0.68
set ylabel sprintf('force F (%s)', funit)
set xlabel sprintf('tip position z (%s)', zunit) offset 0,0.6
set key top right box opaque
set title 'whole segment' font ',10'
set arrow 1 from first zc*zs, graph 0 to first zc*zs, graph 1 nohead ls 4
plot fitfile u ($7 == 0 ? $2*zs : NaN):($4*fs) w p ls 6 t 'data (not fitted)', \
     fitfile u ($7 == 1 ? $2*zs : NaN):($4*fs) w p ls 1 t 'data (fitted)', \
     fitfile u ($2*zs):($5*fs) w l ls 2 t 'fitted model', \
     '+' u (po_z*zs):(po_F*fs) every ::0::0 w p ls 3 t 'pull-off (retract, measured)', \
     NaN w l ls 4 t 'contact point'
unset xlabel
# Middle: the contact region, [z_min, z_c + 2 (largest indentation)].
set xrange [zlo*zs : zhi*zs]
set tmargin at screen 0.60; set bmargin at screen 0.31
set format x ''
set key top right box opaque
set title fitlabel font ',10'
plot fitfile u ($7 == 0 ? $2*zs : NaN):($4*fs) w p ls 6 notitle, \
     fitfile u ($7 == 1 ? $2*zs : NaN):($4*fs) w p ls 1 notitle, \
     fitfile u ($2*zs):($5*fs) w l ls 2 notitle, \
     '+' u (po_z*zs):(po_F*fs) every ::0::0 w p ls 3 notitle, \
     base*fs w l ls 5 t 'fitted baseline'
# Bottom: residuals of the fitted points in the same window.
set tmargin at screen 0.29; set bmargin at screen 0.08
set format x '%g'
set xlabel sprintf('tip position z (%s)   [the tip indents the sample for z < z_c]', zunit)
set ylabel sprintf('model - data (%s)', funit)
set title ''
set key off
plot fitfile u ($7 == 1 ? $2*zs : NaN):($6*fs) w p ls 1, 0 w l ls 5
unset multiplot
