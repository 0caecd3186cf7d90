# Heat maps of a batch AFM fit (`coatcontact afm fit MAP|FILES|FOLDER ... --map-plot FILE.png|pdf`):
# one panel per free estimate, chi2/dof, the measured pull-off and the flags, each curve a cell
# at its grid position; a one-row map (a line) is drawn as profiles, value against position.
# The program sets the variables and reads the picture from stdout (it writes FILE atomically):
#   mapfile        TSV: x, y, flag, one column per estimate (names), chi2/dof, pull-off [N];
#                  '-' where a flagged curve has no value
#   term           'png' or 'pdf'
#   plottitle      title line
#   names, units   the estimates' names and SI units, blank-separated
#   expos, present, vmin, vmax   per value column (estimates, chi2/dof, pull-off), blank-separated:
#                  the power of ten of its unit prefix, 1 when any curve has a value, the
#                  smallest and largest value (SI)
#   cbfix, cblo, cbhi   1: moduli (unit Pa) use the colour range [cblo, cbhi] Pa (--color-range)
#   cblog          1: moduli on a log colour scale (--color-log)
#   flagsin, flagnames  the flags present (numbers); all flag names, in flag order
#   positions      1: x, y are positions [m]; 0: grid indices
#   profile        0: a map; 1: one row (values against x); 2: one column (against y)
#   dx, dy         cell size (grid pitch); xlo, xhi, ylo, yhi: the plotted area
#   rangefile      '' or a file to which the colour (profile: y) range of each panel is
#                  appended as name, min, max in SI (used by the tests)
set datafile separator '\t'
set datafile missing '-'
panels = words(names) + 3
cols = (panels <= 4) ? 2 : 3
rows = int(ceil(panels / (cols * 1.0)))
if (term eq 'pdf') { set terminal pdfcairo size cols * 3.6 + 0.5, rows * 2.9 + 0.4 enhanced font 'Sans,8' } \
else { set terminal pngcairo size cols * 460 + 60, rows * 370 + 40 enhanced font 'Sans,10' }
set encoding utf8
ps = positions ? 1e6 : 1.0               # positions in µm
set tics out nomirror
# viridis (perceptually uniform, readable with colour-blindness and in grey)
viridis = "set palette defined (0 '#440154', 1 '#482878', 2 '#3e4989', 3 '#31688e', 4 '#26828e', 5 '#1f9e89', 6 '#35b779', 7 '#6ece58', 8 '#b5de2b', 9 '#fde725')"
@viridis
pname(e) = e == -15 ? 'f' : e == -12 ? 'p' : e == -9 ? 'n' : e == -6 ? 'µ' : e == -3 ? 'm' : e == 0 ? '' : e == 3 ? 'k' : e == 6 ? 'M' : e == 9 ? 'G' : sprintf('1e%d ', e)
cell(c, s) = column(c) * s
# Enough decimals that neighbouring tick labels differ (ticks at least a tenth of the span apart).
decimals(lo, hi) = (hi > lo) ? min(12, max(0, -floor(log10((hi - lo) / 10.0)))) : 2
min(a, b) = a < b ? a : b
fixed(lo, hi) = sprintf('%%.%df', decimals(lo, hi))
max(a, b) = a > b ? a : b
set format x sprintf('%%.%df', decimals(xlo * ps, xhi * ps))
set format y sprintf('%%.%df', decimals(ylo * ps, yhi * ps))
xname = positions ? 'x (µm)' : 'grid index x'
yname = positions ? 'y (µm)' : 'grid index y'
# Colour (profile: y) range of value column i in its plotted unit, s = 10**(-e): the data's
# extremes (every cell counted), or --color-range for a modulus; widened when flat.
ismod(i) = (i <= words(names)) && (word(units, i) eq 'Pa')
rlo(i, s) = (cbfix && ismod(i)) ? cblo * s : real(word(vmin, i)) * s
rhi(i, s) = (cbfix && ismod(i)) ? cbhi * s : real(word(vmax, i)) * s
pad(v) = (v == 0) ? 1.0 : abs(v) * 0.01
if (profile == 0) {
  set xlabel xname
  set ylabel yname
  set size ratio -1
  set xrange [xlo * ps : xhi * ps]
  set yrange [ylo * ps : yhi * ps]
  # grey where the grid has no value (no curve there, or a flagged one)
  set object 1 rectangle from graph 0, 0 to graph 1, 1 back fillcolor rgb '#d9d9d9' fillstyle solid 1.0 noborder
} else {
  set xlabel (profile == 1 ? xname : yname)
  if (profile == 1) { set xrange [xlo * ps : xhi * ps] } else { set xrange [ylo * ps : yhi * ps]; set format x sprintf('%%.%df', decimals(ylo * ps, yhi * ps)) }
  set grid lc rgb '#dddddd' lw 0.5 dt solid
}
# the position along a profile
pos(dummy) = column(profile == 2 ? 2 : 1) * ps
set multiplot layout rows, cols title plottitle font ',12'
do for [i = 1:words(names) + 2] {
  e = int(word(expos, i))
  s = 10.0**(-e)
  id = (i <= words(names)) ? word(names, i) : (i == words(names) + 1) ? 'chi2_per_dof' : 'pulloff'
  name = (i <= words(names)) ? sprintf('%s (%s%s)', word(names, i), pname(e), word(units, i)) : \
         (i == words(names) + 1) ? 'χ²/dof' : sprintf('pull-off, retract (%sN)', pname(e))
  lo = rlo(i, s)
  hi = rhi(i, s)
  uselog = cblog && ismod(i)
  if (word(present, i) eq '1' && hi <= lo) { lo = lo - pad(lo); hi = hi + pad(hi) }
  if (word(present, i) eq '1' && uselog && !cbfix) { lo = lo / 1.01; hi = hi * 1.01 }
  # a profile's points off the frame: 5 % of the span each side
  if (word(present, i) eq '1' && profile != 0 && !(cbfix && ismod(i))) {
    if (uselog) { m = (hi / lo)**0.05; lo = lo / m; hi = hi * m } else { m = (hi - lo) * 0.05; lo = lo - m; hi = hi + m }
  }
  if (word(present, i) eq '1' && profile == 0) {
    set title name noenhanced
    set colorbox
    # log scale: five labelled ticks evenly spaced in log (a narrow range holds no 1-2-5 value)
    if (uselog) { set logscale cb; set cbtics (); sig = max(3, ceil(-log10((hi / lo)**0.25 - 1)) + 1); \
                  do for [k = 0:4] { v = lo * (hi / lo)**(k / 4.0); set cbtics add (sprintf(sprintf('%%.%dg', sig), v) v) } } \
    else { unset logscale cb; set format cb fixed(lo, hi); set cbtics autofreq }
    set cbrange [lo : hi]
    # a cell without a value is left out (drawn, it would be painted white)
    plot mapfile using (valid(3 + i) ? $1 * ps : NaN):($2 * ps):(dx * ps / 2):(dy * ps / 2):(cell(3 + i, s)) \
         with boxxyerror fs solid 1.0 noborder lc palette notitle
    if (rangefile ne '') { set print rangefile append; print sprintf("%s\t%.10g\t%.10g", id, GPVAL_CB_MIN / s, GPVAL_CB_MAX / s); unset print }
  }
  if (word(present, i) eq '1' && profile != 0) {
    set title name noenhanced
    set ylabel name noenhanced
    if (uselog) { set logscale y; set format y '%.3g' } else { unset logscale y; set format y fixed(lo, hi) }
    set yrange [lo : hi]
    plot mapfile using (pos(0)):(cell(3 + i, s)) with linespoints pt 7 ps 0.8 lc rgb '#31688e' notitle
    if (rangefile ne '') { set print rangefile append; print sprintf("%s\t%.10g\t%.10g", id, GPVAL_Y_MIN / s, GPVAL_Y_MAX / s); unset print }
    unset logscale y
    set ylabel ''
  }
  if (word(present, i) ne '1') {
    # a column without any value (every curve flagged): the grid's cells in grey
    set title name . ': no value' noenhanced
    unset colorbox
    if (profile == 0) {
      plot mapfile using ($1 * ps):($2 * ps):(dx * ps / 2):(dy * ps / 2) with boxxyerror fs solid 1.0 noborder lc rgb '#bdbdbd' notitle
    } else {
      set yrange [0:1]
      plot mapfile using (pos(0)):(0.5) with points pt 7 lc rgb '#bbbbbb' notitle
    }
  }
}
# Flags: one colour per flag present, named in the key (Okabe-Ito colours, colour-blind safe).
flagcolors = "#009e73 #0072b2 #e69f00 #d55e00 #cc79a7 #56b4e9 #f0e442 #999999 #000000 #7f3c8d #882255 #44aa99"
fcol(f) = word(flagcolors, (f % 12) + 1)
set title 'flag'
unset colorbox
unset logscale cb
set key outside right top vertical Left reverse noenhanced samplen 1 spacing 1.1
if (profile == 0) {
  plot for [k in flagsin] mapfile using ($3 == int(k) ? $1 * ps : NaN):($2 * ps):(dx * ps / 2):(dy * ps / 2) \
       with boxxyerror fs solid 1.0 noborder lc rgb fcol(int(k)) title word(flagnames, int(k) + 1)
} else {
  unset grid
  set ylabel ''
  set ytics ('' 0)
  set yrange [-1:1]
  plot for [k in flagsin] mapfile using ($3 == int(k) ? pos(0) : NaN):(0) \
       with points pt 5 ps 1.5 lc rgb fcol(int(k)) title word(flagnames, int(k) + 1)
}
unset multiplot
