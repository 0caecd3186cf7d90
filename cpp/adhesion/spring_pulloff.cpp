// Pull-off through a spring (THEORY.md section 10): with the base position Z = delta + F/k,
// the contact jumps off where dF/ddelta = -k, i.e. at the minimum of Z(a) = D + P/k_bar along
// the adhesive curve. Scanned on the grid and range of AdhesiveModel::pulloff (which also
// gives the two limits exactly), each local minimum located by a root of dZ/da_bar.
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

namespace {

// Root of df in [lo, hi] (df(lo) < 0 <= df(hi)) to relative `tolerance`.
double derivative_root(const std::function<double(double)>& df, double lo, double hi, double tolerance) {
  if (df(hi) == 0.0) return hi;
  const auto found = detail::brent_root(df, lo, hi, {0.0, tolerance, 300});
  if (!found) {
    throw NumericalError("spring pull-off: cannot bracket dZ/da_bar = 0 in a_bar [" +
                         detail::full_precision(lo) + ", " + detail::full_precision(hi) + "]");
  }
  if (!found->converged) {
    throw NumericalError("spring pull-off: root of dZ/da_bar not converged near a_bar = " +
                         detail::full_precision(found->x));
  }
  return found->x;
}

}  // namespace

SpringPulloff AdhesiveModel::pulloff_spring(double eta, double k_bar) const {
  if (std::isnan(k_bar) || k_bar < 0.0) {
    throw InputError("k_bar = " + detail::full_precision(k_bar) +
                     " not allowed (need >= 0; 0 is load control, inf displacement control)");
  }
  const Pulloff limits = pulloff(eta);
  SpringPulloff result;
  result.eta = eta;
  result.k_bar = k_bar;
  // The limits are the existing minima of P and of D, returned as they are (section 10).
  if (k_bar == 0.0 || std::isinf(k_bar)) {
    result.point = k_bar == 0.0 ? limits.load_control : limits.displacement_control;
    result.warnings = limits.warnings;
    return result;
  }
  // Z scaled so that neither term is divided by a tiny or huge k_bar: k_bar Z for k_bar <= 1.
  const double wp = k_bar <= 1.0 ? 1.0 : 1.0 / k_bar;
  const double wd = k_bar <= 1.0 ? k_bar : 1.0;
  auto value = [&](const CurvePoint& p) { return wd * p.penetration + wp * p.load; };
  auto slope = [&](const CurvePoint& p) { return wd * p.dpenetration + wp * p.dload; };
  const std::function<double(double)> dz = [&](double a) { return slope(point(eta, a)); };

  const double lo = limits.a_bar_scan_min, hi = limits.a_bar_scan_max;
  const std::size_t n = static_cast<std::size_t>(
                            std::ceil(std::log10(hi / lo) * pulloff_options_.scan_points_per_decade)) + 1;
  std::vector<double> grid(n);
  std::vector<CurvePoint> points(n);
  for (std::size_t k = 0; k < n; ++k) {
    grid[k] = k + 1 == n ? hi : lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(n - 1));
    points[k] = point(eta, grid[k]);
  }
  int minima = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (!(slope(points[k]) < 0.0 && slope(points[k + 1]) >= 0.0)) continue;
    ++minima;
    const double a = derivative_root(dz, grid[k], grid[k + 1], pulloff_options_.location_tolerance);
    const CurvePoint p = point(eta, a);
    if (value(p) < best) {
      best = value(p);
      result.point.a_bar = a;
      result.point.load = p.load;
      result.point.penetration = p.penetration;
    }
  }
  result.point.local_minima = minima;
  result.point.single_minimum = minima == 1;
  result.point.interior = minima > 0;
  result.point.minimiser_discrepancy = -1.0;  // located by the derivative root alone
  std::ostringstream w;
  w.precision(6);
  if (minima == 0) {
    const std::size_t k = value(points.front()) <= value(points.back()) ? 0 : n - 1;
    result.point.a_bar = grid[k];
    result.point.load = points[k].load;
    result.point.penetration = points[k].penetration;
    w << "eta=" << eta << ", k_bar=" << k_bar << ": spring control: no interior minimum of Z = D + P/k_bar in a_bar ["
      << lo << ", " << hi << "]; the value at a_bar=" << grid[k] << " is a range end, not a pull-off";
    result.warnings.push_back(w.str());
  } else if (minima > 1) {
    w << "eta=" << eta << ", k_bar=" << k_bar << ": spring control: " << minima
      << " local minima of Z = D + P/k_bar; the lowest is reported (a_bar=" << result.point.a_bar << ")";
    result.warnings.push_back(w.str());
  }
  return result;
}

}  // namespace coatcontact
