// A kernel table's values at given points, for bit-for-bit comparisons of two tables: H, then
// H1 appended when with_h1 (the table has it).
#pragma once
#include <vector>

#include "coatcontact/kernel.hpp"

namespace check {

inline std::vector<double> kernel_values(const coatcontact::KernelTable& table, const std::vector<double>& u,
                                         bool with_h1) {
  std::vector<double> h, h1;
  if (with_h1) {
    table.eval(u, h, h1);
    h.insert(h.end(), h1.begin(), h1.end());
  } else {
    table.eval(u, h);
  }
  return h;
}

}  // namespace check
