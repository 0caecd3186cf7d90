// The film's modulus and thickness from synthetic indentation data made with the library's own
// exact coated flat-punch stiffness (THEORY.md section 16, "Checks"): noise-free data give the
// true E1 (or t) at every depth; with noise the fit recovers E1 within 3 standard errors; a
// homogeneous "film" gives its modulus at every depth; a stack whose lower layer equals the
// substrate gives the single film's answer; the coated contact depth recovers data made with
// the coated sink-in, which the half-space epsilon misreads.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../common/check.hpp"
#include "synthetic_film.hpp"

using namespace synthetic;

namespace {

// Bound on the relative error of a noise-free root: the solver delivers E_eq to 1e-8 and
// d ln S / d ln E1 stays above ~0.05 at the deepest a/t used, so E1 is good to ~2e-7.
constexpr double kRootBound = 1e-6;

double worst(const FilmResult& r, double truth) {
  double w = 0;
  for (std::size_t i = 0; i < r.value.size(); ++i) {
    check::that(r.status[i].delivered, "point " + std::to_string(i) + " delivered");
    w = std::max(w, std::fabs(r.value[i] / truth - 1.0));
  }
  return w;
}

OliverPharrOptions op_of(const Film& f) {
  OliverPharrOptions o;
  o.beta = f.beta;
  o.epsilon = f.epsilon;
  o.indenter = f.indenter;
  return o;
}

void noise_free_modulus() {
  Film f;
  f.options = one_film(70e9, 0.17, 500e-9, 162e9, 0.22);  // thermal oxide on silicon
  const IndentTest t = make_test(f, 10e-9, 250e-9, 25);     // a/t 0.06 .. 1.4
  FilmOptions o = f.options;
  o.depth_max = 150e-9;
  const FilmResult r = film(t, op_of(f), o);
  check::below(worst(r, 70e9), kRootBound, "per-depth E1 from exact data, oxide on silicon");
  check::below(std::fabs(r.mean / 70e9 - 1.0), kRootBound, "fitted E1 from exact data");
  check::that(r.apparent_modulus.back() > 1.1 * 70e9, "the Oliver-Pharr modulus shows the substrate at depth");
  std::printf("noise-free: a/t %.3f..%.3f, E_app %.2f..%.2f GPa, E1 worst rel err %.2e, fit %.6g GPa\n",
              r.a_over_t.front(), r.a_over_t.back(), r.apparent_modulus.front() / 1e9,
              r.apparent_modulus.back() / 1e9, worst(r, 70e9), r.mean / 1e9);
}

void noisy_fit() {
  Film f;
  f.options = one_film(70e9, 0.17, 500e-9, 162e9, 0.22);
  f.noise = 0.01;
  const IndentTest t = make_test(f, 10e-9, 200e-9, 60);
  const FilmResult r = film(t, op_of(f), f.options);
  const double z = (r.mean - 70e9) / r.mean_error;
  std::printf("noisy (1%% on S): E1 = %.4g +- %.2g GPa (z = %.2f), s = %.4f, %zu points\n", r.mean / 1e9,
              r.mean_error / 1e9, z, r.rms_relative, r.points);
  check::below(std::fabs(z), 3.0, "fitted E1 within 3 standard errors of the truth");
  check::below(r.mean_error / r.mean, 0.02, "the standard error is a few per mille, not vacuous");
  // A noisy S also moves h_c = h - eps P/S and with it a, which takes up about a third of the
  // 1 % here (eps P/(S h_c) ~ 0.3 at H = 8 GPa): the scatter left is between 0.5 and 1 %.
  check::below(r.rms_relative, 0.01, "the residual scatter is at most the noise");
  check::below(0.005, r.rms_relative, "the residual scatter is not below half the noise");
  // Each per-depth root (interpolated between stacks on a grid of ln E1) put back into a direct
  // solve of its own stack reproduces that depth's E_r = S/(2 beta a): bound 1e-6 as above.
  double worst_root = 0;
  for (std::size_t i = 0; i < r.value.size(); ++i) {
    check::that(r.value_error[i] > 0 && std::isfinite(r.value_error[i]), "per-depth error given");
    const double er = stack_contact_modulus(f.options, f.indenter, r.value[i], r.a_over_t[i]);
    worst_root = std::max(worst_root, std::fabs(er / (r.stiffness[i] / (2 * f.beta * r.contact_radius[i])) - 1));
  }
  std::printf("noisy: per-depth E1 %.3f..%.3f GPa, worst root residual %.2e\n",
              *std::min_element(r.value.begin(), r.value.end()) / 1e9,
              *std::max_element(r.value.begin(), r.value.end()) / 1e9, worst_root);
  check::below(worst_root, kRootBound, "per-depth roots reproduce their E_r");
}

void homogeneous() {
  Film f;
  f.options = one_film(72e9, 0.17, 300e-9, 72e9, 0.17);
  const IndentTest t = make_test(f, 5e-9, 600e-9, 20);  // a/t up to 5.6
  const FilmResult r = film(t, op_of(f), f.options);
  check::below(worst(r, 72e9), kRootBound, "homogeneous film: the same modulus at every depth");
  for (double e : r.apparent_modulus) check::close(e, 72e9, 1e-12, "Oliver-Pharr on a half-space gives E");
}

void multilayer_equals_bilayer() {
  Film f;
  f.options = one_film(70e9, 0.17, 300e-9, 162e9, 0.22);
  f.noise = 0.02;
  const IndentTest t = make_test(f, 10e-9, 200e-9, 12);
  FilmOptions stack = f.options;  // the film, then 200 nm of silicon on silicon
  stack.layers.push_back(Layer{200e-9, Material{162e9, 0.22}, false});
  const FilmResult one = film(t, op_of(f), f.options), two = film(t, op_of(f), stack);
  for (std::size_t i = 0; i < one.value.size(); ++i)
    check::close(two.value[i], one.value[i], kRootBound, "layers: lower layer = substrate gives the bilayer");
  check::close(two.mean, one.mean, kRootBound, "layers: the fitted E1 too");
  check::close(two.a_over_t[3] * 500.0 / 300.0, one.a_over_t[3], 1e-12, "a/t of the stack uses the total thickness");
}

void thickness() {
  Film f;
  f.options = one_film(70e9, 0.17, 500e-9, 162e9, 0.22);
  const IndentTest t = make_test(f, 20e-9, 250e-9, 15);
  FilmOptions o = f.options;
  o.unknown = FilmUnknown::kThickness;
  o.layers.front().thickness = 300e-9;  // only the start
  const FilmResult r = film(t, op_of(f), o);
  check::below(worst(r, 500e-9), kRootBound, "per-depth thickness with the modulus given");
  check::below(std::fabs(r.mean / 500e-9 - 1.0), kRootBound, "fitted thickness");
}

void coated_contact_depth() {
  Film f;
  f.options = one_film(70e9, 0.17, 300e-9, 400e9, 0.2);  // a stiff substrate: kappa < 1
  f.coated_sink_in = true;
  const IndentTest t = make_test(f, 10e-9, 200e-9, 10);
  FilmOptions o = f.options;
  o.contact_depth = ContactDepth::kCoated;
  const FilmResult coated = film(t, op_of(f), o), half = film(t, op_of(f), f.options);
  check::below(worst(coated, 70e9), kRootBound, "the coated contact depth recovers data made with it");
  check::that(half.value.back() > 70e9 * 1.001, "the half-space epsilon overestimates E1 on a stiff substrate");
  std::printf("coated sink-in data: deepest point E1 = %.4g GPa (coated h_c), %.4g GPa (half-space eps)\n",
              coated.value.back() / 1e9, half.value.back() / 1e9);
}

// The contact area from the vendor's hardness column (A = P/H) instead of the area function:
// with H written as the data's own P/A the two give the same film modulus at every depth.
void area_from_hardness() {
  Film f;
  f.options = one_film(70e9, 0.17, 500e-9, 162e9, 0.22);
  IndentTest t = make_test(f, 10e-9, 200e-9, 8);
  for (std::size_t i = 0; i < t.depth.size(); ++i)
    t.hardness.push_back(t.load[i] / contact_area(t.calibration.area, t.depth[i] - 0.75 * t.load[i] / t.stiffness[i]));
  OliverPharrOptions by_area = op_of(f), by_h = op_of(f);
  by_h.area_from_hardness = true;
  const FilmResult a = film(t, by_area, f.options), h = film(t, by_h, f.options);
  for (std::size_t i = 0; i < a.value.size(); ++i)
    check::close(h.value[i], a.value[i], 1e-12, "area = hardness gives the area function's E1");
}

void bad_input() {
  Film f;
  f.options = one_film(70e9, 0.17, 500e-9, 162e9, 0.22);
  const IndentTest t = make_test(f, 10e-9, 100e-9, 5);
  FilmOptions o = f.options;
  o.layers.clear();
  check::throws<InputError>([&] { film(t, op_of(f), o); }, {"layers"});
  o = f.options;
  o.model = FilmModel::kBec;
  o.contact_depth = ContactDepth::kCoated;
  check::throws<InputError>([&] { film(t, op_of(f), o); }, {"coated"});
  check::throws<InputError>([&] { film_model_from_name("nix"); }, {"nix", "doerner-nix"});
}

}  // namespace

int main() {
  noise_free_modulus();
  noisy_fit();
  homogeneous();
  multilayer_equals_bilayer();
  thickness();
  coated_contact_depth();
  area_from_hardness();
  bad_input();
  return check::exit_code();
}
