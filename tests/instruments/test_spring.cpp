// Spring control (THEORY.md section 10): each test names the section-10 check it makes.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "materials.hpp"
#include "check.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"

using namespace coatcontact;
using coatcontact::test::elastic;
using coatcontact::test::material;

namespace {

std::string str(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

// The JKR quintic 4√2 x⁵ + 2√2 k x³ - 6 x² - k = 0 on [2^{-1/2}, (9/8)^{1/6}], x = a_bar^{1/2},
// by bisection (the bracket holds the one root: the polynomial goes from - to +).
double quintic_root(double k) {
  const double s2 = std::sqrt(2.0);
  auto f = [&](double x) { return 4 * s2 * std::pow(x, 5) + 2 * s2 * k * x * x * x - 6 * x * x - k; };
  double lo = 1.0 / s2, hi = std::pow(9.0 / 8.0, 1.0 / 6.0);
  check::that(f(lo) < 0.0 && f(hi) > 0.0, "quintic bracketed at k_bar " + str(k));
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Check "JKR (homogeneous, exact): the quintic" at k_bar = 0.1, 1, 10, and "the limits k_bar
// -> 0, inf give -3/2 and -5/6".
void test_jkr_quintic() {
  const ReducedSolver solver(Stack::film_on(material(1.0, 0.3), elastic(1.0, 0.3)));
  const AdhesiveModel model(solver, 1e-10);
  const double s2 = std::sqrt(2.0);
  for (double k : {0.1, 1.0, 10.0}) {
    const double x = quintic_root(k);
    const double a = x * x;
    const double p = 4.0 / 3.0 * a * a * a - 2 * s2 * std::pow(a, 1.5);
    const double d = a * a - s2 * x;
    for (double eta : {0.5, 2.0}) {
      const SpringPulloff sp = model.pulloff_spring(eta, k);
      const std::string at = " at k_bar " + str(k) + ", eta " + str(eta);
      check::close(sp.point.a_bar, a, check::tier::kInterpolation, "JKR quintic: a_bar" + at);
      check::close(sp.point.load, p, check::tier::kInterpolation, "JKR quintic: P" + at);
      check::close(sp.point.penetration, d, check::tier::kInterpolation, "JKR quintic: D" + at);
      check::that(sp.point.single_minimum && sp.warnings.empty(), "single minimum" + at);
    }
    if (k == 1.0) {
      check::close(a, 0.862633136333, check::tier::kReference, "published a_bar at k_bar = 1");
      check::close(p, -1.410238343649, check::tier::kReference, "published P at k_bar = 1");
      check::close(d, -0.569357990117, check::tier::kReference, "published D at k_bar = 1");
    }
  }
  const Pulloff base = model.pulloff(1.0);
  const SpringPulloff soft = model.pulloff_spring(1.0, 0.0);
  const SpringPulloff stiff = model.pulloff_spring(1.0, std::numeric_limits<double>::infinity());
  check::that(soft.point.load == base.load_control.load && soft.point.a_bar == base.load_control.a_bar, "k_bar = 0 equals load control exactly");
  check::that(stiff.point.load == base.displacement_control.load && stiff.point.a_bar == base.displacement_control.a_bar, "k_bar = inf equals displacement control exactly");
  check::close(soft.point.load, -1.5, check::tier::kInterpolation, "k_bar = 0: -3/2");
  check::close(stiff.point.load, -5.0 / 6.0, check::tier::kInterpolation, "k_bar = inf: -5/6");
  // Between the limits and monotonic in k_bar.
  double previous = -1.5;
  for (double k : {1e-4, 0.01, 1.0, 100.0, 1e4}) {
    const double p = model.pulloff_spring(1.0, k).point.load;
    check::that(p > previous && p < -5.0 / 6.0, "P_spring between the limits and increasing at k_bar " + str(k));
    previous = p;
  }
  bool threw = false;
  try {
    model.pulloff_spring(1.0, -1.0);
  } catch (const InputError&) {
    threw = true;
  }
  check::that(threw, "k_bar < 0 rejected");
}

// Check "the criterion dF/ddelta = -k" on a coated substrate: dP/dD = -k_bar at the
// reported point, soft and stiff film.
void test_coated_criterion() {
  for (double ratio : {0.1, 10.0}) {
    const ReducedSolver solver(Stack::film_on(material(ratio, 0.25), elastic(1.0, 0.25)));
    const AdhesiveModel model(solver, 1e-9);
    for (double eta : {0.3, 1.0, 3.0}) {
      for (double k : {0.1, 1.0, 10.0}) {
        const SpringPulloff sp = model.pulloff_spring(eta, k);
        const CurvePoint p = model.point(eta, sp.point.a_bar);
        check::close(p.dload / p.dpenetration, -k, check::tier::kSolver, "dP/dD = -k_bar, E1*/E0* " + str(ratio) + ", eta " + str(eta) + ", k_bar " + str(k));
        const Pulloff limits = model.pulloff(eta);
        check::that(sp.point.load >= limits.load_control.load && sp.point.load <= limits.displacement_control.load, "spring pull-off between the limits, E1*/E0* " + str(ratio) + ", eta " + str(eta));
      }
    }
  }
}

}  // namespace

int main() {
  test_jkr_quintic();
  test_coated_criterion();
  return check::exit_code();
}
