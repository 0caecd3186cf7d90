// coatcontact fit: least-squares fit of measured a,F or delta,F data to the coated-substrate
// JKR model (THEORY.md section 5; the model, branch choice and error policy are in fit.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/si_text.hpp"
#include "checks.hpp"
#include "commands.hpp"
#include "fit_plot_script.hpp"

namespace coatcontact::cli {
namespace {

const std::vector<OptionSpec>& fit_options() {
  static const std::vector<OptionSpec> spec = {
      {"--columns", "a,F|delta,F|a=N,F=N,..", "the data columns: a,F / delta,F / z,F (F,a, F,delta, F,z reversed) for a two-column file, or name=position|header-name for any file (names a|delta|z, F, sigma_a|sigma_delta|sigma_z, sigma_F, branch: 1 loading, 0 unloading). z is the base (piezo) displacement z = delta + F/k through the spring k of --spring (k may be free: --free w,k)", true},
      {"--radius", "R", "sphere radius (length, e.g. 5mm); or --shape"},
      {"--shape", "SPEC", "any axisymmetric indenter instead of the sphere, as in 'contact --shape': sphere:R, cone:BETA (half included angle, e.g. 70deg), punch:A, power:N,R, blunted-cone:R,BETA, profile:FILE (columns r z). The shape's own parameters are fixed; w, t/h_i, E_i are fitted as for the sphere (no --curve, --plot)"},
      {"--film", "E1,nu1", "film Young's modulus and Poisson ratio (E1 is the start value if fitted); or --layer", false},
      layer_option(true),
      substrate_option(),
      {"--free", "w[,t][,E1]|w,h1..hN,E1..EN", "parameters to fit (default w); the others are fixed. With --layer: h1..hN and E1..EN name the layers' thicknesses and moduli, top first (one layer: t = h1). w_load,w_unload in place of w: each branch its own adhesion energy (rows from the branch column, else loading up to the largest a or delta)"},
      {"--start", "w=..,t=..,E1=..", "start values of free parameters (with units; h2=.., E2=.. with --layer)"},
      {"--thickness", "t", "film thickness with --film (required when t is fixed; start value when free); not with --layer"},
      {"--work", "w", "adhesion energy (required when w is fixed; start value when free)"},
      {"--branch", "load|unload|both", "fit only the loading or unloading rows (default both)"},
      {"--output", "FILE", "write the fitted data table here (default stdout)"},
      {"--curve", "FILE", "also write the fitted model curve (a, delta, F; 200 points) here"},
      {"--sigma", "a=..,F=..", "uncertainty per column: absolute with units (F=10uN) or relative (a=0.3%); delta= for delta,F data"},
      {"--bootstrap", "N", "N residual-bootstrap refits: percentile intervals (68 %, 95 %)"},
      {"--seed", "N", "seed of the bootstrap resampling (default 1)"},
      {"--plot", "FILE", "draw data, fit, residuals and pull-off with gnuplot (PNG or PDF by extension)"},
      indenter_option(),
      {"--model", "jkr|md", "adhesion model: jkr (default) or md, the Maugis-Dugdale zone (a,F data of a rigid sphere; --free w,lambda; slow: one solve per point and trial, keep to a few tens of points)"},
      {"--lambda", "L", "Maugis's lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3, in [1e-3, 1e3] with --model md: fixed, or the start of the search when --free names lambda (default 1)"},
      {"--spring", "k", "machine or cantilever stiffness in N/m (e.g. 500N/m, 0.5mN/um): report its pull-off. With --columns z,F the spring the data were taken through: fixed, or the start of the search when --free names k"},
  };
  return spec;
}

std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string short_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// "below 1e-08" for 3.4e-9: the interpolation check is a rounding-level diagnostic whose
// digits move with the compiler; its decade is what the reader needs.
std::string order_of_magnitude_bound(double value) {
  if (!(value > 0.0) || !std::isfinite(value)) return short_number(value);
  return "below 1e" + std::to_string(static_cast<int>(std::ceil(std::log10(value))));
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream stream(text);
  while (std::getline(stream, item, separator)) items.push_back(item);
  if (!text.empty() && text.back() == separator) items.emplace_back();
  return items;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The index of a parameter named on the command line: w, t, E1 (one film); with --layer also
// h1..hN and E1..EN (t is h1 of a single layer, refused for several).
int parameter_index(const std::string& name, const std::string& option, std::size_t layers, bool stack,
                    bool hysteresis, bool spring, bool md) {
  const std::vector<fit::ParameterInfo> list = fit::parameter_list(layers, hysteresis, spring, md);
  std::string allowed;
  for (const auto& info : list) allowed += (allowed.empty() ? "" : ", ") + info.name;
  if (layers == 1 && stack) allowed += " (h1 = t)";
  if (hysteresis && name == "w") {
    throw InputError(option + ": 'w' is not a parameter when the branches have their own adhesion energies "
                     "(allowed: " + allowed + ")");
  }
  if (!hysteresis && (name == "w_load" || name == "w_unload")) {
    throw InputError(option + ": '" + name + "' needs both branch energies free (--free w_load,w_unload,...)");
  }
  if (name == "lambda" && !md) {
    throw InputError(option + ": 'lambda' is a parameter of the Maugis-Dugdale model only (--model md) (allowed: " +
                     allowed + ")");
  }
  if (name == "k" && !spring) {
    throw InputError(option + ": 'k' (the spring stiffness) is a parameter only of base-displacement data "
                     "(--columns z,F, z = delta + F/k); with a,F or delta,F data k does not enter the curve (allowed: " +
                     allowed + ")");
  }
  if (name == "t" && layers > 1) {
    throw InputError(option + ": 't' is the thickness of a single film; with " + std::to_string(layers) +
                     " layers name the thicknesses h1..h" + std::to_string(layers) + " (allowed: " + allowed + ")");
  }
  const std::string key = layers == 1 && name == "h1" && stack ? "t" : name;
  for (std::size_t which = 0; which < list.size(); ++which) {
    if (list[which].name == key) return static_cast<int>(which);
  }
  throw InputError(option + ": '" + name + "' is not a parameter" +
                   (stack ? " of this " + std::to_string(layers) + "-layer stack" : std::string()) + " (allowed: " +
                   allowed + ")");
}

// Maugis's lambda: a number in [kLambdaRange] (InputError naming `option`).
double parse_lambda(const std::string& text, const std::string& option) {
  char* end = nullptr;
  const double lambda = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(lambda >= fit::kLambdaRange[0] && lambda <= fit::kLambdaRange[1])) {
    throw InputError(option + ": '" + text + "' is not allowed (need a number 1e-3 <= lambda <= 1e3; lambda = 2 sigma0 "
                     "(R/(pi w K^2))^(1/3), K = 4E1*/3)");
  }
  return lambda;
}

Quantity parameter_kind(const fit::ParameterInfo& info) {
  return info.kind == fit::ParameterKind::kWork        ? Quantity::kEnergy
         : info.kind == fit::ParameterKind::kThickness ? Quantity::kLength
                                                       : Quantity::kPressure;
}

// The unit as spelled in header keys ("w_stderr_J_per_m2").
const char* key_unit(const fit::ParameterInfo& info) {
  return info.kind == fit::ParameterKind::kWork     ? "J_per_m2"
         : info.kind == fit::ParameterKind::kSpring ? "N_per_m"
         : info.kind == fit::ParameterKind::kLambda ? "1"
                                                    : info.unit;
}


// ---- columns and data ----------------------------------------------------------------------

// Roles of the data columns: 0 abscissa (a or delta), 1 F, 2 sigma of the abscissa, 3 sigma_F,
// 4 branch (1 loading, 0 unloading).
constexpr int kRoles = 5;
struct ColumnChoice {
  fit::DataKind kind = fit::DataKind::kRadiusForce;
  bool legacy = false;                          // "a,F" style: a two-column file
  bool base = false;                            // z,F: base displacement z = delta + F/k
  std::array<std::string, kRoles> reference{};  // "2" (1-based position) or a header name; "" unused
};

ColumnChoice parse_columns(const std::string& text) {
  ColumnChoice c;
  const std::map<std::string, std::pair<fit::DataKind, bool>> legacy = {
      {"a,F", {fit::DataKind::kRadiusForce, false}},      {"F,a", {fit::DataKind::kRadiusForce, true}},
      {"delta,F", {fit::DataKind::kPenetrationForce, false}}, {"F,delta", {fit::DataKind::kPenetrationForce, true}},
      {"z,F", {fit::DataKind::kPenetrationForce, false}},     {"F,z", {fit::DataKind::kPenetrationForce, true}}};
  if (const auto it = legacy.find(text); it != legacy.end()) {
    c.kind = it->second.first;
    c.legacy = true;
    c.base = text.find('z') != std::string::npos;
    c.reference = {it->second.second ? "2" : "1", it->second.second ? "1" : "2", "", "", ""};
    return c;
  }
  bool has_a = false, has_delta = false, has_z = false;
  for (const std::string& raw : split(text, ',')) {
    const std::string item = trim(raw);
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == item.size()) {
      throw InputError("--columns: '" + item + "' is not allowed (a,F, delta,F, F,a, F,delta, or name=position|header "
                       "name such as a=2,F=5,sigma_F=6)");
    }
    const std::string name = trim(item.substr(0, equals));
    const std::string value = trim(item.substr(equals + 1));
    int role;
    if (name == "a" || name == "delta" || name == "z") {
      role = 0;
      (name == "a" ? has_a : name == "z" ? has_z : has_delta) = true;
    } else if (name == "F") {
      role = 1;
    } else if (name == "sigma_a" || name == "sigma_delta" || name == "sigma_z") {
      role = 2;
    } else if (name == "sigma_F") {
      role = 3;
    } else if (name == "branch") {
      role = 4;
    } else {
      throw InputError("--columns: '" + name + "' is not a column name (a, delta, z, F, sigma_a, sigma_delta, sigma_z, sigma_F, branch)");
    }
    if (!c.reference[role].empty()) throw InputError("--columns: '" + name + "' is given twice (or with its a/delta/z twin)");
    c.reference[role] = value;
  }
  if (int(has_a) + int(has_delta) + int(has_z) != 1) throw InputError("--columns: name exactly one of a=, delta= and z=");
  if (c.reference[1].empty()) throw InputError("--columns: F= is missing");
  c.kind = has_a ? fit::DataKind::kRadiusForce : fit::DataKind::kPenetrationForce;
  c.base = has_z;
  return c;
}

bool is_comment_or_blank(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

// A unit in a header name: "a (um)", "F [mN]", "w/(mJ/m^2)" is not needed; "^2" is accepted.
std::optional<std::string> unit_in_name(const std::string& name) {
  for (const auto& [open, close] : {std::pair<char, char>{'(', ')'}, std::pair<char, char>{'[', ']'}}) {
    const auto a = name.rfind(open);
    const auto b = name.rfind(close);
    if (a != std::string::npos && b != std::string::npos && b > a + 1 && b + 1 >= trim(name).size()) {
      std::string unit = trim(name.substr(a + 1, b - a - 1));
      if (const auto caret = unit.find('^'); caret != std::string::npos) unit.erase(caret, 1);
      return unit;
    }
  }
  return std::nullopt;
}

std::string bare_name(const std::string& name) {
  const auto paren = name.find_first_of("([");
  return trim(paren == std::string::npos ? name : name.substr(0, paren));
}

struct LoadedData {
  fit::Measurements data;
  std::vector<double> sigma_x, sigma_f;  // from columns (empty if none)
  std::vector<double> branch;            // the branch column (empty if none)
  bool has_units = false;                // "# units:" or units in the column names
  std::vector<std::string> declared_columns;
  int declared_line = 0;
};

LoadedData load_data(const std::string& path, const ColumnChoice& choice, fit::DataKind kind) {
  std::string text;
  if (path == "-") {
    std::ostringstream buffer;
    buffer << std::cin.rdbuf();
    text = buffer.str();
  } else {
    // The checks and messages of read_data_file (the text is needed here first).
    struct stat info {};
    if (stat(path.c_str(), &info) != 0) throw InputError(path + ": cannot read data file: " + std::strerror(errno));
    if (!S_ISREG(info.st_mode)) throw InputError(path + ": not a regular file");
    if (static_cast<unsigned long long>(info.st_size) > kMaxDataFileBytes) {
      throw InputError(path + ": larger than " + std::to_string(kMaxDataFileBytes / (1024 * 1024)) +
                       " MB; refusing to read it");
    }
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError(path + ": cannot open data file: " + std::strerror(errno));
    register_input(path, "data file");
    std::ostringstream buffer;
    buffer << file.rdbuf();
    text = buffer.str();
  }
  if (text.size() > kMaxDataFileBytes) {
    throw InputError(std::string(path == "-" ? "stdin" : path) + ": larger than " +
                     std::to_string(kMaxDataFileBytes / (1024 * 1024)) + " MB; refusing to read it");
  }
  const std::string name = path == "-" ? std::string("stdin") : path;
  // Decimal commas ("0,12<TAB>3,4" or "0,12;3,4"): refused with a hint before the reader
  // splits them into wrong columns.
  std::size_t count = 0;
  {
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
      if (count == 0) count = line.find(',') != std::string::npos ? split(line, ',').size() : [&] {
          std::istringstream fields(line);
          std::string f;
          std::size_t k = 0;
          while (fields >> f) ++k;
          return k;
        }();
    }
  }
  if (count == 0) throw InputError(name + ": no data rows");
  if (choice.legacy && count != 2) {
    throw InputError(name + ": " + std::to_string(count) + " columns; --columns " +
                     std::string(kind == fit::DataKind::kRadiusForce ? "a,F" : "delta,F") +
                     " reads two-column files, name the columns of others (e.g. --columns a=2,F=5)");
  }
  DataTable table = read_data_text(text, name, count);
  LoadedData out;
  out.declared_columns = table.declared_columns;
  out.declared_line = table.declared_columns_line;
  out.has_units = !table.units.empty();
  // Each role's column: a 1-based position or a header name (with or without its unit).
  std::array<int, kRoles> index{{-1, -1, -1, -1, -1}};
  const char* role_option[kRoles] = {kind == fit::DataKind::kRadiusForce ? "a" : "delta", "F", "sigma of the abscissa", "sigma_F", "branch"};
  for (int role = 0; role < kRoles; ++role) {
    const std::string& ref = choice.reference[role];
    if (ref.empty()) continue;
    char* end = nullptr;
    const long position = std::strtol(ref.c_str(), &end, 10);
    if (end != ref.c_str() && *end == '\0') {
      if (position < 1 || position > static_cast<long>(count)) {
        throw InputError("--columns: " + std::string(role_option[role]) + "=" + ref + " but " + name + " has " +
                         std::to_string(count) + " columns");
      }
      index[role] = static_cast<int>(position - 1);
    } else {
      for (std::size_t c = 0; c < table.column_names.size(); ++c) {
        if (table.column_names[c] == ref || bare_name(table.column_names[c]) == ref) index[role] = static_cast<int>(c);
      }
      if (index[role] < 0) {
        std::string names;
        for (const auto& n : table.column_names) names += (names.empty() ? "'" : ", '") + n + "'";
        throw InputError("--columns: no column named '" + ref + "' in " + name +
                         (names.empty() ? " (it has no header line)" : " (its columns: " + names + ")"));
      }
    }
  }
  // Units: "# units:" (already applied by the reader) or from the column names.
  const Quantity role_kind[kRoles] = {Quantity::kLength, Quantity::kForce, Quantity::kLength, Quantity::kForce};
  for (int role = 0; role < kRoles; ++role) {
    if (index[role] < 0 || role == 4) continue;  // the branch column is a pure number
    const std::size_t c = static_cast<std::size_t>(index[role]);
    std::optional<std::string> unit;
    if (!table.units.empty()) {
      unit = table.units[c];
    } else if (c < table.column_names.size()) {
      unit = unit_in_name(table.column_names[c]);
      if (unit) {
        const auto info = find_unit(*unit);
        if (!info) throw InputError(name + ": unknown unit '" + *unit + "' in the column name '" + table.column_names[c] + "'");
        for (double& v : table.columns[c]) v = to_si(v, info->to_si);
        out.has_units = true;
      }
    }
    if (unit) {
      const auto info = find_unit(*unit);
      if (!info || info->kind != role_kind[role]) {
        throw InputError(name + ": column " + std::to_string(c + 1) + " (" + role_option[role] + ") has the unit '" +
                         *unit + "', not a " + quantity_name(role_kind[role]) + " (allowed: " +
                         unit_list(role_kind[role]) + ")");
      }
    }
  }
  out.data.kind = kind;
  out.data.abscissa = table.columns[static_cast<std::size_t>(index[0])];
  out.data.force = table.columns[static_cast<std::size_t>(index[1])];
  out.data.line_numbers = table.line_numbers;
  if (index[2] >= 0) out.data.sigma_abscissa = table.columns[static_cast<std::size_t>(index[2])];
  if (index[3] >= 0) out.data.sigma_force = table.columns[static_cast<std::size_t>(index[3])];
  if (index[4] >= 0) out.branch = table.columns[static_cast<std::size_t>(index[4])];
  return out;
}

// --spring k: "500", "500N/m" or a force per length ("0.5mN/um").
double parse_stiffness(const std::string& text) {
  const auto slash = text.rfind('/');
  double k;
  if (slash == std::string::npos) {
    char* end = nullptr;
    k = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0') throw InputError("--spring: '" + text + "' is not a stiffness (e.g. 500N/m)");
  } else {
    const double force = parse_quantity(text.substr(0, slash), Quantity::kForce, "--spring");
    const std::string length = text.substr(slash + 1);
    k = force / parse_quantity(length.empty() || !std::isdigit(static_cast<unsigned char>(length[0])) ? "1" + length : length,
                               Quantity::kLength, "--spring");
  }
  if (!(k > 0.0) || !std::isfinite(k)) throw InputError("--spring: the stiffness must be > 0 (got '" + text + "')");
  return k;
}

// --sigma a=0.3%,F=10uN: per-column uncertainties, relative (%) or absolute (with units).
void apply_sigma_option(const std::optional<std::string>& text, fit::Measurements& data, const ColumnChoice& choice) {
  if (!text) return;
  const bool radius_data = data.kind == fit::DataKind::kRadiusForce;
  for (const std::string& raw : split(*text, ',')) {
    const std::string item = trim(raw);
    const auto equals = item.find('=');
    if (equals == std::string::npos) {
      throw InputError("--sigma: '" + item + "' is not name=value (e.g. --sigma a=0.3%,F=10uN)");
    }
    const std::string name = trim(item.substr(0, equals));
    const std::string value = trim(item.substr(equals + 1));
    const std::string x = radius_data ? "a" : choice.base ? "z" : "delta";
    const bool abscissa = name == x;
    if (!abscissa && name != "F") {
      throw InputError("--sigma: '" + name + "' is not a column of these data (allowed: " + x + ", F)");
    }
    std::vector<double>& sigma = abscissa ? data.sigma_abscissa : data.sigma_force;
    if (!choice.reference[abscissa ? 2 : 3].empty()) {
      throw InputError("--sigma: " + name + " already has an uncertainty column (--columns)");
    }
    if (!sigma.empty()) throw InputError("--sigma: " + name + " is given twice");
    const std::vector<double>& values = abscissa ? data.abscissa : data.force;
    if (!value.empty() && value.back() == '%') {
      char* end = nullptr;
      const std::string number_text = value.substr(0, value.size() - 1);
      const double percent = std::strtod(number_text.c_str(), &end);
      if (end == number_text.c_str() || *end != '\0' || !(percent > 0.0) || !(percent < 100.0)) {
        throw InputError("--sigma " + name + ": '" + value + "' is not a percentage in (0, 100)");
      }
      for (double v : values) sigma.push_back(0.01 * percent * std::fabs(v));
    } else {
      const double absolute = parse_quantity(value, abscissa ? Quantity::kLength : Quantity::kForce, "--sigma " + name);
      if (!(absolute > 0.0)) throw InputError("--sigma " + name + ": must be > 0 (got '" + value + "')");
      sigma.assign(values.size(), absolute);
    }
  }
}

// Characters gnuplot's single-quoted strings and enhanced text take literally enough.
std::string gnuplot_string(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "''";
    } else if (c == '_' || c == '@' || c == '&' || c == '~' || c == '{' || c == '}') {
      out += '\\';  // escaped: enhanced text would read them as markup (^ is kept for the units)
      out += c;
    } else if (static_cast<unsigned char>(c) >= 32 || (c & 0x80)) {
      out += c;
    }
  }
  return out + "'";
}

