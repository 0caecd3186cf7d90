// Regression: the table and the direct solve took different roots of the gap equation
// h(c) = h0 on a thin stiff top layer (THEORY.md section 13, "Which root"). At eta = 0.25,
// lambda = 1 the curve's end has three roots (c/t ~ 0.69, 1.35, 2.8); the direct solve
// bracketed from c = t and took 0.69 (P = -0.057), the table from the homogeneous solid's root
// and took 2.8 (P = -0.936), and single direct points at small a_bar jumped between the
// branches. Both now follow the one rule (bracket outward from the homogeneous solid's root
// where no neighbouring root guides the search): at the end and at single points the two
// paths give the same zone radius, and the table's values lie within their estimates of the
// direct ones.
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
  MaugisDugdaleOptions with_table;
  with_table.use_table = true;
  const MaugisDugdaleModel table(stack, with_table), direct(stack);
  const double eta = 0.25, lambda = 1.0;
  // The end (a_bar = 0) and single points on the stretch where the branches coexist.
  for (double a_bar : {0.0, 0.001, 0.003, 0.01, 0.03}) {
    const MaugisDugdalePoint t = table.point(eta, lambda, a_bar), d = direct.point(eta, lambda, a_bar);
    char at[80];
    std::snprintf(at, sizeof at, " (thin stiff top, eta=0.25 lambda=1 a_bar=%g)", a_bar);
    // Another root differs by ~4x in c (0.69 against 2.8): 5 % tells them apart.
    check::that(std::abs(t.c_bar - d.c_bar) <= 0.05 * d.c_bar,
                std::string("table and direct zone radius on one root: c_bar ") + std::to_string(t.c_bar) + " vs " +
                    std::to_string(d.c_bar) + at);
    // The homogeneous solid's branch is the wide zone, c/t ~ 2.8 (c_bar = eta c/t ~ 0.70).
    check::that(d.c_bar > 0.6, std::string("direct root on the homogeneous branch: c_bar ") + std::to_string(d.c_bar) + at);
    check::that(std::abs(t.load - d.load) <= t.load_error,
                std::string("table P within its estimate of the direct one") + at);
  }
  return check::exit_code();
}
