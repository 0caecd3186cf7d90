# Shared style of every figure (loaded first by each figN.gp).
#
# Inputs (gnuplot -e, set by gnuplot/figures.mk): fmt = 'png' | 'pdf', outfile, gpdir,
# nu1, nu0; the figure script sets W, H (size in pixels; the PDF gets W/72 x H/72 inches,
# the same layout) before loading this file.
#
# Line styles, the same meaning in every figure:
#   ls 1-5    eta series (figs 2, 5, 6, 7): sequential colours, thin film (small eta) dark
#   ls 11-15  modulus-ratio series E1*/E0* = 0.01, 0.1, 1, 10, 100 (figs 8, 9):
#             soft films blue, homogeneous black, stiff films red; see ratio_ls(r)
#   ls 21-24  reduced variables (figs 3, 4): Pi_s, Delta_s, E_eq, Gamma(1)
#   ls 31     JKR / homogeneous reference (black, dashed)
#   ls 32     asymptotes and limits (grey, dotted)
#   dash types of models (fig 9): exact solid, Perriot-Barthel fit dt 2, Gao model dt 4;
#             markers by E1*/E0*: ratio_pt(r)

if (!exists("W")) W = 1000
if (!exists("H")) H = 700
if (!exists("fmt")) fmt = 'png'
if (!exists("nu1")) nu1 = 0.25
if (!exists("nu0")) nu0 = 0.25

font_name = 'DejaVu Sans'
# fmt = 'paper': a journal PDF (make figures-paper). One column (8.5 cm) for a one-panel figure,
# two columns (17.8 cm) for a wide one (W >= 1200), the screen layout's aspect ratio, 8 pt text
# (pdfcairo draws a font at 4/3 of its size: fontscale 0.75 makes 8 the printed size),
# no figure title (the caption carries it: figure_title), panels lettered (a), (b) (panel).
paper = (fmt eq 'paper')
paper_width_cm = (W >= 1200) ? 17.8 : 8.5
figure_title(s) = paper ? '' : s
panel(s, k) = paper ? sprintf('(%c)', 96 + k) : s
# An axis label with its plain-words gloss on screen, the symbol alone in print (the caption
# defines it).
axis_label(s, gloss) = paper ? s : s.'   ('.gloss.')'
if (paper) {
    # A one-column figure gets the height a key and two axis labels need at 8 pt.
    paper_height_cm = (W >= 1200) ? paper_width_cm * H / W : 8.0
    set terminal pdfcairo enhanced color size (paper_width_cm / 2.54), (paper_height_cm / 2.54) \
        font font_name.',8' fontscale 0.75 linewidth 0.6 rounded dashlength 1.0
} else { if (fmt eq 'pdf') {
    set terminal pdfcairo enhanced color size (W/72.0), (H/72.0) font font_name.',12' \
        linewidth 1.2 rounded dashlength 1.2
} else {
    set terminal pngcairo enhanced color size W, H font font_name.',12' \
        linewidth 1.2 rounded dashlength 1.2
} }
set output outfile
set encoding utf8

set border lw 1.2
set tics out nomirror scale 0.8
set grid xtics ytics mxtics mytics lc rgb '#e4e4e4' lw 0.8 dt solid, lc rgb '#f2f2f2' lw 0.6
set key opaque box lc rgb '#c8c8c8' samplen 2.5 spacing 1.15
if (paper) { set key font ',7' samplen 1.5 spacing 1.1 width -1 }
set style fill transparent solid 0.35 noborder

# eta series: sequential (viridis-like, the light end kept readable on white)
set style line 1 lc rgb '#3b0f70' lw 2.4
set style line 2 lc rgb '#3f5fa8' lw 2.4
set style line 3 lc rgb '#1f9e89' lw 2.4
set style line 4 lc rgb '#6cc24a' lw 2.4
set style line 5 lc rgb '#d9a600' lw 2.4
eta_ls(i) = 1 + (i - 1) % 5
# The same colours as integers, for markers drawn in their curve's colour (lc rgb variable).
eta_rgb(i) = word('3870576 4153256 2072201 7127626 14263808', 1 + (i - 1) % 5) + 0

