// Regression: the Maugis-Dugdale annulus quadrature on a stack with a thin top layer. Its
// pieces near the zone ends and near the point x of k(x, y) were one film thickness long
// whatever the kernel; a stack's H varies on its strip |Im u| < 2 h_top/T (THEORY.md
// section 12), so with h_top/T = 0.05 the default quadrature was off by ~1e-3 in D. The
// check (THEORY.md section 13, self-convergence): m, P and D at the default quadrature agree
// with a much finer one (contact p = 32, 36 points per annulus piece).
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "coatcontact/maugis_dugdale.hpp"

using namespace coatcontact;

int main() {
  Substrate base;
  base.material = {100.0, 0.25};
  const Stack stack({{0.05, {10.0, 0.3}}, {0.95, {1.0, 0.45}}}, base);
  MaugisDugdaleOptions fine;
  fine.nodes_per_panel = 32;
  fine.annulus_points = 36;
  const MaugisDugdaleModel coarse_model(stack), fine_model(stack, fine);
  struct Case { double eta, lambda, a_bar; };
  for (const Case& c : {Case{1.0, 1.0, 0.8}, Case{0.3, 0.3, 0.5}, Case{1.0, 0.1, 0.3}}) {
    const MaugisDugdalePoint want = fine_model.point(c.eta, c.lambda, c.a_bar);
    const MaugisDugdalePoint got = coarse_model.point(c.eta, c.lambda, c.a_bar);
    char at[96];
    std::snprintf(at, sizeof at, " (h_top/T = 0.05, eta=%g lambda=%g a_bar=%g)", c.eta, c.lambda, c.a_bar);
    check::close(got.m, want.m, check::tier::kReference, std::string("m default vs fine quadrature") + at, 1.0);
    check::close(got.load, want.load, check::tier::kReference, std::string("P default vs fine quadrature") + at, 1.0);
    check::close(got.penetration, want.penetration, check::tier::kReference,
                 std::string("D default vs fine quadrature") + at, 1.0);
  }
  return check::exit_code();
}
