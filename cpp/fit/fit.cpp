// The public fit API (fit.hpp): validation, then model (fit_model.cpp), least squares
// (least_squares.cpp) and statistics (statistics.cpp).
#include "coatcontact/fit.hpp"

#include <gsl/gsl_rng.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "fit_model.hpp"
#include "sphere_model.hpp"
#include "least_squares.hpp"
#include "search.hpp"
#include "statistics.hpp"

namespace coatcontact::fit {
namespace {

using coatcontact::detail::short_text;
using internal::ContactModel;
using internal::Parameters;

using detail::kPi;
// Load-controlled JKR pull-off in Maugis units, P = F/(pi w R) (THEORY.md section 6).
constexpr double kJkrPulloffLoad = -1.5;
// Effective-variance passes: the weights depend on the slope at the solution; a change of
// their logarithm below kWeightChange moves the estimates far less than their errors.
constexpr int kWeightPasses = 5;
constexpr double kWeightChange = 1e-3;
// A second grid minimum is polished when its cost is within this factor of the best one's,
// and reported when it ends more than kDistinctMinimum apart in some ln p.
constexpr double kSecondCostRatio = 3.0;
constexpr double kDistinctMinimum = 0.05;
constexpr double kMaxDataValue = 1e100;  // SI

void validate(const Measurements& data, const Problem& problem) {
  const std::size_t n = data.size();
  if (data.abscissa.size() != n) throw InputError("fit: abscissa and force columns differ in length");
  if (!problem.shape && (!(problem.sphere_radius > 0.0) || !std::isfinite(problem.sphere_radius))) {
    throw InputError("sphere radius must be > 0 (got " + short_text(problem.sphere_radius) + ")");
  }
  internal::validate_model(data, problem);
  // Validates the constants.
  if (problem.layers.empty()) {
    Stack::film_on(problem.film, problem.substrate, problem.indenter);
  } else {
    Stack(problem.layers, problem.substrate, problem.indenter);
  }
  {
    const std::size_t layer_count = problem.layers.empty() ? 1 : problem.layers.size();
    const std::size_t count = internal::problem_parameters(problem).values.size();
    for (std::size_t which : problem.free_parameters) {
      if (which >= count) {
        throw InputError("fit: free parameter index " + std::to_string(which) + " is outside the " +
                         std::to_string(count) + " parameters of a " + std::to_string(layer_count) +
                         "-layer stack");
      }
    }
    if (std::set<std::size_t>(problem.free_parameters.begin(), problem.free_parameters.end()).size() !=
        problem.free_parameters.size()) {
      throw InputError("fit: a free parameter is named twice");
    }
  }
  if (!(problem.spring_stiffness >= 0.0) || !std::isfinite(problem.spring_stiffness)) {
    throw InputError("spring stiffness must be finite and >= 0 (got " + short_text(problem.spring_stiffness) + ")");
  }
  if (problem.bootstrap < 0 || problem.bootstrap > 100000) {
    throw InputError("bootstrap: the number of resamples must be in [0, 100000] (got " +
                     std::to_string(problem.bootstrap) + ")");
  }
  for (const auto* sigma : {&data.sigma_abscissa, &data.sigma_force}) {
    if (!sigma->empty() && sigma->size() != n) throw InputError("fit: a sigma column differs in length from the data");
    for (std::size_t i = 0; i < sigma->size(); ++i) {
      if (!((*sigma)[i] >= 0.0) || !std::isfinite((*sigma)[i])) {
        const std::string where = data.line_numbers.size() == n ? "line " + std::to_string(data.line_numbers[i])
                                                                : "point " + std::to_string(i + 1);
        throw InputError(where + ": an uncertainty must be finite and >= 0 (got " + short_text((*sigma)[i]) + ")");
      }
    }
  }
  check_tolerance(problem.solver_tolerance);
  if (problem.layers.empty() && (!(problem.thickness > 0.0) || !std::isfinite(problem.thickness))) {
    throw InputError("film thickness must be > 0 (got " + short_text(problem.thickness) + ")");
  }
  if (!(problem.work > 0.0) || !std::isfinite(problem.work)) {
    throw InputError("adhesion energy must be > 0 (got " + short_text(problem.work) + ")");
  }
  double largest_force = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string where = data.line_numbers.size() == n ? "line " + std::to_string(data.line_numbers[i])
                                                            : "point " + std::to_string(i + 1);
    if (!std::isfinite(data.abscissa[i]) || !std::isfinite(data.force[i])) {
      throw InputError(where + ": the data point is not finite");
    }
    // Far beyond any measurement (the CLI's SI bound for every value): refused with its line,
    // not met as a search that finds nothing.
    if (std::fabs(data.abscissa[i]) > kMaxDataValue || std::fabs(data.force[i]) > kMaxDataValue) {
      throw InputError(where + ": " + short_text(data.abscissa[i]) + ", " + short_text(data.force[i]) +
                       " is outside the allowed range [-1e100, 1e100] (SI units)");
    }
    if (data.kind == DataKind::kRadiusForce && !(data.abscissa[i] > 0.0)) {
      throw InputError(where + ": contact radius must be > 0 (got " + short_text(data.abscissa[i]) + ")");
    }
    largest_force = std::max(largest_force, std::fabs(data.force[i]));
  }
  if (!(largest_force > 0.0)) throw InputError("all measured forces are zero: nothing to fit");
}

Result fit_validated(const Measurements& data, const Problem& problem);

}  // namespace

