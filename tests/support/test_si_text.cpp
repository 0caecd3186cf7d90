// Unit tests of si_text and si_text_with_error (coatcontact/si_text.hpp): the labels of
// `coatcontact fit --plot` (issue 28: "E0 prints as 0.001 GPa", "w prints with six digits
// behind an error of three").
#include <cmath>
#include <string>

#include "check.hpp"
#include "coatcontact/si_text.hpp"

using coatcontact::cli::si_text;
using coatcontact::cli::si_text_with_error;

namespace {
void same(const std::string& got, const std::string& expected) {
  check::that(got == expected, ("'" + got + "' == '" + expected + "'").c_str());
}
}  // namespace

int main() {
  // A prefix per quantity, the magnitude in [1, 1000).
  same(si_text(1e6, "Pa"), "1 MPa");
  same(si_text(70e9, "Pa"), "70 GPa");
  same(si_text(2e-3, "m"), "2 mm");
  same(si_text(20e-9, "m"), "20 nm");
  same(si_text(-6.95688e-4, "N"), "-695.7 µN");
  same(si_text(1.99794e-5, "m"), "19.98 µm");
  same(si_text(999.99995, "N"), "1 kN");   // rounds up into the next prefix, not "1000 N"
  same(si_text(1000.0, "N"), "1 kN");
  same(si_text(0.0, "N"), "0 N");
  same(si_text(1.15493, ""), "1.155");     // dimensionless: no prefix
  same(si_text(1e-20, "m"), "1e-05 fm");   // beyond the table: the last prefix, still readable

  // Rounded to the error: two digits when the error starts with 1 or 2, else one.
  same(si_text_with_error(0.0503276, 2.72258e-4, "J/m^2"), "50.33 ± 0.27 mJ/m^2");
  same(si_text_with_error(1.99794e-5, 1.94242e-8, "m"), "19.979 ± 0.019 µm");
  same(si_text_with_error(3.99519e-2, 4.6e-5, "J/m^2"), "39.95 ± 0.05 mJ/m^2");
  same(si_text_with_error(1.2345e6, 3.4e4, "Pa"), "1.23 ± 0.03 MPa");
  same(si_text_with_error(523.0, 140.0, "N/m"), "523 ± 140 N/m");
  same(si_text_with_error(0.7, 0.05, ""), "0.70 ± 0.05");
  // The prefix follows the larger of value and error, so both stay in one unit.
  same(si_text_with_error(2e-4, 3e-3, "m"), "0 ± 3 mm");
  // No usable error: the plain value.
  same(si_text_with_error(0.05, 0.0, "J/m^2"), "50 mJ/m^2");
  same(si_text_with_error(0.05, std::nan(""), "J/m^2"), "50 mJ/m^2");
  return check::exit_code();
}
