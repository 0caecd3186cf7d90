# The modulus against depth of one AFM curve (`coatcontact afm fit FILE --depth-profile --plot
# FILE.png|pdf`; THEORY.md section 15, "Modulus against depth"): the fit's modulus (E, or the
# coating's E1) with its standard error against the deepest fitted indentation, and on a coating
# the half-space fit's apparent E of the same points beside it, with the depth where the
# indentation reaches the stated fraction of t. The program sets the variables and reads the
# picture from stdout (it writes FILE atomically itself):
#   datafile      columns: depth, max_indentation, modulus, modulus_error, apparent, apparent_error
#                 [m, m, Pa, Pa, Pa, Pa]; NaN where a depth has no estimate
#   term          'png' or 'pdf'
#   plottitle     title; modname the modulus's name ('E' or 'E1')
#   coated        1 on a coating (the apparent E and the fraction of t drawn), else 0
#   tlimit        [m] the fraction of t (NaN without a coating); tlabel its key entry
#   zs, zunit     scale and unit of the depth axis; es, eunit of the modulus axis
#   xhi, yhi      the axes' tops (scaled; the values and error bars with a margin; both from 0)
if (term eq 'pdf') { set terminal pdfcairo size 6in,4.2in enhanced font 'Sans,9' } \
else { set terminal pngcairo size 900,620 enhanced font 'Sans,11' }
set encoding utf8
set title plottitle font ',11'
set xlabel sprintf('largest fitted indentation δ_{max} (%s)', zunit)
set ylabel sprintf('modulus (%s)', eunit)
set grid lc rgb '#dddddd'
set key top left box opaque
set style line 1 lc rgb '#0072b2' pt 7 ps 1.1 lw 1.5    # the fit's modulus (Okabe-Ito blue)
set style line 2 lc rgb '#d55e00' pt 5 ps 1.0 lw 1.5    # apparent half-space E (vermillion)
set style line 3 lc rgb '#555555' lw 1.5 dt 2           # the fraction of t
set xrange [0:xhi]
set yrange [0:yhi]
if (coated) { set arrow 1 from first tlimit*zs, graph 0 to first tlimit*zs, graph 1 nohead ls 3 }
if (coated) {
  plot datafile u ($2*zs):($3*es):($4*es) w yerrorlines ls 1 t sprintf('%s, coated fit (± 1 SE)', modname), \
       datafile u ($2*zs):($5*es):($6*es) w yerrorlines ls 2 t 'E, half-space fit (apparent, ± 1 SE)', \
       NaN w l ls 3 t tlabel
} else {
  plot datafile u ($2*zs):($3*es):($4*es) w yerrorlines ls 1 t sprintf('%s (± 1 SE)', modname)
}
