// Maugis scales, the lambda range and the validity limits of a curve in SI units
// (coatcontact/limits.hpp; THEORY.md sections 5, 13).
#include "coatcontact/limits.hpp"

#include <algorithm>
#include <cmath>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

namespace {

using detail::kPi;

std::string show(double v) { return detail::short_text(v); }

void check_positive(double value, const char* what) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw InputError(std::string(what) + " = " + detail::full_precision(value) + " not allowed (need finite and > 0)");
  }
}

// K = 4E*/3 of Maugis (section 13).
double maugis_k(const MaugisScales& s) { return 4.0 * s.modulus / 3.0; }

}  // namespace

MaugisScales maugis_scales(double radius, double thickness, double work, double modulus) {
  check_positive(radius, "sphere radius");
  check_positive(thickness, "film thickness");
  check_positive(work, "work of adhesion");
  check_positive(modulus, "reference modulus");
  MaugisScales s;
  s.radius = radius;
  s.thickness = thickness;
  s.work = work;
  s.modulus = modulus;
  s.length = std::cbrt(kPi * work * radius * radius / modulus);
  if (!(std::isfinite(s.length) && s.length > 0.0)) {
    throw InputError("the adhesive length (pi w R^2/E1*)^(1/3) = " + show(s.length) +
                     " is not a finite positive number");
  }
  s.penetration = s.length * s.length / radius;
  s.force = kPi * work * radius;
  s.eta = thickness / s.length;
  if (!(s.eta >= kMinimumScaled && s.eta <= kMaximumScaled)) {
    // In the units given: the thickness and its allowed range; eta in parentheses.
    throw InputError("film thickness t = " + show(thickness) + " m not allowed for this radius, work and modulus; allowed: t in [" +
                     show(kMinimumScaled * s.length) + ", " + show(kMaximumScaled * s.length) + "] m (eta = t/(pi w R^2/E1*)^(1/3) = " +
                     show(s.eta) + ", allowed [" + show(kMinimumScaled) + ", " + show(kMaximumScaled) + "])");
  }
  return s;
}

MaugisScales maugis_scales(double radius, double thickness, double work, double modulus, double cohesive_stress) {
  MaugisScales s = maugis_scales(radius, thickness, work, modulus);
  const double lambda = maugis_lambda(s, cohesive_stress);
  check_cohesive_range(work / cohesive_stress, thickness);
  if (!(lambda >= kMinimumLambda && lambda <= kMaximumLambda)) {
    // In the units given: sigma0 (and h0 = w/sigma0) and their allowed ranges; lambda in parentheses.
    const double lo = maugis_cohesive_stress(s, kMinimumLambda), hi = maugis_cohesive_stress(s, kMaximumLambda);
    throw InputError("sigma0 = " + show(cohesive_stress) + " Pa (range h0 = w/sigma0 = " + show(work / cohesive_stress) +
                     " m) not allowed for this radius, work and modulus; allowed: sigma0 in [" + show(lo) + ", " +
                     show(hi) + "] Pa, h0 in [" + show(work / hi) + ", " + show(work / lo) + "] m (Maugis's lambda = " +
                     show(lambda) + ", allowed [" + show(kMinimumLambda) + ", " + show(kMaximumLambda) + "])");
  }
  s.cohesive_stress = cohesive_stress;
  s.lambda = lambda;
  return s;
}

std::vector<double> scaled_contact_radii(const std::vector<double>& a, const MaugisScales& s) {
  std::vector<double> a_bar;
  a_bar.reserve(a.size());
  for (double radius : a) {
    if (!(radius / s.length >= kMinimumScaled && radius / s.length <= kMaximumScaled)) {
      throw InputError("contact radius " + show(radius) + " m is not allowed; every a must be in [" +
                       show(kMinimumScaled * s.length) + ", " + show(kMaximumScaled * s.length) +
                       "] m (1e-6 to 1e6 times the length scale)");
    }
    a_bar.push_back(radius / s.length);
  }
  return a_bar;
}

double maugis_lambda(const MaugisScales& s, double cohesive_stress) {
  check_positive(cohesive_stress, "adhesive stress sigma0");
  const double k = maugis_k(s);
  return 2.0 * cohesive_stress * std::cbrt(s.radius / (kPi * s.work * k * k));
}

double maugis_cohesive_stress(const MaugisScales& s, double lambda) {
  check_positive(lambda, "lambda");
  const double k = maugis_k(s);
  return 0.5 * lambda / std::cbrt(s.radius / (kPi * s.work * k * k));
}

