// The solver's compact kernel table (radii a/t <= 40: u_max 80, or 160 and 320 where the
// far-field series falls too slowly at 80; make_solver_table) against the full grid
// (docs/solver.md, "Kernel tables sized to the work"; THEORY.md section 4, the kernel H, and
// section 6, whose checks assume H to the table's stated accuracy). The compact table is kept
// for a radius when the coherent kernel bound, carried from the compact table's own accuracy
// estimate, is <= tolerance / 10 (the rule of the full grid's coherent bound). Checks, over
// material pairs with soft (nearly) incompressible films on stiff, glass-like and rigid
// substrates, compressible and stiff films and a stack, a/t 1e-3..5 (30 radii each) and 6..40
// (4 each):
//  - the tables: |H_compact(u) - H_full(u)| <= the two tables' stated accuracies, u in [0, 80];
//  - every radius: the result solve() returns (compact or full grid) within its error
//    estimate of the full-grid solve, and at the same discretization within the coherent
//    kernel bounds and rounding terms of the two solves (same p, other table);
//  - the compact table serves the bench's pair (film nu1 = 0.5 on a 10x stiffer base) at
//    every a/t <= 5 (issue 37's JKR search on a coating: a full grid per E1 node dominated).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/reduced.hpp"
#include "materials.hpp"
#include "reduced_core.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;
using coatcontact::test::elastic;
using coatcontact::test::material;
using coatcontact::test::rigid;

namespace {

constexpr double kTolerance = kDefaultTolerance;
constexpr double kCompactRange = 80.0;

std::string str(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

double max_relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]) / std::abs(b[i]));
  return worst;
}

struct Case {
  std::string name;
  Stack stack;
  bool compact_required_to_5;  // the compact table must serve every a/t <= 5
};

std::vector<Case> cases() {
  std::vector<Case> out;
  out.push_back({"nu1 0.5, E1/E0 0.1 (bench)", Stack::film_on(material(0.1, 0.5), elastic(1.0, 0.3)), true});
  // Compact grids refused at u_max = 80 (far-field series falling too slowly there): 160, 320.
  out.push_back({"nu1 0.5, E1/E0 0.237", Stack::film_on(material(0.2371, 0.5), elastic(1.0, 0.3)), false});
  out.push_back({"nu1 0.5, E1/E0 0.562", Stack::film_on(material(0.5623, 0.5), elastic(1.0, 0.3)), false});
  out.push_back({"nu1 0.45, E1/E0 0.75, nu0 0.5", Stack::film_on(material(0.7499, 0.45), elastic(1.0, 0.5)), false});
  out.push_back({"nu1 0.5, E1/E0 0.01", Stack::film_on(material(0.01, 0.5), elastic(1.0, 0.3)), false});
  out.push_back({"nu1 0.5, E1/E0 1e-3, nu0 0.5", Stack::film_on(material(1e-3, 0.5), elastic(1.0, 0.5)), false});
  out.push_back({"nu1 0.5 on rigid", Stack::film_on(material(1.0, 0.5), rigid()), false});
  out.push_back({"nu1 0.49, E1/E0 1.4e-5 (glass)", Stack::film_on(material(1.0, 0.49), elastic(7e4, 0.22)), false});
  out.push_back({"nu1 0.49 on rigid", Stack::film_on(material(1.0, 0.49), rigid()), false});
  out.push_back({"nu1 0.3 on rigid", Stack::film_on(material(1.0, 0.3), rigid()), false});
  out.push_back({"stiff film E1/E0 10", Stack::film_on(material(10.0, 0.3), elastic(1.0, 0.25)), false});
  out.push_back({"soft on stiff layers", coatcontact::test::soft_on_stiff_layers(), false});
  return out;
}

std::vector<double> radii() {
  std::vector<double> a;
  for (int i = 0; i < 30; ++i) a.push_back(1e-3 * std::pow(5.0 / 1e-3, i / 29.0));
  for (double x : {6.0, 12.0, 24.0, 40.0}) a.push_back(x);
  return a;
}

