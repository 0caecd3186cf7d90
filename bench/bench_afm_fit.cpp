// Benchmarks of the AFM curve fit (issue 24, THEORY.md section 15): the adhesionless Hertz fit
// of the 2000-point approach of data/afm/fmt-jpk-fd_spot3-0192.jpk-force (10 um sphere on a
// half-space; E, contact point and baseline free; target <= 5 ms), and the same with the tip as
// a tabulated blunted cone (the Sneddon table is built in every fit). The file is read once.
#include <benchmark/benchmark.h>
#include <time.h>

#include <random>
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

Approach segment_of(const std::string& file, coatcontact::afm::SegmentKind kind) {
  const auto curve = coatcontact::afm::read_force_curves(std::string(CC_AFM_DATA_DIR) + "/" + file).at(0);
  const auto* s = curve.find_segment(kind);
  const auto tip = curve.tip_position();
  return Approach{{tip.begin() + s->begin, tip.begin() + s->end}, {curve.force.begin() + s->begin, curve.force.begin() + s->end}};
}

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
  int evaluations = 0;
  for (auto _ : state) {
    const auto r = coatcontact::fit::afm_fit(a.z, a.f, problem);
    benchmark::DoNotOptimize(r.modulus);
    modulus = r.modulus;
    evaluations = r.profile_evaluations;
  }
  state.counters["points"] = static_cast<double>(a.z.size());
  state.counters["E_Pa"] = modulus;
  state.counters["profile_evaluations"] = evaluations;
}

void BM_afm_fit_hertz_2000_point_approach(benchmark::State& state) {
  run_fit(state, coatcontact::fit::afm_paraboloid(10e-6));
}
void BM_afm_fit_blunted_cone_2000_point_approach(benchmark::State& state) {
  run_fit(state, coatcontact::fit::afm_shape(coatcontact::make_blunted_cone(50e-9, 1.2217304763960306)));
}

void BM_afm_fit_jkr_hydrogel_3000_point_retract(benchmark::State& state) {
  static const Approach a = segment_of("fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force", coatcontact::afm::SegmentKind::kRetract);
  coatcontact::fit::AfmFitProblem problem;
  problem.model = coatcontact::fit::AfmModel::kJkr;
  problem.tip = coatcontact::fit::afm_paraboloid(10e-6);
  problem.modulus = 10e3;
  problem.poisson = 0.5;
  problem.spring_constant = 0.061;
  problem.free = {true, true, true, false, true, true};
  double work = 0.0;
  for (auto _ : state) {
    work = coatcontact::fit::afm_fit(a.z, a.f, problem).work;
    benchmark::DoNotOptimize(work);
  }
  state.counters["points"] = static_cast<double>(a.z.size());
  state.counters["w_J_m2"] = work;
}

// A film (E1 = 100 kPa, nu 0.5, t = 4 um) on E0 = 1 MPa, R = 10 um, w = 10 mJ/m2, k = 1 N/m:
// 2000 tip positions over 3 um below to 3 um above the contact point, noise 5 nN.
coatcontact::fit::AfmFitProblem coating_truth() {
  coatcontact::fit::AfmFitProblem p;
  p.model = coatcontact::fit::AfmModel::kJkr;
  p.tip = coatcontact::fit::afm_paraboloid(10e-6);
  coatcontact::fit::AfmCoating c;
  c.film = {100e3, 0.5};
  c.substrate.material = {1e6, 0.3};
  c.thickness = 4e-6;
  p.coating = c;
  p.poisson = 0.5;
  p.work = 10e-3;
  p.spring_constant = 1.0;
  p.contact_point = 1e-6;
  p.baseline = 2e-9;
  p.tilt = 0.01;
  return p;
}

const Approach& coating_retract() {
  static const Approach a = [] {
    Approach out;
    for (int i = 0; i < 2000; ++i) out.z.push_back(-2e-6 + 6e-6 * i / 1999.0);
    out.f = coatcontact::fit::afm_model_force(coating_truth(), out.z);
    std::mt19937_64 rng(1);
    std::normal_distribution<double> noise(0.0, 5e-9);
    for (double& v : out.f) v += noise(rng);
    return out;
  }();
  return a;
}

