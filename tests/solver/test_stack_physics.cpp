// Reduced variables of layer stacks (THEORY.md section 12, with the checks of section 6):
// the identity Γ(1)² = d(ã E_eq)/dã, the limits a/T -> 0 (top layer) and a/T -> ∞ (base),
// and a layer split into identical sublayers. ã = a/T, moduli by the top layer's E*.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/reduced.hpp"

using namespace coatcontact;
namespace tier = check::tier;

namespace {

Layer layer(double h, double e, double nu, bool slip = false) { return Layer{h, Material{e, nu}, slip}; }
Substrate elastic(double e, double nu) { return Substrate{false, Material{e, nu}}; }

std::vector<double> log_space(double from, double to, int count) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i) v.push_back(from * std::pow(to / from, i / (count - 1.0)));
  return v;
}

std::string str(double value) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", value);
  return b;
}

// The issue's stack (stiff top on a soft interlayer on a stiff base) and a sliding variant.
Stack issue_stack() { return Stack({layer(1, 10, 0.3), layer(2, 1, 0.45)}, elastic(100, 0.2)); }
Stack sliding_stack() { return Stack({layer(1, 1, 0.3), layer(1, 3, 0.4, true)}, elastic(1, 0.3)); }

// Section 12 check "identity": Γ(1)² = d(ã E_eq)/dã holds for any kernel (section 6, item 1),
// derivative by 6th-order central differences in ln ã as in test_solver_physics.cpp.
void test_identity() {
  struct Case {
    const char* name;
    Stack stack;
  };
  const Case cases[] = {{"1,10 / 2,1 on 100", issue_stack()}, {"sliding interlayer", sliding_stack()}};
  const double step = 0.05;
  const double coefficient[3] = {3.0 / 4.0, -3.0 / 20.0, 1.0 / 60.0};
  for (const Case& c : cases) {
    const ReducedSolver solver(c.stack);
    double worst = 0.0;
    for (double a : log_space(0.01, 100.0, 9)) {
      std::vector<double> radii;
      for (int k = -3; k <= 3; ++k) radii.push_back(a * std::exp(k * step));
      const auto rows = solver.sweep(radii, 1e-9);
      auto f = [&](int k) {
        const auto& r = rows[static_cast<std::size_t>(k + 3)];
        return r.a_over_t * r.e_eq;
      };
      double ds = 0.0;
      for (int k = 1; k <= 3; ++k) ds += coefficient[k - 1] * (f(k) - f(-k)) / step;
      const double identity = std::sqrt(ds / a);
      check::close(rows[3].gamma1, identity, tier::kIdentityByDifferences,
                   std::string("section 12 identity Γ(1)² = d(ãE_eq)/dã, ") + c.name + ", a/T " + str(a));
      worst = std::max(worst, std::abs(rows[3].gamma1 - identity) / identity);
    }
    std::printf("identity %-20s worst |Γ1 - sqrt(d(ãE)/dã)|/Γ1 = %.2e over a/T in [0.01, 100]\n", c.name, worst);
  }
}

// Section 12 check "limits": a/T -> 0 gives the top layer's half-space (the homogeneous
// values, at least linearly in ã); a/T -> ∞ gives the base: E_eq -> E_base*/E_top*,
// Γ(1) -> sqrt(E_base*/E_top*), approached as O(1/ã).
void test_limits() {
  const ReducedSolver solver(issue_stack());
  const ReducedVariables at_2 = solver.solve(1e-2), at_3 = solver.solve(1e-3);
  const double hom[6] = {8.0 / 3.0, 1.0, 2.0, 1.0, 1.0, 1.0};
  const double v2[6] = {at_2.pi_s, at_2.delta_s, at_2.pi_c, at_2.delta_c, at_2.e_eq, at_2.gamma1};
  const double v3[6] = {at_3.pi_s, at_3.delta_s, at_3.pi_c, at_3.delta_c, at_3.e_eq, at_3.gamma1};
  for (int i = 0; i < 6; ++i) {
    const double d2 = std::abs(v2[i] / hom[i] - 1.0), d3 = std::abs(v3[i] / hom[i] - 1.0);
    std::printf("a/T -> 0, variable %d: deviation %.3e at 1e-2, %.3e at 1e-3\n", i, d2, d3);
    check::that(d3 < d2 / 5.0 && d3 < 1e-2,
                "section 12 limit a/T -> 0 (top layer), variable " + std::to_string(i));
  }
  const double s = issue_stack().substrate().material.reduced_modulus() / issue_stack().top().reduced_modulus();
  const ReducedVariables v100 = solver.solve(100.0), v1000 = solver.solve(1000.0);
  const struct {
    const char* name;
    double at_100, at_1000, limit, bound;
  } limits[] = {{"E_eq -> E_base*/E_top*", v100.e_eq, v1000.e_eq, s, 0.05},
                {"Gamma1 -> sqrt(E_base*/E_top*)", v100.gamma1, v1000.gamma1, std::sqrt(s), 0.01}};
  for (const auto& l : limits) {
    const double d100 = std::abs(l.at_100 / l.limit - 1.0), d1000 = std::abs(l.at_1000 / l.limit - 1.0);
    std::printf("a/T -> inf, %s: deviation %.3e at 100, %.3e at 1000\n", l.name, d100, d1000);
    check::that(d1000 < l.bound && d1000 < d100 / 4.0,
                std::string("section 12 limit a/T -> inf (base), ") + l.name);
  }
}

// Section 12 check "split layer": a layer split into two identical sublayers is the same
// stack. Splitting the interlayer keeps the grid; splitting the top layer halves h_top/T,
// so the table and the panels differ: an independent discretization of the same answer.
void test_split_layer() {
  const ReducedSolver whole(issue_stack());
  const ReducedSolver split_mid(Stack({layer(1, 10, 0.3), layer(0.5, 1, 0.45), layer(1.5, 1, 0.45)},
                                      elastic(100, 0.2)));
  const ReducedSolver split_top(Stack({layer(0.5, 10, 0.3), layer(0.5, 10, 0.3), layer(2, 1, 0.45)},
                                      elastic(100, 0.2)));
  const double tol = 1e-10;
  double worst = 0.0;
  for (double a : {0.05, 0.7, 3.0, 20.0}) {
    const ReducedVariables w = whole.solve(a, tol);
    for (const ReducedSolver* other : {&split_mid, &split_top}) {
      const ReducedVariables v = other->solve(a, tol);
      const double pairs[6][2] = {{w.pi_s, v.pi_s},   {w.delta_s, v.delta_s}, {w.pi_c, v.pi_c},
                                  {w.delta_c, v.delta_c}, {w.e_eq, v.e_eq},   {w.gamma1, v.gamma1}};
      for (const auto& p : pairs) {
        // both solved to 1e-10; the solver tier leaves a margin for the two estimates
        check::close(p[1], p[0], tier::kSolver, "section 12 split layer, a/T " + str(a));
        worst = std::max(worst, std::abs(p[1] / p[0] - 1.0));
      }
    }
  }
  std::printf("split layer: worst relative difference %.2e\n", worst);
}

}  // namespace

int main() {
  test_identity();
  test_limits();
  test_split_layer();
  return check::exit_code();
}
