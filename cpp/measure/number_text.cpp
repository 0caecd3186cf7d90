// Strict decimal numbers and their text (number_text.hpp): the one number grammar of the data
// file reader (measure floor) and of the CLI's value parsers.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>
#include <cmath>
#include <string>
#include <vector>

#include "coatcontact/detail/format.hpp"
#include "number_text.hpp"

namespace coatcontact::detail {

std::string_view trim_blanks(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

std::string trim(std::string_view text) { return std::string(trim_blanks(text)); }

std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> items;
  for (;;) {
    const std::size_t end = text.find(separator);
    items.emplace_back(text.substr(0, end));
    if (end == std::string_view::npos) return items;
    text.remove_prefix(end + 1);
  }
}

NumberStatus parse_decimal(std::string_view text, double& value) {
  if (text.empty()) return NumberStatus::kNotNumber;
  // from_chars takes no '+'; accept one in front of a digit or '.' (not "+-1", not "++1").
  if (text.front() == '+') {
    text.remove_prefix(1);
    if (text.empty() || text.front() == '+' || text.front() == '-') return NumberStatus::kNotNumber;
  }
  // Only the characters of decimal notation: rules out "nan", "inf", "0x1p3" up front, so the
  // message can say which of the two it was.
  for (char c : text) {
    const bool decimal = (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' ||
                         c == '+' || c == '-';
    if (!decimal) {
      std::string lower;
      for (char d : text) lower.push_back(static_cast<char>(d >= 'A' && d <= 'Z' ? d - 'A' + 'a' : d));
      if (!lower.empty() && lower.front() == '-') lower.erase(0, 1);
      if (lower == "nan" || lower == "inf" || lower == "infinity" || lower.rfind("nan(", 0) == 0) {
        return NumberStatus::kNotFinite;
      }
      return NumberStatus::kNotNumber;
    }
  }
  double parsed = 0.0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const auto result = std::from_chars(first, last, parsed, std::chars_format::general);
  if (result.ec == std::errc::invalid_argument) return NumberStatus::kNotNumber;
  if (result.ptr != last) return NumberStatus::kNotNumber;
  if (result.ec == std::errc::result_out_of_range) return NumberStatus::kOutOfRange;
  if (!std::isfinite(parsed)) return NumberStatus::kOutOfRange;
  if (parsed != 0.0 && std::fabs(parsed) < std::numeric_limits<double>::min()) return NumberStatus::kSubnormal;
  value = parsed;
  return NumberStatus::kOk;
}

std::string quote(std::string_view text) {
  constexpr std::size_t kMaxShown = 60;
  std::string out = "'";
  const std::size_t shown = std::min(text.size(), kMaxShown);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    // Printable ASCII and UTF-8 bytes (so "µm" stays readable); control bytes escaped.
    if ((c >= 0x20 && c < 0x7f) || c >= 0x80) {
      out.push_back(static_cast<char>(c));
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (text.size() > kMaxShown) out += "...";
  out += "'";
  return out;
}


std::string number_string(double value) { return full_precision(value); }

}  // namespace coatcontact::detail
