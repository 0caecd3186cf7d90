// Normalized adhesive sphere (THEORY.md section 5, [EqSolNormF, EqSolNormD]) and its pull-off.
//
// With a_bar = eta a/t and L_X = d ln X / d ln(a/t) from the interpolant:
//   P  = a_bar^3 Pi_s/2 - 2 sqrt(2) a_bar^(3/2) E_eq/Gamma
//   D  = a_bar^2 Delta_s - sqrt(2) a_bar^(1/2) / Gamma
//   dP/da_bar = a_bar^2 Pi_s/2 (3 + L_Pi) - 2 sqrt(2) a_bar^(1/2) (E_eq/Gamma) (3/2 + L_E - L_Gamma)
//   dD/da_bar = a_bar Delta_s (2 + L_Delta) - sqrt(2) a_bar^(-1/2) / Gamma (1/2 - L_Gamma)
//
// Pull-off (minimum of P, resp. of D, over a_bar): local minima are counted from sign changes
// of the derivative on a log grid; each is bracketed, minimised with gsl_min_fminimizer_brent
// (which locates an argmin only to ~sqrt(eps) because values are flat there), then refined
// by gsl_root_fsolver_brent on the derivative, which is computed analytically from the
// interpolant and crosses zero linearly: this meets the relative location tolerance
// (default 1e-12) on the interpolated curve.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"

namespace coatcontact {

namespace {

const double kSqrt2 = std::sqrt(2.0);

std::string format_g(double v) { return detail::full_precision(v); }

void check_positive(double value, const std::string& what) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw InputError(what + " = " + format_g(value) + " not allowed (need finite and > 0)");
  }
}

// eta outside [kMinimumScaled, kMaximumScaled] puts a/t = a_bar/eta beyond the solver's range
// (or takes minutes to fail there): refused up front, as the command line does.
void check_eta(double eta) {
  check_positive(eta, "eta");
  if (!(eta >= kMinimumScaled && eta <= kMaximumScaled)) {
    throw InputError("eta = " + format_g(eta) + " is outside the allowed range [" + format_g(kMinimumScaled) +
                     ", " + format_g(kMaximumScaled) + "]");
  }
}

// Which curve is minimised: P (load control) or D (displacement control).
enum class Control { kLoad, kDisplacement };
double value_of(const CurvePoint& p, Control c) { return c == Control::kLoad ? p.load : p.penetration; }
double slope_of(const CurvePoint& p, Control c) { return c == Control::kLoad ? p.dload : p.dpenetration; }

struct Located {
  double a_bar;
  double minimiser_discrepancy;
};

// Minimum of f in the grid cell [x[i], x[i+1]] where f' goes from < 0 to >= 0.
Located locate_minimum(const std::function<double(double)>& f, const std::function<double(double)>& df,
                       const std::vector<double>& x, const std::vector<double>& fx, std::size_t i,
                       double tolerance) {
  detail::GslHandlerOff gsl_guard;
  double x_lo = x[i], x_hi = x[i + 1];

  // 1. Brent minimiser on the values, bracket widened by one cell each side.
  double minimiser_x = std::nan("");
  double minimiser_width = 0.0;
  {
    const std::size_t lo = i > 0 ? i - 1 : i;
    const std::size_t hi = std::min(i + 2, x.size() - 1);
    const std::size_t guess = fx[i] <= fx[i + 1] ? i : i + 1;
    // The minimiser needs f(guess) < f at both ends; at a range end it is skipped.
    const bool bracketed = guess != lo && guess != hi && fx[guess] < fx[lo] && fx[guess] < fx[hi];
    if (bracketed) {
      const auto minimum = detail::brent_minimum(f, x[lo], fx[lo], x[guess], fx[guess], x[hi], fx[hi],
                                                 {0.0, 1e-10, 200});
      if (minimum) {
        minimiser_x = minimum->x;
        minimiser_width = minimum->upper - minimum->lower;
      }
    }
  }

  // 2. Root of the derivative, in a small bracket around the minimiser's answer when the
  //    derivative changes sign there, otherwise in the grid cell (sign change guaranteed).
  if (std::isfinite(minimiser_x)) {
    const double half = std::max(4.0 * minimiser_width, 1e-6 * minimiser_x);
    const double a = std::max(x_lo, minimiser_x - half);
    const double b = std::min(x_hi, minimiser_x + half);
    if (a < b && df(a) < 0.0 && df(b) >= 0.0) {
      x_lo = a;
      x_hi = b;
    }
  }
  double root = x_lo;
  const double d_lo = df(x_lo);
  const double d_hi = df(x_hi);
  if (d_lo == 0.0) {
    root = x_lo;
  } else if (d_hi == 0.0) {
    root = x_hi;
  } else {
    const auto found = detail::brent_root(df, x_lo, x_hi, {0.0, tolerance, 300});
    if (!found) {
      throw NumericalError("cannot bracket the stationary point of the curve in a_bar [" +
                           format_g(x_lo) + ", " + format_g(x_hi) + "]");
    }
    root = found->x;
    if (!found->converged && !(found->upper - found->lower <= tolerance * std::abs(root))) {
      throw NumericalError("root of the derivative not converged to relative " + format_g(tolerance) +
                           " near a_bar = " + format_g(root));
    }
  }
  Located out{root, 0.0};
  out.minimiser_discrepancy = std::isfinite(minimiser_x) ? std::abs(minimiser_x - root) / root : -1.0;
  return out;
}

}  // namespace

