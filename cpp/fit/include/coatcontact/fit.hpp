// Least-squares fit of measured adhesive sphere-contact data (contact radius a and force F, or
// penetration delta and force F) to the coated-substrate JKR model (THEORY.md section 5):
//
//   delta_fp = -sqrt(2 pi a w / E1*) / Gamma(1)                      [selfconsistenceInhom]
//   F        = (a^3 E1* / (2R)) Pi_s(a/t) + 2 a E1* E_eq(a/t) delta_fp [EqForceCS]
//   delta    = (a^2 / R) Delta_s(a/t) + delta_fp                      [EqPenetrationCS]
//
// Free parameters: any non-empty subset of {w, t, E1}; the others are fixed. On a stack of N
// layers (Problem::layers, THEORY.md section 12) t is the total thickness T = sum h_i and the
// parameters are w, h_1..h_N, E_1..E_N (parameter_list). The model is the adhesion floor's:
// the reduced variables come from the ReducedTable (one interpolant, built on demand as t
// moves the range the data need), the JKR law and the Contact's Maugis scales give F and
// delta; each trial E1 (each set of h_i/T and E_i of a stack) needs its own solver and table.
// With Problem::hysteresis the loading and unloading points take their own w (w_load,
// w_unload; Measurements::unloading says which), the pull-offs use w_unload.
//
// Residuals are in force, at the measured a (a,F data), or at the contact radius a* on the
// model curve where delta(a*) equals the measured delta (delta,F data). a* lies on the stable
// branch under displacement control: a* >= a_c, where a_c is the displacement-controlled
// pull-off point (the minimum of delta(a), AdhesiveModel::pulloff). A measured delta below
// the model's minimum delta(a_c) has no equilibrium on that branch; its residual is taken at a_c.
// Weights: with per-point uncertainties (sigma_abscissa, sigma_force) the residuals are divided
// by the effective sigma, sigma_eff^2 = sigma_F^2 + (dF/dx)^2 sigma_x^2, dF/dx along the model
// curve (x = a or delta), weights refreshed at the solution until stable; the covariance is then
// (J^T W J)^-1 and chi^2/(n-p) is reported. Without any sigma the residuals are unweighted,
// s^2 = RSS/(n-p), covariance s^2 (J^T J)^-1, and the errors assume an exact abscissa.
// Start values: a coarse global search over log-parameters (w profiled out for a,F data, where
// F is linear in sqrt(w) at fixed a) picks the start; the problem's values are only a hint.
//
// Errors: InputError for bad problems (n <= number of free parameters, a <= 0 in a,F data,
// negative or non-finite sigmas); NumericalError when the fit does not converge, a parameter
// runs out of its physical range or does not change the fit over its search range (named),
// the parameters are not identifiable from the data, or the model does not describe the data
// (R^2 < kMinimumRSquared).
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <memory>

#include "coatcontact/errors.hpp"
#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::fit {

enum class DataKind { kRadiusForce, kPenetrationForce };  // (a, F) or (delta, F)
enum class Branch { kAll, kLoading, kUnloading };

struct Measurements {
  DataKind kind = DataKind::kRadiusForce;
  std::vector<double> abscissa;  // a [m] (> 0) or delta [m] (any sign)
  std::vector<double> force;     // F [N], compressive positive (any sign)
  std::vector<int> line_numbers;  // source lines (for messages and output); may be empty
  // Standard uncertainties per point (same length as force, or empty: that variable is exact
  // / unknown). With neither, the fit is unweighted.
  std::vector<double> sigma_abscissa;  // [m]
  std::vector<double> sigma_force;     // [N]
  // Per point: true on the unloading branch (fits with w_load and w_unload); empty: one w.
  std::vector<bool> unloading;
  std::size_t size() const { return force.size(); }
};

// The unloading rows by their order: every row after the (first) maximum of the abscissa
// (the turning point itself is loading).
std::vector<bool> unloading_by_order(const Measurements& data);

// Loading = the rows up to and including the (first) maximum of the abscissa, unloading = the
// rows from that maximum on (so the turning point belongs to both). kAll returns `data`.
Measurements select_branch(const Measurements& data, Branch branch);

