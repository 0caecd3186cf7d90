// Core of the reduced-variable solver (internal to coatcontact_solver; tests include it).
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
#include <algorithm>
#include <cstddef>

namespace coatcontact::detail {

// The kernel H(u) = ∫_0^∞ [C(q) - 1] cos(q u) dq seen by the solver. Implementations:
// the Fortran kernel table (production) and analytic kernels (tests).
class KernelSource {
 public:
  virtual ~KernelSource() = default;
  // h[i] = H(u[i]) for any real u[i]. Must be safe to call concurrently.
  virtual void evaluate(std::size_t n, const double* u, double* h) const = 0;
  // H is analytic in the strip |Im u| < analytic_half_width() (2 for C - 1 ~ q² e^{-2q}).
  virtual double analytic_half_width() const = 0;
  // Bound on the absolute error of the H values returned by evaluate().
  virtual double absolute_accuracy() const = 0;
};

// Lengths set for one film (H analytic in |Im u| < 2) times this: a stack's H is analytic only
// in |Im u| < 2 h_top/T (THEORY.md section 12), so its lengths shrink with the strip.
inline double strip_scale(const KernelSource& kernel) { return std::min(1.0, 0.5 * kernel.analytic_half_width()); }

struct Discretization {
  int nodes_per_panel = 14;        // p
  double edge_panel = 1.0;         // length of the panel at the edge (units of t)
  double growth = 1.0;             // panel k+1 length = growth * (distance of its outer end to ã)
  double single_panel_limit = 2.0; // ã at or below this: one panel [0, ã]
  double quadrature_accuracy = 1e-13;  // target relative accuracy of every matrix entry
};

}  // namespace coatcontact::detail
