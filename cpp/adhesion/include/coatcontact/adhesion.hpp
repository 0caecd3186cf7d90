// Adhesive contact of a sphere on a coated substrate in the Maugis normalization
// [EqSolNormF, EqSolNormD] (THEORY.md section 5): an adhesion law turns the reduced variables
// at one contact radius into the normalized load P and penetration D; the model adds the
// curves and the pull-off under load and displacement control.
//
// Normalization with the stack's reference modulus E* (the top layer's):
//   a_bar = a / (pi w R^2/E*)^(1/3), eta = T / (pi w R^2/E*)^(1/3), P = F/(pi w R),
//   D = delta / (pi^2 w^2 R/E*^2)^(1/3).
//
// Thread safety: AdhesiveModel fills its interpolation cache lazily from const member
// functions; do not share one object between threads.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/point_status.hpp"
#include "coatcontact/reduced_table.hpp"

namespace coatcontact {

// Default solver tolerance for the interpolation nodes: the solver's own default. The pull-off
// location inherits up to ~20-40x the relative error of the node values if that error were
// random from node to node (measured with synthetic noise, see reduced_table.cpp); pass a
// tighter tolerance where the solver can meet it.
inline constexpr double kDefaultAdhesiveTolerance = kDefaultTolerance;

// Range of eta and a_bar the normalized models accept: six decades either side of the
// adhesive length. Beyond it the contact is JKR with the top layer's (eta large) or the
// base's (eta small) modulus, and a/t = a_bar/eta would leave the solver's range.
inline constexpr double kMinimumScaled = 1e-6;
inline constexpr double kMaximumScaled = 1e6;


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
  // Estimated absolute errors of a_bar, P and D (THEORY.md section 5, "Pull-off sweeps"): the
  // table's errors of the reduced variables and of their log-derivatives at a_bar, carried to
  // the stationary point to first order.
  double a_bar_err = 0.0, load_err = 0.0, penetration_err = 0.0;
  // The table's estimate of the relative error of the reduced variables at a_bar.
  double reduced_err = 0.0;
};

struct Pulloff {
  double eta = 0.0;
  PulloffPoint load_control;          // minimum of P over a_bar
  PulloffPoint displacement_control;  // minimum of D over a_bar (P, D there)
  double a_bar_scan_min = 0.0, a_bar_scan_max = 0.0;
  std::vector<std::string> warnings;  // empty when both minima are single and interior
};

// Pull-off through a spring of normalized stiffness k_bar = k (pi^2 w^2 R/E*^2)^(1/3)/(pi w R)
// (THEORY.md section 10): the contact jumps off where Z = D + P/k_bar is minimal along the
// curve (dP/dD = -k_bar). k_bar = 0 is load control, k_bar = inf displacement control.
struct SpringPulloff {
  double eta = 0.0;
  double k_bar = 0.0;
  PulloffPoint point;                 // a_bar, P, D at the jump
  std::vector<std::string> warnings;  // several minima of Z, or none inside the range
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

// How the contact edge closes, at the edge of a contact radius the interpolant serves: JKR
// (section 5). Laws that need more than the reduced variables at a/t have models of their own
// on this floor: the Maugis-Dugdale zone (section 13, maugis_dugdale.hpp) and crack kinetics
// (section 14, crack_kinetics.hpp).
class AdhesionLaw {
 public:
  virtual ~AdhesionLaw() = default;
  // P, D and their a_bar derivatives at a_bar from the interpolated reduced variables at
  // a/t = a_bar/eta.
  virtual CurvePoint point(const ReducedPoint& reduced, double eta, double a_bar) const = 0;
};

// Infinitely thin interaction zone: the edge is a crack with energy release rate w
// [selfconsistenceInhom], THEORY.md section 5.
class JkrLaw final : public AdhesionLaw {
 public:
  CurvePoint point(const ReducedPoint& reduced, double eta, double a_bar) const override;
};

class AdhesiveModel {
 public:
  // Reduced variables from the solver at `tolerance` (the solver must outlive the model).
  explicit AdhesiveModel(const ReducedSolver& solver, double tolerance = kDefaultAdhesiveTolerance,
                         TableOptions table = {}, PulloffOptions pulloff = {});
  // Reduced variables from any source (shared ownership); the JKR law unless another is given.
  explicit AdhesiveModel(std::shared_ptr<const ReducedSource> source, TableOptions table = {},
                         PulloffOptions pulloff = {},
                         std::shared_ptr<const AdhesionLaw> law = nullptr);
  ~AdhesiveModel();
  AdhesiveModel(const AdhesiveModel&) = delete;
  AdhesiveModel& operator=(const AdhesiveModel&) = delete;

