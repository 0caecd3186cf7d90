// Kernel table H(u) = int_0^inf [C(q)-1] cos(qu) dq and H1(u) = int_0^u H (THEORY.md section 4)
// against GSL's oscillatory quadrature (QAWO, independent of the FFT method), the sum rule
// int_0^inf H = (pi/2)(C(0)-1), and the table's own consistency (H1' = H, symmetry).
// THEORY.md section 6: these are the kernel facts under every solver check (the K(r,s)
// of [EqEquilibriumCS] is built from H and H1).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "check.hpp"
#include "oscillatory_integral.hpp"
#include "coatcontact/kernel.hpp"

namespace {

// The requirement, |H - H_exact| <= 1e-10 max|H| (and H1 likewise).
constexpr double kTableTier = check::tier::kInterpolation;
// kQuadratureTarget: what GSL is asked for (relative to max|H|), well below kTableTier
// so that the reference does not use up the tolerance.
constexpr double kQuadratureTarget = 1e-13;

struct Case {
  const char* name;
  coatcontact::Material film;
  coatcontact::Substrate substrate;
};

struct Integrand {
  const Case* c;
  double f0 = 0;
  double f(double q) const {
    return coatcontact::compliance_minus_one(coatcontact::Stack::film_on(c->film, c->substrate), std::vector<double>{q})[0];
  }
};

double f_cos(double q, void* p) { return static_cast<Integrand*>(p)->f(q); }
// (f(q) - f0 e^{-q}) / q: regular at 0; its sine transform plus f0 atan(u) is H1(u).
double f_sin_over_q(double q, void* p) {
  auto* in = static_cast<Integrand*>(p);
  if (q == 0) return 0;
  return (in->f(q) - in->f0 * std::exp(-q)) / q;
}

// Breakpoints resolving the q-scales of f (down to 1e-5 for ratio 1e3 films).
const std::vector<double> kBreaks = {0,   1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1,
                                     0.3, 1,    3,    10,   20,   40,   60};

// int_0^60 g(q) w(qu) dq with QAWO on each panel (f < 1e-45 beyond q = 60).
double oscillatory(double (*g)(double, void*), Integrand* in, double u, bool sine, double abs_tol) {
  return check::oscillatory_integral(g, in, u, sine, abs_tol, kBreaks);
}

std::vector<double> test_points() {
  std::vector<double> u = {0.0, 0.01, 0.3, 2000.0};
  for (int i = 0; i < 40; ++i) u.push_back(0.02 * std::pow(1e5, i / 39.0));          // 0.02..2000
  for (int i = 0; i < 12; ++i) u.push_back(1.234 + 166.5 * i);                         // off-grid
  return u;
}

}  // namespace

