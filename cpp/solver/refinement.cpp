// The refinement loop (refinement.hpp; docs/solver.md, Refinement).
#include "refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>

#include "coatcontact/errors.hpp"

namespace coatcontact::detail {

namespace {

double max_relative_difference(const std::vector<double>& coarse, const std::vector<double>& fine) {
  double worst = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    const double scale = std::max(std::abs(fine[i]), 1e-300);
    worst = std::max(worst, std::abs(fine[i] - coarse[i]) / scale);
  }
  return worst;
}

// Convergence rate of the level differences per node per panel (docs/solver.md).
constexpr double kRatePerNode = 6.5;
// The error of the benign material pairs extrapolated to p = 0 (all a/t).
constexpr double kStartErrorScale = 0.03;

// Largest ratio of the condition numbers of the fine and the coarse level of an accepted pair.
// Between resolved levels it stays within 1.3 (measured over p = 4..16 for E1*/E0* = 1, 0.1, 10
// and rigid bases with nu1 <= 0.35 up to a/t = 900); a near-singular level stands out by 16 to
// 2500 (PDMS on glass and on a rigid base, a/t 262.9 and 472.2). At a/t = 472.24 on a rigid base
// (nu1 0.49, tol 1e-4) p = 12 had 67 times the condition of p = 10 and an error of 1.9e-6
// against the pair's difference of 1.6e-6.
constexpr double kConditionJump = 10.0;

// One level of the refinement, or nothing when the level is unresolved: its discrete operator
// is singular or so nearly singular that the flat punch's edge value comes out non-positive
// or non-finite. The continuous I + K is positive definite, but its smallest eigenvalue is
// about min C(q) (E1*/E0* for a compliant film on a stiff base, ~1e-5), and where the level's
// discretization error is larger than that, a discrete eigenvalue can come near zero at an
// isolated (ã, p) (docs/solver.md, Refinement). The next level is then tried.
struct LevelSolver {
  const KernelSource& kernel;
  double a;
  const std::vector<const Shape*>& shapes;
  Discretization disc;
  std::exception_ptr last_failure;

  std::optional<FixedSolve> operator()(int p) {
    disc.nodes_per_panel = p;
    try {
      return solve_shapes(kernel, a, disc, shapes);
    } catch (const NumericalError&) {
      last_failure = std::current_exception();
      return std::nullopt;
    }
  }
};

// The kernel term of a pair whose fine level is `current` (refine): the cheap coherent bound
// when it is small; else, once the discretization and rounding terms fit, the effect of the
// table's errors measured a posteriori: the same discretization re-assembled and re-solved
// with tables on independent grids.
void set_kernel_term(AdaptiveSolve& result, const FixedSolve& current, const LevelSolver& level,
                     double tolerance, const IndependentKernel& independent) {
  std::array<const KernelSource*, kIndependentTables> others{};
  if (current.kernel_error > 0.1 * tolerance && independent) {
    for (int k = 0; k < kIndependentTables; ++k) others[static_cast<std::size_t>(k)] = independent(k);
  }
  if (others[0] == nullptr || others[1] == nullptr) {
    result.kernel_error_kind = KernelErrorKind::kCoherentBound;
    result.kernel_error = current.kernel_error;
  } else if (result.discretization_error + result.rounding_error <= tolerance) {
    double difference = 0.0;
    for (const KernelSource* other : others) {
      const FixedSolve check = solve_shapes(*other, level.a, level.disc, level.shapes);
      difference = std::max(difference, max_relative_difference(check.values, current.values));
    }
    result.kernel_error_kind = KernelErrorKind::kTwoTable;
    result.kernel_error = kTwoTableSafety * difference;
  } else {
    result.kernel_error_kind = KernelErrorKind::kNotEvaluated;
    result.kernel_error = 0.0;
  }
}

}  // namespace

int first_refinement_level(double tolerance) {
  const double p = std::ceil(std::log(kStartErrorScale / tolerance) / std::log(kRatePerNode));
  return std::clamp(static_cast<int>(p), 4, kMaxNodesPerPanel - kRefinementStep);
}

int next_coarse_level(int coarse, int fine, double difference, double tolerance) {
  if (difference <= tolerance || fine >= kMaxNodesPerPanel - kRefinementStep) return fine;
  // Whole steps, rounded down: the levels stay those of the plain schedule, and a jump never
  // passes the level the plain schedule would end on. The hard cases converge faster than the
  // rate (up to ~9 per node), and every level beyond the needed one costs an extra solve, a
  // larger rounding term and a two-table re-solve that may again miss the tolerance.
  const double steps =
      std::floor(std::log(difference / tolerance) / std::log(kRatePerNode) / kRefinementStep);
  const int predicted = coarse + kRefinementStep * static_cast<int>(std::min(steps, double(kMaxNodesPerPanel)));
  return std::clamp(predicted, fine, kMaxNodesPerPanel - kRefinementStep);
}