# modulus-ratio series, by decade of E1*/E0*
set style line 11 lc rgb '#08306b' lw 2.4
set style line 12 lc rgb '#4a90c8' lw 2.4
set style line 13 lc rgb '#000000' lw 2.4
set style line 14 lc rgb '#f08030' lw 2.4
set style line 15 lc rgb '#a50f15' lw 2.4
clamp(x, lo, hi) = x < lo ? lo : (x > hi ? hi : x)
ratio_ls(r) = 11 + clamp(floor(log10(r) + 2.5), 0, 4)
# A marker per E1*/E0* decade (open circle, square, filled circle, triangle, diamond), for
# figures whose curves must stay apart in greyscale print (fig 9): with linespoints pi N.
ratio_pt(r) = word('6 4 7 8 12', 1 + clamp(floor(log10(r) + 2.5), 0, 4)) + 0

# reduced variables
set style line 21 lc rgb '#c0392b' lw 2.4 pt 7 ps 0.5
set style line 22 lc rgb '#2471a3' lw 2.4 pt 5 ps 0.5
set style line 23 lc rgb '#1e8449' lw 2.4 pt 9 ps 0.6
set style line 24 lc rgb '#7d3c98' lw 2.4 pt 11 ps 0.6

# references
set style line 31 lc rgb '#000000' lw 1.8 dt (8, 5)
set style line 32 lc rgb '#808080' lw 1.4 dt (2, 4)
# pull-off markers (in their curve's colour where one curve has them: lc rgb variable)
set style line 41 lc rgb '#000000' lw 1.5 pt 6 ps 1.4
set style line 42 lc rgb '#000000' lw 1.5 pt 8 ps 1.4
if (paper) { set style line 41 ps 0.9; set style line 42 ps 0.9 }

# ---- text -------------------------------------------------------------------------------
# E1*/E0* from the Young's modulus ratio E1/E0 and the Poisson ratios.
star_ratio(r) = r * (1 - nu0**2) / (1 - nu1**2)
nu_label = (nu1 == nu0) ? sprintf("ν_1 = ν_0 = %g", nu1) : sprintf("ν_1 = %g, ν_0 = %g", nu1, nu0)
ratio_text(r) = sprintf("E_1^*/E_0^* = %g", star_ratio(r))
materials_label(r) = ratio_text(r) . ",  " . nu_label

# 1-2-5 tic positions for log axes:  eval 'set ytics ('.tics125.')'
tics125 = ''
do for [k=-4:4] {
    do for [m in "1 2 5"] {
        tics125 = tics125 . sprintf("%s%g", strlen(tics125) ? ', ' : '', real(m) * 10.0**k)
    }
}

# ---- the CLI's output files --------------------------------------------------------------
# Columns are looked up by name in the "# columns:" header line (one shell call per file).
columns_of(file) = system(sprintf("grep -m1 '^# columns:' '%s'", file))
_column_in(h, name, i) = i > words(h) ? 0 : (word(h, i) eq name ? i - 2 : _column_in(h, name, i + 1))
# Usage: eval need('c_eeq', header, 'E_eq', file) -> c_eeq = column number, or exit 1.
need(var, h, name, file) = sprintf("%s = _column_in('%s', '%s', 3); if (%s == 0) { print 'figure: column %s not found in %s'; exit status 1 }", var, h, name, var, name, file)

# ---- formulas ----------------------------------------------------------------------------
# JKR in Maugis units (THEORY.md §6): P(a_bar), D(a_bar); pull-off -3/2 (load), -5/6 (displacement)
jkr_P(a) = 4.0/3.0 * a**3 - 2*sqrt(2) * a**1.5
jkr_D(a) = a**2 - sqrt(2) * a**0.5
