# Figure 2: the adhesive configuration built from the adhesionless one (paper Fig. 2, THEORY.md
# §5 steps 1-4), in Maugis units for one coated system:
#  - the adhesionless curve P_H(D_H): P_H = a_bar^3 Pi_s/2, D_H = a_bar^2 Delta_s, a_bar = eta a/t
#    (from `coatcontact reduced` over a/t);
#  - at contact radius a (a/t = first row of `points`): the flat-punch line of slope
#    dP/dD = 2 a_bar E_eq (the contact stiffness S), tangent to P_H(D_H), followed down by the
#    adhesive displacement D_fp = -sqrt(2) a_bar^(1/2)/Gamma(1) [selfconsistenceInhom] to the
#    adhesive point (D, P);
#  - the same at a slightly larger radius (second row of `points`) down to the same D: the
#    shaded area between the two paths is the elastic energy released when the contact grows
#    at constant penetration, 2 pi a G da = (1/2) delta_fp^2 dS [EqCompliance].
# Inputs: curve, points, ratio, eta.

W = 1000; H = 760
load gpdir.'/style.gp'

h = columns_of(curve)
eval need('c_at', h, 'a_over_t', curve)
eval need('c_pis', h, 'Pi_s', curve)
eval need('c_ds', h, 'Delta_s', curve)
eval need('c_eeq', h, 'E_eq', curve)
eval need('c_g1', h, 'Gamma1', curve)

# value of column c on data row k (0-based) of file f
row_value(f, k, c) = sprintf("stats '%s' every ::%d::%d using %d nooutput; v = STATS_min", f, k, k, c)
array at[2]; array pis[2]; array ds[2]; array eeq[2]; array g1[2]
do for [k = 1:2] {
    eval row_value(points, k - 1, c_at);  at[k] = v
    eval row_value(points, k - 1, c_pis); pis[k] = v
    eval row_value(points, k - 1, c_ds);  ds[k] = v
    eval row_value(points, k - 1, c_eeq); eeq[k] = v
    eval row_value(points, k - 1, c_g1);  g1[k] = v
}
ab(k) = eta * at[k]                       # a_bar
PH(k) = ab(k)**3 * pis[k] / 2             # adhesionless force and penetration
DH(k) = ab(k)**2 * ds[k]
S(k) = 2 * ab(k) * eeq[k]                 # flat-punch stiffness in Maugis units
Dfp = -sqrt(2) * sqrt(ab(1)) / g1[1]      # adhesive flat-punch displacement at radius 1
D_end = DH(1) + Dfp                       # total penetration of the adhesive point
P1 = PH(1) + S(1) * Dfp                   # adhesive force at radius 1
P2 = PH(2) + S(2) * (D_end - DH(2))       # radius 2 unloaded to the same penetration

# the released-energy polygon: P_H curve from radius 1 to radius 2, down line 2, up line 1
set print $released
print sprintf("%.12g %.12g", DH(1), PH(1))
set print
set table $released append
plot curve using (eta**2 * column(c_at)**2 * column(c_ds)):(eta**3 * column(c_at)**3 * column(c_pis) / 2) \
    with table if (column(c_at) > at[1] && column(c_at) < at[2])
unset table
set print $released append
print sprintf("%.12g %.12g", DH(2), PH(2))
print sprintf("%.12g %.12g", D_end, P2)
print sprintf("%.12g %.12g", D_end, P1)
print sprintf("%.12g %.12g", DH(1), PH(1))
set print

x_lo = D_end - 0.9; x_hi = DH(2) + 0.9
y_lo = P2 - 0.6;     y_hi = PH(2) + 1.6

set title figure_title(sprintf("Fig. 2 — the adhesive point from the adhesionless curve by a flat-punch displacement\n{/*0.85 %s,  η = %g,  contact radius ā = %.3g (a/t = %.3g)}", materials_label(ratio), eta, ab(1), at[1])) font ',14'
set xlabel axis_label('D = δ / (π^2 w^2 R/E_1^{*2})^{1/3}', 'normalized penetration')
set ylabel axis_label('P = F / (π w R)', 'normalized force')
set xrange [x_lo:x_hi]
set yrange [y_lo:y_hi]
set xzeroaxis ls 32
set key top left

