// The fit's force models (private to the fit floor): one interface that the least squares,
// the global search and the statistics know a model through (Model, fit_model.hpp), and the
// parameter vector it is evaluated at. Each model is one file: the sphere through the reduced
// interpolant (sphere_model.cpp), base-displacement data through a spring (spring_model.cpp),
// any shape (shape_model.cpp), the Maugis-Dugdale zone (maugis_dugdale_fit.cpp), loading and
// unloading with their own w (branch_model.cpp); make_force_model (force_models.cpp) is the one
// place that reads the Problem's choice.
#pragma once
#include <array>
#include <cmath>
#include <functional>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/fit.hpp"

namespace coatcontact::fit::internal {

// The parameter vector (fit.hpp, parameter_list): w, h_1..h_N, E_1..E_N.
struct Parameters {
  std::vector<double> values;
  std::size_t layers = 1;
  bool hysteresis = false;  // w_unload follows the moduli
  bool spring = false;      // k last (Problem::base_displacement)
  bool md = false;          // lambda last (Problem::maugis_dugdale)

  Parameters() = default;
  Parameters(double work, double thickness, double film_modulus)  // one film
      : values{work, thickness, film_modulus} {}
  Parameters(std::vector<double> v, std::size_t layer_count, bool two_works = false, bool with_spring = false)
      : values(std::move(v)), layers(layer_count), hysteresis(two_works), spring(with_spring) {}
  double stiffness() const { return values.back(); }  // k [N/m] (spring only)
  double lambda() const { return values.back(); }     // Maugis's lambda (md only)
  double work() const { return values[kWork]; }
  double unload_work() const { return hysteresis ? values[unload_work_index(layers)] : work(); }
  // The parameters of one branch: one w (its own), no w_unload (k kept).
  Parameters branch(bool unloading) const;
  double thickness(std::size_t layer) const { return values[thickness_index(layer)]; }
  double modulus(std::size_t layer) const { return values[modulus_index(layer, layers)]; }
  double total_thickness() const;  // T = sum h_i
  // One film only.
  std::array<double, kParameterCount> as_array() const { return {values[0], values[1], values[2]}; }
  static Parameters from(const std::array<double, kParameterCount>& v) {
    return {v[kWork], v[kThickness], v[kFilmModulus]};
  }
};

// The layers of a problem (one film: `film` of thickness `thickness`) and its hint vector.
std::vector<Layer> problem_layers(const Problem& problem);
Parameters problem_parameters(const Problem& problem);
// The free parameters' indices, ascending.
std::vector<int> free_indices(const Problem& problem);

// What C(q) depends on: the relative thicknesses h_i/T (1 for one film) and the moduli.
struct StackKey {
  std::vector<double> relative_thickness, modulus;
  static StackKey of(const Parameters& p);
  bool operator==(const StackKey& other) const {
    return relative_thickness == other.relative_thickness && modulus == other.modulus;
  }
};

// The stack of a problem with the relative thicknesses and moduli of `key`.
Stack stack_of(const Problem& problem, const StackKey& key);

// The model at every data point.
struct ModelAtData {
  std::vector<double> radius, penetration, force;
  std::vector<double> force_lnw, force_lnt;  // d F_model / d ln p along the residual's path
  // dF/d delta along the curve at unclamped delta,F points (0 elsewhere): converts a change of
  // the model's delta at fixed a into a change of the residual at fixed measured delta.
  std::vector<double> slope;
  // dF/dx along the curve at each point, x the data's abscissa (a, or delta): what turns a
  // sigma of x into one of F (effective variance). 0 at clamped points.
  std::vector<double> force_x;
  std::vector<bool> clamped;
  bool has_pulloff = false;
  double pulloff_radius = 0.0, pulloff_penetration = 0.0, pulloff_force = 0.0;
  bool has_load_pulloff = false;
  double load_pulloff_radius = 0.0, load_pulloff_penetration = 0.0, load_pulloff_force = 0.0;
  // n points, every value 0 (false), no pull-off.
  static ModelAtData zeros(std::size_t n) {
    ModelAtData m;
    for (auto* v : {&m.radius, &m.penetration, &m.force, &m.force_lnw, &m.force_lnt, &m.slope, &m.force_x}) v->assign(n, 0.0);
    m.clamped.assign(n, false);
    return m;
  }
};

// One axis of the global search's grid: a parameter and its values.
struct SearchAxis {
  std::size_t which;
  std::vector<double> values;
};

// Relative step of the central differences in ln p: truncation ~h^2/6 ~ 2e-7, noise of the
// interpolated values ~tolerance/h ~ 1e-5 relative.
constexpr double kStep = 1e-3;
// Grid ratio above the pull-off radius on which a measured delta is bracketed (delta(a)
// rises monotonically there; 32 points per decade as AdhesiveModel's pull-off scan).
inline const double kBracketRatio = std::pow(10.0, 1.0 / 32.0);
constexpr std::size_t kMaxBracketSteps = 32 * 6;  // six decades above a_c
// Grid density of the search axes that cost a table or full evaluations per value (E_i, h_i of
// several layers, w of delta,F data, k, lambda).
constexpr double kCoarsePointsPerDecade = 2.0;

// A force model: F (and the contact radius) at the data points for a parameter vector.
class ForceModel {
 public:
  virtual ~ForceModel() = default;

