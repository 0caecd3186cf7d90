// Adapter from the Fortran kernel table to the solver's KernelSource.
#include "table_kernel.hpp"

#include <algorithm>
#include <vector>

namespace coatcontact::detail {

TableKernel::TableKernel(const Stack& stack, int grid_variant)
    : table_(stack, grid_variant), info_(table_.info()) {
  if (stack.is_multilayer()) {
    half_width_ = 2.0 * stack.layers().front().thickness / stack.total_thickness();
  }
}

void TableKernel::evaluate(std::size_t n, const double* u, double* h) const {
  // Chunks keep the C interface's int lengths small; H1 goes to a per-thread buffer (a null
  // pointer would make the library allocate scratch on every call).
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  thread_local std::vector<double> h1;
  if (h1.size() < std::min(n, kChunk)) h1.resize(std::min(n, kChunk));
  for (std::size_t start = 0; start < n; start += kChunk) {
    const std::size_t count = std::min(kChunk, n - start);
    table_.eval(u + start, count, h + start, h1.data());
  }
}

}  // namespace coatcontact::detail
