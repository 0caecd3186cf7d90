// Physics tests of the fit model (coatcontact_fit), against independent computations:
//  1. THEORY.md section 6, "Homogeneous substrate": with E0 = E1, nu0 = nu1 the model curve is
//     the JKR curve F = 4 E* a^3/(3R) - sqrt(8 pi w E* a^3), delta = a^2/R - sqrt(2 pi a w/E*),
//     written here in closed form (no solver involved).
//  2. Same check: fits of noise-free closed-form JKR a,F and delta,F data return w, and the
//     displacement-controlled pull-off found on the delta,F branch is P = F/(pi w R) = -5/6 at
//     a = l/2 (l = (pi w R^2/E*)^(1/3), the minimum of D = a_bar^2 - sqrt(2) a_bar^(1/2)).
//  3. Coated substrate: the model (ReducedTable + JkrLaw + Contact scales) against the reduced
//     variables solved directly by ReducedSolver at a few a/t, put into [EqForceCS] and
//     [EqPenetrationCS] here in SI units (no adhesion floor involved); exact_point as well.
//  4. The Jacobian of the fit (analytic in w and t, central difference in E1) against central
//     differences of the whole model at the data, for a,F and delta,F data.
//  5. select_branch splits at the maximum of the abscissa.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/reduced.hpp"
#include "check.hpp"
#include "fit_model.hpp"  // the fit's private model, for the Jacobian check

namespace {

using namespace coatcontact;

// Tolerance tiers (check.hpp's, scaled where this test's error has several sources). Every
// quantity compared is of order one (ratios, or errors already divided by their scale), so
// the checks are absolute: check::close with floor 1.
// The homogeneous reduced variables are exactly 8/3, 1, 1, 1; the solver delivers them to its
// tolerance (kSolver); forces are compared on the scale pi w R, so cancellation between the
// two JKR terms cannot hide an error. A factor 10 leaves room for the interpolant.
constexpr double kHomogeneousTier = 10 * check::tier::kSolver;
// A noise-free fit must return w to the accuracy of the model (same tier).
constexpr double kRecoveryTier = kHomogeneousTier;
// Interpolation of the coated-substrate reduced variables (ReducedTable, order-24 Chebyshev
// per decade: ~1e-12 relative, reduced_table.cpp) plus the solver tolerance of both sides
// (measured: ~1e-11 relative to F). Compared relative to |F|, or to pi w R where F passes
// through zero.
constexpr double kInterpolationTier = 10 * check::tier::kSolver;
// Jacobian columns against central differences of the model with step h = 1e-4 in ln p:
// truncation ~h^2 ~ 1e-8 of the column scale, plus the E1 column's own difference error
// (~2e-7). Relative to the largest entry of the column.
constexpr double kJacobianTier = 10 * check::tier::kIdentityByDifferences;
// The pull-off radius is the location of a flat minimum of delta(a), found far less
// precisely than the value there.
constexpr double kFlatMinimumTier = 10 * check::tier::kIdentityByDifferences;
// Scale of the absolute comparisons (see above).
constexpr double kUnit = 1.0;

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
  check::close(force_error, 0.0, kHomogeneousTier, "homogeneous: max |F - F_JKR| / (pi w R)", kUnit);
  check::close(penetration_error, 0.0, kHomogeneousTier, "homogeneous: max |delta - delta_JKR| / (l^2/R)", kUnit);
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
  check::that(r1.converged, "homogeneous a,F fit converged");
  check::close(r1.value[fit::kWork] / truth.work, 1.0, kRecoveryTier, "homogeneous a,F: w / w_true", kUnit);

  // delta,F on the stable branch of displacement control (a_bar >= 1/2).
  fit::Measurements penetration_data;
  penetration_data.kind = fit::DataKind::kPenetrationForce;
  for (int i = 0; i <= 30; ++i) {
    const double a = length * (0.52 + 0.08 * i);
    penetration_data.abscissa.push_back(jkr_penetration(truth, a));
    penetration_data.force.push_back(jkr_force(truth, a));
  }
  const fit::Result r2 = fit::fit(penetration_data, start);
  check::that(r2.converged, "homogeneous delta,F fit converged");
  check::close(r2.value[fit::kWork] / truth.work, 1.0, kRecoveryTier, "homogeneous delta,F: w / w_true", kUnit);
  const double force_scale = M_PI * truth.work * truth.sphere_radius;
  check::close(r2.displacement_pulloff_force / force_scale, -5.0 / 6.0, kRecoveryTier,
              "homogeneous: displacement-controlled pull-off P (JKR -5/6)", kUnit);
  check::close(r2.displacement_pulloff_radius / length, 0.5, kFlatMinimumTier,
              "homogeneous: displacement-controlled pull-off a_bar (JKR 1/2; root of a flat minimum)", kUnit);
  std::size_t clamped = 0;
  for (bool c : r2.clamped) clamped += c ? 1 : 0;
  check::that(clamped == 0, "no data point below the minimum of delta");
}

fit::Problem coated_problem() {
  fit::Problem p;
  p.sphere_radius = 5e-3;
  p.film = Material{1e6, 0.49};
  p.substrate.material = Material{70e9, 0.22};
  p.thickness = 50e-6;
  p.work = 0.04;
  return p;
}

