// The peers' adhesionless AFM models against nanite's formulas, written out here (THEORY.md
// section 15, the Hertz/Sneddon fit; section 11, Sneddon's integral): the three-sided
// pyramid (hertz_pyr3s, Bilodeau 1992), the exact sphere (Sneddon 1965, nanite's
// sneddon_spher) and the contact-point weights (nanite's weight.weight_cp).
//  - g(delta) = F/E* agrees with the closed forms to 1e-10 (relative);
//  - a noise-free synthetic curve of each is fitted back to its truth;
//  - a weighted fit of a noisy curve satisfies the normal equations of nanite's weighted
//    residuals, and its z_c is a minimum of that weighted sum;
//  - the real spot3 approach is fitted with each (E printed for the issue's closing note).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"

namespace {

namespace fit = coatcontact::fit;
namespace afm = coatcontact::afm;
using coatcontact::InputError;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// nanite's hertz_pyr3s per E/(1 - nu^2): 0.8887 tan(alpha) delta^2.
double nanite_pyramid3(double alpha, double delta) { return 0.8887 * std::tan(alpha) * delta * delta; }

// nanite's sneddon_spher, parametric in a: (delta, F per E/(1 - nu^2)).
std::pair<double, double> nanite_sphere(double radius, double a) {
  const double l = std::log((radius + a) / (radius - a));
  return {0.5 * a * l, 0.5 * (radius * radius + a * a) * l - a * radius};
}

// nanite's weight_cp: min(|delta - cp|/D, 1) on its tip-position axis.
double nanite_weight(double cp, double z, double distance) { return std::min(std::abs(z - cp) / distance, 1.0); }

void check_model_values() {
  const double alpha = 35.0 * kDeg;
  std::vector<double> delta;
  for (int k = 1; k <= 40; ++k) delta.push_back(1e-9 * std::pow(1.25, k));
  const std::vector<double> g = fit::afm_force_per_modulus(fit::afm_pyramid3(alpha), delta);
  for (std::size_t i = 0; i < delta.size(); ++i) {
    check::close(g[i], nanite_pyramid3(alpha, delta[i]), check::tier::kInterpolation, "pyramid3: nanite's hertz_pyr3s");
  }
  // The sphere over a/R from 0.02 (the series branch) to 0.98: nanite's closed form loses at
  // most (R/a)^2 eps = 2.5e-13 there, well inside the tier.
  const double radius = 5e-6;
  std::vector<double> d, expected;
  for (int k = 1; k <= 49; ++k) {
    const auto [dk, fk] = nanite_sphere(radius, 0.02 * k * radius);
    d.push_back(dk), expected.push_back(fk);
  }
  const std::vector<double> gs = fit::afm_force_per_modulus(fit::afm_sneddon_sphere(radius), d);
  for (std::size_t i = 0; i < d.size(); ++i) {
    check::close(gs[i], expected[i], check::tier::kInterpolation, "sneddon-sphere: nanite's sneddon_spher");
  }
  // Small contacts: the Hertz limit (4/3) sqrt(R) delta^1.5 (relative terms of order delta/R).
  const std::vector<double> tiny = fit::afm_force_per_modulus(fit::afm_sneddon_sphere(radius), {1e-15});
  check::close(tiny[0], 4.0 / 3.0 * std::sqrt(radius) * std::pow(1e-15, 1.5), 1e-9, "sneddon-sphere: the Hertz limit");
  check::throws<InputError>([] { fit::afm_pyramid3(95.0 * kDeg); }, {"face angle"});
  check::throws<InputError>([] { fit::afm_sneddon_sphere(0.0); }, {"radius"});
}

// A synthetic approach: z from z_hi down to z_lo, F = b + E* g(z_c - z) (+ noise).
struct Curve {
  std::vector<double> z, f;
};
Curve synthetic(const fit::AfmTip& tip, double modulus, double contact, double baseline, double noise, unsigned seed) {
  Curve c;
  const int n = 600;
  for (int i = 0; i < n; ++i) c.z.push_back(1e-6 - 3e-6 * i / (n - 1));
  std::vector<double> delta(c.z.size());
  for (std::size_t i = 0; i < c.z.size(); ++i) delta[i] = std::max(0.0, contact - c.z[i]);
  const std::vector<double> g = fit::afm_force_per_modulus(tip, delta);
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  for (std::size_t i = 0; i < g.size(); ++i) c.f.push_back(baseline + modulus / 0.75 * g[i] + (noise > 0 ? gauss(random) : 0.0));
  return c;
}

void check_recovery(const fit::AfmTip& tip, double weight_cp, const std::string& name) {
  const double modulus = 5e3, contact = 0.3e-6, baseline = 1e-10;
  const Curve c = synthetic(tip, modulus, contact, baseline, 0.0, 1);
  fit::AfmFitProblem problem;
  problem.tip = tip;
  problem.poisson = 0.5;
  problem.weight_cp = weight_cp;
  const fit::AfmFitResult r = fit::afm_fit(c.z, c.f, problem);
  // z_c is the minimum of a smooth sum, so located to ~sqrt(eps) of its scale (~1e-13 m
  // here, 1e-7 of the 1.3 um indentation); E and b follow to that relative order.
  const double max_force = *std::max_element(c.f.begin(), c.f.end()) - baseline;
  check::close(r.modulus, modulus, 1e-6, name + ": noise-free E recovered");
  check::below(std::abs(r.contact_point - contact), 1e-12, name + ": noise-free z_c recovered [m]");
  check::below(std::abs(r.baseline - baseline), 1e-6 * max_force, name + ": noise-free b recovered [N]");
}

// Weighted least squares with nanite's weights: at the fit, sum w^2 r g = 0 and sum w^2 r = 0
// (E and b free) and z_c is a minimum of sum (w r)^2; and the weights change the fit.
void check_weighting() {
  const fit::AfmTip tip = fit::afm_sneddon_sphere(5e-6);
  const Curve c = synthetic(tip, 5e3, 0.3e-6, 0.0, 2e-10, 7);
  const double distance = 0.5e-6;
  fit::AfmFitProblem problem;
  problem.tip = tip;
  problem.poisson = 0.5;
  const fit::AfmFitResult plain = fit::afm_fit(c.z, c.f, problem);
  problem.weight_cp = distance;
  const fit::AfmFitResult r = fit::afm_fit(c.z, c.f, problem);
  const auto weighted = [&](double contact, double* normal_e, double* normal_b) {
    std::vector<double> delta(c.z.size());
    for (std::size_t i = 0; i < c.z.size(); ++i) delta[i] = std::max(0.0, contact - c.z[i]);
    const std::vector<double> g = fit::afm_force_per_modulus(tip, delta);
    double cost = 0.0, se = 0.0, sb = 0.0, scale_e = 0.0, scale_b = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double w = nanite_weight(contact, c.z[i], distance);
      const double residual = c.f[i] - r.baseline - r.modulus / 0.75 * g[i];
      cost += w * w * residual * residual;
      se += w * w * residual * g[i], scale_e += std::abs(w * w * c.f[i] * g[i]);
      sb += w * w * residual, scale_b += std::abs(w * w * c.f[i]);
    }
    if (normal_e) *normal_e = se / scale_e;
    if (normal_b) *normal_b = sb / scale_b;
    return cost;
  };
  double normal_e = 0.0, normal_b = 0.0;
  const double best = weighted(r.contact_point, &normal_e, &normal_b);
  check::below(std::abs(normal_e), check::tier::kInterpolation, "weight_cp: nanite's weighted normal equation in E");
  check::below(std::abs(normal_b), check::tier::kInterpolation, "weight_cp: nanite's weighted normal equation in b");
  for (double step : {-1e-9, 1e-9}) {
    check::that(weighted(r.contact_point + step, nullptr, nullptr) >= best * (1 - 1e-12),
                "weight_cp: z_c minimizes nanite's weighted residuals");
  }
  check::that(std::abs(r.modulus - plain.modulus) > 1e-6 * plain.modulus, "weight_cp: the weights change the noisy fit");
  std::printf("weighting (noisy synthetic, E = 5000 Pa): unweighted E = %.6g +- %.3g, weighted (D = 500 nm) E = %.6g +- %.3g\n",
              plain.modulus, plain.modulus_error, r.modulus, r.modulus_error);
  problem.free.tilt = true;
  check::throws<InputError>([&] { fit::afm_fit(c.z, c.f, problem); }, {"weighting"});
}

