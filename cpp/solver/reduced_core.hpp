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
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "kernel_source.hpp"
#include "shape_solve.hpp"

namespace coatcontact::detail {

// Order of the six outputs everywhere in the solver.
enum ReducedIndex { kPiS = 0, kDeltaS, kPiC, kDeltaC, kEEq, kGamma1, kReducedCount };
using ReducedValues = std::array<double, kReducedCount>;

// One solve at a fixed discretization: the six reduced variables (sphere and cone).
struct FixedSolve {
  ReducedValues values{};
  int unknowns = 0;
  int panels = 0;
  double inverse_norm = 0.0;  // estimate of ||A^{-1}||_inf (LAPACK dgecon)
  // Coherent worst-case bound on the relative output error caused by the kernel accuracy
  // (|δH| <= ε with one sign everywhere; cheap, but grows like ã E_eq: docs/solver.md).
  double kernel_error = 0.0;
  // Relative error from rounding in the assembly and LU solve: ε_machine cond_inf(A)
  // (calibrated: the measured error is <= 0.08 of it, docs/solver.md).
  double rounding_error = 0.0;
  double consistency = 0.0;     // |Γ1 direct - Γ1 by reciprocity| / Γ1 (a discretization check)
  std::size_t kernel_evaluations = 0;
};

// Throws NumericalError if the linear system is singular or the results are not finite.
FixedSolve solve_fixed(const KernelSource& kernel, double a_over_t, const Discretization& disc);

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

// The refinement loop: solves at increasing p until the difference between two successive
// levels plus the kernel and rounding terms is <= tolerance; returns the finer level.
struct AdaptiveSolve {
  ReducedValues values{};
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

// Never throws for lack of convergence (converged = false, estimate set); throws
// NumericalError only if a linear system fails. The kernel term is the coherent bound when
// that is <= tolerance / 10; otherwise, once the discretization has converged, kTwoTableSafety
// times the max relative difference of the six outputs from re-solves at the same
// discretization with `independent`'s tables (an a-posteriori estimate).
// bound_limit: give up (converged = false) right after the first level when its coherent
// bound exceeds this (a caller that would discard such a solve; solve_on_solver_tables).
AdaptiveSolve solve_adaptive(const KernelSource& kernel, double a_over_t, double tolerance,
                             const IndependentKernel& independent = {},
                             double bound_limit = std::numeric_limits<double>::infinity());

}  // namespace coatcontact::detail
