// Maugis-Dugdale adhesive sphere on a coated substrate (THEORY.md section 13): the Maugis
// normalization on top of the per-radius cohesive-zone solve (cpp/loads/cohesive_zone.hpp),
// the curve down to its end a -> 0, and the pull-offs.
//
// Units of the solve: t = 1, E* = 1 and R = 1 (the paraboloid makes R scale out). Then the
// Maugis length is (pi w R^2/E*)^(1/3) = t/eta, so pi w = eta^-3 and
//   sigma_hat = 2 sigma0/E* = lambda K^(2/3)/eta,  h0 = w/sigma0 = 2/(pi eta^3 sigma_hat),
//   a/t = a_bar/eta,  P = F/(pi w R) = eta^3 F,  D = delta/(t^2/(eta^2 R)) = eta^2 delta.
//
// Pull-off: the minimum of P (or D) over a_bar is located on a log grid, each grid minimum
// refined by Brent's minimiser in ln a_bar. Values near a minimum are flat, so that locates
// a_bar only to ~location_tolerance (the minimum value itself to ~its square plus the noise
// of the root c(a), ~1e-13); the location is then refined as the root of dP/da_bar (dD/da_bar)
// differentiated implicitly through c(a) (THEORY.md section 13), to ~1e-10 (the direct solve; a
// half-space's closed form, exactly; a tiled table's ~1e-5 values leave the minimiser's). Near
// DMT's end P is so flat that the minimiser is off by up to ~1e-3 there, and the root's own
// error, its slope's noise over the slope's derivative, enters the estimates ("Error estimates
// of the state", "Flat minima").
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/solve_cache.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "parallel.hpp"
#include "cohesive_zone.hpp"
#include "md_table.hpp"
#include "solve_cache.hpp"
#include "table_kernel.hpp"

