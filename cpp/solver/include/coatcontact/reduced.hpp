// Reduced variables of the coated-substrate contact (THEORY.md sections 4-5): for one
// contact radius over coating thickness a/t, solve the integral equation [EqEquilibriumCS]
// for the flat punch, the sphere and the cone, and return
//   Pi_s, Delta_s (sphere), Pi_c, Delta_c (cone), E_eq (flat-punch stiffness), Gamma1 (edge value).
#pragma once
#include <memory>
#include <vector>

#include "coatcontact/point_status.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

// The six reduced variables at one a/t: what a solve returns and the interpolant
// (ReducedPoint, reduced_table.hpp) hands on, so one is passed as the other without a copy
// field by field.
struct ReducedValues {
  double a_over_t = 0.0;
  double pi_s = 0.0;
  double delta_s = 0.0;
  double pi_c = 0.0;
  double delta_c = 0.0;
  double e_eq = 0.0;
  double gamma1 = 0.0;
};

struct ReducedVariables : ReducedValues {
  double error_estimate = 0.0;  // estimated max relative error over the six values
  int unknowns = 0;             // size of the final linear system
};

// Allowed range of the relative tolerance of solve() and sweep().
constexpr double kMinimumTolerance = 1e-13;
constexpr double kMaximumTolerance = 1e-1;
constexpr double kDefaultTolerance = 1e-8;
// Largest a/t accepted (the film is then far thinner than the contact; the kernel table's
// asymptotic range covers it).
constexpr double kMaximumAOverT = 1e8;

// InputError naming the tolerance and its allowed range unless it lies in
// [kMinimumTolerance, kMaximumTolerance] (the one check every layer uses).
void check_tolerance(double tolerance);

class ReducedSolver {
 public:
  // Builds the kernel table of the stack once (a few ms).
  explicit ReducedSolver(const Stack& stack);
  ~ReducedSolver();
  ReducedSolver(ReducedSolver&&) noexcept;
  ReducedSolver& operator=(ReducedSolver&&) noexcept;

  // One contact radius. Refines until error_estimate <= tolerance; throws NumericalError
  // if it cannot (never returns silently wrong numbers). InputError if a_over_t is not in
  // (0, kMaximumAOverT] or tolerance not in [kMinimumTolerance, kMaximumTolerance].
  ReducedVariables solve(double a_over_t, double tolerance = kDefaultTolerance) const;

  // Many contact radii (may run in parallel); same errors as solve().
  std::vector<ReducedVariables> sweep(const std::vector<double>& a_over_t,
                                      double tolerance = kDefaultTolerance) const;
  // The same radii, each one that can be solved: a radius whose tolerance cannot be met gets
  // status[i].delivered = false and the NumericalError's message (its row holds a_over_t and
  // zeros); the others equal solve()'s. InputError as solve() (before any work).
  std::vector<ReducedVariables> sweep(const std::vector<double>& a_over_t, double tolerance,
                                      std::vector<PointStatus>& status) const;

  const Stack& stack() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace coatcontact
