// THEORY.md section 6, item 2 ("Homogeneous case"): with the exact homogeneous reduced variables
// (8/3, 1, 2, 1, 1, 1) the procedure of section 5 must give the JKR curves
//   P = (4/3) a^3 - 2 sqrt(2) a^(3/2),  D = a^2 - sqrt(2) a^(1/2)
// and the pull-offs P = -3/2 at a_bar = (9/8)^(1/3) (load control, dP/da = 0) and
// P = -5/6, D = -3/4 at a_bar = 1/2 (displacement control, dD/da = 0).
// Also: Contact in SI units against the dimensional JKR formulas, and the flags when the
// scanned range holds no minimum.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "check.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/errors.hpp"
#include "stand_in_sources.hpp"

using namespace adhesive_test;  // stand-in sources
using coatcontact::AdhesiveModel;

namespace {
namespace tier = check::tier;
// Curves: constants are interpolated as ln(c) and exponentiated: a few ulps, amplified by the
// cancellation in P near its zero; tier::kMachine relative to max(1,|P|) leaves a 100x margin.
// Pull-off location: root of the derivative to relative 1e-12 (PulloffOptions default),
// i.e. the 1e-8 requirement with three decades to spare: tier::kReference.
constexpr double kLocationTier = tier::kReference;
// Pull-off values: quadratic in the location error, so at machine level.
constexpr double kValueTier = tier::kMachine;
// Derivatives: Chebyshev differentiation of the (constant) ln X amplifies rounding of the
// node values by ~order^2 = 576: 600 * 2.2e-16 ~ 1.3e-13 in d ln X/d ln(a/t).
constexpr double kDerivativeTier = tier::kAmplified;

double jkr_load(double a) { return 4.0 / 3.0 * a * a * a - 2.0 * std::sqrt(2.0) * std::pow(a, 1.5); }
double jkr_pen(double a) { return a * a - std::sqrt(2.0 * a); }
}  // namespace

