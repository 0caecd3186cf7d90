// The fit's model at the data points (fit_model.hpp): the parameter vector, the range checks,
// and the Jacobian around the problem's force model.
#include "fit_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {
namespace {

using coatcontact::detail::short_text;

// One film without the parameters of a model beyond w, t, E1: Problem::free names the free
// ones; otherwise Problem::free_parameters does (by index in the parameter vector).
bool free_by_index(const Problem& problem) {
  return !problem.layers.empty() || problem_parameters(problem).values.size() != kParameterCount;
}

}  // namespace

// ---- parameters -----------------------------------------------------------------------------

Parameters Parameters::branch(bool unloading) const {
  Parameters out(std::vector<double>(values.begin(), values.begin() + static_cast<long>(1 + 2 * layers)), layers);
  out.values[kWork] = unloading ? unload_work() : work();
  if (spring) {
    out.values.push_back(stiffness());
    out.spring = true;
  }
  if (md) {
    out.values.push_back(lambda());
    out.md = true;
  }
  return out;
}

double Parameters::total_thickness() const {
  double total = 0.0;
  for (std::size_t i = 0; i < layers; ++i) total += thickness(i);
  return total;
}

std::vector<Layer> problem_layers(const Problem& problem) {
  if (!problem.layers.empty()) return problem.layers;
  return {Layer{problem.thickness, problem.film}};
}

Parameters problem_parameters(const Problem& problem) {
  const std::vector<Layer> layers = problem_layers(problem);
  const std::size_t n = layers.size();
  std::vector<double> v(1 + 2 * n + (problem.hysteresis ? 1 : 0));
  v[kWork] = problem.work;
  for (std::size_t i = 0; i < n; ++i) {
    v[thickness_index(i)] = layers[i].thickness;
    v[modulus_index(i, n)] = layers[i].material.youngs_modulus;
  }
  if (problem.hysteresis) v[unload_work_index(n)] = problem.unload_work;
  if (problem.base_displacement) v.push_back(problem.spring_stiffness);
  if (problem.maugis_dugdale) v.push_back(problem.lambda);
  Parameters p(std::move(v), n, problem.hysteresis, problem.base_displacement);
  p.md = problem.maugis_dugdale;
  return p;
}

std::vector<int> free_indices(const Problem& problem) {
  std::vector<int> out;
  if (!free_by_index(problem)) {
    for (int which = 0; which < kParameterCount; ++which) {
      if (problem.free[which]) out.push_back(which);
    }
    return out;
  }
  for (std::size_t which : problem.free_parameters) out.push_back(static_cast<int>(which));
  if (out.empty() && problem.free[kWork]) out.push_back(kWork);
  std::sort(out.begin(), out.end());
  return out;
}

StackKey StackKey::of(const Parameters& p) {
  StackKey key;
  const double total = p.total_thickness();
  for (std::size_t i = 0; i < p.layers; ++i) {
    // One film: exactly 1 (the film is the unit length, as Stack::film_on has it).
    key.relative_thickness.push_back(p.layers == 1 ? 1.0 : p.thickness(i) / total);
    key.modulus.push_back(p.modulus(i));
  }
  return key;
}

Stack stack_of(const Problem& problem, const StackKey& key) {
  std::vector<Layer> layers = problem_layers(problem);
  for (std::size_t i = 0; i < layers.size(); ++i) {
    layers[i].thickness = key.relative_thickness[i];
    layers[i].material.youngs_modulus = key.modulus[i];
  }
  return Stack(layers, problem.substrate, problem.indenter);
}

std::size_t cache_capacity(const Problem& problem) {
  const Parameters p = problem_parameters(problem);
  const std::vector<ParameterInfo> names = parameter_list(p.layers, p.hysteresis, p.spring);
  std::size_t changing = 0;
  for (int which : free_indices(problem)) {
    if (names[which].kind != ParameterKind::kWork && names[which].kind != ParameterKind::kSpring &&
        names[which].kind != ParameterKind::kLambda &&
        !(which == kThickness && p.layers == 1)) {
      ++changing;
    }
  }
  return std::max<std::size_t>(4, 2 + 2 * changing);
}

// ---- the model at the data ------------------------------------------------------------------

Model::Model(const Problem& problem, const Measurements& data) : data_(&data), model_(make_force_model(problem)) {
  const Parameters p = problem_parameters(problem);
  names_ = parameter_list(p.layers, p.hysteresis, p.spring, p.md);
}

