// The reduced table of the Maugis-Dugdale cohesive zone (THEORY.md section 13, "The cohesive
// zone as a table"), against the direct per-radius solve (CohesiveZone), which stays the
// reference:
//  1. linearity in the three loads: the direct solve at (σ̂, R) equals δ_H/R + σ̂ d,
//     F_H/R + σ̂ f, g_R/R + σ̂ g_σ from two solves at R = 1;
//  2. the 1-D parts are the JKR reduced variables: δ_H = a² Δ_s, F_H = a³ Π_s/2;
//  3. homogeneous limit: the functions equal their closed forms, and the table's states
//     equal Maugis's closed form (1e-10);
//  4. every table value (m, P, D) within its own error estimate of the direct solve, over
//     four stacks (soft film, stiff film, rigid base with ν = 0.5, thin stiff top layer),
//     λ = 1e-3..1e3, ā = 0.01..10, two η.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "check.hpp"
#include "maugis_closed_form.hpp"
#include "md_tiers.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/reduced.hpp"
#include "cohesive_zone.hpp"
#include "md_table.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;
using detail::CohesiveFunctions;

namespace {
constexpr double kPi = 3.14159265358979323846;
// Table against the direct solve: the direct solve's own noise (root to 1e-13 in ln(c/a - 1),
// values ~1e-13 relative) is added to the table's error estimate.
constexpr double kDirectNoise = 1e-11;

Stack film_on(double e1, double nu1, double e0, double nu0, bool rigid = false) {
  Substrate s;
  s.material = {e0, nu0};
  s.rigid = rigid;
  return Stack::film_on({e1, nu1}, s);
}
}  // namespace

