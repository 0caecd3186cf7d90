// coatcontact::ReducedSolver (cpp/solver/include/coatcontact/reduced.hpp): input checks, the kernel
// table of the material pair, and the refinement loop of reduced_core.
#include "coatcontact/reduced.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <mutex>
#include <sstream>
#include <utility>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/solve_cache.hpp"
#include "parallel.hpp"
#include "reduced_core.hpp"
#include "solve_cache.hpp"
#include "table_kernel.hpp"

namespace coatcontact {

struct ReducedSolver::Impl {
  explicit Impl(const Stack& s) : stack(s) {}
  Stack stack;
  std::array<std::once_flag, detail::kSolverTableLevels> level_once;
  std::array<std::unique_ptr<detail::TableKernel>, detail::kSolverTableLevels> level_table;

  // The table for radii of `level` (detail::solver_table_level), built on first use.
  const detail::TableKernel& kernel(int level) {
    const auto k = static_cast<std::size_t>(level);
    std::call_once(level_once[k], [this, level, k] { level_table[k] = detail::make_solver_table(stack, level); });
    return *level_table[k];
  }

  // The same H on independent grids, for the a-posteriori kernel-error estimate.
  detail::IndependentTables independent{stack};

  // Radii solved before, by this process or others (coatcontact/solve_cache.hpp), or null.
  // Declared last: destroyed (and written) first.
  std::unique_ptr<detail::SolveCache> cache;
  const ReducedVariables* cached(double a_over_t, double tolerance, ReducedVariables& out) const {
    if (!cache) return nullptr;
    const auto hit = cache->find(a_over_t, tolerance);
    if (!hit) return nullptr;
    out = *hit;
    return &out;
  }
  // Before radii the cache lacks: the table that the constructor builds without a cache, so
  // that a stack whose table cannot be built fails the same way, outside any per-radius status.
  // True when the cache holds every radius (the sweep then starts no threads).
  bool prepare_to_solve(const std::vector<double>& a_over_t, double tolerance) {
    if (!cache) return false;
    ReducedVariables ignored;
    for (double a : a_over_t) {
      if (cached(a, tolerance, ignored) == nullptr) {
        kernel(0);
        return false;
      }
    }
    return true;
  }
};

namespace {

using detail::full_precision;

void check_arguments(double a_over_t, double tolerance) {
  if (!std::isfinite(a_over_t) || !(a_over_t > 0.0) || !(a_over_t <= kMaximumAOverT)) {
    throw InputError("a/t " + full_precision(a_over_t) + " is not allowed; it must be > 0 and <= " +
                     full_precision(kMaximumAOverT));
  }
  check_tolerance(tolerance);
}

}  // namespace

void check_tolerance(double tolerance) {
  if (!std::isfinite(tolerance) || !(tolerance >= kMinimumTolerance) ||
      !(tolerance <= kMaximumTolerance)) {
    throw InputError("tolerance " + full_precision(tolerance) + " is outside the allowed range [" +
                     full_precision(kMinimumTolerance) + ", " + full_precision(kMaximumTolerance) + "]");
  }
}

ReducedSolver::ReducedSolver(const Stack& stack) : impl_(std::make_unique<Impl>(stack)) {
  const std::string cache_directory = solve_cache_directory();
  if (cache_directory.empty()) {
    impl_->kernel(0);  // constants the kernel library rejects fail here, at construction
  } else {
    // The table waits for the first radius the cache lacks (prepare_to_solve); its cheap
    // input check stays here.
    kernel_detail::check_stack_table_supported(impl_->stack);
    impl_->cache = std::make_unique<detail::SolveCache>(cache_directory, impl_->stack);
  }
}

ReducedSolver::~ReducedSolver() = default;
ReducedSolver::ReducedSolver(ReducedSolver&&) noexcept = default;
ReducedSolver& ReducedSolver::operator=(ReducedSolver&&) noexcept = default;

const Stack& ReducedSolver::stack() const { return impl_->stack; }

ReducedVariables ReducedSolver::solve(double a_over_t, double tolerance) const {
  check_arguments(a_over_t, tolerance);
  Impl* impl = impl_.get();
  ReducedVariables hit;
  if (impl->cached(a_over_t, tolerance, hit) != nullptr) return hit;
  impl->prepare_to_solve({a_over_t}, tolerance);
  const detail::AdaptiveSolve solution = detail::solve_on_solver_tables(
      [impl](int level) -> const detail::KernelSource& { return impl->kernel(level); }, a_over_t,
      tolerance, impl->independent.source());
  if (!solution.converged) {
    std::ostringstream message;
    message.precision(3);
    message << "reduced variables at a/t = " << full_precision(a_over_t) << ": the error estimate "
            << solution.error_estimate << " exceeds the tolerance " << tolerance
            << " (discretization " << solution.discretization_error << " at "
            << solution.unknowns << " unknowns, kernel-table accuracy ";
    switch (solution.kernel_error_kind) {
      case detail::KernelErrorKind::kCoherentBound:
        message << solution.kernel_error << " (bound)";
        break;
      case detail::KernelErrorKind::kTwoTable:
        message << solution.kernel_error << " (two-table estimate)";
        break;
      case detail::KernelErrorKind::kNotEvaluated:
        message << "not evaluated (bound " << solution.kernel_bound << ")";
        break;
    }
    message << ", rounding " << solution.rounding_error << "; ";
    if (solution.kernel_error + solution.rounding_error > tolerance) {
      message << "the last two do not shrink with refinement: use a larger tolerance)";
    } else {
      message << "no convergence within " << detail::kMaxNodesPerPanel << " nodes per panel)";
    }
    throw NumericalError(message.str());
  }
  ReducedVariables v;
  v.a_over_t = a_over_t;
  v.pi_s = solution.values[detail::kPiS];
  v.delta_s = solution.values[detail::kDeltaS];
  v.pi_c = solution.values[detail::kPiC];
  v.delta_c = solution.values[detail::kDeltaC];
  v.e_eq = solution.values[detail::kEEq];
  v.gamma1 = solution.values[detail::kGamma1];
  v.error_estimate = solution.error_estimate;
  v.unknowns = solution.unknowns;
  if (impl->cache) impl->cache->add(tolerance, v);
  return v;
}

namespace {

// The order in which a sweep starts its radii (the loop takes them in this order, two or more
// at a time): the largest radius first, so that the full kernel table it needs (~17 ms, built
// once) is built while the other threads solve the radii of the compact table; then those,
// then the other radii of the full table, each group from the largest a/t down (a solve's cost
// grows with a/t, ~0.01 ms at a/t 1 to ~3 ms at 1e4: the costly ones first leave no long solve
// alone at the end).
std::vector<std::size_t> solving_order(const std::vector<double>& a_over_t) {
  std::vector<std::size_t> order(a_over_t.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const int full = detail::kSolverTableLevels - 1;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    const bool i_full = detail::solver_table_level(a_over_t[i]) == full;
    const bool j_full = detail::solver_table_level(a_over_t[j]) == full;
    if (i_full != j_full) return j_full;  // compact-table radii before full-table ones
    return a_over_t[i] > a_over_t[j];
  });
  if (!order.empty() && detail::solver_table_level(a_over_t[order.back()]) == full) {
    // some radius needs the full table: its largest (the first full-table one) goes first
    const auto first_full = std::find_if(order.begin(), order.end(), [&](std::size_t i) {
      return detail::solver_table_level(a_over_t[i]) == full;
    });
    std::rotate(order.begin(), first_full, first_full + 1);
  }
  return order;
}

}  // namespace

