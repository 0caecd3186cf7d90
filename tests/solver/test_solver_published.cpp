// Comparison with the published approximations of THEORY.md section 6 (fits, not exact):
// Perriot & Barthel's 2004 empirical E_eq and the bottom-effect series for a sphere on a thin
// bonded incompressible layer on a rigid base (Dimitriadis et al. 2002). Printed as markdown
// tables (reproduced in docs/solver.md). A comparison, not a pass/fail gate: the test fails
// only if the solver itself fails or returns non-finite numbers.
#include <cmath>
#include <cstdio>
#include <exception>

#include "coatcontact/reduced.hpp"

using namespace coatcontact;

namespace {

int failures = 0;

void require(bool condition, const char* what) {
  if (!condition) {
    ++failures;
    std::printf("FAIL %s\n", what);
  }
}

// E_eq,fit / E1* = r + (1 - r) / (1 + (ã/x0)^n), r = E0*/E1*, log10 x0 = -0.093 + 0.792 L
// + 0.05 L², L = log10 r, n = 1.27. (Written so that ã -> 0 gives the film, 1; THEORY.md's
// "(x0 t/a)^n" with E0* and E1* in those places would give the substrate at ã -> 0.)
double perriot_barthel_fit(double r, double a) {
  const double l = std::log10(r);
  const double x0 = std::pow(10.0, -0.093 + 0.792 * l + 0.05 * l * l);
  return r + (1.0 - r) / (1.0 + std::pow(a / x0, 1.27));
}

void compare_perriot_barthel() {
  std::printf("\n### E_eq: solver vs the Perriot-Barthel 2004 fit (nu0 = nu1 = 0.25)\n\n");
  std::printf("| E1*/E0* | a/t | E_eq solver | E_eq fit | fit/solver - 1 |\n|---|---|---|---|---|\n");
  for (double ratio : {0.01, 0.1, 10.0, 100.0}) {
    Material film;
    film.youngs_modulus = ratio;
    film.poisson_ratio = 0.25;
    Substrate substrate;
    substrate.material.youngs_modulus = 1.0;
    substrate.material.poisson_ratio = 0.25;
    const ReducedSolver solver(Stack::film_on(film, substrate));
    double worst = 0.0;
    for (double a : {0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0}) {
      const ReducedVariables v = solver.solve(a);
      require(std::isfinite(v.e_eq) && v.e_eq > 0.0, "E_eq finite and positive");
      const double fit = perriot_barthel_fit(1.0 / ratio, a);
      const double deviation = fit / v.e_eq - 1.0;
      worst = std::max(worst, std::abs(deviation));
      std::printf("| %g | %g | %.6f | %.6f | %+.3f |\n", ratio, a, v.e_eq, fit, deviation);
    }
    std::printf("| %g | worst | | | %.3f |\n", ratio, worst);
  }
}

// Sphere on an incompressible film bonded to a rigid base: F/F_Hertz at the same δ is
// (3/8) Π_s / Δ_s^{3/2}, and χ = sqrt(R δ)/t = ã sqrt(Δ_s).
void compare_bottom_effect() {
  std::printf("\n### Sphere on a thin incompressible bonded layer (rigid base): F/F_Hertz\n\n");
  std::printf("| a/t | chi | solver | series 1 + 1.133 chi + 1.283 chi^2 + 0.769 chi^3 + 0.0975 chi^4 | series/solver - 1 |\n|---|---|---|---|---|\n");
  Material film;
  film.youngs_modulus = 1.0;
  film.poisson_ratio = 0.5;
  Substrate substrate;
  substrate.rigid = true;
  const ReducedSolver solver(Stack::film_on(film, substrate));
  for (double a : {0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0}) {
    const ReducedVariables v = solver.solve(a);
    const double ratio = 3.0 / 8.0 * v.pi_s / std::pow(v.delta_s, 1.5);
    const double chi = a * std::sqrt(v.delta_s);
    const double series = 1.0 + 1.133 * chi + 1.283 * chi * chi + 0.769 * chi * chi * chi +
                          0.0975 * chi * chi * chi * chi;
    require(std::isfinite(ratio) && ratio > 0.0, "F/F_Hertz finite and positive");
    std::printf("| %g | %.4f | %.6f | %.6f | %+.4f |\n", a, chi, ratio, series, series / ratio - 1.0);
  }
}

}  // namespace

int main() {
  try {
    compare_perriot_barthel();
    compare_bottom_effect();
  } catch (const std::exception& e) {
    std::printf("FAIL solver error: %s\n", e.what());
    return 1;
  }
  if (failures != 0) return 1;
  std::printf("\ntest_solver_published: comparison printed (not a gate)\n");
  return 0;
}
