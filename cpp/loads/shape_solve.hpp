// The adhesionless solutions of the flat punch and of indenter shapes on one factored system
// (THEORY.md section 5 steps 1-2; docs/solver.md): the right-hand sides θ of the shapes, the
// functionals E_eq, Γ(1), Π, Δ, and first-order bounds of the kernel table's effect on them.
#pragma once
#include <cstddef>
#include <vector>

#include "kernel_source.hpp"
#include "shape.hpp"

namespace coatcontact::detail {

// The two reduced numbers of one indenter shape (loads/shape.hpp).
struct ShapeValues {
  double pi = 0.0;     // Π: adhesionless force over its homogeneous value's scale
  double delta = 0.0;  // Δ: adhesionless penetration over δ0(a)
};

// The flat punch and any shapes on one factorization, at a fixed discretization.
struct ShapeSolve {
  double e_eq = 0.0;
  double gamma1 = 0.0;
  std::vector<ShapeValues> shapes;  // in the order given
  int unknowns = 0;
  int panels = 0;
  double inverse_norm = 0.0;
  double kernel_error = 0.0;    // as FixedSolve::kernel_error, over every output
  double rounding_error = 0.0;
  double consistency = 0.0;
  std::size_t kernel_evaluations = 0;
};

// Throws NumericalError if the linear system is singular or the results are not finite.
ShapeSolve solve_shapes(const KernelSource& kernel, double a_over_t, const Discretization& disc,
                        const std::vector<const Shape*>& shapes);

}  // namespace coatcontact::detail
