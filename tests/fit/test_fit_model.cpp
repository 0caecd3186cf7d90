// Physics tests of the fit model (coatcontact_fit), against independent computations:
//  1. THEORY.md section 6, "Homogeneous substrate": with E0 = E1, nu0 = nu1 the model curve is
//     the JKR curve F = 4 E* a^3/(3R) - sqrt(8 pi w E* a^3), delta = a^2/R - sqrt(2 pi a w/E*),
//     written here in closed form (no solver involved).
//  2. Same check: fits of noise-free closed-form JKR a,F and delta,F data return w, and the
//     displacement-controlled pull-off found on the delta,F branch is P = F/(pi w R) = -5/6 at
//     a = l/2 (l = (pi w R^2/E*)^(1/3), the minimum of D = a_bar^2 - sqrt(2) a_bar^(1/2)).
//  3. Coated substrate: the interpolated model (lattice + spline) against the reduced
//     variables solved directly at each a/t, and against the adhesive model of
//     coatcontact_adhesive (a separate interpolation, Chebyshev in ln(a/t)).
//  4. select_branch splits at the maximum of the abscissa.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/reduced.hpp"

namespace {

using namespace coatcontact;

// Tolerance tiers (relative unless stated):
// The homogeneous reduced variables are exactly 8/3, 1, 1, 1; the solver delivers them to its
// tolerance (1e-8 here); forces are compared on the scale pi w R, so cancellation between the
// two JKR terms cannot hide an error. 1e-7 leaves a factor 100 for the spline of constants.
constexpr double kHomogeneousTier = 1e-7;
// A noise-free fit must return w to the accuracy of the model (same tier).
constexpr double kRecoveryTier = 1e-7;
// Interpolation of the coated-substrate reduced variables, 24 nodes per decade in a/t: the
// spline of ln X is exact for power laws; what remains is ~(5/384) h^4 |d^4 ln X/dx^4| with
// h = ln(10)/24 ~ 0.1, plus the solver tolerance 1e-8 (measured: ~2e-8 relative to F).
// Compared relative to |F|, or to pi w R where F passes through zero.
constexpr double kInterpolationTier = 1e-6;

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    ++failures;
    std::printf("FAIL: %s\n", what.c_str());
  }
}

void check_close(double value, double expected, double tolerance, const std::string& what) {
  const bool ok = std::fabs(value - expected) <= tolerance;
  std::printf("%s %s: %.12g vs %.12g (|diff| %.3g, tol %.3g)\n", ok ? "ok  " : "FAIL", what.c_str(), value,
              expected, std::fabs(value - expected), tolerance);
  if (!ok) ++failures;
}

fit::Problem homogeneous_problem() {
  fit::Problem problem;
  problem.sphere_radius = 5e-3;
  problem.film = Material{1e6, 0.3};
  problem.substrate.rigid = false;
  problem.substrate.material = Material{1e6, 0.3};
  problem.thickness = 50e-6;
  problem.work = 0.04;
  return problem;
}

double jkr_force(const fit::Problem& p, double a) {
  const double E = p.film.reduced_modulus();
  return 4.0 * E * a * a * a / (3.0 * p.sphere_radius) - std::sqrt(8.0 * M_PI * p.work * E * a * a * a);
}
double jkr_penetration(const fit::Problem& p, double a) {
  const double E = p.film.reduced_modulus();
  return a * a / p.sphere_radius - std::sqrt(2.0 * M_PI * a * p.work / E);
}

void test_homogeneous_curve() {
  const fit::Problem p = homogeneous_problem();
  const double E = p.film.reduced_modulus();
  const double length = std::cbrt(M_PI * p.work * p.sphere_radius * p.sphere_radius / E);
  const double force_scale = M_PI * p.work * p.sphere_radius;
  const double penetration_scale = length * length / p.sphere_radius;
  const auto curve = fit::model_curve(p, 0.05 * length, 5.0 * length, 41);
  double force_error = 0.0;
  double penetration_error = 0.0;
  for (const auto& point : curve) {
    force_error = std::max(force_error, std::fabs(point.force - jkr_force(p, point.radius)) / force_scale);
    penetration_error = std::max(
        penetration_error, std::fabs(point.penetration - jkr_penetration(p, point.radius)) / penetration_scale);
  }
  check_close(force_error, 0.0, kHomogeneousTier, "homogeneous: max |F - F_JKR| / (pi w R)");
  check_close(penetration_error, 0.0, kHomogeneousTier, "homogeneous: max |delta - delta_JKR| / (l^2/R)");
}

