// Benchmarks of the AFM curve fit (issue 24, THEORY.md section 15): the adhesionless Hertz fit
// of the 2000-point approach of data/afm/fmt-jpk-fd_spot3-0192.jpk-force (10 um sphere on a
// half-space; E, contact point and baseline free; target <= 5 ms), and the same with the tip as
// a tabulated blunted cone (the Sneddon table is built in every fit). The file is read once.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/indenter_shape.hpp"

#ifndef CC_AFM_DATA_DIR
#define CC_AFM_DATA_DIR "data/afm"
#endif

namespace {

struct Approach {
  std::vector<double> z, f;
};

const Approach& spot3_approach() {
  static const Approach a = [] {
    const auto curve = coatcontact::afm::read_force_curves(std::string(CC_AFM_DATA_DIR) + "/fmt-jpk-fd_spot3-0192.jpk-force").at(0);
    const auto* s = curve.find_segment(coatcontact::afm::SegmentKind::kApproach);
    const auto tip = curve.tip_position();
    return Approach{{tip.begin() + s->begin, tip.begin() + s->end}, {curve.force.begin() + s->begin, curve.force.begin() + s->end}};
  }();
  return a;
}

void run_fit(benchmark::State& state, const coatcontact::fit::AfmTip& tip) {
  const Approach& a = spot3_approach();
  coatcontact::fit::AfmFitProblem problem;
  problem.tip = tip;
  problem.poisson = 0.5;
  double modulus = 0.0;
  for (auto _ : state) {
    modulus = coatcontact::fit::afm_fit(a.z, a.f, problem).modulus;
    benchmark::DoNotOptimize(modulus);
  }
  state.counters["points"] = static_cast<double>(a.z.size());
  state.counters["E_Pa"] = modulus;
}

void BM_afm_fit_hertz_2000_point_approach(benchmark::State& state) {
  run_fit(state, coatcontact::fit::afm_paraboloid(10e-6));
}
void BM_afm_fit_blunted_cone_2000_point_approach(benchmark::State& state) {
  run_fit(state, coatcontact::fit::afm_shape(coatcontact::make_blunted_cone(50e-9, 1.2217304763960306)));
}

}  // namespace

BENCHMARK(BM_afm_fit_hertz_2000_point_approach)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_blunted_cone_2000_point_approach)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
