// The AFM Hertz fit on a multi-layer sample (THEORY.md section 15, "A stack of layers"; check
// "AFM stack fit"): AfmCoating carries layers, the free layer's modulus read from the tabled
// force law (CoatedTable) of that layer.
//  - Two identical bonded layers of thicknesses h1 + h2 = t are one film of thickness t: the
//    stack's model force equals the film's (both tables' estimated errors are ~1e-6, their
//    log-log force tables ~1e-5); with E fixed, the fitted z_c and b of a noisy curve equal the
//    film's within 1/100 of their standard errors (the models differ by the tables' errors only,
//    far below the noise); on the noise-free curve the free top layer's E lands on the truth
//    within 1/100 of the noisy fit's standard error (with "recovery": its search is slow).
//  - A cell (1 um, 2 kPa) on a gel (4 um, 20 kPa) on a rigid base: a curve made by the stack's own
//    model plus noise; the cell's modulus (layer 1 free) and the gel's (layer 2 free), each from a
//    start 4x off, are recovered within 3 standard errors.
//  - Bad input: a free layer outside the stack, a free t or Maugis-Dugdale on two layers (JKR and
//    DMT take a stack: test_afm_stack_adhesive.cpp).
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/stack.hpp"

namespace fit = coatcontact::fit;
using coatcontact::InputError;
using coatcontact::Layer;
using coatcontact::Material;
using coatcontact::Stack;
using coatcontact::Substrate;