namespace coatcontact {

namespace {

using detail::kPi;
// First bracket step in ln(c/a - 1) from a guess interpolated between neighbouring a_bar.
constexpr double kNearStep = 0.05;
constexpr double kMinNearStep = 1e-7;
// First root step from the minimiser's c/a - 1: the refinement's points lie mostly within 100
// location tolerances (1e-5) of its a_bar (at most a grid cell, where P is flat).
constexpr double kSlopeStep = 1e-4;
// Relative error of a direct solve's values (tests/adhesive/test_md_table.cpp: root to 1e-13 in
// ln(c/a - 1), values ~1e-13 relative, with a margin).
constexpr double kDirectNoise = 1e-11;
// Location of a direct pull-off: the root of the implicit derivative (~1e-10 relative, with a
// margin; MaugisDugdaleModel::refine).
constexpr double kDirectLocation = 1e-9;
// Step in ln a_bar of the central differences at a pull-off from the table (locate_errors): the
// curve and the table's change vary over a grid cell (0.3 in ln a).
constexpr double kErrorStep = 0.01;

void check_value(double value, const std::string& what, bool zero_allowed) {
  if (!std::isfinite(value) || !(zero_allowed ? value >= 0.0 : value > 0.0)) {
    throw InputError(what + " = " + detail::full_precision(value) + " not allowed (need finite and " +
                     (zero_allowed ? ">= 0)" : "> 0)"));
  }
}

// The quantity whose minimum along the curve is the pull-off: P (load control), D
// (displacement control) or Z = D + P/k_bar (a spring, THEORY.md section 10).
struct Control {
  enum Kind { kLoad, kDisplacement, kSpring } kind;
  double k_bar = 0.0;
};
double value_of(const MaugisDugdalePoint& p, Control c) {
  switch (c.kind) {
    case Control::kLoad: return p.load;
    case Control::kDisplacement: return p.penetration;
    default: return p.penetration + p.load / c.k_bar;
  }
}
double error_of(const MaugisDugdalePoint& p, Control c) {
  switch (c.kind) {
    case Control::kLoad: return p.load_error;
    case Control::kDisplacement: return p.penetration_error;
    default: return p.penetration_error + p.load_error / c.k_bar;
  }
}

// A table point's change when the coarse splines stand for the fine ones (MdTableState::*_shift),
// in the point's units: P, D, m.
struct PointShift {
  double load = 0.0, penetration = 0.0, m = 0.0;
};
double shift_of(const PointShift& s, Control c) {
  switch (c.kind) {
    case Control::kLoad: return s.load;
    case Control::kDisplacement: return s.penetration;
    default: return s.penetration + s.load / c.k_bar;
  }
}

// Error estimates at a minimum at ln a_bar = x from the table (THEORY.md section 13, "Error
// estimates of the state"): the minimum each check gives lies dx = -E'/V'' away (E the check's
// change of the minimised V, V'' by central differences of the curve), and every printed
// quantity's change there is its own E plus its slope times dx; each estimate is
// kStateErrorFactor times the largest weighted change, plus the minimiser's location tolerance
// times the slope.
using PointAt = std::function<const MaugisDugdalePoint&(double)>;
using Shifts = std::map<double, std::array<PointShift, detail::kStateChecks>>;
void locate_errors(MaugisDugdalePoint& q, double x, Control control, const PointAt& point_at, const Shifts& shifts,
                   double tol, bool checks = true) {
  const double h = kErrorStep;
  const MaugisDugdalePoint pp = point_at(x + h), pm = point_at(x - h), p0 = point_at(x);
  const double v2 = (value_of(pp, control) - 2.0 * value_of(p0, control) + value_of(pm, control)) / (h * h);
  double change[4] = {0.0, 0.0, 0.0, 0.0};  // P, D, m, ln a_bar: the largest of the checks'
  for (int c = 0; checks && c < detail::kStateChecks; ++c) {
    const PointShift sp = shifts.at(x + h)[c], sm = shifts.at(x - h)[c], s0 = shifts.at(x)[c];
    const double e1 = (shift_of(sp, control) - shift_of(sm, control)) / (2.0 * h);
    const double dx = v2 > 0.0 ? -e1 / v2 : 0.0;
    const double moved[4] = {s0.load + (pp.load - pm.load) / (2.0 * h) * dx,
                             s0.penetration + (pp.penetration - pm.penetration) / (2.0 * h) * dx,
                             s0.m + (pp.m - pm.m) / (2.0 * h) * dx, dx};
    for (int i = 0; i < 4; ++i) change[i] = std::max(change[i], detail::kCheckWeights[c] * std::abs(moved[i]));
  }
  auto located = [&](double value, double plus, double minus) {
    return std::abs(plus - minus) / (2.0 * h) * tol + kDirectNoise * std::abs(value);
  };
  const double k = detail::kStateErrorFactor;
  q.load_error = k * change[0] + located(q.load, pp.load, pm.load);
  q.penetration_error = k * change[1] + located(q.penetration, pp.penetration, pm.penetration);
  q.m_error = k * change[2] + located(q.m, pp.m, pm.m);
  q.a_bar_error = q.a_bar * (k * change[3] + tol);
}

// From the table, another local minimum whose value lies within the two estimates of the lowest
// may be the true lowest (the table's errors can reorder shallow minima, as near the curve's end
// on a stiff film at small lambda): the reported minimum's estimates grow to cover it.
void widen_to_minima(MaugisDugdalePoint& best, const std::vector<MaugisDugdalePoint>& minima, Control control) {
  for (const MaugisDugdalePoint& q : minima) {
    if (value_of(q, control) > value_of(best, control) + error_of(best, control) + error_of(q, control)) continue;
    best.a_bar_error = std::max(best.a_bar_error, std::abs(q.a_bar - best.a_bar) + q.a_bar_error);
    best.load_error = std::max(best.load_error, std::abs(q.load - best.load) + q.load_error);
    best.penetration_error = std::max(best.penetration_error, std::abs(q.penetration - best.penetration) + q.penetration_error);
    best.m_error = std::max(best.m_error, std::abs(q.m - best.m) + q.m_error);
  }
}

// Start of the root c(a) at ln a_bar = x from the roots u = ln(c/a - 1) already known at other
// x: u interpolated (extrapolated) through the three nearest (quadratic), the first bracket
// step twice its difference from the linear estimate through the two nearest (at least
// kMinNearStep); with two known roots the linear estimate and kNearStep; fewer: unchanged.
// Returns whether it set them (a guide for the root).
bool start_from(const std::map<double, double>& roots, double x, double& guess, double& step) {
  if (roots.size() < 2) return false;
  std::vector<std::pair<double, double>> near;  // up to three on each side, nearest first
  auto hi_it = roots.lower_bound(x);
  auto lo_it = hi_it;
  for (int k = 0; k < 3 && hi_it != roots.end(); ++k, ++hi_it) near.push_back(*hi_it);
  for (int k = 0; k < 3 && lo_it != roots.begin(); ++k) near.push_back(*--lo_it);
  std::sort(near.begin(), near.end(),
            [&](const auto& p, const auto& q) { return std::abs(p.first - x) < std::abs(q.first - x); });
  const double x0 = near[0].first, u0 = near[0].second, x1 = near[1].first, u1 = near[1].second;
  const double linear = u0 + (u1 - u0) * (x - x0) / (x1 - x0);
  double u = linear, s = kNearStep;
  if (near.size() >= 3) {
    const double x2 = near[2].first, u2 = near[2].second;
    u = u0 * (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2)) + u1 * (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2)) +
        u2 * (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1));
    s = std::clamp(2.0 * std::abs(u - linear), kMinNearStep, kNearStep);
  }
  if (!(std::isfinite(u) && std::isfinite(s))) return false;
  guess = std::exp(u);
  step = s;
  return true;
}

