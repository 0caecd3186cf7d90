// Fit of the crack-kinetics law (THEORY.md section 14, fitting, check 5): force-time curves
// simulated at three retract speeds with Gaussian noise on F are fitted back to the w, v*, n
// that made them within three standard errors, on the homogeneous solid and on a coating; with
// the film modulus E1 free too, over several noise seeds; data at one retract speed with v* and
// n free are refused.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/kinetics_fit.hpp"
#include "coatcontact/reduced.hpp"

using namespace coatcontact;

namespace {

// A fitted value within this many standard errors of the truth: a 3-sigma test of an unbiased
// estimator fails by chance with probability 0.3% per parameter (the seed is fixed).
constexpr double kStandardErrors = 3.0;
constexpr std::size_t kPointsPerCurve = 60;

// The README's run: approach at 1 um/s to 1 mN, dwell 1 s, retract until contact is lost.
std::vector<KineticsSegmentSI> protocol(double retract_speed) {
  std::vector<KineticsSegmentSI> p(3);
  p[0].kind = DriveSegment::Kind::kApproach;
  p[0].speed = 1e-6;
  p[0].target_force = 1e-3;
  p[0].has_target = true;
  p[1].kind = DriveSegment::Kind::kDwell;
  p[1].duration = 1.0;
  p[2].kind = DriveSegment::Kind::kRetract;
  p[2].speed = retract_speed;
  return p;
}

struct Truth {
  double radius = 2e-3, thickness = 50e-6, work = 0.04, v_star = 1e-6, n = 0.6, spring = 500.0;
};

// Synthetic curves: states of the simulation itself (no interpolation enters the data), about
// kPointsPerCurve up to the pull-off and the run-off after it (which the fit leaves out), F plus
// noise of `noise` times max |F|.
std::vector<fit::KineticsCurve> synthetic(const Stack& stack, const Truth& truth, const std::vector<double>& speeds,
                                          double noise, unsigned long seed) {
  const ReducedSolver solver(stack);
  const AdhesiveModel model(solver);
  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> rng(gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free);
  gsl_rng_set(rng.get(), seed);
  std::vector<fit::KineticsCurve> curves;
  for (double speed : speeds) {
    KineticsSetupSI setup;
    setup.radius = truth.radius;
    setup.thickness = truth.thickness;
    setup.work = truth.work;
    setup.v_star = truth.v_star;
    setup.n = truth.n;
    setup.spring = truth.spring;
    setup.protocol = protocol(speed);
    const KineticsResultSI run = simulate_kinetics_si(model, setup).front();
    fit::KineticsCurve curve;
    curve.protocol = setup.protocol;
    curve.spring = truth.spring;
    double largest = 0.0;
    for (double f : run.force) largest = std::max(largest, std::fabs(f));
    std::size_t before_pulloff = 0;
    while (before_pulloff < run.t.size() && run.t[before_pulloff] < run.pulloff.time) ++before_pulloff;
    const std::size_t stride = std::max<std::size_t>(1, before_pulloff / kPointsPerCurve);
    for (std::size_t i = 0; i + 1 < run.t.size(); i += stride) {
      if (!curve.time.empty() && !(run.t[i] > curve.time.back())) continue;
      curve.time.push_back(run.t[i]);
      curve.force.push_back(run.force[i] + gsl_ran_gaussian(rng.get(), noise * largest));
      curve.sigma_force.push_back(noise * largest);
    }
    std::printf("  curve at %.3g m/s: %zu points of %zu states, pull-off %.6g N at %.6g s, loss at %.6g s\n", speed,
                curve.time.size(), run.t.size(), run.pulloff.force, run.pulloff.time, run.loss.time);
    curves.push_back(std::move(curve));
  }
  return curves;
}

void recovers(const char* what, const Stack& stack) {
  std::printf("%s\n", what);
  const Truth truth;
  const auto curves = synthetic(stack, truth, {1e-6, 1e-5, 1e-4}, 0.01, 7);
  fit::KineticsFitProblem problem;
  problem.radius = truth.radius;
  problem.thickness = truth.thickness;
  // Start away from the truth: the fit has to find it.
  problem.work = 1.5 * truth.work;
  problem.v_star = 3.0 * truth.v_star;
  problem.n = 0.45;
  const fit::Result r = fit::fit_kinetics(stack, curves, problem);
  const double expected[] = {truth.work, truth.v_star, truth.n};
  for (int j = 0; j < 3; ++j) {
    const double deviation = std::fabs(r.value[j] - expected[j]) / r.standard_error[j];
    std::printf("  %-6s = %.6g +- %.3g (truth %.6g: %.2f standard errors)\n", r.parameters[j].name.c_str(),
                r.value[j], r.standard_error[j], expected[j], deviation);
    check::below(deviation, kStandardErrors, (std::string(what) + ": " + r.parameters[j].name + " within 3 SE").c_str());
    // The errors mean something: each below 20% of its value at 1% noise on three curves.
    check::below(r.standard_error[j] / r.value[j], 0.2, (std::string(what) + ": relative error of " + r.parameters[j].name).c_str());
  }
  std::printf("  chi2/dof %.3f, %zu points, %d iterations, %ld simulations, %.2f s\n", r.chi2_per_dof, r.points,
              r.iterations, r.solver_calls, r.seconds);
  check::below(std::fabs(r.chi2_per_dof - 1.0), 0.5, (std::string(what) + ": chi2/dof near 1").c_str());
}

// E1 free with w, v*, n (each trial E1 builds its own table): every parameter within 3 SE of the
// truth for each of several noise seeds, from a start 20% off in w, 1.5x in v*, 0.55 for n and
// 15% off in E1 (a modulus known beforehand to that accuracy). Farther starts can lead the trust
// region into the valley of tiny w and v* where w (v/v*)^n mimics the data (measured: 30% off in
// E1 and 2x in v* reached w = 7e-8 for seed 22), which the fit reports as a NumericalError.
void recovers_film_modulus(const Stack& stack) {
  const Truth truth;
  for (unsigned long seed : {21ul, 22ul, 23ul}) {
    std::printf("coating, E1 free, seed %lu\n", seed);
    const auto curves = synthetic(stack, truth, {1e-6, 1e-5, 1e-4}, 0.01, seed);
    fit::KineticsFitProblem problem;
    problem.radius = truth.radius;
    problem.thickness = truth.thickness;
    problem.work = 1.2 * truth.work;
    problem.v_star = 1.5 * truth.v_star;
    problem.n = 0.55;
    problem.film_modulus = 1.15 * stack.top().youngs_modulus;
    problem.free = {{true, true, true, false, true}};
    const fit::Result r = fit::fit_kinetics(stack, curves, problem);
    const double expected[] = {truth.work, truth.v_star, truth.n, truth.thickness, stack.top().youngs_modulus};
    for (int j : {fit::kKinWork, fit::kKinSpeed, fit::kKinExponent, fit::kKinFilmModulus}) {
      const double deviation = std::fabs(r.value[j] - expected[j]) / r.standard_error[j];
      std::printf("  %-6s = %.6g +- %.3g (truth %.6g: %.2f standard errors)\n", r.parameters[j].name.c_str(),
                  r.value[j], r.standard_error[j], expected[j], deviation);
      check::below(deviation, kStandardErrors, "E1 free: " + r.parameters[j].name + " within 3 SE");
    }
    check::below(r.standard_error[fit::kKinFilmModulus] / r.value[fit::kKinFilmModulus], 0.2,
                 "E1 free: relative error of E1");
    std::printf("  chi2/dof %.3f, %d iterations, %ld simulations, %.2f s\n", r.chi2_per_dof, r.iterations,
                r.solver_calls, r.seconds);
  }
}

void one_speed_refused(const Stack& stack) {
  const Truth truth;
  const auto curves = synthetic(stack, truth, {1e-5, 1e-5}, 0.01, 11);
  fit::KineticsFitProblem problem;
  problem.radius = truth.radius;
  problem.thickness = truth.thickness;
  problem.work = truth.work;
  problem.v_star = truth.v_star;
  problem.n = truth.n;
  check::throws<InputError>([&] { fit::fit_kinetics(stack, curves, problem); }, {"one speed", "fix v_star or n"});
  // With n fixed the same data determine w and v*.
  problem.free = {{true, true, false, false, false}};
  problem.v_star = 2.0 * truth.v_star;
  const fit::Result r = fit::fit_kinetics(stack, curves, problem);
  const double deviation = std::fabs(r.value[fit::kKinSpeed] - truth.v_star) / r.standard_error[fit::kKinSpeed];
  std::printf("one speed, n fixed: v_star = %.6g +- %.3g (%.2f SE)\n", r.value[fit::kKinSpeed],
              r.standard_error[fit::kKinSpeed], deviation);
  check::below(deviation, kStandardErrors, "one speed, n fixed: v_star within 3 SE");
}

}  // namespace

// Argument "film_modulus": only the fits with E1 free (test kinetics_fit_film_modulus: each
// builds tables at every trial E1, minutes of CPU); none: the others.
int main(int argc, char** argv) {
  Substrate glass;
  glass.material = Material{70e9, 0.22};
  Substrate rubber;
  rubber.material = Material{1e6, 0.49};
  const Material film{1e6, 0.49};
  // The homogeneous solid: the film of the substrate's material.
  const Stack coating = Stack::film_on(film, glass);
  if (argc > 1 && std::string(argv[1]) == "film_modulus") {
    recovers_film_modulus(coating);
    return check::exit_code();
  }
  recovers("homogeneous solid (E = 1 MPa)", Stack::film_on(film, rubber));
  recovers("coating (1 MPa, 50 um on glass)", coating);
  one_speed_refused(coating);
  return check::exit_code();
}
