// Benchmarks of the Maugis-Dugdale reduced table (THEORY.md section 13, "The cohesive zone as
// a table") on the paper's soft film (E1*/E0* = 0.1, nu = 0.25): one pull-off at
// (eta, lambda) = (1, 1) on a new model (the tiles it needs built on demand), through a table
// that exists, and by the direct per-radius solve; 33 pull-offs (eta = 1, lambda log-spaced
// over 1e-2..1e2, as `pulloff --lambda` with 33 values) on a new model and through an existing
// table; the whole table (a/t in [1e-4, 1e2], c/t <= 1e4) built at once.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "coatcontact/maugis_dugdale.hpp"

namespace {

coatcontact::Stack soft_film() {
  coatcontact::Material film;
  film.youngs_modulus = 0.1;
  film.poisson_ratio = 0.25;
  coatcontact::Substrate substrate;
  substrate.material.youngs_modulus = 1.0;
  substrate.material.poisson_ratio = 0.25;
  return coatcontact::Stack::film_on(film, substrate);
}

coatcontact::MaugisDugdaleOptions table_options() {
  coatcontact::MaugisDugdaleOptions o;
  o.use_table = true;
  return o;
}

// The model whose table is built (by a first point) outside the timings that use it.
const coatcontact::MaugisDugdaleModel& built_model() {
  static const auto model = [] {
    auto m = std::make_unique<coatcontact::MaugisDugdaleModel>(soft_film(), table_options());
    (void)m->point(1.0, 1.0, 1.0);
    return m;
  }();
  return *model;
}

std::vector<std::pair<double, double>> lambdas_33() {
  std::vector<std::pair<double, double>> cases;
  for (int k = 0; k < 33; ++k) cases.emplace_back(1.0, std::pow(10.0, -2.0 + 4.0 * k / 32.0));
  return cases;
}

void BM_md_pulloff_new_table(benchmark::State& state) {
  for (auto _ : state) {
    const coatcontact::MaugisDugdaleModel model(soft_film(), table_options());
    benchmark::DoNotOptimize(model.pulloff(1.0, 1.0));
    state.counters["table_nodes"] = static_cast<double>(model.table_nodes());
    state.counters["table_s"] = model.table_seconds();
  }
}
BENCHMARK(BM_md_pulloff_new_table)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

void BM_md_pulloffs_33_lambda_new_table(benchmark::State& state) {
  const auto cases = lambdas_33();
  for (auto _ : state) {
    const coatcontact::MaugisDugdaleModel model(soft_film(), table_options());
    benchmark::DoNotOptimize(model.pulloffs(cases));
    state.counters["table_nodes"] = static_cast<double>(model.table_nodes());
    state.counters["table_s"] = model.table_seconds();
  }
}
BENCHMARK(BM_md_pulloffs_33_lambda_new_table)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

void BM_md_table_build_whole(benchmark::State& state) {
  for (auto _ : state) {
    const coatcontact::MaugisDugdaleModel model(soft_film(), table_options());
    model.build_table();
    state.counters["table_nodes"] = static_cast<double>(model.table_nodes());
  }
}
BENCHMARK(BM_md_table_build_whole)->Unit(benchmark::kSecond)->Iterations(1)->Repetitions(1)->UseRealTime();

void BM_md_pulloff_table(benchmark::State& state) {
  const coatcontact::MaugisDugdaleModel& model = built_model();
  for (auto _ : state) benchmark::DoNotOptimize(model.pulloff(1.0, 1.0));
}
BENCHMARK(BM_md_pulloff_table)->Unit(benchmark::kMillisecond);

void BM_md_pulloff_direct(benchmark::State& state) {
  static const coatcontact::MaugisDugdaleModel model(soft_film());
  for (auto _ : state) benchmark::DoNotOptimize(model.pulloff(1.0, 1.0));
}
BENCHMARK(BM_md_pulloff_direct)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_md_pulloffs_33_lambda_table(benchmark::State& state) {
  const coatcontact::MaugisDugdaleModel& model = built_model();
  const auto cases = lambdas_33();
  for (auto _ : state) benchmark::DoNotOptimize(model.pulloffs(cases));
}
BENCHMARK(BM_md_pulloffs_33_lambda_table)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
