// Physics-aware checks of the CLI (see checks.hpp).
#include "checks.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::cli {
namespace {

std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Solver evaluations per decade of a/t in the interpolation table (TableOptions::order + 1).
constexpr double kEvaluationsPerDecade = 25.0;

}  // namespace

double plan_table_work(const ReducedSolver& solver, double tolerance, double a_over_t_min,
                       double a_over_t_max, const std::string& options) {
  double total = 0.0, slowest = 0.0;
  for (double a : {a_over_t_min, a_over_t_max}) {
    const auto start = std::chrono::steady_clock::now();
    try {
      solver.solve(a, tolerance);
    } catch (const NumericalError& e) {
      throw InputError(options + ": the solver cannot reach the tolerance " + show(tolerance) + " at a/t = " +
                       show(a) + " (an end of the a/t range this request needs), so the run would fail after "
                       "building the whole table; allowed: a larger --tol, or parameters needing a/t closer "
                       "to 1 (solver: " + e.what() + ")");
    } catch (const InputError& e) {
      throw InputError(options + ": " + e.what());
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    total += seconds;
    slowest = std::max(slowest, seconds);
  }
  const double decades = std::max(1.0, std::ceil(std::log10(a_over_t_max / a_over_t_min)) + 1.0);
  // Mean of the two ends per node, nodes solved in parallel (ReducedSolver::sweep).
  const double threads = std::max(1u, std::thread::hardware_concurrency());
  const double estimate = 0.5 * total * kEvaluationsPerDecade * decades / threads;
  if (estimate > kMaxWorkSeconds) {
    throw InputError(options + ": estimated run time " + show(std::round(estimate)) + " s (" + show(decades) +
                     " decades of a/t, up to " + show(slowest) + " s per solve) is over the limit of " +
                     show(kMaxWorkSeconds) + " s; allowed: a larger --tol or a narrower range");
  }
  progress_set_estimate(estimate);
  return estimate;
}

std::vector<double> sphere_default_a_bar(const AdhesiveModel& model, const Contact& sphere,
                                         const SphereLimits& limits, double lo, double hi,
                                         std::size_t points) {
  // Scan 32 points per decade for the first a_bar past a limit; the curve then ends below it.
  const double l = sphere.length_scale();
  const std::size_t scan = std::max<std::size_t>(8, static_cast<std::size_t>(32 * std::log10(hi / lo)));
  double last_inside = 0.0;
  for (std::size_t k = 0; k < scan; ++k) {
    const double a_bar = lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(scan - 1));
    const CurvePoint p = model.point(sphere.eta(), a_bar);
    const double a = a_bar * l;
    const double delta = p.penetration * sphere.penetration_scale();
    const double force = p.load * sphere.force_scale();
    const bool inside = a <= kMaxContactRadiusOverR * limits.radius && delta <= limits.thickness &&
                        force / (M_PI * a * a) <= kMaxPressureOverModulus * limits.film_reduced_modulus;
    if (!inside) break;
    last_inside = a_bar;
  }
  if (last_inside > lo) hi = std::min(hi, last_inside);
  std::vector<double> v(points);
  for (std::size_t k = 0; k < points; ++k) {
    v[k] = lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(points - 1));
  }
  v.back() = hi;
  return v;
}

std::vector<std::string> sphere_physics_warnings(const std::vector<double>& a, const std::vector<double>& delta,
                                                 const std::vector<double>& force, const SphereLimits& limits) {
  std::vector<std::string> warnings;
  double a_max = 0.0, delta_max = -INFINITY, p_max = -INFINITY;
  for (std::size_t i = 0; i < a.size(); ++i) {
    a_max = std::max(a_max, a[i]);
    delta_max = std::max(delta_max, delta[i]);
    p_max = std::max(p_max, force[i] / (M_PI * a[i] * a[i]));
  }
  if (delta_max > limits.thickness) {
    warnings.push_back("penetration reaches " + show(delta_max) + " m, more than the film thickness t = " +
                       show(limits.thickness) + " m: the sphere would pass through the film");
  }
  if (a_max > kMaxContactRadiusOverR * limits.radius) {
    warnings.push_back("contact radius reaches " + show(a_max) + " m, above 0.1 R = " +
                       show(kMaxContactRadiusOverR * limits.radius) +
                       " m: the paraboloid approximation of the sphere no longer holds");
  }
  if (p_max > kMaxPressureOverModulus * limits.film_reduced_modulus) {
    warnings.push_back("mean pressure F/(pi a^2) reaches " + show(p_max) + " Pa, above 0.1 E1* = " +
                       show(kMaxPressureOverModulus * limits.film_reduced_modulus) +
                       " Pa: strains this large are beyond linear elasticity");
  }
  return warnings;
}

void check_fit_columns(const std::string& columns, const std::vector<std::string>& declared, int declared_line,
                       const std::string& data_path) {
  // --columns against the file's own "# columns:" line (only names this program knows).
  if (declared.size() != 2) return;
  const auto known = [](const std::string& n) { return n == "a" || n == "delta" || n == "F"; };
  if (!known(declared[0]) || !known(declared[1])) return;
  const std::string pair = declared[0] + "," + declared[1];
  if (pair != columns) {
    throw InputError("--columns: '" + columns + "' does not match the data file's column line '# columns: " +
                     declared[0] + " " + declared[1] + "' (" + short_name(data_path) + ":" + std::to_string(declared_line) +
                     "); allowed: --columns " + pair);
  }
}

}  // namespace coatcontact::cli