void Model::check_range(const Parameters& p) const {
  for (std::size_t which = 0; which < p.values.size(); ++which) {
    const double v = p.values[which];
    const ParameterInfo& info = names_[which];
    if (info.kind == ParameterKind::kWork && !(v >= kWorkRange[0] && v <= kWorkRange[1])) {
      throw NumericalError(info.name + " ran to " + short_text(v) + " J/m2, outside [" + short_text(kWorkRange[0]) +
                           ", " + short_text(kWorkRange[1]) + "]: the data do not determine " + info.name);
    }
    if (info.kind == ParameterKind::kModulus && !(v >= kModulusRange[0] && v <= kModulusRange[1])) {
      throw NumericalError(info.name + " ran to " + short_text(v) + " Pa, outside [" + short_text(kModulusRange[0]) +
                           ", " + short_text(kModulusRange[1]) + "]: the data do not determine " + info.name);
    }
  }
  for (std::size_t which = 0; which < p.values.size(); ++which) {
    const double v = p.values[which];
    const ParameterInfo& info = names_[which];
    if (info.kind == ParameterKind::kLambda && !(v >= kMinimumLambda && v <= kMaximumLambda)) {
      throw NumericalError("lambda ran to " + short_text(v) + ", outside [" + short_text(kMinimumLambda) + ", " +
                           short_text(kMaximumLambda) + "]: the data do not determine lambda");
    }
    if (info.kind == ParameterKind::kSpring && (!(v > 0.0) || !std::isfinite(v))) {
      throw NumericalError("k ran to " + short_text(v) + " N/m: the data do not determine the spring stiffness k");
    }
    if (info.kind == ParameterKind::kThickness && (!(v > 0.0) || !std::isfinite(v))) {
      throw NumericalError(info.name + " ran to " + short_text(v) + " m: the data do not determine " + info.name);
    }
  }
}

std::string Model::describe(const Parameters& p) const {
  std::string text;
  for (std::size_t which = 0; which < p.values.size(); ++which) {
    text += (text.empty() ? "" : ", ") + names_[which].name + " = " + short_text(p.values[which]) + " " +
            names_[which].unit;
  }
  return text;
}

void Model::rethrow_at(const Parameters& p) const {
  std::string what;
  try {
    throw;
  } catch (const std::exception& error) {
    what = error.what();
  }
  throw NumericalError("model evaluation failed at " + describe(p) + " (" + what +
                       "); if the fit wandered there, try start values closer to the solution");
}

ModelAtData Model::at_data(const Parameters& p, bool with_pulloff) {
  check_range(p);
  coatcontact::detail::GslHandlerOff handler_off;
  try {
    return model_->evaluate(p, *data_, with_pulloff);
  } catch (const std::exception&) {
    rethrow_at(p);
  }
}

std::vector<std::vector<double>> Model::force_derivatives(const Parameters& p, const ModelAtData& m,
                                                          const std::vector<int>& which) {
  const std::size_t n = m.radius.size();
  std::vector<std::vector<double>> columns;
  for (int parameter : which) {
    const auto index = static_cast<std::size_t>(parameter);
    if (auto column = model_->analytic_column(p, m, *data_, index)) {
      columns.push_back(std::move(*column));
      continue;
    }
    std::vector<double> column(n, 0.0);
    for (double sign : {1.0, -1.0}) {
      Parameters q = p;
      q.values[index] *= std::exp(sign * kStep);
      check_range(q);
      coatcontact::detail::GslHandlerOff handler_off;
      try {
        const std::vector<double> shifted = model_->shifted_force(q, m, *data_);
        for (std::size_t i = 0; i < n; ++i) column[i] += sign * shifted[i] / (2.0 * kStep);
      } catch (const std::exception&) {
        rethrow_at(q);
      }
    }
    columns.push_back(std::move(column));
  }
  return columns;
}

std::optional<std::array<double, 3>> Model::spring_pulloff(const Parameters& p, double given) {
  return model_->spring_pulloff(p, model_->reported_spring(p, given));
}

double Model::interpolation_error(const Parameters& p, const ModelAtData& m) {
  return model_->interpolation_error(p, m, *data_);
}

}  // namespace coatcontact::fit::internal