namespace {

struct Curve {
  std::vector<double> z, f;
};

fit::AfmFitProblem problem_on(const fit::AfmCoating& coating) {
  fit::AfmFitProblem p;
  p.tip = fit::afm_paraboloid(10e-6);
  p.coating = coating;
  p.poisson = coating.film.poisson_ratio;
  p.contact_point = 2e-6;
  p.baseline = 1e-10;
  return p;
}

Curve synthetic(const fit::AfmFitProblem& truth, double noise, unsigned seed) {
  Curve c;
  for (int i = 0; i < 300; ++i) c.z.push_back(4e-6 * (1.0 - i / 299.0));
  c.f = fit::afm_model_force(truth, c.z);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  if (noise > 0.0) {
    for (double& v : c.f) v += gauss(rng);
  }
  return c;
}

void check_identical_layers() {
  Substrate elastic;
  elastic.material = {1e6, 0.3};
  const Material film{5e3, 0.5};
  fit::AfmCoating one;
  one.film = film;
  one.substrate = elastic;
  one.thickness = 2e-6;
  const fit::AfmCoating two = fit::afm_coating(Stack({Layer{0.7e-6, film}, Layer{1.3e-6, film}}, elastic), 0);
  check::that(two.multilayer() && two.total_thickness(two.thickness) == 2e-6, "two layers, T = 2 um");
  fit::AfmFitProblem p1 = problem_on(one), p2 = problem_on(two);

  const Curve clean = synthetic(p1, 0.0, 0);
  const std::vector<double> f2 = fit::afm_model_force(p2, clean.z);
  double worst = 0.0;
  for (std::size_t i = 0; i < f2.size(); ++i) {
    const double contact = clean.f[i] - p1.baseline;
    if (contact > 1e-12) worst = std::max(worst, std::abs((f2[i] - p1.baseline) / contact - 1.0));
  }
  std::printf("identical layers vs one film: model forces differ by %.2e at most (relative)\n", worst);
  // Both are CoatedTable values (estimated <= ~1e-6) through the same log-log force table.
  check::below(worst, 1e-5, "two identical layers: the film's force");

  const Curve noisy = synthetic(p1, 1e-9, 7);
  for (fit::AfmFitProblem* p : {&p1, &p2}) p->free.modulus = false;
  const fit::AfmFitResult r1 = fit::afm_fit(noisy.z, noisy.f, p1);
  const fit::AfmFitResult r2 = fit::afm_fit(noisy.z, noisy.f, p2);
  std::printf("E fixed: z_c %.9g vs %.9g +- %.3g m, b %.6g vs %.6g +- %.3g N\n", r2.contact_point, r1.contact_point,
              r1.contact_point_error, r2.baseline, r1.baseline, r1.baseline_error);
  check::below(std::abs(r2.contact_point - r1.contact_point) / r1.contact_point_error, 0.01, "identical layers: z_c within SE/100");
  check::below(std::abs(r2.baseline - r1.baseline) / r1.baseline_error, 0.01, "identical layers: b within SE/100");

}

// The identical layers with the top layer's modulus free (a search: ~20 table nodes, slow).
void check_identical_layers_free() {
  Substrate elastic;
  elastic.material = {1e6, 0.3};
  const Material film{5e3, 0.5};
  fit::AfmCoating one;
  one.film = film;
  one.substrate = elastic;
  one.thickness = 2e-6;
  fit::AfmFitProblem p1 = problem_on(one);
  fit::AfmFitProblem p2 = problem_on(fit::afm_coating(Stack({Layer{0.7e-6, film}, Layer{1.3e-6, film}}, elastic), 0));
  const Curve clean = synthetic(p1, 0.0, 0), noisy = synthetic(p1, 1e-9, 7);
  p2.coating->film.youngs_modulus = 2e4;  // the start 4x off
  const fit::AfmFitResult se = fit::afm_fit(noisy.z, noisy.f, p1);
  const fit::AfmFitResult r = fit::afm_fit(clean.z, clean.f, p2);
  std::printf("noise-free, top layer free: E1 = %.6f Pa (truth 5000, noisy SE %.3g)\n", r.modulus, se.modulus_error);
  check::below(std::abs(r.modulus - 5e3) / se.modulus_error, 0.01, "identical layers, top layer free: E1 on the truth");
}

void check_recovery() {
  Substrate glass;
  glass.rigid = true;
  const Stack cell_on_gel({Layer{1e-6, {2e3, 0.5}}, Layer{4e-6, {2e4, 0.5}}}, glass);
  for (std::size_t k : {0u, 1u}) {
    const fit::AfmFitProblem truth = problem_on(fit::afm_coating(cell_on_gel, k));
    const double e = cell_on_gel.layers()[k].material.youngs_modulus;
    const Curve c = synthetic(truth, 2e-10, 11 + static_cast<unsigned>(k));
    fit::AfmFitProblem p = truth;
    p.coating->film.youngs_modulus = e * 4.0;
    const fit::AfmFitResult r = fit::afm_fit(c.z, c.f, p);
    const std::string name = "cell on gel, layer " + std::to_string(k + 1) + " free";
    std::printf("%s: E = %.6g +- %.3g Pa (truth %g), z_c %.3e m\n", name.c_str(), r.modulus, r.modulus_error, e,
                r.contact_point);
    check::below(std::abs(r.modulus - e) / r.modulus_error, 3.0, name + ": E within 3 SE of the truth");
    check::below(std::abs(r.contact_point - truth.contact_point) / r.contact_point_error, 3.0, name + ": z_c within 3 SE");
  }
}

void check_refusals() {
  Substrate glass;
  glass.rigid = true;
  const Stack two({Layer{1e-6, {2e3, 0.5}}, Layer{4e-6, {2e4, 0.5}}}, glass);
  check::throws<InputError>([&] { fit::afm_coating(two, 2); }, {"free layer 3", "allowed: 1..2", "E1..E2"});
  const Curve c = synthetic(problem_on(fit::afm_coating(two, 0)), 0.0, 0);
  fit::AfmFitProblem p = problem_on(fit::afm_coating(two, 0));
  p.free.thickness = true;
  check::throws<InputError>([&] { fit::afm_fit(c.z, c.f, p); }, {"t is free on one film only", "E1..E2"});
  p = problem_on(fit::afm_coating(two, 0));
  p.coating->free_layer = 5;
  check::throws<InputError>([&] { fit::afm_fit(c.z, c.f, p); }, {"free layer 6", "allowed: 1..2"});
  p = problem_on(fit::afm_coating(two, 0));
  p.model = fit::AfmModel::kMd;
  p.spring_constant = 0.1;
  p.work = 1e-3;
  p.surface_force_range = 1e-9;
  check::throws<InputError>([&] { fit::afm_fit(c.z, c.f, p); }, {"--model md takes one bonded film", "--model hertz, jkr or dmt"});
}

}  // namespace

int main(int argc, char** argv) {
  const std::string part = argc > 1 ? argv[1] : "all";
  if (part == "all" || part == "identical") {
    check_refusals();
    check_identical_layers();
  }
  if (part == "all" || part == "recovery") {
    check_identical_layers_free();
    check_recovery();
  }
  return check::exit_code();
}
