// ShapeContact (coatcontact/shape_contact.hpp): THEORY.md section 5 steps 3-4 on top of the
// adhesionless solutions of any shape (section 11), in SI units, and the pull-offs (section 10).
#include "coatcontact/shape_contact.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "parallel.hpp"

namespace coatcontact {

namespace {

using detail::kPi;

void check_si(double value, const std::string& what) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw InputError(what + " = " + detail::full_precision(value) + " not allowed (need finite and > 0)");
  }
}

// a with δ0(a) = sqrt(2π a w/E): where adhesion and elasticity balance (the JKR pull-off radius
// up to a factor of order one). δ0(a)/sqrt(a) increases for every shape here (δ0 ~ a^n, n >= 1
// at small a): bisection in ln a.
double balance_radius(const IndenterShape& shape, double work, double modulus) {
  auto excess = [&](double a) { return shape.delta0(a) - std::sqrt(2 * kPi * a * work / modulus); };
  double lo = 1e-15, hi = std::min(1e3, shape.max_contact_radius());
  if (excess(hi) <= 0.0) return hi;
  if (excess(lo) >= 0.0) return lo;
  for (int i = 0; i < 200 && hi / lo > 1.0 + 1e-12; ++i) {
    const double mid = std::sqrt(lo * hi);
    (excess(mid) < 0.0 ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace

ShapeContact::ShapeContact(const ShapeSolver& solver, std::shared_ptr<const IndenterShape> shape,
                           double thickness, double work, double tolerance)
    : solver_(solver), shape_(std::move(shape)), thickness_(thickness), work_(work), tolerance_(tolerance),
      modulus_(solver.stack().reference_modulus()) {
  if (!shape_) throw InputError("ShapeContact needs a shape");
  check_si(thickness, "film thickness");
  check_si(work, "work of adhesion");
}

ShapePoint ShapeContact::at(double a) const {
  check_si(a, "contact radius");
  const ShapeVariables v = solver_.solve(*shape_, a, thickness_, tolerance_);
  ShapePoint p;
  p.radius = a;
  const double d0 = shape_->flat() ? 0.0 : shape_->delta0(a);
  p.penetration_h = shape_->flat() ? 0.0 : v.delta * d0;
  p.force_h = shape_->flat() ? 0.0 : modulus_ * a * d0 * v.pi / 2;
  // Section 5 steps 3-4 (shape-independent): g(a) from the crack-tip energy balance.
  const double stiffness = 2 * a * modulus_ * v.e_eq;
  const double flat_punch = -std::sqrt(2 * kPi * a * work_ / modulus_) / v.gamma1;
  p.penetration = p.penetration_h + flat_punch;
  p.force = p.force_h + stiffness * flat_punch;
  p.error_estimate = v.error_estimate;
  return p;
}

std::vector<ShapePoint> ShapeContact::curve(const std::vector<double>& radii) const {
  for (double a : radii) check_si(a, "contact radius");
  std::vector<ShapePoint> out(radii.size());
  detail::parallel_for(radii.size(), [&](std::size_t i) { out[i] = at(radii[i]); });
  return out;
}

std::vector<ShapePoint> ShapeContact::curve(const std::vector<double>& radii, std::vector<PointStatus>& status) const {
  for (double a : radii) check_si(a, "contact radius");
  return detail::parallel_points<ShapePoint>(
      radii.size(), [&](std::size_t i) { return at(radii[i]); },
      [&](std::size_t i) {
        ShapePoint blank{};
        blank.radius = radii[i];
        return blank;
      },
      status);
}

std::pair<double, double> ShapeContact::default_range() const {
  if (shape_->flat()) return {shape_->max_contact_radius(), shape_->max_contact_radius()};
  const Stack& stack = solver_.stack();
  double lo = balance_radius(*shape_, work_, modulus_), hi = lo;
  if (!stack.substrate().rigid) {
    // The base's modulus as seen with this indenter: E_r,base (section 9).
    const double base = 1.0 / (1.0 / stack.substrate().material.reduced_modulus() +
                                stack.indenter_ratio() / stack.top().reduced_modulus());
    const double a_base = balance_radius(*shape_, work_, base);
    lo = std::min(lo, a_base);
    hi = std::max(hi, a_base);
  }
  lo *= 0.01;
  hi = std::min(10 * hi, shape_->max_contact_radius());
  // Keep a/t inside the solver's range.
  hi = std::min(hi, 1e7 * thickness_);
  lo = std::min(lo, 0.1 * hi);
  return {lo, hi};
}

ShapePulloff ShapeContact::pulloff(double spring, int points_per_decade) const {
  ShapePulloff result;
  result.spring_stiffness = spring;
  if (!(spring >= 0.0) || !std::isfinite(spring)) {
    throw InputError("spring stiffness " + detail::full_precision(spring) + " N/m not allowed (need finite and > 0)");
  }
  if (shape_->flat()) {  // one contact radius: every control jumps at the same point
    const ShapePoint p = at(shape_->max_contact_radius());
    const ShapeJump jump{p.radius, p.penetration, p.force, 1, true};
    result.load = result.displacement = jump;
    if (spring > 0.0) result.spring = jump;
    result.scan_min = result.scan_max = p.radius;
    return result;
  }
  const auto [lo, hi] = default_range();
  result.scan_min = lo;
  result.scan_max = hi;
  const std::size_t n =
      static_cast<std::size_t>(std::ceil(std::log10(hi / lo) * points_per_decade)) + 1;
  std::vector<double> grid(n);
  for (std::size_t k = 0; k < n; ++k) {
    grid[k] = k + 1 == n ? hi : lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(n - 1));
  }
  const std::vector<ShapePoint> points = curve(grid);

  enum Mode { kLoad, kDisplacement, kSpring };
  auto value = [&](const ShapePoint& p, Mode mode) {
    switch (mode) {
      case kLoad: return p.force;
      case kDisplacement: return p.penetration;
      default: return p.penetration + p.force / spring;  // Z = δ + F/k (section 10)
    }
  };
  for (Mode mode : {kLoad, kDisplacement, kSpring}) {
    if (mode == kSpring && spring == 0.0) continue;
    const char* name = mode == kLoad ? "load control (minimum of F)"
                       : mode == kDisplacement ? "displacement control (minimum of delta)"
                                               : "spring control (minimum of delta + F/k)";
    ShapeJump best;
    double best_value = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double f = value(points[k], mode);
      if (!(f < value(points[k - 1], mode) && f <= value(points[k + 1], mode))) continue;
      ++best.local_minima;
      // Brent on x = a/a_k in [a_{k-1}, a_{k+1}]/a_k (values near 1: full relative precision).
      std::function<double(double)> objective = [&](double x) { return value(at(x * grid[k]), mode); };
      const auto minimum = detail::brent_minimum(objective, grid[k - 1] / grid[k], value(points[k - 1], mode), 1.0,
                                                 f, grid[k + 1] / grid[k], value(points[k + 1], mode),
                                                 {1e-10, 0.0, 100});
      const double x = minimum ? minimum->x : 1.0;
      const ShapePoint p = at(x * grid[k]);
      if (value(p, mode) < best_value) {
        best_value = value(p, mode);
        best.radius = p.radius;
        best.penetration = p.penetration;
        best.force = p.force;
      }
      best.interior = true;
    }
    std::ostringstream w;
    w.precision(6);
    if (!best.interior) {
      const std::size_t k = value(points.front(), mode) <= value(points.back(), mode) ? 0 : n - 1;
      best.radius = points[k].radius;
      best.penetration = points[k].penetration;
      best.force = points[k].force;
      w << name << ": no interior minimum for a in [" << lo << ", " << hi << "] m; the value at a = "
        << points[k].radius << " m is a range end, not a pull-off";
      result.warnings.push_back(w.str());
    } else if (best.local_minima > 1) {
      w << name << ": " << best.local_minima << " local minima for a in [" << lo << ", " << hi
        << "] m; the global one is reported (a = " << best.radius << " m)";
      result.warnings.push_back(w.str());
    }
    (mode == kLoad ? result.load : mode == kDisplacement ? result.displacement : result.spring) = best;
  }
  return result;
}

ValidityLimits ShapeContact::validity_limits(double sphere_radius) const {
  ValidityLimits limits;
  limits.thickness = thickness_;
  limits.modulus = modulus_;
  limits.sphere_radius = sphere_radius;
  limits.max_contact_radius = shape_->max_contact_radius();
  return limits;
}

std::vector<std::string> ShapeContact::validity_warnings(const std::vector<ShapePoint>& curve,
                                                         double sphere_radius) const {
  std::vector<double> a, delta, force;
  for (const ShapePoint& p : curve) {
    a.push_back(p.radius);
    delta.push_back(p.penetration);
    force.push_back(p.force);
  }
  return coatcontact::validity_warnings(a, delta, force, validity_limits(sphere_radius));
}

}  // namespace coatcontact