CurvePoint JkrLaw::point(const ReducedPoint& r, double eta, double a_bar) const {
  const double root_a = std::sqrt(a_bar);
  const double a15 = a_bar * root_a;
  const double e_over_g = r.e_eq / r.gamma1;
  CurvePoint p;
  p.eta = eta;
  p.a_bar = a_bar;
  p.a_over_t = r.a_over_t;
  p.load = a_bar * a_bar * a_bar * r.pi_s / 2.0 - 2.0 * kSqrt2 * a15 * e_over_g;
  p.penetration = a_bar * a_bar * r.delta_s - kSqrt2 * root_a / r.gamma1;
  p.dload = a_bar * a_bar * r.pi_s / 2.0 * (3.0 + r.dlog_pi_s) -
            2.0 * kSqrt2 * root_a * e_over_g * (1.5 + r.dlog_e_eq - r.dlog_gamma1);
  p.dpenetration = a_bar * r.delta_s * (2.0 + r.dlog_delta_s) -
                   kSqrt2 / (root_a * r.gamma1) * (0.5 - r.dlog_gamma1);
  return p;
}

AdhesiveModel::AdhesiveModel(std::shared_ptr<const ReducedSource> source, TableOptions table,
                             PulloffOptions pulloff, std::shared_ptr<const AdhesionLaw> law)
    : source_(std::move(source)), law_(std::move(law)), pulloff_options_(pulloff) {
  if (!source_) throw InputError("AdhesiveModel needs a reduced-variable source");
  if (!law_) law_ = std::make_shared<JkrLaw>();
  if (pulloff_options_.scan_points_per_decade < 4) {
    throw InputError("scan_points_per_decade must be >= 4");
  }
  if (!(pulloff_options_.location_tolerance >= 1e-15 && pulloff_options_.location_tolerance <= 1e-6)) {
    throw InputError("pull-off location_tolerance must be in [1e-15, 1e-6]");
  }
  table_ = std::make_unique<ReducedTable>(*source_, table);
}

AdhesiveModel::~AdhesiveModel() = default;

CurvePoint AdhesiveModel::point(double eta, double a_bar) const {
  check_eta(eta);
  check_positive(a_bar, "a_bar");
  return law_->point(table_->at(a_bar / eta), eta, a_bar);
}

std::pair<double, double> AdhesiveModel::default_curve_range() const {
  const double r = stack().substrate_length_ratio();
  return {0.01 * std::min(1.0, r), 10.0 * std::max(1.0, r)};
}