// The parameter vector of a fit on N layers (top first): w, the thicknesses h_1..h_N, the
// Young's moduli E_1..E_N. One film (N = 1) gives the three of the paper, w, t, E1, at the
// indices below; its thickness is called t. Only h_i/T and the moduli enter C(q), so every
// distinct set of them has its own kernel table; the total thickness T = sum h_i scales the
// lengths.
enum Parameter : int { kWork = 0, kThickness = 1, kFilmModulus = 2 };
constexpr int kParameterCount = 3;  // one film
const char* parameter_name(int parameter);  // one film: "w", "t", "E1"

// kSpeed, kExponent: the crack-kinetics law's v* and n (kinetics_fit.hpp).
enum class ParameterKind { kWork, kThickness, kModulus, kSpring, kLambda, kSpeed, kExponent };
struct ParameterInfo {
  ParameterKind kind = ParameterKind::kWork;
  std::size_t layer = 0;  // 0-based, top first (thickness and modulus)
  std::string name;       // "w", "t" (one film) or "h2", "E1"
  const char* unit = "";  // "J/m2", "m", "Pa"
};
// The parameters of a fit on `layers` layers, in the order of the parameter vector. With
// `hysteresis` the loading and unloading branches have their own adhesion energy: w is then
// called w_load and w_unload follows the moduli.
// With `spring` (Problem::base_displacement) the stiffness k [N/m] comes last; with `lambda`
// (Problem::maugis_dugdale) Maugis's lambda (dimensionless) comes last.
std::vector<ParameterInfo> parameter_list(std::size_t layers, bool hysteresis = false, bool spring = false,
                                          bool lambda = false);
// Index in the parameter vector of w, h_i or E_i (0-based layer).
inline std::size_t thickness_index(std::size_t layer) { return 1 + layer; }
inline std::size_t modulus_index(std::size_t layer, std::size_t layers) { return 1 + layers + layer; }
inline std::size_t unload_work_index(std::size_t layers) { return 1 + 2 * layers; }
inline std::size_t spring_index(std::size_t layers, bool hysteresis) { return 1 + 2 * layers + (hysteresis ? 1 : 0); }

struct Problem {
  double sphere_radius = 0.0;  // R [m] (unused with `shape`)
  // Any axisymmetric indenter instead of the sphere (THEORY.md section 11): the model is then
  // the adhesion floor's ShapeContact, solved directly at every model radius (no interpolant;
  // w enters only through delta_fp ~ sqrt(w), so dF/d ln w stays analytic, the other
  // derivatives are central differences in ln p). Null: the sphere of radius sphere_radius.
  // The shape's own parameters (cone angle, tip radius, ...) are fixed.
  std::shared_ptr<const IndenterShape> shape;
  Material film;               // E1 (hint and centre of the search range if free, else fixed), nu1
  Substrate substrate;
  double thickness = 0.0;  // t [m] (a hint to the search if free, else fixed)
  double work = 0.0;       // w [J/m2] (a hint to the search if free, else fixed)
  std::array<bool, kParameterCount> free{{true, false, false}};
  // A stack of layers instead of `film` and `thickness` (when not empty): top first, thickness
  // in m, moduli and thicknesses are hints if free, else fixed. `free_parameters` then names
  // the free ones by their index in the parameter vector (parameter_list); left empty, w alone
  // is free if free[kWork] (the default), and the rest of `free` is unused.
  std::vector<Layer> layers;
  std::vector<std::size_t> free_parameters;
  // JKR hysteresis: the loading rows (Measurements::unloading false) take w_load = `work`,
  // the unloading rows w_unload = `unload_work`; both are free (named in free_parameters, which
  // then replaces `free` for one film too). The pull-offs are predicted with w_unload.
  bool hysteresis = false;
  double unload_work = 0.0;  // w_unload [J/m2] (a hint to the search)
  Indenter indenter;  // rigid by default; elastic: the stack's reference modulus is E_r
  double spring_stiffness = 0.0;  // k [N/m] of the machine/cantilever (> 0: its pull-off is reported)
  // The abscissa of kPenetrationForce data is the base (piezo) displacement z = delta + F/k,
  // the indenter sitting on a spring of stiffness k (THEORY.md section 10): the model's
  // delta + F/k is matched to z on the branch that is stable under spring control (a >= the
  // spring pull-off radius), and k (spring_stiffness: hint if free, else fixed) is appended to
  // the parameter vector as "k" (spring_index), so it can be named in free_parameters. F and z
  // together carry k: along the curve dz/dF = d delta/dF + 1/k.
  bool base_displacement = false;
  // Maugis-Dugdale cohesive zone instead of JKR (THEORY.md section 13, MaugisDugdaleModel of
  // the adhesion floor): F = pi w R P(a_bar; eta, lambda), lambda = 2 sigma0 (R/(pi w K^2))^(1/3),
  // K = 4E1*/3. `lambda` (hint if free, else fixed) is appended to the parameter vector as
  // "lambda". a,F data of a rigid sphere only; every derivative a central difference in ln p,
  // no spring pull-off.
  bool maugis_dugdale = false;
  double lambda = 1.0;
  // The Maugis-Dugdale values by the direct per-radius solve (the reference) instead of the
  // reduced table of the cohesive zone (one table per stack, shared by every w, t and lambda).
  bool maugis_dugdale_direct = false;
  double solver_tolerance = kDefaultTolerance;  // of the solves behind the interpolant
  int max_iterations = 200;
  bool global_search = true;  // false: start from the values above (bootstrap refits, tests)
  int bootstrap = 0;          // residual-bootstrap refits (0: none)
  unsigned long bootstrap_seed = 1;
};