// Brent minimiser on f over [lo, hi] with f(mid) below both ends; exceptions thrown by f are
// rethrown. Where GSL refuses the triple, mid.
double minimise(const std::function<double(double)>& f, double lo, double mid, double hi, double f_lo,
                double f_mid, double f_hi, double tolerance) {
  const auto minimum = detail::brent_minimum(f, lo, f_lo, mid, f_mid, hi, f_hi, {tolerance, 0.0, 200});
  return minimum ? minimum->x : mid;
}

// d/dā_M of P (load) or of Δ_M along Maugis's homogeneous curve (THEORY.md section 13,
// "Normalization and homogeneous check"), e = m - 1 at ā_M = a: X_a - X_e R_a/R_e, with R the
// residual of the curve's equation, s = sqrt(m² - 1), φ = arccos(1/m), ds/de = m/s,
// dφ/de = 1/(m s). Exact up to rounding, so a flat minimum is located as this slope's root.
// *scale receives the sum of its terms' magnitudes (they cancel at the root: its rounding).
double half_space_slope(double lambda, double a, double e, bool load, double* scale = nullptr) {
  const double m = 1.0 + e, s = std::sqrt(e * (2.0 + e)), phi = std::atan(s);
  const double s1 = s + (m * m - 2.0) * phi, s2 = s * phi - e;
  const double s1_e = 2.0 * s / m + 2.0 * m * phi, s2_e = m * phi / s + 1.0 / m - 1.0;
  const double r_a = lambda * a * s1 + 4.0 * lambda * lambda * s2 / 3.0;
  const double r_e = 0.5 * lambda * a * a * s1_e + 4.0 * lambda * lambda * a * s2_e / 3.0;
  const double de = -r_a / r_e;
  const double terms[3] = {load ? 3.0 * a * a : 2.0 * a, load ? -2.0 * lambda * a * (s + m * m * phi) : -4.0 * lambda * s / 3.0,
                           load ? -lambda * a * a * (2.0 * m / s + 2.0 * m * phi) * de : -4.0 * lambda * a * (m / s) * de / 3.0};
  if (scale != nullptr) *scale = std::abs(terms[0]) + std::abs(terms[1]) + std::abs(terms[2]);
  return terms[0] + terms[1] + terms[2];
}

// Relative error of a half-space pull-off located as the root of half_space_slope at ln ā = x:
// the slope's rounding (an ulp of its terms' sum: near DMT's end terms ~1e5 times the
// slope's scale cancel) and the root c(a)'s ~1e-13 in ln(c/a - 1) (MaugisDugdaleTable::solve's
// Brent tolerance), over the slope's derivative in x, times the state's error factor.
// excess_at(x) is the curve's c/a - 1.
double half_space_location_error(double lambda, double x, bool load, const std::function<double(double)>& excess_at) {
  constexpr double kRootNoise = 1e-13, kStep = 1e-4, kUlps = 1.0;
  const double k13 = std::cbrt(4.0 / 3.0);
  auto slope_at = [&](double v) { return half_space_slope(lambda, k13 * std::exp(v), excess_at(v), load); };
  const double a = k13 * std::exp(x), e = excess_at(x);
  double scale = 0.0;
  const double g = half_space_slope(lambda, a, e, load, &scale);
  const double noise = std::abs(half_space_slope(lambda, a, e * (1.0 + kRootNoise), load) - g) +
                       kUlps * std::numeric_limits<double>::epsilon() * scale;
  const double change = std::abs(slope_at(x + kStep) - slope_at(x - kStep)) / (2.0 * kStep);
  return change > 0.0 ? detail::kStateErrorFactor * noise / change : 0.0;
}

// A film on a substrate of its own material is one half-space: C = 1 and H = 0 (an elastic
// indenter keeps C' = 1), so the zone's functions are Maugis's closed forms.
bool is_half_space(const Stack& s) {
  const Material& top = s.top();
  const Material& base = s.substrate().material;
  return !s.is_multilayer() && !s.substrate().rigid && base.youngs_modulus == top.youngs_modulus &&
         base.poisson_ratio == top.poisson_ratio;
}