const char* parameter_name(int parameter) {
  switch (parameter) {
    case kWork: return "w";
    case kThickness: return "t";
    case kFilmModulus: return "E1";
    default: return "?";
  }
}

std::vector<ParameterInfo> parameter_list(std::size_t layers, bool hysteresis, bool spring, bool lambda) {
  std::vector<ParameterInfo> list;
  list.push_back({ParameterKind::kWork, 0, hysteresis ? "w_load" : "w", "J/m2"});
  for (std::size_t i = 0; i < layers; ++i) {
    list.push_back({ParameterKind::kThickness, i, layers == 1 ? "t" : "h" + std::to_string(i + 1), "m"});
  }
  for (std::size_t i = 0; i < layers; ++i) {
    list.push_back({ParameterKind::kModulus, i, "E" + std::to_string(i + 1), "Pa"});
  }
  if (hysteresis) list.push_back({ParameterKind::kWork, 0, "w_unload", "J/m2"});
  if (spring) list.push_back({ParameterKind::kSpring, 0, "k", "N/m"});
  if (lambda) list.push_back({ParameterKind::kLambda, 0, "lambda", ""});  // dimensionless
  return list;
}

std::vector<bool> unloading_by_order(const Measurements& data) {
  std::vector<bool> out(data.size(), false);
  if (data.size() == 0) return out;
  const std::size_t top = static_cast<std::size_t>(
      std::max_element(data.abscissa.begin(), data.abscissa.end()) - data.abscissa.begin());
  for (std::size_t i = top + 1; i < data.size(); ++i) out[i] = true;
  return out;
}

Measurements select_branch(const Measurements& data, Branch branch) {
  if (branch == Branch::kAll || data.size() == 0) return data;
  const std::size_t top = static_cast<std::size_t>(
      std::max_element(data.abscissa.begin(), data.abscissa.end()) - data.abscissa.begin());
  const std::size_t begin = branch == Branch::kLoading ? 0 : top;
  const std::size_t end = branch == Branch::kLoading ? top + 1 : data.size();
  Measurements out;
  out.kind = data.kind;
  out.abscissa.assign(data.abscissa.begin() + begin, data.abscissa.begin() + end);
  out.force.assign(data.force.begin() + begin, data.force.begin() + end);
  if (data.line_numbers.size() == data.size()) {
    out.line_numbers.assign(data.line_numbers.begin() + begin, data.line_numbers.begin() + end);
  }
  if (!data.sigma_abscissa.empty()) {
    out.sigma_abscissa.assign(data.sigma_abscissa.begin() + begin, data.sigma_abscissa.begin() + end);
  }
  if (!data.sigma_force.empty()) out.sigma_force.assign(data.sigma_force.begin() + begin, data.sigma_force.begin() + end);
  if (!data.unloading.empty()) out.unloading.assign(data.unloading.begin() + begin, data.unloading.begin() + end);
  return out;
}

