# Published approximations of the flat-punch equivalent modulus E_eq (in units of E1*), for
# comparison with the exact values (figure 9). Needs nu1, nu0 (film, substrate Poisson ratios).
# r is the film/substrate Young's modulus ratio E1/E0, at = a/t.

# ---- Perriot & Barthel, J. Mater. Res. 19 (2004) 600: empirical fit (THEORY.md §6) --------
# E_eq,fit = E1* + (E0* - E1*) / (1 + (x0 t/a)^n),  log10 x0 = -0.093 + 0.792 L + 0.05 L^2,
# L = log10(E0*/E1*), n = 1.27. x0 is the a/t of the film-to-substrate transition (x0 ~ 5.6
# for a soft film E1*/E0* = 0.1, ~ 0.13 for a stiff one). Note: THEORY.md §6 writes the
# fraction with E0* and E1* swapped, which would give the substrate modulus at a/t -> 0;
# this orientation has the right limits (film at a/t -> 0, substrate at a/t -> oo).
pb_L(rs) = log10(1.0 / rs)
pb_x0(rs) = 10**(-0.093 + 0.792 * pb_L(rs) + 0.05 * pb_L(rs)**2)
pb_n = 1.27
pb_eeq(at, r) = 1 + (1.0 / star_ratio(r) - 1) / (1 + (pb_x0(star_ratio(r)) / at)**pb_n)

# ---- Gao, Chiu & Lee, Int. J. Solids Struct. 29 (1992) 2471: weight-function model ---------
# xi = t/a;  mu_eff = mu0 + (mu1 - mu0) I0(xi);
# nu_eff = 1 - (1 - nu0)(1 - nu1) / [1 - (1 - I1) nu1 - I1 nu0];  E_eff* = 2 mu_eff/(1 - nu_eff)
# I0(xi) = (2/pi) atan xi + [(1 - 2 nu) xi ln((1 + xi^2)/xi^2) - xi/(1 + xi^2)] / (2 pi (1 - nu))
# I1(xi) = (2/pi) atan xi + (xi/pi) ln((1 + xi^2)/xi^2)
# Limits checked: xi -> oo (thick film): I0, I1 -> 1, film values; xi -> 0: substrate values.
# Convention for nu in I0: Gao et al. expand about a homogeneous solid; we take the composite
# nu_eff(xi) (as e.g. the NIMS toolbox does). With nu0 = nu1 (all figures here) every choice
# (film, substrate or composite nu) gives the same curve.
gao_I1(xi) = 2 / pi * atan(xi) + xi / pi * log((1 + xi**2) / xi**2)
gao_nu(xi) = 1 - (1 - nu0) * (1 - nu1) / (1 - (1 - gao_I1(xi)) * nu1 - gao_I1(xi) * nu0)
gao_I0(xi, nu) = 2 / pi * atan(xi) + \
    ((1 - 2 * nu) * xi * log((1 + xi**2) / xi**2) - xi / (1 + xi**2)) / (2 * pi * (1 - nu))
# shear moduli with E0 = 1, E1 = r
gao_mu1(r) = r / (2 * (1 + nu1))
gao_mu0 = 1.0 / (2 * (1 + nu0))
gao_mu(xi, r) = gao_mu0 + (gao_mu1(r) - gao_mu0) * gao_I0(xi, gao_nu(xi))
gao_eeq(at, r) = (2 * gao_mu(1.0 / at, r) / (1 - gao_nu(1.0 / at))) / (r / (1 - nu1**2))