// The stack's kernel tables, built on first use: a table whose nodes all come from the solve
// cache, or a half-space's closed forms, never evaluates H, and the full grid costs 7-35 ms a
// stack (an AFM fit with E1 free on an elastic base holds one model per E1 node). A node at
// (a, c) evaluates H up to |u| ~ 2c/t: the AFM fit's all within the compact grid, the table's
// larger c/t (up to 1e4) on the full grid (THEORY.md section 13, "Kernel tables by reach").
class LazyKernel : public detail::ReachKernel {
 public:
  explicit LazyKernel(const Stack& stack) : detail::ReachKernel(stack, detail::kCohesiveZoneCompactRange) {}
};

}  // namespace

struct MaugisDugdaleModel::Impl {
  Impl(const Stack& s, const MaugisDugdaleOptions& o) : stack(s), options(o), kernel(s) {
    disc.nodes_per_panel = o.nodes_per_panel;
    disc.quadrature_accuracy = o.quadrature_accuracy;
    quadrature.points_per_piece = o.annulus_points;
    if (o.use_table) {
      detail::MdTableOptions range;
      range.a_over_t_min = o.table_a_over_t_min;
      range.a_over_t_max = o.table_a_over_t_max;
      range.closed_form = is_half_space(s);
      const bool cached = !range.closed_form && !solve_cache_directory().empty();
      table = std::make_unique<detail::MaugisDugdaleTable>(kernel, disc, quadrature, range,
                                                           cached ? detail::SolveCache::key_of(s) : "");
    }
  }
  Stack stack;
  MaugisDugdaleOptions options;
  LazyKernel kernel;
  detail::Discretization disc;
  detail::CohesiveQuadrature quadrature;
  std::unique_ptr<detail::MaugisDugdaleTable> table;  // options.use_table

  // dP/da_bar (load) or dD/da_bar along the curve, by implicit differentiation through c(a)
  // (THEORY.md section 13): dX/da = X_a - X_c h_a/h_c, the partial derivatives at fixed c
  // (resp. a) by fourth-order central differences of the smooth map (a, c) -> (F, δ, h), which
  // involves no root finder; steps 1e-3 (c - a) give ~1e-12 relative.
  double slope(double eta, double sigma_hat, double h0, double a, bool load, double guess_excess,
               double step_factor = 1.0) const {
    const detail::CohesiveZone zone(kernel, a, 1.0, disc, quadrature);
    const detail::CohesiveState st = zone.solve(sigma_hat, h0, guess_excess, kSlopeStep);
    const double c = st.c, step = step_factor * 1e-3 * std::min(c - a, a);
    auto value = [&](const detail::CohesiveState& x) { return load ? x.force : x.delta; };
    const double w[2] = {8.0 / 12.0, -1.0 / 12.0};  // f'(0) ~ Σ w_k (f(k s) - f(-k s)) / s
    double x_c = 0.0, h_c = 0.0, x_a = 0.0, h_a = 0.0;
    for (int k = 1; k <= 2; ++k) {
      const detail::CohesiveState cp = zone.evaluate(sigma_hat, (c + k * step) / a - 1.0);
      const detail::CohesiveState cm = zone.evaluate(sigma_hat, (c - k * step) / a - 1.0);
      x_c += w[k - 1] * (value(cp) - value(cm)) / step;
      h_c += w[k - 1] * (cp.gap - cm.gap) / step;
      const double ap = a + k * step, am = a - k * step;
      const detail::CohesiveState sp =
          detail::CohesiveZone(kernel, ap, 1.0, disc, quadrature).evaluate(sigma_hat, c / ap - 1.0);
      const detail::CohesiveState sm =
          detail::CohesiveZone(kernel, am, 1.0, disc, quadrature).evaluate(sigma_hat, c / am - 1.0);
      x_a += w[k - 1] * (value(sp) - value(sm)) / step;
      h_a += w[k - 1] * (sp.gap - sm.gap) / step;
    }
    const double total = x_a - x_c * h_a / h_c;  // d/da in units of t
    return load ? eta * eta * total : eta * total;  // P = η³F, D = η²δ, ā = η a
  }

  // Relative error of a pull-off at ln ā = x located as the root of its slope (refine): the
  // slope's noise over the slope's derivative in x, times the state's error factor. The closed
  // form's noise is its rounding (half_space_location_error); the direct slope's, the change of
  // its differences from step s to 2s and s/2 (the values' ~1e-13 over steps ~1e-3 a: near DMT's
  // end, where P is flat, up to ~1e-4 in ln ā). excess_at(x): the curve's c/a - 1.
  double root_location_error(double eta, double lambda, double x, bool load,
                             const std::function<double(double)>& excess_at) const {
    if (table) return half_space_location_error(lambda, x, load, excess_at);
    const double sigma_hat = lambda * std::cbrt(16.0 / 9.0) / eta;
    const double h0 = 2.0 / (kPi * eta * eta * eta * sigma_hat);
    auto g = [&](double v, double step_factor) {
      return slope(eta, sigma_hat, h0, std::exp(v) / eta, load, excess_at(v), step_factor);
    };
    constexpr double kStep = 1e-4;
    const double g1 = g(x, 1.0);  // two comparisons: one may agree by chance
    const double noise = std::max(std::abs(g1 - g(x, 2.0)), std::abs(g1 - g(x, 0.5)));
    const double change = std::abs(g(x + kStep, 1.0) - g(x - kStep, 1.0)) / (2.0 * kStep);
    return std::max(kDirectLocation, change > 0.0 ? detail::kStateErrorFactor * noise / change : 0.0);
  }

