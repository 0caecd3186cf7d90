// Benchmarks of the reduced-variable solver (docs/solver.md): time per contact radius at
// a/t = 0.01, 1, 100, 1000 and the standard sweep (200 log-spaced a/t in [0.01, 100], all six
// variables at tolerance 1e-8), with the number of unknowns used. Material: the paper's soft
// film, E1*/E0* = 0.1, nu0 = nu1 = 0.25 (kernel table built once, outside the timing); and an
// incompressible film on a rigid substrate (the two-table kernel-error estimate).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "coatcontact/reduced.hpp"

namespace {

const coatcontact::ReducedSolver& soft_film_solver() {
  static const coatcontact::ReducedSolver solver = [] {
    coatcontact::Material film;
    film.youngs_modulus = 0.1;
    film.poisson_ratio = 0.25;
    coatcontact::Substrate substrate;
    substrate.material.youngs_modulus = 1.0;
    substrate.material.poisson_ratio = 0.25;
    return coatcontact::ReducedSolver(coatcontact::Stack::film_on(film, substrate));
  }();
  return solver;
}

std::vector<double> standard_sweep_radii() {
  std::vector<double> radii(200);
  for (int i = 0; i < 200; ++i) radii[static_cast<std::size_t>(i)] = 0.01 * std::pow(1e4, i / 199.0);
  return radii;
}

// Times solve() at one contact radius (tolerance 1e-8) and reports its size and estimate.
void time_one_radius(benchmark::State& state, const coatcontact::ReducedSolver& solver,
                     double a_over_t) {
  coatcontact::ReducedVariables v;
  for (auto _ : state) {
    v = solver.solve(a_over_t, 1e-8);
    benchmark::DoNotOptimize(v);
  }
  state.counters["a_over_t"] = a_over_t;
  state.counters["unknowns"] = v.unknowns;
  state.counters["error_estimate"] = v.error_estimate;
}

// One contact radius, a/t = range(0) / 100.
void BM_SolvePerRadius(benchmark::State& state) {
  const double a_over_t = static_cast<double>(state.range(0)) / 100.0;
  time_one_radius(state, soft_film_solver(), a_over_t);
}
BENCHMARK(BM_SolvePerRadius)->Arg(1)->Arg(100)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// An incompressible film on a rigid substrate (PDMS on glass), a/t = range(0): the coherent
// kernel bound exceeds tol/10 there, so the final level is re-solved with the two
// independent kernel tables (built once, on the warm-up solve outside the timing).
const coatcontact::ReducedSolver& incompressible_on_rigid_solver() {
  static const coatcontact::ReducedSolver solver = [] {
    coatcontact::Material film;
    film.youngs_modulus = 1.0;
    film.poisson_ratio = 0.5;
    coatcontact::Substrate substrate;
    substrate.rigid = true;
    coatcontact::ReducedSolver s(coatcontact::Stack::film_on(film, substrate));
    s.solve(100.0, 1e-8);  // builds the independent tables
    return s;
  }();
  return solver;
}

void BM_SolveIncompressibleOnRigid(benchmark::State& state) {
  const double a_over_t = static_cast<double>(state.range(0));
  time_one_radius(state, incompressible_on_rigid_solver(), a_over_t);
}
BENCHMARK(BM_SolveIncompressibleOnRigid)->Arg(10)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

// The standard sweep with sweep() (parallel over radii when OpenMP is available).
void BM_StandardSweep(benchmark::State& state) {
  const auto& solver = soft_film_solver();
  const auto radii = standard_sweep_radii();
  std::vector<coatcontact::ReducedVariables> rows;
  for (auto _ : state) {
    rows = solver.sweep(radii, 1e-8);
    benchmark::DoNotOptimize(rows.data());
  }
  double total = 0.0, largest = 0.0, worst = 0.0;
  for (const auto& v : rows) {
    total += v.unknowns;
    largest = std::max(largest, double(v.unknowns));
    worst = std::max(worst, v.error_estimate);
  }
  state.counters["radii"] = double(rows.size());
  state.counters["unknowns_total"] = total;
  state.counters["unknowns_max"] = largest;
  state.counters["worst_estimate"] = worst;
}
BENCHMARK(BM_StandardSweep)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same sweep one radius at a time on one thread (the serial cost).
void BM_StandardSweepSerial(benchmark::State& state) {
  const auto& solver = soft_film_solver();
  const auto radii = standard_sweep_radii();
  for (auto _ : state) {
    for (double a : radii) benchmark::DoNotOptimize(solver.solve(a, 1e-8));
  }
  state.counters["radii"] = double(radii.size());
}
BENCHMARK(BM_StandardSweepSerial)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
