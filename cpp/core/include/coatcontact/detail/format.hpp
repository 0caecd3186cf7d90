// Numbers in messages and headers: one spelling for the whole library.
#pragma once
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>

namespace coatcontact::detail {

// Round-trip text of `value` ("%.17g", locale-independent).
inline std::string full_precision(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  return std::string(buffer, result.ptr);
}

// `value` with `digits` significant digits (default stream format), for readable messages.
inline std::string short_text(double value, int digits = 6) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(digits);
  out << value;
  return out.str();
}

}  // namespace coatcontact::detail
