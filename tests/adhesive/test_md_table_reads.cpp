// The cheap reads of the Maugis-Dugdale table (THEORY.md section 13, "The homogeneous root by
// Newton"; docs/speed.md, "Maugis-Dugdale table reads"), each against an independent computation:
//  1. homogeneous_gap_functions equals homogeneous_functions' g_R and g_σ bit for bit;
//  2. homogeneous_root (Newton on ln h) is the root of the closed forms' gap found by GSL's
//     Brent to 1e-13 on homogeneous_functions, to 1e-9 in ln(c/a - 1) (the table's bracket
//     starts there; the rule "Which root" needs it to ~1e-6), and clamps to the range's ends
//     where the root lies outside, as before;
//  3. MaugisDugdaleTable::solve without estimates returns the same state as with them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "check.hpp"
#include "coatcontact/detail/brent.hpp"
#include "cohesive_zone.hpp"
#include "md_table.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;

int main() {
  // 1. Bit for bit, across the table's range of a and c/a - 1 (the series branch of T - atan T
  //    below T = 0.1 included).
  int differ = 0, compared = 0;
  for (double a = 1e-3; a <= 1e3; a *= 3.7) {
    for (double e = 1e-16; e <= 1e8; e *= 2.3) {
      const detail::CohesiveFunctions h = detail::homogeneous_functions(a, e);
      const auto [g_r, g_s] = detail::homogeneous_gap_functions(a, e);
      ++compared;
      if (g_r != h.g_r || g_s != h.g_s) ++differ;
    }
  }
  check::that(differ == 0, "homogeneous_gap_functions bit for bit: " + std::to_string(differ) + " of " +
                               std::to_string(compared) + " differ");

  // 2. The homogeneous root against Brent on the full closed forms.
  double worst = 0.0;
  for (double a : {1e-3, 0.05, 1.0, 30.0, 1e3}) {
    for (double sigma_hat : {1e-3, 0.2, 1.0, 30.0, 1e3}) {
      for (double h0 : {1e-9, 1e-4, 0.1, 10.0, 1e5}) {
        const double lo = std::log(1e-16), hi = std::log(1e4 / a);
        auto gap = [&](double s) {
          const detail::CohesiveFunctions h = detail::homogeneous_functions(a, std::exp(s));
          return h.g_r + sigma_hat * h.g_s - h0;
        };
        const double got = detail::homogeneous_root(sigma_hat, h0, a, lo, hi);
        const std::string at = " a=" + check::text(a) + " sigma_hat=" + check::text(sigma_hat) + " h0=" + check::text(h0);
        if (gap(lo) >= 0.0) {
          check::that(got == lo, "homogeneous root clamps to the range's low end" + at);
        } else if (gap(hi) <= 0.0) {
          check::that(got == hi, "homogeneous root clamps to the range's high end" + at);
        } else {
          const auto want = detail::brent_root(gap, lo, hi, {1e-13, 0.0, 200});
          if (!check::that(want.has_value(), "Brent brackets the homogeneous root" + at)) continue;
          check::close(got, want->x, 1e-9, "homogeneous root in ln(c/a - 1)" + at, 1.0);
          worst = std::max(worst, std::abs(got - want->x));
        }
      }
    }
  }
  std::printf("homogeneous root: worst |Newton - Brent(1e-13)| in ln(c/a - 1) %.2e\n", worst);
  // h0 <= 0: h > h0 on the whole range, so the low end (as Brent's end test gave).
  check::that(detail::homogeneous_root(1.0, 0.0, 1.0, -30.0, 5.0) == -30.0, "homogeneous root at h0 = 0: the low end");

  // 3. The state without estimates is the state with them, on a layered stack.
  Substrate base;
  base.material = {10.0, 0.25};
  const Stack soft = Stack::film_on({1.0, 0.25}, base);
  const detail::TableKernel kernel(soft);
  detail::MdTableOptions small;
  small.a_over_t_min = 0.1;
  small.a_over_t_max = 3.0;
  small.c_over_t_max = 30.0;
  small.step = 0.6;
  const detail::MaugisDugdaleTable table(kernel, detail::Discretization{}, detail::CohesiveQuadrature{}, small);
  for (double a : {0.2, 1.3}) {
    for (double lambda : {0.3, 3.0}) {
      const double sigma_hat = lambda * std::cbrt(16.0 / 9.0), h0 = 2.0 / (M_PI * sigma_hat);
      const auto full = table.solve(sigma_hat, h0, a, true), bare = table.solve(sigma_hat, h0, a, false);
      const std::string at = " a=" + check::text(a) + " lambda=" + check::text(lambda);
      if (!check::that(full.has_value() && bare.has_value(), "table states exist" + at)) continue;
      check::that(full->excess == bare->excess && full->delta == bare->delta && full->force == bare->force,
                  "state without estimates equals the state with them, bit for bit" + at);
      check::that(bare->excess_error == 0.0 && bare->delta_error == 0.0 && bare->force_error == 0.0,
                  "state without estimates has no estimates" + at);
    }
  }
  return check::exit_code();
}