// Ranges of the global search (the model itself accepts wider values; kSearch* only bound the
// grid): w over [kSearchWork], t with the data's a/t in [kSearchAOverT] (a,F data: the range
// covers every a), E1 within a factor kSearchModulusFactor of the given value; in a stack of
// several layers each h_i within kSearchThicknessFactor and each E_i within
// kSearchModulusFactor of its given value.
constexpr double kSearchWork[2] = {1e-5, 10.0};      // J/m2
constexpr double kSearchAOverT[2] = {1e-2, 50.0};
constexpr double kSearchModulusFactor = 10.0;
constexpr double kSearchThicknessFactor = 10.0;
constexpr double kSearchSpringFactor = 10.0;  // k of z,F data, around its hint (--spring)
constexpr double kSearchLambdaFactor = 10.0;  // Maugis-Dugdale lambda, around its hint
// The lambda the fit accepts and may run to is the library's one range, [kMinimumLambda,
// kMaximumLambda] of limits.hpp (THEORY.md section 13); inf (JKR) is the JKR model, not a fit value.

// Physical ranges of the parameters the model accepts (leaving them means the data do not
// determine them), and the a/t (a/T for a stack) it is tabulated for.
constexpr double kWorkRange[2] = {1e-9, 1e4};      // J/m2
constexpr double kModulusRange[2] = {1e-2, 1e13};  // Pa
constexpr double kAOverTRange[2] = {1e-5, 1e5};

// Below this coefficient of determination the fit is refused as "the model does not describe
// the data" (e.g. a fit of pure noise): the model must explain at least half of the variance of
// the measured forces about their mean.
constexpr double kMinimumRSquared = 0.5;
// Column-scaled condition number of the Jacobian above which parameters count as not
// identifiable from the data.
constexpr double kMaximumCondition = 1e10;