int main() {
  const Stack soft = film_on(1.0, 0.25, 10.0, 0.25), stiff = film_on(10.0, 0.25, 1.0, 0.25);
  const Stack rigid_base = film_on(1.0, 0.5, 1.0, 0.5, true);
  Substrate base;
  base.material = {100.0, 0.25};
  const Stack thin_top({{0.05, {10.0, 0.3}}, {0.95, {1.0, 0.45}}}, base);
  const Stack homogeneous = film_on(1.0, 0.3, 1.0, 0.3);
  detail::Discretization disc;
  const detail::CohesiveQuadrature quadrature;

  // 1. Linearity in (1/R, δ, σ̂) at a handful of (a, c), soft and stiff films.
  for (const Stack* stack : {&soft, &stiff}) {
    const detail::TableKernel kernel(*stack);
    for (double a : {0.05, 0.7, 4.0}) {
      const detail::CohesiveZone unit(kernel, a, 1.0, disc, quadrature);
      for (double excess : {1e-3, 0.3, 20.0}) {
        const CohesiveFunctions f = detail::cohesive_functions(unit, excess);
        const double radius = 3.7, sigma_hat = 0.45;
        const detail::CohesiveZone zone(kernel, a, radius, disc, quadrature);
        const detail::CohesiveState st = zone.evaluate(sigma_hat, excess);
        const std::string at = " a/t=" + check::text(a) + " c/a-1=" + check::text(excess);
        const double delta = f.delta_h / radius + sigma_hat * f.d;
        const double force = f.force_h / radius + sigma_hat * f.f;
        const double gap = f.g_r / radius + sigma_hat * f.g_s;
        check::close(st.delta, delta, check::tier::kReference, "linearity: delta" + at,
                     std::abs(f.delta_h / radius) + std::abs(sigma_hat * f.d));
        check::close(st.force, force, check::tier::kReference, "linearity: F" + at,
                     std::abs(f.force_h / radius) + std::abs(sigma_hat * f.f));
        check::close(st.gap, gap, check::tier::kReference, "linearity: h(c)" + at,
                     std::abs(f.g_r / radius) + std::abs(sigma_hat * f.g_s));
      }
    }
  }

  // 2. The 1-D parts are the JKR reduced variables of section 5.
  {
    const detail::TableKernel kernel(soft);
    const ReducedSolver solver(soft);
    for (double a : {0.03, 1.0, 30.0}) {
      const detail::CohesiveZone zone(kernel, a, 1.0, disc, quadrature);
      const CohesiveFunctions f = detail::cohesive_functions(zone, 0.5);
      const ReducedVariables r = solver.solve(a, 1e-11);
      check::close(f.delta_h, a * a * r.delta_s, 1e-9, "delta_H = a^2 Delta_s at a/t=" + check::text(a));
      check::close(f.force_h, a * a * a * r.pi_s / 2.0, 1e-9, "F_H = a^3 Pi_s/2 at a/t=" + check::text(a));
    }
  }

  // 3. Homogeneous limit: functions and the table's states against the closed forms.
  {
    const detail::TableKernel kernel(homogeneous);
    double worst = 0.0;
    for (double a : {0.01, 1.0, 50.0}) {
      const detail::CohesiveZone zone(kernel, a, 1.0, disc, quadrature);
      for (double excess : {1e-6, 1e-2, 1.0, 1e4}) {
        const CohesiveFunctions f = detail::cohesive_functions(zone, excess);
        const CohesiveFunctions h = detail::homogeneous_functions(a, excess);
        const std::string at = " a/t=" + check::text(a) + " c/a-1=" + check::text(excess);
        for (auto [got, want, name] : {std::tuple{f.d, h.d, "d"}, std::tuple{f.f, h.f, "f"},
                                       std::tuple{f.g_r, h.g_r, "g_R"}, std::tuple{f.g_s, h.g_s, "g_sigma"},
                                       std::tuple{f.delta_h, h.delta_h, "delta_H"},
                                       std::tuple{f.force_h, h.force_h, "F_H"}}) {
          check::close(got, want, check::tier::kInterpolation, std::string("homogeneous closed form ") + name + at);
          worst = std::max(worst, std::abs(got - want) / std::abs(want));
        }
      }
    }
    std::printf("homogeneous functions vs closed forms: worst relative difference %.2e\n", worst);
    detail::MdTableOptions small;
    small.a_over_t_min = 1e-2;
    small.a_over_t_max = 1e1;
    small.step = 0.5;
    small.c_over_t_max = 1e3;
    const detail::MaugisDugdaleTable table(kernel, disc, quadrature, small);
    const double k13 = std::cbrt(4.0 / 3.0), k23 = k13 * k13;
    const double eta = 1.0;
    worst = 0.0;
    for (double lambda : {0.1, 0.5, 1.0, 3.0}) {
      for (double a_bar : {0.1, 0.5, 1.0, 2.0}) {
        const double sigma_hat = lambda * std::cbrt(16.0 / 9.0) / eta;
        const double h0 = 2.0 / (kPi * eta * eta * eta * sigma_hat);
        const auto st = table.solve(sigma_hat, h0, a_bar / eta);
        const std::string at = " lambda=" + check::text(lambda) + " a_bar=" + check::text(a_bar);
        if (!check::that(st.has_value(), "homogeneous table state exists" + at)) continue;
        const maugis::State want = maugis::solve(lambda, k13 * a_bar);
        const double p = eta * eta * eta * st->force, d = eta * eta * st->delta;
        check::close(1.0 + st->excess, want.m, check::tier::kInterpolation, "homogeneous table m vs Maugis" + at);
        check::close(p, want.load, check::tier::kInterpolation, "homogeneous table P vs Maugis" + at, 1.0);
        check::close(d * k23, want.penetration, check::tier::kInterpolation, "homogeneous table Delta_M vs Maugis" + at,
                     1.0);
        worst = std::max({worst, std::abs(1.0 + st->excess - want.m) / want.m, std::abs(p - want.load),
                          std::abs(d * k23 - want.penetration)});
      }
    }
    std::printf("homogeneous table states vs Maugis's closed form: worst difference %.2e\n", worst);
    for (double lambda : {0.01, 1.0, 30.0}) {
      const double sigma_hat = lambda * std::cbrt(16.0 / 9.0) / eta;
      const double h0 = 2.0 / (kPi * eta * eta * eta * sigma_hat);
      const auto st = table.solve_end(sigma_hat, h0);
      const std::string at = " lambda=" + check::text(lambda);
      if (!check::that(st.has_value(), "homogeneous end of the curve from the table" + at)) continue;
      const maugis::State want = maugis::end_of_curve(lambda);
      check::close(eta * eta * eta * st->force, want.load, check::tier::kInterpolation,
                   "homogeneous table P(a -> 0) vs Maugis" + at, 1.0);
      check::close(eta * eta * st->delta * k23, want.penetration, check::tier::kInterpolation,
                   "homogeneous table Delta_M(a -> 0) vs Maugis" + at, 1.0);
    }
  }

  // 4. Table against the direct solve, each within the table's error estimate.
  {
    // The table's range per stack covers a/t = a_bar/eta of its points. The thin top layer's
    // kernel varies on the layer's scale, so its annulus needs 20 times more pieces: its table
    // stops at c/t = 100 (eta = 3 only) to keep the test's time down.
    struct Named {
      const Stack* stack;
      const char* name;
      std::vector<double> etas;
      double a_max, c_max;
    };
    int compared = 0, compared_end = 0, outside = 0;
    for (const Named& s : {Named{&soft, "soft film", {0.3, 3.0}, 50.0, 1e4},
                           Named{&stiff, "stiff film", {0.3, 3.0}, 50.0, 1e4},
                           Named{&rigid_base, "rigid base nu=0.5", {0.3, 3.0}, 50.0, 1e4},
                           Named{&thin_top, "thin stiff top layer", {3.0}, 5.0, 100.0}}) {
      const detail::TableKernel kernel(*s.stack);
      detail::MdTableOptions range;
      range.a_over_t_min = 2e-3;
      range.a_over_t_max = s.a_max;
      range.c_over_t_max = s.c_max;
      // Only the tiles the compared points need are built (the table's default).
      const detail::MaugisDugdaleTable table(kernel, disc, quadrature, range);
      double worst_ratio = 0.0, worst_m = 0.0, worst_p = 0.0, worst_d = 0.0;
      for (double eta : s.etas) {
        for (double lambda : {1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3}) {
          const double sigma_hat = lambda * std::cbrt(16.0 / 9.0) / eta;
          const double h0 = 2.0 / (kPi * eta * eta * eta * sigma_hat);
          {  // the end of the curve, a = 0
            const auto st = table.solve_end(sigma_hat, h0);
            const std::string at = std::string(" ") + s.name + " eta=" + check::text(eta) + " lambda=" + check::text(lambda) + " a=0";
            if (st) {
              const detail::CohesiveZone zone(kernel, 0.0, 1.0, disc, quadrature);
              const detail::CohesiveState want = zone.solve(sigma_hat, h0, st->excess, 0.05);
              check::below(std::abs(st->excess - want.excess), st->excess_error + kDirectNoise * want.excess,
                           "c within its error estimate" + at);
              check::below(std::abs(st->delta - want.delta), st->delta_error + kDirectNoise * std::abs(want.delta),
                           "delta within its error estimate" + at);
              check::below(std::abs(st->force - want.force), st->force_error + kDirectNoise * std::abs(want.force),
                           "F within its error estimate" + at);
              ++compared_end;
            } else {
              ++outside;
            }
          }
          for (double a_bar : {0.01, 0.1, 1.0, 10.0}) {
            const double a = a_bar / eta;
            const auto st = table.solve(sigma_hat, h0, a);
            if (!st) {
              ++outside;
              continue;
            }
            const detail::CohesiveZone zone(kernel, a, 1.0, disc, quadrature);
            const detail::CohesiveState want = zone.solve(sigma_hat, h0, st->excess, 0.05);
            const std::string at = std::string(" ") + s.name + " eta=" + check::text(eta) + " lambda=" + check::text(lambda) +
                                   " a_bar=" + check::text(a_bar);
            const double e_m = std::abs(st->excess - want.excess);
            const double e_d = std::abs(st->delta - want.delta), e_f = std::abs(st->force - want.force);
            const double b_m = st->excess_error + kDirectNoise * want.excess;
            const double b_d = st->delta_error + kDirectNoise * std::abs(want.delta);
            const double b_f = st->force_error + kDirectNoise * std::abs(want.force);
            check::below(e_m, b_m, "c/a - 1 within its error estimate" + at);
            check::below(e_d, b_d, "delta within its error estimate" + at);
            check::below(e_f, b_f, "F within its error estimate" + at);
            worst_ratio = std::max({worst_ratio, e_m / b_m, e_d / b_d, e_f / b_f});
            worst_m = std::max(worst_m, e_m / (1.0 + want.excess));
            worst_p = std::max(worst_p, e_f / std::max(std::abs(want.force), 1.0 / (eta * eta * eta)));
            worst_d = std::max(worst_d, e_d / std::max(std::abs(want.delta), 1.0 / (eta * eta)));
            ++compared;
          }
        }
      }
      std::printf("%s: worst |table - direct| / estimate %.3f; worst error of m %.2e, P %.2e, D %.2e (relative to max(|value|, 1))\n",
                  s.name, worst_ratio, worst_m, worst_p, worst_d);
      std::printf("%s: %ld direct solves of the %d x %d table's tiles in %.2f s\n", s.name, table.nodes_solved(),
                  table.nodes_x(), table.nodes_s(), table.build_seconds());
    }
    std::printf("table vs direct: %d points and %d curve ends compared, %d outside the table's range\n", compared,
                compared_end, outside);
    check::that(compared >= 100, "at least 100 points compared (got " + std::to_string(compared) + ")");
  }
  // 5. Pull-offs through the table (MaugisDugdaleOptions::use_table) against the direct ones:
  //    the table's states (above) carry at most ~6e-5 in P and D (relative to max(|value|, 1)),
  //    so kTableTier leaves a margin of 10 for the minimum's location.
  {
    constexpr double kTableTier = 1e-3;
    MaugisDugdaleOptions with_table;
    with_table.use_table = true;
    with_table.table_a_over_t_min = 1e-4;
    with_table.table_a_over_t_max = 50.0;
    const MaugisDugdaleModel direct(soft), tabled(soft, with_table);
    for (auto [eta, lambda] : {std::pair{1.0, 1.0}, std::pair{0.3, 0.1}, std::pair{3.0, 10.0}}) {
      const MaugisDugdalePulloff want = direct.pulloff(eta, lambda), got = tabled.pulloff(eta, lambda);
      const std::string at = " soft film eta=" + check::text(eta) + " lambda=" + check::text(lambda);
      std::printf("pull-off%s: P (load) table %.10f direct %.10f; D (displacement) table %.10f direct %.10f\n",
                  at.c_str(), got.load_control.point.load, want.load_control.point.load,
                  got.displacement_control.point.penetration, want.displacement_control.point.penetration);
      check::close(got.load_control.point.load, want.load_control.point.load, kTableTier, "pull-off P (load)" + at, 1.0);
      check::close(got.displacement_control.point.penetration, want.displacement_control.point.penetration,
                   kTableTier, "pull-off D (displacement)" + at, 1.0);
      // The pull-off values within their error estimates of the direct curve at the table's
      // location (the location itself is the minimiser's, ~1e-7).
      for (const auto* p : {&got.load_control.point, &got.displacement_control.point}) {
        const MaugisDugdalePoint d = direct.point(eta, lambda, p->a_bar);
        check::below(std::abs(p->load - d.load), p->load_error + d.load_error, "pull-off point P within its estimate" + at);
        check::below(std::abs(p->penetration - d.penetration), p->penetration_error + d.penetration_error,
                     "pull-off point D within its estimate" + at);
      }
    }
    // Pull-offs where the curve's end and an interior minimum are within the table's estimates
    // of each other (stiff film, small lambda): the reported value within its estimate of the
    // direct pull-off.
    {
      MaugisDugdaleOptions stiff_table = with_table;
      const MaugisDugdaleModel stiff_direct(stiff), stiff_tabled(stiff, stiff_table);
      for (auto [eta, lambda] : {std::pair{1.0, 0.01}, std::pair{1.0, 0.31622776601683794}, std::pair{10.0, 0.01}}) {
        const MaugisDugdalePulloff want = stiff_direct.pulloff(eta, lambda), got = stiff_tabled.pulloff(eta, lambda);
        const std::string at = " stiff film eta=" + check::text(eta) + " lambda=" + check::text(lambda);
        check::below(std::abs(got.load_control.point.load - want.load_control.point.load),
                     got.load_control.point.load_error + want.load_control.point.load_error,
                     "pull-off P (load) within its estimate" + at);
        check::below(std::abs(got.displacement_control.point.penetration - want.displacement_control.point.penetration),
                     got.displacement_control.point.penetration_error + want.displacement_control.point.penetration_error,
                     "pull-off D (displacement) within its estimate" + at);
      }
    }
    // 6. Curve points of the model (MaugisDugdaleModel::curve, as the CLI and the fit use it)
    //    within their error estimates of the direct ones, with the end of the curve.
    int curve_points = 0;
    for (double lambda : {0.01, 0.3, 1.0, 10.0}) {
      const std::vector<double> a_bar = {0.0, 0.02, 0.2, 0.7, 1.5, 4.0};
      const auto got = tabled.curve(1.0, lambda, a_bar), want = direct.curve(1.0, lambda, a_bar);
      for (std::size_t k = 0; k < a_bar.size(); ++k) {
        const std::string at = " soft film eta=1 lambda=" + check::text(lambda) + " a_bar=" + check::text(a_bar[k]);
        check::that(got[k].from_table, "curve point from the table" + at);
        check::below(std::abs(got[k].load - want[k].load), got[k].load_error + want[k].load_error,
                     "curve P within its estimate" + at);
        check::below(std::abs(got[k].penetration - want[k].penetration),
                     got[k].penetration_error + want[k].penetration_error, "curve D within its estimate" + at);
        ++curve_points;
      }
    }
    std::printf("model curve points from the table: %d compared; table nodes %ld\n", curve_points,
                tabled.table_nodes());
    // 7. Through a spring (THEORY.md sections 10 and 13): between load and displacement control,
    //    from the table within its estimate of the direct one.
    for (double k_bar : {0.3, 3.0}) {
      const double eta = 1.0, lambda = 1.0;
      const MaugisDugdalePulloff want = direct.pulloff_spring(eta, lambda, k_bar),
                                 got = tabled.pulloff_spring(eta, lambda, k_bar);
      const std::string at = " soft film eta=1 lambda=1 k_bar=" + check::text(k_bar);
      std::printf("spring pull-off%s: P table %.10f direct %.10f\n", at.c_str(), got.spring_control.point.load,
                  want.spring_control.point.load);
      check::that(want.load_control.point.load <= want.spring_control.point.load &&
                      want.spring_control.point.load <= want.displacement_control.point.load,
                  "P_load <= P_spring <= P_disp" + at);
      const auto z = [k_bar](const MaugisDugdalePoint& p) { return p.penetration + p.load / k_bar; };
      const MaugisDugdalePoint& t = got.spring_control.point;
      check::below(std::abs(z(t) - z(want.spring_control.point)),
                   t.penetration_error + t.load_error / k_bar + want.spring_control.point.penetration_error +
                       want.spring_control.point.load_error / k_bar,
                   "spring pull-off Z within its estimate" + at);
    }
  }
  // 8. Large lambda through a spring: the homogeneous JKR value of THEORY.md section 10's quintic
  //    (k_bar = 1: P = -1.410238343649), approached like 1/lambda^2 (~1e-6 at lambda = 1e3).
  {
    // The 1/lambda^2 approach leaves ~1e-6 at lambda = 1e3; the location is flat to first order.
    constexpr double kJkrApproachTier = 1e-4, kJkrLocationTier = 1e-3;
    const MaugisDugdaleModel homogeneous_md(homogeneous);
    const MaugisDugdalePulloff p = homogeneous_md.pulloff_spring(1.0, 1e3, 1.0);
    std::printf("homogeneous spring pull-off at lambda = 1e3, k_bar = 1: P = %.10f (JKR -1.410238343649)\n",
                p.spring_control.point.load);
    check::close(p.spring_control.point.load, -1.410238343649, kJkrApproachTier,
                 "homogeneous spring pull-off vs JKR quintic", 1.0);
    check::close(p.spring_control.point.a_bar, 0.862633136333, kJkrLocationTier,
                 "homogeneous spring pull-off a_bar vs JKR quintic");
  }
  // 9. Elastic indenter (THEORY.md sections 9 and 13): film = substrate with an elastic tip is
  //    Maugis's closed form in E_r units, by the direct solve and from the table.
  {
    Indenter tip;
    tip.rigid = false;
    tip.material = {0.7, 0.2};
    Substrate same;
    same.material = {1.0, 0.3};
    const Stack elastic_tip = Stack::film_on({1.0, 0.3}, same, tip);
    MaugisDugdaleOptions with_table;
    with_table.use_table = true;
    const MaugisDugdaleModel direct(elastic_tip), tabled(elastic_tip, with_table);
    const double k13 = std::cbrt(4.0 / 3.0), k23 = k13 * k13;
    double worst = 0.0;
    for (double lambda : {0.1, 1.0, 10.0}) {
      for (double a_bar : {0.2, 1.0, 3.0}) {
        const maugis::State want = maugis::solve(lambda, k13 * a_bar);
        const std::string at = " elastic tip lambda=" + check::text(lambda) + " a_bar=" + check::text(a_bar);
        const MaugisDugdalePoint d = direct.point(1.0, lambda, a_bar), t = tabled.point(1.0, lambda, a_bar);
        check::close(d.m, want.m, check::tier::kInterpolation, "elastic tip: direct m vs Maugis" + at);
        check::close(d.load, want.load, check::tier::kInterpolation, "elastic tip: direct P vs Maugis" + at, 1.0);
        check::close(d.penetration * k23, want.penetration, check::tier::kInterpolation,
                     "elastic tip: direct Delta_M vs Maugis" + at, 1.0);
        check::close(t.load, want.load, check::tier::kInterpolation, "elastic tip: table P vs Maugis" + at, 1.0);
        worst = std::max({worst, std::abs(d.load - want.load), std::abs(t.load - want.load)});
      }
    }
    std::printf("elastic tip on a homogeneous solid vs Maugis (E_r units): worst |P| difference %.2e\n", worst);
  }
  return check::exit_code();
}
