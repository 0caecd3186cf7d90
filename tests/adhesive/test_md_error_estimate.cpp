// Error estimates of the Maugis-Dugdale table that mean what they say (THEORY.md section 13,
// "Error estimates of the state"; issue 37 item 4): against the direct per-radius solve (the
// reference, use_table = false), on a soft film, a stiff film, a rigid base with ν = 0.5 and a
// thin stiff top layer, over η and λ:
//  1. curve points: m, P, D within their estimates, and the estimates at most kMaxOverestimate
//     times the actual error;
//  2. pull-offs (load and displacement control): a_bar, m, P, D the same.
// Only errors the reference can measure count: above kMeasurable (relative) — the direct
// solve's values carry ~1e-11 and its pull-off location ~1e-10.
// The distribution of estimate / actual is printed per quantity. Measured on this set (700
// values): min 1.33, quartiles 2.9 / 3.3 / 5.7, 95 % 30, max 340; 15.6 % above 10x. The lower
// bound is asserted everywhere, the upper one for the share kOverFraction: a pointwise estimate
// overstates where the splines happen to be far more accurate than every check.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "check.hpp"
#include "coatcontact/maugis_dugdale.hpp"

using namespace coatcontact;

namespace {
constexpr double kMeasurable = 1e-8;       // relative: 100x the reference's own error, or more
constexpr double kMaxOverestimate = 10.0;  // the bound on estimate / actual
constexpr double kOverFraction = 0.2;      // share of the set allowed above it (measured 15.6 %)

Stack film_on(double e1, double nu1, double e0, double nu0, bool rigid = false) {
  Substrate s;
  s.material = {e0, nu0};
  s.rigid = rigid;
  return Stack::film_on({e1, nu1}, s);
}

std::map<std::string, std::vector<double>> ratios;  // estimate / actual per quantity
int other_minimum = 0;                               // pull-offs at another minimum than the direct one

std::string g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

void compare(const std::string& what, const std::string& name, double table, double estimate, double direct) {
  const double actual = std::abs(table - direct);
  if (!(actual > kMeasurable * std::max(std::abs(direct), 1e-300))) return;
  ratios[name].push_back(estimate / actual);
  check::that(actual <= estimate, what + " " + name + ": error " + g(actual) + " within estimate " + g(estimate));
  if (estimate > kMaxOverestimate * actual) {
    std::printf("over 10x: %s %s: estimate %s, error %s\n", what.c_str(), name.c_str(), g(estimate).c_str(),
                g(actual).c_str());
  }
}

void compare_points(const std::string& what, const MaugisDugdalePoint& t, const MaugisDugdalePoint& d, bool pulloff) {
  compare(what, "P", t.load, t.load_error, d.load);
  compare(what, "D", t.penetration, t.penetration_error, d.penetration);
  if (t.a_bar > 0.0 && d.a_bar > 0.0) {
    compare(what, "m", t.m, t.m_error, d.m);
    if (pulloff) compare(what, "a_bar", t.a_bar, t.a_bar_error, d.a_bar);
  }
}
}  // namespace

int main() {
  Layer top{0.05, {10.0, 0.3}}, under{0.95, {1.0, 0.45}};
  Substrate base;
  base.material = {100.0, 0.25};
  const Stack thin_top({top, under}, base);
  const std::vector<std::pair<std::string, Stack>> stacks = {
      {"soft film", film_on(1.0, 0.25, 10.0, 0.25)},
      {"stiff film", film_on(10.0, 0.25, 1.0, 0.25)},
      {"rigid base nu=0.5", film_on(1.0, 0.5, 1.0, 0.5, true)},
      {"thin stiff top", thin_top}};
  MaugisDugdaleOptions with_table;
  with_table.use_table = true;
  for (const auto& [name, stack] : stacks) {
    const MaugisDugdaleModel table(stack, with_table), direct(stack);
    for (double eta : {0.3, 1.0, 3.0}) {
      for (double lambda : {0.1, 1.0, 3.0}) {
        const std::string at = name + " eta=" + std::to_string(eta) + " lambda=" + std::to_string(lambda);
        const std::vector<double> a_bar = {0.07, 0.3, 1.1, 2.9};
        const auto tc = table.curve(eta, lambda, a_bar), dc = direct.curve(eta, lambda, a_bar);
        for (std::size_t k = 0; k < a_bar.size(); ++k) compare_points(at + " a_bar=" + std::to_string(a_bar[k]), tc[k], dc[k], false);
        const MaugisDugdalePulloff tp = table.pulloff(eta, lambda), dp = direct.pulloff(eta, lambda);
        compare_points(at + " curve end", tp.curve_end, dp.curve_end, false);
        // Interior minima only: a pull-off at the curve's end carries, besides the end's error,
        // the interior minimum set aside within the estimates (maugis_dugdale.hpp), and a
        // minimum of the table more than kSameMinimum away from the direct one is another of
        // the curve's shallow minima (THEORY.md section 13, stiff film at small lambda), not an
        // error of this one: both counted and printed.
        constexpr double kSameMinimum = 0.05;
        for (const auto& [kind, t, d] : {std::tuple{"load", &tp.load_control, &dp.load_control},
                                         std::tuple{"displacement", &tp.displacement_control, &dp.displacement_control}}) {
          if (!t->interior || !d->interior) continue;
          if (std::abs(t->point.a_bar - d->point.a_bar) > kSameMinimum * d->point.a_bar) {
            ++other_minimum;
            std::printf("%s %s-control pull-off: table at a_bar %s, direct at %s (another minimum)\n", at.c_str(),
                        kind, g(t->point.a_bar).c_str(), g(d->point.a_bar).c_str());
            continue;
          }
          compare_points(at + " " + kind + "-control pull-off", t->point, d->point, true);
        }
      }
    }
  }
  std::vector<double> all;
  for (auto& [name, r] : ratios) {
    std::sort(r.begin(), r.end());
    std::printf("estimate/actual %-6s n=%3zu min %.3g median %.3g 90%% %.3g max %.3g\n", name.c_str(), r.size(),
                r.front(), r[r.size() / 2], r[r.size() * 9 / 10], r.back());
    all.insert(all.end(), r.begin(), r.end());
  }
  std::sort(all.begin(), all.end());
  const auto over = static_cast<double>(std::count_if(all.begin(), all.end(), [](double r) { return r > kMaxOverestimate; }));
  std::printf("estimate/actual all n=%zu: 5%% %.3g 25%% %.3g 50%% %.3g 75%% %.3g 95%% %.3g; over 10x: %.0f\n", all.size(),
              all[all.size() / 20], all[all.size() / 4], all[all.size() / 2], all[all.size() * 3 / 4],
              all[all.size() * 19 / 20], over);
  // The estimate is pointwise (the checks' differences): where the splines happen to be
  // far more accurate than every check it overstates (15.6 % of the set above 10x, at most 340x).
  check::below(over / static_cast<double>(all.size()), kOverFraction, "fraction of estimates above 10x the error");
  std::printf("pull-offs at another minimum than the direct one: %d\n", other_minimum);
  check::that(ratios.size() == 4, "every quantity measured (P, D, m, a_bar at pull-offs)");
  return check::exit_code();
}
