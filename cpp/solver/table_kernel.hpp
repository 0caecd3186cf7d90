// The Fortran kernel table (coatcontact::KernelTable, cpp/include/coatcontact/kernel.hpp) as
// the solver's KernelSource (internal to coatcontact_solver).
#pragma once
#include "coatcontact/kernel.hpp"
#include "coatcontact/stack.hpp"
#include "reduced_core.hpp"

namespace coatcontact::detail {

class TableKernel : public KernelSource {
 public:
  // Builds the table of H for the stack (THEORY.md section 4). InputError for constants the
  // kernel library rejects, NumericalError if the table cannot be built.
  // grid_variant: the table's grid (0 = default; 1, 2 = independent grids used to estimate
  // the effect of the table's errors a posteriori, docs/solver.md).
  explicit TableKernel(const Stack& stack, int grid_variant = 0);

  void evaluate(std::size_t n, const double* u, double* h) const override;
  // C - 1 ~ q² e^{-2q}: H is analytic in |Im u| < 2 (THEORY.md section 4); a stack's
  // C - 1 ~ exp(-2 q h_top/T): |Im u| < 2 h_top/T (section 12).
  double analytic_half_width() const override { return half_width_; }
  double absolute_accuracy() const override { return info_.abs_accuracy; }

 private:
  KernelTable table_;
  KernelTableInfo info_;
  double half_width_ = 2.0;
};

}  // namespace coatcontact::detail