// CPU time of the whole process (all threads: the solver's sweeps run in parallel; the
// benchmark library's own CPU column counts the calling thread only) [s].
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// cold: the shared node sweeps dropped before every fit (a first curve); else kept (a further
// curve of the same sample, as in a map).
void run_coating(benchmark::State& state, bool modulus_free, bool cold = true) {
  const Approach& a = coating_retract();
  coatcontact::fit::AfmFitProblem problem = coating_truth();
  problem.coating->film.youngs_modulus = modulus_free ? 250e3 : 100e3;
  problem.work = 0.0;
  problem.tilt = 0.0;
  problem.free = {modulus_free, true, true, false, true, true};
  long calls = 0;
  double cpu = 0.0;
  for (auto _ : state) {
    if (cold) coatcontact::fit::afm_clear_shared_sweeps();
    const double before = process_cpu_seconds();
    const auto r = coatcontact::fit::afm_fit(a.z, a.f, problem);
    cpu += process_cpu_seconds() - before;
    calls = r.solver_calls;
    benchmark::DoNotOptimize(calls);
  }
  state.counters["points"] = static_cast<double>(a.z.size());
  state.counters["solves"] = static_cast<double>(calls);
  state.counters["process_cpu_ms"] = 1e3 * cpu / static_cast<double>(state.iterations());
}

void BM_afm_fit_jkr_coating_E1_w_free(benchmark::State& state) { run_coating(state, true); }
void BM_afm_fit_jkr_coating_w_free(benchmark::State& state) { run_coating(state, false); }
void BM_afm_fit_jkr_coating_E1_w_free_further_curve(benchmark::State& state) { run_coating(state, true, false); }

// Hertz on a coating (THEORY.md section 15, "Tabled coated force laws"): spot3's approach as a
// film (nu1 = 0.5, t = 2 um, E1 started at 10 kPa, free) on E0 = 1 MPa (nu0 0.3) or on a rigid
// base. cold: the shared table dropped before every fit (a sample's first curve: the fit builds
// the nodes it needs); warm: kept (a further curve); direct: a solver sweep per trial E1.
enum class Path { kCold, kWarm, kDirect };
void run_hertz_coating(benchmark::State& state, bool rigid, Path path) {
  const Approach& a = spot3_approach();
  coatcontact::fit::AfmFitProblem problem;
  problem.tip = coatcontact::fit::afm_paraboloid(10e-6);
  coatcontact::fit::AfmCoating c;
  c.film = {1e4, 0.5};
  if (rigid) c.substrate.rigid = true;
  else c.substrate.material = {1e6, 0.3};
  c.thickness = 2e-6;
  c.direct = path == Path::kDirect;
  problem.coating = c;
  double cpu = 0.0, modulus = 0.0;
  long solves = 0;
  int evaluations = 0;
  if (path == Path::kWarm) coatcontact::fit::afm_fit(a.z, a.f, problem);  // the table exists
  for (auto _ : state) {
    if (path == Path::kCold) coatcontact::fit::afm_clear_shared_sweeps();
    const double before = process_cpu_seconds();
    const auto r = coatcontact::fit::afm_fit(a.z, a.f, problem);
    cpu += process_cpu_seconds() - before;
    modulus = r.modulus;
    solves = r.solver_calls;
    evaluations = r.profile_evaluations;
  }
  state.counters["E1_Pa"] = modulus;
  state.counters["profile_evaluations"] = evaluations;
  state.counters["solves"] = static_cast<double>(solves);
  state.counters["process_cpu_ms"] = 1e3 * cpu / static_cast<double>(state.iterations());
}
void BM_afm_fit_hertz_coating_elastic_E1_free_first_curve(benchmark::State& s) { run_hertz_coating(s, false, Path::kCold); }
void BM_afm_fit_hertz_coating_elastic_E1_free_further_curve(benchmark::State& s) { run_hertz_coating(s, false, Path::kWarm); }
void BM_afm_fit_hertz_coating_elastic_E1_free_direct(benchmark::State& s) { run_hertz_coating(s, false, Path::kDirect); }
void BM_afm_fit_hertz_coating_rigid_E1_free_first_curve(benchmark::State& s) { run_hertz_coating(s, true, Path::kCold); }
void BM_afm_fit_hertz_coating_rigid_E1_free_further_curve(benchmark::State& s) { run_hertz_coating(s, true, Path::kWarm); }
void BM_afm_fit_hertz_coating_rigid_E1_free_direct(benchmark::State& s) { run_hertz_coating(s, true, Path::kDirect); }

}  // namespace

BENCHMARK(BM_afm_fit_hertz_coating_elastic_E1_free_first_curve)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_afm_fit_hertz_coating_elastic_E1_free_further_curve)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_hertz_coating_elastic_E1_free_direct)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_afm_fit_hertz_coating_rigid_E1_free_first_curve)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_afm_fit_hertz_coating_rigid_E1_free_further_curve)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_hertz_coating_rigid_E1_free_direct)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_afm_fit_jkr_hydrogel_3000_point_retract)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_jkr_coating_E1_w_free)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_jkr_coating_w_free)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_jkr_coating_E1_w_free_further_curve)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_hertz_2000_point_approach)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_afm_fit_blunted_cone_2000_point_approach)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
