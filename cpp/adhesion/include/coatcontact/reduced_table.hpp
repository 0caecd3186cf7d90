// The one interpolant of the reduced variables (THEORY.md section 5) that the adhesion
// models and the fit share, and the sources it is built from.
//
// The reduced variables Pi_s, Delta_s, Pi_c, Delta_c, E_eq, Gamma(1) come from a
// ReducedSource (the ReducedSolver through SolverSource, or any other provider such as exact
// homogeneous values in tests). They are solved once on Chebyshev nodes in ln(a/t) and
// interpolated (ReducedTable): the interpolant also gives the derivatives needed to locate
// the pull-off by a root of dP/da_bar, which the direct solver values cannot provide to 1e-8.
// Measurement behind the choice: see the comment at the top of cpp/adhesion/reduced_table.cpp.
//
// Thread safety: ReducedTable fills its cache lazily from const member functions; do not
// share one object between threads.
#pragma once
#include <cstddef>
#include <map>
#include <memory>
#include <vector>

#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

// ---- where the reduced variables come from ------------------------------------------

class ReducedSource {
 public:
  virtual ~ReducedSource() = default;
  // Reduced variables at each a/t (> 0). Throws NumericalError when it cannot deliver them.
  virtual std::vector<ReducedVariables> evaluate(const std::vector<double>& a_over_t) const = 0;
  virtual const Stack& stack() const = 0;
};

// The ReducedSolver at a fixed tolerance. Keeps a reference: the solver must outlive it.
class SolverSource final : public ReducedSource {
 public:
  explicit SolverSource(const ReducedSolver& solver, double tolerance = kDefaultTolerance);
  std::vector<ReducedVariables> evaluate(const std::vector<double>& a_over_t) const override;
  const Stack& stack() const override;
  double tolerance() const { return tolerance_; }

 private:
  const ReducedSolver& solver_;
  double tolerance_;
};

// ---- interpolation of the reduced variables -----------------------------------------

// Values and logarithmic derivatives d ln(X) / d ln(a/t) of the six reduced variables.
struct ReducedPoint : ReducedValues {
  double dlog_pi_s = 0.0, dlog_delta_s = 0.0, dlog_pi_c = 0.0, dlog_delta_c = 0.0,
         dlog_e_eq = 0.0, dlog_gamma1 = 0.0;
};

// The values of solved reduced variables as a ReducedPoint (the log-derivatives are 0).
ReducedPoint reduced_point_of(const ReducedVariables& v);

struct TableOptions {
  // Chebyshev order per segment in u = ln(a/t) (order + 1 source evaluations per segment).
  std::size_t order = 24;
  // Segments are decades of a/t, halved while the tail of a series exceeds
  // tail_tolerance + tail_noise_factor * (largest error estimate of the source at the nodes).
  double tail_tolerance = 1e-10;
  double tail_noise_factor = 10.0;
  int max_halvings = 4;  // then NumericalError
};

// Piecewise Chebyshev interpolant (GSL gsl_cheb_*) of ln X versus ln(a/t), one series per
// variable per segment, built on demand from `source` (which must outlive the table).
class ReducedTable {
 public:
  explicit ReducedTable(const ReducedSource& source, TableOptions options = {});
  ~ReducedTable();
  ReducedTable(const ReducedTable&) = delete;
  ReducedTable& operator=(const ReducedTable&) = delete;

  // Builds every segment covering [a_over_t_min, a_over_t_max] with one batched source call.
  void prepare(double a_over_t_min, double a_over_t_max) const;
  // Which variables at() evaluates: all six, or only those of one indenter and the flat punch
  // (E_eq, Gamma(1)); the others are left 0. The kinetics asks for one indenter's at every step.
  enum class Variables { kAll, kSphere, kCone };
  // Interpolated values and log-derivatives (builds the segment if needed).
  ReducedPoint at(double a_over_t, Variables which = Variables::kAll) const;

  // Largest tail estimate of the built series (an estimate of the relative interpolation
  // error of the values) and the largest error estimate reported by the source.
  double interpolation_error_estimate() const;
  double source_error_estimate() const;
  std::size_t source_evaluations() const { return evaluations_; }
  std::size_t segments() const;
  const ReducedSource& source() const { return source_; }
  const TableOptions& options() const { return options_; }

 private:
  struct Segment;
  void build_decades(const std::vector<long>& decades) const;
  const Segment& segment_for(double u) const;

  const ReducedSource& source_;
  TableOptions options_;
  mutable std::map<double, std::unique_ptr<Segment>> segments_;  // keyed by left end in u
  mutable std::map<long, bool> built_decades_;
  mutable std::size_t evaluations_ = 0;
  mutable double interpolation_error_ = 0.0;
  mutable double source_error_ = 0.0;
};

}  // namespace coatcontact