std::vector<CurvePoint> AdhesiveModel::curve_solved(double eta, const std::vector<double>& a_bar) const {
  check_eta(eta);
  if (a_bar.empty()) throw InputError("empty a_bar list");
  std::vector<double> a_over_t;
  for (double a : a_bar) {
    check_positive(a, "a_bar");
    a_over_t.push_back(a / eta);
  }
  const std::vector<ReducedVariables> solved = source_->evaluate(a_over_t);
  std::vector<CurvePoint> out;
  out.reserve(a_bar.size());
  for (std::size_t i = 0; i < solved.size(); ++i) {
    CurvePoint p = law_->point(reduced_point_of(solved[i]), eta, a_bar[i]);
    p.dload = 0.0;
    p.dpenetration = 0.0;
    out.push_back(p);
  }
  return out;
}

std::vector<CurvePoint> AdhesiveModel::curve(double eta, const std::vector<double>& a_bar) const {
  check_eta(eta);
  if (a_bar.empty()) throw InputError("empty a_bar list");
  for (double a : a_bar) check_positive(a, "a_bar");
  const auto [lo, hi] = std::minmax_element(a_bar.begin(), a_bar.end());
  table_->prepare(*lo / eta, *hi / eta);
  std::vector<CurvePoint> out;
  out.reserve(a_bar.size());
  for (double a : a_bar) out.push_back(point(eta, a));
  return out;
}

std::vector<CurvePoint> AdhesiveModel::curve(double eta, const std::vector<double>& a_bar,
                                             std::vector<PointStatus>& status) const {
  check_eta(eta);
  if (a_bar.empty()) throw InputError("empty a_bar list");
  for (double a : a_bar) check_positive(a, "a_bar");
  const auto [lo, hi] = std::minmax_element(a_bar.begin(), a_bar.end());
  try {
    table_->prepare(*lo / eta, *hi / eta);  // every decade in one batch of solves
  } catch (const NumericalError&) {
    // A decade cannot be built: each point's decade is tried on its own below, once.
  }
  // Decades of a/t as the table keys them (reduced_table.cpp): a failed decade is not tried again.
  std::map<long, std::string> failed_decades;
  std::vector<CurvePoint> out(a_bar.size());
  std::vector<PointStatus> outcome(a_bar.size());
  for (std::size_t i = 0; i < a_bar.size(); ++i) {
    const double a_over_t = a_bar[i] / eta;
    const long decade = static_cast<long>(std::floor(std::log(a_over_t) / std::log(10.0)));
    const auto known = failed_decades.find(decade);
    if (known == failed_decades.end()) {
      try {
        out[i] = point(eta, a_bar[i]);
        continue;
      } catch (const NumericalError& e) {
        failed_decades[decade] = e.what();
      }
    }
    out[i] = CurvePoint{};
    out[i].eta = eta;
    out[i].a_bar = a_bar[i];
    out[i].a_over_t = a_over_t;
    outcome[i] = PointStatus{false, failed_decades[decade]};
  }
  status = std::move(outcome);
  return out;
}

