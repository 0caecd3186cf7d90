// The force models' common ground (force_model.hpp): the interface's defaults, the helpers the
// models share, and make_force_model, the one place that reads the Problem's choice of model.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "force_model.hpp"

namespace coatcontact::fit::internal {

std::unique_ptr<ForceModel> make_spring_model(const Problem& problem);       // spring_model.cpp
std::unique_ptr<ForceModel> make_shape_model(const Problem& problem);        // shape_model.cpp
std::unique_ptr<ForceModel> make_maugis_dugdale_model(const Problem& problem);  // maugis_dugdale_fit.cpp
std::unique_ptr<ForceModel> make_branch_model(std::unique_ptr<ForceModel> inner);  // branch_model.cpp
std::unique_ptr<ForceModel> make_sphere_model(const Problem& problem);       // sphere_model.cpp

namespace {
using coatcontact::detail::short_text;
}  // namespace

void validate_model(const Measurements& data, const Problem& problem) {
  const std::size_t n = data.size();
  if (problem.hysteresis) {
    if (data.unloading.size() != n) throw InputError("fit: w_load,w_unload need the branch of every point");
    const auto unloading_points = static_cast<std::size_t>(std::count(data.unloading.begin(), data.unloading.end(), true));
    if (unloading_points == 0 || unloading_points == n) {
      throw InputError(std::string("w_load,w_unload: the data have no ") + (unloading_points == 0 ? "unloading" : "loading") +
                       " rows; each adhesion energy needs points of its own branch");
    }
    if (!(problem.unload_work > 0.0) || !std::isfinite(problem.unload_work)) {
      throw InputError("adhesion energy of unloading must be > 0 (got " + short_text(problem.unload_work) + ")");
    }
    const std::size_t w_unload = unload_work_index(problem.layers.empty() ? 1 : problem.layers.size());
    const auto named = [&](std::size_t which) {
      return std::find(problem.free_parameters.begin(), problem.free_parameters.end(), which) != problem.free_parameters.end();
    };
    if (!named(kWork) || !named(w_unload)) throw InputError("fit: w_load and w_unload are free together");
  }
  if (problem.maugis_dugdale) {
    if (data.kind != DataKind::kRadiusForce) throw InputError("fit: the Maugis-Dugdale model fits a,F data only");
    if (problem.shape || problem.base_displacement || problem.hysteresis || !problem.indenter.rigid) {
      throw InputError("fit: the Maugis-Dugdale model takes a rigid sphere, one w and a,F data");
    }
    if (!(problem.lambda >= kMinimumLambda && problem.lambda <= kMaximumLambda)) {
      throw InputError("fit: lambda = " + short_text(problem.lambda) + " is outside [" + short_text(kMinimumLambda) +
                       ", " + short_text(kMaximumLambda) + "]");
    }
  }
  if (problem.base_displacement) {
    if (data.kind != DataKind::kPenetrationForce) {
      throw InputError("fit: base-displacement data are z,F data (the penetration kind)");
    }
    if (problem.shape) throw InputError("fit: base-displacement (z,F) data with a shape are not supported");
    if (!(problem.spring_stiffness > 0.0) || !std::isfinite(problem.spring_stiffness)) {
      throw InputError("fit: z,F data need the spring stiffness k > 0 (got " + short_text(problem.spring_stiffness) + ")");
    }
  }
}

std::unique_ptr<ForceModel> make_force_model(const Problem& problem) {
  std::unique_ptr<ForceModel> model = problem.maugis_dugdale     ? make_maugis_dugdale_model(problem)
                                      : problem.shape             ? make_shape_model(problem)
                                      : problem.base_displacement ? make_spring_model(problem)
                                                                  : make_sphere_model(problem);
  if (problem.hysteresis) model = make_branch_model(std::move(model));
  return model;
}

// ---- the interface's defaults -----------------------------------------------------------------

std::optional<std::vector<double>> ForceModel::analytic_column(const Parameters&, const ModelAtData& m,
                                                               const Measurements&, std::size_t parameter) const {
  // At fixed a (at fixed measured delta along the residual's path) from the law: ModelAtData.
  if (parameter == static_cast<std::size_t>(kWork)) return m.force_lnw;
  return std::nullopt;
}

std::optional<std::array<double, 3>> ForceModel::spring_pulloff(const Parameters&, double) { return std::nullopt; }

double ForceModel::reported_spring(const Parameters&, double given) const { return given; }

double ForceModel::interpolation_error(const Parameters&, const ModelAtData&, const Measurements&) { return 0.0; }

bool ForceModel::work_separates() const { return true; }

std::vector<std::size_t> ForceModel::work_parameters(const Parameters&) const {
  return {static_cast<std::size_t>(kWork)};
}

std::vector<std::size_t> ForceModel::work_parameter_of_points(const Parameters&, const Measurements& data) const {
  return std::vector<std::size_t>(data.size(), static_cast<std::size_t>(kWork));
}

void ForceModel::add_search_axes(const Parameters&, const std::vector<int>&, std::vector<SearchAxis>&) const {}

// ---- shared helpers ---------------------------------------------------------------------------

std::vector<double> log_axis(double lo, double hi, double per_decade) {
  const int count = std::max(2, static_cast<int>(std::ceil(per_decade * std::log10(hi / lo))) + 1);
  std::vector<double> axis;
  for (int k = 0; k < count; ++k) axis.push_back(lo * std::pow(hi / lo, k / static_cast<double>(count - 1)));
  return axis;
}

void check_a_over_t(double radius, double total_thickness) {
  const double x = radius / total_thickness;
  if (!(x >= kAOverTRange[0] && x <= kAOverTRange[1])) {
    throw NumericalError("the model needs a/t = " + short_text(x) + ", outside [" + short_text(kAOverTRange[0]) + ", " +
                         short_text(kAOverTRange[1]) + "]");
  }
}

// Brent root of f on [lo, hi] (f(lo) < 0 <= f(hi)).
double find_root(const std::function<double(double)>& f, double lo, double hi) {
  if (f(hi) == 0.0) return hi;
  const auto found = detail::brent_root(f, lo, hi, {0.0, 1e-13, 200});
  if (!found) throw NumericalError("could not bracket a measured penetration on the model curve");
  if (!found->converged) throw NumericalError("root finder on the model curve did not converge");
  return found->x;
}

}  // namespace coatcontact::fit::internal
