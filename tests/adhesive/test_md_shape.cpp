// The Maugis-Dugdale cohesive zone under an indenter of any axisymmetric shape (THEORY.md
// section 13, "Any axisymmetric shape"): CohesiveZone with a shape load δ0(x).
//  1. the paraboloid given as a shape load (δ0 = x²/R) equals the sphere's own path
//     (closed-form gap term) on coatings, states and the four table functions;
//  2. the homogeneous cone (δ0 = k x) equals the closed form derived in section 13 and
//     written out here: δ = k a - σ̂ sqrt(c² - a²), F = 2 (δ a - k a²/2) - σ̂ [c² φa - a sqrt(c² - a²)],
//     h(c) = (2/π) [k sqrt(c² - a²) - δ φa - σ̂ (c - a)], and at the curve's end a = 0;
//  3. on a coating, the cone's zone is linear in its loads: the state at σ̂ equals the
//     functions' reconstruction δ_H + σ̂ d, F_H + σ̂ f, h = g_R + σ̂ g_σ, with d, f, g_σ those of
//     the paraboloid (the shape enters g_R, δ_H and F_H alone).
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "coatcontact/stack.hpp"
#include "cohesive_zone.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;

namespace {

constexpr double kPi = 3.14159265358979323846;

Stack film_on(double e1, double nu1, double e0, double nu0) {
  Substrate s;
  s.material = {e0, nu0};
  return Stack::film_on({e1, nu1}, s);
}

}  // namespace

int main() {
  const Stack soft = film_on(1.0, 0.25, 10.0, 0.25), stiff = film_on(10.0, 0.25, 1.0, 0.25);
  const Stack homogeneous = film_on(1.0, 0.3, 1.0, 0.3);
  const detail::Discretization disc;
  const detail::CohesiveQuadrature quadrature;

  // 1. Paraboloid as a shape load against the sphere's path.
  for (const Stack* stack : {&soft, &stiff}) {
    const detail::TableKernel kernel(*stack);
    for (double radius : {1.0, 2.5}) {
      for (double a : {0.0, 0.05, 0.7, 4.0}) {
        const detail::CohesiveZone sphere(kernel, a, radius, disc, quadrature);
        const detail::CohesiveZone shaped(kernel, a, [radius](double x) { return x * x / radius; }, disc, quadrature);
        for (double excess : {1e-3, 0.3, 20.0}) {
          const double e = a > 0.0 ? excess : excess * 2.0;  // at a = 0: c itself
          const std::string at = " R=" + check::text(radius) + " a/t=" + check::text(a) + " excess=" + check::text(e);
          const detail::CohesiveState s = sphere.evaluate(0.45, e), p = shaped.evaluate(0.45, e);
          check::close(p.delta, s.delta, check::tier::kAmplified, "paraboloid = sphere: delta" + at, 1e-3);
          check::close(p.force, s.force, check::tier::kAmplified, "paraboloid = sphere: force" + at, 1e-3);
          check::close(p.gap, s.gap, check::tier::kAmplified, "paraboloid = sphere: gap" + at, 1e-6);
          if (a > 0.0) {
            const detail::CohesiveFunctions fs = sphere.functions(e), fp = shaped.functions(e);
            check::close(fp.g_r, fs.g_r, check::tier::kAmplified, "paraboloid = sphere: g_R" + at, 1e-9);
            check::close(fp.delta_h, fs.delta_h, check::tier::kAmplified, "paraboloid = sphere: delta_H" + at);
          }
        }
      }
    }
  }

  // 2. Homogeneous cone, k = (π/2) cot β (section 11), against the closed form.
  {
    const detail::TableKernel kernel(homogeneous);
    for (double k : {0.3, 2.0}) {
      for (double a : {0.0, 0.1, 1.5}) {
        const detail::CohesiveZone cone(kernel, a, [k](double x) { return k * x; }, disc, quadrature);
        for (double excess : {1e-4, 0.5, 30.0}) {
          const double sigma_hat = 0.8;
          const double c = a > 0.0 ? a * (1.0 + excess) : excess;
          const double root = std::sqrt(c * c - a * a), phi = std::acos(a / c);
          const double delta = k * a - sigma_hat * root;
          const double force = 2.0 * (delta * a - 0.5 * k * a * a) - sigma_hat * (c * c * phi - a * root);
          const double gap = 2.0 / kPi * (k * root - delta * phi - sigma_hat * (c - a));
          const detail::CohesiveState st = cone.evaluate(sigma_hat, excess);
          const std::string at = " k=" + check::text(k) + " a/t=" + check::text(a) + " excess=" + check::text(excess);
          check::close(st.delta, delta, check::tier::kReference, "homogeneous cone: delta" + at, c);
          check::close(st.force, force, check::tier::kReference, "homogeneous cone: force" + at, c * c);
          check::close(st.gap, gap, check::tier::kReference, "homogeneous cone: gap" + at, c);
        }
      }
    }
  }

  // 3. A cone on a coating: linear in its loads, its σ̂ parts those of the paraboloid.
  for (const Stack* stack : {&soft, &stiff}) {
    const detail::TableKernel kernel(*stack);
    const double k = 1.2;
    for (double a : {0.05, 0.7, 4.0}) {
      const detail::CohesiveZone cone(kernel, a, [k](double x) { return k * x; }, disc, quadrature);
      const detail::CohesiveZone sphere(kernel, a, 1.0, disc, quadrature);
      for (double excess : {1e-3, 0.3, 20.0}) {
        const std::string at = " a/t=" + check::text(a) + " excess=" + check::text(excess);
        const detail::CohesiveFunctions f = cone.functions(excess), fs = sphere.functions(excess);
        for (double sigma_hat : {0.05, 3.0}) {
          const detail::CohesiveState st = cone.evaluate(sigma_hat, excess);
          check::close(st.delta, f.delta_h + sigma_hat * f.d, check::tier::kReference, "cone linearity: delta" + at,
                       std::abs(f.delta_h));
          check::close(st.force, f.force_h + sigma_hat * f.f, check::tier::kReference, "cone linearity: force" + at,
                       std::abs(f.force_h));
          check::close(st.gap, f.g_r + sigma_hat * f.g_s, check::tier::kReference, "cone linearity: gap" + at,
                       std::abs(f.g_r));
        }
        check::close(f.d, fs.d, check::tier::kMachine, "cone d = paraboloid d" + at);
        check::close(f.f, fs.f, check::tier::kMachine, "cone f = paraboloid f" + at);
        check::close(f.g_s, fs.g_s, check::tier::kMachine, "cone g_sigma = paraboloid g_sigma" + at);
      }
    }
  }
  return check::exit_code();
}
