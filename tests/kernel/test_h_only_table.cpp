// Tables without H1 (cc_kernel_table_create_h / _stack_h, KernelTable::HOnly: the solver's
// full-grid and independent tables, issue 26 item 3): H, the grid, the accuracy estimate and
// the sum rule equal those of the table with H1 bit for bit, on every grid variant the solver
// uses, for a film on an elastic and on a rigid base and for a 3-layer stack; H1 is refused.
// Bit for bit because the solver's printed values must not change (THEORY.md section 4: H and
// H1 are separate transforms of the same samples).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../common/check.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/kernel.hpp"

namespace {

using coatcontact::KernelTable;
using coatcontact::Layer;
using coatcontact::Material;
using coatcontact::Stack;
using coatcontact::Substrate;

void compare(const std::string& name, const Stack& stack, int variant) {
  const KernelTable full(stack, variant);
  const KernelTable h_only(stack, variant, KernelTable::HOnly{});
  const auto a = full.info(), b = h_only.info();
  const std::string what = name + ", variant " + std::to_string(variant);
  check::that(a.u_max == b.u_max && a.du == b.du && a.c_zero == b.c_zero && a.half_integral == b.half_integral &&
                  a.abs_accuracy == b.abs_accuracy && a.max_abs_h == b.max_abs_h,
              what + ": the same grid, sum rule and accuracy");
  std::vector<double> u;
  for (double x = -30.0; x <= 1.5 * a.u_max; x += 0.0731) u.push_back(x);  // nodes between, series beyond
  std::vector<double> ha, hb;
  full.eval(u, ha);
  h_only.eval(u, hb);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < u.size(); ++i) differing += ha[i] == hb[i] ? 0 : 1;
  check::that(differing == 0, what + ": H equal at " + std::to_string(u.size()) + " points (" +
                                  std::to_string(differing) + " differ)");
  std::vector<double> h(1), h1(1);
  bool refused = false;
  try {
    h_only.eval(u.data(), 1, h.data(), h1.data());
  } catch (const coatcontact::InputError&) {
    refused = true;
  }
  check::that(refused, what + ": H1 refused");
}

}  // namespace

int main() {
  const Stack film = Stack::film_on(Material{1.0, 0.3}, Substrate{false, Material{10.0, 0.25}});
  const Stack rigid = Stack::film_on(Material{1.0, 0.49}, Substrate{true, {}});
  const Stack layers({Layer{1.0, Material{1.0, 0.3}, false}, Layer{2.0, Material{5.0, 0.25}, false},
                      Layer{1.0, Material{0.5, 0.45}, false}},
                     Substrate{false, Material{20.0, 0.3}});
  for (int variant : {0, 1, 2}) {
    compare("film on an elastic base", film, variant);
    compare("film on a rigid base", rigid, variant);
  }
  compare("3-layer stack", layers, 0);
  compare("3-layer stack", layers, 1);
  return check::exit_code();
}
