// The fit model at the data points (private to coatcontact_fit): the adhesive contact of
// THEORY.md section 5 evaluated through the adhesion floor (ReducedTable, JkrLaw, Contact),
// the branch choice for delta,F data, the residuals and the derivatives of the model force.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/shape_contact.hpp"
#include "coatcontact/shape_solver.hpp"

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

// One stack: its solver and the adhesive model (SolverSource + ReducedTable) on it. The
// moduli and h_i/T enter C(q), so every distinct set needs its own kernel table and
// interpolant.
class ModelEntry {
 public:
  ModelEntry(const Problem& problem, const StackKey& key);
  const AdhesiveModel& model() const { return *model_; }
  const ReducedSolver& solver() const { return *solver_; }
  const StackKey& key() const { return key_; }
  bool has_model() const { return model_ != nullptr; }
  // A fit with Problem::shape: the shape floor's solver on the same stack (no table, no model).
  const ShapeSolver& shape_solver() const { return *shape_solver_; }
  // A Maugis-Dugdale fit (Problem::maugis_dugdale): the adhesion floor's model on the stack.
  const MaugisDugdaleModel& md_model() const { return *md_model_; }

 private:
  StackKey key_;
  std::unique_ptr<ShapeSolver> shape_solver_;
  std::unique_ptr<MaugisDugdaleModel> md_model_;
  std::unique_ptr<ReducedSolver> solver_;  // declared first: the model keeps a reference
  std::unique_ptr<AdhesiveModel> model_;
};

// The few entries a fit needs at once (the stack and its neighbours e^(+-h) in each
// table-changing free parameter, for the Jacobian), most recent first.
class ModelCache {
 public:
  ModelCache(const Problem& problem, std::size_t capacity) : problem_(problem), capacity_(capacity) {}
  ModelEntry& get(const Parameters& p);
  long solver_calls() const;  // reduced-variable solves of every table built so far

 private:
  const Problem& problem_;
  std::size_t capacity_;
  std::vector<std::unique_ptr<ModelEntry>> entries_;
  long retired_calls_ = 0;
};

// F and delta at contact radius a (SI) with their derivatives: along the curve (d/da at
// fixed parameters) and with respect to ln w and ln t at fixed a.
struct SiPoint {
  double radius = 0.0, force = 0.0, penetration = 0.0;
  double force_a = 0.0, penetration_a = 0.0;
  double force_lnw = 0.0, penetration_lnw = 0.0;
  double force_lnt = 0.0, penetration_lnt = 0.0;
};

// The contact for one parameter set: a Contact (which owns the Maugis scales) on the model
// of the parameters' E1.
class ContactModel {
 public:
  ContactModel(const AdhesiveModel& model, double sphere_radius, const Parameters& p);
  SiPoint at(double radius) const;
  // F and delta from reduced variables solved directly (no interpolation).
  SiPoint exact(const ReducedVariables& v, double radius) const;
  const Contact& contact() const { return contact_; }
  void prepare(double radius_min, double radius_max) const;
  void prepare_pulloff() const;  // the decades of AdhesiveModel's pull-off scan, in one batch

 private:
  SiPoint to_si(const coatcontact::CurvePoint& full, const coatcontact::CurvePoint& fixed_x) const;
  const AdhesiveModel& model_;
  double total_thickness_;  // T [m], the unit length
  Contact contact_;
};

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
};

class Model {
 public:
  Model(const Problem& problem, const Measurements& data);

  // The model at every data point; any failure becomes a NumericalError naming the parameters.
  // with_pulloff: also report the pull-offs (load and displacement control) for a,F data
  // (delta,F data always need the displacement-controlled one: it bounds the stable branch).
  ModelAtData at_data(const Parameters& p, bool with_pulloff = false);
  // d F_model / d ln p_j at every data point for the parameters in `which` (w and the one
  // film's t analytic, every parameter that changes the table (E_i; h_i of several layers) by
  // a central difference in ln p at the model radii of `m`: the same derivative as a
  // re-inversion of delta at p e^(+-h), without its square-root singularity near a_c).
  std::vector<std::vector<double>> force_derivatives(const Parameters& p, const ModelAtData& m,
                                                     const std::vector<int>& which);
  // max |F_exact - F_model| over (up to 16 of) the data points, the reduced variables solved
  // directly at each model radius (first order in the delta mismatch for delta,F data) [N].
  double interpolation_error(const Parameters& p, const ModelAtData& m);
  long solver_calls() const { return cache_.solver_calls() + check_calls_ + shape_calls_; }
  // Pull-off through a spring of stiffness k [N/m] at p: {a, delta, F} (SI), or nothing when
  // the jump is not inside the scanned range.
  std::optional<std::array<double, 3>> spring_pulloff(const Parameters& p, double k);
  // Swap the data (same kind and size: bootstrap resamples), keeping the tables.
  void set_data(const Measurements& data) { data_ = &data; }
  const Measurements& data() const { return *data_; }
  const std::vector<ParameterInfo>& names() const { return names_; }
  std::string describe(const Parameters& p) const;  // "w = .. J/m2, t = .. m, E1 = .. Pa"

 private:
  ModelAtData evaluate(const Parameters& p, bool with_pulloff);
  // One w for every point of `data`.
  ModelAtData evaluate_single(const Parameters& p, const Measurements& data, bool with_pulloff);
  // The same through ShapeContact (Problem::shape): direct solves at every radius.
  ModelAtData evaluate_shape(const Parameters& p, const Measurements& data, bool with_pulloff);
  ShapeContact shape_contact(const Parameters& branch);
  // Problem::maugis_dugdale: F and delta at the measured a (a,F data), one solve per point.
  ModelAtData evaluate_md(const Parameters& p, const Measurements& data, bool with_pulloff);
  void check_range(const Parameters& p) const;
  [[noreturn]] void rethrow_at(const Parameters& p) const;

  const Problem& problem_;
  const Measurements* data_;
  ModelCache cache_;
  std::vector<ParameterInfo> names_;
  long check_calls_ = 0;
  long shape_calls_ = 0;  // ShapeContact::at calls (shape fits)
};

}  // namespace coatcontact::fit::internal
