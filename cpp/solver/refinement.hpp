// The refinement loop of the solver (docs/solver.md, Refinement): any load cases (the flat
// punch and a list of shapes, load_case.hpp) on one kernel, solved at increasing p until the
// difference between two successive levels plus the kernel-table and rounding terms is
// <= tolerance. The reduced variables (sphere and cone, reduced_core.hpp) and every indenter
// shape (coatcontact/shape_solver.hpp) are refined by it.
#pragma once
#include <functional>
#include <limits>
#include <vector>

#include "fixed_solve.hpp"
#include "kernel_source.hpp"
#include "load_case.hpp"

namespace coatcontact::detail {

// How the kernel-table term of an AdaptiveSolve was obtained.
enum class KernelErrorKind {
  kCoherentBound,    // FixedSolve::kernel_error (small enough: <= tolerance / 10)
  kTwoTable,         // kTwoTableSafety x the largest difference from solves with independent tables
  kNotEvaluated,     // the bound was too large and the discretization never converged
};

// Safety factor on the two-table difference (docs/solver.md): over 300 measured cases
// (rigid substrate nu1 = 0, 0.3, 0.5 and E1*/E0* = 1e-3, a/t in [3, 900], p = 16, 22, 28) the
// difference from a further independent table (variant 3) was at most 5.2 times (99%: 5.0)
// the larger of the differences from variants 1 and 2; with one table alone it reached 16.
constexpr double kTwoTableSafety = 10.0;
// Independent tables used for the estimate (grid variants 1 and 2).
constexpr int kIndependentTables = 2;

// The result of the refinement loop: the finer level of the last pair.
struct AdaptiveSolve {
  std::vector<double> values;          // in the order of FixedSolve::values
  double error_estimate = 0.0;
  double discretization_error = 0.0;  // the level difference alone
  double kernel_error = 0.0;          // the kernel term used (see kernel_error_kind)
  double kernel_bound = 0.0;          // the coherent bound at the last level (diagnostic)
  double rounding_error = 0.0;
  KernelErrorKind kernel_error_kind = KernelErrorKind::kCoherentBound;
  int unknowns = 0;
  int nodes_per_panel = 0;
  int table_level = 0;                // the kernel table used (solve_on_solver_tables)
  bool converged = false;
};

// Supplies table `index` (0 .. kIndependentTables - 1) of the same H on an independent grid
// (TableKernel grid variants 1 and 2), built on first use; nullptr when there is none (then
// the coherent bound is always used).
using IndependentKernel = std::function<const KernelSource*(int index)>;

// Largest p the refinement tries.
constexpr int kMaxNodesPerPanel = 48;
// Nodes per panel added from one level to the next.
constexpr int kRefinementStep = 2;

// The refinement schedule of every adaptive solve (docs/solver.md, Refinement). The error of
// the outputs falls by ~6.5 per node per panel; for most material pairs it is below
// 0.03 / 6.5^p at every a/t (measured: p = 8 gives <= 2e-9), so the first level is where
// that model meets the tolerance (p = 8 at tol 1e-8).
int first_refinement_level(double tolerance);
// After two levels coarse < fine whose difference (the coarse level's error) exceeds the
// tolerance: the coarse level of the next pair, where the same rate predicts an error <=
// tolerance; `fine` (a step of one level) when that is no further or the difference fits. A hard case (a compliant
// film on a stiff base at large a/t, errors ~1e-2 at p = 8) then skips the levels between.
int next_coarse_level(int coarse, int fine, double difference, double tolerance);

// Whether a pair of levels may be accepted, from their rounding terms ε_machine cond_∞: not
// when the fine level is far worse conditioned than the coarse one (a near-singular discrete
// operator, whose error the pair's difference does not bound; docs/solver.md, Refinement).
bool conditioned_alike(double coarse_rounding, double fine_rounding);

// Where the loop gives up early.
struct RefinementRules {
  // Give up (converged = false) right after the first level when its coherent bound exceeds
  // this (a caller that would discard such a solve; solve_on_solver_tables).
  double bound_limit = std::numeric_limits<double>::infinity();
  // Stop when the kernel term cannot meet the tolerance: the coherent bound above it at both
  // levels of a pair, or a two-table term above it that no longer halves per level. false:
  // refine on to kMaxNodesPerPanel (ShapeSolver).
  bool stop_when_kernel_term_stalls = true;
};

// Never throws for lack of convergence (converged = false, estimate set); throws
// NumericalError only if every level or a two-table re-solve fails. The kernel term is the
// coherent bound when that is <= tolerance / 10; otherwise, once the discretization has
// converged, kTwoTableSafety times the max relative difference of the outputs from re-solves
// at the same discretization with `independent`'s tables (an a-posteriori estimate).
AdaptiveSolve refine(const KernelSource& kernel, double a_over_t, const std::vector<const Shape*>& shapes,
                     double tolerance, const IndependentKernel& independent = {},
                     const RefinementRules& rules = {});

}  // namespace coatcontact::detail
