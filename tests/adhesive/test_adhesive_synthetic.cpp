// Interpolation and pull-off machinery against smooth synthetic reduced variables with
// analytic derivatives (THEORY.md section 5; supports the pull-off checks of section 6, items 2 and 4-7):
//  1. interpolation error of the values and of d ln X/d ln(a/t) at points between nodes;
//  2. pull-off location against an independent bisection on the exact derivative: the
//     1e-8 relative requirement;
//  3. a curve with two local minima of P is flagged, and the lower one is reported.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "check.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "stand_in_sources.hpp"

using namespace adhesive_test;  // stand-in sources
using coatcontact::AdhesiveModel;

namespace {
// Order-24 Chebyshev per decade of a/t in ln(a/t): for these sigmoids (poles at distance
// pi/n from the real axis) the series converge like rho^-24 with rho ~ 4.5, i.e. to ~1e-15;
// the tail test bounds the values: tier::kInterpolation.
constexpr double kInterpolationTier = check::tier::kInterpolation;
// Derivatives of a Chebyshev interpolant lose up to order^2 ~ 600 against values.
constexpr double kDerivativeTier = 100 * kInterpolationTier;
// The requirement on the pull-off location.
constexpr double kLocationTier = check::tier::kSolver;
// Pull-off values (second order in location, first order in the interpolated values).
constexpr double kValueTier = kInterpolationTier;

std::shared_ptr<SyntheticSource> like_film(double ratio) {
  // E1*/E0* = ratio: E_eq -> 1/ratio, Gamma -> 1/sqrt(ratio), Pi_s -> 8/(3 ratio) at large a/t.
  const double r = 1.0 / ratio;
  return std::make_shared<SyntheticSource>(sigmoid(8.0 / 3.0, 8.0 / 3.0 * r, 2.0, 1.1), sigmoid(1.0, 0.8, 3.0, 1.5),
                                           sigmoid(1.0, r, 1.0, 1.27), sigmoid(1.0, std::sqrt(r), 0.7, 1.2), ratio);
}
}  // namespace

int main() {
  check::verbose = true;  // the log lists every measured error against its tier
  std::mt19937_64 rng(12345);
  for (double ratio : {0.1, 10.0}) {
    auto src = like_film(ratio);
    AdhesiveModel model(src);
    const auto& table = model.table();
    std::uniform_real_distribution<double> u(std::log(1e-4), std::log(1e4));
    double worst_value = 0, worst_dlog = 0;
    for (int i = 0; i < 2000; ++i) {
      const double x = std::exp(u(rng));
      const auto p = table.at(x);
      auto rel = [](double g, double w) { return std::abs(g - w) / std::abs(w); };
      worst_value = std::max({worst_value, rel(p.pi_s, src->pi_s().f(x)), rel(p.delta_s, src->delta_s().f(x)),
                              rel(p.e_eq, src->e_eq().f(x)), rel(p.gamma1, src->gamma1().f(x))});
      worst_dlog = std::max({worst_dlog, std::abs(p.dlog_pi_s - src->pi_s().dlog(x)),
                             std::abs(p.dlog_delta_s - src->delta_s().dlog(x)),
                             std::abs(p.dlog_e_eq - src->e_eq().dlog(x)),
                             std::abs(p.dlog_gamma1 - src->gamma1().dlog(x))});
    }
    const std::string at = " (E1*/E0*=" + std::to_string(ratio) + ")";
    std::printf("     table: %zu segments, %zu evaluations, tail estimate %.2e\n", table.segments(),
                table.source_evaluations(), table.interpolation_error_estimate());
    check::below(worst_value, kInterpolationTier, "worst relative value error" + at);
    check::below(worst_dlog, kDerivativeTier, "worst d ln X/d ln(a/t) error" + at);

    for (double eta : {0.01, 0.1, 1.0, 10.0, 100.0}) {
      const auto po = model.pulloff(eta);
      const std::string e = " eta=" + std::to_string(eta) + at;
      // Reference: bisection on the exact derivative inside +-20% of the found point,
      // after checking the bracket.
      const double a_l = po.load_control.a_bar, a_d = po.displacement_control.a_bar;
      auto dp = [&](double a) { return src->dload(eta, a); };
      auto dd = [&](double a) { return src->dpenetration(eta, a); };
      check::that(dp(0.8 * a_l) < 0 && dp(1.2 * a_l) > 0, "exact dP/da brackets the load pull-off" + e);
      check::that(dd(0.8 * a_d) < 0 && dd(1.2 * a_d) > 0, "exact dD/da brackets the disp pull-off" + e);
      const double ref_l = bisect(dp, 0.8 * a_l, 1.2 * a_l);
      const double ref_d = bisect(dd, 0.8 * a_d, 1.2 * a_d);
      check::close(a_l / ref_l, 1.0, kLocationTier, "load a_bar / exact" + e);
      check::close(a_d / ref_d, 1.0, kLocationTier, "disp a_bar / exact" + e);
      check::close(po.load_control.load, src->load(eta, ref_l), kValueTier, "P_load vs exact" + e, 1.0);
      check::close(po.displacement_control.penetration, src->penetration(eta, ref_d), kValueTier,
                   "D_disp vs exact" + e, 1.0);
      check::close(po.displacement_control.load, src->load(eta, ref_d), kValueTier, "P_disp vs exact" + e,
                   1.0);
      check::that(po.warnings.empty(), "single minima" + e);
    }
  }

  // Two minima: a narrow bump of E_eq at a/t = 2 (eta = 1) adds a second dip of P near
  // a_bar = 2 besides the JKR one near 1.04.
  {
    Smooth bump{[](double x) { return 1.0 + 0.5 * std::exp(-std::pow(std::log(x / 2.0), 2) / (2 * 0.15 * 0.15)); },
                [](double x) {
                  const double l = std::log(x / 2.0);
                  const double g = 0.5 * std::exp(-l * l / (2 * 0.15 * 0.15));
                  return -g * l / (0.15 * 0.15) / (1.0 + g);
                }};
    auto src = std::make_shared<SyntheticSource>(constant(8.0 / 3.0), constant(1.0), bump, constant(1.0), 1.0);
    AdhesiveModel model(src);
    const auto po = model.pulloff(1.0);
    check::that(po.load_control.local_minima == 2 && !po.load_control.single_minimum,
                "two minima of P counted");
    check::that(!po.warnings.empty(), "warning issued for two minima");
    for (const auto& w : po.warnings) std::printf("     warning: %s\n", w.c_str());
    // Reference: every sign change of the exact dP/da on a fine grid, refined by bisection;
    // the lower of the two minima must be the one reported.
    auto dp = [&](double a) { return src->dload(1.0, a); };
    std::vector<double> minima;
    for (double a = 0.5; a < 4.0; a *= 1.001) {
      if (dp(a) < 0 && dp(a * 1.001) >= 0) minima.push_back(bisect(dp, a, a * 1.001));
    }
    check::that(minima.size() == 2, "reference finds two minima");
    if (minima.size() == 2) {
      const double ref = src->load(1.0, minima[0]) < src->load(1.0, minima[1]) ? minima[0] : minima[1];
      std::printf("     exact minima at a_bar %.6f (P %.6f) and %.6f (P %.6f)\n", minima[0],
                  src->load(1.0, minima[0]), minima[1], src->load(1.0, minima[1]));
      check::close(po.load_control.a_bar / ref, 1.0, kLocationTier, "lower minimum reported (a_bar)");
      check::close(po.load_control.load, src->load(1.0, ref), kValueTier, "lower minimum reported (P)", 1.0);
    }
  }
  return check::exit_code();
}
