// The adhesive sphere in SI units (THEORY.md section 5, [EqSolNormF, EqSolNormD]): the
// Maugis scales, their allowed range, the curve's default range and the pull-off forces.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/limits.hpp"

namespace coatcontact {

// Rigid sphere of radius R on a coating of thickness t, work of adhesion w (SI units, all > 0).
// Keeps a reference to `model`, which must outlive it.
// Maugis scales (limits.hpp): length l = (pi w R^2/E*)^(1/3), penetration l^2/R, force pi w R;
// eta = t/l. InputError (naming the inputs that produced it) unless l is finite and eta lies
// in [kMinimumScaled, kMaximumScaled].
class Contact {
 public:
  Contact(const AdhesiveModel& model, double radius, double thickness, double work_of_adhesion);

  const MaugisScales& scales() const { return scales_; }
  double length_scale() const { return scales_.length; }
  double penetration_scale() const { return scales_.penetration; }
  double force_scale() const { return scales_.force; }
  double eta() const { return scales_.eta; }
  // The limits of a sphere of this radius on this coating (limits.hpp), and the warnings of a
  // curve against them.
  ValidityLimits validity_limits() const;

  // SI points of the curve at the default a_bar range (AdhesiveModel::default_curve_range).
  struct Point {
    double radius = 0.0;       // a [m]
    double penetration = 0.0;  // delta [m]
    double force = 0.0;        // F [N], compressive positive
  };
  std::vector<Point> default_curve(std::size_t points) const;
  std::vector<std::string> validity_warnings(const std::vector<Point>& curve) const;

  double force(double contact_radius) const;        // F [N], compressive positive
  double penetration(double contact_radius) const;  // delta [m]
  double pulloff_force_load() const;   // [N] (negative: tensile)
  double pulloff_force_disp() const;   // [N]
  const Pulloff& pulloff() const;      // normalized details (computed once)
  const AdhesiveModel& model() const { return model_; }

 private:
  const AdhesiveModel& model_;
  MaugisScales scales_;
  mutable std::unique_ptr<Pulloff> pulloff_;
};

// n values log-spaced from lo to hi inclusive (the last one exactly hi).
std::vector<double> log_spaced(double lo, double hi, std::size_t n);

}  // namespace coatcontact
