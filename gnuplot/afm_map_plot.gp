# Heat maps of a batch AFM fit (`coatcontact afm fit MAP|FILES|FOLDER ... --map-plot FILE.png|pdf`):
# one panel per free estimate, chi2/dof, the measured pull-off and the flags, each curve a cell
# at its grid position. The program sets the variables and reads the picture from stdout (it
# writes FILE atomically itself):
#   mapfile        TSV: x, y, flag, one column per estimate (names), chi2/dof, pull-off [N];
#                  '-' where a flagged curve has no value
#   term           'png' or 'pdf'
#   plottitle      title line
#   names, units   the estimates' names and SI units, blank-separated
#   positions      1: x, y are positions [m]; 0: grid indices
#   dx, dy         cell size (grid pitch); xlo, xhi, ylo, yhi: the plotted area
set datafile separator '\t'
set datafile missing '-'
panels = words(names) + 3
cols = (panels <= 4) ? 2 : 3
rows = int(ceil(panels / (cols * 1.0)))
if (term eq 'pdf') { set terminal pdfcairo size cols * 3.4, rows * 2.9 + 0.4 enhanced font 'Sans,8' } \
else { set terminal pngcairo size cols * 430, rows * 370 + 40 enhanced font 'Sans,10' }
set encoding utf8
ps = positions ? 1e6 : 1.0               # positions in µm
set xlabel (positions ? 'x (µm)' : 'grid index x')
set ylabel (positions ? 'y (µm)' : 'grid index y')
set size ratio -1
set tics out nomirror
set palette rgbformulae 33,13,10
# The engineering prefix of a column's largest magnitude.
pexp(v) = (v > 0) ? 3 * floor(log10(v) / 3.0 + 1e-9) : 0
pname(e) = e == -15 ? 'f' : e == -12 ? 'p' : e == -9 ? 'n' : e == -6 ? 'µ' : e == -3 ? 'm' : e == 0 ? '' : e == 3 ? 'k' : e == 6 ? 'M' : e == 9 ? 'G' : sprintf('1e%d ', e)
cell(c, s) = column(c) * s
# Each column's prefix, before the ranges are set (stats honours them).
array expo[words(names) + 2]
do for [i = 1:words(names) + 2] {
  stats mapfile using (abs(column(3 + i))) nooutput
  expo[i] = (STATS_records > 0) ? pexp(STATS_max) : 0
}
set xrange [xlo * ps : xhi * ps]
set yrange [ylo * ps : yhi * ps]
set multiplot layout rows, cols title plottitle font ',12'
do for [i = 1:words(names)] {
  e = expo[i]
  set title sprintf('%s (%s%s)', word(names, i), pname(e), word(units, i)) noenhanced
  unset cbrange
  plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2):(cell(3 + i, 10.0**(-e))) \
       with boxxyerror fs solid 1.0 noborder lc palette notitle
}
set title 'χ²/dof'
plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2):(column(4 + words(names))) \
     with boxxyerror fs solid 1.0 noborder lc palette notitle
e = expo[words(names) + 2]
set title sprintf('pull-off, retract (%sN)', pname(e))
plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2):(cell(5 + words(names), 10.0**(-e))) \
     with boxxyerror fs solid 1.0 noborder lc palette notitle
set title 'flag'
set cbrange [-0.5:9.5]
set cbtics ('fitted' 0, 'no contact' 1, 'jump-in' 2, 'no convergence' 3, 'empty segment' 4, 'missing segment' 5, 'calibration' 6, 'too few points' 7, 'unreadable' 8, 'bad data' 9) font ',8'
set palette maxcolors 10
set palette defined (0 '#2ca02c', 1 '#1f77b4', 2 '#ff7f0e', 3 '#d62728', 4 '#9467bd', 5 '#8c564b', 6 '#e377c2', 7 '#7f7f7f', 8 '#bcbd22', 9 '#17becf')
plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2):3 \
     with boxxyerror fs solid 1.0 noborder lc palette notitle
unset multiplot