double jkr_work_estimate(const Measurements& data, double sphere_radius) {
  if (data.force.empty()) return kDefaultStartWork;
  const double f_min = *std::min_element(data.force.begin(), data.force.end());
  // F_min = kJkrPulloffLoad * (pi w R), the force scale of Contact.
  return f_min < 0.0 ? f_min / (kJkrPulloffLoad * kPi * sphere_radius) : kDefaultStartWork;
}

double start_work(const Measurements& data, const Problem& problem) {
  return problem.shape ? kDefaultStartWork : jkr_work_estimate(data, problem.sphere_radius);
}

std::string units_hint(const Measurements& data, const Problem& problem) {
  if (problem.shape || data.force.empty() || !(problem.sphere_radius > 0.0)) return "";
  const double f_min = *std::min_element(data.force.begin(), data.force.end());
  if (!(f_min < 0.0)) return "";
  const double work = jkr_work_estimate(data, problem.sphere_radius);
  if (work >= kSearchWork[0] && work <= kSearchWork[1]) return "";
  return "the most tensile force, F = " + short_text(f_min) + " N, needs w = " + short_text(work) +
         " J/m2 for a sphere of R = " + short_text(problem.sphere_radius) +
         " m (JKR pull-off F = -(3/2) pi w R), outside the plausible [" + short_text(kSearchWork[0]) + ", " +
         short_text(kSearchWork[1]) + "] J/m2: are the units of F and R right?";
}

void check_start(const Measurements& data, const Problem& problem) {
  const Parameters hint = internal::problem_parameters(problem);
  const std::vector<ParameterInfo> names =
      parameter_list(hint.layers, hint.hysteresis, hint.spring, hint.md);
  const std::string hint_text = units_hint(data, problem);
  for (std::size_t which = 0; which < names.size(); ++which) {
    const double v = hint.values[which];
    if (names[which].kind == ParameterKind::kWork && !(v >= kWorkRange[0] && v <= kWorkRange[1])) {
      throw StartError(which, names[which].name + " = " + short_text(v) + " J/m2 is outside the range the fit explores, [" +
                                  short_text(kWorkRange[0]) + ", " + short_text(kWorkRange[1]) + "] J/m2" +
                                  (hint_text.empty() ? "" : "; " + hint_text));
    }
    if (names[which].kind == ParameterKind::kModulus && !(v >= kModulusRange[0] && v <= kModulusRange[1])) {
      throw StartError(which, names[which].name + " = " + short_text(v) + " Pa is outside the range the fit explores, [" +
                                  short_text(kModulusRange[0]) + ", " + short_text(kModulusRange[1]) + "] Pa");
    }
  }
  if (data.kind == DataKind::kRadiusForce && data.size() > 0) {
    const auto [lo, hi] = std::minmax_element(data.abscissa.begin(), data.abscissa.end());
    const double total = hint.total_thickness();
    const double a_lo = *lo / total, a_hi = *hi / total;
    if (!(a_lo >= kAOverTRange[0] && a_hi <= kAOverTRange[1])) {
      throw StartError(thickness_index(0),
                       std::string(hint.layers == 1 ? "t" : "T") + " = " + short_text(total) +
                           " m puts the data's contact radii (" + short_text(*lo) + " to " + short_text(*hi) +
                           " m) at a/t = " + short_text(a_lo) + " to " + short_text(a_hi) + ", outside the range [" +
                           short_text(kAOverTRange[0]) + ", " + short_text(kAOverTRange[1]) +
                           "] the model is tabulated for; allowed: t in [" + short_text(*hi / kAOverTRange[1]) + ", " +
                           short_text(*lo / kAOverTRange[0]) + "] m");
    }
  }
}