  // The curve at a_bar; the root c(a) is searched from guess_excess (c/a - 1, or c at a = 0)
  // in first steps of `step` in ln(excess). *excess receives the root's excess.
  // The direct state whose root c is the one the table takes without a guide (md_table.hpp,
  // bracket_outward; THEORY.md section 13, "Which root"): bracketed outward from the
  // homogeneous solid's root in ln(c/a - 1) (ln c at the curve's end), then Brent to 1e-13.
  detail::CohesiveState homogeneous_branch(const detail::CohesiveZone& zone, double sigma_hat, double h0,
                                           double a) const {
    const double lo = std::log(1e-14), hi = std::log(1e8);  // CohesiveZone::solve's range
    std::vector<std::pair<double, detail::CohesiveState>> seen;
    std::function<double(double)> f = [&](double u) {
      seen.emplace_back(u, zone.evaluate(sigma_hat, std::exp(u)));
      return seen.back().second.gap - h0;
    };
    const double start = a > 0.0 ? detail::homogeneous_root(sigma_hat, h0, a, lo, hi)
                                  : std::log(detail::homogeneous_end_root(sigma_hat, h0));
    const auto bracket = detail::bracket_outward(f, start, lo, hi);
    std::optional<detail::BrentResult> root;
    if (bracket && bracket->first != bracket->second) root = detail::brent_root(f, bracket->first, bracket->second, {1e-13, 0.0, 200});
    if (!bracket || (bracket->first != bracket->second && !root)) {
      throw NumericalError("cohesive zone: no root of h(c) = h0 for c/a - 1 in [1e-14, 1e8] at a/t = " +
                           detail::short_text(a));
    }
    const double u = root ? root->x : bracket->first;
    for (auto it = seen.rbegin(); it != seen.rend(); ++it) {
      if (it->first == u) return it->second;
    }
    return zone.evaluate(sigma_hat, std::exp(u));
  }

  // guided: guess_excess and step come from neighbouring roots of the same curve (start_from);
  // otherwise the direct solve takes the homogeneous branch's root, as the table does.
  MaugisDugdalePoint point(double eta, double lambda, double a_bar, double guess_excess, double step,
                           double* excess = nullptr, PointShift* shift = nullptr,
                           bool guided = false) const {  // shift: kStateChecks
    const double sigma_hat = lambda * std::cbrt(16.0 / 9.0) / eta;  // K^(2/3), K = 4/3
    const double h0 = 2.0 / (kPi * eta * eta * eta * sigma_hat);
    const double a = a_bar / eta;
    MaugisDugdalePoint p;
    p.eta = eta;
    p.lambda = lambda;
    p.a_bar = a_bar;
    p.a_over_t = a;
    if (table) {
      if (const auto st = a > 0.0 ? table->solve(sigma_hat, h0, a, options.table_errors) : table->solve_end(sigma_hat, h0)) {
        if (excess != nullptr) *excess = st->excess;
        p.m = a > 0.0 ? 1.0 + st->excess : std::numeric_limits<double>::infinity();
        p.c_bar = eta * (a > 0.0 ? a * (1.0 + st->excess) : st->excess);
        p.load = eta * eta * eta * st->force;
        p.penetration = eta * eta * st->delta;
        p.m_error = a > 0.0 ? st->excess_error : 0.0;
        p.load_error = eta * eta * eta * st->force_error;
        p.penetration_error = eta * eta * st->delta_error;
        p.from_table = true;
        if (shift != nullptr) {
          for (int c = 0; c < detail::kStateChecks; ++c) {
            shift[c] = {eta * eta * eta * st->shift[c][2], eta * eta * st->shift[c][1], st->shift[c][0]};
          }
        }
        return p;
      }
    }
    const detail::CohesiveZone zone(kernel, a, 1.0, disc, quadrature);
    const detail::CohesiveState st =
        guided ? zone.solve(sigma_hat, h0, guess_excess, step) : homogeneous_branch(zone, sigma_hat, h0, a);
    if (excess != nullptr) *excess = st.excess;
    p.m = a > 0.0 ? 1.0 + st.excess : std::numeric_limits<double>::infinity();
    p.c_bar = eta * st.c;
    p.load = eta * eta * eta * st.force;
    p.penetration = eta * eta * st.delta;
    p.gap_evaluations = zone.last_evaluations();
    p.m_error = a > 0.0 ? kDirectNoise * p.m : 0.0;
    p.load_error = kDirectNoise * std::abs(p.load);
    p.penetration_error = kDirectNoise * std::abs(p.penetration);
    return p;
  }
};