// |H_compact - H_full| <= acc_compact + acc_full on a grid finer than the tables' step (nodes
// and midpoints of both stencils).
void check_tables(const Case& c, const detail::TableKernel& compact, const detail::TableKernel& full) {
  const std::size_t n = 80001;
  std::vector<double> u(n), hc(n), hf(n);
  for (std::size_t i = 0; i < n; ++i) u[i] = kCompactRange * static_cast<double>(i) / static_cast<double>(n - 1);
  compact.evaluate(n, u.data(), hc.data());
  full.evaluate(n, u.data(), hf.data());
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(hc[i] - hf[i]));
  const double allowed = compact.absolute_accuracy() + full.absolute_accuracy();
  std::printf("%-30s tables: max|H_c - H_f| %.2e, stated accuracy compact (u_max %g) %.2e, full %.2e\n",
              c.name.c_str(), worst, compact.u_max(), compact.absolute_accuracy(), full.absolute_accuracy());
  check::below(worst, allowed, c.name + ": compact table within the stated accuracies of the full grid");
}

struct Tally {
  int radii = 0;
  int on_compact = 0;
  double worst_ratio = 0.0;         // |result - full| / allowed
  double worst_kernel_ratio = 0.0;  // same-p difference / allowed
};

void check_radius(const Case& c, double a, const std::function<const detail::KernelSource&(int)>& table,
                  const detail::TableKernel& full, detail::IndependentTables& independent, Tally& tally) {
  const detail::AdaptiveSolve solved = detail::solve_on_solver_tables(table, a, kTolerance, independent.source());
  const detail::AdaptiveSolve reference = detail::solve_adaptive(full, a, kTolerance, independent.source());
  const std::string at = c.name + " at a/t " + str(a);
  check::that(solved.converged && reference.converged, at + ": both solves converged");
  if (!solved.converged || !reference.converged) return;
  const bool compact = solved.table_level == 0;
  const double difference = max_relative_difference(solved.values, reference.values);
  // The reference's own rounding (~1 ulp at small a/t, where the estimates are ~1e-15).
  const double allowed = solved.error_estimate + reference.rounding_error;
  check::below(difference, allowed, at + ": within its estimate of the full-grid solve");
  ++tally.radii;
  tally.worst_ratio = std::max(tally.worst_ratio, difference / allowed);
  if (!compact) {
    check::that(difference == 0.0, at + ": a radius refused by the compact table is the full grid's");
    if (a <= 5.0 && c.compact_required_to_5) check::that(false, at + ": the compact table serves it");
    return;
  }
  ++tally.on_compact;
  detail::Discretization disc;
  disc.quadrature_accuracy = std::clamp(1e-4 * kTolerance, 1e-14, 1e-11);
  disc.nodes_per_panel = solved.nodes_per_panel;
  const detail::FixedSolve same_p = detail::solve_fixed(full, a, disc);
  const double kernel_difference = max_relative_difference(solved.values, same_p.values);
  // Same p: the kernel terms and the two LU solves' rounding (ε cond) differ, nothing else.
  const double kernel_allowed =
      solved.kernel_bound + same_p.kernel_error + solved.rounding_error + same_p.rounding_error;
  check::below(kernel_difference, kernel_allowed, at + ": same discretization within the kernel bounds");
  tally.worst_kernel_ratio = std::max(tally.worst_kernel_ratio, kernel_difference / kernel_allowed);
}

void test_compact_against_full_grid() {
  const std::vector<double> a_list = radii();
  int total = 0;
  for (const Case& c : cases()) {
    std::unique_ptr<detail::TableKernel> levels[detail::kSolverTableLevels];
    const auto table = [&](int level) -> const detail::KernelSource& {
      auto& t = levels[level];
      if (!t) t = detail::make_solver_table(c.stack, level);
      return *t;
    };
    const detail::TableKernel full(c.stack);
    detail::IndependentTables independent(c.stack);
    const detail::TableKernel& compact = dynamic_cast<const detail::TableKernel&>(table(0));
    check::that(compact.u_max() <= 4.0 * kCompactRange, c.name + ": a compact table (u_max " + str(compact.u_max()) + ")");
    check_tables(c, compact, full);
    Tally tally;
    for (double a : a_list) check_radius(c, a, table, full, independent, tally);
    std::printf("%-30s %d radii, %d on the compact table; max |result - full| / estimate %.2e, "
                "same-p difference / (kernel + rounding terms) %.2e\n",
                c.name.c_str(), tally.radii, tally.on_compact, tally.worst_ratio, tally.worst_kernel_ratio);
    total += tally.radii;
  }
  check::that(total >= 200, "at least 200 radii compared");
}

}  // namespace

int main() {
  test_compact_against_full_grid();
  return check::exit_code();
}