void AdhesiveModel::estimate_errors(PulloffPoint& point, double eta, bool load_control, double lo, double hi) const {
  const double a = point.a_bar, a_over_t = a / eta;
  const ReducedPoint r = table_->at(a_over_t);
  const double value_err = table_->error_estimate_at(a_over_t);
  const double slope_err = table_->derivative_error_at(a_over_t);
  const CurvePoint base = law_->point(r, eta, a);
  // Worst-case sums of the changes of P, D and their slopes when each reduced variable moves
  // by its relative error and each log-derivative by its error (the law is linear in each).
  double err[4] = {0.0, 0.0, 0.0, 0.0};  // P, D, dP/da_bar, dD/da_bar
  auto add = [&](const ReducedPoint& moved) {
    const CurvePoint p = law_->point(moved, eta, a);
    err[0] += std::abs(p.load - base.load);
    err[1] += std::abs(p.penetration - base.penetration);
    err[2] += std::abs(p.dload - base.dload);
    err[3] += std::abs(p.dpenetration - base.dpenetration);
  };
  double ReducedPoint::*values[] = {&ReducedPoint::pi_s, &ReducedPoint::delta_s, &ReducedPoint::pi_c,
                                    &ReducedPoint::delta_c, &ReducedPoint::e_eq, &ReducedPoint::gamma1};
  double ReducedPoint::*slopes[] = {&ReducedPoint::dlog_pi_s, &ReducedPoint::dlog_delta_s, &ReducedPoint::dlog_pi_c,
                                    &ReducedPoint::dlog_delta_c, &ReducedPoint::dlog_e_eq, &ReducedPoint::dlog_gamma1};
  for (int j = 0; j < 6; ++j) {
    ReducedPoint moved = r;
    moved.*values[j] *= 1.0 + value_err;
    add(moved);
    moved = r;
    moved.*slopes[j] += slope_err;
    add(moved);
  }
  // Curvature of the minimised curve from its analytic slope on either side.
  const double a_up = std::min(a * (1.0 + 1e-4), hi), a_down = std::max(a * (1.0 - 1e-4), lo);
  const CurvePoint above = law_->point(table_->at(a_up / eta), eta, a_up);
  const CurvePoint below = law_->point(table_->at(a_down / eta), eta, a_down);
  const double curvature = load_control ? (above.dload - below.dload) / (a_up - a_down)
                                        : (above.dpenetration - below.dpenetration) / (a_up - a_down);
  const double shift = std::abs(curvature) > 0.0 ? err[load_control ? 2 : 3] / std::abs(curvature) : 0.0;
  point.a_bar_err = std::min(shift, a);
  point.reduced_err = value_err;
  const double half_curve = 0.5 * std::abs(curvature) * point.a_bar_err * point.a_bar_err;
  if (load_control) {
    point.load_err = err[0] + half_curve;
    point.penetration_err = err[1] + std::abs(base.dpenetration) * point.a_bar_err;
  } else {
    point.penetration_err = err[1] + half_curve;
    point.load_err = err[0] + std::abs(base.dload) * point.a_bar_err;
  }
}

std::pair<double, double> AdhesiveModel::pulloff_scan_range() const {
  const double r = stack().substrate_length_ratio();
  const double lo = pulloff_options_.a_bar_min > 0.0 ? pulloff_options_.a_bar_min : 1e-3 * std::min(1.0, r);
  const double hi = pulloff_options_.a_bar_max > 0.0 ? pulloff_options_.a_bar_max : 10.0 * std::max(1.0, r);
  if (!(lo < hi && std::isfinite(hi))) {
    throw InputError("pull-off a_bar range [" + format_g(lo) + ", " + format_g(hi) + "] not allowed");
  }
  return {lo, hi};
}

void AdhesiveModel::prepare_pulloff_range(const std::vector<double>& etas) const {
  if (etas.empty()) throw InputError("empty eta list");
  for (double eta : etas) check_eta(eta);
  const auto [lo, hi] = pulloff_scan_range();
  const auto [eta_min, eta_max] = std::minmax_element(etas.begin(), etas.end());
  table_->prepare_range(lo / *eta_max, hi / *eta_min);
}