MaugisDugdaleModel::MaugisDugdaleModel(const Stack& stack, MaugisDugdaleOptions options) {
  if (options.nodes_per_panel < 4 || options.nodes_per_panel > 48 || options.annulus_points < 4 ||
      options.annulus_points > 80) {
    throw InputError("Maugis-Dugdale model: nodes_per_panel must be in [4, 48], annulus_points in [4, 80]");
  }
  if (options.scan_points_per_decade < 4) throw InputError("scan_points_per_decade must be >= 4");
  impl_ = std::make_unique<Impl>(stack, options);
}

MaugisDugdaleModel::~MaugisDugdaleModel() = default;
const Stack& MaugisDugdaleModel::stack() const { return impl_->stack; }
const MaugisDugdaleOptions& MaugisDugdaleModel::options() const { return impl_->options; }
void MaugisDugdaleModel::build_table() const {
  if (impl_->table) impl_->table->build();
}
bool MaugisDugdaleModel::table_in_closed_form() const { return impl_->table && impl_->table->options().closed_form; }
long MaugisDugdaleModel::table_nodes() const { return impl_->table ? impl_->table->nodes_used() : 0; }
double MaugisDugdaleModel::table_seconds() const { return impl_->table ? impl_->table->build_seconds() : 0.0; }

MaugisDugdalePoint MaugisDugdaleModel::point(double eta, double lambda, double a_bar) const {
  check_value(eta, "eta", false);
  check_value(lambda, "lambda", false);
  check_value(a_bar, "a_bar", true);
  return impl_->point(eta, lambda, a_bar, 1.0, 1.5);
}

std::vector<MaugisDugdalePoint> MaugisDugdaleModel::curve(double eta, double lambda,
                                                          const std::vector<double>& a_bar) const {
  for (double a : a_bar) check_value(a, "a_bar", true);
  check_value(eta, "eta", false);
  check_value(lambda, "lambda", false);
  std::vector<MaugisDugdalePoint> out;
  out.reserve(a_bar.size());
  std::map<double, double> roots;  // ln a_bar -> ln(c/a - 1) of the points so far (a > 0)
  for (double a : a_bar) {
    if (a == 0.0) {
      out.push_back(point(eta, lambda, a));
      continue;
    }
    const double x = std::log(a);
    double guess = 1.0, step = 1.5, excess = 1.0;
    const bool guided = start_from(roots, x, guess, step);
    out.push_back(impl_->point(eta, lambda, a, guess, step, &excess, nullptr, guided));
    roots[x] = std::log(excess);
  }
  return out;
}

// The minimiser's location (~location_tolerance) refined as the root of the implicit
// derivative (Impl::slope; a half-space's: half_space_slope) by regula falsi (Illinois) in
// ln a_bar on a bracket 100 times wider than its tolerance, widened tenfold up to a grid cell
// until the slope changes sign; kept as it is when it never does.
double MaugisDugdaleModel::refine(double eta, double lambda, double x, bool load, double guess_excess,
                                  int& evaluations) const {
  const bool closed_form = table_in_closed_form();
  if (impl_->table && !closed_form) return x;  // the table's values carry ~1e-5: the minimiser's location suffices
  const double sigma_hat = lambda * std::cbrt(16.0 / 9.0) / eta;
  const double h0 = 2.0 / (kPi * eta * eta * eta * sigma_hat);
  std::function<double(double)> g = [&](double v) {
    ++evaluations;
    return impl_->slope(eta, sigma_hat, h0, std::exp(v) / eta, load, guess_excess);
  };
  if (closed_form) {
    g = [&](double v) {
      ++evaluations;
      double excess = guess_excess;
      impl_->point(eta, lambda, std::exp(v), guess_excess, 1.5, &excess);
      return half_space_slope(lambda, std::cbrt(4.0 / 3.0) * std::exp(v), excess, load);
    };
  }
  double half = 100.0 * impl_->options.location_tolerance;
  double l = x - half, r = x + half, gl = g(l), gr = g(r);
  // The minimiser stops ~sqrt(noise |P| / P'') away, beyond 1e-3 in ln a_bar where P is flat
  // (DMT's end, lambda < 0.03): the bracket widens to a grid cell.
  while (!(gl < 0.0 && gr > 0.0) && half < 0.3) {
    half *= 10.0;
    l = x - half, r = x + half, gl = g(l), gr = g(r);
  }
  if (!(gl < 0.0 && gr > 0.0)) return x;
  int side = 0;
  for (int iter = 0; iter < 30 && r - l > 1e-13; ++iter) {
    const double m = r - gr * (r - l) / (gr - gl);
    const double gm = g(m);
    if (gm == 0.0) return m;
    if (gm < 0.0) {
      l = m;
      gl = gm;
      if (side == -1) gr *= 0.5;
      side = -1;
    } else {
      r = m;
      gr = gm;
      if (side == 1) gl *= 0.5;
      side = 1;
    }
    if (!closed_form && std::abs(gm) < 1e-13) break;  // the closed form's slope is tiny where P is flat
  }
  return gl == gr ? 0.5 * (l + r) : r - gr * (r - l) / (gr - gl);
}

