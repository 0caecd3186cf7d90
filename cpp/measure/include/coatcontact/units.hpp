// Physical units of the toolkit's inputs: the one table of spellings that the CLI's options,
// the data file reader (measure floor) and the bindings read.
#pragma once
#include <optional>
#include <string>

namespace coatcontact {

//   kPressure: Pa kPa MPa GPa     kLength: m cm mm um µm nm     kEnergy: J/m2 mJ/m2 N/m ..
//   kForce:    N mN uN µN nN
enum class Quantity { kPressure, kLength, kEnergy, kForce };

struct UnitInfo {
  Quantity kind;
  double to_si;  // SI value of one unit
};

// value * to_si, correctly rounded for the decimal prefixes: sub-units divide by the exact
// power of ten (50 um -> 5e-05, not 4.9999999999999996e-05).
double to_si(double value, double unit_to_si);
// The unit spelled exactly `unit` ("um", "MPa", ...), or nullopt if there is none.
std::optional<UnitInfo> find_unit(const std::string& unit);
// "pressure", "length", "energy per area", "force".
const char* quantity_name(Quantity kind);
// The allowed spellings of `kind`, e.g. "Pa kPa MPa GPa".
std::string unit_list(Quantity kind);

}  // namespace coatcontact
