# Figure 12 (beyond the paper): adhesive force-penetration curves of three indenters on the
# same coating (THEORY.md §11): F(δ) (solid) and the adhesionless F_H(δ_H) (dashed), with
# the load-controlled pull-off (circle) read from each file's header.
# Inputs: files (one `coatcontact contact` output per shape), shapes (the --shape values).

W = 1000; H = 720
load gpdir.'/style.gp'

n = words(files)
f1 = word(files, 1)
h = columns_of(f1)
eval need('c_d', h, 'delta_m', f1)
eval need('c_f', h, 'F_N', f1)
eval need('c_dh', h, 'delta_H_m', f1)
eval need('c_fh', h, 'F_H_N', f1)
header_value(file, key, field) = real(system(sprintf( \
    "awk -F': ' '/^# %s/ { n = split($2, v, \" \"); print v[%d] }' '%s'", key, field, file)))
film = system(sprintf("awk -F': ' '/^# film E1\\* /{e=$2} /^# film thickness/{t=$2} END{printf \"t = %%g nm, E_1^* = %%g MPa\", t*1e9, e*1e-6}' '%s'", f1))

set title "Fig. 12 — adhesive contact of three indenter shapes on one coating (".film.")" font ',14'
set xlabel 'penetration δ [nm]'
set ylabel 'force F [nN]'
set xrange [-6:15]
set yrange [-40:60]
set key top left
set xzeroaxis ls 32
set yzeroaxis ls 32
array F[n]
array D[n]
do for [k = 1:n] {
    F[k] = header_value(word(files, k), 'pull-off force, load control', 1)
    D[k] = header_value(word(files, k), 'pull-off force, load control', 7)
}
plot for [k = 1:n] word(files, k) using (column(c_d) * 1e9):(column(c_f) * 1e9) with lines \
         ls eta_ls(2 * k - 1) title word(shapes, k), \
     for [k = 1:n] word(files, k) using (column(c_dh) * 1e9):(column(c_fh) * 1e9) with lines \
         ls eta_ls(2 * k - 1) dt (6, 4) lw 1.4 notitle, \
     for [k = 1:n] '+' using (D[k] * 1e9):(F[k] * 1e9) every ::0::0 with points ls 41 \
         title (k == 1 ? 'pull-off, load control' : '')
unset output