// Per-parameter fields are indexed like the parameter vector (parameter_list; one film: kWork,
// kThickness, kFilmModulus).
struct Result {
  std::vector<ParameterInfo> parameters;  // names and units
  std::vector<double> value;           // fitted or fixed values
  std::vector<double> standard_error;  // 0 for fixed parameters
  std::vector<bool> free;
  // Correlation coefficients between parameters (1 on the diagonal, 0 for fixed ones).
  std::vector<std::vector<double>> correlation;
  std::size_t points = 0;
  int free_count = 0;
  double residual_norm = 0.0;   // sqrt(RSS) [N]
  double residual_sigma = 0.0;  // s = sqrt(RSS/(n-p)) [N]
  double r_squared = 0.0;       // 1 - RSS / sum (F - mean F)^2
  bool weighted = false;        // per-point sigmas were given
  double chi2 = 0.0;            // sum (residual / sigma_eff)^2 (weighted fits)
  double chi2_per_dof = 0.0;    // chi2 / (n - p)
  std::vector<double> sigma_effective;  // per point [N] (weighted fits; else empty)
  // Residual bootstrap (Problem::bootstrap > 0): percentile intervals of each free parameter.
  int bootstrap_samples = 0;    // refits that converged
  std::vector<double> interval68_low, interval68_high;
  std::vector<double> interval95_low, interval95_high;
  // Global search: grid points evaluated, and a second local minimum if one was found and
  // polished to distinct parameters (cost ratio = its chi2 or RSS over the best one's).
  int search_evaluations = 0;
  double search_seconds = 0.0;  // wall time of the search (tables it builds included)
  bool second_minimum = false;
  std::vector<double> second_value;
  double second_cost_ratio = 0.0;
  int iterations = 0;
  bool converged = false;
  std::string stop_reason;  // "small step", "small gradient", ...
  // Per data point (same order as the input):
  std::vector<double> model_radius;  // a at which the model is evaluated [m]
  std::vector<double> model_penetration;  // delta of the model at that a [m]
  std::vector<double> model_force;   // F of the model [N]
  std::vector<double> residual;      // model - data [N]
  std::vector<bool> clamped;         // delta data below the model's minimum delta
  // Interpolation check at the solution: the model force recomputed with the reduced
  // variables solved directly at each data point's a/t, max |F_exact - F_model| over points
  // (first order in the delta mismatch for delta,F data) [N].
  double interpolation_error = 0.0;
  // Displacement-controlled pull-off of the fitted model (AdhesiveModel::pulloff), for both
  // kinds of data (0 when the model has no interior minimum of delta).
  double displacement_pulloff_radius = 0.0;       // a_c [m]
  double displacement_pulloff_penetration = 0.0;  // delta(a_c) [m]
  double displacement_pulloff_force = 0.0;        // F(a_c) [N]
  // Pull-off through the spring k of Problem::spring_stiffness (THEORY.md section 10).
  bool has_spring_pulloff = false;
  double spring_pulloff_radius = 0.0, spring_pulloff_penetration = 0.0, spring_pulloff_force = 0.0;
  // Load-controlled pull-off (minimum of F along the model curve), reported for every fit.
  bool has_load_pulloff = false;
  double load_pulloff_radius = 0.0, load_pulloff_penetration = 0.0, load_pulloff_force = 0.0;
  double solver_tolerance = 0.0;  // tolerance of every reduced-variable solve (Problem's)
  long solver_calls = 0;  // reduced-variable solves (all E1 values, and the check)
  double seconds = 0.0;   // wall time of the fit
};

Result fit(const Measurements& data, const Problem& problem);

// The start values of a problem (the hints of its free parameters, the values of its fixed
// ones) against the ranges the fit explores: w and w_unload in kWorkRange, every E_i in
// kModulusRange, the a/t (a/T) of a,F data in kAOverTRange. fit() checks them first; a caller
// that maps its own option names to the parameters catches StartError, which names the
// parameter by its index in the parameter vector.
class StartError : public InputError {
 public:
  StartError(std::size_t parameter, const std::string& what) : InputError(what), parameter_(parameter) {}
  std::size_t parameter() const { return parameter_; }

 private:
  std::size_t parameter_;
};
void check_start(const Measurements& data, const Problem& problem);

// What the data imply when they look like a unit mix-up, or "" when they look plausible: for
// the sphere, the w that the most tensile force needs under JKR (F = -(3/2) pi w R) when it is
// outside kSearchWork ("... needs w = 2.1e+04 J/m2 ...: are the units of F and R right?").
// fit() appends it to a failure; callers append it to their own refusals.
std::string units_hint(const Measurements& data, const Problem& problem);

// Start value of w from the most tensile measured force through the JKR load-controlled
// pull-off F_min = -(3/2) pi w R (THEORY.md section 6; the film shifts the pull-off, but the
// estimate is close enough to start from); 50 mJ/m2 if no force is tensile.
double jkr_work_estimate(const Measurements& data, double sphere_radius);
// The start value of w when none is given: jkr_work_estimate for the sphere; for a shape (no
// sphere radius) kDefaultStartWork, the search then finds w on its own.
constexpr double kDefaultStartWork = 0.05;  // J/m2
double start_work(const Measurements& data, const Problem& problem);

// The model curve for fixed parameters (used by fit() and for plotting/tests).
struct CurvePoint {
  double radius = 0.0;       // a [m]
  double penetration = 0.0;  // delta [m]
  double force = 0.0;        // F [N]
};

// The exact model at contact radius a (reduced variables solved directly at a/t).
CurvePoint exact_point(const Problem& problem, double radius);

// `count` points log-spaced in a over [radius_min, radius_max], from the interpolated
// reduced variables (the same model the fit uses).
std::vector<CurvePoint> model_curve(const Problem& problem, double radius_min, double radius_max,
                                    int count);

}  // namespace coatcontact::fit
