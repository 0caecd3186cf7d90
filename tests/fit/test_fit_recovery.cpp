// Physics test of the fit on the example data sets of data/ (synthetic, known parameters,
// Gaussian force noise of known standard deviation; see data/README.md):
//  - the fit recovers w (t fixed) and w, t together within 3 standard errors, for the a,F and
//    the delta,F set, and for the loading and unloading branches of the a,F set separately;
//  - the residual standard deviation s estimates the true noise sigma;
//  - the interpolation error of the model is far below the noise.
// This is a statistical check of the whole chain (reader, model, branch inversion, GSL fit,
// covariance). It complements the THEORY.md section 6 checks of test_fit_model (homogeneous
// limit, JKR pull-off -5/6); the data were generated from the reduced variables solved
// directly at each point, not from the interpolant the fit uses.
// Usage: test_fit_recovery DATA_DIR
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "check.hpp"

namespace {

using namespace coatcontact;

// The truth behind data/example_*.tsv (scripts/make_example_data.sh).
constexpr double kRadius = 5e-3;
constexpr double kThickness = 50e-6;
constexpr double kFilmModulus = 1e6;
constexpr double kFilmPoisson = 0.49;
constexpr double kSubstrateModulus = 70e9;
constexpr double kSubstratePoisson = 0.22;
constexpr double kWork = 0.04;
constexpr double kNoise = 10e-6;  // N

// Tiers: estimates within 3 standard errors (a fixed seed makes this deterministic; for a
// correct fit the chance of exceeding 3 SE is 0.3 % per parameter). s within 30 % of sigma:
// with n - p ~ 78 the relative spread of s is 1/sqrt(2 (n-p)) ~ 8 %, 30 % is ~ 4 spreads.
// Interpolation error below 1 % of sigma: "<< noise".
constexpr double kStandardErrors = 3.0;
constexpr double kSigmaTier = 0.3;
constexpr double kInterpolationOverSigma = 0.01;


fit::Measurements load(const std::string& path, fit::DataKind kind) {
  const DataTable table = read_data_file(path, 2, {kind == fit::DataKind::kRadiusForce, false},
                                         {Quantity::kLength, Quantity::kForce});
  fit::Measurements m;
  m.kind = kind;
  m.abscissa = table.columns[0];
  m.force = table.columns[1];
  m.line_numbers = table.line_numbers;
  return m;
}

void run_case(const std::string& name, const fit::Measurements& data, bool fit_thickness) {
  fit::Problem problem;
  problem.sphere_radius = kRadius;
  problem.film = Material{kFilmModulus, kFilmPoisson};
  problem.substrate.material = Material{kSubstrateModulus, kSubstratePoisson};
  // Start values off the truth: w by 50 %, t by 20 %.
  problem.work = 1.5 * kWork;
  problem.thickness = fit_thickness ? 0.8 * kThickness : kThickness;
  problem.free = {true, fit_thickness, false};
  const fit::Result r = fit::fit(data, problem);
  std::printf("%s: %zu points, %d iterations, %.3f s, %ld solver calls, s = %.4g N\n", name.c_str(), r.points,
              r.iterations, r.seconds, r.solver_calls, r.residual_sigma);
  check::that(r.converged, name + ": converged");
  const double truth[2] = {kWork, kThickness};
  for (int which = 0; which < (fit_thickness ? 2 : 1); ++which) {
    const double deviation = (r.value[which] - truth[which]) / r.standard_error[which];
    char text[200];
    std::snprintf(text, sizeof text, "%s: %s = %.6g +- %.3g (truth %.6g, %.2f SE)", name.c_str(),
                  fit::parameter_name(which), r.value[which], r.standard_error[which], truth[which], deviation);
    check::that(r.standard_error[which] > 0.0, std::string(text) + ": standard error > 0");
    check::below(std::fabs(deviation), kStandardErrors, std::string(text) + ": |deviation| in SE");
  }
  char text[200];
  std::snprintf(text, sizeof text, "%s: s = %.4g N vs sigma %.4g N", name.c_str(), r.residual_sigma, kNoise);
  check::close(r.residual_sigma, kNoise, kSigmaTier, text);
  std::snprintf(text, sizeof text, "%s: interpolation error %.3g N = %.2e sigma", name.c_str(),
                r.interpolation_error, r.interpolation_error / kNoise);
  check::below(r.interpolation_error, kInterpolationOverSigma * kNoise, text);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::printf("usage: test_fit_recovery DATA_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  check::verbose = true;  // the log reports every estimate against the truth
  try {
    const auto radius_data = load(dir + "/example_a_F.tsv", fit::DataKind::kRadiusForce);
    const auto penetration_data = load(dir + "/example_delta_F.tsv", fit::DataKind::kPenetrationForce);
    run_case("a,F  w", radius_data, false);
    run_case("a,F  w,t", radius_data, true);
    run_case("a,F  loading, w", fit::select_branch(radius_data, fit::Branch::kLoading), false);
    run_case("a,F  unloading, w", fit::select_branch(radius_data, fit::Branch::kUnloading), false);
    run_case("delta,F  w", penetration_data, false);
    run_case("delta,F  w,t", penetration_data, true);
  } catch (const std::exception& error) {
    check::that(false, std::string("exception: ") + error.what());
  }
  return check::exit_code();
}
