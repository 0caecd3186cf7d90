// Library-private pieces shared by the AFM curve fits (afm_curve_model.cpp: Hertz/Sneddon;
// afm_adhesive_model.cpp: the adhesive search through the cantilever) and the model files that
// register them (afm_<name>_model.cpp, coatcontact/afm_models.hpp). Not installed.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_models.hpp"

namespace coatcontact::fit::internal {

// A model's parameter table: E, t, contact_point, baseline, the model's `own`, tilt (free by
// default when tilt_free).
std::vector<AfmParameterInfo> afm_parameter_table(const std::vector<AfmParameterInfo>& own, bool tilt_free);
// w [J/m2] of the adhesive models: free by default, > 0.
AfmParameterInfo afm_work_parameter();

// The Hertz/Sneddon fit (afm_curve_model.cpp) and its model force at z.
AfmFitResult afm_fit_hertz(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                           int free_count);
// The coated Hertz fit's search for a free E1 on an elastic base (THEORY.md section 15, "Tabled
// coated force laws", "The search"): kProfiled (afm_fit_hertz's) finds the fixed point of the
// closed-form scale and polishes it by Gauss-Newton at the contact point; kNested minimizes over
// ln E1 with a contact-point search per trial (the direct path's search; kept to check the
// first against).
enum class CoatedE1Search { kProfiled, kNested };
AfmFitResult afm_fit_hertz(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                           int free_count, CoatedE1Search search);
std::vector<double> afm_hertz_model_force(const AfmFitProblem& problem, const std::vector<double>& z);

// s^2 (J^T J)^-1 on the column-scaled normal matrix: the standard errors of the columns'
// parameters; NumericalError if a column is zero or the matrix singular.
std::vector<double> afm_standard_errors(const std::vector<std::vector<double>>& columns, double sigma);

// From r.model_force and r.indentation (filled): residuals (model - data), rss, points in
// contact (indentation > contact_threshold; none: NumericalError "afm fit: " + no_contact),
// max indentation, residual sigma, R^2, and chi2 when noise_sigma > 0.
void afm_residual_statistics(AfmFitResult& r, const std::vector<double>& force, double noise_sigma, int free_count,
                             double contact_threshold, const std::string& no_contact);

// The least-squares step x minimizing |J x - residual| (J by columns; SVD, tiny singular values dropped).
std::vector<double> afm_least_squares_step(const std::vector<std::vector<double>>& columns, const std::vector<double>& residual);

// Parameters of one trial of an adhesive model: E (half-space) or E1 [Pa], w [J/m2], t [m] (coating).
struct AdhesiveTrial {
  double modulus = 0.0;
  double work = 0.0;
  double thickness = 0.0;
};

// GSL's natural cubic spline through (x_k, y_k) as explicit pieces (THEORY.md section 15, "The
// JKR search on a coating"): GSL solves for the spline, its slopes at the knots give each
// interval's cubic y_k + s (b_k + s (c_k + s d_k)), s = x - x_k, so an evaluation is one
// interval lookup and a Horner step (no per-call coefficient solve or accelerator).
class SplinePieces {
 public:
  SplinePieces() = default;
  SplinePieces(std::vector<double> x, std::vector<double> y);  // x strictly increasing, >= 3 knots
  // The interval holding v (clamped to the first/last): binary search, or direct indexing
  // when the knots were declared uniform.
  std::size_t interval(double v) const;
  double value(double v, std::size_t k) const {
    const double s = v - x_[k];
    return y_[k] + s * (b_[k] + s * (c_[k] + s * d_[k]));
  }
  double slope(double v, std::size_t k) const {
    const double s = v - x_[k];
    return b_[k] + s * (2.0 * c_[k] + 3.0 * s * d_[k]);
  }
  double value(double v) const { return value(v, interval(v)); }
  // Knots uniform in x to rounding: interval() indexes directly.
  void declare_uniform() { uniform_ = true; }
  const std::vector<double>& x() const { return x_; }

 private:
  std::vector<double> x_, y_, b_, c_, d_;
  bool uniform_ = false;
};

// The adhesive force F(delta) on the branch a cantilever of stiffness k holds (THEORY.md
// section 15, JKR and Maugis-Dugdale alike): from the curve point(a) = (delta, F) [SI], the
// jump-off a_s is the lowest minimum of Z = delta + F/k on a scan of a in [a_lo, a_hi]
// (per_decade points, polished by Brent) or, when given and lower, the curve's end a -> 0
// (`end`: its (delta, F)); then (delta, F) at `nodes` radii from a_s up past max_indentation,
// F against delta by a cubic spline (past the last node the power law of the last two nodes,
// for trial contact points only), zero for delta <= delta(a_s). NumericalError when Z has no
// minimum on the scan (and no end) or the branch is not finite.
class SpringBranch {
 public:
  using CurvePoint = std::function<std::pair<double, double>(double)>;
  SpringBranch(const CurvePoint& point, double scale, double lo, double hi, int per_decade, double spring,
               double max_indentation, double a_top, int nodes, std::optional<std::pair<double, double>> end,
               double reduced_modulus);
  ~SpringBranch();
  SpringBranch(const SpringBranch&) = delete;
  SpringBranch& operator=(const SpringBranch&) = delete;

  std::pair<double, double> at(double delta) const;  // F and dF/ddelta (0 off contact)
  double value(double delta) const;                   // F alone (the contact search's sums)
  // F at contact - z[i] for i < count, z ascending (the indentations descending): one walk
  // down the knots instead of a search per point.
  void values(double contact, const double* z, std::size_t count, double* out) const;
  double jump_delta() const { return jump_delta_; }
  double jump_force() const { return jump_force_; }
  bool jump_at_end() const { return jump_at_end_; }  // the jump-off is the curve's end a -> 0
  double max_indentation() const { return delta_.back(); }
  double max_radius() const { return a_max_; }
  double top_radius() const { return a_top_; }  // the largest radius evaluated for the table
  double reduced_modulus() const { return reduced_; }

