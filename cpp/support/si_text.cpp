// SI-prefixed numbers for plot labels (coatcontact/si_text.hpp).
#include "coatcontact/si_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace coatcontact::cli {
namespace {

struct SiScale {
  double factor;       // multiply the value by this
  const char* prefix;  // "m", "µ", ...
};

SiScale si_scale(double magnitude, const std::string& unit) {
  if (unit.empty() || !(magnitude > 0.0) || !std::isfinite(magnitude)) return {1.0, ""};
  static const char* const kPrefixes[] = {"f", "p", "n", "µ", "m", "", "k", "M", "G", "T"};
  // The small offset keeps an exact power of 1000 out of the lower prefix despite log10 rounding.
  int exponent = 3 * static_cast<int>(std::floor(std::log10(magnitude) / 3.0 + 1e-9));
  exponent = std::min(12, std::max(-15, exponent));
  return {std::pow(10.0, -exponent), kPrefixes[(exponent + 15) / 3]};
}

std::string with_unit(const char* number, const SiScale& scale, const std::string& unit) {
  return std::string(number) + (unit.empty() ? "" : " " + std::string(scale.prefix) + unit);
}

}  // namespace

std::string si_text(double value, const std::string& unit) {
  // The prefix of the printed (4-digit) magnitude: 999.99995 prints as 1 k, not 1000.
  char rounded[64];
  std::snprintf(rounded, sizeof rounded, "%.4g", std::fabs(value));
  const SiScale scale = si_scale(std::strtod(rounded, nullptr), unit);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4g", value * scale.factor);
  return with_unit(buffer, scale, unit);
}

std::string si_text_with_error(double value, double error, const std::string& unit) {
  if (!(error > 0.0) || !std::isfinite(error) || !std::isfinite(value)) return si_text(value, unit);
  const SiScale scale = si_scale(std::max(std::fabs(value), error), unit);
  const double scaled_error = error * scale.factor;
  const int lead = static_cast<int>(std::floor(std::log10(scaled_error)));
  const int digits = scaled_error / std::pow(10.0, lead) < 3.0 ? 2 : 1;
  const int decimals = std::min(15, std::max(0, digits - 1 - lead));
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%.*f ± %.*f", decimals, value * scale.factor, decimals, scaled_error);
  return with_unit(buffer, scale, unit);
}

}  // namespace coatcontact::cli
