# Figure 12 (beyond the paper): adhesive force-penetration curves of three indenters on the
# same coating (THEORY.md §11): F(δ) (solid) and the adhesionless F_H(δ_H) (dashed), with
# the load-controlled pull-off (circle, in its curve's colour) read from each file's header. The sphere is a
# paraboloid z = r²/(2R): beyond a = R (cross) it no longer approximates a sphere, and its
# curve goes on dotted.
# In print the key is short (a key wider than the plot is drawn empty); captions.txt says the rest.
# Inputs: files (one `coatcontact contact` output per shape), shapes (the --shape values).

W = 1000; H = 720
load gpdir.'/style.gp'

n = words(files)
f1 = word(files, 1)
h = columns_of(f1)
eval need('c_a', h, 'a_m', f1)
eval need('c_d', h, 'delta_m', f1)
eval need('c_f', h, 'F_N', f1)
eval need('c_dh', h, 'delta_H_m', f1)
eval need('c_fh', h, 'F_H_N', f1)
# From a file's header, one awk per file: the load-controlled pull-off force and penetration
# (fields 1 and 7 of that line) and the paraboloid's R (0 for other shapes).
header_values(file) = system(sprintf("awk -F': ' '/^# pull-off force, load control/ { split($2, v, \" \"); f = v[1]; d = v[7] } \
    /^# shape: paraboloid/ { r = substr($0, index($0, \"R = \") + 4) + 0 } \
    END { printf \"%%s %%s %%.12e\\n\", f == \"\" ? 0 : f, d == \"\" ? 0 : d, r }' '%s'", file))
coating = system(sprintf("awk -F': ' '/^# film E1\\* /{e=$2} /^# film thickness/{t=$2} /^# substrate E0\\* /{s=$2} \
    /^# work of adhesion/{w=$2} END{printf \"t = %%.3g nm, E_1^* = %%.3g MPa, E_0^* = %%.3g GPa, w = %%.3g mJ/m^2\", \
    t*1e9, e*1e-6, s*1e-9, w*1e3}' '%s'", f1))
# A readable name of a --shape value: sphere:20nm -> sphere, R = 20 nm.
shape_text(s) = system("echo '".s."' | sed -e 's/^sphere:/sphere, R = /' \
    -e 's/^blunted-cone:\\([^,]*\\),\\(.*\\)deg$/blunted cone, R = \\1, β = \\2°/' \
    -e 's/^power:\\([^,]*\\),/power law z ∝ r^{\\1}, R = /' -e 's/^cone:\\(.*\\)deg$/cone, β = \\1°/' \
    -e 's/^punch:/flat punch, a = /' -e 's/\\([0-9]\\)\\(nm\\|um\\|mm\\)/\\1 \\2/g'")

set title figure_title("Fig. 12 — three indenter shapes on one coating\n{/*0.85 ".coating."}") font ',14'
set xlabel 'penetration δ (nm)'
set ylabel 'force F (nN)'
set xrange [-6:15]
set yrange [-40:60]
set key top left
set xzeroaxis ls 32
set yzeroaxis ls 32
array F[n]
array D[n]
array R[n]      # a of the tabulated point nearest to a = R for a paraboloid, 1e300 for other shapes
array RD[n]     # delta, F there (adhesive), and RDH, RFH (adhesionless)
array RF[n]
array RDH[n]
array RFH[n]
do for [k = 1:n] {
    file = word(files, k)
    hv = header_values(file)
    F[k] = real(word(hv, 1))
    D[k] = real(word(hv, 2))
    r = real(word(hv, 3))
    R[k] = 1e300
    RD[k] = NaN; RF[k] = NaN; RDH[k] = NaN; RFH[k] = NaN
    if (r > 0) {
        # the tabulated point nearest to a = R (log-spaced radii): solid up to it, dotted after
        stats file using (abs(log(column(c_a) / r))) nooutput
        i = int(STATS_index_min)
        stats file every ::i::i using (column(c_a)) nooutput
        R[k] = STATS_min
        stats file every ::i::i using (column(c_d)) nooutput
        RD[k] = STATS_min
        stats file every ::i::i using (column(c_f)) nooutput
        RF[k] = STATS_min
        stats file every ::i::i using (column(c_dh)) nooutput
        RDH[k] = STATS_min
        stats file every ::i::i using (column(c_fh)) nooutput
        RFH[k] = STATS_min
    }
}
plot for [k = 1:n] word(files, k) using (column(c_a) <= R[k] ? column(c_d) * 1e9 : NaN):(column(c_f) * 1e9) \
         with lines ls eta_ls(2 * k - 1) title (paper ? '' : 'adhesive (JKR), ').shape_text(word(shapes, k)), \
     for [k = 1:n] word(files, k) using (column(c_a) >= R[k] ? column(c_d) * 1e9 : NaN):(column(c_f) * 1e9) \
         with lines ls eta_ls(2 * k - 1) dt 3 lw 1.4 notitle, \
     for [k = 1:n] word(files, k) using (column(c_dh) * 1e9):(column(c_fh) * 1e9) with lines \
         ls eta_ls(2 * k - 1) dt (6, 4) lw 1.4 notitle, \
     NaN with lines lc rgb '#555555' dt (6, 4) lw 1.4 title (paper ? 'w = 0' : 'adhesionless (w = 0), same shape and colour'), \
     for [k = 1:n] '+' using (D[k] * 1e9):(F[k] * 1e9):(eta_rgb(2 * k - 1)) every ::0::0 with points ls 41 \
         lc rgb variable notitle, \
     NaN with points ls 41 lc rgb '#555555' title (paper ? 'pull-off' : 'pull-off, load control (circle, curve colour)'), \
     for [k = 1:n] '+' using (RD[k] * 1e9):(RF[k] * 1e9) every ::0::0 with points lc rgb 'black' pt 2 ps (paper ? 0.9 : 1.6) lw 1.5 \
         title (R[k] < 1e300 ? (paper ? 'a = R' : 'a = R: paraboloid ≠ sphere beyond (dotted)') : ''), \
     for [k = 1:n] '+' using (RDH[k] * 1e9):(RFH[k] * 1e9) every ::0::0 with points lc rgb 'black' pt 2 ps (paper ? 0.9 : 1.6) lw 1.5 \
         notitle
unset output
