// Measured force curves from data tables (measured_curve.hpp).
#include "coatcontact/measured_curve.hpp"

#include <cctype>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/units.hpp"
#include "number_text.hpp"

namespace coatcontact::measure {
namespace {

using detail::split;
using detail::trim;

bool is_comment_or_blank(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

// Decimal commas ("0,12<TAB>3,4" or "0,12;3,4") are refused with a hint before the reader
// splits them into wrong columns.
void refuse_decimal_commas(const std::string& text, const std::string& name) {
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (is_comment_or_blank(line)) continue;
    bool digit_comma_digit = false;
    for (std::size_t k = 1; k + 1 < line.size(); ++k) {
      if (line[k] == ',' && std::isdigit(static_cast<unsigned char>(line[k - 1])) &&
          std::isdigit(static_cast<unsigned char>(line[k + 1]))) {
        digit_comma_digit = true;
      }
    }
    if (digit_comma_digit && line.find_first_of("\t;") != std::string::npos) {
      throw InputError(name + ":" + std::to_string(number) + ": the numbers look like they use decimal commas ('" +
                       trim(line).substr(0, 40) + "'); write decimal points (e.g. sed 's/,/./g' on a tab-separated "
                       "file) and separate columns by tabs, blanks or commas");
    }
  }
}

const char* abscissa_name(Abscissa abscissa) {
  return abscissa == Abscissa::kRadius ? "a" : abscissa == Abscissa::kPenetration ? "delta" : "z";
}

// The 0-based column of each role: a 1-based position or a header name (with or without its unit).
std::array<int, kCurveRoles> column_indices(const DataTable& table, const CurveColumns& columns,
                                            const std::string& name, const char* const role_name[kCurveRoles]) {
  std::array<int, kCurveRoles> index{{-1, -1, -1, -1, -1}};
  const std::size_t count = table.columns.size();
  for (int role = 0; role < kCurveRoles; ++role) {
    const std::string& ref = columns.reference[role];
    if (ref.empty()) continue;
    char* end = nullptr;
    const long position = std::strtol(ref.c_str(), &end, 10);
    if (end != ref.c_str() && *end == '\0') {
      if (position < 1 || position > static_cast<long>(count)) {
        throw InputError("--columns: " + std::string(role_name[role]) + "=" + ref + " but " + name + " has " +
                         std::to_string(count) + " columns");
      }
      index[role] = static_cast<int>(position - 1);
      continue;
    }
    for (std::size_t c = 0; c < table.column_names.size(); ++c) {
      if (table.column_names[c] == ref || bare_column_name(table.column_names[c]) == ref) index[role] = static_cast<int>(c);
    }
    if (index[role] < 0) {
      std::string names;
      for (const auto& n : table.column_names) names += (names.empty() ? "'" : ", '") + n + "'";
      throw InputError("--columns: no column named '" + short_name(ref) + "' in " + name +
                       (names.empty() ? " (it has no header line)" : " (its columns: " + names + ")"));
    }
  }
  return index;
}

}  // namespace

CurveColumns parse_curve_columns(const std::string& text, const std::string& option) {
  CurveColumns c;
  c.text = text;
  const std::map<std::string, std::pair<Abscissa, bool>> two_column = {
      {"a,F", {Abscissa::kRadius, false}},      {"F,a", {Abscissa::kRadius, true}},
      {"delta,F", {Abscissa::kPenetration, false}}, {"F,delta", {Abscissa::kPenetration, true}},
      {"z,F", {Abscissa::kBaseDisplacement, false}},     {"F,z", {Abscissa::kBaseDisplacement, true}}};
  if (const auto it = two_column.find(text); it != two_column.end()) {
    c.abscissa = it->second.first;
    c.two_column = true;
    c.reference = {it->second.second ? "2" : "1", it->second.second ? "1" : "2", "", "", ""};
    return c;
  }
  bool has_a = false, has_delta = false, has_z = false;
  for (const std::string& raw : split(text, ',')) {
    const std::string item = trim(raw);
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == item.size()) {
      throw InputError(option + ": '" + short_name(item) + "' is not allowed (a,F, delta,F, F,a, F,delta, or "
                       "name=position|header name such as a=2,F=5,sigma_F=6)");
    }
    const std::string name = trim(item.substr(0, equals));
    const std::string value = trim(item.substr(equals + 1));
    int role;
    if (name == "a" || name == "delta" || name == "z") {
      role = kAbscissaColumn;
      (name == "a" ? has_a : name == "z" ? has_z : has_delta) = true;
    } else if (name == "F") {
      role = kForceColumn;
    } else if (name == "sigma_a" || name == "sigma_delta" || name == "sigma_z") {
      role = kAbscissaSigmaColumn;
    } else if (name == "sigma_F") {
      role = kForceSigmaColumn;
    } else if (name == "branch") {
      role = kBranchColumn;
    } else {
      throw InputError(option + ": '" + short_name(name) +
                       "' is not a column name (a, delta, z, F, sigma_a, sigma_delta, sigma_z, sigma_F, branch)");
    }
    if (!c.reference[role].empty()) throw InputError(option + ": '" + name + "' is given twice (or with its a/delta/z twin)");
    c.reference[role] = value;
  }
  if (int(has_a) + int(has_delta) + int(has_z) != 1) throw InputError(option + ": name exactly one of a=, delta= and z=");
  if (c.reference[kForceColumn].empty()) throw InputError(option + ": F= is missing");
  c.abscissa = has_a ? Abscissa::kRadius : has_z ? Abscissa::kBaseDisplacement : Abscissa::kPenetration;
  return c;
}

