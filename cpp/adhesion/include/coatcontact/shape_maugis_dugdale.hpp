// Maugis-Dugdale contact of an axisymmetric indenter of any allowed shape on a coated substrate,
// in SI units (THEORY.md section 13, "Any axisymmetric shape"): per contact radius a the direct
// cohesive-zone solve with the shape as one more load, the zone edge c from h(c) = h0 = w/σ0,
// then δ and F. No Maugis λ without a sphere radius: the inputs are σ0, w and lengths.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/point_status.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

struct ShapeMdPoint {
  double radius = 0.0;         // a [m] (0: the end of the curve, no contact)
  double penetration = 0.0;    // δ [m]
  double force = 0.0;          // F [N], compressive positive
  double zone_edge = 0.0;      // c [m], outer edge of the cohesive zone
  double penetration_h = 0.0;  // δ_H [m] (adhesionless, same a)
  double force_h = 0.0;        // F_H [N]
};

// One pull-off of the cohesive-zone curve: an interior minimum, or the curve's end a -> 0.
struct ShapeMdJump {
  ShapeMdPoint point;
  int local_minima = 0;   // interior local minima of the minimised quantity in the scan
  bool interior = false;  // false: the end of the curve a -> 0 (no vertical tangent)
};

struct ShapeMdPulloff {
  ShapeMdJump load;          // minimum of F
  ShapeMdJump displacement;  // minimum of δ
  ShapeMdPoint curve_end;    // a -> 0
  double scan_min = 0.0, scan_max = 0.0;
  std::vector<std::string> warnings;
};

// Whether the cohesive zone is defined under the shape (section 13: a continuous non-decreasing
// profile beyond the contact); false for the flat punch. `why` receives the reason and what is
// allowed when false.
bool cohesive_zone_allowed(const IndenterShape& shape, std::string* why = nullptr);

class ShapeMaugisDugdale {
 public:
  // thickness t [m] (the stack's unit length), work w [J/m²], cohesive stress σ0 [Pa]; the range
  // h0 = w/σ0 at most kMaximumRangeOverThickness t. InputError for a shape that does not allow
  // the zone (cohesive_zone_allowed) or values out of range.
  ShapeMaugisDugdale(const Stack& stack, std::shared_ptr<const IndenterShape> shape, double thickness, double work,
                     double cohesive_stress);
  ~ShapeMaugisDugdale();
  ShapeMaugisDugdale(const ShapeMaugisDugdale&) = delete;
  ShapeMaugisDugdale& operator=(const ShapeMaugisDugdale&) = delete;

  // a > 0; NumericalError when h(c) = h0 has no root (e.g. the zone would leave a measured profile).
  ShapeMdPoint at(double contact_radius) const;
  // The end of the curve a -> 0: a disk of tension of radius c.
  ShapeMdPoint curve_end() const;
  // Many radii in parallel (same results as serial); radii the solve cannot serve get
  // status[i].delivered = false and the reason.
  std::vector<ShapeMdPoint> curve(const std::vector<double>& radii, std::vector<PointStatus>& status) const;

  // Pull-offs under load and displacement control (THEORY.md sections 10 and 13): the minimum
  // of F (δ) over contact radii in [scan_min, scan_max] [m], log-spaced, points_per_decade,
  // each interior local minimum refined by Brent's minimiser, against the curve's end a -> 0,
  // which is reported when it is lower (the MD curve reaches a = 0 at finite force).
  ShapeMdPulloff pulloff(double scan_min, double scan_max, int points_per_decade = 24) const;

  double cohesive_stress() const { return sigma0_; }
  double reference_modulus() const { return modulus_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::shared_ptr<const IndenterShape> shape_;
  double thickness_, work_, sigma0_, modulus_;
  ShapeMdPoint solve(double a) const;
};

}  // namespace coatcontact
