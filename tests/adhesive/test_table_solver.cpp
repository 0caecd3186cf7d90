// Interpolation error of the reduced-variable table against direct ReducedSolver values at
// points between the Chebyshev nodes (the measurement behind "interpolate, don't solve per
// point"; THEORY.md section 5), the section-6 identity (item 1) Gamma(1)^2 = d(a/t E_eq)/d(a/t) on the
// interpolated derivatives, and the stability of the pull-off location under a tighter table.
// Timings are printed for the report only (no timed assertions).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "check.hpp"
#include "materials.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"

namespace {
// Nodes and direct values both at the solver's default tolerance; the interpolant adds its
// tail (<= 1e-10 + 10 x node error estimate). Tier: the solver's default accuracy, i.e. the
// interpolated curve is as good as a direct solve.
constexpr double kTolerance = coatcontact::kDefaultTolerance;
constexpr double kInterpolationTier = check::tier::kSolver;
// The identity [EqGde1] with a differentiated interpolant: a converged solver satisfies it to
// 1e-7 (THEORY.md section 6, item 1); differentiation of the interpolant costs up to
// ~order^2 = 600 x the node error, which is far below 1e-8 in practice.
constexpr double kIdentityTier = check::tier::kIdentityByDifferences;
// Pull-off location: the 1e-8 relative requirement, table at 1e-8 vs table at 1e-9.
constexpr double kLocationTier = check::tier::kSolver;

using coatcontact::test::material;
}  // namespace

int main() {
  check::verbose = true;  // the log lists every measured error against its tier
  struct Case {
    const char* name;
    coatcontact::Material film;
    coatcontact::Substrate substrate;
  };
  std::vector<Case> cases;
  for (double ratio : {0.1, 10.0}) {
    coatcontact::Substrate s;
    s.material = material(1e9, 0.25);
    cases.push_back({ratio < 1 ? "soft film 0.1" : "stiff film 10", material(1e9 * ratio, 0.25), s});
  }
  coatcontact::Substrate rigid;
  rigid.rigid = true;
  cases.push_back({"rigid, nu1=0.25", material(1e9, 0.25), rigid});
  cases.push_back({"rigid, nu1=0.5", material(1e9, 0.5), rigid});

  std::mt19937_64 rng(2024);
  for (const auto& c : cases) {
    const coatcontact::ReducedSolver solver(coatcontact::Stack::film_on(c.film, c.substrate));
    coatcontact::SolverSource source(solver, kTolerance);
    coatcontact::ReducedTable table(source);
    // Decades of a/t from 1e-3 upwards, to 1e3 or to the first decade the solver cannot
    // deliver (reported; at least up to 1e2 is required).
    const auto t0 = std::chrono::steady_clock::now();
    double top = 1e-3;
    for (int k = -3; k < 3; ++k) {
      try {
        table.prepare(std::pow(10.0, k + 0.5), std::pow(10.0, k + 0.5));
        top = std::pow(10.0, k + 1) * (1 - 1e-12);
      } catch (const coatcontact::NumericalError& e) {
        std::printf("     %s: solver unavailable in a/t [1e%d, 1e%d]: %s\n", c.name, k, k + 1, e.what());
        break;
      }
    }
    const double t_table = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    check::that(top >= 9.9, std::string("table reaches a/t = 10, ") + c.name);

    std::uniform_real_distribution<double> u(std::log(1e-3), std::log(top));
    std::vector<double> x(60);
    for (auto& v : x) v = std::exp(u(rng));
    const auto t1 = std::chrono::steady_clock::now();
    const auto direct = solver.sweep(x, kTolerance);
    const double t_direct = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    double worst = 0, worst_identity = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const auto p = table.at(x[i]);
      auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
      worst = std::max({worst, rel(p.pi_s, direct[i].pi_s), rel(p.delta_s, direct[i].delta_s),
                        rel(p.pi_c, direct[i].pi_c), rel(p.delta_c, direct[i].delta_c), rel(p.e_eq, direct[i].e_eq),
                        rel(p.gamma1, direct[i].gamma1)});
      // Gamma^2 = d(x E)/dx = E (1 + d ln E/d ln x)
      worst_identity = std::max(worst_identity, rel(p.gamma1 * p.gamma1, p.e_eq * (1 + p.dlog_e_eq)));
    }
    std::printf("     %-16s table a/t in [1e-3,%.0f]: %zu segments, %zu solves, %.3f s (%.2f ms/solve); "
                "direct: %zu solves %.3f s; tail est %.1e, solver est %.1e\n",
                c.name, top, table.segments(), table.source_evaluations(), t_table,
                1e3 * t_table / static_cast<double>(table.source_evaluations()), x.size(), t_direct,
                table.interpolation_error_estimate(), table.source_error_estimate());
    check::below(worst, kInterpolationTier, std::string("worst interpolation error, ") + c.name);
    check::below(worst_identity, kIdentityTier, std::string("Gamma^2 = d(xE)/dx from table, ") + c.name);

    if (!c.substrate.rigid || c.film.poisson_ratio < 0.5) {
      coatcontact::AdhesiveModel m8(solver, 1e-8);
      coatcontact::AdhesiveModel m9(solver, 1e-9);
      double worst_loc = 0;
      for (double eta : {0.3, 1.0, 3.0}) {
        const auto a = m8.pulloff(eta), b = m9.pulloff(eta);
        worst_loc = std::max({worst_loc, std::abs(a.load_control.a_bar / b.load_control.a_bar - 1),
                              std::abs(a.displacement_control.a_bar / b.displacement_control.a_bar - 1)});
      }
      check::below(worst_loc, kLocationTier, std::string("pull-off location, table 1e-8 vs 1e-9, ") + c.name);
    }
  }
  return check::exit_code();
}
