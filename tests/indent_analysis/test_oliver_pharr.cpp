// Oliver–Pharr and the calibration (THEORY.md section 16). On the shared fused-silica NanoSuite
// file (data/indentation/FS_Calibration.xls): E and H averaged over the file's range, computed
// from load, displacement and harmonic contact stiffness with the file's area function, against
// the vendor's own per-test "E/H Average Over Defined Range" (E within 0.5 %, H within 1 %: the
// issue's acceptance bounds); the quasi-static unloading stiffness against the CSM stiffness at
// the same peak. On data made here: the unloading power law, the area function and the frame
// compliance come back exactly.
#include <cmath>
#include <cstdio>
#include <string>

#include "../common/check.hpp"
#include "coatcontact/oliver_pharr.hpp"

using namespace coatcontact;
using namespace coatcontact::indent;

namespace {

constexpr double kPi = 3.14159265358979323846;

void vendor_averages(const std::vector<IndentTest>& tests) {
  check::that(tests.size() == 16, "16 tests in FS_Calibration.xls");
  double worst_e = 0, worst_h = 0;
  for (const IndentTest& t : tests) {
    const OliverPharrResult r = oliver_pharr(t);  // the file's area function, nu = 0.18, range 100-200 nm
    const double e = t.vendor_results.at("E_mean"), h = t.vendor_results.at("H_mean");
    std::printf("%s: E %.3f GPa (vendor %.3f, %+.2f %%), H %.3f GPa (vendor %.3f, %+.2f %%), %zu points\n",
                t.name.c_str(), r.modulus_mean / 1e9, e / 1e9, 100 * (r.modulus_mean / e - 1), r.hardness_mean / 1e9,
                h / 1e9, 100 * (r.hardness_mean / h - 1), r.range_points);
    check::close(r.modulus_mean, e, 0.005, t.name + ": E against the vendor's average");
    check::close(r.hardness_mean, h, 0.01, t.name + ": H against the vendor's average");
    check::that(r.csm && r.range_points > 100, t.name + ": CSM points in 100-200 nm");
    worst_e = std::max(worst_e, std::fabs(r.modulus_mean / e - 1));
    worst_h = std::max(worst_h, std::fabs(r.hardness_mean / h - 1));
  }
  std::printf("worst: E %.3f %%, H %.3f %%\n", 100 * worst_e, 100 * worst_h);
}

// Two measurements of one stiffness: the unloading's power law at the peak and the CSM channel
// there. Measured: 0.5-4.9 % apart on these tests (the hold's creep and the CSM oscillation
// differ); bound 7 %.
void unloading_on_file(const std::vector<IndentTest>& tests) {
  for (std::size_t k : {0u, 5u, 10u}) {
    const IndentTest& t = tests[k];
    OliverPharrOptions o;
    o.stiffness = StiffnessSource::kUnloading;
    const OliverPharrResult r = oliver_pharr(t, o);
    std::size_t top = 0;
    for (std::size_t i = 0; i < t.load.size(); ++i)
      if (t.load[i] > t.load[top]) top = i;
    double csm = 0;  // the CSM stiffness over the last 5 loading points before the peak
    int n = 0;
    for (std::size_t j = top + 1; j-- > 0 && n < 5;)
      if (t.stiffness[j] > 0) { csm += t.stiffness[j]; ++n; }
    csm /= n;
    std::printf("%s unloading: S %.4g N/m (m %.3f, h_f %.1f nm, %zu points, rms %.1e), CSM %.4g N/m\n", t.name.c_str(),
                r.unloading.stiffness, r.unloading.exponent, r.unloading.final_depth * 1e9, r.unloading.points,
                r.unloading.rms_relative, csm);
    check::close(r.unloading.stiffness, csm, 0.07, t.name + ": unloading S near the CSM S at the peak");
    check::that(r.unloading.exponent > 1.0 && r.unloading.exponent < 2.0, "unloading exponent between 1 and 2");
  }
}

void unloading_power_law() {
  const double alpha = 3.2e5, hf = 400e-9, m = 1.38;  // P in N, h in m
  std::vector<double> h, p;
  for (int i = 0; i <= 100; ++i) {  // loading, then unloading to 20 % of P_max
    h.push_back(1e-6 * i / 100);
    p.push_back(alpha * std::pow(std::max(0.0, h.back() - hf), m) * (0.5 + 0.5 * i / 100.0));
  }
  const double hmax = 1e-6, pmax = alpha * std::pow(hmax - hf, m);
  for (int i = 0; i < 200; ++i) {
    const double pp = pmax * (1 - 0.8 * i / 199.0);
    p.push_back(pp);
    h.push_back(hf + std::pow(pp / alpha, 1 / m));
  }
  const UnloadingFit f = fit_unloading(h, p);
  const double s = m * alpha * std::pow(hmax - hf, m - 1);
  // The log-log line is exact for an exact power law; the profile's minimum in ln(h_min - h_f)
  // is located to ~sqrt(machine epsilon) (a minimum, not a root), so h_f, m and S to ~1e-5.
  check::close(f.final_depth, hf, 1e-5, "unloading h_f");
  check::close(f.exponent, m, 1e-5, "unloading m");
  check::close(f.stiffness, s, 1e-5, "unloading S = m alpha (h_max - h_f)^(m-1)");
}

// CSM data of a sample with E = 72 GPa on a tip with a known area function, 1/S_meas = 1/S + C_f.
IndentTest calibration_data(const AreaFunction& area, double compliance, double hmin, double hmax) {
  IndentTest t;
  const Indenter tip{false, diamond()};
  const double er = reduced_of_sample(72e9, 0.17, tip), hardness = 9e9;
  for (int i = 0; i < 80; ++i) {
    const double hc = hmin + (hmax - hmin) * i / 79;
    const double a = contact_area(area, hc), s = 2 * er * std::sqrt(a / kPi), p = hardness * a;
    t.depth.push_back(hc + 0.75 * p / s);
    t.load.push_back(p);
    t.stiffness.push_back(1 / (1 / s + compliance));
  }
  return t;
}

void calibration() {
  const AreaFunction area{{24.5, 410.0, -1300.0}};
  CalibrationOptions c;
  c.terms = 3;
  const AreaCalibration a = calibrate_area({calibration_data(area, 0, 40e-9, 900e-9)}, c);
  for (std::size_t k = 0; k < 3; ++k)
    // A linear least-squares fit of exact data: the coefficients to the conditioning of the
    // three columns h^2, h, h^(1/2) over 40-900 nm (~1e6) times the rounding: kAmplified x 1e3.
    check::close(a.area.coefficients[k], area.coefficients[k], 1e-8, "area coefficient C" + std::to_string(k), 1.0);
  check::below(a.rms_relative, 1e-10, "area fit residual of exact data");
  c.fixed_c0 = 24.5;
  const AreaCalibration held = calibrate_area({calibration_data(area, 0, 40e-9, 900e-9)}, c);
  check::that(held.area.coefficients[0] == 24.5 && held.errors[0] == 0.0, "held C0 stays 24.5");
  check::close(held.area.coefficients[1], 410.0, 1e-8, "C1 with C0 held");
  // Frame: constant hardness and a perfect Berkovich make 1/S_meas exactly linear in 1/sqrt(P).
  const double cf = 1.5e-7;
  const FrameCalibration f = calibrate_frame({calibration_data(AreaFunction{{24.5}}, cf, 50e-9, 2000e-9)}, c);
  check::close(f.compliance, cf, 1e-9, "frame compliance from 1/S against 1/sqrt(P)");
  check::close(f.frame_stiffness, 1 / cf, 1e-9, "frame stiffness");
  // ... and Oliver–Pharr with that stiffness removes it again: E = 72 GPa at every depth.
  OliverPharrOptions o;
  o.area = AreaFunction{{24.5}};
  o.poisson = 0.17;
  o.frame_stiffness = 1 / cf;
  IndentTest t = calibration_data(AreaFunction{{24.5}}, cf, 50e-9, 2000e-9);
  for (std::size_t i = 0; i < t.depth.size(); ++i) t.depth[i] += t.load[i] * cf;  // the frame's own deflection
  const OliverPharrResult r = oliver_pharr(t, o);
  for (double e : r.modulus) check::close(e, 72e9, 1e-12, "E after the frame correction");
  check::close(r.hardness.back(), 9e9, 1e-12, "H after the frame correction");
}

void bad_options(const IndentTest& t) {
  OliverPharrOptions o;
  o.beta = -1;
  check::throws<InputError>([&] { oliver_pharr(t, o); }, {"beta", "-1"});
  o = {};
  o.depth_min = 300e-9;
  o.depth_max = 200e-9;
  check::throws<InputError>([&] { oliver_pharr(t, o); }, {"depth range maximum"});
  IndentTest bare = t;
  bare.calibration.poisson = kNotGiven;
  check::throws<InputError>([&] { oliver_pharr(bare, {}); }, {"Poisson"});
  bare = t;
  bare.calibration.area.coefficients.clear();
  check::throws<InputError>([&] { oliver_pharr(bare, {}); }, {"area function"});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::printf("usage: test_oliver_pharr DATA_DIR\n");
    return 2;
  }
  const auto tests = read_indentation(std::string(argv[1]) + "/FS_Calibration.xls");
  vendor_averages(tests);
  unloading_on_file(tests);
  unloading_power_law();
  calibration();
  bad_options(tests.front());
  return check::exit_code();
}
