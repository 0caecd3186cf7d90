# Figures 3 and 4: the four reduced variables versus a~ = a/t (THEORY.md §5, paper section 6.1).
# Inputs: reduced (file from `coatcontact reduced`), ratio (E1/E0), fignum, film_word.
# Left: the adhesionless sphere, Pi_s (left axis, log) and Delta_s (right axis).
# Right: the flat punch, E_eq and Gamma(1) (log axis), with their a~ -> 0 and a~ -> oo limits.

W = 1400; H = 620
load gpdir.'/style.gp'

h = columns_of(reduced)
eval need('c_at', h, 'a_over_t', reduced)
eval need('c_pis', h, 'Pi_s', reduced)
eval need('c_ds', h, 'Delta_s', reduced)
eval need('c_eeq', h, 'E_eq', reduced)
eval need('c_g1', h, 'Gamma1', reduced)

rs = star_ratio(ratio)        # E1*/E0*
inv = 1.0 / rs                # E0*/E1*: the substrate limit of E_eq

stats reduced using (column(c_at)) nooutput
at_min = STATS_min; at_max = STATS_max
stats reduced using (column(c_ds)) nooutput
ds_lo = STATS_min; ds_hi = STATS_max

set multiplot layout 1, 2 title figure_title(sprintf("Fig. %d — reduced variables of a %s,  %s", fignum, film_word, materials_label(ratio))) font ',14' margins (paper ? 0.1 : 0.07), 0.93, 0.13, (paper ? 0.9 : 0.86) spacing 0.13, 0

set logscale x
set xrange [at_min:at_max]
set format x '10^{%L}'
set xlabel axis_label('ã = a/t', 'contact radius / film thickness')

# ---- left: adhesionless sphere ----
set title panel('adhesionless sphere:  F_H = a^3 E_1^* Π_s / (2R),   δ_H = (a^2/R) Δ_s', 1)
set logscale y
set ylabel axis_label('Π_s', 'force factor, log scale') tc ls 21
set format y '%g'
eval 'set ytics ('.tics125.')'
pis_lo = (8.0/3) * (inv < 1 ? inv : 1); pis_hi = (8.0/3) * (inv > 1 ? inv : 1)
set yrange [pis_lo / 1.6 : pis_hi * 1.6]
set y2label 'Δ_s   (penetration factor)' tc ls 22
set y2tics nomirror tc ls 22
ds_span = (ds_hi - ds_lo) > 0.04 ? (ds_hi - ds_lo) : 0.04
set y2range [ds_lo - 0.35*ds_span : ds_hi + 0.35*ds_span]
set ytics nomirror tc ls 21
if (inv > 1) { set key bottom right } else { set key top right }
set label 1 'Π_s = 8/3 (film)' at graph 0.02, first (8.0/3) * (inv > 1 ? 0.82 : 1.22) left tc ls 32 front
set label 2 sprintf('Π_s = (8/3) E_0^*/E_1^* = %.3g (substrate)', 8.0/3*inv) \
    at graph 0.98, first (8.0/3) * inv * (inv > 1 ? 1.22 : 0.82) right tc ls 32 front
plot 8.0/3 ls 32 notitle, \
     8.0/3*inv ls 32 notitle, \
     reduced using (column(c_at)):(column(c_pis)) with lines ls 21 title 'Π_s (left axis)', \
     reduced using (column(c_at)):(column(c_ds)) axes x1y2 with lines ls 22 title 'Δ_s (right axis)'
unset label 1; unset label 2
unset y2tics; unset y2label; set ytics mirror tc default

# ---- right: flat punch ----
set title panel('flat punch:  S = 2a E_1^* E_{eq},   g(a) = δ_{fp} E_1^* Γ(1)/2', 2)
set ylabel axis_label('E_{eq},  Γ(1)', 'log scale') tc default
lo = inv < 1 ? inv : 1; hi = inv > 1 ? inv : 1
set yrange [lo / 1.6 : hi * 1.6]
eval 'set ytics ('.tics125.')'
if (inv > 1) { set key bottom right } else { set key top right }
set label 3 sprintf('E_0^*/E_1^* = %.3g', inv) at graph 0.98, first inv * (inv > 1 ? 1.15 : 0.87) right tc ls 32 front
set label 4 sprintf('(E_0^*/E_1^*)^{1/2} = %.3g', sqrt(inv)) at graph 0.98, first sqrt(inv) * (inv > 1 ? 1.15 : 0.87) right tc ls 32 front
plot 1 ls 32 notitle, inv ls 32 notitle, sqrt(inv) ls 32 notitle, \
     reduced using (column(c_at)):(column(c_eeq)) with lines ls 23 title 'E_{eq}  (contact stiffness)', \
     reduced using (column(c_at)):(column(c_g1)) with lines ls 24 title 'Γ(1)  (edge stress intensity)'
unset multiplot
unset output
