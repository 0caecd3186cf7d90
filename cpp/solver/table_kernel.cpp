// Adapter from the Fortran kernel table to the solver's KernelSource.
#include "table_kernel.hpp"

#include <algorithm>
#include <cmath>
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
// A compact table's H carries its own accuracy estimate (~1e-13; measured against the
// full grid: <= 0.11 of the two stated accuracies, test solver_compact_table_within_estimate),
// and the coherent kernel bound is that accuracy carried through the solve. A compact solve is
// kept by the rule the full grid's coherent bound follows (<= tolerance / 10): its results lie
// within their estimates of the full-grid solve (measured on soft incompressible films on
// stiff and rigid bases and stacks, a/t 1e-3..40), though not to the full grid's last digits
// (up to ~6e-13 relative at a/t = 40). A limit tied to those digits (1e-12) would send soft
// nu1 = 0.5 films to the full grid from a/t ~ 1.5 on (9-12 ms a table; THEORY.md section 15,
// the JKR search on a coating, builds four).
constexpr double kCoherentBoundShare = 0.1;
// A compact grid is refused where the far-field series still falls slowly at its end (ratio of
// its last two terms > 0.1, cc_kernel_tables.f90): a singularity of C - 1 near q = 0, as for
// nu1 = 0.5 films at E1*/E0* ~ 0.3 (ratio 0.12 at u = 80). The ratio falls like 1/u_max², so
// twice or four times the range (2-4x the compact grid's cost, 1/16-1/8 of the full grid's)
// is tried before the full grid.
constexpr double kCompactRangeGrowth = 4.0;
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
    for (double range = kSolverTableRange[k]; range <= kCompactRangeGrowth * kSolverTableRange[k]; range *= 2.0) {
      try {
        return std::make_unique<TableKernel>(stack, range);
      } catch (const NumericalError&) {
        // too short for this stack's accuracy target: a longer compact grid, then the next level
      }
    }
  }
  return std::make_unique<TableKernel>(stack);
}

ReachKernel::ReachKernel(const Stack& stack, double compact_range)
    : stack_(stack), compact_range_(compact_range), half_width_(analytic_half_width_of(stack)) {}

const TableKernel* ReachKernel::compact() const {
  std::call_once(compact_once_, [this] {
    try {
      compact_ = std::make_unique<TableKernel>(stack_, compact_range_);
    } catch (const NumericalError&) {
      // the compact grid misses its accuracy target for this stack: the full grid serves all
    }
  });
  return compact_.get();
}

const TableKernel& ReachKernel::full() const {
  std::call_once(full_once_, [this] { full_ = std::make_unique<TableKernel>(stack_); });
  return *full_;
}

void ReachKernel::evaluate(std::size_t n, const double* u, double* h) const {
  // A flag, not a running max |u| (whose latency chain cost ~2 % of an MD fit, the flag 0.7 %). A
  // NaN goes to the full grid, which reports it.
  bool within = true;
  for (std::size_t i = 0; i < n; ++i) within &= std::abs(u[i]) <= compact_range_;
  const TableKernel* table = within ? compact() : nullptr;  // its u_max >= compact_range
  if (table != nullptr) {
    table->evaluate(n, u, h);
  } else {
    full().evaluate(n, u, h);
  }
}

double ReachKernel::absolute_accuracy() const {
  const TableKernel* table = compact();
  const double accuracy = full().absolute_accuracy();
  return table != nullptr ? std::max(accuracy, table->absolute_accuracy()) : accuracy;
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
  const double keep_bound = kCoherentBoundShare * tolerance;
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
