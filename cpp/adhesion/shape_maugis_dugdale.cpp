// ShapeMaugisDugdale (coatcontact/shape_maugis_dugdale.hpp): the cohesive zone of THEORY.md
// section 13 ("Any axisymmetric shape") in SI units. The zone is solved in its own units
// (cohesive_zone.hpp): lengths in t, stresses in E1* (the stack's reference modulus), so
//   x = r/t,  load δ0(x) = δ0(x t)/t,  σ̂ = 2σ0/E1*,  h0 = w/(σ0 t),
//   δ [m] = δ t,  c [m] = c t,  F [N] = F E1* t²   (F = 2∫γ with γ = 2g/E1*: the flat punch's 2aE*δ).
#include "coatcontact/shape_maugis_dugdale.hpp"

#include <cmath>
#include <functional>
#include <sstream>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/limits.hpp"
#include "cohesive_zone.hpp"
#include "parallel.hpp"
#include "table_kernel.hpp"

namespace coatcontact {

namespace {

void check_si(double value, const std::string& what) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw InputError(what + " = " + detail::full_precision(value) + " not allowed (need finite and > 0)");
  }
}

}  // namespace

bool cohesive_zone_allowed(const IndenterShape& shape, std::string* why) {
  // Every other shape of indenter_shape.hpp is a continuous non-decreasing profile (a measured
  // one is checked non-decreasing when read; its zone must stay within its last r, per radius).
  if (!shape.flat()) return true;
  if (why != nullptr) {
    *why = "a flat punch has no surface beyond its contact radius for the cohesive zone to act on and a fixed "
           "contact radius (THEORY.md section 13); allowed with the zone: continuous non-decreasing profiles "
           "(sphere, cone, power, blunted-cone, profile)";
  }
  return false;
}

struct ShapeMaugisDugdale::Impl {
  explicit Impl(const Stack& stack) : kernel(stack) {}
  detail::TableKernel kernel;
  detail::Discretization disc;
  detail::CohesiveQuadrature quadrature;
};

ShapeMaugisDugdale::ShapeMaugisDugdale(const Stack& stack, std::shared_ptr<const IndenterShape> shape,
                                       double thickness, double work, double cohesive_stress)
    : shape_(std::move(shape)), thickness_(thickness), work_(work), sigma0_(cohesive_stress),
      modulus_(stack.reference_modulus()) {
  if (!shape_) throw InputError("ShapeMaugisDugdale needs a shape");
  std::string why;
  if (!cohesive_zone_allowed(*shape_, &why)) throw InputError(why);
  check_si(thickness, "film thickness");
  check_si(work, "work of adhesion");
  check_si(cohesive_stress, "adhesive stress sigma0");
  check_cohesive_range(work / cohesive_stress, thickness);
  impl_ = std::make_unique<Impl>(stack);
}

ShapeMaugisDugdale::~ShapeMaugisDugdale() = default;

ShapeMdPoint ShapeMaugisDugdale::solve(double a_si) const {
  const double t = thickness_;
  const double r_max = shape_->max_contact_radius();
  const IndenterShape& shape = *shape_;
  // Beyond a measured profile's last radius there is no surface: the gap there counts as
  // unbounded (kBeyond), so that the root search brackets from inside; a root at the profile's
  // end is refused below.
  constexpr double kBeyond = 1e100;
  const detail::ShapeLoad load = [&shape, t, r_max](double x) {
    const double r = x * t;
    return r > r_max ? kBeyond : shape.delta0(r) / t;
  };
  const double a = a_si / t;
  const double sigma_hat = 2.0 * sigma0_ / modulus_;
  const double h0 = work_ / (sigma0_ * t);
  const detail::CohesiveZone zone(impl_->kernel, a, load, impl_->disc, impl_->quadrature);
  const detail::CohesiveState st = zone.solve(sigma_hat, h0);
  if (st.c * t >= r_max * (1.0 - 1e-9)) {
    std::ostringstream m;
    m.precision(6);
    m << "cohesive zone at a = " << a_si << " m reaches the shape's last radius " << r_max
      << " m (h(c) = h0 has no root inside the profile)";
    throw NumericalError(m.str());
  }
  ShapeMdPoint p;
  p.radius = a_si;
  p.penetration = st.delta * t;
  p.force = st.force * modulus_ * t * t;
  p.zone_edge = st.c * t;
  if (a > 0.0) {
    const detail::CohesiveFunctions h = zone.adhesionless();
    p.penetration_h = h.delta_h * t;
    p.force_h = h.force_h * modulus_ * t * t;
  }
  return p;
}

ShapeMdPoint ShapeMaugisDugdale::at(double contact_radius) const {
  check_si(contact_radius, "contact radius");
  if (contact_radius > shape_->max_contact_radius()) {
    throw InputError("contact radius " + detail::full_precision(contact_radius) + " m exceeds the shape's largest radius");
  }
  return solve(contact_radius);
}

