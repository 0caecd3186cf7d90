# The plots of `coatcontact indent analyse|film FILE ... --plot FILE.png|FILE.pdf`. The program
# sets the variables and reads the picture from stdout (it writes FILE atomically itself):
#   datafile     the command's table; for analyse a second block (after two blank lines) holds
#                the whole test's depth [m] and load [N]
#   mode         'analyse' (load-depth; E and H against depth) or 'film' / 'thickness' (the
#                film's modulus or thickness against depth, one curve per model)
#   term         'png' or 'pdf'
#   plottitle    the test and the file
#   emean, hmean (analyse) the averages over the range [Pa]
#   models, nmodels (film) the models' names, in the order of the table's column pairs
#   ymax         (film) top of the modulus axis [Pa] (the first contact's values run off it)
if (term eq 'pdf') { set terminal pdfcairo size 7.5in,6in enhanced font 'Sans,9' } \
else { set terminal pngcairo size 1100,850 enhanced font 'Sans,11' }
set encoding utf8
set grid lc rgb '#dddddd'
set datafile missing '-'
set key box opaque
if (mode eq 'analyse') {
  set multiplot layout 2,1 title plottitle font ',12'
  set xlabel 'depth h (nm)'
  set ylabel 'load P (mN)'
  set key top left
  plot datafile index 1 u ($1 >= 0 ? $1*1e9 : NaN):($2*1e3) w l lw 2 lc rgb '#1f77b4' t 'load-depth (in contact, h >= 0)'
  set ylabel 'E, H (GPa)'
  set key top right
  set yrange [0:1.6*emean/1e9]   # the first contact's spikes off the scale
  plot datafile index 0 u ($1*1e9):($10 == 1 ? $8/1e9 : NaN) w p pt 7 ps 0.4 lc rgb '#d62728' t sprintf('E (range mean %.2f GPa)', emean/1e9), \
       datafile index 0 u ($1*1e9):($10 == 0 ? $8/1e9 : NaN) w p pt 7 ps 0.3 lc rgb '#f4a3a3' t 'E (outside the range)', \
       datafile index 0 u ($1*1e9):($10 == 1 ? $9/1e9 : NaN) w p pt 5 ps 0.4 lc rgb '#2ca02c' t sprintf('H (range mean %.2f GPa)', hmean/1e9), \
       datafile index 0 u ($1*1e9):($10 == 0 ? $9/1e9 : NaN) w p pt 5 ps 0.3 lc rgb '#a3d9a3' t 'H (outside the range)'
  unset multiplot
} else {
  set title plottitle font ',12'
  set xlabel 'depth h (nm)'
  set key outside right top
  if (mode eq 'film') {
    set ylabel 'Young''s modulus (GPa)'
    set yrange [0:ymax/1e9]
    colours = '#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd #8c564b #e377c2 #7f7f7f #bcbd22 #17becf #aec7e8'
    plot datafile u ($1*1e9):($7/1e9) w l lw 2 dt 2 lc rgb '#555555' t 'Oliver-Pharr (composite)', \
         for [k=1:nmodels] datafile u ($1*1e9):(column(7 + 2*k)/1e9) w lp lw (k == 1 ? 3 : 1.5) pt 7 ps 0.35 \
             lc rgb (word(models, k) eq 'exact' ? '#000000' : word(colours, k)) t word(models, k)
  } else {
    set ylabel 'film thickness (nm)'
    plot for [k=1:nmodels] datafile u ($1*1e9):(column(7 + 2*k)*1e9) w lp lw 2 pt 7 ps 0.35 t word(models, k)
  }
}
