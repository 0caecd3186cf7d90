// Synthetic CSM indentation tests of a film from the library's own exact coated stiffness
// (THEORY.md section 16): a perfect Berkovich area function, a constant hardness, and at each
// contact depth h_c the stack's S = 2 beta a E_ref E_eq(a/t), P = H A, h = h_c + eps kappa P/S.
#pragma once
#include <cmath>
#include <random>
#include <vector>

#include "coatcontact/indent_film.hpp"
#include "coatcontact/reduced.hpp"

namespace synthetic {

using namespace coatcontact;
using namespace coatcontact::indent;

constexpr double kPi = 3.14159265358979323846;

struct Film {
  FilmOptions options;            // the layers with their true moduli, the substrate
  Indenter indenter{false, diamond()};
  double beta = 1.0, epsilon = 0.75, hardness = 8e9;
  bool coated_sink_in = false;    // h - h_c from the coated cone (kappa), else the half-space's
  double noise = 0.0;             // relative sd of S
  unsigned seed = 38;
};

// kappa of the stack at a/t: the coated cone's sink-in over the homogeneous cone's.
inline double kappa(const Stack& stack, double a_over_t) {
  const ReducedVariables v = ReducedSolver(stack).solve(a_over_t);
  return 8.0 * v.e_eq / (kPi * v.pi_c) * (0.5 * kPi * v.delta_c - 1.0) / (2.0 - 4.0 / kPi);
}

// Contact depths from hc_min to hc_max (m), n points.
inline IndentTest make_test(const Film& f, double hc_min, double hc_max, int n) {
  IndentTest t;
  t.name = "synthetic film";
  t.calibration.area.coefficients = {24.5};
  t.calibration.poisson = f.options.layers.front().material.poisson_ratio;
  double total = 0;
  for (const Layer& l : f.options.layers) total += l.thickness;
  const Stack stack(f.options.layers, f.options.substrate, f.indenter);
  std::mt19937 rng(f.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double hc = hc_min + (hc_max - hc_min) * i / (n - 1);
    const double area = 24.5 * hc * hc, a = std::sqrt(area / kPi);
    const double er = stack_contact_modulus(f.options, f.indenter, f.options.layers.front().material.youngs_modulus,
                                            a / total);
    const double s = 2.0 * f.beta * a * er, p = f.hardness * area;
    const double k = f.coated_sink_in ? kappa(stack, a / total) : 1.0;
    t.depth.push_back(hc + f.epsilon * k * p / s);
    t.load.push_back(p);
    t.stiffness.push_back(s * (1.0 + f.noise * gauss(rng)));
  }
  return t;
}

inline FilmOptions one_film(double e1, double nu1, double thickness, double e0, double nu0) {
  FilmOptions o;
  o.layers = {Layer{thickness, Material{e1, nu1}, false}};
  o.substrate = Substrate{false, Material{e0, nu0}};
  return o;
}

}  // namespace synthetic