MaugisDugdalePulloff MaugisDugdaleModel::pulloff(double eta, double lambda) const {
  return pulloff_spring(eta, lambda, 0.0);
}

MaugisDugdalePulloff MaugisDugdaleModel::pulloff_spring(double eta, double lambda, double k_bar) const {
  check_value(eta, "eta", false);
  check_value(lambda, "lambda", false);
  if (!(k_bar >= 0.0)) throw InputError("k_bar = " + detail::full_precision(k_bar) + " not allowed (need >= 0)");
  const MaugisDugdaleOptions& o = impl_->options;
  const double r = impl_->stack.substrate_length_ratio();
  const double lo = o.a_bar_min > 0.0 ? o.a_bar_min : 1e-3 * std::min(1.0, r);
  const double hi = o.a_bar_max > 0.0 ? o.a_bar_max : 10.0 * std::max(1.0, r);
  if (!(lo < hi && std::isfinite(hi))) throw InputError("pull-off a_bar range not allowed");
  MaugisDugdalePulloff result;
  result.eta = eta;
  result.lambda = lambda;
  result.a_bar_scan_min = lo;
  result.a_bar_scan_max = hi;
  const std::size_t n =
      static_cast<std::size_t>(std::ceil(std::log10(hi / lo) * o.scan_points_per_decade)) + 1;
  // Every point computed, by ln a_bar: the searches below revisit points (the minimiser, stuck
  // at its own resolution, may evaluate the same two points until its iteration limit).
  std::map<double, MaugisDugdalePoint> memo;  // by ln a_bar
  std::map<double, double> roots;              // ln a_bar -> ln(c/a - 1)
  Shifts shifts;  // ln a_bar -> checks - splines
  int evaluations = 0;
  PointAt point_at = [&](double x) -> const MaugisDugdalePoint& {
    auto it = memo.find(x);
    if (it != memo.end()) return it->second;
    ++evaluations;
    double guess = 1.0, step = 1.5, excess = 1.0;
    const bool guided = start_from(roots, x, guess, step);
    std::array<PointShift, detail::kStateChecks> shift{};
    it = memo.emplace(x, impl_->point(eta, lambda, std::exp(x), guess, step, &excess, shift.data(), guided)).first;
    roots[x] = std::log(excess);
    shifts[x] = shift;
    return it->second;
  };
  std::vector<double> v(n);  // ln a_bar
  std::vector<MaugisDugdalePoint> points(n);
  for (std::size_t k = 0; k < n; ++k) {
    v[k] = std::log(lo) + std::log(hi / lo) * static_cast<double>(k) / static_cast<double>(n - 1);
    points[k] = point_at(v[k]);
  }
  result.curve_end = point(eta, lambda, 0.0);
  ++evaluations;

  const bool closed_form = table_in_closed_form();
  std::vector<Control> controls = {{Control::kLoad, 0.0}, {Control::kDisplacement, 0.0}};
  // k_bar = inf is displacement control; 0 (none) leaves spring_control empty.
  if (k_bar > 0.0) controls.push_back(std::isinf(k_bar) ? Control{Control::kDisplacement, 0.0} : Control{Control::kSpring, k_bar});
  result.k_bar = k_bar;
  for (std::size_t which = 0; which < controls.size(); ++which) {
    const Control control = controls[which];
    const char* name = which == 2 ? "spring control (minimum of Z = D + P/k_bar)"
                       : control.kind == Control::kLoad ? "load control (minimum of P)"
                                                        : "displacement control (minimum of D)";
    MaugisDugdalePulloffPoint best;
    std::vector<MaugisDugdalePoint> minima;  // every local minimum, refined
    bool found = false;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double f0 = value_of(points[k - 1], control), f1 = value_of(points[k], control),
                   f2 = value_of(points[k + 1], control);
      if (!(f1 < f0 && f1 <= f2)) continue;
      ++best.local_minima;
      MaugisDugdalePoint at = points[k];
      if (f1 < f2) {
        std::function<double(double)> f = [&](double x) { return value_of(point_at(x), control); };
        double x = minimise(f, v[k - 1], v[k], v[k + 1], f0, f1, f2, o.location_tolerance);
        // The implicit-derivative refinement is written for P and D; Z is left at the minimiser's.
        double location = o.location_tolerance;
        bool slope_root = false;  // a half-space's location: the closed form's slope root
        if (control.kind != Control::kSpring) {
          const double minimiser = x;
          x = refine(eta, lambda, x, control.kind == Control::kLoad, std::exp(roots.at(x)), evaluations);
          if (x != minimiser && (closed_form || !impl_->table)) {
            const std::function<double(double)> excess_at = [&](double u) {
              point_at(u);
              return std::exp(roots.at(u));
            };
            location = impl_->root_location_error(eta, lambda, x, control.kind == Control::kLoad, excess_at);
            slope_root = true;
          }
        }
        at = point_at(x);
        if (value_of(at, control) > f1) {
          at = points[k];
          x = v[k];
          location = o.location_tolerance;
          slope_root = false;
        }
        if (at.from_table || slope_root) locate_errors(at, x, control, point_at, shifts, location, !slope_root);
      } else if (at.from_table) {
        locate_errors(at, v[k], control, point_at, shifts, o.location_tolerance);
      }
      if (!at.from_table && !(at.a_bar_error > 0.0)) at.a_bar_error = kDirectLocation * at.a_bar;
      minima.push_back(at);
      if (!found || value_of(at, control) < value_of(best.point, control)) best.point = at;
      found = true;
    }
    if (found && best.point.from_table) widen_to_minima(best.point, minima, control);
    const MaugisDugdalePoint& end = result.curve_end;
    std::ostringstream w;
    w.precision(6);
    // From the table, a minimum within the two values' error estimates of the curve's end is
    // not told apart from it (near the end P and D are flat): the end is reported, as the
    // direct solve would.
    const double margin = best.point.from_table ? error_of(best.point, control) + error_of(end, control) : 0.0;
    if (!found || value_of(end, control) <= value_of(best.point, control) + margin) {
      // The contact shrinks to a point at finite force (THEORY.md section 13, no vertical
      // tangent): the pull-off sits at the end of the curve.
      // An interior minimum below the end, set aside within the estimates, bounds the error
      // of the value reported: the end's error grows by their difference and the minimum's.
      const double below = found ? value_of(end, control) - value_of(best.point, control) : 0.0;
      const double widened = below > 0.0 ? below + error_of(best.point, control) : 0.0;
      best.point = end;
      best.interior = false;
      if (widened > error_of(end, control)) {
        if (control.kind == Control::kLoad) {
          best.point.load_error = widened;
        } else {
          best.point.penetration_error = widened;  // D, and Z through a spring (D + P/k_bar)
        }
      }
      if (value_of(points[n - 1], control) < value_of(end, control)) {
        w << "eta=" << eta << " lambda=" << lambda << ": " << name << ": no minimum in a_bar [" << lo << ", "
          << hi << "] and the range end is below the curve's end a -> 0";
        result.warnings.push_back(w.str());
      }
    }
    if (value_of(points[0], control) < value_of(points[1], control) &&
        value_of(points[0], control) < value_of(end, control)) {
      w.str("");
      w << "eta=" << eta << " lambda=" << lambda << ": " << name << ": P or D is lower at a_bar=" << lo
        << " than at both neighbours; a minimum below the scanned range cannot be excluded";
      result.warnings.push_back(w.str());
    }
    if (best.local_minima > 1) {
      w.str("");
      w << "eta=" << eta << " lambda=" << lambda << ": " << name << ": " << best.local_minima
        << " local minima; the lowest is reported";
      result.warnings.push_back(w.str());
    }
    (which == 2 ? result.spring_control : which == 0 ? result.load_control : result.displacement_control) = best;
  }
  result.point_evaluations = evaluations;
  return result;
}

std::vector<MaugisDugdalePulloff> MaugisDugdaleModel::pulloffs(
    const std::vector<std::pair<double, double>>& eta_lambda) const {
  std::vector<MaugisDugdalePulloff> results(eta_lambda.size());
  // Each pull-off (~0.1-1 s) is independent and deterministic.
  detail::parallel_for(eta_lambda.size(),
                       [&](std::size_t k) { results[k] = pulloff(eta_lambda[k].first, eta_lambda[k].second); });
  return results;
}

}  // namespace coatcontact