Result fit(const Measurements& data, const Problem& problem) {
  validate(data, problem);
  const std::size_t n = data.size();
  const std::size_t p_count = internal::free_indices(problem).size();
  if (p_count == 0) {
    throw InputError(problem.layers.empty() ? "no free parameter: name at least one of w, t, E1"
                                            : "no free parameter: name at least one of w, h1..hN, E1..EN");
  }
  if (n <= p_count) {
    throw InputError(std::to_string(n) + " data point" + (n == 1 ? "" : "s") + " for " +
                     std::to_string(p_count) + " free parameter" + (p_count == 1 ? "" : "s") +
                     ": a fit needs more points than free parameters");
  }
  // A contact radius at or above R is no sphere contact: almost always a length in the wrong unit.
  for (std::size_t i = 0; i < n && data.kind == DataKind::kRadiusForce && !problem.shape; ++i) {
    if (data.abscissa[i] >= problem.sphere_radius) {
      const std::string where = data.line_numbers.size() == n ? "line " + std::to_string(data.line_numbers[i])
                                                              : "point " + std::to_string(i + 1);
      throw InputError(where + ": contact radius a = " + short_text(data.abscissa[i]) +
                       " m is not below the sphere radius R = " + short_text(problem.sphere_radius) +
                       " m: are the units right? (lengths in m, forces in N)");
    }
  }
  check_start(data, problem);
  try {
    return fit_validated(data, problem);
  } catch (const NumericalError& error) {
    const std::string hint_text = units_hint(data, problem);
    if (hint_text.empty()) throw;
    throw NumericalError(std::string(error.what()) + "; " + hint_text);
  }
}

namespace {
// Residual bootstrap: resample the standardized residuals (centred, inflated by sqrt(n/(n-p))
// for the fitted degrees of freedom), refit from the estimate with the same weights, take
// percentiles into result's intervals.
void bootstrap(internal::Model& model, const Measurements& data, const Problem& problem,
               const std::vector<int>& free_index, const Parameters& estimate, const std::vector<double>& model_force,
               const std::vector<double>& final_scale, Result& result) {
  const std::size_t n = data.size();
  const std::size_t p_count = free_index.size();
  const std::size_t parameter_count = estimate.values.size();
  std::vector<double> e(n);
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    e[i] = result.residual[i] * final_scale[i];
    mean += e[i] / static_cast<double>(n);
  }
  const double inflate = std::sqrt(static_cast<double>(n) / static_cast<double>(n - p_count));
  for (double& x : e) x = (x - mean) * inflate;
  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> rng(gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free);
  gsl_rng_set(rng.get(), problem.bootstrap_seed);
  Measurements resampled = data;
  model.set_data(resampled);
  std::vector<std::vector<double>> samples(parameter_count);
  for (int b = 0; b < problem.bootstrap; ++b) {
    for (std::size_t i = 0; i < n; ++i) {
      resampled.force[i] = model_force[i] - e[gsl_rng_uniform_int(rng.get(), n)] / final_scale[i];
    }
    try {
      const internal::Minimum r = internal::minimize(model, problem, free_index, estimate, final_scale, false);
      for (int which : free_index) samples[which].push_back(r.values.values[which]);
      ++result.bootstrap_samples;
    } catch (const NumericalError&) {
      // A resample the fit cannot follow does not count (bootstrap_samples says how many did).
    }
  }
  model.set_data(data);
  if (result.bootstrap_samples < std::max(10, problem.bootstrap / 2)) {
    throw NumericalError("bootstrap: only " + std::to_string(result.bootstrap_samples) + " of " +
                         std::to_string(problem.bootstrap) + " refits converged; the intervals would mean nothing");
  }
  const auto percentile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double position = q * static_cast<double>(v.size() - 1);
    const std::size_t k = static_cast<std::size_t>(position);
    const double f = position - static_cast<double>(k);
    return k + 1 < v.size() ? v[k] * (1.0 - f) + v[k + 1] * f : v[k];
  };
  for (auto* v : {&result.interval68_low, &result.interval68_high, &result.interval95_low, &result.interval95_high}) {
    v->assign(parameter_count, 0.0);
  }
  for (int which : free_index) {
    result.interval68_low[which] = percentile(samples[which], 0.16);
    result.interval68_high[which] = percentile(samples[which], 0.84);
    result.interval95_low[which] = percentile(samples[which], 0.025);
    result.interval95_high[which] = percentile(samples[which], 0.975);
  }
}

