// The fit's model at the data points (private to the fit floor): the force model of the problem
// (force_model.hpp) behind one facade that the least squares, the global search and the
// statistics use. It checks the parameters' physical ranges, names the parameters in failures,
// and takes the Jacobian: closed-form columns from the force model, central differences in
// ln p of the rest.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/fit.hpp"
#include "force_model.hpp"

namespace coatcontact::fit::internal {

class Model {
 public:
  Model(const Problem& problem, const Measurements& data);

  // The model at every data point; any failure becomes a NumericalError naming the parameters.
  // with_pulloff: also report the pull-offs (load and displacement control) for a,F data
  // (delta,F data always need the displacement-controlled one: it bounds the stable branch).
  ModelAtData at_data(const Parameters& p, bool with_pulloff = false);
  // d F_model / d ln p_j at every data point for the parameters in `which`: the force model's
  // closed form where it has one (w, the one film's t, k), else a central difference in ln p at
  // the model radii of `m` (the same derivative as a re-inversion of delta at p e^(+-h), without
  // its square-root singularity near a_c).
  std::vector<std::vector<double>> force_derivatives(const Parameters& p, const ModelAtData& m,
                                                     const std::vector<int>& which);
  // max |F_exact - F_model| over (up to 16 of) the data points, the reduced variables solved
  // directly at each model radius (first order in the delta mismatch for delta,F data) [N].
  double interpolation_error(const Parameters& p, const ModelAtData& m);
  long solver_calls() const { return model_->solver_calls(); }
  // Pull-off through a spring at p: {a, delta, F} (SI), or nothing when the jump is not inside
  // the scanned range; the spring is the problem's (`given` [N/m]) or the fitted k of z,F data.
  std::optional<std::array<double, 3>> spring_pulloff(const Parameters& p, double given);
  // Swap the data (same kind and size: bootstrap resamples), keeping the tables.
  void set_data(const Measurements& data) { data_ = &data; }
  const Measurements& data() const { return *data_; }
  const ForceModel& force_model() const { return *model_; }
  const std::vector<ParameterInfo>& names() const { return names_; }
  std::string describe(const Parameters& p) const;  // "w = .. J/m2, t = .. m, E1 = .. Pa"

 private:
  void check_range(const Parameters& p) const;
  [[noreturn]] void rethrow_at(const Parameters& p) const;

  const Measurements* data_;
  std::unique_ptr<ForceModel> model_;
  std::vector<ParameterInfo> names_;
};

}  // namespace coatcontact::fit::internal
