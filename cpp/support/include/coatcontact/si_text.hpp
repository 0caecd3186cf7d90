// Numbers for people: a value in the SI prefix that suits it, and a value rounded to the
// digits its standard error supports. Used by the plot labels of `coatcontact fit --plot`
// (part of the CLI support library; not installed).
#pragma once
#include <string>

namespace coatcontact::cli {

// "1 MPa" for (1e6, "Pa"), "-695.7 µN" for (-6.95688e-4, "N"): four significant digits,
// the prefix f .. T that puts the magnitude in [1, 1000). An empty unit: no prefix.
std::string si_text(double value, const std::string& unit);

// "50.33 ± 0.27 mJ/m^2" for (0.0503276, 2.72258e-4, "J/m^2"): the error to two significant
// digits when they start with 1 or 2, else to one; the value to the same decimal place; one
// prefix for both, chosen by the larger of |value| and error. A zero or non-finite error
// gives si_text(value, unit).
std::string si_text_with_error(double value, double error, const std::string& unit);

}  // namespace coatcontact::cli