// Runs gnuplot on the embedded script (gnuplot/fit_plot.gp) with the tables in a private
// temporary folder; returns the picture (gnuplot writes it to stdout; the caller writes the
// file atomically). InputError when gnuplot is missing or fails.
std::string render_fit_plot(const std::string& table, const std::string& curve, const std::string& x_name,
                            const std::string& title, const std::string& fit_label, const std::string& term,
                            double lp_x, double lp_f, double dp_x, double dp_f, double spring_k) {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/coatcontact-plot.XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) throw InputError("--plot: cannot create a temporary folder for gnuplot");
  const std::string dir(buffer.data());
  struct Cleanup {
    std::string dir;
    ~Cleanup() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } cleanup{dir};
  const auto save = [&](const std::string& name, const std::string& text) {
    std::ofstream file(dir + "/" + name, std::ios::binary);
    file << text;
    if (!file) throw InputError("--plot: cannot write the temporary file " + dir + "/" + name);
  };
  save("fit.tsv", table);
  save("curve.tsv", curve);
  save("fit_plot.gp", kFitPlotScript);
  const auto value = [](double v) { return std::isfinite(v) ? number(v) : std::string("NaN"); };
  const std::string settings = "fitfile=" + gnuplot_string(dir + "/fit.tsv") + "; curvefile=" +
                               gnuplot_string(dir + "/curve.tsv") + "; xname='" + x_name + "'; term='" + term +
                               "'; plottitle=" + gnuplot_string(title) + "; fitlabel=" + gnuplot_string(fit_label) +
                               "; lp_x=" + value(lp_x) + "; lp_F=" + value(lp_f) + "; dp_x=" + value(dp_x) +
                               "; dp_F=" + value(dp_f) + "; spring_k=" + value(spring_k);
  save("settings.gp", settings + "\n");
  const std::string command = "gnuplot '" + dir + "/settings.gp' '" + dir + "/fit_plot.gp' 2>'" + dir + "/err'";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw InputError("--plot: cannot run gnuplot");
  std::string picture;
  char chunk[65536];
  std::size_t got;
  while ((got = std::fread(chunk, 1, sizeof chunk, pipe)) > 0) picture.append(chunk, got);
  const int status = pclose(pipe);
  if (status != 0 || picture.empty()) {
    std::ifstream err(dir + "/err");
    std::string first;
    std::getline(err, first);
    throw InputError("--plot: gnuplot failed" + (first.empty() ? std::string(" (is gnuplot with the cairo terminals installed?)")
                                                               : ": " + first));
  }
  return picture;
}

