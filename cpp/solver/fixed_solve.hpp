// The adhesionless solutions of the flat punch and of indenter shapes on one factored system
// at one discretization (THEORY.md section 5 steps 1-2; docs/solver.md): the right-hand sides
// θ of the shapes, the functionals E_eq, Γ(1), Π, Δ, and first-order bounds of the kernel
// table's effect on them. The refinement loop (refinement.hpp) repeats it at increasing p.
#pragma once
#include <cstddef>
#include <vector>

#include "kernel_source.hpp"
#include "load_case.hpp"

namespace coatcontact::detail {

// One solve at a fixed discretization: the result type of every load case.
struct FixedSolve {
  // Π, Δ of each shape in the order given, then E_eq and Γ(1) of the flat punch (for the
  // shapes sphere, cone: the order of ReducedIndex).
  std::vector<double> values;
  int unknowns = 0;
  int panels = 0;
  // Coherent worst-case bound on the relative output error caused by the kernel accuracy
  // (|δH| <= ε with one sign everywhere; cheap, but grows like ã E_eq: docs/solver.md).
  double kernel_error = 0.0;
  // Relative error from rounding in the assembly and LU solve: ε_machine cond_inf(A)
  // (calibrated: the measured error is <= 0.08 of it, docs/solver.md).
  double rounding_error = 0.0;
  double consistency = 0.0;  // |Γ1 direct - Γ1 by reciprocity| / Γ1 (a discretization check)

  double pi(std::size_t shape) const { return values[2 * shape]; }
  double delta(std::size_t shape) const { return values[2 * shape + 1]; }
  double e_eq() const { return values[values.size() - 2]; }
  double gamma1() const { return values.back(); }
};

// Throws NumericalError if the linear system is singular or the results are not finite.
FixedSolve solve_shapes(const KernelSource& kernel, double a_over_t, const Discretization& disc,
                        const std::vector<const Shape*>& shapes);

}  // namespace coatcontact::detail
