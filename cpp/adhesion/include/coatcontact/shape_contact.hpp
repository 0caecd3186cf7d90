// Adhesive (JKR) contact of any axisymmetric indenter on a coated substrate, in SI units
// (THEORY.md sections 5 and 11): at each contact radius a the adhesionless solution of the
// shape (ShapeSolver) plus the flat-punch displacement of [selfconsistenceInhom],
//   δ_fp = -sqrt(2π a w/E_r)/Γ(1),  δ = δ_H + δ_fp,  F = F_H + S δ_fp,
// which does not depend on the shape; and the pull-off under load, displacement and spring
// control (section 10), scanning the whole range since blunted and measured shapes can
// have several local minima.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/point_status.hpp"
#include "coatcontact/shape_solver.hpp"

namespace coatcontact {

struct ShapePoint {
  double radius = 0.0;         // a [m]
  double penetration = 0.0;    // δ [m] (adhesive)
  double force = 0.0;          // F [N], compressive positive (adhesive)
  double penetration_h = 0.0;  // δ_H [m] (adhesionless, same a)
  double force_h = 0.0;        // F_H [N]
  double error_estimate = 0.0; // relative, of the solver's values
};

// One pull-off: the jump-off point of one control mode.
struct ShapeJump {
  double radius = 0.0, penetration = 0.0, force = 0.0;
  int local_minima = 0;   // of the minimised quantity in the scanned range
  bool interior = false;  // false: the minimum is at a range end (not a pull-off)
};

struct ShapePulloff {
  ShapeJump load;          // minimum of F
  ShapeJump displacement;  // minimum of δ
  ShapeJump spring;        // minimum of δ + F/k (only when a spring was given)
  double spring_stiffness = 0.0;  // k [N/m], 0: none
  double scan_min = 0.0, scan_max = 0.0;
  std::vector<std::string> warnings;
};

class ShapeContact {
 public:
  // The solver must outlive the contact. thickness t [m], work of adhesion w [J/m²] > 0.
  ShapeContact(const ShapeSolver& solver, std::shared_ptr<const IndenterShape> shape, double thickness,
               double work, double tolerance);

  ShapePoint at(double contact_radius) const;
  // Many radii (in parallel; same results as serial).
  std::vector<ShapePoint> curve(const std::vector<double>& radii) const;
  // Every radius the solver can serve at the tolerance; the others get status[i].delivered =
  // false and the reason (their rows hold the radius and zeros). Delivered points equal at()'s.
  std::vector<ShapePoint> curve(const std::vector<double>& radii, std::vector<PointStatus>& status) const;
  // Contact radii holding both JKR pull-offs (film and base modulus): [0.01 a_min, 10 a_max],
  // a_c solving δ0(a) = sqrt(2π a w/E) for the top and the base's reduced moduli, cut at the
  // shape's largest radius. A flat punch gives [A, A].
  std::pair<double, double> default_range() const;
  // spring_stiffness k [N/m] > 0 adds spring control; 0 for none.
  ShapePulloff pulloff(double spring_stiffness, int points_per_decade = 24) const;

  // The validity limits of this contact (limits.hpp): the coating thickness, the reference
  // modulus, the shape's largest radius and, for a paraboloid standing for a sphere, its
  // radius `sphere_radius` (0: none); and the warnings of a curve against them.
  ValidityLimits validity_limits(double sphere_radius = 0.0) const;
  std::vector<std::string> validity_warnings(const std::vector<ShapePoint>& curve, double sphere_radius = 0.0) const;

  const IndenterShape& shape() const { return *shape_; }
  double reference_modulus() const { return modulus_; }

 private:
  const ShapeSolver& solver_;
  std::shared_ptr<const IndenterShape> shape_;
  double thickness_, work_, tolerance_, modulus_;
};

}  // namespace coatcontact
