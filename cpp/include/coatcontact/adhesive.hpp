// Adhesive (JKR-type) contact of a rigid sphere on a coated substrate: the four-step
// procedure of THEORY.md section 5 [EqPenetrationCS, EqForceCS, selfconsistenceInhom] in the
// Maugis normalization [EqSolNormF, EqSolNormD], the pull-off under load and displacement
// control, and the same in physical units.
//
// Design: the reduced variables Pi_s, Delta_s, Pi_c, Delta_c, E_eq, Gamma(1) come from a
// ReducedSource (the ReducedSolver through SolverSource, or any other provider such as exact
// homogeneous values in tests). They are solved once on Chebyshev nodes in ln(a/t) and
// interpolated (ReducedTable): the interpolant also gives the derivatives needed to locate
// the pull-off by a root of dP/da_bar, which the direct solver values cannot provide to 1e-8.
// Measurement behind the choice: see the comment at the top of cpp/adhesive/reduced_table.cpp.
//
// Thread safety: ReducedTable and AdhesiveModel fill their interpolation cache lazily from
// const member functions; do not share one object between threads.
#pragma once
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "coatcontact/materials.hpp"
#include "coatcontact/reduced.hpp"

namespace coatcontact {

// Default solver tolerance for the interpolation nodes: the solver's own default. The pull-off
// location inherits up to ~20-40x the relative error of the node values if that error were
// random from node to node (measured with synthetic noise, see reduced_table.cpp); pass a
// tighter tolerance where the solver can meet it.
inline constexpr double kDefaultAdhesiveTolerance = kDefaultTolerance;

// ---- where the reduced variables come from ------------------------------------------

class ReducedSource {
 public:
  virtual ~ReducedSource() = default;
  // Reduced variables at each a/t (> 0). Throws NumericalError when it cannot deliver them.
  virtual std::vector<ReducedVariables> evaluate(const std::vector<double>& a_over_t) const = 0;
  virtual const Material& film() const = 0;
  virtual const Substrate& substrate() const = 0;
};

// The ReducedSolver at a fixed tolerance. Keeps a reference: the solver must outlive it.
class SolverSource final : public ReducedSource {
 public:
  explicit SolverSource(const ReducedSolver& solver, double tolerance = 1e-8);
  std::vector<ReducedVariables> evaluate(const std::vector<double>& a_over_t) const override;
  const Material& film() const override;
  const Substrate& substrate() const override;
  double tolerance() const { return tolerance_; }

