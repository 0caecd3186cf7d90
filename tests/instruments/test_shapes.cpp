// Indenters of any axisymmetric shape (THEORY.md section 11) on a homogeneous half-space
// against Sneddon's closed forms, a sampled profile's convergence order, and spring control
// in SI units (section 10). Each test names the check it makes.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "materials.hpp"
#include "check.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/shape_contact.hpp"

using namespace coatcontact;
using coatcontact::test::elastic;
using coatcontact::test::material;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kClosedForm = 1e-10;

std::string str(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

// Homogeneous half-space: film = substrate, E* = 1e9/(1 - 0.09).
const Stack& homogeneous() {
  static const Stack stack = Stack::film_on(material(1e9, 0.3), elastic(1e9, 0.3));
  return stack;
}

// Check "power law on a homogeneous half-space": δ_H = c_n a^n/R^(n-1),
// F_H = 2E* c_n n a^(n+1)/((n+1) R^(n-1)), and the JKR load-controlled pull-off.
void test_power_law(const ShapeSolver& solver) {
  const double e = homogeneous().reference_modulus();
  const double radius = 2e-6, t = 1e-6, w = 0.05;
  for (double n : {1.5, 2.0, 3.0, 4.0}) {
    const auto shape = make_power_law(n, radius);
    const ShapeContact contact(solver, shape, t, w, 1e-11);
    const double c = power_law_coefficient(n);
    for (double a : {1e-8, 3e-7, 2e-6}) {
      const ShapePoint p = contact.at(a);
      const double d = c * std::pow(a, n) / std::pow(radius, n - 1);
      const double f = 2 * e * c * n * std::pow(a, n + 1) / ((n + 1) * std::pow(radius, n - 1));
      const std::string at = "power law n " + str(n) + ", a " + str(a);
      check::close(p.penetration_h, d, kClosedForm, "delta_H " + at);
      check::close(p.force_h, f, kClosedForm, "F_H " + at);
      // Section 5 steps 3-4 on a half-space: δ = δ_H - sqrt(2π a w/E*), F = F_H - 2aE* sqrt(2π a w/E*).
      const double fp = std::sqrt(2 * kPi * a * w / e);
      check::close(p.penetration, d - fp, kClosedForm, "delta " + at, std::abs(d) + fp);
      check::close(p.force, f - 2 * a * e * fp, kClosedForm, "F " + at, std::abs(f) + 2 * a * e * fp);
    }
    const double k = 2 * n * c * e / ((n + 1) * std::pow(radius, n - 1));
    const double root = std::sqrt(2 * kPi * w * e);
    const double a_p = std::pow(3 * root / ((n + 1) * k), 1.0 / (n - 0.5));
    const double f_p = -(2 * n - 1) / (n + 1) * root * std::pow(a_p, 1.5);
    const ShapePulloff po = contact.pulloff(0.0);
    check::close(po.load.force, f_p, kClosedForm, "JKR pull-off force, power law n " + str(n));
    check::close(po.load.radius, a_p, check::tier::kIdentityByDifferences, "JKR pull-off radius, power law n " + str(n));
    check::that(po.load.local_minima == 1 && po.warnings.empty(), "single minimum, power law n " + str(n));
    std::printf("power law n = %g: pull-off %.15g N (closed form %.15g)\n", n, po.load.force, f_p);
  }
}

// Check "blunted cone on both sides of the tangent point" and "the exact sphere": δ_H = δ0(a)
// and F_H/E* from section 11 for a <= b (Sneddon's sphere) and a >= b.
void test_blunted_cone(const ShapeSolver& solver) {
  const double e = homogeneous().reference_modulus();
  const double radius = 1e-6, beta = 70.0 * kPi / 180.0;
  const auto shape = make_blunted_cone(radius, beta);
  const ShapeContact contact(solver, shape, 1e-6, 0.05, 1e-11);
  const double b = radius * std::cos(beta);
  for (double a : {0.1 * b, 0.5 * b, 0.99 * b, b, 1.01 * b, 2 * b, 10 * b}) {
    const ShapePoint p = contact.at(a);
    const std::string at = "blunted cone a/b " + str(a / b);
    check::close(p.penetration_h, shape->delta0(a), kClosedForm, "delta_H " + at);
    check::close(p.force_h, e * blunted_cone_force_over_modulus(radius, beta, a), kClosedForm, "F_H " + at);
  }
}

// Check "a sampled profile converging at the stated order": a spherical cap sampled at N
// points; the error of δ0 falls like h³ and 50 points give about 1e-4.
void test_profile_order() {
  const double radius = 1.0, r_max = 0.5;
  auto exact = [&](double r) { return r * std::atanh(r / radius); };
  double previous = 0.0;
  for (int n : {25, 50, 100, 200}) {
    std::vector<double> r(static_cast<std::size_t>(n)), z(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      r[static_cast<std::size_t>(i)] = r_max * i / (n - 1);
      z[static_cast<std::size_t>(i)] = radius - std::sqrt(radius * radius - r[static_cast<std::size_t>(i)] * r[static_cast<std::size_t>(i)]);
    }
    const auto shape = make_measured_profile(r, z, "sphere cap");
    // Over the knots and the midpoints (the points of the profile's own estimate): the error
    // relative to δ0(r_max) (O(h³)) and pointwise (O(h²) near the apex, where δ0 ~ r²).
    double worst = 0.0, worst_pointwise = 0.0;
    for (std::size_t i = 1; i < r.size(); ++i) {
      for (double x : {r[i], 0.5 * (r[i - 1] + r[i])}) {
        const double error = std::abs(shape->delta0(x) - exact(x));
        worst = std::max(worst, error / exact(r_max));
        worst_pointwise = std::max(worst_pointwise, error / exact(x));
      }
    }
    std::printf("profile %3d points: error of delta0 %.3e of delta0(r_max), pointwise %.3e, estimate %.3e\n", n,
                worst, worst_pointwise, shape->interpolation_error());
    if (n == 50) check::that(worst_pointwise < 2e-4, "50 points give about 1e-4 or better");
    if (previous > 0.0) check::that(previous / worst > 0.95 * 8.0, "order >= 3 at " + std::to_string(n) + " points");
    check::that(shape->interpolation_error() < 3 * worst_pointwise && shape->interpolation_error() > worst_pointwise / 3, "error estimate within a factor 3 of the pointwise error at " + std::to_string(n) + " points");
    previous = worst;
  }
}

// Spring control in SI units (section 10): between the two limits, and dF/dδ = -k there.
void test_spring_si() {
  const ShapeSolver solver(Stack::film_on(material(1e8, 0.25), elastic(1e9, 0.25)));
  const auto shape = make_paraboloid(1e-5);
  const ShapeContact contact(solver, shape, 1e-6, 0.05, 1e-9);
  const double w = 0.05, radius = 1e-5, e = solver.stack().reference_modulus();
  // k in units of π w R / (π² w² R/E²)^(1/3): k_bar = 1.
  const double k = kPi * w * radius / std::cbrt(kPi * kPi * w * w * radius / (e * e));
  const ShapePulloff po = contact.pulloff(k);
  check::that(po.spring.force > po.load.force && po.spring.force < po.displacement.force, "spring pull-off between the limits");
  const double h = 1e-4 * po.spring.radius;
  const ShapePoint lo = contact.at(po.spring.radius - h), hi = contact.at(po.spring.radius + h);
  check::close((hi.force - lo.force) / (hi.penetration - lo.penetration), -k, 1e-4, "dF/ddelta = -k at the spring pull-off");
}

void test_bad_shapes() {
  auto rejected = [](auto make) {
    try {
      make();
    } catch (const InputError&) {
      return true;
    }
    return false;
  };
  check::that(rejected([] { make_cone(0.0); }), "beta = 0 rejected");
  check::that(rejected([] { make_cone(kPi / 2); }), "beta = 90 deg rejected");
  check::that(rejected([] { make_power_law(0.0, 1.0); }), "N = 0 rejected");
  check::that(rejected([] { make_power_law(-1.0, 1.0); }), "N < 0 rejected");
  check::that(rejected([] { make_blunted_cone(0.0, 1.0); }), "R <= 0 rejected");
  check::that(rejected([] { make_measured_profile({0.1, 0.2, 0.3, 0.4, 0.5}, {0, 1, 2, 3, 4}, "f"); }), "profile not at r = 0 rejected");
  check::that(rejected([] { make_measured_profile({0, 0.2, 0.1, 0.4, 0.5}, {0, 1, 2, 3, 4}, "f"); }), "unsorted profile rejected");
  check::that(rejected([] { make_measured_profile({0, 0.1, 0.2, 0.3, 0.4}, {0, 1, 0.5, 3, 4}, "f"); }), "non-monotonic profile rejected");
  check::that(rejected([] { make_measured_profile({0, 0.1, 0.2}, {0, 1, 2}, "f"); }), "short profile rejected");
  const ShapeSolver solver(homogeneous());
  const auto profile = make_measured_profile({0, 0.1, 0.2, 0.3, 0.4}, {0, 0.01, 0.04, 0.09, 0.16}, "f");
  check::that(rejected([&] { solver.solve(*profile, 0.5, 1.0, 1e-8); }), "contact radius beyond the profile rejected");
}

}  // namespace

int main() {
  const ShapeSolver solver(homogeneous());
  test_power_law(solver);
  test_blunted_cone(solver);
  test_profile_order();
  test_spring_si();
  test_bad_shapes();
  return check::exit_code();
}
