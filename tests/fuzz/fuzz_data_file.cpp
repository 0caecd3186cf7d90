// libFuzzer target: the data file reader on arbitrary text. The first byte chooses the
// number of columns (1..4), the non-negative flags and whether unit kinds are checked.
// An InputError is the expected answer to bad input; anything else is a bug and aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/data_file.hpp"

using namespace coatcontact;

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_data_file: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const unsigned selector = data[0];
  const std::size_t columns = 1 + (selector & 3u);
  std::vector<bool> nonnegative(columns);
  for (std::size_t c = 0; c < columns; ++c) nonnegative[c] = ((selector >> (2 + c)) & 1u) != 0;
  std::vector<std::optional<Quantity>> kinds;
  if ((selector & 0x80u) != 0) {
    // depth, load, then dimensionless columns
    kinds = {Quantity::kLength, Quantity::kForce, std::nullopt, std::nullopt};
    kinds.resize(columns);
  }
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const DataTable table = read_data_text(text, "fuzz", columns, nonnegative, kinds);
    require(table.columns.size() == columns, "wrong number of columns");
    require(table.rows() >= 1 && table.rows() <= kMaxDataRows, "row count out of range");
    require(table.column_names.empty() || table.column_names.size() == columns, "column names");
    require(table.units.empty() || table.units.size() == columns, "units");
    for (std::size_t c = 0; c < columns; ++c) {
      require(table.columns[c].size() == table.rows(), "ragged columns");
      for (double v : table.columns[c]) {
        require(std::isfinite(v), "non-finite value returned");
        require(!nonnegative[c] || v >= 0.0, "negative value in a non-negative column");
      }
    }
    for (std::size_t r = 1; r < table.rows(); ++r) {
      require(table.line_numbers[r] > table.line_numbers[r - 1], "line numbers not increasing");
    }
  } catch (const InputError&) {
    // bad input, reported properly
  }
  return 0;
}
