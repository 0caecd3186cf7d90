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
#include <string>
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
  // Verified segments (prepare_range): each segment is also solved directly at both its ends,
  // where the interpolation error of Chebyshev nodes of the first kind peaks (|T_(n+1)| = 1),
  // and halved while max(tail / 10, the larger relative difference there) exceeds
  // tail_tolerance + tail_noise_factor x the nodes' estimates (max_halvings reached: the
  // segment is kept, its estimate says what it is worth).
  bool verify = false;
  // Initial width of a segment of prepare_range, in decades of a/t.
  double decades_per_segment = 1.0;
  // Initial segment ends of prepare_range, in log10(a/t), ascending; outside them (and when
  // empty) the grid of decades_per_segment. Lets segments be narrow where the variables turn
  // (a/t ~ 1) and wide where they approach their limits, so that few are halved.
  std::vector<double> breaks_decades;
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
  // Builds segments covering exactly [a_over_t_min, a_over_t_max] (widths of
  // options().decades_per_segment decades, halved as needed), for a table that serves only
  // that range: at() outside it is an InputError. Only on a table with no segment yet.
  void prepare_range(double a_over_t_min, double a_over_t_max) const;
  // Estimated largest relative error of the six interpolated values at a/t (of the segment
  // holding it): its interpolation error (the tail; verified: max(tail / 10, differences at the
  // ends)) + the largest error estimate of
  // the source at its nodes and ends.
  double error_estimate_at(double a_over_t) const;
  // Its first part alone: the estimated difference of the interpolant from the source's values.
  double interpolation_error_at(double a_over_t) const;
  // Estimated error of the interpolated log-derivatives d ln X / d ln(a/t) at a/t (absolute),
  // from that difference taken as e T_(n+1) over the segment (THEORY.md section 5, "Pull-off
  // sweeps"); the source's own error is taken smooth in a/t and not counted here.
  double derivative_error_at(double a_over_t) const;
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
  // A table of prepare_range serves only [range_min(), range_max()] of a/t.
  bool ranged() const { return ranged_; }
  double range_min() const;
  double range_max() const;

 private:
  struct Segment;
  struct Pending;
  void build_decades(const std::vector<long>& decades) const;
  void build_segments(std::vector<Pending> pending) const;
  const Segment& segment_for(double u) const;

  const ReducedSource& source_;
  TableOptions options_;
  mutable std::map<double, std::unique_ptr<Segment>> segments_;  // keyed by left end in u
  mutable std::map<long, bool> built_decades_;
  mutable std::size_t evaluations_ = 0;
  mutable double interpolation_error_ = 0.0;
  mutable double source_error_ = 0.0;
  mutable bool ranged_ = false;  // prepare_range: only [range_lo_, range_hi_] in u is served
  mutable double range_lo_ = 0.0, range_hi_ = 0.0;
};

// ---- many radii through the verified interpolant --------------------------------------

// The table of interpolated_sweep at `tolerance`: order 14, two decades a segment, verified
// ends, halved while max(tail, end difference) > 0.4 tolerance + the nodes' own estimate.
TableOptions sweep_table_options(double tolerance);

// The table of the pull-off sweep (THEORY.md section 5, "Pull-off sweeps"): its nodes solved at
// kPulloffNodeShare x tol, the verified interpolation error held below (1 - kPulloffNodeShare)
// x tol, so that every value's estimate (interpolation + node estimate) is <= tol.
inline constexpr double kPulloffNodeShare = 0.7;
TableOptions pulloff_sweep_table_options(double tolerance);

// The table of interpolated_sweep: sweep_table_options with graded initial segments (two
// decades below a/t = 0.1, half decades to 10, a decade to 100, then two decades), the layout
// that the reduced variables of soft and stiff films, rigid bases and stacks mostly verify
// without halving (docs/speed.md, "200 radii (radii37)").
TableOptions radii_sweep_table_options(double tolerance);

struct InterpolatedSweep {
  // One row per a/t, as ReducedSolver::sweep's; error_estimate is the table's
  // (error_estimate_at) on interpolated rows (unknowns 0), the solver's on solved ones.
  std::vector<ReducedVariables> rows;
  // Per row: the table's estimate of its difference from a direct solve (interpolation_error_at;
  // 0 on solved rows). error_estimate adds the nodes' own error estimates to it.
  std::vector<double> interpolation_error;
  std::size_t interpolated = 0;    // rows read from the table
  std::size_t source_solves = 0;   // direct solves of the table (nodes and verified ends)
  std::size_t segments = 0;
  std::string direct_reason;       // why every row was solved directly (empty if the table served)
};

// Reduced variables at many a/t from one verified ReducedTable over [min, max] (docs/solver.md,
// Sweeps): a row whose table estimate exceeds `tolerance` is solved directly, and every row is
// when the radii are too few for the table to pay (fewer than 1.5 times its expected solves)
// or a node cannot be solved (the reason is kept). Same InputErrors as ReducedSolver::sweep;
// `status` as its tolerant overload (null: NumericalError at the first row not delivered).
InterpolatedSweep interpolated_sweep(const ReducedSolver& solver, const std::vector<double>& a_over_t,
                                     double tolerance, std::vector<PointStatus>* status = nullptr);

}  // namespace coatcontact
