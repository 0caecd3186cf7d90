// Benchmarks of the crack kinetics (THEORY.md section 14) on the paper's soft film
// (E1*/E0* = 0.1, nu = 0.25, eta = 1; n = 0.6, v_a* = v*), spring k_bar = 1: one approach
// (V = 1 to P = 1), dwell (tau = 1), retract (V = 1) simulation, and a sweep of 30 retract
// speeds V = 1e-3..1e3 (the part before the retract simulated once), the same sweep under load
// control (k_bar = 0; rates dP/dtau) and the one simulation for a cone (THEORY.md section 14,
// "The cone"). The reduced-variable table is built once, outside the timing. Counters: ODE steps
// and the pull-off P.
// BM_KineticsFitThreeSpeeds: the fit of w, v*, n (THEORY.md section 14, fitting) to three
// curves (the README's run on its coating, retract at 1, 10, 100 um/s, 60 points each, 1% noise),
// from a start 1.5x, 3x, 0.75x off; the table is built before the timing.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/kinetics_fit.hpp"
#include "coatcontact/reduced.hpp"

namespace {

using namespace coatcontact;

const AdhesiveModel& soft_film_model() {
  static const ReducedSolver solver = [] {
    Material film{0.1, 0.25};
    Substrate substrate;
    substrate.material = Material{1.0, 0.25};
    return ReducedSolver(Stack::film_on(film, substrate));
  }();
  static const AdhesiveModel model(solver);
  return model;
}

std::vector<DriveSegment> protocol() {
  std::vector<DriveSegment> p(3);
  p[0].kind = DriveSegment::Kind::kApproach;
  p[0].rate = 1.0;
  p[0].target_load = 1.0;
  p[1].kind = DriveSegment::Kind::kDwell;
  p[1].duration = 1.0;
  p[2].kind = DriveSegment::Kind::kRetract;
  p[2].rate = 1.0;
  return p;
}

void warm_up(const AdhesiveModel& model) {
  static bool done = false;
  if (!done) simulate_kinetics(model, 1.0, KineticLaw{}, 1.0, protocol());  // builds the table
  done = true;
}

void BM_KineticsOneSimulation(benchmark::State& state) {
  const AdhesiveModel& model = soft_film_model();
  warm_up(model);
  KineticsResult r;
  for (auto _ : state) {
    r = simulate_kinetics(model, 1.0, KineticLaw{}, 1.0, protocol());
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["P_pulloff"] = r.pulloff.load;
}
BENCHMARK(BM_KineticsOneSimulation)->Unit(benchmark::kMillisecond);

void BM_KineticsSweep30(benchmark::State& state) {
  const AdhesiveModel& model = soft_film_model();
  warm_up(model);
  std::vector<double> speeds(30);
  for (int i = 0; i < 30; ++i) speeds[static_cast<std::size_t>(i)] = 1e-3 * std::pow(1e6, i / 29.0);
  std::vector<KineticsResult> r;
  for (auto _ : state) {
    r = sweep_kinetics(model, 1.0, KineticLaw{}, 1.0, protocol(), speeds);
    benchmark::DoNotOptimize(r);
  }
  state.counters["P_pulloff_slowest"] = r.front().pulloff.load;
  state.counters["P_pulloff_fastest"] = r.back().pulloff.load;
}
BENCHMARK(BM_KineticsSweep30)->Unit(benchmark::kMillisecond);

void BM_KineticsSweep30LoadControl(benchmark::State& state) {
  const AdhesiveModel& model = soft_film_model();
  warm_up(model);
  std::vector<double> speeds(30);
  for (int i = 0; i < 30; ++i) speeds[static_cast<std::size_t>(i)] = 1e-3 * std::pow(1e6, i / 29.0);
  std::vector<KineticsResult> r;
  std::size_t steps = 0;
  for (auto _ : state) {
    r = sweep_kinetics(model, 1.0, KineticLaw{}, 0.0, protocol(), speeds);
    benchmark::DoNotOptimize(r);
  }
  for (const KineticsResult& run : r) steps += run.steps;
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["P_pulloff_slowest"] = r.front().pulloff.load;
  state.counters["P_pulloff_fastest"] = r.back().pulloff.load;
}
BENCHMARK(BM_KineticsSweep30LoadControl)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_KineticsOneSimulationCone(benchmark::State& state) {
  const AdhesiveModel& model = soft_film_model();
  // The cone's default range of a_bar reaches further (section 14): its decades of the table first.
  KineticsResult r = simulate_kinetics(model, KineticsTip::kCone, 1.0, KineticLaw{}, 1.0, protocol());
  for (auto _ : state) {
    r = simulate_kinetics(model, KineticsTip::kCone, 1.0, KineticLaw{}, 1.0, protocol());
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["P_pulloff"] = r.pulloff.load;
}
BENCHMARK(BM_KineticsOneSimulationCone)->Unit(benchmark::kMillisecond);

const AdhesiveModel& coating_model() {
  static const ReducedSolver solver = [] {
    Material film{1e6, 0.49};
    Substrate glass;
    glass.material = Material{70e9, 0.22};
    return ReducedSolver(Stack::film_on(film, glass));
  }();
  static const AdhesiveModel model(solver);
  return model;
}

KineticsSetupSI readme_setup(double retract_speed) {
  KineticsSetupSI setup;
  setup.radius = 2e-3;
  setup.thickness = 50e-6;
  setup.work = 0.04;
  setup.v_star = 1e-6;
  setup.n = 0.6;
  setup.spring = 500.0;
  setup.protocol.resize(3);
  setup.protocol[0] = {DriveSegment::Kind::kApproach, 1e-6, 0.0, 1e-3, true};
  setup.protocol[1] = {DriveSegment::Kind::kDwell, 0.0, 1.0, 0.0, false};
  setup.protocol[2] = {DriveSegment::Kind::kRetract, retract_speed, 0.0, 0.0, false};
  return setup;
}

void BM_KineticsFitThreeSpeeds(benchmark::State& state) {
  const AdhesiveModel& model = coating_model();
  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> rng(gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free);
  std::vector<fit::KineticsCurve> curves;
  for (double speed : {1e-6, 1e-5, 1e-4}) {
    const KineticsSetupSI setup = readme_setup(speed);
    const KineticsResultSI run = simulate_kinetics_si(model, setup).front();  // builds the table
    fit::KineticsCurve curve;
    curve.protocol = setup.protocol;
    curve.spring = setup.spring;
    double largest = 0.0;
    for (double f : run.force) largest = std::max(largest, std::fabs(f));
    const std::size_t stride = std::max<std::size_t>(1, run.t.size() / 60);
    for (std::size_t i = 0; i + 1 < run.t.size(); i += stride) {
      if (!curve.time.empty() && !(run.t[i] > curve.time.back())) continue;
      curve.time.push_back(run.t[i]);
      curve.force.push_back(run.force[i] + gsl_ran_gaussian(rng.get(), 0.01 * largest));
      curve.sigma_force.push_back(0.01 * largest);
    }
    curves.push_back(std::move(curve));
  }
  fit::KineticsFitProblem problem;
  problem.radius = 2e-3;
  problem.thickness = 50e-6;
  problem.work = 0.06;
  problem.v_star = 3e-6;
  problem.n = 0.45;
  fit::Result r;
  for (auto _ : state) {
    r = fit::fit_kinetics(model, curves, problem);
    benchmark::DoNotOptimize(r);
  }
  state.counters["w"] = r.value[fit::kKinWork];
  state.counters["v_star"] = r.value[fit::kKinSpeed];
  state.counters["n"] = r.value[fit::kKinExponent];
  state.counters["simulations"] = static_cast<double>(r.solver_calls);
  state.counters["iterations"] = r.iterations;
}
BENCHMARK(BM_KineticsFitThreeSpeeds)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
