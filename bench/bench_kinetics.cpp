// Benchmarks of the crack kinetics (THEORY.md section 14) on the paper's soft film
// (E1*/E0* = 0.1, nu = 0.25, eta = 1; n = 0.6, v_a* = v*), spring k_bar = 1: one approach
// (V = 1 to P = 1), dwell (tau = 1), retract (V = 1) simulation, and a sweep of 30 retract
// speeds V = 1e-3..1e3 (the part before the retract simulated once). The reduced-variable
// table is built once, outside the timing. Counters: ODE steps and the pull-off P.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "coatcontact/crack_kinetics.hpp"
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

}  // namespace

BENCHMARK_MAIN();