int run_fit_body(const Args& args) {
  const auto& spec = fit_options();
  Arguments arguments(args, spec, 1);
  if (arguments.help()) {
    std::cout << usage(
        "fit",
        "DATA --columns a,F|delta,F|z,F (--radius R | --shape SPEC) (--film E1,nu1 | --layer h,E,nu[,slip] ...) --substrate E0,nu0|rigid "
        "[--free w[,t][,E1] | --free w,h1..hN,E1..EN] [--start w=..,t=..,E1=..] [--thickness t] [--work w] "
        "[--branch load|unload|both] [--sigma a=..,F=..] [--bootstrap N [--seed N]] [--indenter E2,nu2] "
        "[--output FILE] [--curve FILE] [--plot FILE.png|FILE.pdf]",
        "Fits the adhesion energy w (and optionally the film thickness t and modulus E1) to measured\n"
        "contact radius-force (a,F) or penetration-force (delta,F) data of a sphere on a coated\n"
        "substrate, by nonlinear least squares (GSL trust region in log-parameters) on the exact model\n"
        "of THEORY.md section 5. The coating may be a stack of layers (--layer h,E,nu[,slip], top\n"
        "first, h a length, THEORY.md section 12): then any of w, h1..hN, E1..EN may be free, the others\n"
        "keep their given values. --free w_load,w_unload gives the loading and the unloading rows their\n"
        "own adhesion energy (JKR hysteresis; pull-offs with w_unload). No start values are needed: a\n"
        "coarse global search over the physical ranges picks the start (--start only adds a hint).\n"
        "Residuals are in force; with --sigma (or sigma columns) each is weighted by the effective\n"
        "variance sigma_F^2 + (dF/da)^2 sigma_a^2 and chi2/(n-p) is reported; without, the noise is\n"
        "estimated from the scatter and the errors assume an exact a (or delta). For delta,F data the\n"
        "model is taken on the stable branch under displacement control. DATA: TSV/CSV or '-'\n"
        "(stdin), '#' comments, units from a '# units: um mN' line or column names like 'a (um)'; SI\n"
        "otherwise. F is compressive positive.\n"
        "--shape SPEC replaces the sphere by any indenter of 'contact --shape' (cone, flat punch, power\n"
        "law, blunted cone, measured profile; THEORY.md section 11): the model is then solved directly\n"
        "at each data point (slower: seconds to minutes), the shape's own parameters stay fixed.\n"
        "--columns z,F: the abscissa is the base (piezo) displacement z = delta + F/k of a sphere on a\n"
        "spring k (cantilever, machine frame; --spring k): the model is taken on the branch stable under\n"
        "spring control, and k itself can be fitted (--free w,k): F and z together carry it.\n"
        "--model md: a Maugis-Dugdale cohesive zone instead of JKR (THEORY.md section 13), lambda fixed\n"
        "(--lambda) or free (--free w,lambda); a,F data of a rigid sphere, one solve per point and trial.\n"
        "Exit 2: bad input; exit 3: no convergence, parameters not determined, or no model fit.",
        spec);
    return kExitSuccess;
  }
  if (arguments.positionals().size() != 1) {
    throw InputError("give exactly one data file (coatcontact fit DATA --columns ...)");
  }
  const std::string path = arguments.positionals()[0];

  // ---- columns ----
  const std::string columns = arguments.require("--columns");
  const ColumnChoice choice = parse_columns(columns);
  const fit::DataKind kind = choice.kind;
  const bool radius_data = kind == fit::DataKind::kRadiusForce;
  const std::string x_name = radius_data ? "a" : choice.base ? "z" : "delta";

  // ---- physical parameters ----
  fit::Problem problem;
  if (const auto text = arguments.get("--shape")) {
    if (arguments.has("--radius")) {
      throw InputError("--shape and --radius exclude each other (a sphere is --radius R or --shape sphere:R)");
    }
    if (arguments.has("--curve") || arguments.has("--plot")) {
      throw InputError("--shape: --curve and --plot draw the sphere's interpolated curve only; the fitted table "
                       "(--output) has the model at every data point");
    }
    std::string profile_end;
    problem.shape = parse_shape(*text, profile_end);
  } else {
    if (!arguments.has("--radius")) throw InputError("missing required option --radius R (or --shape SPEC) (see --help)");
    problem.sphere_radius = parse_quantity(arguments.require("--radius"), Quantity::kLength, "--radius");
  }
  // --film (one film of thickness t) or --layer, repeated (a stack whose layers carry their
  // thicknesses); parse_stack refuses both together and checks the constants.
  const bool stack_given = arguments.has("--layer");
  {
    const Stack stack = parse_stack(arguments);
    if (stack_given) {
      if (arguments.has("--thickness")) {
        throw InputError("--thickness: cannot be combined with --layer (the layers carry their thicknesses; "
                         "fit one with --free h1..hN)");
      }
      problem.layers = stack.layers();
    } else {
      problem.film = stack.top();
    }
    problem.substrate = stack.substrate();
    problem.indenter = stack.indenter();
  }
  const std::size_t layer_count = stack_given ? problem.layers.size() : 1;
  // Loading and unloading with their own adhesion energy (JKR hysteresis): named in --free.
  const std::vector<std::string> free_items = split(arguments.get("--free").value_or("w"), ',');
  const bool hysteresis = std::any_of(free_items.begin(), free_items.end(), [](const std::string& item) {
    return trim(item) == "w_load" || trim(item) == "w_unload";
  });
  // --model md: the Maugis-Dugdale zone (lambda last in the parameter vector; --lambda its value).
  bool md = false;
  if (const auto text = arguments.get("--model")) {
    if (*text == "md") {
      md = true;
    } else if (*text != "jkr") {
      throw InputError("--model: '" + *text + "' is not allowed (jkr, the default, or md: Maugis-Dugdale)");
    }
  }
  if (md) {
    problem.maugis_dugdale = true;
    if (!radius_data) throw InputError("--model md: fits a,F data only (--columns a,F)");
    if (problem.shape) throw InputError("--model md: the Maugis-Dugdale zone is fitted for the sphere only, not --shape");
    if (hysteresis) throw InputError("--model md: one adhesion energy only (not w_load,w_unload)");
    if (!problem.indenter.rigid) throw InputError("--model md: a rigid sphere only (not --indenter)");
    if (arguments.has("--spring")) throw InputError("--model md: no spring pull-off (leave out --spring)");
    if (const auto text = arguments.get("--lambda")) problem.lambda = parse_lambda(*text, "--lambda");
  } else if (arguments.has("--lambda")) {
    throw InputError("--lambda: only with --model md");
  }
  const std::vector<fit::ParameterInfo> parameters = fit::parameter_list(layer_count, hysteresis, choice.base, md);
  const std::size_t parameter_count = parameters.size();
  const std::size_t unload_index = fit::unload_work_index(layer_count);
  problem.hysteresis = hysteresis;
  if (const auto text = arguments.get("--spring")) problem.spring_stiffness = parse_stiffness(*text);
  // z,F: the base (piezo) displacement z = delta + F/k; k is a parameter (--spring: its value).
  problem.base_displacement = choice.base;
  if (choice.base) {
    if (problem.shape) {
      throw InputError("--columns z,F: base-displacement data are fitted with the sphere only (--radius), not --shape");
    }
    if (!arguments.has("--spring")) {
      throw InputError("--columns z,F: give the spring stiffness with --spring k (its value when fixed, the start of "
                       "the search when --free names k)");
    }
  }
  if (const auto text = arguments.get("--bootstrap")) {
    char* end = nullptr;
    const long n = std::strtol(text->c_str(), &end, 10);
    if (end == text->c_str() || *end != '\0' || n < 10 || n > 100000) {
      throw InputError("--bootstrap: '" + *text + "' is not an integer in [10, 100000]");
    }
    problem.bootstrap = static_cast<int>(n);
  }
  if (const auto text = arguments.get("--seed")) {
    char* end = nullptr;
    const long long n = std::strtoll(text->c_str(), &end, 10);
    if (end == text->c_str() || *end != '\0' || n < 0 || n > 4000000000LL) {
      throw InputError("--seed: '" + *text + "' is not an integer in [0, 4e9]");
    }
    if (!arguments.get("--bootstrap")) throw InputError("--seed: only used with --bootstrap");
    problem.bootstrap_seed = static_cast<unsigned long>(n);
  }
  if (const auto text = arguments.get("--plot")) {
    const auto dot = text->rfind('.');
    const std::string extension = dot == std::string::npos ? "" : text->substr(dot + 1);
    if (extension != "png" && extension != "pdf") {
      throw InputError("--plot: '" + *text + "' must end in .png or .pdf (the format follows the extension)");
    }
  }
  std::vector<bool> free(parameter_count, false);
  for (const std::string& item : free_items) {
    const int which = parameter_index(trim(item), "--free", layer_count, stack_given, hysteresis, choice.base, md);
    if (free[which]) throw InputError("--free: '" + trim(item) + "' is named twice");
    free[which] = true;
  }
  if (hysteresis && !(free[fit::kWork] && free[unload_index])) {
    throw InputError("--free: name both w_load and w_unload (the two branches' adhesion energies are fitted together)");
  }
  for (std::size_t which = 0; which < parameter_count; ++which) {
    if ((stack_given || hysteresis || choice.base || md) && free[which]) problem.free_parameters.push_back(which);
    if (!stack_given && !hysteresis && !choice.base && !md) problem.free[which] = free[which];
  }
  std::vector<std::optional<double>> start(parameter_count);
  if (const auto text = arguments.get("--start")) {
    for (const std::string& item : split(*text, ',')) {
      const auto equals = item.find('=');
      if (equals == std::string::npos) {
        throw InputError("--start: '" + trim(item) + "' is not name=value (e.g. w=40mJ/m2,t=50um)");
      }
      const std::string name = trim(item.substr(0, equals));
      const int which = parameter_index(name, "--start", layer_count, stack_given, hysteresis, choice.base, md);
      if (!free[which]) {
        throw InputError("--start: " + name + " is not free (add it to --free, or fix it with its own option)");
      }
      if (start[which]) throw InputError("--start: " + name + " is given twice");
      if (parameters[which].kind == fit::ParameterKind::kLambda) {
        start[which] = parse_lambda(item.substr(equals + 1), "--start lambda");
      } else if (parameters[which].kind == fit::ParameterKind::kSpring) {
        try {
          start[which] = parse_stiffness(item.substr(equals + 1));
        } catch (const InputError& error) {
          std::string message = error.what();
          if (message.rfind("--spring: ", 0) == 0) message = message.substr(10);
          throw InputError("--start k: " + message);
        }
      } else {
        start[which] = parse_quantity(item.substr(equals + 1), parameter_kind(parameters[which]), "--start " + name);
      }
    }
  }
  if (choice.base && start[parameters.size() - 1]) problem.spring_stiffness = *start[parameters.size() - 1];
  if (md && start[parameters.size() - 1]) problem.lambda = *start[parameters.size() - 1];
  std::optional<double> thickness;
  std::optional<double> work;
  if (const auto text = arguments.get("--thickness")) thickness = parse_quantity(*text, Quantity::kLength, "--thickness");
  if (const auto text = arguments.get("--work")) work = parse_quantity(*text, Quantity::kEnergy, "--work");
  fit::Branch branch = fit::Branch::kAll;
  if (const auto text = arguments.get("--branch"); text && hysteresis && *text != "both") {
    throw InputError("--branch: '" + *text + "' keeps one branch, but w_load,w_unload need both (leave --branch out)");
  }
  if (choice.reference[4].size() > 0 && !hysteresis) {
    throw InputError("--columns: branch=" + choice.reference[4] +
                     " is read only when the branches have their own adhesion energies (--free w_load,w_unload)");
  }
  if (const auto text = arguments.get("--branch")) {
    if (*text == "load") {
      branch = fit::Branch::kLoading;
    } else if (*text == "unload") {
      branch = fit::Branch::kUnloading;
    } else if (*text != "both") {
      throw InputError("--branch: '" + *text + "' is not allowed (load, unload or both)");
    }
  }

  // ---- data ----
  check_output_paths({{"--output", arguments.get("--output").value_or("")},
                      {"--curve", arguments.get("--curve").value_or("")},
                      {"--plot", arguments.get("--plot").value_or("")}});
  const LoadedData loaded = load_data(path, choice, kind);
  fit::Measurements all = loaded.data;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (radius_data && !(all.abscissa[i] > 0.0)) {
      throw InputError(path + ":" + std::to_string(all.line_numbers[i]) +
                       ": contact radius must be > 0 (got " + short_number(all.abscissa[i]) +
                       "); points out of contact are not on the equilibrium curve, remove them");
    }
    // A contact radius at or above R is not a sphere contact: almost always forgotten units.
    if (!problem.shape && radius_data && all.abscissa[i] >= problem.sphere_radius) {
      throw InputError(path + ":" + std::to_string(all.line_numbers[i]) + ": contact radius a = " +
                       short_number(all.abscissa[i]) + " m is not below the sphere radius --radius " +
                       short_number(problem.sphere_radius) + " m" +
                       (loaded.has_units ? std::string("")
                                         : "; the file declares no units, so its numbers were read as metres and "
                                           "newtons: add a line '# units: um mN' (or name the columns 'a (um)', 'F (mN)')"));
    }
  }
  if (problem.shape && radius_data) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (all.abscissa[i] > problem.shape->max_contact_radius()) {
        throw InputError(path + ":" + std::to_string(all.line_numbers[i]) + ": contact radius a = " +
                         short_number(all.abscissa[i]) + " m exceeds the largest radius of --shape (" +
                         problem.shape->description() + ")");
      }
    }
  }
  if (!problem.shape && !radius_data && !loaded.has_units) {
    double largest = 0.0;
    for (double d : all.abscissa) largest = std::max(largest, std::fabs(d));
    if (largest >= problem.sphere_radius) {
      throw InputError(path + ": penetrations up to " + short_number(largest) + " m exceed the sphere radius --radius " +
                       short_number(problem.sphere_radius) + " m; the file declares no units, so its numbers were "
                       "read as metres and newtons: add a line '# units: um mN' (or name the columns 'delta (um)', 'F (mN)')");
    }
  }
  apply_sigma_option(arguments.get("--sigma"), all, choice);
  // The branch of each row: the branch column (1 loading, 0 unloading), else the row order.
  std::string branch_source;
  if (hysteresis) {
    if (!loaded.branch.empty()) {
      all.unloading.assign(all.size(), false);
      for (std::size_t i = 0; i < all.size(); ++i) {
        const double b = loaded.branch[i];
        if (b != 0.0 && b != 1.0) {
          throw InputError(path + ":" + std::to_string(all.line_numbers[i]) + ": branch = " + short_number(b) +
                           " is not allowed (1 for a loading row, 0 for an unloading row)");
        }
        all.unloading[i] = b == 0.0;
      }
      branch_source = "the branch column (1 loading, 0 unloading)";
    } else {
      all.unloading = fit::unloading_by_order(all);
      branch_source = std::string("the row order (loading up to the largest ") + (radius_data ? "a" : "delta") +
                      ", unloading after it)";
    }
  }
  const fit::Measurements data = fit::select_branch(all, branch);

  // ---- start values / fixed values ----
  if (stack_given) {
    // The layers' given values are the hints of the free ones (or --start) and fix the others.
    for (std::size_t which = 0; which < parameter_count; ++which) {
      if (!start[which] || which == fit::kWork) continue;
      const fit::ParameterInfo& info = parameters[which];
      Layer& layer = problem.layers[info.layer];
      (info.kind == fit::ParameterKind::kThickness ? layer.thickness : layer.material.youngs_modulus) = *start[which];
    }
  } else if (free[fit::kThickness]) {
    // Without a hint the search needs none: t ~ the middle of the contact radii (a/t ~ 1).
    double middle = 0.0;
    for (double x : data.abscissa) middle = std::max(middle, std::fabs(x));
    if (!radius_data && !problem.shape) middle = std::sqrt(problem.sphere_radius * middle);
    problem.thickness = start[fit::kThickness].value_or(thickness.value_or(0.3 * middle));
  } else {
    if (!thickness) throw InputError("t is fixed: give it with --thickness (or add t to --free)");
    problem.thickness = *thickness;
  }
  if (free[fit::kWork]) {
    if (start[fit::kWork]) {
      problem.work = *start[fit::kWork];
    } else if (work) {
      problem.work = *work;
    } else {
      // A shape has no sphere radius for the JKR estimate: the search finds w on its own.
      problem.work = problem.shape ? 0.05 : fit::jkr_work_estimate(data, problem.sphere_radius);
    }
    if (hysteresis) {
      problem.unload_work = start[unload_index].value_or(
          work.value_or(problem.shape ? 0.05 : fit::jkr_work_estimate(data, problem.sphere_radius)));
    }
  } else {
    if (!work) throw InputError("w is fixed: give it with --work (or add w to --free)");
    problem.work = *work;
  }
  if (!stack_given && free[fit::kFilmModulus] && start[fit::kFilmModulus]) {
    problem.film.youngs_modulus = *start[fit::kFilmModulus];
  }
  // The hint (free) or fixed value of every parameter, in the order of the parameter vector.
  std::vector<double> start_values{problem.work};
  if (stack_given) {
    for (const Layer& layer : problem.layers) start_values.push_back(layer.thickness);
    for (const Layer& layer : problem.layers) start_values.push_back(layer.material.youngs_modulus);
  } else {
    start_values.push_back(problem.thickness);
    start_values.push_back(problem.film.youngs_modulus);
  }
  if (hysteresis) {
    start_values.push_back(problem.unload_work);
    if (!(problem.unload_work >= fit::kWorkRange[0] && problem.unload_work <= fit::kWorkRange[1])) {
      throw InputError(std::string(start[unload_index] ? "--start w_unload" : "--work") + ": w_unload = " +
                       short_number(problem.unload_work) + " J/m2 is outside the range the fit explores, [" +
                       short_number(fit::kWorkRange[0]) + ", " + short_number(fit::kWorkRange[1]) + "] J/m2");
    }
  }
  if (choice.base) start_values.push_back(problem.spring_stiffness);  // k, last
  if (md) start_values.push_back(problem.lambda);                     // lambda, last
  const auto source_option = [&](std::size_t which) -> std::string {
    if (start[which]) return "--start " + parameters[which].name;
    return stack_given ? "--layer" : which == fit::kThickness ? "--thickness" : "--film";
  };
  double total_thickness = 0.0;
  for (std::size_t i = 0; i < layer_count; ++i) total_thickness += start_values[fit::thickness_index(i)];
  check_fit_start({choice.legacy ? columns : std::string("a,F"), loaded.declared_columns, loaded.declared_line, path, radius_data, data.abscissa,
                   problem.work, total_thickness, start_values[fit::modulus_index(0, layer_count)],
                   free[fit::kWork] ? (start[fit::kWork] ? "--start w" : work ? "--work" : "--radius (with the data's most tensile force, the start value of w)") : "--work",
                   layer_count == 1 ? source_option(fit::kThickness) : "--layer (their total thickness)",
                   source_option(fit::modulus_index(0, layer_count))});
  for (std::size_t i = 1; i < layer_count; ++i) {
    const std::size_t which = fit::modulus_index(i, layer_count);
    if (!(start_values[which] >= fit::kModulusRange[0] && start_values[which] <= fit::kModulusRange[1])) {
      throw InputError(source_option(which) + ": " + parameters[which].name + " = " + short_number(start_values[which]) +
                       " Pa is outside the range the fit explores, [" + short_number(fit::kModulusRange[0]) + ", " +
                       short_number(fit::kModulusRange[1]) + "] Pa");
    }
  }

  const fit::Result result = [&] {
    try {
      return fit::fit(data, problem);
    } catch (const NumericalError& error) {
      // An unweighted fit assumes an exact abscissa; scatter in a (or delta) near the steep
      // part of the curve then drags w to the edge of its range. Say so and how to fix it.
      const std::string what = error.what();
      const bool runaway = what.find("the data do not determine w") != std::string::npos;
      if (!runaway || !data.sigma_abscissa.empty() || !data.sigma_force.empty()) throw;
      throw NumericalError(what + ". No uncertainties were given: if " + x_name +
                           " is noisy, that noise may dominate an unweighted fit in force; give both, e.g. --sigma " +
                           x_name + "=2%,F=1uN (or sigma columns), to weight each point by its effective variance");
    }
  }();

  // ---- output ----
  std::vector<std::pair<std::string, std::string>> header;
  std::string command = "coatcontact fit";
  for (const auto& a : args) command += " " + a;
  header.emplace_back("command", command);
  header.emplace_back("data", path);
  header.emplace_back("columns_in_file", columns);
  header.emplace_back("branch", branch == fit::Branch::kAll ? "both" : branch == fit::Branch::kLoading ? "load" : "unload");
  if (hysteresis) {
    const auto unloading_rows = std::count(data.unloading.begin(), data.unloading.end(), true);
    header.emplace_back("branches", std::to_string(data.size() - static_cast<std::size_t>(unloading_rows)) + " loading rows (w_load), " +
                                        std::to_string(unloading_rows) + " unloading rows (w_unload), from " + branch_source +
                                        "; pull-offs predicted with w_unload");
  }
  header.emplace_back("points", std::to_string(result.points) + " (of " + std::to_string(all.size()) + " in the file)");
  if (problem.shape) {
    header.emplace_back("indenter_shape", problem.shape->description());
  } else {
    header.emplace_back("sphere_radius_m", number(problem.sphere_radius));
  }
  if (stack_given) {
    std::string layers_text;
    for (std::size_t i = 0; i < layer_count; ++i) {
      const Layer& layer = problem.layers[i];
      const std::string k = std::to_string(i + 1);
      layers_text += (i == 0 ? "" : "; ") + std::string("h") + k + " = " + number(layer.thickness) + " m" +
                     (free[fit::thickness_index(i)] ? " (free)" : "") + ", E" + k + " = " +
                     number(layer.material.youngs_modulus) + " Pa" +
                     (free[fit::modulus_index(i, layer_count)] ? " (free)" : "") + ", nu" + k + " = " +
                     number(layer.material.poisson_ratio) + (layer.slip_below ? ", slip below" : "");
    }
    header.emplace_back("layers", std::to_string(layer_count) + " (top first; given values, hints of the free ones): " +
                                      layers_text);
  } else {
    header.emplace_back("film_nu1", number(problem.film.poisson_ratio));
  }
  header.emplace_back("substrate", problem.substrate.rigid ? std::string("rigid")
                                                           : "E0 = " + number(problem.substrate.material.youngs_modulus) +
                                                                 " Pa, nu0 = " + number(problem.substrate.material.poisson_ratio));
  std::string free_names;
  for (std::size_t which = 0; which < parameter_count; ++which) {
    if (!free[which]) continue;
    free_names += (free_names.empty() ? "" : ",") + parameters[which].name;
  }
  header.emplace_back("free", free_names);
  for (std::size_t which = 0; which < parameter_count; ++which) {
    const std::string& name = parameters[which].name;
    header.emplace_back(name + "_" + key_unit(parameters[which]), number(result.value[which]));
    if (free[which]) {
      header.emplace_back(name + "_stderr_" + key_unit(parameters[which]), number(result.standard_error[which]));
      header.emplace_back(name + "_hint_" + key_unit(parameters[which]), number(start_values[which]));
    } else {
      header.emplace_back(name + "_status", "fixed");
    }
  }
  for (std::size_t a = 0; a < parameter_count; ++a) {
    for (std::size_t b = a + 1; b < parameter_count; ++b) {
      if (free[a] && free[b]) {
        header.emplace_back("correlation_" + parameters[a].name + "_" + parameters[b].name,
                            number(result.correlation[a][b]));
      }
    }
  }
  if (problem.bootstrap > 0) {
    for (std::size_t which = 0; which < parameter_count; ++which) {
      if (!free[which]) continue;
      const std::string name = parameters[which].name + "_";
      header.emplace_back(name + "interval68_" + key_unit(parameters[which]),
                          number(result.interval68_low[which]) + " " + number(result.interval68_high[which]));
      header.emplace_back(name + "interval95_" + key_unit(parameters[which]),
                          number(result.interval95_low[which]) + " " + number(result.interval95_high[which]));
    }
    header.emplace_back("bootstrap", std::to_string(result.bootstrap_samples) + " of " + std::to_string(problem.bootstrap) +
                                         " residual resamples refitted (seed " + std::to_string(problem.bootstrap_seed) +
                                         "), percentile intervals");
  }
  header.emplace_back("indenter", problem.indenter.rigid ? std::string("rigid")
                                                         : "E2 = " + number(problem.indenter.material.youngs_modulus) +
                                                               " Pa, nu2 = " + number(problem.indenter.material.poisson_ratio));
  if (result.weighted) {
    header.emplace_back("weights", "effective variance sigma_F^2 + (dF/d" + x_name + ")^2 sigma_" + x_name +
                                       "^2 (dF/d" + x_name + " along the fitted curve)");
    header.emplace_back("chi2", number(result.chi2));
    header.emplace_back("chi2_per_dof", number(result.chi2_per_dof));
    if (result.chi2_per_dof > 2.0 || result.chi2_per_dof < 0.5) {
      header.emplace_back("warning", "chi2/(n-p) = " + short_number(result.chi2_per_dof) +
                                         " is far from 1: the stated uncertainties do not match the scatter, and "
                                         "the standard errors (which trust them) are off by sqrt(chi2/(n-p))");
    }
  } else {
    header.emplace_back("weights", "none: residuals in F, noise level from the scatter; the errors assume exact " +
                                       x_name + " (give --sigma " + x_name + "=..,F=.. if " + x_name + " is measured)");
  }
  header.emplace_back("global_search", std::to_string(result.search_evaluations) + " model evaluations over log-parameters, " +
                                          short_number(result.search_seconds) + " s");
  if (result.second_minimum) {
    std::string text;
    for (std::size_t which = 0; which < parameter_count; ++which) {
      if (!free[which]) continue;
      text += std::string(text.empty() ? "" : ", ") + parameters[which].name + " = " +
              short_number(result.second_value[which]) + " " + parameters[which].unit;
    }
    header.emplace_back("second_minimum", text + " (cost " + short_number(result.second_cost_ratio) + " x the best)");
  }
  if (problem.spring_stiffness > 0.0) {
    if (result.has_spring_pulloff) {
      header.emplace_back("spring_pulloff_F_N", number(result.spring_pulloff_force));
      header.emplace_back("spring_pulloff_a_m", number(result.spring_pulloff_radius));
      header.emplace_back("spring_pulloff_delta_m", number(result.spring_pulloff_penetration));
    } else {
      header.emplace_back("spring_pulloff", "not found inside the scanned range of the fitted model");
    }
  }
  if (result.has_load_pulloff) {
    header.emplace_back("load_pulloff_F_N", number(result.load_pulloff_force));
    header.emplace_back("load_pulloff_a_m", number(result.load_pulloff_radius));
    header.emplace_back("load_pulloff_delta_m", number(result.load_pulloff_penetration));
  }
  header.emplace_back("residual_norm_N", number(result.residual_norm));
  header.emplace_back("residual_sigma_N", number(result.residual_sigma));
  header.emplace_back("r_squared", number(result.r_squared));
  header.emplace_back("iterations", std::to_string(result.iterations));
  header.emplace_back("converged", result.converged ? "yes (" + result.stop_reason + ")" : "no");
  header.emplace_back("interpolation_error_N", number(result.interpolation_error));
  header.emplace_back("interpolation_error_over_sigma", number(result.interpolation_error / result.residual_sigma));
  header.emplace_back("solver_tolerance", number(result.solver_tolerance));
  header.emplace_back("solver_calls", std::to_string(result.solver_calls));
  header.emplace_back("fit_seconds", short_number(result.seconds));
  if (result.displacement_pulloff_radius > 0.0) {
    header.emplace_back("displacement_pulloff_a_m", number(result.displacement_pulloff_radius));
    header.emplace_back("displacement_pulloff_delta_m", number(result.displacement_pulloff_penetration));
    header.emplace_back("displacement_pulloff_F_N", number(result.displacement_pulloff_force));
  }
  std::size_t clamped = 0;
  for (bool c : result.clamped) clamped += c ? 1 : 0;
  if (!radius_data) {
    header.emplace_back("model_branch", "a >= a_c (first minimum of delta(a)); points with delta < delta(a_c): "
                                        + std::to_string(clamped) + " (taken at a_c)");
  }
  std::vector<std::string> out_columns =
      radius_data ? std::vector<std::string>{"line", "a_m", "F_data_N", "F_model_N", "residual_N", "sigma_eff_N"}
                  : std::vector<std::string>{"line", "delta_m", "F_data_N", "a_model_m", "F_model_N", "residual_N",
                                             "clamped", "sigma_eff_N"};
  if (hysteresis) out_columns.push_back("branch");  // 1 loading, 0 unloading

  // The curve (for --curve and --plot), then the table; every file is produced in memory
  // first (the plot by gnuplot) so a failure leaves no half-written set of files.
  const std::optional<std::string> curve_path = arguments.get("--curve");
  const std::optional<std::string> plot_path = arguments.get("--plot");
  const std::vector<std::string> curve_columns{"a_m", "delta_m", "F_N"};
  std::ostringstream curve_text;
  if (curve_path || plot_path) {
    fit::Problem fitted = problem;
    // With two adhesion energies the curve is the unloading one (the pull-offs' w).
    fitted.work = result.value[hysteresis ? unload_index : static_cast<std::size_t>(fit::kWork)];
    fitted.hysteresis = false;
    if (stack_given) {
      for (std::size_t i = 0; i < layer_count; ++i) {
        fitted.layers[i].thickness = result.value[fit::thickness_index(i)];
        fitted.layers[i].material.youngs_modulus = result.value[fit::modulus_index(i, layer_count)];
      }
    } else {
      fitted.thickness = result.value[fit::kThickness];
      fitted.film.youngs_modulus = result.value[fit::kFilmModulus];
    }
    double a_lo = *std::min_element(result.model_radius.begin(), result.model_radius.end());
    const double a_hi = 1.05 * *std::max_element(result.model_radius.begin(), result.model_radius.end());
    if (result.displacement_pulloff_radius > 0.0) a_lo = std::min(a_lo, result.displacement_pulloff_radius);
    if (result.has_load_pulloff) a_lo = std::min(a_lo, result.load_pulloff_radius);
    a_lo *= radius_data ? 0.9 : 0.3;
    const std::vector<fit::CurvePoint> curve = fit::model_curve(fitted, a_lo, a_hi, 200);
    auto curve_header = header;
    curve_header.emplace_back("curve", std::string("fitted model, 200 points log-spaced in a") + (hysteresis ? " (with w_unload)" : ""));
    write_header(curve_text, curve_header, curve_columns);
    for (const auto& p : curve) write_row(curve_text, {p.radius, p.penetration, p.force}, curve_columns);
  }

  std::ostringstream table_text;
  write_header(table_text, header, out_columns);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double line = data.line_numbers.empty() ? static_cast<double>(i + 1) : data.line_numbers[i];
    // sigma_eff: the weight's sigma, or the residual standard deviation of an unweighted fit.
    const double sigma = result.weighted ? result.sigma_effective[i] : result.residual_sigma;
    std::vector<double> row =
        radius_data ? std::vector<double>{line, data.abscissa[i], data.force[i], result.model_force[i], result.residual[i], sigma}
                    : std::vector<double>{line, data.abscissa[i], data.force[i], result.model_radius[i], result.model_force[i],
                                          result.residual[i], result.clamped[i] ? 1.0 : 0.0, sigma};
    if (hysteresis) row.push_back(data.unloading[i] ? 0.0 : 1.0);
    write_row(table_text, row, out_columns);
  }

  std::string picture;
  if (plot_path) {
    const double nan = std::nan("");
    // z,F data are drawn against the base displacement z = delta + F/k (THEORY.md section 10):
    // the model curve and the pull-offs too.
    const double spring_k = choice.base ? result.value[fit::spring_index(layer_count, hysteresis)] : nan;
    const auto abscissa = [&](double radius, double penetration, double force) {
      return radius_data ? radius : choice.base ? penetration + force / spring_k : penetration;
    };
    const double lp_x = result.has_load_pulloff
                            ? abscissa(result.load_pulloff_radius, result.load_pulloff_penetration, result.load_pulloff_force)
                            : nan;
    const double dp_x = result.displacement_pulloff_radius > 0.0
                            ? abscissa(result.displacement_pulloff_radius, result.displacement_pulloff_penetration,
                                       result.displacement_pulloff_force)
                            : nan;
    std::string estimates;
    for (std::size_t which = 0; which < parameter_count; ++which) {
      if (!free[which]) continue;
      const std::string unit = parameters[which].kind == fit::ParameterKind::kWork ? "J/m^2" : parameters[which].unit;
      estimates += std::string(estimates.empty() ? "" : ",  ") + parameters[which].name + " = " +
                   si_text_with_error(result.value[which], result.standard_error[which], unit);
    }
    const std::string fit_label =
        "fit: " + estimates + "   (n = " + std::to_string(result.points) +
        (result.weighted ? ", χ^2/(n-p) = " + si_text(result.chi2_per_dof, "") : ", s = " + si_text(result.residual_sigma, "N")) +
        (result.has_load_pulloff ? ", pull-off " + si_text(result.load_pulloff_force, "N") : "") + ")";
    std::string substrate = problem.substrate.rigid ? std::string("rigid substrate")
                                                    : "E0 = " + si_text(problem.substrate.material.youngs_modulus, "Pa") +
                                                          ", ν0 = " + short_number(problem.substrate.material.poisson_ratio);
    const std::string name = path == "-" ? std::string("stdin") : path.substr(path.find_last_of('/') + 1);
    std::string coating;
    if (stack_given) {
      coating = std::to_string(layer_count) + " layers (";
      for (std::size_t i = 0; i < layer_count; ++i) {
        coating += (i == 0 ? "" : "; ") + si_text(result.value[fit::thickness_index(i)], "m") + ", " +
                   si_text(result.value[fit::modulus_index(i, layer_count)], "Pa");
      }
      coating += ")";
    } else {
      coating = "film E1 = " + si_text(result.value[fit::kFilmModulus], "Pa") + " (ν1 = " +
                short_number(problem.film.poisson_ratio) + "), t = " + si_text(result.value[fit::kThickness], "m");
    }
    const std::string title = name + ": R = " + si_text(problem.sphere_radius, "m") + ", " + coating + ", " + substrate;
    picture = render_fit_plot(table_text.str(), curve_text.str(), x_name, title, fit_label,
                              plot_path->substr(plot_path->rfind('.') + 1), lp_x, result.load_pulloff_force, dp_x,
                              result.displacement_pulloff_force, spring_k);
  }

  const std::string output_path = arguments.get("--output").value_or("");
  std::unique_ptr<Output> plot_output;
  if (plot_path) {
    plot_output = std::make_unique<Output>(*plot_path, "--plot");
    plot_output->stream().write(picture.data(), static_cast<std::streamsize>(picture.size()));
  }
  std::unique_ptr<Output> curve_output;
  if (curve_path) {
    curve_output = std::make_unique<Output>(*curve_path, "--curve");
    curve_output->stream() << curve_text.str();
  }
  Output output(output_path);
  output.stream() << table_text.str();
  if (plot_output) plot_output->commit();
  if (curve_output) curve_output->commit();
  output.commit();

  if (!output_path.empty()) {
    // The table went to a file: a short human-readable summary on stdout.
    std::cout << "coatcontact fit: " << result.points << " points (" << x_name << ",F), "
              << result.free_count << " free parameter" << (result.free_count == 1 ? "" : "s") << ", converged ("
              << result.stop_reason << ") after " << result.iterations << " iterations\n";
    std::size_t width = 0;
    for (const auto& info : parameters) width = std::max(width, info.name.size());
    for (std::size_t which = 0; which < parameter_count; ++which) {
      std::cout << "  " << parameters[which].name << std::string(width - parameters[which].name.size(), ' ') << " = "
                << short_number(result.value[which]) << " " << parameters[which].unit;
      if (free[which]) {
        std::cout << " +- " << short_number(result.standard_error[which]) << " (standard error)";
        if (problem.bootstrap > 0) {
          std::cout << ", bootstrap 68 % [" << short_number(result.interval68_low[which]) << ", "
                    << short_number(result.interval68_high[which]) << "]";
        }
      } else {
        std::cout << " (fixed)";
      }
      std::cout << "\n";
    }
    std::cout << "  residual norm " << short_number(result.residual_norm) << " N, sigma "
              << short_number(result.residual_sigma) << " N, R^2 " << short_number(result.r_squared)
              << ", interpolation error " << order_of_magnitude_bound(result.interpolation_error / result.residual_sigma)
              << " sigma\n";
    if (result.weighted) {
      std::cout << "  weighted by sigma_F^2 + (dF/d" << x_name << ")^2 sigma_" << x_name
                << "^2: chi2/(n-p) = " << short_number(result.chi2_per_dof) << "\n";
    } else {
      std::cout << "  unweighted: the errors assume exact " << x_name << " (give --sigma if it is measured)\n";
    }
    if (result.has_load_pulloff) {
      std::cout << "  predicted pull-off: " << short_number(result.load_pulloff_force) << " N under load control";
      if (result.displacement_pulloff_radius > 0.0) {
        std::cout << ", " << short_number(result.displacement_pulloff_force) << " N under displacement control";
      }
      std::cout << "\n";
    }
    if (result.has_spring_pulloff) {
      std::cout << "  predicted pull-off through the spring k = "
                << short_number(choice.base ? result.value.back() : problem.spring_stiffness)
                << " N/m: " << short_number(result.spring_pulloff_force) << " N\n";
    }
    if (result.second_minimum) {
      std::cout << "  note: a second minimum at";
      for (std::size_t which = 0; which < parameter_count; ++which) {
        if (free[which]) std::cout << " " << parameters[which].name << " = " << short_number(result.second_value[which]);
      }
      std::cout << " (cost " << short_number(result.second_cost_ratio) << " x the best)\n";
    }
  }
  return kExitSuccess;
}

}  // namespace

int run_fit(const Args& args) {
  return run_guarded("fit", [&] { return run_fit_body(args); });
}

}  // namespace coatcontact::cli
