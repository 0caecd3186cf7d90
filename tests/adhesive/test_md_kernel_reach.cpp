// Kernel tables by reach (THEORY.md section 13, "Kernel tables by reach"): the Maugis-Dugdale
// model's kernel source (ReachKernel) serves a call whose every |u| lies within the compact
// grid's range from that grid, any other from the full grid. Checked against the full grid alone
// (the same H on 8 times the panels, another period and pole treatment), on the stacks of the MD
// tests and the AFM fit's elastic base (E1 from 1e-5 to 42 E0), nodes a/t 1e-3..100, c/t <= 150:
//  - each of a node's functions (δ_H, F_H, d, f, g_R, g_σ) differs from the full grid's by at most
//    1/10 of the nodes' noise (MdTableOptions::source_noise, 2e-10 of the larger of the value and
//    its homogeneous form), or by at most twice what the full grid's own table error moves it
//    (the difference between two independent full grids, variants 0 and 1) where that is the
//    larger: at a/t = 100 on a rigid or near-rigid base (F_H, δ_H) and for g_R at c/a - 1 = 1e-6
//    the two full grids differ by up to ~1e-7 of the homogeneous form (and by the rounding of
//    the c²-sized gaps whose difference g_R is);
//  - a node's values do not depend on what the source served before (the solve cache's rule).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/stack.hpp"
#include "cohesive_zone.hpp"
#include "md_table.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;

namespace {
Stack film_on(double e1, double nu1, double e0, double nu0, bool rigid = false) {
  Substrate s;
  s.material = {e0, nu0};
  s.rigid = rigid;
  return Stack::film_on({e1, nu1}, s);
}

// The Maugis-Dugdale models' compact range.
constexpr double kCompactRange = detail::kCohesiveZoneCompactRange;
// The nodes' noise relative to their values (MdTableOptions::source_noise).
const double kSourceNoise = detail::MdTableOptions{}.source_noise;

std::vector<double> values_of(const detail::CohesiveFunctions& v) { return {v.delta_h, v.force_h, v.d, v.f, v.g_r, v.g_s}; }
const char* const kNames[] = {"delta_H", "F_H", "d", "f", "g_R", "g_s"};
}  // namespace

int main() {
  struct Named {
    Stack stack;
    std::string name;
  };
  Substrate base;
  base.material = {1.0, 0.3};
  const Stack thin_top({{0.05, {10.0, 0.3}}, {0.95, {1.0, 0.45}}}, base);
  const std::vector<Named> stacks = {
      {film_on(1.0, 0.25, 10.0, 0.25), "soft film"},
      {film_on(10.0, 0.25, 1.0, 0.25), "stiff film"},
      {film_on(1.0, 0.5, 1.0, 0.5, true), "rigid base nu=0.5"},
      {thin_top, "thin stiff top layer"},
      // The AFM fit's elastic base (film nu 0.5 on nu0 0.25) at E1 nodes it visits.
      {film_on(1e-5, 0.5, 1.0, 0.25), "fit base E1/E0=1e-5"},
      {film_on(0.1, 0.5, 1.0, 0.25), "fit base E1/E0=0.1"},
      {film_on(1.0, 0.5, 1.0, 0.25), "fit base E1/E0=1"},
      {film_on(15.0, 0.5, 1.0, 0.25), "fit base E1/E0=15"},
      {film_on(42.0, 0.5, 1.0, 0.25), "fit base E1/E0=42"},
  };
  detail::Discretization disc;
  detail::CohesiveQuadrature quadrature;
  quadrature.points_per_piece = detail::MdTableOptions{}.node_points_per_piece;
  // (a/t, c/a - 1) with 2c <= 320 (the AFM fit's a/t <= 100); a = 0: the curve's end, c/t.
  const double nodes[][2] = {{1e-3, 1e-6}, {1e-3, 10.0}, {0.03, 0.5}, {0.3, 1e-4}, {0.3, 3.0},
                             {1.0, 0.2},   {3.0, 1e-3},  {3.0, 20.0}, {30.0, 0.1}, {100.0, 1e-6},
                             {100.0, 0.5}, {0.0, 1e-3},  {0.0, 1.0},  {0.0, 100.0}};
  for (const Named& s : stacks) {
    const detail::TableKernel full(s.stack), independent(s.stack, 1);
    const detail::ReachKernel reach(s.stack, kCompactRange);
    double worst = 0.0, worst_independent = 0.0;  // relative to max(|value|, |homogeneous form|)
    for (const auto& node : nodes) {
      const double a = node[0], excess = node[1];
      auto functions = [&](const detail::KernelSource& kernel) {
        return values_of(detail::CohesiveZone(kernel, a, 1.0, disc, quadrature).functions(excess));
      };
      const std::vector<double> want = functions(full), got = functions(reach), other = functions(independent);
      const std::vector<double> scale =
          values_of(a > 0.0 ? detail::homogeneous_functions(a, excess) : detail::homogeneous_end_functions(excess));
      // g_R is the small difference of gaps of size ~c² (c = a (1 + excess), or c at the end):
      // their rounding.
      const double c = a > 0.0 ? a * (1.0 + excess) : excess, rounding = check::tier::kRounding * c * c;
      for (std::size_t k = a > 0.0 ? 0 : 2; k < want.size(); ++k) {  // the curve's end has no δ_H, F_H
        const double difference = std::abs(got[k] - want[k]), own = std::abs(other[k] - want[k]);
        const double size = std::max(std::abs(want[k]), std::abs(scale[k]));
        worst = std::max(worst, difference / size);
        worst_independent = std::max(worst_independent, own / size);
        check::below(difference, std::max({0.1 * kSourceNoise * size, 2.0 * own, rounding}),
                     s.name + ": " + kNames[k] + " at (a/t, c/a - 1) = (" + std::to_string(a) + ", " +
                         std::to_string(excess) + "), reach tables against the full grid");
      }
    }
    // A pure function of the node: a fresh source that served a node far beyond the compact range
    // (a/t = 200, both grids built) first gives the same bits at a near node.
    const detail::ReachKernel fresh(s.stack, kCompactRange);
    (void)detail::CohesiveZone(fresh, 200.0, 1.0, disc, quadrature).functions(0.5);
    const std::vector<double> near_first =
        values_of(detail::CohesiveZone(reach, 3.0, 1.0, disc, quadrature).functions(0.2));
    const std::vector<double> near_after =
        values_of(detail::CohesiveZone(fresh, 3.0, 1.0, disc, quadrature).functions(0.2));
    check::that(near_first == near_after, s.name + ": a node's values do not depend on what was solved before");
    std::printf("%-22s largest |reach - full| %.3g, |variant 1 - full| %.3g (of the value or the homogeneous form)\n", s.name.c_str(), worst,
                worst_independent);
  }
  return check::exit_code();
}
