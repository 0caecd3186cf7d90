// The cohesive-zone table at its ends (THEORY.md section 13, "The cohesive zone as a table"),
// where the AFM Maugis-Dugdale fit used to fall back to the direct solve at every trial:
//  1. a homogeneous half-space (film on a substrate of its own material: H = 0) is answered
//     by the homogeneous closed forms with no node solved, and equals the direct solve (the
//     section's homogeneous check, here against the library's own direct path, kClosedFormTier),
//     at lambda = 1e4 and large a_bar too (c/a - 1 below the grid's 1e-9) and at the curve's end;
//  2. on coatings (soft film, stiff film, rigid base with nu = 0.5), the JKR end lambda = 1e4:
//     points whose root c/a - 1 lies below the grid's excess_min, and curve ends whose zone
//     c/t lies below the grid's 1e-5, come from the table (flat ratios, "Behaviour at the JKR
//     end") and lie within their error estimates of the direct solve.
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "md_tiers.hpp"
#include "coatcontact/maugis_dugdale.hpp"

using namespace coatcontact;

namespace {

// The direct solve's own noise (MaugisDugdalePoint's error without the table).
constexpr double kDirectNoise = 1e-11;

Stack film_on(double e1, double nu1, double e0, double nu0, bool rigid = false) {
  Substrate s;
  s.material = {e0, nu0};
  s.rigid = rigid;
  return Stack::film_on({e1, nu1}, s);
}

std::string where(const char* stack, double eta, double lambda, double a_bar) {
  char b[160];
  std::snprintf(b, sizeof b, "%s eta %g lambda %g a_bar %g", stack, eta, lambda, a_bar);
  return b;
}

// The table's point against the direct one: m, P, D within the table's estimate plus the
// direct solve's noise.
void within_estimate(const MaugisDugdalePoint& t, const MaugisDugdalePoint& d, const std::string& what) {
  check::that(t.from_table, what + ": from the table");
  check::below(std::abs(t.load - d.load), t.load_error + kDirectNoise * std::abs(d.load),
               what + ": P within its estimate");
  check::below(std::abs(t.penetration - d.penetration), t.penetration_error + kDirectNoise * std::abs(d.penetration),
               what + ": D within its estimate");
  if (t.a_bar > 0.0) {
    check::below(std::abs(t.m - d.m), t.m_error + kDirectNoise * d.m, what + ": m within its estimate");
  }
}

void half_space() {
  const Stack stack = film_on(1.0, 0.3, 1.0, 0.3);
  MaugisDugdaleOptions with;
  with.use_table = true;
  const MaugisDugdaleModel table(stack, with), direct(stack);
  for (double lambda : {0.3, 1e4}) {
    for (double a_bar : {0.0, 0.01, 1.0, 30.0}) {
      const std::string what = where("half-space", 1.0, lambda, a_bar);
      const MaugisDugdalePoint t = table.point(1.0, lambda, a_bar), d = direct.point(1.0, lambda, a_bar);
      check::that(t.from_table, what + ": closed form (no direct solve)");
      check::close(t.load, d.load, kClosedFormTier, what + ": P", 1.0);
      check::close(t.penetration, d.penetration, kClosedFormTier, what + ": D", 1.0);
      if (a_bar > 0.0) check::close(t.m, d.m, kClosedFormTier, what + ": m", 1.0);
      if (lambda == 1e4 && a_bar == 30.0) check::that(t.m - 1.0 < 1e-9, what + ": c/a - 1 below the grid's 1e-9");
    }
  }
  check::that(table.table_nodes() == 0, "half-space: no node solved");
}

void coatings() {
  const struct {
    const char* name;
    Stack stack;
  } cases[] = {{"soft film", film_on(1.0, 0.25, 10.0, 0.25)},
               {"stiff film", film_on(10.0, 0.25, 1.0, 0.25)},
               {"rigid base nu 0.5", film_on(1.0, 0.5, 1.0, 0.5, true)}};
  for (const auto& c : cases) {
    MaugisDugdaleOptions with;
    with.use_table = true;
    const MaugisDugdaleModel table(c.stack, with), direct(c.stack);
    const double lambda = 1e4;
    // JKR end at a large radius: c/a - 1 ~ 3/(4 lambda^2 a_bar) < 1e-9.
    for (double eta : {0.3, 3.0}) {
      const double a_bar = 30.0 * eta;
      const MaugisDugdalePoint t = table.point(eta, lambda, a_bar), d = direct.point(eta, lambda, a_bar);
      const std::string what = where(c.name, eta, lambda, a_bar);
      check::that(d.m - 1.0 < 1e-9, what + ": root below the grid's c/a - 1 = 1e-9");
      within_estimate(t, d, what);
    }
    // The curve's end at small eta: the zone's c/t ~ 2/(pi eta^3 sigma_hat^2 (1 - 2/pi)) < 1e-5.
    for (double eta : {0.03, 0.3}) {
      const MaugisDugdalePoint t = table.point(eta, lambda, 0.0), d = direct.point(eta, lambda, 0.0);
      const std::string what = where(c.name, eta, lambda, 0.0);
      check::that(d.c_bar / eta < 1e-5, what + ": the end's zone below the grid's c/t = 1e-5");
      within_estimate(t, d, what);
    }
  }
}

}  // namespace

int main() {
  half_space();
  coatings();
  return check::exit_code();
}