  // P, D and their derivatives at a_bar for film thickness eta (both > 0, finite).
  CurvePoint point(double eta, double a_bar) const;
  std::vector<CurvePoint> curve(double eta, const std::vector<double>& a_bar) const;
  // Every point whose decade of the table can be built (the table is built a decade of a/t at
  // a time): the others get status[i].delivered = false and the reason (their rows hold eta,
  // a_bar, a/t and zeros). Delivered points equal curve()'s. InputError as curve().
  std::vector<CurvePoint> curve(double eta, const std::vector<double>& a_bar, std::vector<PointStatus>& status) const;
  // P and D at each a_bar from its own solve of the reduced variables, without the table: for
  // radii whose table decade reaches beyond what the source can deliver (the table is built a
  // whole decade of a/t at a time). dload and dpenetration are not set (0).
  std::vector<CurvePoint> curve_solved(double eta, const std::vector<double>& a_bar) const;
  // Pull-off under load and displacement control; NumericalError if it cannot be located.
  // On a table of prepare_pulloff_range, eta's whole scan must lie in its range (InputError).
  Pulloff pulloff(double eta) const;
  // The a_bar range a pull-off scans (PulloffOptions::a_bar_min/max or their defaults).
  std::pair<double, double> pulloff_scan_range() const;
  // Builds the table over exactly the a/t that the pull-offs of `etas` scan, with one
  // ReducedTable::prepare_range (a verified table, e.g. sweep_table_options: the pull-off
  // sweep, THEORY.md section 5, "Pull-off sweeps"). Only on a model whose table is empty.
  void prepare_pulloff_range(const std::vector<double>& etas) const;
  // Pull-off through a spring (cpp/adhesion/spring_pulloff.cpp). k_bar >= 0 or +inf; the two
  // limits return exactly pulloff(eta)'s load- and displacement-controlled points. InputError
  // for a negative or NaN k_bar.
  SpringPulloff pulloff_spring(double eta, double k_bar) const;

  // Default a_bar range of a curve: both JKR limits of the pull-off, a_bar ~ 1 (top layer)
  // and a_bar ~ (E*/E_base*)^(1/3) (base), and the Hertz-like regime above:
  //   [0.01 min(1, r), 10 max(1, r)], r = stack().substrate_length_ratio().
  std::pair<double, double> default_curve_range() const;

  const ReducedTable& table() const { return *table_; }
  const Stack& stack() const { return source_->stack(); }
  const AdhesionLaw& law() const { return *law_; }
  const PulloffOptions& pulloff_options() const { return pulloff_options_; }

 private:
  // Fills the error estimates of a pull-off point located in the scan [lo, hi] (minimum of P
  // or of D).
  void estimate_errors(PulloffPoint& point, double eta, bool load_control, double lo, double hi) const;
  std::shared_ptr<const ReducedSource> source_;
  std::shared_ptr<const AdhesionLaw> law_;
  std::unique_ptr<ReducedTable> table_;
  PulloffOptions pulloff_options_;
};

// The model whose pull-offs serve a list of etas at solver tolerance `tolerance` (THEORY.md
// section 5, "Pull-off sweeps"): for several etas, a model on one verified table over exactly
// the a/t they scan (nodes at kPulloffNodeShare x tolerance, pulloff_sweep_table_options), built
// here; nullptr for a single eta, or when a node of that table cannot be solved (`why_not`, if
// given, says which): then each eta's pull-off is the decade model's (AdhesiveModel(solver,
// tolerance)). The CLI, the C API and Python call this one function. InputError for a bad eta.
std::unique_ptr<AdhesiveModel> pulloff_sweep_model(const ReducedSolver& solver, double tolerance,
                                                   const std::vector<double>& etas, std::string* why_not = nullptr);

}  // namespace coatcontact
