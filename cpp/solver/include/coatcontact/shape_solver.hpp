// Adhesionless solutions of any axisymmetric indenter on a coated substrate (THEORY.md
// sections 5 and 11): at one contact radius a, the flat punch and θ = -δ0(r)/δ0(a) on one
// factorization, refined until the relative error estimate meets the tolerance.
#pragma once
#include <memory>

#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

struct ShapeVariables {
  double a_over_t = 0.0;
  double e_eq = 0.0;    // S = 2 a E_ref E_eq
  double gamma1 = 0.0;  // Γ(1) = 2 g_fp(a)/E_ref
  double pi = 0.0;      // F_H = E_ref a δ0(a) Π/2 (Π = 8/3 for a homogeneous paraboloid)
  double delta = 0.0;   // δ_H = Δ δ0(a)
  double error_estimate = 0.0;
  int unknowns = 0;
};

class ShapeSolver {
 public:
  // Builds the kernel table of the stack once.
  explicit ShapeSolver(const Stack& stack);
  ~ShapeSolver();
  ShapeSolver(ShapeSolver&&) noexcept;
  ShapeSolver& operator=(ShapeSolver&&) noexcept;

  // `shape` at contact radius `contact_radius` on a film of thickness `thickness` (same unit).
  // For a flat punch only e_eq and gamma1 are set. InputError for a/t outside (0, 1e8] or a
  // radius beyond the shape's; NumericalError if the tolerance cannot be met. Thread-safe.
  ShapeVariables solve(const IndenterShape& shape, double contact_radius, double thickness,
                       double tolerance) const;

  const Stack& stack() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace coatcontact