  // The model at every point of `data`, all with the adhesion energy p.work(). with_pulloff: also
  // the pull-offs (load and displacement control) for a,F data.
  virtual ModelAtData evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) = 0;
  // d F_model / d ln p_parameter at the points, where the model has it in closed form (w, the one
  // film's t, the spring's k); nullopt: Model takes the central difference of shifted_force.
  virtual std::optional<std::vector<double>> analytic_column(const Parameters& p, const ModelAtData& m,
                                                             const Measurements& data, std::size_t parameter) const;
  // At q (p with one parameter shifted by e^(+-kStep)), per point: F - slope x at the model radius
  // of `m`, x the model's abscissa (delta, delta + F/k); the change of the residual at the fixed
  // measured x, to first order. The w of each point is q.branch(data.unloading[i]).
  virtual std::vector<double> shifted_force(const Parameters& q, const ModelAtData& m, const Measurements& data) = 0;
  // The pull-off through a spring k [N/m] at p (w_unload with two energies): {a, delta, F}, or
  // nothing when the jump is outside the scanned range or the model has none.
  virtual std::optional<std::array<double, 3>> spring_pulloff(const Parameters& p, double k);
  // The k whose pull-off the fit reports: the caller's, or the fitted one of z,F data.
  virtual double reported_spring(const Parameters& p, double given) const;
  // max |F_exact - F_model| over a sample of points (0 for a model solved at every point) [N].
  virtual double interpolation_error(const Parameters& p, const ModelAtData& m, const Measurements& data);
  virtual long solver_calls() const = 0;

  // For the global search: the contact radius of penetration |delta| without adhesion; whether
  // F = A - B sqrt(w) at fixed a (then w is profiled out of a,F data); the centre of a w axis
  // (0: the default range); the w parameter of each point (one per adhesion energy); the model's
  // own axes (k, lambda), after w's.
  virtual double adhesionless_radius(double penetration) const = 0;
  virtual bool work_separates() const;
  virtual double work_estimate(const Measurements& data) const = 0;
  virtual std::vector<std::size_t> work_parameters(const Parameters& hint) const;
  virtual std::vector<std::size_t> work_parameter_of_points(const Parameters& hint, const Measurements& data) const;
  virtual void add_search_axes(const Parameters& hint, const std::vector<int>& free_index,
                               std::vector<SearchAxis>& axes) const;
};

// The model a problem asks for (its checks first: validate_model).
std::unique_ptr<ForceModel> make_force_model(const Problem& problem);
// InputError when the problem's model does not fit its data or options.
void validate_model(const Measurements& data, const Problem& problem);

// Log-spaced axis from lo to hi with per_decade points per decade (at least 2).
std::vector<double> log_axis(double lo, double hi, double per_decade);
// The stack entries a fit keeps at once: the stack and its two neighbours in each free
// parameter that changes the table, and one spare (at least four).
std::size_t cache_capacity(const Problem& problem);
// "the model needs a/t = .., outside [..]" unless a/T is inside kAOverTRange.
void check_a_over_t(double radius, double total_thickness);
// Brent root of f on [lo, hi] (f(lo) < 0 <= f(hi)).
double find_root(const std::function<double(double)>& f, double lo, double hi);

}  // namespace coatcontact::fit::internal