y_fp = PH(1) + 0.6                        # height of the delta_fp dimension line
set arrow 1 from D_end, y_fp to DH(1), y_fp heads lc rgb '#000000' lw 1.2 size 0.05, 20 front
set arrow 2 from DH(1), PH(1) to DH(1), y_fp + 0.15 nohead dt 3 lc rgb '#000000' front
set arrow 3 from D_end, P1 to D_end, y_fp + 0.15 nohead dt 3 lc rgb '#000000' front
set label 1 sprintf('δ_{fp}:  D_{fp} = -√2 ā^{1/2}/Γ(1) = %.3f', Dfp) at (DH(1) + D_end) / 2, y_fp + 0.3 center front
P_mid = (PH(1) + P1) / 2                 # the slope label points at the line there
set label 2 sprintf('slope S = 2ā E_{eq} = %.3f', S(1)) at x_lo + 0.1, PH(1) - 0.6 left front
set arrow 4 from x_lo + 0.55, PH(1) - 0.75 to DH(1) + (P_mid - PH(1)) / S(1) - 0.02, P_mid \
    lc rgb '#000000' lw 1 size 0.04, 20 front
set label 3 'adhesionless point (D_H, P_H)' at DH(1) + 0.07, PH(1) - 0.05 left front
set label 4 'adhesive point (D, P)' at D_end - 0.07, P1 right front
set label 5 'energy released ≈ ½ δ_{fp}^2 ΔS = 2π a G Δa' at D_end + 0.12, P2 - 0.25 left tc rgb '#b0601a' front
set arrow 5 from D_end + 0.11, P2 - 0.2 to D_end + 0.02, (P1 + P2) / 2 lc rgb '#b0601a' lw 1.2 size 0.04, 20 front

tangent(D, k) = PH(k) + S(k) * (D - DH(k))
# The two flat-punch lines by their end points: sampled over a range ('+'), the last sample of
# 101 came and went with 1e-11 changes of the data (a line end moving by 1 % of its length).
set print $tangent1
print sprintf("%.12g %.12g", D_end, tangent(D_end, 1))
print sprintf("%.12g %.12g", DH(1) + 0.5, tangent(DH(1) + 0.5, 1))
set print $tangent2
print sprintf("%.12g %.12g", D_end, tangent(D_end, 2))
print sprintf("%.12g %.12g", DH(2), tangent(DH(2), 2))
set print
set print $marks
print sprintf("%.12g %.12g", DH(1), PH(1))
print sprintf("%.12g %.12g", D_end, P1)
set print
set print $marks2
print sprintf("%.12g %.12g", DH(2), PH(2))
set print
set samples 101
plot $released using 1:2 with filledcurves closed fc rgb '#f0a050' fs transparent solid 0.55 \
         title sprintf('energy released as ā grows from %.3g to %.3g at constant D', ab(1), ab(2)), \
     curve using (eta**2 * column(c_at)**2 * column(c_ds)):(eta**3 * column(c_at)**3 * column(c_pis) / 2) \
         with lines lc rgb '#000000' lw 2.4 title 'adhesionless curve P_H(D_H)', \
     curve using (eta**2 * column(c_at)**2 * column(c_ds) - sqrt(2 * eta * column(c_at)) / column(c_g1)): \
         (eta**3 * column(c_at)**3 * column(c_pis) / 2 - 2 * sqrt(2) * (eta * column(c_at))**1.5 * column(c_eeq) / column(c_g1)) \
         with lines ls 3 lw 1.6 title sprintf('adhesive curve P(D), η = %g (all contact radii)', eta), \
     $tangent1 using 1:2 with lines ls 21 \
         title 'flat-punch line at ā: slope S(ā), tangent to P_H', \
     $tangent2 using 1:2 with lines ls 21 dt 2 lw 1.6 \
         title 'flat-punch line at ā + Δā, down to the same D', \
     $marks using 1:2 with points ls 41 pt 7 ps 1.3 notitle, \
     $marks2 using 1:2 with points ls 41 pt 6 ps 1.1 notitle
unset output
