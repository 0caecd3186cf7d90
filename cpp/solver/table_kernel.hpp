// The Fortran kernel table (coatcontact::KernelTable, cpp/solver/include/coatcontact/kernel.hpp) as
// the solver's KernelSource (internal to coatcontact_solver).
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <mutex>

#include "coatcontact/kernel.hpp"
#include "coatcontact/stack.hpp"
#include "reduced_core.hpp"
#include "refinement.hpp"

namespace coatcontact::detail {

class TableKernel : public KernelSource {
 public:
  // Builds the table of H for the stack (THEORY.md section 4). InputError for constants the
  // kernel library rejects, NumericalError if the table cannot be built.
  // grid_variant: the table's grid (0 = default; 1, 2 = independent grids used to estimate
  // the effect of the table's errors a posteriori, docs/solver.md).
  explicit TableKernel(const Stack& stack, int grid_variant = 0);
  // Grid variant 0 on a compact grid that tabulates at least [0, u_range] (series beyond).
  TableKernel(const Stack& stack, double u_range);

  void evaluate(std::size_t n, const double* u, double* h) const override;
  // C - 1 ~ q² e^{-2q}: H is analytic in |Im u| < 2 (THEORY.md section 4); a stack's
  // C - 1 ~ exp(-2 q h_top/T): |Im u| < 2 h_top/T (section 12).
  double analytic_half_width() const override { return half_width_; }
  double absolute_accuracy() const override { return info_.abs_accuracy; }
  // End of the tabulated range (the far-field series beyond).
  double u_max() const { return info_.u_max; }

 private:
  KernelTable table_;
  KernelTableInfo info_;
  double half_width_ = 2.0;
};

// The same H on independent grids (variants 1 and 2), for the a-posteriori kernel-error
// estimate (docs/solver.md); built on first need (~20-50 ms each), only when the coherent
// bound is too large for the tolerance (rigid substrates, very soft films, large a/t).
class IndependentTables {
 public:
  explicit IndependentTables(const Stack& stack) : stack_(stack) {}
  // Table `index`, or nullptr when they cannot be built (the coherent bound stays the kernel
  // term). Thread-safe; `stack` must outlive this.
  const KernelSource* get(int index);
  // The refinement loop's view of them.
  IndependentKernel source() {
    return [this](int index) { return get(index); };
  }

 private:
  const Stack& stack_;
  std::once_flag once_;
  std::array<std::unique_ptr<TableKernel>, kIndependentTables> tables_;
};

// H for solves whose reach varies call by call (the Maugis-Dugdale nodes, THEORY.md section 13,
// "Kernel tables by reach"): a call whose every |u| <= compact_range is served by the compact grid
// tabulating at least [0, compact_range] (variant 0; 1/8 of the full grid's panels for 320), any
// other call by the full default grid; each built on first need. The
// table a call uses depends on its u alone, so a value is the same whatever was evaluated before.
// A stack whose compact grid misses its accuracy target uses the full grid for every call.
// Thread-safe; `stack` is copied.
class ReachKernel : public KernelSource {
 public:
  ReachKernel(const Stack& stack, double compact_range);
  void evaluate(std::size_t n, const double* u, double* h) const override;
  double analytic_half_width() const override { return half_width_; }
  // The larger of the two grids' (both built).
  double absolute_accuracy() const override;

 private:
  const TableKernel* compact() const;  // nullptr when refused
  const TableKernel& full() const;
  Stack stack_;
  double compact_range_;
  double half_width_;
  mutable std::once_flag compact_once_, full_once_;
  mutable std::unique_ptr<TableKernel> compact_, full_;
};

// The cohesive-zone solves' compact range (THEORY.md section 13, "Kernel tables by reach"): the
// AFM fit's nodes (a/t <= 100, roots c/t <~ 130) all reach u <= 256; 1/8 of the full grid's panels,
// 1/12-1/5 of its build.
inline constexpr double kCohesiveZoneCompactRange = 320.0;

// Tables sized to the work: the solver needs H at |x +- y| <= 2 a/t only, so radii up to
// kSolverTableRange[k] / 2 use a compact table of that range (a fraction of the full grid's
// FFT work, which dominated a one-radius call); the last level is the full default grid. The
// level depends on a/t alone, so a radius gets the same values whatever else is solved.
// One compact level (u <= 80, a/t <= 40): compact levels 320 and 1280, measured with an
// acceptance limit of 1e-12 on the coherent bound (not with tolerance / 10, table_kernel.cpp),
// were nearly always refused, and the first-level solves spent finding that out made the
// 200-radius sweep 10% slower than the full grid alone. Under tolerance / 10 they are kept, within
// their estimates, but a sweep to a/t 1e4 still needs the full grid: 1.25x its CPU (docs/speed.md,
// "200 radii, second round").
constexpr int kSolverTableLevels = 2;
int solver_table_level(double a_over_t);
// The table of `level`: a compact grid that misses its accuracy target is tried at twice and
// four times its range, then falls back to the next level's grid.
std::unique_ptr<TableKernel> make_solver_table(const Stack& stack, int level);
// The reduced variables (solve_adaptive) on the table of a/t's level, `table(level)`; where that is not decided by the
// cheap coherent kernel bound <= tolerance / 10 (the attempt then stops after its first level),
// again on the full grid, whose independent tables give the two-table estimate.
AdaptiveSolve solve_on_solver_tables(const std::function<const KernelSource&(int level)>& table,
                                     double a_over_t, double tolerance,
                                     const IndependentKernel& independent);

}  // namespace coatcontact::detail