void test_coated_direct() {
  const fit::Problem p = coated_problem();
  const double E = p.film.reduced_modulus();
  const double R = p.sphere_radius;
  const double force_scale = M_PI * p.work * R;
  const auto curve = fit::model_curve(p, 20e-6, 400e-6, 13);
  const ReducedSolver solver(Stack::film_on(p.film, p.substrate));
  double force_error = 0.0;
  double penetration_error = 0.0;
  double exact_point_error = 0.0;
  for (std::size_t i = 1; i + 1 < curve.size(); i += 2) {
    const double a = curve[i].radius;
    const ReducedVariables v = solver.solve(a / p.thickness, 1e-8);
    const double delta_fp = -std::sqrt(2.0 * M_PI * a * p.work / E) / v.gamma1;
    const double force = a * a * a * E / (2.0 * R) * v.pi_s + 2.0 * a * E * v.e_eq * delta_fp;
    const double penetration = a * a / R * v.delta_s + delta_fp;
    // Relative to the force itself, or to pi w R where F passes through zero.
    const double scale = std::max(force_scale, std::fabs(force));
    force_error = std::max(force_error, std::fabs(curve[i].force - force) / scale);
    penetration_error = std::max(penetration_error, std::fabs(curve[i].penetration - penetration) /
                                                        std::max(std::fabs(penetration), a * a / R));
    exact_point_error = std::max(exact_point_error, std::fabs(fit::exact_point(p, a).force - force) / scale);
  }
  check::close(force_error, 0.0, kInterpolationTier, "coated: model vs direct solve, max |dF|/max(|F|, pi w R)", kUnit);
  check::close(penetration_error, 0.0, kInterpolationTier,
              "coated: model vs direct solve, max |d delta|/max(|delta|, a^2/R)", kUnit);
  check::close(exact_point_error, 0.0, kInterpolationTier, "coated: exact_point vs direct solve", kUnit);
}

// Central differences of the model force at the data in ln p (re-inverting delta for
// delta,F data) against Model::force_derivatives.
void check_jacobian(const fit::Measurements& data, const std::string& name) {
  const fit::Problem problem = coated_problem();
  fit::internal::Model model(problem, data);
  const fit::internal::Parameters p{problem.work, problem.thickness, problem.film.youngs_modulus};
  const fit::internal::ModelAtData m = model.at_data(p);
  const auto columns = model.force_derivatives(p, m, {fit::kWork, fit::kThickness, fit::kFilmModulus});
  const double h = 1e-4;
  for (int which = 0; which < fit::kParameterCount; ++which) {
    auto up = p.as_array();
    auto down = p.as_array();
    up[which] *= std::exp(h);
    down[which] *= std::exp(-h);
    const auto mu = model.at_data(fit::internal::Parameters::from(up));
    const auto md = model.at_data(fit::internal::Parameters::from(down));
    double largest = 0.0;
    double error = 0.0;
    for (std::size_t i = 0; i < data.size(); ++i) {
      largest = std::max(largest, std::fabs(columns[which][i]));
      error = std::max(error, std::fabs((mu.force[i] - md.force[i]) / (2.0 * h) - columns[which][i]));
    }
    check::close(error / largest, 0.0, kJacobianTier,
                name + ": dF/d ln " + fit::parameter_name(which) + " vs central difference", kUnit);
  }
}

void test_jacobian() {
  const fit::Problem p = coated_problem();
  fit::Measurements radius_data;
  radius_data.kind = fit::DataKind::kRadiusForce;
  fit::Measurements penetration_data;
  penetration_data.kind = fit::DataKind::kPenetrationForce;
  // Radii from the jump-in to beyond, and their penetrations well above the pull-off minimum
  // (near it a*(delta) has a square-root singularity that finite differences cannot follow).
  for (int i = 0; i <= 20; ++i) {
    const double a = 60e-6 + 10e-6 * i;
    const fit::CurvePoint point = fit::exact_point(p, a);
    radius_data.abscissa.push_back(a);
    radius_data.force.push_back(point.force);
    penetration_data.abscissa.push_back(point.penetration);
    penetration_data.force.push_back(point.force);
  }
  check_jacobian(radius_data, "a,F");
  check_jacobian(penetration_data, "delta,F");
}

void test_branches() {
  fit::Measurements m;
  m.abscissa = {1, 2, 3, 5, 4, 2};
  m.force = {10, 20, 30, 50, 40, 20};
  m.line_numbers = {3, 4, 5, 6, 7, 8};
  const auto load = fit::select_branch(m, fit::Branch::kLoading);
  const auto unload = fit::select_branch(m, fit::Branch::kUnloading);
  check::that(load.size() == 4 && load.abscissa.back() == 5 && load.line_numbers.back() == 6, "loading = rows up to max");
  check::that(unload.size() == 3 && unload.abscissa.front() == 5 && unload.force.back() == 20, "unloading = rows from max");
  check::that(fit::select_branch(m, fit::Branch::kAll).size() == 6, "both = all rows");
}

}  // namespace

int main() {
  check::verbose = true;  // the log reports the measured errors
  try {
    test_branches();
    test_homogeneous_curve();
    test_homogeneous_fits();
    test_coated_direct();
    test_jacobian();
  } catch (const std::exception& error) {
    check::that(false, std::string("exception: ") + error.what());
  }
  return check::exit_code();
}