std::string lambda_range_text() {
  return "[" + show(kMinimumLambda) + ", " + show(kMaximumLambda) + "] or inf";
}

void check_lambda(double lambda, const std::string& source) {
  if (std::isinf(lambda) && lambda > 0.0) return;
  if (!(lambda >= kMinimumLambda && lambda <= kMaximumLambda)) {
    throw InputError("lambda " + show(lambda) + (source.empty() ? "" : " " + source) + " not allowed (need " +
                     lambda_range_text() + ")");
  }
}

void check_cohesive_range(double range, double thickness) {
  if (!(range <= kMaximumRangeOverThickness * thickness)) {
    throw InputError("the range h0 = w/sigma0 = " + show(range) + " m exceeds " + show(kMaximumRangeOverThickness) +
                     " film thicknesses (" + show(kMaximumRangeOverThickness * thickness) + " m)");
  }
}

namespace {

bool has_shape_limit(const ValidityLimits& l) {
  return l.max_contact_radius > 0.0 && std::isfinite(l.max_contact_radius);
}

}  // namespace

bool within_validity(double a, double delta, double force, const ValidityLimits& l) {
  if (delta > l.thickness) return false;
  if (force / (kPi * a * a) > kMaxPressureOverModulus * l.modulus) return false;
  if (l.sphere_radius > 0.0 && a > kMaxContactRadiusOverR * l.sphere_radius) return false;
  if (has_shape_limit(l) && a > l.max_contact_radius) return false;
  return true;
}

std::vector<std::string> validity_warnings(const std::vector<double>& a, const std::vector<double>& delta,
                                           const std::vector<double>& force, const ValidityLimits& l) {
  std::vector<std::string> warnings;
  double a_max = 0.0, delta_max = -INFINITY, p_max = -INFINITY;
  for (std::size_t i = 0; i < a.size() && i < delta.size() && i < force.size(); ++i) {
    a_max = std::max(a_max, a[i]);
    delta_max = std::max(delta_max, delta[i]);
    if (a[i] > 0.0) p_max = std::max(p_max, force[i] / (kPi * a[i] * a[i]));
  }
  if (delta_max > l.thickness) {
    warnings.push_back("penetration reaches " + show(delta_max) + " m, more than the film thickness t = " +
                       show(l.thickness) + " m: the indenter would pass through the film");
  }
  if (l.sphere_radius > 0.0 && a_max > l.sphere_radius) {
    warnings.push_back("contact radius reaches " + show(a_max) + " m, past the sphere's own radius R = " +
                       show(l.sphere_radius) + " m: no sphere has this contact, the paraboloid does not describe it");
  } else if (l.sphere_radius > 0.0 && a_max > kMaxContactRadiusOverR * l.sphere_radius) {
    warnings.push_back("contact radius reaches " + show(a_max) + " m, above 0.1 R = " +
                       show(kMaxContactRadiusOverR * l.sphere_radius) +
                       " m: the paraboloid approximation of the sphere no longer holds");
  }
  if (has_shape_limit(l) && a_max > l.max_contact_radius) {
    warnings.push_back("contact radius reaches " + show(a_max) + " m, past the shape's largest radius " +
                       show(l.max_contact_radius) + " m");
  }
  if (p_max > kMaxPressureOverModulus * l.modulus) {
    warnings.push_back("mean pressure F/(pi a^2) reaches " + show(p_max) + " Pa, above 0.1 E1* = " +
                       show(kMaxPressureOverModulus * l.modulus) +
                       " Pa: strains this large are beyond linear elasticity");
  }
  return warnings;
}

void check_sphere_contact_radii(const std::vector<double>& a, double sphere_radius) {
  if (a.empty() || !(sphere_radius > 0.0)) return;
  const double a_max = *std::max_element(a.begin(), a.end());
  if (a_max > kMaxContactRadiusOverSphere * sphere_radius) {
    throw InputError("contact radius " + show(a_max) + " m is more than " + show(kMaxContactRadiusOverSphere) +
                     " times the sphere radius R = " + show(sphere_radius) +
                     " m: no sphere has this contact; allowed: a <= " +
                     show(kMaxContactRadiusOverSphere * sphere_radius) +
                     " m (the paraboloid approximation holds for a <= 0.1 R)");
  }
}

}  // namespace coatcontact