Result fit_validated(const Measurements& data, const Problem& problem) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::size_t n = data.size();
  const std::vector<int> free_index = internal::free_indices(problem);
  const std::size_t p_count = free_index.size();

  internal::Model model(problem, data);
  const Parameters hint = internal::problem_parameters(problem);
  const std::size_t parameter_count = hint.values.size();
  internal::SearchResult search;
  search.best = hint;
  if (problem.global_search) search = internal::global_search(model, free_index, hint);
  const double search_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();

  // Unweighted: one constant scale (any gives the same estimates; this one keeps GSL's
  // tolerances meaningful). Weighted: 1/sigma_eff from the model's slope, refreshed at each
  // solution until it no longer moves (the effective-variance iteration).
  const bool weighted = !data.sigma_force.empty() || !data.sigma_abscissa.empty();
  double largest_force = 0.0;
  for (double f : data.force) largest_force = std::max(largest_force, std::fabs(f));
  std::vector<double> scale(n, 1.0 / largest_force);
  if (weighted) scale = internal::inverse_sigma(data, model.at_data(search.best));
  internal::Minimum minimum;
  Parameters start = search.best;
  int iterations = 0;
  for (int pass = 0; pass < kWeightPasses; ++pass) {
    minimum = internal::minimize(model, problem, free_index, start, scale, !problem.global_search);
    iterations += minimum.iterations;
    if (!weighted) break;
    const std::vector<double> next = internal::inverse_sigma(data, model.at_data(minimum.values));
    double change = 0.0;
    for (std::size_t i = 0; i < n; ++i) change = std::max(change, std::fabs(std::log(next[i] / scale[i])));
    scale = next;
    start = minimum.values;
    if (change < kWeightChange) break;
  }
  minimum.iterations = iterations;

  Result result;
  result.search_evaluations = search.evaluations;
  result.search_seconds = search_seconds;
  result.iterations = minimum.iterations;
  result.converged = true;
  result.stop_reason = minimum.stop_reason;
  result.points = n;
  result.free_count = static_cast<int>(p_count);
  result.parameters = model.names();
  result.free.assign(parameter_count, false);
  for (int which : free_index) result.free[static_cast<std::size_t>(which)] = true;
  result.value = minimum.values.values;
  const internal::ModelAtData m = model.at_data(minimum.values, true);
  const auto jacobian = model.force_derivatives(minimum.values, m, free_index);
  const std::vector<double> inv_sigma = weighted ? internal::inverse_sigma(data, m) : std::vector<double>{};
  internal::fill_statistics(data, m.force, jacobian, free_index, inv_sigma, result);
  result.sigma_effective.clear();
  for (double u : inv_sigma) result.sigma_effective.push_back(1.0 / u);
  if (m.has_load_pulloff) {
    result.has_load_pulloff = true;
    result.load_pulloff_radius = m.load_pulloff_radius;
    result.load_pulloff_penetration = m.load_pulloff_penetration;
    result.load_pulloff_force = m.load_pulloff_force;
  }
  const std::vector<double> final_scale = weighted ? inv_sigma : scale;
  if (problem.spring_stiffness > 0.0) {
    try {
      // z,F data: through the fitted (or fixed) k of the parameter vector (Model::spring_pulloff).
      if (const auto s = model.spring_pulloff(minimum.values, problem.spring_stiffness)) {
        result.has_spring_pulloff = true;
        result.spring_pulloff_radius = (*s)[0];
        result.spring_pulloff_penetration = (*s)[1];
        result.spring_pulloff_force = (*s)[2];
      }
    } catch (const NumericalError&) {
      // Reported as absent (the header says so); the fit itself stands.
    }
  }

  // A second local minimum of the search, polished: reported when it stays apart from the best.
  if (search.has_second && search.second_cost <= kSecondCostRatio * search.best_cost) {
    try {
      const internal::Minimum other = internal::minimize(model, problem, free_index, search.second, final_scale, false);
      double distance = 0.0;
      for (int which : free_index) {
        distance = std::max(distance, std::fabs(std::log(other.values.values[which] / result.value[which])));
      }
      if (distance > kDistinctMinimum && other.cost >= minimum.cost) {
        result.second_minimum = true;
        result.second_value = other.values.values;
        result.second_cost_ratio = other.cost / minimum.cost;
      }
    } catch (const NumericalError&) {
      // No second solution there.
    }
  }

  if (problem.bootstrap > 0) {
    bootstrap(model, data, problem, free_index, minimum.values, m.force, final_scale, result);
  }
  result.model_radius = m.radius;
  result.model_penetration = m.penetration;
  result.model_force = m.force;
  result.clamped = m.clamped;
  if (m.has_pulloff) {
    result.displacement_pulloff_radius = m.pulloff_radius;
    result.displacement_pulloff_penetration = m.pulloff_penetration;
    result.displacement_pulloff_force = m.pulloff_force;
  }
  result.interpolation_error = model.interpolation_error(minimum.values, m);
  result.solver_tolerance = problem.solver_tolerance;
  result.solver_calls = model.solver_calls();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace

