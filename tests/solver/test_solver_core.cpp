// Unit tests of the solver core (cpp/solver/reduced_core.*) on analytic kernels, against an
// independent brute-force Nyström solution on a fine uniform grid (analytic_kernels.hpp).
#include <cmath>
#include <cstdio>
#include <string>

#include "analytic_kernels.hpp"
#include "check.hpp"
#include "gauss_legendre.hpp"
#include "reduced_core.hpp"

using namespace coatcontact;

namespace {

namespace tier = check::tier;
// Agreement of two brute-force resolutions (0.25 vs 0.5 panels, 12 points), which bounds the
// reference's own error on these smooth analytic kernels.
constexpr double kBruteSelfTier = 1e-12;

const char* const kNames[] = {"Pi_s", "Delta_s", "Pi_c", "Delta_c", "E_eq", "Gamma1"};

void test_gauss_rules() {
  for (int n : {1, 2, 7, 16, 33, 64, 160}) {
    const auto& rule = detail::gauss_rule(n);
    double sum = 0.0, moment = 0.0;
    for (int k = 0; k < n; ++k) {
      sum += rule.weights[static_cast<std::size_t>(k)];
      moment += rule.weights[static_cast<std::size_t>(k)] * std::pow(rule.nodes[static_cast<std::size_t>(k)], 2 * n - 2);
    }
    check::close(sum, 2.0, tier::kMachine, "Gauss " + std::to_string(n) + " weights sum to 2");
    // Exact for degree 2n - 1: ∫ x^(2n-2) = 2/(2n-1).
    check::close(moment, 2.0 / (2 * n - 1), tier::kAmplified, "Gauss " + std::to_string(n) + " degree 2n-2");
  }
}

// H = 0: the homogeneous values 8/3, 1, 2, 1, 1, 1 exactly (THEORY.md section 6, item 2).
void test_zero_kernel() {
  const test::ZeroKernel kernel;
  const double expected[6] = {8.0 / 3.0, 1.0, 2.0, 1.0, 1.0, 1.0};
  for (double a : {1e-3, 0.5, 3.0, 50.0, 1000.0}) {
    const auto r = detail::solve_adaptive(kernel, a, 1e-8);
    check::that(r.converged, "zero kernel converges at a/t " + std::to_string(a));
    for (int i = 0; i < 6; ++i) {
      check::close(r.values[static_cast<std::size_t>(i)], expected[i], tier::kMachine,
                   std::string("zero kernel ") + kNames[i] + " at a/t " + std::to_string(a));
    }
  }
}

// Solver against brute force: the true error must be within the requested tolerance.
void test_against_brute_force() {
  const test::LorentzKernel soft(-0.9, 2.0);        // C(0) = 0.1 (soft film)
  const test::LorentzKernel stiff(9.0, 2.0);        // C(0) = 10 (stiff film)
  const test::DoublePoleKernel double_pole(3.0, 2.0);  // C(0) = 1, sign-changing H
  const test::LorentzKernel narrow(-0.5, 0.7);      // strip half-width 0.7 (not 2)
  const detail::KernelSource* kernels[] = {&soft, &stiff, &double_pole, &narrow};
  const char* names[] = {"soft", "stiff", "double-pole", "narrow"};
  for (int k = 0; k < 4; ++k) {
    for (double a : {0.05, 0.7, 1.9, 2.5, 6.0, 15.0, 40.0}) {
      const auto fine = test::brute_force(*kernels[k], a, 0.25, 12);
      const auto coarse = test::brute_force(*kernels[k], a, 0.5, 12);
      for (double tolerance : {1e-6, 1e-10}) {
        const auto r = detail::solve_adaptive(*kernels[k], a, tolerance);
        const std::string where = std::string(names[k]) + " kernel, a/t " + std::to_string(a) +
                                  ", tol " + std::to_string(tolerance);
        check::that(r.converged, where + ": converged");
        check::below(r.error_estimate, tolerance, where + ": estimate <= tolerance");
        for (int i = 0; i < 6; ++i) {
          const auto idx = static_cast<std::size_t>(i);
          check::close(coarse[idx], fine[idx], kBruteSelfTier,
                       where + ": brute-force self-consistency " + kNames[i]);
          check::close(r.values[idx], fine[idx], tolerance + kBruteSelfTier,
                       where + ": " + kNames[i] + " within tolerance");
        }
      }
    }
  }
}

// The cost statement: the number of unknowns grows only logarithmically with a/t. Panels are
// graded geometrically (docs/solver.md), so 100x the radius adds log2(100) ~ 7 panels; the
// nodes per panel may rise by a refinement step or two where the solution has more structure.
void test_unknowns_independent_of_radius() {
  const test::LorentzKernel kernel(-0.9, 2.0);
  const auto small = detail::solve_adaptive(kernel, 10.0, 1e-8);
  const auto large = detail::solve_adaptive(kernel, 1000.0, 1e-8);
  const int small_panels = small.unknowns / small.nodes_per_panel;
  const int large_panels = large.unknowns / large.nodes_per_panel;
  std::printf("unknowns at tol 1e-8: a/t 10 -> %d (%d panels x %d), a/t 1000 -> %d (%d x %d)\n",
              small.unknowns, small_panels, small.nodes_per_panel, large.unknowns, large_panels,
              large.nodes_per_panel);
  check::below(large_panels - small_panels, 8, "panels grow like log2(a/t)");
  check::below(large.nodes_per_panel - small.nodes_per_panel, 2 * detail::kRefinementStep,
               "nodes per panel nearly independent of a/t");
}

}  // namespace

int main() {
  test_gauss_rules();
  test_zero_kernel();
  test_against_brute_force();
  test_unknowns_independent_of_radius();
  return check::exit_code();
}
