// Adapter from the Fortran kernel table to the solver's KernelSource.
#include "table_kernel.hpp"

#include <algorithm>
#include <limits>

#include "coatcontact/errors.hpp"

namespace coatcontact::detail {

namespace {
// A stack's C - 1 ~ exp(-2 q h_top/T): H is analytic in |Im u| < 2 h_top/T (THEORY.md section
// 12); one film (h_top = T) gives section 4's |Im u| < 2.
double analytic_half_width_of(const Stack& stack) {
  return 2.0 * stack.layers().front().thickness / stack.total_thickness();
}
}  // namespace

TableKernel::TableKernel(const Stack& stack, int grid_variant)
    : table_(stack, grid_variant, KernelTable::HOnly{}),  // the solver evaluates H alone
      info_(table_.info()),
      half_width_(analytic_half_width_of(stack)) {}

TableKernel::TableKernel(const Stack& stack, double u_range)
    : table_(stack, u_range), info_(table_.info()), half_width_(analytic_half_width_of(stack)) {}

void TableKernel::evaluate(std::size_t n, const double* u, double* h) const {
  // Chunks keep the C interface's int lengths small; no H1 (the library then evaluates H only).
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  for (std::size_t start = 0; start < n; start += kChunk) {
    const std::size_t count = std::min(kChunk, n - start);
    table_.eval(u + start, count, h + start, nullptr);
  }
}

namespace {
// A compact table's H differs from the full grid's by up to the tables' stated accuracy
// (~1e-14 max|H|, other FFT length, pole split and aliasing), and the coherent kernel bound is
// that accuracy carried through the solve. Where the bound is larger than this (ill-conditioned
// systems: soft incompressible films, rigid substrates, large a/t) the difference reached 4e-12
// relative; there the full grid is used, so that every result stays within ~1e-14 of the
// full-grid solve (measured: <= 1e-2 of the bound).
constexpr double kCompactKernelBound = 1e-12;
constexpr double kSolverTableRange[kSolverTableLevels - 1] = {80.0};
}  // namespace

int solver_table_level(double a_over_t) {
  for (int k = 0; k + 1 < kSolverTableLevels; ++k) {
    if (2.0 * a_over_t <= kSolverTableRange[k]) return k;
  }
  return kSolverTableLevels - 1;
}

std::unique_ptr<TableKernel> make_solver_table(const Stack& stack, int level) {
  for (int k = level; k + 1 < kSolverTableLevels; ++k) {
    try {
      return std::make_unique<TableKernel>(stack, kSolverTableRange[k]);
    } catch (const NumericalError&) {
      // too short for this stack's accuracy target: next level
    }
  }
  return std::make_unique<TableKernel>(stack);
}

const KernelSource* IndependentTables::get(int index) {
  std::call_once(once_, [this] {
    try {
      for (int k = 0; k < kIndependentTables; ++k) {
        tables_[static_cast<std::size_t>(k)] = std::make_unique<TableKernel>(stack_, k + 1);
      }
    } catch (const NumericalError&) {
      for (auto& table : tables_) table.reset();
    }
  });
  return tables_[static_cast<std::size_t>(index)].get();
}

AdaptiveSolve solve_on_solver_tables(const std::function<const KernelSource&(int level)>& table,
                                     double a_over_t, double tolerance,
                                     const IndependentKernel& independent) {
  const int level = solver_table_level(a_over_t);
  const bool full = level + 1 == kSolverTableLevels;
  // On a compact table without the independent tables: where those would be needed (coherent
  // bound > tol / 10) the attempt stops early and costs no two-table re-solves.
  const double keep_bound = std::min(0.1 * tolerance, kCompactKernelBound);
  AdaptiveSolve result = solve_adaptive(table(level), a_over_t, tolerance,
                                        full ? independent : IndependentKernel{},
                                        full ? std::numeric_limits<double>::infinity() : keep_bound);
  const bool cheap = result.converged && result.kernel_error_kind == KernelErrorKind::kCoherentBound &&
                     result.kernel_bound <= keep_bound;
  if (!full && !cheap) {
    result = solve_adaptive(table(kSolverTableLevels - 1), a_over_t, tolerance, independent);
    result.table_level = kSolverTableLevels - 1;
  } else {
    result.table_level = level;
  }
  return result;
}

}  // namespace coatcontact::detail
