// Kernel tables of stacks (THEORY.md section 12 with section 4): H and H1 of a stack's
// C(q) - 1 against GSL quadrature of the stack kernel, the table's own accuracy estimate, the
// sum rule, continuity at u_max (the asymptotic series uses the Taylor coefficients of the
// power-series recursion), and one bonded layer = the one-film table bit for bit. Prints the
// cost of a table for N = 1, 3, 20 layers.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "../common/check.hpp"
#include "../common/oscillatory_integral.hpp"
#include "coatcontact/kernel.hpp"

namespace {

using coatcontact::Layer;
using coatcontact::Material;
using coatcontact::Stack;
using coatcontact::Substrate;

// The table's requirement (as for one film, test_kernel_table.cpp): 1e-10 of max|H|.
constexpr double kTableTier = check::tier::kInterpolation;
constexpr double kQuadratureTarget = 1e-13;

struct Integrand {
  const Stack* stack;
  double f0 = 0;
  double f(double q) const { return coatcontact::compliance_minus_one(*stack, std::vector<double>{q})[0]; }
};

double f_cos(double q, void* p) { return static_cast<Integrand*>(p)->f(q); }
double f_sin_over_q(double q, void* p) {
  auto* in = static_cast<Integrand*>(p);
  if (q == 0) return 0;
  return (in->f(q) - in->f0 * std::exp(-q)) / q;
}

// Up to q = 400: C - 1 ~ exp(-2 q h_top/T) < 1e-45 there for h_top/T >= 1/8.
const std::vector<double> kBreaks = {0,   1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3,
                                     1,   3,    10,   20,   40,   60,   100,  160,  250,  400};

double oscillatory(double (*g)(double, void*), Integrand* in, double u, bool sine, double abs_tol) {
  return check::oscillatory_integral(g, in, u, sine, abs_tol, kBreaks);
}

struct Case {
  const char* name;
  Stack stack;
};

Layer layer(double h, double e, double nu, bool slip = false) { return Layer{h, Material{e, nu}, slip}; }
Substrate elastic(double e, double nu) { return Substrate{false, Material{e, nu}}; }
Substrate rigid() { return Substrate{true, {}}; }

double seconds_for_table(const Stack& stack) {
  const auto start = std::chrono::steady_clock::now();
  const coatcontact::KernelTable table(stack);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main() {
  gsl_set_error_handler_off();
  const double pi = 3.14159265358979323846;
  const std::vector<Case> cases = {
      {"issue stack 1,10/2,1 on 100", Stack({layer(1, 10, 0.3), layer(2, 1, 0.45)}, elastic(100, 0.2))},
      {"3 layers on rigid", Stack({layer(1, 1, 0.3), layer(1, 5, 0.5), layer(2, 0.2, 0.25)}, rigid())},
      {"1 layer sliding on rigid", Stack({layer(1, 1, 0.5, true)}, rigid())},
      {"2 layers, sliding on elastic", Stack({layer(2, 1, 0.3), layer(1, 3, 0.4, true)}, elastic(1, 0.3))},
      {"stiff top 1e3 on soft", Stack({layer(1, 1e3, 0.3), layer(1, 1, 0.3)}, elastic(1, 0.3))},
      {"thin top 1/8", Stack({layer(1, 2, 0.3), layer(7, 1, 0.4)}, elastic(10, 0.3))},
  };
  std::vector<double> us = {0.0, 0.01, 0.3, 2000.0};
  for (int i = 0; i < 30; ++i) us.push_back(0.02 * std::pow(1e5, i / 29.0));
  for (int i = 0; i < 8; ++i) us.push_back(1.234 + 250.5 * i);

  for (const Case& c : cases) {
    const coatcontact::KernelTable table(c.stack);
    const auto info = table.info();
    Integrand in{&c.stack};
    in.f0 = in.f(0.0);
    const double scale = info.max_abs_h;
    const double h1_scale = std::max(scale, std::fabs(info.half_integral));
    double max_h = 0, max_h1 = 0;
    for (double u : us) {
      double h = 0, h1 = 0;
      table.eval(&u, 1, &h, &h1);
      const double h_ref = oscillatory(f_cos, &in, u, false, kQuadratureTarget * scale);
      const double h1_ref = in.f0 * std::atan(u) +
                            oscillatory(f_sin_over_q, &in, u, true, kQuadratureTarget * h1_scale);
      max_h = std::max(max_h, std::fabs(h - h_ref) / scale);
      max_h1 = std::max(max_h1, std::fabs(h1 - h1_ref) / h1_scale);
    }
    // section 12 + 4: H of the stack's C - 1 to the table tier, and an honest estimate
    check::below(max_h, kTableTier, std::string(c.name) + ": H vs GSL");
    check::below(max_h1, kTableTier, std::string(c.name) + ": H1 vs GSL");
    check::below(info.abs_accuracy, kTableTier * scale, std::string(c.name) + ": estimated accuracy");
    check::that(max_h * scale <= 10.0 * info.abs_accuracy + kQuadratureTarget * scale * 10.0,
                std::string(c.name) + ": the estimate is not below the measured error");
    check::below(std::fabs(info.half_integral - 0.5 * pi * in.f0), check::tier::kRounding * h1_scale,
                 std::string(c.name) + ": sum rule (pi/2)(C(0) - 1)");
    // The asymptotic series beyond u_max (Taylor coefficients of the series recursion)
    // continues the table.
    const double below = table.h(info.u_max * (1 - 1e-9)), above = table.h(info.u_max * (1 + 1e-9));
    const double below1 = table.h1(info.u_max * (1 - 1e-9)), above1 = table.h1(info.u_max * (1 + 1e-9));
    check::below(std::fabs(below - above), kTableTier * scale, std::string(c.name) + ": H continuous at u_max");
    check::below(std::fabs(below1 - above1), kTableTier * h1_scale,
                 std::string(c.name) + ": H1 continuous at u_max");
    std::printf("%-30s max|H| %.4g  |H-GSL|/max|H| %.2e  |H1-GSL|/max %.2e  estimate %.2e  du %.4g\n",
                c.name, scale, max_h, max_h1, info.abs_accuracy / scale, info.du);
  }

  // One bonded layer: the one-film table, bit for bit (the same code path).
  {
    const Stack film({layer(3.0, 2.0, 0.3)}, elastic(1.0, 0.25));
    const Material f{2.0, 0.3};
    const coatcontact::KernelTable a(film), b(Stack::film_on(f, elastic(1.0, 0.25)));
    cc_kernel_table* raw = nullptr;
    const double h = 3.0, e = 2.0, nu = 0.3;
    const int slip = 0;
    check::that(cc_kernel_table_create_stack(1, &h, &e, &nu, &slip, 0, 1.0, 0.25, 0, &raw) == CC_OK,
                "one-layer stack table");
    bool same = true;
    for (double u : us) {
      double h_raw = 0;
      cc_kernel_table_eval(raw, 1, &u, &h_raw, nullptr);
      same = same && a.h(u) == b.h(u) && a.h1(u) == b.h1(u) && h_raw == b.h(u);
    }
    cc_kernel_table_destroy(raw);
    check::that(same, "one bonded layer: the one-film table bit for bit");
  }

  // Bad input: a top layer thinner than T/32 is refused before the build (InputError from
  // the C++ table; CC_ERR_ACCURACY from the C one), a bad thickness is InputError from the stack.
  {
    bool refused = false;
    try {
      coatcontact::KernelTable t(Stack({layer(1, 1, 0.3), layer(100, 2, 0.3)}, elastic(1, 0.3)));
    } catch (const coatcontact::InputError& e) {
      refused = std::string(e.what()).find("1/32") != std::string::npos;
    }
    check::that(refused, "top layer < T/32: InputError naming the 1/32 limit");
    {
      cc_kernel_table* thin = nullptr;
      const double h[2] = {1.0, 100.0}, e[2] = {1.0, 2.0}, nu[2] = {0.3, 0.3};
      const int slip[2] = {0, 0};
      check::that(cc_kernel_table_create_stack(2, h, e, nu, slip, 0, 1.0, 0.3, 0, &thin) == CC_ERR_ACCURACY &&
                      thin == nullptr,
                  "top layer < T/32 through the C table: CC_ERR_ACCURACY");
      check::that(cc_kernel_stack_max_refinement() == 32, "cc_kernel_stack_max_refinement: 32");
    }
    cc_kernel_table* raw = nullptr;
    const double h[2] = {1.0, -1.0}, e[2] = {1.0, 1.0}, nu[2] = {0.3, 0.3};
    const int slip[2] = {0, 0};
    check::that(cc_kernel_table_create_stack(2, h, e, nu, slip, 1, 0, 0, 0, &raw) == CC_ERR_THICKNESS &&
                    raw == nullptr,
                "negative thickness: CC_ERR_THICKNESS");
    check::that(cc_kernel_table_create_stack(0, h, e, nu, slip, 1, 0, 0, 0, &raw) == CC_ERR_LAYER_COUNT,
                "no layer: CC_ERR_LAYER_COUNT");
  }

  // Cost of a table (variant 0) for N = 1, 3, 20 layers of equal thickness on an elastic base.
  for (int n : {1, 3, 20}) {
    std::vector<Layer> layers;
    for (int i = 0; i < n; ++i) layers.push_back(layer(1.0, 1.0 + i, 0.3 + 0.005 * i));
    const Stack stack(layers, elastic(50.0, 0.25));
    // top h/T = 1/n: the grid is refined by the next power of 2 >= n
    std::printf("cost of a kernel table, N = %2d layers: %.3f s\n", n, seconds_for_table(stack));
  }
  return check::exit_code();
}