int main() {
  gsl_set_error_handler_off();  // GSL's roundoff warnings are judged by the comparison below
  using coatcontact::Material;
  using coatcontact::Substrate;
  const std::vector<Case> cases = {
      {"soft 0.1", {0.1, 0.25}, {false, {1.0, 0.25}}},
      {"stiff 10", {10.0, 0.25}, {false, {1.0, 0.25}}},
      {"rigid nu=0.3", {1.0, 0.3}, {true, {}}},
      {"rigid nu=0.5", {1.0, 0.5}, {true, {}}},
      {"ratio 1e-3", {1e-3, 0.3}, {false, {1.0, 0.3}}},
      {"ratio 1e3", {1e3, 0.3}, {false, {1.0, 0.3}}},
      {"ratio 1e4 nu=0.5", {1e4, 0.5}, {false, {1.0, 0.5}}},
      // the stability range, and ratios around the pole-removal threshold q0 = 0.05
      {"ratio 1e4", {1e4, 0.3}, {false, {1.0, 0.2}}},
      {"ratio 1e-4", {1e-4, 0.45}, {false, {1.0, 0.1}}},
      {"ratio 8", {8.0, 0.2}, {false, {1.0, 0.4}}},
      {"ratio 30", {30.0, 0.35}, {false, {1.0, 0.25}}},
      {"near-homogeneous", {1.0, 0.3}, {false, {1.0, 0.2}}},
  };
  const std::vector<double> us = test_points();
  const double pi = 3.14159265358979323846;

  for (const Case& c : cases) {
    const coatcontact::KernelTable table(coatcontact::Stack::film_on(c.film, c.substrate));
    const auto info = table.info();
    Integrand in{&c};
    const auto taylor = coatcontact::compliance_taylor(coatcontact::Stack::film_on(c.film, c.substrate), 15);
    in.f0 = taylor[0];
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
      if (std::fabs(h - h_ref) > kTableTier * scale || std::fabs(h1 - h1_ref) > kTableTier * h1_scale)
        std::printf("  %s u=%g: H=%.17g ref=%.17g  H1=%.17g ref=%.17g\n", c.name, u, h, h_ref, h1,
                    h1_ref);
    }
    check::below(max_h, kTableTier, std::string(c.name) + ": H vs GSL");
    check::below(max_h1, kTableTier, std::string(c.name) + ": H1 vs GSL");
    check::below(info.abs_accuracy, kTableTier * scale, std::string(c.name) + ": estimated accuracy");
    std::printf("%-17s max|H| %.4g  |H-GSL|/max|H| %.2e  |H1-GSL|/max %.2e  estimate %.2e\n", c.name,
                scale, max_h, max_h1, info.abs_accuracy / scale);

    // Sum rule: half_integral = (pi/2) f(0), and H1(u) -> it. Far out (u = 1e8, beyond every
    // pole scale: q0 u >> 1 with q0 ~ 5e-5 for ratio 1e4) the tail is the raw-f expansion
    // f1/u - 2 f3/u^3 + 24 f5/u^5.
    check::below(std::fabs(info.half_integral - 0.5 * pi * in.f0), check::tier::kRounding * h1_scale,
                 c.name + std::string(": sum rule value"));
    for (double u : {1e8, 1e9}) {
      const double tail = taylor[1] / u - 2 * taylor[3] / (u * u * u) + 24 * taylor[5] / std::pow(u, 5);
      const double h1 = table.h1(u);
      check::below(std::fabs(h1 - (info.half_integral + tail)), kTableTier * h1_scale,
                   c.name + std::string(": sum rule H1(inf)"));
    }

    // Consistency: H1(u) = int_0^u H (Gauss-Legendre on the table's H, 8 points per 0.25).
    {
      static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                  0.9602898564975363};
      static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                  0.1012285362903763};
      for (double upper : {1.0, 7.3, 40.0}) {
        double integral = 0;
        const int panels = static_cast<int>(upper / 0.25) + 1;
        const double hstep = upper / panels;
        for (int k = 0; k < panels; ++k) {
          const double mid = (k + 0.5) * hstep;
          for (int j = 0; j < 4; ++j)
            integral += 0.5 * hstep * w[j] * (table.h(mid + 0.5 * hstep * x[j]) + table.h(mid - 0.5 * hstep * x[j]));
        }
        check::below(std::fabs(integral - table.h1(upper)), kTableTier * h1_scale,
                     c.name + std::string(": H1 = int H"));
      }
    }
    // Symmetry and continuity at the end of the table.
    for (double u : {0.37, 55.5, 3000.0}) {
      check::that(table.h(-u) == table.h(u) && table.h1(-u) == -table.h1(u),
                  c.name + std::string(": parity"));
    }
    {
      const double below = table.h(info.u_max - 1e-9), above = table.h(info.u_max + 1e-9);
      check::below(std::fabs(below - above), kTableTier * scale,
                   c.name + std::string(": continuity at u_max"));
    }
  }

  // Homogeneous: H = H1 = 0 exactly.
  {
    const coatcontact::KernelTable table(coatcontact::Stack::film_on(Material{2.0, 0.3}, Substrate{false, {2.0, 0.3}}));
    check::that(table.h(0.0) == 0.0 && table.h1(5.0) == 0.0 && table.h(1e4) == 0.0, "homogeneous H = 0");
  }
  // Two threads reading one table give identical values.
  {
    const coatcontact::KernelTable table(coatcontact::Stack::film_on(Material{0.1, 0.25}, Substrate{false, {1.0, 0.25}}));
    std::vector<double> u(20000), a, b, a1, b1;
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = 0.1 * static_cast<double>(i);
    std::thread t1([&] { table.eval(u, a, a1); });
    std::thread t2([&] { table.eval(u, b, b1); });
    t1.join();
    t2.join();
    check::that(a == b && a1 == b1, "concurrent evaluation");
  }
  // Bad constants are refused when the stack is made, with the constant's name.
  {
    bool thrown = false;
    try {
      coatcontact::KernelTable bad(coatcontact::Stack::film_on(Material{1.0, 0.6}, Substrate{false, {1.0, 0.3}}));
    } catch (const coatcontact::InputError& e) {
      thrown = std::string(e.what()).find("film: Poisson ratio") != std::string::npos;
    }
    check::that(thrown, "InputError for nu1 = 0.6");
    thrown = false;
    try {
      coatcontact::compliance(coatcontact::Stack::film_on(Material{1.0, 0.3}, Substrate{false, {-2.0, 0.3}}), 1.0);
    } catch (const coatcontact::InputError& e) {
      thrown = std::string(e.what()).find("substrate: Young's modulus") != std::string::npos;
    }
    check::that(thrown, "InputError for E0 < 0");
  }

  return check::exit_code();
}
