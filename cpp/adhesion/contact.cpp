// The adhesive sphere in SI units: the Maugis scales of THEORY.md section 5
// [EqSolNormF, EqSolNormD] applied to the normalized AdhesiveModel.
#include "coatcontact/contact.hpp"

#include <cmath>
#include <memory>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

namespace {

void check_si(double value, const char* what) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw InputError(std::string(what) + " = " + detail::full_precision(value) +
                     " not allowed (need finite and > 0)");
  }
}

}  // namespace

std::vector<double> log_spaced(double lo, double hi, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t k = 0; k < n; ++k) {
    v[k] = n == 1 ? lo : lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(n - 1));
  }
  if (n > 1) v.back() = hi;
  return v;
}

Contact::Contact(const AdhesiveModel& model, double radius, double thickness, double work_of_adhesion)
    : model_(model),
      scales_(maugis_scales(radius, thickness, work_of_adhesion, model.stack().reference_modulus())) {}

ValidityLimits Contact::validity_limits() const {
  ValidityLimits limits;
  limits.thickness = scales_.thickness;
  limits.modulus = scales_.modulus;
  limits.sphere_radius = scales_.radius;
  return limits;
}

std::vector<std::string> Contact::validity_warnings(const std::vector<Point>& curve) const {
  std::vector<double> a, delta, force;
  for (const Point& p : curve) {
    a.push_back(p.radius);
    delta.push_back(p.penetration);
    force.push_back(p.force);
  }
  return coatcontact::validity_warnings(a, delta, force, validity_limits());
}

std::vector<Contact::Point> Contact::default_curve(std::size_t points) const {
  const auto [lo, hi] = model_.default_curve_range();
  const std::vector<CurvePoint> curve = model_.curve(eta(), log_spaced(lo, hi, points));
  std::vector<Point> out;
  out.reserve(curve.size());
  for (const CurvePoint& p : curve) {
    out.push_back({p.a_bar * length_scale(), p.penetration * penetration_scale(), p.load * force_scale()});
  }
  return out;
}

double Contact::force(double contact_radius) const {
  check_si(contact_radius, "contact radius");
  return force_scale() * model_.point(eta(), contact_radius / length_scale()).load;
}

double Contact::penetration(double contact_radius) const {
  check_si(contact_radius, "contact radius");
  return penetration_scale() * model_.point(eta(), contact_radius / length_scale()).penetration;
}

const Pulloff& Contact::pulloff() const {
  if (!pulloff_) pulloff_ = std::make_unique<Pulloff>(model_.pulloff(eta()));
  return *pulloff_;
}

double Contact::pulloff_force_load() const { return force_scale() * pulloff().load_control.load; }
double Contact::pulloff_force_disp() const {
  return force_scale() * pulloff().displacement_control.load;
}

}  // namespace coatcontact