 private:
  const ReducedSolver& solver_;
  double tolerance_;
};

// ---- interpolation of the reduced variables -----------------------------------------

// Values and logarithmic derivatives d ln(X) / d ln(a/t) of the six reduced variables.
struct ReducedPoint {
  double a_over_t = 0.0;
  double pi_s = 0.0, delta_s = 0.0, pi_c = 0.0, delta_c = 0.0, e_eq = 0.0, gamma1 = 0.0;
  double dlog_pi_s = 0.0, dlog_delta_s = 0.0, dlog_pi_c = 0.0, dlog_delta_c = 0.0,
         dlog_e_eq = 0.0, dlog_gamma1 = 0.0;
};

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
  // Interpolated values and log-derivatives (builds the segment if needed).
  ReducedPoint at(double a_over_t) const;

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

// ---- the normalized adhesive sphere -------------------------------------------------

// One point of the normalized curve: a_bar = eta a/t, P = F/(pi w R), D = delta/(pi^2 w^2 R/E1*^2)^(1/3).
struct CurvePoint {
  double eta = 0.0;
  double a_bar = 0.0;
  double a_over_t = 0.0;
  double load = 0.0;         // P
  double penetration = 0.0;  // D
  double dload = 0.0;         // dP/da_bar
  double dpenetration = 0.0;  // dD/da_bar
};

// Stationary points are counted on a log grid (PulloffOptions::scan_points_per_decade): two
// minima closer than one grid cell would be counted as one.
struct PulloffPoint {
  double a_bar = 0.0;
  double load = 0.0;         // P
  double penetration = 0.0;  // D
  bool interior = true;        // a stationary point inside the scanned range (else an end)
  bool single_minimum = true;  // exactly one local minimum in the scanned range
  int local_minima = 1;
  // |a_bar from gsl_min_fminimizer_brent - a_bar from the root of the derivative| / a_bar:
  // shows the ~sqrt(eps) limit of minimising values (diagnostic only; -1 if the minimiser
  // could not be bracketed on the grid, e.g. a minimum in the first or last grid cell).
  double minimiser_discrepancy = 0.0;
};

struct Pulloff {
  double eta = 0.0;
  PulloffPoint load_control;          // minimum of P over a_bar
  PulloffPoint displacement_control;  // minimum of D over a_bar (P, D there)
  double a_bar_scan_min = 0.0, a_bar_scan_max = 0.0;
  std::vector<std::string> warnings;  // empty when both minima are single and interior
};

struct PulloffOptions {
  // Scanned range of a_bar; <= 0 selects the default
  //   [1e-3 min(1, r), 10 max(1, r)],  r = (E1*/E0*)^(1/3)  (r = 1 for a rigid substrate)
  // which holds both JKR limits (pull-off at a_bar ~ (9/8)^(1/3) and (9/8)^(1/3) r).
  double a_bar_min = 0.0;
  double a_bar_max = 0.0;
  int scan_points_per_decade = 32;  // grid on which the minima are counted and bracketed
  double location_tolerance = 1e-12;  // relative, on the root of the derivative
};

class AdhesiveModel {
 public:
  // Reduced variables from the solver at `tolerance` (the solver must outlive the model).
  explicit AdhesiveModel(const ReducedSolver& solver, double tolerance = kDefaultAdhesiveTolerance,
                         TableOptions table = {}, PulloffOptions pulloff = {});
  // Reduced variables from any source (shared ownership).
  explicit AdhesiveModel(std::shared_ptr<const ReducedSource> source, TableOptions table = {},
                         PulloffOptions pulloff = {});
  ~AdhesiveModel();
  AdhesiveModel(const AdhesiveModel&) = delete;
  AdhesiveModel& operator=(const AdhesiveModel&) = delete;

  // P, D and their derivatives at a_bar for film thickness eta (both > 0, finite).
  CurvePoint point(double eta, double a_bar) const;
  std::vector<CurvePoint> curve(double eta, const std::vector<double>& a_bar) const;
  // Pull-off under load and displacement control; NumericalError if it cannot be located.
  Pulloff pulloff(double eta) const;

  const ReducedTable& table() const { return *table_; }
  const Material& film() const { return source_->film(); }
  const Substrate& substrate() const { return source_->substrate(); }
  const PulloffOptions& pulloff_options() const { return pulloff_options_; }

 private:
  std::shared_ptr<const ReducedSource> source_;
  std::unique_ptr<ReducedTable> table_;
  PulloffOptions pulloff_options_;
};

// ---- physical units -----------------------------------------------------------------

// Rigid sphere of radius R on a film of thickness t, work of adhesion w (SI units, all > 0).
// Keeps a reference to `model`, which must outlive it.
// Maugis scales: length l = (pi w R^2/E1*)^(1/3), penetration l^2/R, force pi w R; eta = t/l.
class SphereContact {
 public:
  SphereContact(const AdhesiveModel& model, double radius, double thickness, double work_of_adhesion);

  double length_scale() const { return length_scale_; }
  double penetration_scale() const { return length_scale_ * length_scale_ / radius_; }
  double force_scale() const;
  double eta() const { return thickness_ / length_scale_; }

  double force(double contact_radius) const;        // F [N], compressive positive
  double penetration(double contact_radius) const;  // delta [m]
  double pulloff_force_load() const;   // [N] (negative: tensile)
  double pulloff_force_disp() const;   // [N]
  const Pulloff& pulloff() const;      // normalized details (computed once)

 private:
  const AdhesiveModel& model_;
  double radius_, thickness_, work_;
  double length_scale_;
  mutable std::unique_ptr<Pulloff> pulloff_;
};

}  // namespace coatcontact