CurvePoint exact_point(const Problem& problem, double radius) {
  if (problem.shape) throw InputError("exact_point: the sphere only (a shape's model is ShapeContact::at)");
  const Parameters p = internal::problem_parameters(problem);
  if (!(radius > 0.0) || !(p.total_thickness() > 0.0)) throw InputError("exact_point: a and t must be > 0");
  coatcontact::detail::GslHandlerOff handler_off;
  const internal::SphereEntry entry(problem, internal::StackKey::of(p));
  const ContactModel contact(entry.model(), problem.sphere_radius, p);
  const SolverSource source(entry.solver(), problem.solver_tolerance);
  const internal::SiPoint s = contact.exact(source.evaluate({radius / p.total_thickness()}).front(), radius);
  return {radius, s.penetration, s.force};
}

std::vector<CurvePoint> model_curve(const Problem& problem, double radius_min, double radius_max,
                                    int count) {
  if (!(radius_min > 0.0) || !(radius_max >= radius_min) || count < 2) {
    throw InputError("model_curve: need 0 < a_min <= a_max and at least 2 points");
  }
  if (problem.shape) throw InputError("model_curve: the sphere only (a shape's curve is ShapeContact::curve)");
  coatcontact::detail::GslHandlerOff handler_off;
  const Parameters p = internal::problem_parameters(problem);
  const internal::SphereEntry entry(problem, internal::StackKey::of(p));
  const ContactModel contact(entry.model(), problem.sphere_radius, p);
  contact.prepare(radius_min, radius_max);
  std::vector<CurvePoint> curve;
  for (double a : log_spaced(radius_min, radius_max, static_cast<std::size_t>(count))) {
    const internal::SiPoint s = contact.at(a);
    curve.push_back({a, s.penetration, s.force});
  }
  return curve;
}

}  // namespace coatcontact::fit
