// Maugis-Dugdale on a homogeneous half-space (film = substrate) against Maugis's closed form
// solved in this test (THEORY.md section 13, "Homogeneous closed form (the check)"):
//  - m(ā), P, Δ_M over λ = 0.1..10 and ā_M = 0.05..1.5, tier 1e-9 (reached: ~1e-13; the
//    kernel of identical materials is zero to the table's accuracy, so only the root c(a),
//    the regularity and the gap formula are exercised: they are exact up to rounding);
//  - the curve's end a -> 0 (finite c, P, Δ_M; no NaN) and its approach from a > 0;
//  - load-controlled pull-offs -1.81556, -1.60073, -1.51676 at λ = 0.3, 1, 3 (to the digits
//    given) and to 1e-9 against the closed form's minimum, its location a_M to 1e-8;
//  - DMT limit λ -> 0: P -> -2; JKR limit λ -> ∞: P -> -3/2.
#include <cmath>
#include <cstdio>
#include <string>

#include <algorithm>

#include "check.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "maugis_closed_form.hpp"
#include "md_tiers.hpp"

using namespace coatcontact;

int main() {
  Material film;
  film.youngs_modulus = 1.0;
  film.poisson_ratio = 0.3;
  Substrate same;
  same.material = film;
  const MaugisDugdaleModel model(Stack::film_on(film, same));
  const double k13 = std::cbrt(4.0 / 3.0), k23 = k13 * k13;  // ā_M = k13 ā, Δ_M = k23 D
  const double eta = 0.7;  // any: the film is invisible

  double worst = 0.0;
  for (double lambda : {0.1, 0.3, 1.0, 3.0, 10.0}) {
    for (double a_m : {0.05, 0.1, 0.3, 0.6, 1.0, 1.5}) {
      const MaugisDugdalePoint p = model.point(eta, lambda, a_m / k13);
      const maugis::State want = maugis::solve(lambda, a_m);
      const std::string at = "lambda=" + check::text(lambda) + " a_M=" + check::text(a_m);
      check::close(p.m, want.m, kClosedFormTier, "m " + at, 1.0);
      check::close(p.load, want.load, kClosedFormTier, "P " + at, 1.0);
      check::close(p.penetration * k23, want.penetration, kClosedFormTier, "Delta_M " + at, 1.0);
      worst = std::max({worst, std::abs(p.m - want.m) / want.m, std::abs(p.load - want.load),
                        std::abs(p.penetration * k23 - want.penetration)});
    }
    // The end of the curve, and its approach (c stays finite, m ~ c/a).
    const MaugisDugdalePoint end = model.point(eta, lambda, 0.0);
    const maugis::State want_end = maugis::end_of_curve(lambda);
    check::that(std::isinf(end.m) && std::isfinite(end.load) && std::isfinite(end.penetration), "end of the curve lambda=" + check::text(lambda) + ": m infinite, P and D finite");
    check::close(end.load, want_end.load, kClosedFormTier, "P(a -> 0) lambda=" + check::text(lambda), 1.0);
    check::close(end.penetration * k23, want_end.penetration, kClosedFormTier, "Delta_M(a -> 0) lambda=" + check::text(lambda), 1.0);
    const MaugisDugdalePoint near = model.point(eta, lambda, 1e-7);
    check::close(near.load, end.load, kEndOfCurveTier, "P(a_bar = 1e-7) -> P(a -> 0) lambda=" + check::text(lambda), 1.0);
  }
  std::printf("worst homogeneous error over the grid: %.2e\n", worst);

  // Pull-offs (load control): Maugis's values to the digits given, and the closed form's
  // minimum computed here to 1e-9.
  const double published[3][2] = {{0.3, -1.81556}, {1.0, -1.60073}, {3.0, -1.51676}};
  for (const auto& row : published) {
    const MaugisDugdalePulloff r = model.pulloff(eta, row[0]);
    const double want = maugis::pulloff_load(row[0]);
    check::close(r.load_control.point.load, row[1], kPublishedDigitsTier, "pull-off lambda=" + check::text(row[0]) + " vs Maugis", 1.0);
    check::close(r.load_control.point.load, want, kClosedFormTier, "pull-off lambda=" + check::text(row[0]) + " vs closed form", 1.0);
    check::that(r.load_control.interior, "pull-off lambda=" + check::text(row[0]) + " is a stationary point");
    // Location: implicit derivative through c(a) (THEORY.md section 13), against the closed form.
    const double a_m = r.load_control.point.a_bar * k13;
    check::close(a_m, maugis::pulloff_location(row[0], 0.9 * a_m, 1.1 * a_m), check::tier::kSolver, "pull-off location a_M lambda=" + check::text(row[0]) + " vs closed form", 1.0);
    check::that(std::isfinite(r.displacement_control.point.load), "displacement-controlled pull-off finite");
  }

  // DMT limit λ -> 0: P -> -2 (the deviation shrinks with λ), JKR limit: -> -3/2.
  double previous = 1.0;
  for (double lambda : {0.1, 0.03, 0.01}) {
    const MaugisDugdalePulloff r = model.pulloff(eta, lambda);
    const double deviation = std::abs(r.load_control.point.load + 2.0);
    std::printf("DMT limit: lambda=%g P=%.10f |P + 2| = %.3e\n", lambda, r.load_control.point.load, deviation);
    check::that(deviation < previous, "DMT limit: |P + 2| decreases at lambda=" + check::text(lambda));
    previous = deviation;
  }
  check::that(previous < 0.05, "DMT limit: |P + 2| < 0.05 at lambda = 0.01");
  const MaugisDugdalePulloff jkr = model.pulloff(eta, 100.0);
  check::close(jkr.load_control.point.load, -1.5, kLimitTier, "JKR limit lambda=100", 1.0);
  return check::exit_code();
}
