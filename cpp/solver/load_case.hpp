// The scale-free indenter interface of the solver (THEORY.md sections 2, 5 and 11): a shape
// as a load case, the right-hand side θ = -δ0(r)/δ0(a) of the adhesionless problem inside the
// contact. The solver turns any shape into its two reduced numbers (docs/solver.md):
//   Δ = -γ_θ(ã)/γ_fp(ã)   (adhesionless penetration, δ_H = Δ δ0(a)),
//   Π = 4 (Δ E_eq + (1/ã) ∫ γ_θ)   (adhesionless force over its homogeneous scale).
// The shapes in SI units (coatcontact/indenter_shape.hpp) reach the solver through it.
#pragma once
#include <vector>

namespace coatcontact {

class Shape {
 public:
  virtual ~Shape() = default;
  // θ at ξ = r/a in [0, 1], scaled so that θ(1) = -1 (δ0 divided by δ0(a)).
  virtual double theta(double xi) const = 0;
  // true: solve with θ directly (θ extends evenly and smoothly through r = 0);
  // false: use only reciprocity (∫ γ_θ = ∫ θ γ_fp, γ_θ(ã) = θ(ã) - (1/π) ∫ θ w), which needs no
  // accurate γ_θ — for a kink at the apex such as the cone's.
  virtual bool smooth_at_apex() const = 0;
  // ξ in [0, 1] where θ is not smooth (0 for a non-smooth apex, the blunted cone's tangent
  // point, a measured profile's knots). When not empty (and smooth_at_apex() is false), the
  // reciprocity integrals ∫ θ γ_fp and ∫ θ w are product integrals (θ integrated exactly
  // against the interpolants of γ_fp and w, on pieces graded toward these points) instead of
  // node sums: THEORY.md section 11 needs 1e-10 for θ = -ξ^1.5.
  virtual std::vector<double> singular_points() const { return {}; }
  // Halvings of the graded pieces toward each singular point (fewer for a profile's knots,
  // where θ is C^2).
  virtual int grading_levels() const { return 48; }
};

// Paraboloid z = r²/(2R): δ0 = r²/R, θ = -ξ² (Π_s, Δ_s).
class SphereShape final : public Shape {
 public:
  double theta(double xi) const override { return -xi * xi; }
  bool smooth_at_apex() const override { return true; }
};

// Cone z = r/tan β: δ0 = (π/2) r/tan β, θ = -ξ (Π_c, Δ_c).
class ConeShape final : public Shape {
 public:
  double theta(double xi) const override { return -xi; }
  bool smooth_at_apex() const override { return false; }
};

}  // namespace coatcontact
