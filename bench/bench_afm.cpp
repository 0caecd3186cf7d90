// Benchmarks of the AFM readers (issue 24): reading a JPK force curve of 2 x 2000 points
// (data/afm/fmt-jpk-fd_spot3-0192.jpk-force: open, unzip, parse the headers, decode and
// calibrate three channels; target <= 2 ms), a QI map of 4 curves and the Igor wave of 10097
// points. The file is read from disk in every iteration (the page cache keeps it warm).
#include <benchmark/benchmark.h>

#include <string>

#include "coatcontact/afm_readers.hpp"

#ifndef CC_AFM_DATA_DIR
#define CC_AFM_DATA_DIR "data/afm"
#endif

namespace {

void read_file(benchmark::State& state, const char* name) {
  const std::string path = std::string(CC_AFM_DATA_DIR) + "/" + name;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto curves = coatcontact::afm::read_force_curves(path);
    points = 0;
    for (const auto& c : curves) points += c.point_count();
    benchmark::DoNotOptimize(points);
  }
  state.counters["points"] = static_cast<double>(points);
}

void BM_afm_read_jpk_2000_point_curve(benchmark::State& state) { read_file(state, "fmt-jpk-fd_spot3-0192.jpk-force"); }
void BM_afm_read_jpk_qi_map_4_curves(benchmark::State& state) { read_file(state, "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data"); }
void BM_afm_read_igor_10097_points(benchmark::State& state) { read_file(state, "fmt-igor-fd_U3_3_p10004.ibw"); }

}  // namespace

BENCHMARK(BM_afm_read_jpk_2000_point_curve)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_read_jpk_qi_map_4_curves)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_read_igor_10097_points)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