bool conditioned_alike(double coarse_rounding, double fine_rounding) {
  return fine_rounding <= kConditionJump * coarse_rounding;
}

AdaptiveSolve refine(const KernelSource& kernel, double a, const std::vector<const Shape*>& shapes,
                     double tolerance, const IndependentKernel& independent, const RefinementRules& rules) {
  Discretization base;
  base.quadrature_accuracy = std::clamp(1e-4 * tolerance, 1e-14, 1e-11);
  LevelSolver solve_level{kernel, a, shapes, base, nullptr};
  int coarse_p = first_refinement_level(tolerance);
  std::optional<FixedSolve> previous = solve_level(coarse_p);
  AdaptiveSolve result;
  if (previous && previous->kernel_error > rules.bound_limit) {  // the caller would not keep this solve
    result.kernel_bound = previous->kernel_error;
    result.kernel_error = previous->kernel_error;
    result.rounding_error = previous->rounding_error;
    result.unknowns = previous->unknowns;
    result.nodes_per_panel = coarse_p;
    result.error_estimate = std::numeric_limits<double>::infinity();
    return result;
  }
  bool any_pair = false;
  double previous_two_table = std::numeric_limits<double>::infinity();
  for (int p = coarse_p + kRefinementStep; p <= kMaxNodesPerPanel;) {
    if (!previous) {  // an unresolved coarse level: the next level starts the pair
      previous = solve_level(p);
      coarse_p = p;
      p += kRefinementStep;
      continue;
    }
    std::optional<FixedSolve> solved = solve_level(p);
    if (!solved) {  // an unresolved fine level: a fresh pair above it
      previous.reset();
      coarse_p = p;
      p += kRefinementStep;
      continue;
    }
    const FixedSolve& current = *solved;
    any_pair = true;
    result.values = current.values;
    result.discretization_error = max_relative_difference(previous->values, current.values);
    result.discretization_error = std::max(result.discretization_error, current.consistency);
    result.kernel_bound = current.kernel_error;
    result.rounding_error = current.rounding_error;
    result.unknowns = current.unknowns;
    result.nodes_per_panel = p;
    set_kernel_term(result, current, solve_level, tolerance, independent);
    result.error_estimate =
        result.discretization_error + result.kernel_error + result.rounding_error;
    // A fine level far worse conditioned than its coarse one is near a spurious singularity
    // (LevelSolver): its error is not bounded by the pair's difference, so the pair is not
    // accepted and the fine level becomes the coarse one of the next pair.
    if (result.error_estimate <= tolerance && conditioned_alike(previous->rounding_error, current.rounding_error) &&
        result.kernel_error_kind != KernelErrorKind::kNotEvaluated) {
      result.converged = true;
      return result;
    }
    // The coherent bound does not shrink with p: stop when it is too large at both levels
    // of the pair. The rounding term does shrink, often long after the values have
    // converged, so it never stops the refinement: the discrete operator's condition number
    // is the operator's only at well resolved levels. A near-singular level stands alone
    // (LevelSolver; 1e4 times its neighbours' condition, E1*/E0* = 1.8e-5, ã = 262.87,
    // p = 10); for an incompressible film on silicon at ã = 965.4, ε cond_∞ is 1e-8 to
    // 1.3e-8 from p = 14 to 20, where the values agree to 1e-9, then falls to 1.3e-9 at
    // p = 24 and 3e-11 at p = 32 (docs/solver.md, Refinement).
    // The two-table difference also carries the quadrature's sampling of the
    // table's grid-scale errors, which falls with p (measured: 1e-8 at p = 20, 8e-10 at 24,
    // incompressible film on a rigid substrate, a/t = 300): refine while it halves per level.
    if (rules.stop_when_kernel_term_stalls) {
      const double bound_floor = std::min(previous->kernel_error, current.kernel_error);
      if (result.kernel_error_kind == KernelErrorKind::kCoherentBound && bound_floor > tolerance) {
        return result;
      }
      if (result.kernel_error_kind == KernelErrorKind::kTwoTable && result.kernel_error > tolerance) {
        if (!(result.kernel_error < 0.5 * previous_two_table)) return result;
        previous_two_table = result.kernel_error;
      }
    }
    const int next = next_coarse_level(coarse_p, p, result.discretization_error, tolerance);
    if (next > p) {  // a fresh pair further on
      previous = solve_level(next);
    } else {
      previous = current;
    }
    coarse_p = next;
    p = next + kRefinementStep;
  }
  // Every level unresolved: the reason of the last one (NumericalError).
  if (!any_pair && solve_level.last_failure) std::rethrow_exception(solve_level.last_failure);
  return result;
}

}  // namespace coatcontact::detail
