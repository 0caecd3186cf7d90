// Adhesive sphere in physical units: the Maugis scales of THEORY.md section 5
// [EqSolNormF, EqSolNormD] applied to the normalized AdhesiveModel.
#include <cmath>
#include <memory>
#include <sstream>

#include "coatcontact/adhesive.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

namespace {
void check_si(double value, const char* what) {
  if (!(value > 0.0 && std::isfinite(value))) {
    std::ostringstream s;
    s.precision(17);
    s << what << " = " << value << " not allowed (need finite and > 0)";
    throw InputError(s.str());
  }
}
}  // namespace

SphereContact::SphereContact(const AdhesiveModel& model, double radius, double thickness,
                             double work_of_adhesion)
    : model_(model), radius_(radius), thickness_(thickness), work_(work_of_adhesion) {
  check_si(radius, "sphere radius");
  check_si(thickness, "film thickness");
  check_si(work_of_adhesion, "work of adhesion");
  // l = (pi w R^2 / E1*)^(1/3): a = a_bar l, t = eta l.
  length_scale_ = std::cbrt(M_PI * work_ * radius_ * radius_ / model_.film().reduced_modulus());
  check_si(length_scale_, "Maugis length (pi w R^2/E1*)^(1/3)");
}

double SphereContact::force_scale() const { return M_PI * work_ * radius_; }

double SphereContact::force(double contact_radius) const {
  check_si(contact_radius, "contact radius");
  return force_scale() * model_.point(eta(), contact_radius / length_scale_).load;
}

double SphereContact::penetration(double contact_radius) const {
  check_si(contact_radius, "contact radius");
  return penetration_scale() * model_.point(eta(), contact_radius / length_scale_).penetration;
}

const Pulloff& SphereContact::pulloff() const {
  if (!pulloff_) pulloff_ = std::make_unique<Pulloff>(model_.pulloff(eta()));
  return *pulloff_;
}

double SphereContact::pulloff_force_load() const { return force_scale() * pulloff().load_control.load; }
double SphereContact::pulloff_force_disp() const {
  return force_scale() * pulloff().displacement_control.load;
}

}  // namespace coatcontact
