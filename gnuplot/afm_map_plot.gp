# Heat maps of a batch AFM fit (`coatcontact afm fit MAP|FILES|FOLDER ... --map-plot FILE.png|pdf`):
# one panel per free estimate, chi2/dof, the measured pull-off and the flags, each curve a cell
# at its grid position. The program sets the variables and reads the picture from stdout (it
# writes FILE atomically itself):
#   mapfile        TSV: x, y, flag, one column per estimate (names), chi2/dof, pull-off [N];
#                  '-' where a flagged curve has no value
#   term           'png' or 'pdf'
#   plottitle      title line
#   names, units   the estimates' names and SI units, blank-separated
#   expos, present per value column (estimates, chi2/dof, pull-off), blank-separated: the
#                  power of ten of its unit prefix, and 1 when any curve has a value
#   positions      1: x, y are positions [m]; 0: grid indices
#   dx, dy         cell size (grid pitch); xlo, xhi, ylo, yhi: the plotted area
set datafile separator '\t'
set datafile missing '-'
panels = words(names) + 3
cols = (panels <= 4) ? 2 : 3
rows = int(ceil(panels / (cols * 1.0)))
if (term eq 'pdf') { set terminal pdfcairo size cols * 3.4 + 0.5, rows * 2.9 + 0.4 enhanced font 'Sans,8' } \
else { set terminal pngcairo size cols * 430 + 60, rows * 370 + 40 enhanced font 'Sans,10' }
set encoding utf8
ps = positions ? 1e6 : 1.0               # positions in µm
set xlabel (positions ? 'x (µm)' : 'grid index x')
set ylabel (positions ? 'y (µm)' : 'grid index y')
set size ratio -1
set tics out nomirror
set palette rgbformulae 33,13,10
set format cb '%.5g'
pname(e) = e == -15 ? 'f' : e == -12 ? 'p' : e == -9 ? 'n' : e == -6 ? 'µ' : e == -3 ? 'm' : e == 0 ? '' : e == 3 ? 'k' : e == 6 ? 'M' : e == 9 ? 'G' : sprintf('1e%d ', e)
cell(c, s) = column(c) * s
set xrange [xlo * ps : xhi * ps]
set yrange [ylo * ps : yhi * ps]
set multiplot layout rows, cols title plottitle font ',12'
# One panel per value column (4 .. 3 + words(names) + 2): estimates, chi2/dof, pull-off; a
# column without any value (every curve flagged) shows the grid's cells in grey.
do for [i = 1:words(names) + 2] {
  e = int(word(expos, i))
  name = (i <= words(names)) ? sprintf('%s (%s%s)', word(names, i), pname(e), word(units, i)) : \
         (i == words(names) + 1) ? 'χ²/dof' : sprintf('pull-off, retract (%sN)', pname(e))
  if (word(present, i) eq '1') {
    set title name noenhanced
    set colorbox
    plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2):(cell(3 + i, 10.0**(-e))) \
         with boxxyerror fs solid 1.0 noborder lc palette notitle
  } else {
    set title name . ': no value' noenhanced
    unset colorbox
    plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2) \
         with boxxyerror fs solid 1.0 noborder lc rgb '#dddddd' notitle
  }
}
set colorbox
set title 'flag'
set cbrange [-0.5:9.5]
set cbtics ('fitted' 0, 'no contact' 1, 'jump-in' 2, 'no conv.' 3, 'empty seg.' 4, 'no segment' 5, 'calibration' 6, 'few points' 7, 'unreadable' 8, 'bad data' 9) font ',8'
set palette maxcolors 10
set palette defined (0 '#2ca02c', 1 '#1f77b4', 2 '#ff7f0e', 3 '#d62728', 4 '#9467bd', 5 '#8c564b', 6 '#e377c2', 7 '#7f7f7f', 8 '#bcbd22', 9 '#17becf')
plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2):3 \
     with boxxyerror fs solid 1.0 noborder lc palette notitle
unset multiplot
