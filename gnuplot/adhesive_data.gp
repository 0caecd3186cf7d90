# Helper for figures 5, 6, 7: reads the `coatcontact adhesive` file (one block per eta) and
# the `coatcontact pulloff` file for the same eta values.
# Inputs: adhesive, pulloff (file names). Defines: n_eta, eta_of[i] (i = 1..n_eta, block i-1),
# column numbers c_abar, c_P, c_D, c_pl, c_al, c_dl, c_pd, c_ad, c_dd, and P_low (lowest P).

h = columns_of(adhesive)
eval need('c_eta', h, 'eta', adhesive)
eval need('c_abar', h, 'a_bar', adhesive)
eval need('c_P', h, 'P', adhesive)
eval need('c_D', h, 'D', adhesive)
h = columns_of(pulloff)
eval need('c_peta', h, 'eta', pulloff)
eval need('c_pl', h, 'P_load', pulloff)
eval need('c_al', h, 'a_bar_load', pulloff)
eval need('c_dl', h, 'D_load', pulloff)
eval need('c_pd', h, 'P_disp', pulloff)
eval need('c_ad', h, 'a_bar_disp', pulloff)
eval need('c_dd', h, 'D_disp', pulloff)

stats adhesive using (column(c_eta)) nooutput
n_eta = STATS_blocks
array eta_of[n_eta]
do for [i = 1:n_eta] {
    stats adhesive index (i - 1) using (column(c_eta)) nooutput
    eta_of[i] = STATS_min
}
stats pulloff using (column(c_pl)) nooutput
P_low = STATS_min
eta_title(i) = sprintf("η = %g%s", eta_of[i], \
    i == 1 ? "  (thinnest film)" : (i == n_eta ? "  (thickest film)" : ""))