ShapeMdPoint ShapeMaugisDugdale::curve_end() const { return solve(0.0); }

std::vector<ShapeMdPoint> ShapeMaugisDugdale::curve(const std::vector<double>& radii,
                                                    std::vector<PointStatus>& status) const {
  for (double a : radii) check_si(a, "contact radius");
  std::vector<ShapeMdPoint> out(radii.size());
  std::vector<PointStatus> outcome(radii.size());
  detail::parallel_for(radii.size(), [&](std::size_t i) {
    try {
      out[i] = at(radii[i]);
    } catch (const NumericalError& e) {
      out[i] = ShapeMdPoint{};
      out[i].radius = radii[i];
      outcome[i] = PointStatus{false, e.what()};
    }
  });
  status = std::move(outcome);
  return out;
}

ShapeMdPulloff ShapeMaugisDugdale::pulloff(double scan_min, double scan_max, int points_per_decade) const {
  check_si(scan_min, "pull-off scan's smallest contact radius");
  check_si(scan_max, "pull-off scan's largest contact radius");
  if (!(scan_min < scan_max) || points_per_decade < 4) {
    throw InputError("pull-off scan: need scan_min < scan_max and >= 4 points per decade");
  }
  ShapeMdPulloff result;
  result.scan_min = scan_min;
  result.scan_max = scan_max;
  result.curve_end = curve_end();
  std::size_t n = static_cast<std::size_t>(std::ceil(std::log10(scan_max / scan_min) * points_per_decade)) + 1;
  std::vector<double> grid(n);
  for (std::size_t k = 0; k < n; ++k) {
    grid[k] = k + 1 == n ? scan_max
                         : scan_min * std::pow(scan_max / scan_min, static_cast<double>(k) / static_cast<double>(n - 1));
  }
  std::vector<ShapeMdPoint> points(n);
  std::vector<PointStatus> status(n);
  detail::parallel_for(n, [&](std::size_t k) {
    try {
      points[k] = at(grid[k]);
    } catch (const NumericalError& e) {
      status[k] = PointStatus{false, e.what()};
    }
  });
  // A measured profile ends: the scan stops before the first radius whose zone leaves it.
  std::size_t served = 0;
  while (served < n && status[served].delivered) ++served;
  if (served < n) {
    if (served < 3) throw NumericalError("pull-off scan: " + status[served].reason);
    std::ostringstream w;
    w.precision(6);
    w << "pull-off scan stops at a = " << grid[served - 1] << " m: " << status[served].reason;
    result.warnings.push_back(w.str());
    n = served;
    grid.resize(n);
    points.resize(n);
    result.scan_max = grid.back();
  }
  for (bool load : {true, false}) {
    auto value = [load](const ShapeMdPoint& p) { return load ? p.force : p.penetration; };
    const char* name = load ? "load control (minimum of F)" : "displacement control (minimum of delta)";
    ShapeMdJump best;
    bool found = false;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double f = value(points[k]);
      if (!(f < value(points[k - 1]) && f <= value(points[k + 1]))) continue;
      ++best.local_minima;
      // Brent on x = a/a_k in [a_{k-1}, a_{k+1}]/a_k (values near 1: full relative precision).
      std::function<double(double)> objective = [&](double x) { return value(at(x * grid[k])); };
      ShapeMdPoint p = points[k];
      try {
        const auto minimum = detail::brent_minimum(objective, grid[k - 1] / grid[k], value(points[k - 1]), 1.0, f,
                                                   grid[k + 1] / grid[k], value(points[k + 1]), {1e-10, 0.0, 100});
        if (minimum) p = at(minimum->x * grid[k]);
      } catch (const NumericalError&) {  // the zone left a measured profile: the grid point stands
      }
      if (value(p) > f) p = points[k];
      if (!found || value(p) < value(best.point)) best.point = p;
      found = true;
    }
    best.interior = found && value(best.point) < value(result.curve_end);
    std::ostringstream w;
    w.precision(6);
    if (!best.interior) best.point = result.curve_end;
    if (value(points.front()) < value(points[1]) && value(points.front()) < value(result.curve_end)) {
      w << name << ": lower at a = " << scan_min << " m than at both neighbours; a minimum below the scanned range "
        << "cannot be excluded";
      result.warnings.push_back(w.str());
    } else if (value(points.back()) < value(best.point)) {
      w << name << ": the value at a = " << scan_max << " m, the scan's end, is below the one reported";
      result.warnings.push_back(w.str());
    }
    if (best.local_minima > 1) {
      w.str("");
      w << name << ": " << best.local_minima << " local minima for a in [" << scan_min << ", " << scan_max
        << "] m; the lowest is reported";
      result.warnings.push_back(w.str());
    }
    (load ? result.load : result.displacement) = best;
  }
  return result;
}

}  // namespace coatcontact
