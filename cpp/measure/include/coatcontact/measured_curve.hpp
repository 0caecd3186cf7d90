// A measured force curve read from a data table (measure floor): which columns hold the
// abscissa (contact radius a, penetration delta or base displacement z = delta + F/k), the
// force F, their uncertainties and the branch, and in which units. The fit, the CLI, the C API
// and the bindings read curves through this one reader.
#pragma once
#include <array>
#include <string>
#include <vector>

namespace coatcontact::measure {

enum class Abscissa { kRadius, kPenetration, kBaseDisplacement };  // a, delta, z = delta + F/k

// Roles of the data columns: the abscissa, F, the sigma of the abscissa, sigma_F, the branch
// (1 loading, 0 unloading).
enum CurveRole : int { kAbscissaColumn = 0, kForceColumn, kAbscissaSigmaColumn, kForceSigmaColumn, kBranchColumn };
constexpr int kCurveRoles = 5;

struct CurveColumns {
  Abscissa abscissa = Abscissa::kRadius;
  bool two_column = false;  // "a,F" style: a two-column file
  std::array<std::string, kCurveRoles> reference{};  // "2" (1-based position) or a header name; "" unused
  std::string text;  // as given
};

// "a,F" | "delta,F" | "z,F" (or reversed: "F,a" ...) for a two-column file, or
// "name=position|header-name,..." with the names a|delta|z, F, sigma_a|sigma_delta|sigma_z,
// sigma_F, branch. InputError naming `option` otherwise.
CurveColumns parse_curve_columns(const std::string& text, const std::string& option = "--columns");

struct MeasuredCurve {
  Abscissa abscissa = Abscissa::kRadius;
  std::vector<double> x, force;         // SI: m, N
  std::vector<double> sigma_x, sigma_force;  // from columns (empty if none)
  std::vector<double> branch;           // the branch column (empty if none)
  std::vector<int> line_numbers;        // 1-based source line of each row
  std::size_t file_columns = 0;
  bool has_units = false;               // "# units:" or units in the column names
  // The units as read, for the output's header: "a um, F mN (from the '# units:' line)", "a um (column
  // name 'a (um)'), F N (SI: no unit given)", or "none declared: read as SI (m, N)".
  std::string units;
  std::vector<std::string> declared_columns;  // a "# columns:" comment of the file
  int declared_line = 0;
};

// A column name's unit: "a (um)", "F [mN]", "a/um", "a_um" (a known unit after the last '_').
// The unit text (may be unknown: the caller refuses it), or "" when the name carries none.
std::string unit_in_column_name(const std::string& name);
// The name without its unit: "a (um)" -> "a", "a/um" -> "a", "a_um" -> "a".
std::string bare_column_name(const std::string& name);

// The curve of `text` (the contents of `name`, for messages). Decimal commas are refused with a
// hint; units are read from a "# units:" line or the column names (InputError naming the line
// or column when a unit is unknown or of the wrong kind).
MeasuredCurve read_curve_text(const std::string& text, const std::string& name, const CurveColumns& columns);

}  // namespace coatcontact::measure
