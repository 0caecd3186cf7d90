# Fit of the example data (data/example_a_F.tsv, data/example_delta_F.tsv): data, fitted
# model and residuals. Run by `make fit-example`:
#   gnuplot -e "gpdir='gnuplot'; dir='build/figures'; outfile='build/figures/fit_example.png'" gnuplot/fit_example.gp
# Inputs in `dir` (written by `coatcontact fit ... --output ... --curve ...`):
#   fit_a_F.tsv, curve_a_F.tsv, fit_delta_F.tsv, curve_delta_F.tsv
if (!exists("gpdir")) gpdir = 'gnuplot'
if (!exists("dir")) dir = 'build/figures'
if (!exists("outfile")) outfile = dir.'/fit_example.png'
W = 1300; H = 900
load gpdir.'/style.gp'

# "# key: value" header lines of the fit tables (keys as written: "w [J/m2]"); a free
# parameter's value is "estimate +- standard error".
header(file, key) = system(sprintf("awk -v k='# %s: ' 'index($0, k) == 1 { print substr($0, length(k) + 1); exit }' '%s'", key, file))
num(file, key) = real(word(header(file, key), 1))
err(file, key) = real(word(header(file, key), 3))
fa = dir.'/fit_a_F.tsv'; ca = dir.'/curve_a_F.tsv'
fd = dir.'/fit_delta_F.tsv'; cd = dir.'/curve_delta_F.tsv'

label(file) = sprintf("fit: w = %.2f ± %.2f mJ/m^2,  t = %.2f ± %.2f µm   (n = %s, s = %.1f µN)", \
    1e3*num(file, 'w [J/m2]'), 1e3*err(file, 'w [J/m2]'), \
    1e6*num(file, 't [m]'), 1e6*err(file, 't [m]'), \
    word(header(file, 'points'), 1), 1e6*num(file, 'residual sigma [N]'))

set style line 41 lc rgb '#1f77b4' pt 6 ps 0.9 lw 1.2   # data
set style line 42 lc rgb '#d62728' lw 2.2               # fitted model
set style line 43 lc rgb '#2ca02c' pt 7 ps 0.7          # pull-off point
set style line 44 lc rgb '#555555' lw 1 dt 3            # zero line

set multiplot title "Fit of synthetic adhesive contact data: PDMS-like film (E1 = 1 MPa, ν1 = 0.49) on glass (E0 = 70 GPa), R = 5 mm\n".\
    "truth: w = 40 mJ/m^2, t = 50 µm; Gaussian force noise σ = 10 µN; fitted: w and t together" font ',13'

top = 0.88; mid = 0.40; bottom = 0.08
# ---- a,F: data and model ----
set lmargin at screen 0.08; set rmargin at screen 0.47
set tmargin at screen top; set bmargin at screen mid
set format x ''
set xlabel ''
set ylabel 'force F (mN)'
set key top left
set title label(fa) font ',11'
plot ca u ($1*1e6):($3*1e3) w l ls 42 t 'model F(a)', \
     fa u ($2*1e6):($3*1e3) w p ls 41 t 'data (loading + unloading)', \
     0 w l ls 44 notitle
# ---- a,F: residuals ----
set tmargin at screen mid - 0.02; set bmargin at screen bottom
set format x '%g'
set xlabel 'contact radius a (µm)'
set ylabel 'residual F_{model} - F_{data} (µN)'
set title ''
set key off
plot fa u ($2*1e6):($5*1e6) w p ls 41, 0 w l ls 44
# ---- delta,F: data and model ----
set lmargin at screen 0.57; set rmargin at screen 0.96
set tmargin at screen top; set bmargin at screen mid
set format x ''
set xlabel ''
set ylabel 'force F (mN)'
set key top left
set title label(fd) font ',11'
xc = 1e6*num(fd, 'pull-off penetration, displacement control [m]'); yc = 1e3*num(fd, 'pull-off force, displacement control [N]')
ac = num(fd, 'pull-off contact radius, displacement control [m]')
plot cd u ($1 >= ac ? $2*1e6 : NaN):($3*1e3) w l ls 42 t 'model F(δ), stable branch a ≥ a_c', \
     cd u ($1 <= ac ? $2*1e6 : NaN):($3*1e3) w l ls 42 dt 2 t 'a < a_c (unstable)', \
     fd u ($2*1e6):($3*1e3) w p ls 41 t 'data (loading + unloading)', \
     '+' u (xc):(yc) every ::0::0 w p ls 43 ps 1.6 t 'displacement-controlled pull-off', \
     0 w l ls 44 notitle
# ---- delta,F: residuals ----
set tmargin at screen mid - 0.02; set bmargin at screen bottom
set format x '%g'
set xlabel 'penetration δ (µm)'
set ylabel 'residual F_{model} - F_{data} (µN)'
set title ''
set key off
plot fd u ($2*1e6):($6*1e6) w p ls 41, 0 w l ls 44
unset multiplot