 private:
  double reduced_ = 0.0, a_max_ = 0.0, a_top_ = 0.0, jump_delta_ = 0.0, jump_force_ = 0.0, last_slope_ = 1.5;
  bool jump_at_end_ = false;
  std::vector<double> delta_, force_;
  SplinePieces spline_;
};

// A spring-held adhesive model other than JKR for the shared search of the adhesive fit: the
// branch of a trial, and the report of the estimates (lambda, warnings) once fitted.
struct SpringModel {
  std::string name;
  std::function<std::unique_ptr<SpringBranch>(const AdhesiveTrial&, double max_indentation)> branch;
  std::function<void(const AdhesiveTrial&, AfmFitResult&)> report;
  // Set for a model with a table per E1 node (MD on an elastic base with E1 free): coarse(true)
  // reads a trial between the nodes kCoarseNodeStep apart, linearly in ln E1, each node's table
  // at the trial's own scale; coarse(false) is the model (THEORY.md section 15, "The coarse nodes").
  std::function<void(bool)> coarse;
};

// The coarse stage's node spacing, in nodes (8: one node a decade; its nodes are nodes of the
// model, so their tables serve the final stage too).
constexpr long kCoarseNodeStep = 8;

// The four reduced variables of THEORY.md section 5 at one a/t (the half-space's values by default).
struct ReducedAt {
  double pi_s = 8.0 / 3.0, delta_s = 1.0, e_eq = 1.0, gamma1 = 1.0;
};

// A contact law on the reduced variables for the adhesive fit through the cantilever: (delta, F)
// at contact radius a from the reduced variables at a/t (E* the film's reduced modulus), the
// curve's end a -> 0 when the law has one there, the pull-off through a soft lever in units of
// pi w R (the start of w's search), and the report of the estimates (lambda, warnings).
struct ReducedLaw {
  std::string name;
  std::function<std::pair<double, double>(double a, const ReducedAt& v, double reduced, double work, double radius)> point;
  std::function<std::optional<std::pair<double, double>>(double reduced, double work, double radius)> end;
  double soft_pulloff = 1.5;
  std::function<void(const AfmFitProblem&, AfmFitResult&)> report;
};
const ReducedLaw& jkr_law();  // THEORY.md section 5, steps 3-4

// The adhesive fit through the cantilever (THEORY.md section 15): `model` when given, else the
// law on the reduced variables (null: JKR).
AfmFitResult afm_fit_adhesive(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                              int free_count, const SpringModel* model, const ReducedLaw* law = nullptr);
// The model force at z of a law on the reduced variables (problem at its estimates).
std::vector<double> afm_reduced_model_force(const AfmFitProblem& problem, const std::vector<double>& z, const ReducedLaw& law);

// Cubic Lagrange weights of the nodes j0..j0+3 at x (node j at x = j).
void lagrange_weights(double x, long j0, double weight[4]);

// The Maugis-Dugdale fit through the cantilever (afm_md_model.cpp) and its model force at z.
AfmFitResult afm_fit_md(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                        int free_count);
// Its search for a free E1 on an elastic base (THEORY.md section 15, "The coarse nodes"):
// kCoarseNodes (afm_fit_md's) first on one node a decade, then on every node; kEveryNode on every
// node throughout (the search before; kept to check the first against).
enum class MdE1Search { kCoarseNodes, kEveryNode };
AfmFitResult afm_fit_md(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                        int free_count, MdE1Search search);
std::vector<double> afm_md_model_force(const AfmFitProblem& problem, const std::vector<double>& z);

// The JKR fit through the cantilever (afm_jkr_model.cpp) and its model force at z.
AfmFitResult afm_fit_jkr(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                         int free_count);
std::vector<double> afm_jkr_model_force(const AfmFitProblem& problem, const std::vector<double>& z);
// Tabor's mu and Maugis's lambda (h0 = kDugdaleRangeOverZ0 z0) of the estimates in r
// (reduced_modulus, work); afm_jkr_lambda adds the warning when lambda is below kJkrMinimumLambda.
void afm_tabor_maugis(const AfmFitProblem& problem, AfmFitResult& r);
void afm_jkr_lambda(const AfmFitProblem& problem, AfmFitResult& r);

}  // namespace coatcontact::fit::internal

#include "coatcontact/coated_table.hpp"

namespace coatcontact::fit::internal {

// The process's tabled coated force law of a coating (THEORY.md section 15, "Tabled coated
// force laws"): one CoatedTable per (nu1, substrate, solver tolerance), E1 free, a/t over
// kCoatingAOverT, shared by every fit, curve and thread (built node by node on demand).
std::shared_ptr<const CoatedTable> afm_coated_table(const AfmCoating& coating);
// A multi-layer sample's shape (free layer; per layer h_i/T, E_i (0: the free one), nu_i, slip):
// with the substrate and nu of the free layer, what keys its tables and sweeps (empty: one film).
std::vector<double> afm_stack_shape(const AfmCoating& coating);
// Drops them (afm_clear_shared_sweeps: a benchmark's first curve of a sample).
void afm_clear_coated_tables();
// A multi-layer sample's limits (AfmCoating): the free layer in range, the Hertz model, t fixed.
void check_afm_coating(const AfmFitProblem& problem);

}  // namespace coatcontact::fit::internal
