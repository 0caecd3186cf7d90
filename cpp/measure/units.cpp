// The unit table (units.hpp): one spelling list for the CLI's options, the data file reader and
// the bindings.
#include "coatcontact/units.hpp"

#include <cmath>

namespace coatcontact {
namespace {

struct UnitRow {
  const char* spelling;
  Quantity kind;
  double to_si;
};

// Case-sensitive SI spellings; µ is accepted as U+00B5 (micro sign) and U+03BC (Greek mu).
constexpr UnitRow kUnits[] = {
    {"Pa", Quantity::kPressure, 1.0},       {"kPa", Quantity::kPressure, 1e3},
    {"MPa", Quantity::kPressure, 1e6},      {"GPa", Quantity::kPressure, 1e9},
    {"m", Quantity::kLength, 1.0},          {"cm", Quantity::kLength, 1e-2},
    {"mm", Quantity::kLength, 1e-3},
    {"um", Quantity::kLength, 1e-6},        {"\xc2\xb5m", Quantity::kLength, 1e-6},
    {"\xce\xbcm", Quantity::kLength, 1e-6}, {"nm", Quantity::kLength, 1e-9},
    {"J/m2", Quantity::kEnergy, 1.0},       {"mJ/m2", Quantity::kEnergy, 1e-3},
    {"J/m^2", Quantity::kEnergy, 1.0},      {"mJ/m^2", Quantity::kEnergy, 1e-3},
    {"J/m\xc2\xb2", Quantity::kEnergy, 1.0}, {"mJ/m\xc2\xb2", Quantity::kEnergy, 1e-3},
    {"N/m", Quantity::kEnergy, 1.0},        {"mN/m", Quantity::kEnergy, 1e-3},
    {"N", Quantity::kForce, 1.0},           {"mN", Quantity::kForce, 1e-3},
    {"uN", Quantity::kForce, 1e-6},         {"\xc2\xb5N", Quantity::kForce, 1e-6},
    {"\xce\xbcN", Quantity::kForce, 1e-6},  {"nN", Quantity::kForce, 1e-9},
};

}  // namespace

double to_si(double value, double unit_to_si) {
  // 1e-3, 1e-6, 1e-9 are not exact doubles, but their inverses round to exact integers.
  return unit_to_si < 1.0 ? value / std::round(1.0 / unit_to_si) : value * unit_to_si;
}

const char* quantity_name(Quantity kind) {
  switch (kind) {
    case Quantity::kPressure: return "pressure";
    case Quantity::kLength: return "length";
    case Quantity::kEnergy: return "energy per area";
    case Quantity::kForce: return "force";
  }
  return "quantity";
}

std::string unit_list(Quantity kind) {
  switch (kind) {
    case Quantity::kPressure: return "Pa kPa MPa GPa";
    case Quantity::kLength: return "m cm mm um \xc2\xb5m nm";
    case Quantity::kEnergy: return "J/m2 mJ/m2 J/m^2 mJ/m^2 J/m\xc2\xb2 mJ/m\xc2\xb2 N/m mN/m";
    case Quantity::kForce: return "N mN uN \xc2\xb5N nN";
  }
  return "";
}

std::optional<UnitInfo> find_unit(const std::string& unit) {
  for (const auto& row : kUnits) {
    if (unit == row.spelling) return UnitInfo{row.kind, row.to_si};
  }
  return std::nullopt;
}

}  // namespace coatcontact