// The real spot3 approach (a 10 um sphere in the other tests): E of each model.
void check_spot3(const std::string& dir) {
  const auto curves = afm::read_force_curves(dir + "/fmt-jpk-fd_spot3-0192.jpk-force");
  const afm::ForceCurve& c = curves.at(0);
  const afm::Segment* seg = c.find_segment(afm::SegmentKind::kApproach);
  if (!check::that(seg != nullptr, "spot3: approach segment")) return;
  const std::vector<double> tip_all = c.tip_position();
  const std::vector<double> z(tip_all.begin() + seg->begin, tip_all.begin() + seg->end);
  const std::vector<double> f(c.force.begin() + seg->begin, c.force.begin() + seg->end);
  const auto run = [&](const fit::AfmTip& tip, double weight_cp, const char* name) {
    fit::AfmFitProblem problem;
    problem.tip = tip;
    problem.poisson = 0.5;
    problem.weight_cp = weight_cp;
    const fit::AfmFitResult r = fit::afm_fit(z, f, problem);
    std::printf("spot3 %-34s E = %.6g +- %.3g Pa, z_c = %.9g m, max indentation %.3g m, R2 = %.5f\n", name, r.modulus,
                r.modulus_error, r.contact_point, r.max_indentation, r.r_squared);
    check::that(r.r_squared > 0.9, std::string("spot3: the model explains the approach: ") + name);
    return r;
  };
  const fit::AfmFitResult parabola = run(fit::afm_paraboloid(10e-6), 0.0, "paraboloid R = 10 um");
  const fit::AfmFitResult sphere = run(fit::afm_sneddon_sphere(10e-6), 0.0, "sneddon-sphere R = 10 um");
  run(fit::afm_paraboloid(10e-6), 0.5e-6, "paraboloid, weight_cp 500 nm");
  run(fit::afm_sneddon_sphere(10e-6), 0.5e-6, "sneddon-sphere, weight_cp 500 nm");
  run(fit::afm_pyramid3(35.0 * kDeg), 0.0, "pyramid3 35 deg");
  run(fit::afm_pyramid3(35.0 * kDeg), 0.5e-6, "pyramid3 35 deg, weight_cp 500 nm");
  // Indentations far below R: the exact sphere is the paraboloid to O(delta/R).
  check::close(sphere.modulus, parabola.modulus, 0.01, "spot3: exact sphere ~ paraboloid at delta << R");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: test_afm_peer_models DATA_DIR\n");
    return 2;
  }
  check_model_values();
  check_recovery(fit::afm_pyramid3(35.0 * kDeg), 0.0, "pyramid3");
  check_recovery(fit::afm_sneddon_sphere(5e-6), 0.0, "sneddon-sphere");
  check_recovery(fit::afm_sneddon_sphere(5e-6), 0.5e-6, "sneddon-sphere, weight_cp");
  check_recovery(fit::afm_pyramid3(35.0 * kDeg), 0.5e-6, "pyramid3, weight_cp");
  check_weighting();
  check_spot3(argv[1]);
  return check::exit_code();
}
