# Figure 1: schematic of an adhesive contact (paper Fig. 1), drawn over computed profiles of a
# homogeneous elastic half-space indented by a rigid sphere (radius R, contact radius a):
#  - top: the sphere and the deformed surface of the JKR solution (Hertz + flat punch,
#    Johnson's "Contact mechanics" eqs. 3.42 and 3.36 outside the contact), the gap h(r);
#  - bottom: a surface stress with a finite interaction zone a < r < c (Maugis-Dugdale form:
#    Hertz pressure plus a uniform adhesive tension sigma0 over a < r < c, which inside the
#    contact becomes -(2 sigma0/pi) atan(sqrt((c^2-a^2)/(a^2-r^2)))): compressive in the centre,
#    tensile on both sides of the contact edge. In the JKR limit c -> a the tension inside
#    becomes the square-root singularity carried by g(a).
# Lengths in units of a; the vertical scale of the top panel is exaggerated.

W = 1000; H = 900
load gpdir.'/style.gp'

R = 2.0                        # sphere radius (in units of a: exaggerated curvature)
dfp = -0.15                    # flat-punch (adhesive) displacement, delta_fp < 0
delta = 1.0 / R + dfp          # JKR penetration delta = a^2/R + delta_fp
c = 1.3                        # interaction zone outer radius (drawn wide for clarity)
s0 = 0.75                      # adhesive tension sigma0 / p_H
r1 = 0.55; r2 = 0.75           # where theta(r1) and g(r2) are evaluated
ytop = 0.75; ybot = -0.5       # vertical extent of the top panel

# surface displacement u_z (positive into the solid), JKR, outside the contact |r| > 1
uH(r) = ((2 - r**2) * asin(1 / r) + sqrt(r**2 - 1)) / (pi * R)
ufp(r) = 2 * dfp / pi * asin(1 / r)
surface(r) = abs(r) <= 1 ? r**2 / (2 * R) - delta : -(uH(abs(r)) + ufp(abs(r)))
sphere(r) = r**2 / (2 * R) - delta
# normal surface stress / p_H (compressive positive)
sig(r) = abs(r) < 1 ? sqrt(1 - r**2) - 2 * s0 / pi * atan(sqrt((c**2 - 1) / (1 - r**2))) : \
         (abs(r) < c ? -s0 : 0)

set multiplot title figure_title("Fig. 1 — adhesive contact: contact zone, interaction zone, gap and surface stress") font ',14'
set xrange [-2.2:2.2]
set lmargin at screen 0.12; set rmargin at screen 0.96
set samples 801
unset grid
unset key

# ---- top: geometry ----
set tmargin at screen 0.92; set bmargin at screen 0.55
set yrange [ybot:ytop]
unset ytics; unset xtics
set border 0
set ylabel 'height (exaggerated)' offset 2, 0
set object 1 rect from -c, graph 0 to -1, graph 1 fc rgb '#f6c89f' fs transparent solid 0.45 noborder behind
set object 2 rect from 1, graph 0 to c, graph 1 fc rgb '#f6c89f' fs transparent solid 0.45 noborder behind
set label 1 'interaction zone' at -2.15, 0.32 left tc rgb '#b0601a' front
set arrow 1 from -1.75, 0.27 to -1.15, 0.02 lc rgb '#b0601a' lw 1.2 size 0.05, 20 front
set arrow 2 from -1, 0.55 to 1, 0.55 heads lc rgb '#000000' lw 1.2 size 0.05, 20 front
set arrow 3 from -1, 0.55 to -1, sphere(1) nohead dt 3 lc rgb '#000000' front
set arrow 4 from 1, 0.55 to 1, sphere(1) nohead dt 3 lc rgb '#000000' front
set label 2 'contact zone, radius a' at 0, 0.62 center front
set label 3 'rigid sphere' at 0, 0.32 center front
set label 4 'elastic solid' at 1.6, -0.4 center front
rg = 1.75                      # where the gap h(r) is shown
set arrow 5 from rg, surface(rg) to rg, sphere(rg) heads lc rgb '#000000' lw 1.2 size 0.04, 20 front
set label 5 'gap h(r)' at rg + 0.05, (surface(rg) + sphere(rg)) / 2 left front
set label 6 'undeformed surface' at -2.15, 0.05 left tc rgb '#808080' front
set label 7 'θ(r_1) collects u_z(s), s < r_1' at 0, -0.4 center tc ls 22 front
plot sphere(x) with filledcurves y1=ytop fc rgb '#d5d8dc' fs solid 1, \
     sphere(x) with lines lc rgb '#555555' lw 1.5, \
     surface(x) with filledcurves y1=ybot fc rgb '#fdebd0' fs solid 1, \
     surface(x) with lines lc rgb '#000000' lw 2.2, \
     0 with lines ls 32, \
     '+' using (abs($1) < r1 ? $1 : NaN):(surface($1)) with lines ls 22 lw 6
unset object 1; unset object 2
do for [k = 1:7] { unset label k }
do for [k = 1:5] { unset arrow k }

# ---- bottom: surface stress ----
set tmargin at screen 0.52; set bmargin at screen 0.09
set border 3
set xtics nomirror ('-c' -c, '-a' -1, '0' 0, 'r_1' r1, 'r_2' r2, 'a' 1, 'c' c)
set ytics nomirror
set yrange [-1.0:1.2]
set xlabel 'radial position r'
set ylabel axis_label('normal surface stress σ_z / p_H', 'compression > 0') offset 0, 0
set xzeroaxis ls 32
set object 1 rect from -c, graph 0 to -1, graph 1 fc rgb '#f6c89f' fs transparent solid 0.45 noborder behind
set object 2 rect from 1, graph 0 to c, graph 1 fc rgb '#f6c89f' fs transparent solid 0.45 noborder behind
set label 1 'compressive centre' at 0, 0.9 center front
set label 2 'tensile edge' at -1.6, -0.55 center front
set label 3 'tensile edge' at 1.6, -0.55 center front
set label 4 'g(r_2) collects σ_z(s), s > r_2' at 1.25, 0.55 left tc ls 21 front
set arrow 1 from 1.22, 0.55 to 0.95, 0.1 ls 21 lw 1.2 size 0.05, 20
set label 5 'r_1' at r1, 1.12 center tc ls 22 front
set arrow 2 from r1, 1.05 to r1, -1.0 nohead ls 22 dt 3 lw 1.2
set arrow 3 from r2, 1.05 to r2, -1.0 nohead ls 21 dt 3 lw 1.2
set label 6 'r_2' at r2, 1.12 center tc ls 21 front
plot '+' using ($1 > r2 ? $1 : NaN):(sig($1)) with filledcurves y1=0 fc rgb '#c0392b' fs transparent solid 0.3, \
     sig(x) with lines lc rgb '#000000' lw 2.2
unset multiplot
unset output
