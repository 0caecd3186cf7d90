// Closed-form indenter shapes (THEORY.md sections 2 and 11).
#include <cmath>
#include <memory>
#include <sstream>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/indenter_shape.hpp"

namespace coatcontact {

namespace {

using detail::kPi;

using detail::full_precision;

void require(bool ok, const std::string& what, double value, const std::string& allowed) {
  if (!ok) throw InputError(what + " " + full_precision(value) + " is not allowed; " + allowed);
}

void check_length(double value, const std::string& what) {
  require(std::isfinite(value) && value > 0.0, what, value, "it must be finite and > 0");
}

void check_angle(double beta) {
  require(std::isfinite(beta) && beta > 0.0 && beta < kPi / 2, "half included angle (rad)", beta,
          "it must lie in (0, 90) degrees");
}

std::string text(double v) { return detail::short_text(v); }

class Paraboloid final : public IndenterShape {
 public:
  explicit Paraboloid(double radius) : radius_(radius) {}
  double delta0(double r) const override { return r * r / radius_; }
  bool smooth_at_apex() const override { return true; }
  std::string description() const override { return "paraboloid z = r^2/(2R), R = " + text(radius_) + " m"; }

 private:
  double radius_;
};

class Cone final : public IndenterShape {
 public:
  explicit Cone(double beta) : beta_(beta) {}
  double delta0(double r) const override { return kPi / 2 * r / std::tan(beta_); }
  bool smooth_at_apex() const override { return false; }
  std::string description() const override {
    return "cone z = r cot(beta), beta = " + text(beta_ * 180 / kPi) + " deg";
  }

 private:
  double beta_;
};

// A four-sided pyramid as the cone of equal cross-section area (the usual axisymmetric stand-in,
// as `afm fit` takes it): tan(beta) = 2 tan(theta)/sqrt(pi), theta the face half angle.
class Pyramid final : public IndenterShape {
 public:
  Pyramid(double theta, double beta) : theta_(theta), cone_(beta) {}
  double delta0(double r) const override { return cone_.delta0(r); }
  bool smooth_at_apex() const override { return false; }
  std::string description() const override {
    return "four-sided pyramid, face half angle " + text(theta_ * 180 / kPi) + " deg, as the " + cone_.description() +
           " of equal area";
  }

 private:
  double theta_;
  Cone cone_;
};

class FlatPunch final : public IndenterShape {
 public:
  explicit FlatPunch(double radius) : radius_(radius) {}
  double delta0(double) const override { return 0.0; }
  bool smooth_at_apex() const override { return true; }
  bool flat() const override { return true; }
  double max_contact_radius() const override { return radius_; }
  std::string description() const override { return "flat punch, radius " + text(radius_) + " m"; }

 private:
  double radius_;
};

class PowerLaw final : public IndenterShape {
 public:
  PowerLaw(double n, double radius) : n_(n), radius_(radius), c_(power_law_coefficient(n)) {}
  double delta0(double r) const override { return c_ * radius_ * std::pow(r / radius_, n_); }
  // |ξ|^n is smooth through 0 only for even integers n (section 11); else reciprocity.
  bool smooth_at_apex() const override { return std::fmod(n_, 2.0) == 0.0; }
  std::string description() const override {
    return "power law z = r^n/(n R^(n-1)), n = " + text(n_) + ", R = " + text(radius_) + " m";
  }

 private:
  double n_, radius_, c_;
};

class BluntedCone final : public IndenterShape {
 public:
  BluntedCone(double radius, double beta)
      : radius_(radius), beta_(beta), b_(radius * std::cos(beta)), s_(radius * std::sin(beta)) {}
  double delta0(double r) const override {
    if (r <= b_) return r * std::atanh(r / radius_);  // spherical cap, exact
    const double root = std::sqrt((r - b_) * (r + b_));
    return r * (std::log((r + radius_) / (root + s_)) + std::acos(b_ / r) / std::tan(beta_));
  }
  bool smooth_at_apex() const override { return true; }  // r artanh(r/R) is even in r
  std::vector<double> kinks() const override { return {b_}; }  // (r - b)^{3/2} term
  std::string description() const override {
    return "blunted cone: spherical cap R = " + text(radius_) + " m tangent at b = R cos(beta) = " + text(b_) +
           " m to a cone of half angle beta = " + text(beta_ * 180 / kPi) + " deg";
  }

 private:
  double radius_, beta_, b_, s_;
};

}  // namespace

double power_law_coefficient(double n) {
  return std::sqrt(kPi) / 2 * std::exp(std::lgamma(n / 2) - std::lgamma((n + 1) / 2));
}

double blunted_cone_force_over_modulus(double radius, double beta, double a) {
  const double b = radius * std::cos(beta), s = radius * std::sin(beta);
  const double rr = radius * radius + a * a;
  if (a <= b) return rr * std::atanh(a / radius) - radius * a;
  const double root = std::sqrt((a - b) * (a + b));
  return s * root - radius * a + rr * std::log((radius + a) / (s + root)) +
         (a * a * std::acos(b / a) + b * root) / std::tan(beta);
}

std::shared_ptr<const IndenterShape> make_paraboloid(double radius) {
  check_length(radius, "sphere radius R");
  return std::make_shared<Paraboloid>(radius);
}

std::shared_ptr<const IndenterShape> make_cone(double beta) {
  check_angle(beta);
  return std::make_shared<Cone>(beta);
}

std::shared_ptr<const IndenterShape> make_pyramid(double face_half_angle) {
  check_angle(face_half_angle);
  const double beta = std::atan(2.0 * std::tan(face_half_angle) / std::sqrt(kPi));
  check_angle(beta);
  return std::make_shared<Pyramid>(face_half_angle, beta);
}

std::shared_ptr<const IndenterShape> make_flat_punch(double radius) {
  check_length(radius, "punch radius");
  return std::make_shared<FlatPunch>(radius);
}

std::shared_ptr<const IndenterShape> make_power_law(double n, double radius) {
  require(std::isfinite(n) && n > 0.0 && n <= 100.0, "power-law exponent N", n, "it must lie in (0, 100]");
  check_length(radius, "power-law radius R");
  return std::make_shared<PowerLaw>(n, radius);
}

std::shared_ptr<const IndenterShape> make_blunted_cone(double radius, double beta) {
  check_length(radius, "tip radius R");
  check_angle(beta);
  return std::make_shared<BluntedCone>(radius, beta);
}

}  // namespace coatcontact
