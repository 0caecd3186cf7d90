// number_string of number_text.hpp: used by materials.cpp (library) and by the CLI parsers,
// so it is built into the library.
#include <charconv>
#include <cmath>
#include <string>

#include "number_text.hpp"

namespace coatcontact::detail {

std::string number_string(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  return std::string(buffer, result.ptr);
}

}  // namespace coatcontact::detail
