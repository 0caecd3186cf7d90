# Control plots of a batch (`coatcontact afm fit MAP|FILES|FOLDER --curve-plots FILE.pdf`): one
# page per curve, in the table's curve order. Top: the force against the tip position in the
# contact region (from the deepest point to two largest indentations above the contact point), the
# approach (and the retract of a retract fit), fitted points dark and the others light, the
# model over the fitted segment and the contact point; bottom: the residuals (model - data) of
# the fitted points. A curve without estimates shows its data (when it has any) and its flag.
# The program sets the variables and reads the PDF from stdout (it writes FILE atomically):
#   datafile     one block per page (`index i-1`), columns: tip position [m], force [N], model
#                [N] (NaN off the fitted segment), residual [N] (NaN for points not fitted),
#                segment (0 approach, 1 retract), fitted (0/1)
#   N            pages; per page i (arrays 1..N):
#   T[i], K[i]   title (file, curve, grid place, flag, rating) and the estimates' line
#   HAS[i]       1: the block has data; RES[i] 1: the curve has estimates (model and residuals)
#   ZS[i], ZU[i], FS[i], FU[i]  scale and unit of the tip-position and force axes
#   XLO[i], XHI[i]  the tip-position window (scaled)
#   ZC[i]        fitted contact point [m] (NaN: none); RET[i] 1: a retract fit (its retract drawn)
set terminal pdfcairo size 7.5in,5.5in enhanced font 'Sans,9'
set encoding utf8
set grid lc rgb '#dddddd'
# Okabe-Ito colours (colour-blind safe): approach blue, retract vermillion; light when not fitted.
approach_fit = 0x0072b2; approach_other = 0xa6c8e0; retract_fit = 0xd55e00; retract_other = 0xf2bfa0
colour(seg, fitted) = seg < 0.5 ? (fitted > 0.5 ? approach_fit : approach_other) : (fitted > 0.5 ? retract_fit : retract_other)
set style line 2 lc rgb '#000000' lw 1.8                 # model
set style line 4 lc rgb '#009e73' lw 1.5 dt 2            # contact point (bluish green)
set style line 5 lc rgb '#555555' lw 1 dt 3              # zero
do for [i=1:N] {
  set multiplot title T[i] font ',11'
  set lmargin at screen 0.11; set rmargin at screen 0.97
  set tmargin at screen 0.86; set bmargin at screen 0.36
  set autoscale
  set xrange [XLO[i]:XHI[i]]
  unset arrow 1
  unset label 1
  set title K[i] font ',9'
  set format x ''
  unset xlabel
  set ylabel sprintf('force F (%s)', FU[i])
  set key top right box opaque
  if (ZC[i] == ZC[i]) { set arrow 1 from first ZC[i]*ZS[i], graph 0 to first ZC[i]*ZS[i], graph 1 nohead ls 4 }
  if (HAS[i] + RES[i] == 2) {
    plot datafile index (i-1) u ($1*ZS[i]):($2*FS[i]):(colour($5, $6)) w p pt 7 ps 0.3 lc rgb variable notitle, \
         NaN w p pt 7 ps 0.6 lc rgb '#0072b2' t 'approach (fitted dark)', \
         NaN w p pt 7 ps 0.6 lc rgb '#d55e00' t (RET[i] == 1 ? 'retract (fitted dark)' : ''), \
         datafile index (i-1) u ($1*ZS[i]):($3*FS[i]) w l ls 2 t 'model', \
         NaN w l ls 4 t 'contact point'
  } else { if (HAS[i] == 1) {
    plot datafile index (i-1) u ($1*ZS[i]):($2*FS[i]):(colour($5, 0)) w p pt 7 ps 0.3 lc rgb variable notitle, \
         NaN w p pt 7 ps 0.6 lc rgb '#a6c8e0' t 'data (no estimates)'
  } else {
    set xrange [0:1]; set yrange [0:1]
    set key off
    set label 1 'no data to draw (see the flag above)' at graph 0.5, 0.5 center
    plot NaN notitle
  } }
  # Bottom: the residuals of the fitted points.
  set tmargin at screen 0.33; set bmargin at screen 0.09
  set autoscale
  set xrange [XLO[i]:XHI[i]]
  unset arrow 1
  unset label 1
  set title ''
  set format x '%g'
  set xlabel sprintf('tip position z (%s)   [the tip indents the sample for z < z_c]', ZU[i])
  set ylabel sprintf('model - data (%s)', FU[i])
  set key off
  if (ZC[i] == ZC[i]) { set arrow 1 from first ZC[i]*ZS[i], graph 0 to first ZC[i]*ZS[i], graph 1 nohead ls 4 }
  if (HAS[i] + RES[i] == 2) {
    plot datafile index (i-1) u ($1*ZS[i]):($4*FS[i]):(colour($5, 1)) w p pt 7 ps 0.3 lc rgb variable, 0 w l ls 5
  } else {
    if (HAS[i] == 0) { set xrange [0:1] }
    set yrange [-1:1]
    set label 1 'no residuals: the curve has no estimates' at graph 0.5, 0.5 center
    plot NaN notitle
  }
  unset multiplot
}
