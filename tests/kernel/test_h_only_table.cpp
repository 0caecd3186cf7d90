// Tables without H1 (cc_kernel_table_create_h / _stack_h, KernelTable::HOnly: the solver's
// full-grid and independent tables, issue 26 item 3): H, the grid, the accuracy estimate and
// the sum rule equal those of the table with H1 bit for bit, on every grid variant the solver
// uses, for a film on an elastic and on a rigid base and for a 3-layer stack; H1 is refused.
// Bit for bit because the solver's printed values must not change (THEORY.md section 4: H and
// H1 are separate transforms of the same samples). The H-only evaluation is also the batched
// one, checked here against the point-by-point evaluation of the table with H1, in one long
// batch and in batches of every length up to two chunks.
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
  // The H-only path evaluates in chunks (cc_kernel_tables.f90, evaluate_kernel_h_many): the
  // nodes themselves (t = 0), the reflected stencil within 5 steps of u = 0, u_max on both
  // sides, and table and far-field points interleaved (the far ones are kept out of a chunk).
  for (int k = -8; k <= 8; ++k) {
    u.push_back(k * a.du);
    u.push_back((k + 0.37) * a.du);
  }
  for (double x : {a.u_max, std::nextafter(a.u_max, 0.0), std::nextafter(a.u_max, 2.0 * a.u_max)}) u.push_back(x);
  for (int k = 0; k < 300; ++k) u.push_back(k % 3 == 0 ? (1.0 + 0.01 * k) * a.u_max : 0.013 * k - 2.0);
  // ha: with H1, point by point (evaluate_kernel_table); hb, hc: H alone, batched, on either table.
  std::vector<double> ha, ha1, hb, hc;
  full.eval(u, ha, ha1);
  h_only.eval(u, hb);
  full.eval(u, hc);
  std::size_t differing = 0, differing_batch = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    differing += ha[i] == hb[i] ? 0 : 1;
    differing_batch += ha[i] == hc[i] ? 0 : 1;
  }
  check::that(differing == 0, what + ": H equal at " + std::to_string(u.size()) + " points (" +
                                  std::to_string(differing) + " differ)");
  check::that(differing_batch == 0, what + ": H alone (batched) equal to H with H1 at " + std::to_string(u.size()) +
                                        " points (" + std::to_string(differing_batch) + " differ)");
  // Batches of every length up to two chunks (the basis is computed for a chunk's own points:
  // odd lengths end in the loop's scalar remainder), each from a different start, point by
  // point equal to the elemental values.
  std::size_t differing_lengths = 0;
  std::vector<double> part(130);
  for (std::size_t count = 1; count <= 130; ++count) {
    const std::size_t start = (7 * count) % (u.size() - count);
    h_only.eval(u.data() + start, count, part.data());
    for (std::size_t i = 0; i < count; ++i) differing_lengths += part[i] == ha[start + i] ? 0 : 1;
  }
  check::that(differing_lengths == 0, what + ": batches of 1..130 points equal point by point (" +
                                          std::to_string(differing_lengths) + " values differ)");
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
