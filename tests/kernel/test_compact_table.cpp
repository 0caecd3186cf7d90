// Compact kernel tables (cc_kernel_table_create_range / _stack_range, issue 11: the solver's
// tables sized to the work) against the full default grid of the same film or stack: on the
// range they tabulate and beyond it (asymptotic series), H agrees with the full table to the
// kernel table's tier (1e-10 of max|H|), for soft, matched, stiff (pole removal) and
// rigid-substrate films and for 3-layer stacks; a compact table holds H only (H1 is refused);
// bad ranges are rejected.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../common/check.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/kernel.hpp"

namespace {

using coatcontact::Layer;
using coatcontact::Material;
using coatcontact::Stack;
using coatcontact::Substrate;

// Both tables meet the kernel table's target, 1e-10 of max|H| (THEORY.md section 4).
constexpr double kTableTier = check::tier::kInterpolation;

Layer layer(double h, double e, double nu) { return Layer{h, Material{e, nu}, false}; }
Substrate elastic(double e, double nu) { return Substrate{false, Material{e, nu}}; }
Substrate rigid() { return Substrate{true, {}}; }

struct Case {
  std::string name;
  Stack stack;
  bool must_build;  // the compact grid serves the solver's first level (u <= 80) here
};

void compare(const Case& c) {
  const coatcontact::KernelTable full(c.stack);
  const auto full_info = full.info();
  for (double range : {80.0, 320.0, 1280.0}) {
    const std::string name = c.name + ", range " + std::to_string(static_cast<int>(range));
    try {
      const coatcontact::KernelTable compact(c.stack, range);
      const auto info = compact.info();
      check::that(info.u_max >= range && info.u_max <= full_info.u_max, name + ": covers the range");
      check::that(info.du == full_info.du, name + ": the full grid's step");
      // nodes, off-grid points and the series beyond u_max, up to 3x the range
      std::vector<double> u;
      for (double x = 0; x <= 3 * range; x += 0.0137) u.push_back(x);
      for (double x = 0; x <= info.u_max; x += info.du) u.push_back(x);
      std::vector<double> hc, hf;
      compact.eval(u, hc);
      full.eval(u, hf);
      double worst = 0;
      for (std::size_t i = 0; i < u.size(); ++i) worst = std::max(worst, std::fabs(hc[i] - hf[i]));
      // max|H| = 0 for a homogeneous pair (H = 0 exactly): then both must be exactly 0.
      const double scale = full_info.max_abs_h > 0 ? full_info.max_abs_h : 1.0;
      std::printf("%-40s u_max %6.0f  max|H - H_full|/max|H| %.2e (stated %.2e)\n", name.c_str(),
                  info.u_max, worst / scale, info.abs_accuracy / scale);
      if (full_info.max_abs_h > 0) {
        check::below(worst / scale, kTableTier, name + ": H equals the full table's");
        check::below(info.abs_accuracy, kTableTier * scale, name + ": stated accuracy");
      } else {
        check::that(worst == 0 && info.max_abs_h == 0, name + ": H = 0 as on the full table");
      }
      double h = 0, h1 = 0, at = 1.0;
      check::throws<coatcontact::InputError>([&] { compact.eval(&at, 1, &h, &h1); }, "H1");
    } catch (const coatcontact::NumericalError& e) {
      std::printf("%-40s accuracy target missed (the solver takes a longer grid): %s\n", name.c_str(),
                  e.what());
      check::that(!(c.must_build && range == 80.0), name + ": compact table built");
    }
  }
}

void test_bad_ranges() {
  const double h[3] = {1, 1, 2}, e[3] = {1, 5, 0.2}, nu[3] = {0.3, 0.5, 0.25};
  const int slip[3] = {0, 0, 0};
  for (double range : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    cc_kernel_table* t = nullptr;
    check::that(cc_kernel_table_create_range(0.1, 0.25, 1, 0.25, 0, range, &t) == CC_ERR_ARGUMENT &&
                    t == nullptr,
                "film: range " + std::to_string(range) + " rejected");
    check::that(cc_kernel_table_create_stack_range(3, h, e, nu, slip, 1, 0, 0, range, &t) == CC_ERR_ARGUMENT &&
                    t == nullptr,
                "stack: range " + std::to_string(range) + " rejected");
  }
  check::that(cc_kernel_table_create_range(0.1, 0.25, 1, 0.25, 0, 80, nullptr) == CC_ERR_ARGUMENT,
              "null handle rejected");
  check::that(cc_kernel_table_create_stack_range(3, h, e, nu, slip, 1, 0, 0, 80, nullptr) == CC_ERR_ARGUMENT,
              "stack: null handle rejected");
}

}  // namespace

int main() {
  const std::vector<Case> cases = {
      {"film 0.1/1", Stack::film_on(Material{0.1, 0.25}, elastic(1, 0.25)), true},
      {"film 1e-3/1 nu 0.5", Stack::film_on(Material{1e-3, 0.5}, elastic(1, 0.5)), false},
      {"film 1/1", Stack::film_on(Material{1, 0.3}, elastic(1, 0.3)), true},
      {"film 3/1", Stack::film_on(Material{3, 0.25}, elastic(1, 0.25)), true},
      {"film 10/1", Stack::film_on(Material{10, 0.25}, elastic(1, 0.25)), true},
      {"film 100/1", Stack::film_on(Material{100, 0.25}, elastic(1, 0.25)), false},
      {"film 1e4/1", Stack::film_on(Material{1e4, 0.3}, elastic(1, 0.3)), false},
      {"film on rigid", Stack::film_on(Material{1, 0.3}, rigid()), false},
      {"film nu 0.5 on rigid", Stack::film_on(Material{1, 0.5}, rigid()), false},
      {"3 layers on rigid", Stack({layer(1, 1, 0.3), layer(1, 5, 0.5), layer(2, 0.2, 0.25)}, rigid()), false},
      {"3 layers 1,10/1,1/2,3 on 100",
       Stack({layer(1, 10, 0.3), layer(1, 1, 0.45), layer(2, 3, 0.3)}, elastic(100, 0.2)), false},
      {"3 layers, soft top 1/4", Stack({layer(1, 0.5, 0.3), layer(1, 2, 0.4), layer(2, 1, 0.3)}, elastic(3, 0.3)),
       true},
  };
  for (const Case& c : cases) compare(c);
  test_bad_ranges();
  return check::exit_code();
}