std::string unit_in_column_name(const std::string& raw) {
  const std::string name = trim(raw);
  // "a (um)", "F [mN]" ("^2" accepted: "w (mJ/m^2)").
  for (const auto& [open, close] : {std::pair<char, char>{'(', ')'}, std::pair<char, char>{'[', ']'}}) {
    const auto a = name.rfind(open);
    const auto b = name.rfind(close);
    if (a != std::string::npos && b != std::string::npos && b > a + 1 && b + 1 >= name.size()) {
      std::string unit = trim(name.substr(a + 1, b - a - 1));
      if (const auto caret = unit.find('^'); caret != std::string::npos) unit.erase(caret, 1);
      return unit;
    }
  }
  // "a/um", "F / mN": everything after the first '/' is the unit (read, or refused if unknown).
  if (const auto slash = name.find('/'); slash != std::string::npos && slash > 0 && slash + 1 < name.size()) {
    return trim(name.substr(slash + 1));
  }
  // "a_um", "F_mN", "a_m" (as coatcontact writes its tables): a known unit after the last '_'.
  if (const auto underscore = name.rfind('_'); underscore != std::string::npos && underscore > 0) {
    const std::string unit = name.substr(underscore + 1);
    if (find_unit(unit)) return unit;
  }
  return "";
}

std::string bare_column_name(const std::string& raw) {
  const std::string name = trim(raw);
  const auto paren = name.find_first_of("([");
  if (paren != std::string::npos) return trim(name.substr(0, paren));
  if (const auto slash = name.find('/'); slash != std::string::npos && slash > 0) return trim(name.substr(0, slash));
  if (const auto underscore = name.rfind('_'); underscore != std::string::npos && underscore > 0 &&
                                                 find_unit(name.substr(underscore + 1))) {
    return name.substr(0, underscore);
  }
  return name;
}

MeasuredCurve read_curve_text(const std::string& text, const std::string& name, const CurveColumns& columns) {
  refuse_decimal_commas(text.substr(0, 3) == "\xef\xbb\xbf" ? text.substr(3) : text, name);
  DataTable table = read_data_text(text, name, 0);
  const std::size_t count = table.columns.size();
  if (columns.two_column && count != 2) {
    throw InputError(name + ":" + std::to_string(table.line_numbers.front()) + ": " + std::to_string(count) +
                     " columns; --columns " + columns.text +
                     " reads two-column files, name the columns of others (e.g. --columns a=2,F=5)");
  }
  MeasuredCurve out;
  out.abscissa = columns.abscissa;
  out.file_columns = count;
  out.declared_columns = table.declared_columns;
  out.declared_line = table.declared_columns_line;
  out.has_units = !table.units.empty();
  const char* const role_name[kCurveRoles] = {columns.abscissa == Abscissa::kRadius ? "a" : "delta", "F",
                                              "sigma of the abscissa", "sigma_F", "branch"};
  const std::array<int, kCurveRoles> index = column_indices(table, columns, name, role_name);
  // Units: "# units:" (already applied by the reader) or from the column names.
  const Quantity role_kind[kCurveRoles] = {Quantity::kLength, Quantity::kForce, Quantity::kLength, Quantity::kForce,
                                           Quantity::kLength};
  std::string units;
  for (int role = 0; role < kCurveRoles; ++role) {
    if (index[role] < 0 || role == kBranchColumn) continue;  // the branch column is a pure number
    const std::size_t c = static_cast<std::size_t>(index[role]);
    std::string unit;
    std::string source;
    if (!table.units.empty()) {
      unit = table.units[c];
    } else if (c < table.column_names.size()) {
      unit = unit_in_column_name(table.column_names[c]);
      if (!unit.empty()) {
        const auto info = find_unit(unit);
        if (!info) {
          throw InputError(name + ": unknown unit '" + short_name(unit) + "' in the column name '" +
                           short_name(table.column_names[c]) + "' (allowed: " + unit_list(role_kind[role]) + ")");
        }
        for (double& v : table.columns[c]) v = to_si(v, info->to_si);
        out.has_units = true;
        source = " (column name '" + table.column_names[c] + "')";
      }
    }
    if (!unit.empty()) {
      const auto info = find_unit(unit);
      if (!info || info->kind != role_kind[role]) {
        throw InputError(name + ": column " + std::to_string(c + 1) + " (" + role_name[role] + ") has the unit '" +
                         unit + "', not a " + quantity_name(role_kind[role]) + " (allowed: " +
                         unit_list(role_kind[role]) + ")");
      }
    }
    const std::string role_label = role == kAbscissaColumn     ? abscissa_name(columns.abscissa)
                                   : role == kForceColumn      ? "F"
                                   : role == kAbscissaSigmaColumn ? std::string("sigma_") + abscissa_name(columns.abscissa)
                                                               : "sigma_F";
    units += (units.empty() ? "" : ", ") + role_label + " " +
             (unit.empty() ? std::string(role_kind[role] == Quantity::kLength ? "m" : "N") + " (SI: no unit given)"
                           : unit + source);
  }
  if (!out.has_units) {
    out.units = "none declared: read as SI (m, N)";
  } else {
    out.units = units + (table.units.empty() ? "" : " (from the '# units:' line)");
  }
  out.x = table.columns[static_cast<std::size_t>(index[kAbscissaColumn])];
  out.force = table.columns[static_cast<std::size_t>(index[kForceColumn])];
  out.line_numbers = table.line_numbers;
  if (index[kAbscissaSigmaColumn] >= 0) out.sigma_x = table.columns[static_cast<std::size_t>(index[kAbscissaSigmaColumn])];
  if (index[kForceSigmaColumn] >= 0) out.sigma_force = table.columns[static_cast<std::size_t>(index[kForceSigmaColumn])];
  if (index[kBranchColumn] >= 0) out.branch = table.columns[static_cast<std::size_t>(index[kBranchColumn])];
  return out;
}

}  // namespace coatcontact::measure
