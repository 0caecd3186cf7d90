// The reduced variables: the sphere and the cone as the load cases of the refinement loop
// (internal to coatcontact_solver; tests include it).
//
// In units of the film thickness t (x = r/t, ã = a/t, g = (E1*/2) γ), the integral
// equation [EqEquilibriumCS] of THEORY.md section 4 reads, for 0 <= x <= ã,
//
//   θ(x) = γ(x) + (1/π) ∫_0^ã γ(y) [H(x - y) + H(x + y)] dy.
//
// It is discretized on panels graded geometrically toward the contact edge x = ã, with
// p Gauss-Legendre nodes per panel (unknowns: γ at the nodes). Matrix rows are plain
// Nyström sums where the kernel is smooth on the scale of the panel, and product
// integration (the kernel integrated exactly against the panel's interpolating polynomial)
// where it is not, so the number of unknowns does not grow with ã.
#pragma once
#include <limits>

#include "fixed_solve.hpp"
#include "kernel_source.hpp"
#include "refinement.hpp"

namespace coatcontact::detail {

// Order of the six outputs everywhere in the solver (FixedSolve::values of the load cases
// sphere, cone).
enum ReducedIndex { kPiS = 0, kDeltaS, kPiC, kDeltaC, kEEq, kGamma1, kReducedCount };

// The six reduced variables at a fixed discretization. Throws NumericalError if the linear
// system is singular or the results are not finite.
FixedSolve solve_fixed(const KernelSource& kernel, double a_over_t, const Discretization& disc);

// The six reduced variables refined to `tolerance` (refine; bound_limit: RefinementRules).
AdaptiveSolve solve_adaptive(const KernelSource& kernel, double a_over_t, double tolerance,
                             const IndependentKernel& independent = {},
                             double bound_limit = std::numeric_limits<double>::infinity());

}  // namespace coatcontact::detail
