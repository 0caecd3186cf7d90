// The public fit API (fit.hpp): validation, then model (fit_model.cpp), least squares
// (least_squares.cpp) and statistics (statistics.cpp).
#include "coatcontact/fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "fit_model.hpp"
#include "least_squares.hpp"
#include "statistics.hpp"

namespace coatcontact::fit {
namespace {

using coatcontact::detail::short_text;
using internal::ContactModel;
using internal::Parameters;

constexpr double kPi = 3.14159265358979323846;
// Load-controlled JKR pull-off in Maugis units, P = F/(pi w R) (THEORY.md section 6).
constexpr double kJkrPulloffLoad = -1.5;
constexpr double kDefaultWork = 0.05;  // J/m2, when no measured force is tensile

void validate(const Measurements& data, const Problem& problem) {
  const std::size_t n = data.size();
  if (data.abscissa.size() != n) throw InputError("fit: abscissa and force columns differ in length");
  if (!(problem.sphere_radius > 0.0) || !std::isfinite(problem.sphere_radius)) {
    throw InputError("sphere radius must be > 0 (got " + short_text(problem.sphere_radius) + ")");
  }
  Stack::film_on(problem.film, problem.substrate);  // validates the constants
  check_tolerance(problem.solver_tolerance);
  if (!(problem.thickness > 0.0) || !std::isfinite(problem.thickness)) {
    throw InputError("film thickness must be > 0 (got " + short_text(problem.thickness) + ")");
  }
  if (!(problem.work > 0.0) || !std::isfinite(problem.work)) {
    throw InputError("adhesion energy must be > 0 (got " + short_text(problem.work) + ")");
  }
  double largest_force = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(data.abscissa[i]) || !std::isfinite(data.force[i])) {
      throw InputError("data point " + std::to_string(i + 1) + " is not finite");
    }
    if (data.kind == DataKind::kRadiusForce && !(data.abscissa[i] > 0.0)) {
      const std::string where = data.line_numbers.size() == n
                                    ? "line " + std::to_string(data.line_numbers[i])
                                    : "point " + std::to_string(i + 1);
      throw InputError(where + ": contact radius must be > 0 (got " + short_text(data.abscissa[i]) + ")");
    }
    largest_force = std::max(largest_force, std::fabs(data.force[i]));
  }
  if (!(largest_force > 0.0)) throw InputError("all measured forces are zero: nothing to fit");
}

}  // namespace

const char* parameter_name(int parameter) {
  switch (parameter) {
    case kWork: return "w";
    case kThickness: return "t";
    case kFilmModulus: return "E1";
    default: return "?";
  }
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
  return out;
}

double jkr_work_estimate(const Measurements& data, double sphere_radius) {
  if (data.force.empty()) return kDefaultWork;
  const double f_min = *std::min_element(data.force.begin(), data.force.end());
  // F_min = kJkrPulloffLoad * (pi w R), the force scale of Contact.
  return f_min < 0.0 ? f_min / (kJkrPulloffLoad * kPi * sphere_radius) : kDefaultWork;
}

Result fit(const Measurements& data, const Problem& problem) {
  const auto clock_start = std::chrono::steady_clock::now();
  validate(data, problem);
  const std::size_t n = data.size();
  std::vector<int> free_index;
  for (int which = 0; which < kParameterCount; ++which) {
    if (problem.free[which]) free_index.push_back(which);
  }
  const std::size_t p_count = free_index.size();
  if (p_count == 0) throw InputError("no free parameter: name at least one of w, t, E1");
  if (n <= p_count) {
    throw InputError(std::to_string(n) + " data point" + (n == 1 ? "" : "s") + " for " +
                     std::to_string(p_count) + " free parameter" + (p_count == 1 ? "" : "s") +
                     ": a fit needs more points than free parameters");
  }

  internal::Model model(problem, data);
  const internal::Minimum minimum = internal::minimize(model, data, problem, free_index);

  Result result;
  result.iterations = minimum.iterations;
  result.converged = true;
  result.stop_reason = minimum.stop_reason;
  result.points = n;
  result.free_count = static_cast<int>(p_count);
  result.free = problem.free;
  result.value = minimum.values.as_array();
  const internal::ModelAtData m = model.at_data(minimum.values, true);
  const auto jacobian = model.force_derivatives(minimum.values, m, free_index);
  internal::fill_statistics(data, m.force, jacobian, free_index, result);
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

CurvePoint exact_point(const Problem& problem, double radius) {
  if (!(radius > 0.0) || !(problem.thickness > 0.0)) throw InputError("exact_point: a and t must be > 0");
  coatcontact::detail::GslHandlerOff handler_off;
  const internal::ModelEntry entry(problem, problem.film.youngs_modulus);
  const Parameters p{problem.work, problem.thickness, problem.film.youngs_modulus};
  const ContactModel contact(entry.model(), problem.sphere_radius, p);
  const SolverSource source(entry.solver(), problem.solver_tolerance);
  const internal::SiPoint s = contact.exact(source.evaluate({radius / problem.thickness}).front(), radius);
  return {radius, s.penetration, s.force};
}

std::vector<CurvePoint> model_curve(const Problem& problem, double radius_min, double radius_max,
                                    int count) {
  if (!(radius_min > 0.0) || !(radius_max >= radius_min) || count < 2) {
    throw InputError("model_curve: need 0 < a_min <= a_max and at least 2 points");
  }
  coatcontact::detail::GslHandlerOff handler_off;
  const internal::ModelEntry entry(problem, problem.film.youngs_modulus);
  const Parameters p{problem.work, problem.thickness, problem.film.youngs_modulus};
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