std::vector<ReducedVariables> ReducedSolver::sweep(const std::vector<double>& a_over_t,
                                                   double tolerance) const {
  // Check everything first, so that bad input fails before any work.
  for (double a : a_over_t) check_arguments(a, tolerance);
  const bool all_cached = impl_->prepare_to_solve(a_over_t, tolerance);
  std::vector<ReducedVariables> results(a_over_t.size());
  if (all_cached) {
    for (std::size_t i = 0; i < a_over_t.size(); ++i) results[i] = solve(a_over_t[i], tolerance);
    return results;
  }
  // Each radius is independent and deterministic: the parallel result equals the serial one,
  // and the error thrown is the first radius's in the caller's order, as a serial loop's.
  const std::vector<std::size_t> order = solving_order(a_over_t);
  std::vector<std::exception_ptr> errors(a_over_t.size());
  detail::parallel_for(order.size(), [&](std::size_t k) {
    const std::size_t i = order[k];
    try {
      results[i] = solve(a_over_t[i], tolerance);
    } catch (const NumericalError&) {
      errors[i] = std::current_exception();
    }
  });
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return results;
}

std::vector<ReducedVariables> ReducedSolver::sweep(const std::vector<double>& a_over_t, double tolerance,
                                                   std::vector<PointStatus>& status) const {
  for (double a : a_over_t) check_arguments(a, tolerance);
  if (impl_->prepare_to_solve(a_over_t, tolerance)) {
    status.assign(a_over_t.size(), PointStatus{});
    return sweep(a_over_t, tolerance);
  }
  const std::vector<std::size_t> order = solving_order(a_over_t);
  std::vector<PointStatus> ordered_status;
  const std::vector<ReducedVariables> ordered = detail::parallel_points<ReducedVariables>(
      order.size(), [&](std::size_t k) { return solve(a_over_t[order[k]], tolerance); },
      [&](std::size_t k) {
        ReducedVariables blank{};
        blank.a_over_t = a_over_t[order[k]];
        return blank;
      },
      ordered_status);
  std::vector<ReducedVariables> results(a_over_t.size());
  status.assign(a_over_t.size(), PointStatus{});
  for (std::size_t k = 0; k < order.size(); ++k) {
    results[order[k]] = ordered[k];
    status[order[k]] = ordered_status[k];
  }
  return results;
}

}  // namespace coatcontact