Pulloff AdhesiveModel::pulloff(double eta) const {
  check_eta(eta);
  Pulloff result;
  result.eta = eta;
  auto [lo, hi] = pulloff_scan_range();
  // Build the table decade by decade upwards: if the source fails at large a/t (thin films,
  // large a_bar), the scan stops below the failing decade and says so (warning below), or
  // throws if no minimum was found by then.
  std::string truncation;
  if (table_->ranged()) {  // a sweep's verified table (pulloff_sweep): it must hold the whole scan
    const double slack = 1.0 + 1e-12;
    if (!(lo / eta >= table_->range_min() / slack && hi / eta <= table_->range_max() * slack)) {
      throw InputError("pull-off at eta = " + format_g(eta) + " scans a/t [" + format_g(lo / eta) + ", " +
                       format_g(hi / eta) + "], outside the table's range [" + format_g(table_->range_min()) + ", " +
                       format_g(table_->range_max()) + "]");
    }
  } else {
    const long k_lo = static_cast<long>(std::floor(std::log10(lo / eta)));
    const long k_hi = static_cast<long>(std::floor(std::log10(hi / eta)));
    for (long k = k_lo; k <= k_hi; ++k) {
      const double inside = std::pow(10.0, static_cast<double>(k) + 0.5);  // builds decade k only
      try {
        table_->prepare(inside, inside);
      } catch (const NumericalError& error) {
        const double top = std::pow(10.0, static_cast<double>(k)) * eta * (1.0 - 1e-12);
        if (k == k_lo || top <= lo) throw;
        hi = top;
        truncation = error.what();
        break;
      }
    }
  }
  result.a_bar_scan_min = lo;
  result.a_bar_scan_max = hi;

  const double decades = std::log10(hi / lo);
  const std::size_t n =
      static_cast<std::size_t>(std::ceil(decades * pulloff_options_.scan_points_per_decade)) + 1;
  std::vector<double> grid(n);
  std::vector<CurvePoint> points(n);
  for (std::size_t k = 0; k < n; ++k) {
    grid[k] = k + 1 == n ? hi : lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(n - 1));
    points[k] = point(eta, grid[k]);
  }

  for (Control control : {Control::kLoad, Control::kDisplacement}) {
    const char* name = control == Control::kLoad ? "load control (minimum of P)"
                                                 : "displacement control (minimum of D)";
    std::vector<double> fx(n), dfx(n);
    for (std::size_t k = 0; k < n; ++k) {
      fx[k] = value_of(points[k], control);
      dfx[k] = slope_of(points[k], control);
    }
    std::function<double(double)> f = [&](double a) { return value_of(point(eta, a), control); };
    std::function<double(double)> df = [&](double a) { return slope_of(point(eta, a), control); };

    PulloffPoint best;
    double best_value = 0.0;
    bool found = false;
    int minima = 0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      if (!(dfx[k] < 0.0 && dfx[k + 1] >= 0.0)) continue;
      ++minima;
      const Located at = locate_minimum(f, df, grid, fx, k, pulloff_options_.location_tolerance);
      const CurvePoint p = point(eta, at.a_bar);
      if (!found || value_of(p, control) < best_value) {  // several minima: keep the lowest
        best_value = value_of(p, control);
        best.a_bar = p.a_bar;
        best.load = p.load;
        best.penetration = p.penetration;
        best.minimiser_discrepancy = at.minimiser_discrepancy;
      }
      found = true;
    }
    best.local_minima = minima;
    best.single_minimum = minima == 1;
    best.interior = found;
    std::ostringstream w;
    w.precision(6);
    if (!found) {
      // No stationary minimum: report the range end with the lower value, flagged.
      const std::size_t k = fx.front() <= fx.back() ? 0 : n - 1;
      best.a_bar = grid[k];
      best.load = points[k].load;
      best.penetration = points[k].penetration;
      best.minimiser_discrepancy = -1.0;
      w << "eta=" << eta << ": " << name << ": no interior minimum in a_bar [" << lo << ", " << hi
        << "]; the value at a_bar=" << grid[k] << " is a range end, not a pull-off";
      result.warnings.push_back(w.str());
    } else if (minima > 1) {
      w << "eta=" << eta << ": " << name << ": " << minima << " local minima in a_bar [" << lo << ", "
        << hi << "]; the lowest is reported (a_bar=" << best.a_bar << ")";
      result.warnings.push_back(w.str());
    }
    if (!found && !truncation.empty()) {
      throw NumericalError("pull-off at eta = " + format_g(eta) + ", " + name +
                           ": no minimum below a_bar = " + format_g(hi) +
                           " and the reduced variables are unavailable above: " + truncation);
    }
    if (found) estimate_errors(best, eta, control == Control::kLoad, lo, hi);
    (control == Control::kLoad ? result.load_control : result.displacement_control) = best;
  }
  if (!truncation.empty()) {
    std::ostringstream w;
    w.precision(6);
    w << "eta=" << eta << ": scan stopped at a_bar=" << hi << " (a/t=" << hi / eta
      << "): reduced variables unavailable above (" << truncation
      << "); minima found below are reported but a lower one above cannot be excluded";
    result.warnings.push_back(w.str());
  }
  return result;
}

}  // namespace coatcontact
