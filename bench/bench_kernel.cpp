// Benchmarks of the layered-substrate kernel: table build time (one FFTW DCT-I + DST-I of
// 2^17 panels, pole removal for stiff films) and H(u)/H1(u) evaluation throughput.
#include <benchmark/benchmark.h>

#include <vector>

#include "coatcontact/kernel.hpp"

namespace {

struct Pair {
  double e1, nu1, e0, nu0;
  bool rigid;
};
const Pair kPairs[] = {
    {0.1, 0.25, 1.0, 0.25, false},  // soft film
    {10.0, 0.25, 1.0, 0.25, false}, // stiff film
    {1e3, 0.3, 1.0, 0.3, false},    // very stiff film (pole removal)
    {1.0, 0.5, 1.0, 0.0, true},     // incompressible film on a rigid substrate
};

coatcontact::Material film_of(const Pair& p) { return {p.e1, p.nu1}; }
coatcontact::Substrate substrate_of(const Pair& p) { return {p.rigid, {p.e0, p.nu0}}; }

void BM_TableBuild(benchmark::State& state) {
  const Pair& p = kPairs[state.range(0)];
  for (auto _ : state) {
    coatcontact::KernelTable table(coatcontact::Stack::film_on(film_of(p), substrate_of(p)));
    benchmark::DoNotOptimize(table);
  }
}
BENCHMARK(BM_TableBuild)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_Eval(benchmark::State& state) {
  const Pair& p = kPairs[0];
  const coatcontact::KernelTable table(coatcontact::Stack::film_on(film_of(p), substrate_of(p)));
  std::vector<double> u(4096), h, h1;
  const double u_max = static_cast<double>(state.range(0));
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = u_max * static_cast<double>(i) / 4096.0;
  for (auto _ : state) {
    table.eval(u, h, h1);
    benchmark::DoNotOptimize(h.data());
    benchmark::DoNotOptimize(h1.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(u.size()));
}
// inside the table (interpolation) and far beyond it (asymptotic series)
BENCHMARK(BM_Eval)->Arg(100)->Arg(100000);

void BM_Compliance(benchmark::State& state) {
  const Pair& p = kPairs[1];
  std::vector<double> q(4096);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = 40.0 * static_cast<double>(i) / 4096.0;
  for (auto _ : state) {
    auto c = coatcontact::compliance(coatcontact::Stack::film_on(film_of(p), substrate_of(p)), q);
    benchmark::DoNotOptimize(c.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(q.size()));
}
BENCHMARK(BM_Compliance);

}  // namespace

BENCHMARK_MAIN();