int main() {
  check::verbose = true;  // the log lists every measured error against its tier
  auto source = std::make_shared<HomogeneousSource>();
  AdhesiveModel model(source);

  // Curves at several eta (eta must not matter for identical materials).
  const std::vector<double> a_bar = {1e-3, 0.01, 0.1, 0.5, (std::cbrt(9.0 / 8.0)), 1.0, 2.0, 10.0, 100.0};
  for (double eta : {1e-3, 0.1, 1.0, 10.0, 1e3}) {
    double worst_p = 0, worst_d = 0, worst_dp = 0, worst_dd = 0;
    for (const auto& p : model.curve(eta, a_bar)) {
      const double a = p.a_bar;
      auto rel = [](double g, double w) { return std::abs(g - w) / std::max(1.0, std::abs(w)); };
      worst_p = std::max(worst_p, rel(p.load, jkr_load(a)));
      worst_d = std::max(worst_d, rel(p.penetration, jkr_pen(a)));
      worst_dp = std::max(worst_dp, rel(p.dload, 4 * a * a - 3 * std::sqrt(2.0 * a)));
      worst_dd = std::max(worst_dd, rel(p.dpenetration, 2 * a - 1 / std::sqrt(2.0 * a)));
      check::close(p.a_over_t, a / eta, tier::kRounding, "a_over_t = a_bar/eta");
    }
    const std::string at = " (eta=" + check::text(eta) + ")";
    check::below(worst_p, tier::kMachine, "JKR P worst error" + at);
    check::below(worst_d, tier::kMachine, "JKR D worst error" + at);
    check::below(worst_dp, kDerivativeTier, "JKR dP/da worst error" + at);
    check::below(worst_dd, kDerivativeTier, "JKR dD/da worst error" + at);
  }

  // Pull-offs. Load control: 4a^2 = 3 sqrt(2) a^(1/2) -> a = (9/8)^(1/3), P = -3/2,
  // D = (9/8)^(2/3) - sqrt(2) (9/8)^(1/6). Displacement control: 2a = a^(-1/2)/sqrt(2)
  // -> a = 1/2, D = -3/4, P = -5/6.
  const double a_load = std::cbrt(9.0 / 8.0);
  for (double eta : {0.01, 1.0, 100.0}) {
    const auto po = model.pulloff(eta);
    const std::string at = " (eta=" + check::text(eta) + ")";
    check::close(po.load_control.a_bar, a_load, kLocationTier, "load-control a_bar" + at);
    check::close(po.load_control.load, -1.5, kValueTier, "load-control P = -3/2" + at);
    check::close(po.load_control.penetration, jkr_pen(a_load), kValueTier, "load-control D" + at, 1.0);
    check::close(po.displacement_control.a_bar, 0.5, kLocationTier, "disp-control a_bar = 1/2" + at, 1.0);
    check::close(po.displacement_control.load, -5.0 / 6.0, kValueTier, "disp-control P = -5/6" + at, 1.0);
    check::close(po.displacement_control.penetration, -0.75, kValueTier, "disp-control D = -3/4" + at, 1.0);
    check::that(po.load_control.single_minimum && po.load_control.interior,
                "load control single interior" + at);
    check::that(po.displacement_control.single_minimum && po.displacement_control.interior,
                "disp control single interior" + at);
    check::that(po.warnings.empty(), "no warnings" + at);
    // The value minimiser alone is limited to ~sqrt(eps): it must be close but is not used.
    check::that(po.load_control.minimiser_discrepancy >= 0 && po.load_control.minimiser_discrepancy < 1e-5,
                "Brent minimiser ran and agrees to 1e-5" + at);
    std::printf("     minimiser-only location error (load, disp): %.2e %.2e\n",
                po.load_control.minimiser_discrepancy, po.displacement_control.minimiser_discrepancy);
  }

  // A range without the minimum is flagged, never silently reported as a pull-off.
  {
    coatcontact::PulloffOptions narrow;
    narrow.a_bar_min = 0.01;
    narrow.a_bar_max = 0.4;  // both minima (1.04 and 0.5) lie above
    AdhesiveModel m(source, {}, narrow);
    const auto po = m.pulloff(1.0);
    check::that(!po.load_control.interior && !po.displacement_control.interior,
                "range without minimum flagged");
    check::that(po.warnings.size() == 2, "two warnings when neither minimum is in range");
    for (const auto& w : po.warnings) std::printf("     warning: %s\n", w.c_str());
  }

  // Physical units: F = pi w R P, delta = (pi^2 w^2 R/E1*^2)^(1/3) D, a = (pi w R^2/E1*)^(1/3) a_bar,
  // checked against the dimensional JKR formulas F = 4E*a^3/(3R) - sqrt(8 pi w E*) a^(3/2),
  // delta = a^2/R - sqrt(2 pi w a/E*).
  {
    const double radius = 5e-6, thickness = 1e-6, work = 0.05;
    const double e_star = source->stack().reference_modulus();
    coatcontact::Contact sphere(model, radius, thickness, work);
    check::close(sphere.length_scale(), std::cbrt(M_PI * work * radius * radius / e_star), tier::kMachine,
                 "Maugis length");
    for (double a : {1e-9, 1e-8, 5e-8, 2e-7}) {
      const double f_jkr = 4 * e_star * a * a * a / (3 * radius) - std::sqrt(8 * M_PI * work * e_star) * std::pow(a, 1.5);
      const double d_jkr = a * a / radius - std::sqrt(2 * M_PI * work * a / e_star);
      check::close(sphere.force(a) / std::abs(f_jkr), f_jkr / std::abs(f_jkr), tier::kAmplified,
                   "SI force / JKR at a=" + check::text(a));
      check::close(sphere.penetration(a) / std::abs(d_jkr), d_jkr / std::abs(d_jkr), tier::kAmplified,
                   "SI penetration / JKR at a=" + check::text(a));
    }
    check::close(sphere.pulloff_force_load() / (M_PI * work * radius), -1.5, kValueTier,
                 "SI pull-off (load) / (pi w R)");
    check::close(sphere.pulloff_force_disp() / (M_PI * work * radius), -5.0 / 6.0, kValueTier,
                 "SI pull-off (disp) / (pi w R)", 1.0);
  }

  // Bad inputs are InputError: eta = 0, a_bar < 0, an empty a_bar list, eta = NaN, t = 0,
  // w < 0, R = 0.
  using coatcontact::InputError;
  check::throws<InputError>([&] { (void)(model.point(0.0, 1.0)); }, {});
  check::throws<InputError>([&] { (void)(model.point(1.0, -1.0)); }, {});
  check::throws<InputError>([&] { (void)(model.curve(1.0, {})); }, {});
  check::throws<InputError>([&] { (void)(model.pulloff(std::nan(""))); }, {});
  check::throws<InputError>([&] { (void)(coatcontact::Contact(model, 1.0, 0.0, 1.0)); }, {});
  check::throws<InputError>([&] { (void)(coatcontact::Contact(model, 1.0, 1.0, -1.0)); }, {});
  check::throws<InputError>([&] { (void)(coatcontact::Contact(model, 0.0, 1.0, 1.0)); }, {});
  return check::exit_code();
}
