// ShapeMaugisDugdale (coatcontact/shape_maugis_dugdale.hpp): the cohesive zone of THEORY.md
// section 13 ("Any axisymmetric shape") in SI units. The zone is solved in its own units
// (cohesive_zone.hpp): lengths in t, stresses in E1* (the stack's reference modulus), so
//   x = r/t,  load δ0(x) = δ0(x t)/t,  σ̂ = 2σ0/E1*,  h0 = w/(σ0 t),
//   δ [m] = δ t,  c [m] = c t,  F [N] = F E1* t²   (F = 2∫γ with γ = 2g/E1*: the flat punch's 2aE*δ).
#include "coatcontact/shape_maugis_dugdale.hpp"

#include <cmath>
#include <sstream>

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
  const detail::ShapeLoad load = [&shape, t, r_max](double x) {
    const double r = x * t;
    if (r > r_max) {
      std::ostringstream m;
      m.precision(6);
      m << "cohesive zone reaches r = " << r << " m, beyond the shape's last radius " << r_max << " m";
      throw NumericalError(m.str());
    }
    return shape.delta0(r) / t;
  };
  const double a = a_si / t;
  const double sigma_hat = 2.0 * sigma0_ / modulus_;
  const double h0 = work_ / (sigma0_ * t);
  const detail::CohesiveZone zone(impl_->kernel, a, load, impl_->disc, impl_->quadrature);
  const detail::CohesiveState st = zone.solve(sigma_hat, h0);
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

}  // namespace coatcontact