void test_homogeneous_fits() {
  const fit::Problem truth = homogeneous_problem();
  const double E = truth.film.reduced_modulus();
  const double length = std::cbrt(M_PI * truth.work * truth.sphere_radius * truth.sphere_radius / E);
  fit::Problem start = truth;
  start.work = 0.025;  // deliberately off
  start.free = {true, false, false};

  // a,F: loading and unloading, on both sides of the load-controlled pull-off (a_bar = 0.63).
  fit::Measurements radius_data;
  radius_data.kind = fit::DataKind::kRadiusForce;
  for (int i = 0; i <= 30; ++i) radius_data.abscissa.push_back(length * (0.3 + 0.1 * i));
  for (int i = 0; i <= 30; ++i) radius_data.abscissa.push_back(length * (3.25 - 0.1 * i));
  for (double a : radius_data.abscissa) radius_data.force.push_back(jkr_force(truth, a));
  const fit::Result r1 = fit::fit(radius_data, start);
  check(r1.converged, "homogeneous a,F fit converged");
  check_close(r1.value[fit::kWork] / truth.work, 1.0, kRecoveryTier, "homogeneous a,F: w / w_true");

  // delta,F on the stable branch of displacement control (a_bar >= 1/2).
  fit::Measurements penetration_data;
  penetration_data.kind = fit::DataKind::kPenetrationForce;
  for (int i = 0; i <= 30; ++i) {
    const double a = length * (0.52 + 0.08 * i);
    penetration_data.abscissa.push_back(jkr_penetration(truth, a));
    penetration_data.force.push_back(jkr_force(truth, a));
  }
  const fit::Result r2 = fit::fit(penetration_data, start);
  check(r2.converged, "homogeneous delta,F fit converged");
  check_close(r2.value[fit::kWork] / truth.work, 1.0, kRecoveryTier, "homogeneous delta,F: w / w_true");
  const double force_scale = M_PI * truth.work * truth.sphere_radius;
  check_close(r2.displacement_pulloff_force / force_scale, -5.0 / 6.0, kRecoveryTier,
              "homogeneous: displacement-controlled pull-off P (JKR -5/6)");
  check_close(r2.displacement_pulloff_radius / length, 0.5, 1e-5,
              "homogeneous: displacement-controlled pull-off a_bar (JKR 1/2; root of a flat minimum)");
  std::size_t clamped = 0;
  for (bool c : r2.clamped) clamped += c ? 1 : 0;
  check(clamped == 0, "no data point below the minimum of delta");
}

void test_coated_interpolation() {
  fit::Problem p;
  p.sphere_radius = 5e-3;
  p.film = Material{1e6, 0.49};
  p.substrate.material = Material{70e9, 0.22};
  p.thickness = 50e-6;
  p.work = 0.04;
  const double force_scale = M_PI * p.work * p.sphere_radius;
  const double a_min = 20e-6;
  const double a_max = 400e-6;  // a/t <= 8: the adhesive table then stays below a/t = 10
  const auto curve = fit::model_curve(p, a_min, a_max, 13);
  ReducedSolver solver(Stack::film_on(p.film, p.substrate));
  AdhesiveModel adhesive(solver, 1e-8);
  Contact contact(adhesive, p.sphere_radius, p.thickness, p.work);
  double direct_error = 0.0;
  double adhesive_error = 0.0;
  for (std::size_t i = 1; i + 1 < curve.size(); ++i) {
    const auto exact = fit::exact_point(p, curve[i].radius);
    // Relative to the force itself, or to pi w R where F passes through zero.
    const double scale = std::max(force_scale, std::fabs(exact.force));
    direct_error = std::max(direct_error, std::fabs(curve[i].force - exact.force) / scale);
    adhesive_error = std::max(adhesive_error, std::fabs(curve[i].force - contact.force(curve[i].radius)) / scale);
  }
  check_close(direct_error, 0.0, kInterpolationTier, "coated: spline model vs direct solve, max |dF|/max(|F|, pi w R)");
  check_close(adhesive_error, 0.0, kInterpolationTier,
              "coated: fit model vs coatcontact_adhesive Contact, max |dF|/max(|F|, pi w R)");
}

void test_branches() {
  fit::Measurements m;
  m.abscissa = {1, 2, 3, 5, 4, 2};
  m.force = {10, 20, 30, 50, 40, 20};
  m.line_numbers = {3, 4, 5, 6, 7, 8};
  const auto load = fit::select_branch(m, fit::Branch::kLoading);
  const auto unload = fit::select_branch(m, fit::Branch::kUnloading);
  check(load.size() == 4 && load.abscissa.back() == 5 && load.line_numbers.back() == 6, "loading = rows up to max");
  check(unload.size() == 3 && unload.abscissa.front() == 5 && unload.force.back() == 20, "unloading = rows from max");
  check(fit::select_branch(m, fit::Branch::kAll).size() == 6, "both = all rows");
}

}  // namespace

int main() {
  try {
    test_branches();
    test_homogeneous_curve();
    test_homogeneous_fits();
    test_coated_interpolation();
  } catch (const std::exception& error) {
    std::printf("FAIL: exception: %s\n", error.what());
    return 1;
  }
  std::printf("%s (%d failure%s)\n", failures == 0 ? "PASS" : "FAIL", failures, failures == 1 ? "" : "s");
  return failures == 0 ? 0 : 1;
}
