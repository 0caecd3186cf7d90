// Value parsers, argument parsing, TSV formatting and run_guarded of the coatcontact CLI.
// (Atomic output files are in output.cpp.)
#include "coatcontact/cli_support.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>
#include <iostream>
#include <ostream>
#include <set>
#include <sstream>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/table_text.hpp"
#include "number_text.hpp"

namespace coatcontact {

namespace cli {
namespace {

using detail::NumberStatus;
using detail::quote;
using detail::trim_blanks;

constexpr std::size_t kMaxListPoints = 1000000;  // N of MIN:MAX:N and items of a list
constexpr double kMinQuantity = 1e-100;  // SI, any quantity
constexpr double kMaxQuantity = 1e100;
constexpr const char* kListExpected = "expected comma-separated numbers or MIN:MAX:N";

[[noreturn]] void fail(const std::string& option, const std::string& message) {
  throw InputError(option + ": " + message);
}

// Message tail for a number that did not parse, e.g. "'abc' is not a number".
std::string number_problem(NumberStatus status, std::string_view text) {
  switch (status) {
    case NumberStatus::kNotFinite:
      return quote(text) + " is not a finite number";
    case NumberStatus::kOutOfRange:
      return quote(text) + " is outside the range of a double";
    case NumberStatus::kSubnormal:
      return quote(text) + " is too small (nonzero values need a magnitude of at least 2.2250738585072014e-308)";
    default:
      return text.empty() ? std::string("empty value") : quote(text) + " is not a number";
  }
}

}  // namespace

namespace {

// Number with optional unit -> SI value > 0. `what` names the value ("length",
// "Young's modulus").
double parse_quantity_impl(std::string_view raw, Quantity kind, const std::string& option,
                           const std::string& what) {
  const std::string_view text = trim_blanks(raw);
  const std::string expected = "expected a number with an optional unit (" + unit_list(kind) + ")";
  if (text.empty()) fail(option, "empty " + what + "; " + expected);
  // The number is the longest prefix of decimal-notation characters. No unit starts with
  // 'e' or 'E', so "2e3MPa" splits as "2e3" + "MPa".
  std::size_t split = 0;
  while (split < text.size()) {
    const char c = text[split];
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-')) break;
    ++split;
  }
  const std::string_view number = text.substr(0, split);
  std::string_view unit = text.substr(split);
  if (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);  // "2 MPa": one space

  double value = 0.0;
  const NumberStatus status = detail::parse_decimal(number, value);
  if (status != NumberStatus::kOk) {
    if (number.empty() || status == NumberStatus::kNotNumber) {
      // Report nan/inf spelled as the whole text, otherwise "not a number".
      double ignored = 0.0;
      const NumberStatus whole = detail::parse_decimal(text, ignored);
      if (whole == NumberStatus::kNotFinite) {
        fail(option, what + " " + quote(text) + " is not a finite number; " + expected);
      }
      fail(option, what + " " + quote(text) + " is not a number; " + expected);
    }
    fail(option, what + " " + number_problem(status, text) + "; " + expected);
  }
  double factor = 1.0;
  if (!unit.empty()) {
    const auto info = find_unit(std::string(unit));
    if (!info || info->kind != kind) {
      fail(option, "unknown " + std::string(quantity_name(kind)) + " unit " + quote(unit) + " in " +
                       quote(text) + "; allowed units: " + unit_list(kind));
    }
    factor = info->to_si;
  }
  if (!(value > 0.0)) fail(option, what + " " + quote(text) + " must be > 0");
  const double si = to_si(value, factor);
  if (!std::isfinite(si)) fail(option, what + " " + quote(text) + " is too large");
  if (!(si > 0.0)) fail(option, what + " " + quote(text) + " is too small to represent");
  // Far beyond any physical value, yet products and ratios of two such values stay normal
  // doubles (E1*/E0*, w R^2/E1*): an extreme input is refused here, not met as inf or NaN later.
  if (!(si >= kMinQuantity && si <= kMaxQuantity)) {
    fail(option, what + " " + quote(text) + " is outside the allowed range [1e-100, 1e100] (SI units)");
  }
  return si;
}

// "E,nu" -> material; E as a pressure.
Material parse_material_impl(std::string_view text, const std::string& option) {
  const std::string expected = "expected E,nu (Young's modulus, Poisson ratio), e.g. 2MPa,0.3";
  const std::size_t comma = text.find(',');
  if (trim_blanks(text).empty()) fail(option, "empty value; " + expected);
  if (comma == std::string_view::npos || text.find(',', comma + 1) != std::string_view::npos) {
    fail(option, quote(text) + " is not two comma-separated values; " + expected);
  }
  Material material;
  material.youngs_modulus =
      parse_quantity_impl(text.substr(0, comma), Quantity::kPressure, option, "Young's modulus");
  const std::string_view nu_text = trim_blanks(text.substr(comma + 1));
  double nu = 0.0;
  const NumberStatus status = detail::parse_decimal(nu_text, nu);
  if (status != NumberStatus::kOk) {
    fail(option, "Poisson ratio " + number_problem(status, nu_text) + "; " + expected);
  }
  if (!(nu > -1.0 && nu <= 0.5)) {
    fail(option, "Poisson ratio " + std::string(nu_text) + " is outside the allowed range (-1, 0.5]");
  }
  material.poisson_ratio = nu;
  if (!std::isfinite(material.reduced_modulus())) {
    fail(option, "Young's modulus " + quote(trim_blanks(text.substr(0, comma))) + " is too large");
  }
  return material;
}

bool looks_like_negative_number(const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return false;
  if (arg[1] >= '0' && arg[1] <= '9') return true;
  return arg.size() >= 3 && arg[1] == '.' && arg[2] >= '0' && arg[2] <= '9';
}

bool looks_like_option(const std::string& arg) {
  return arg.size() >= 2 && arg[0] == '-' && !looks_like_negative_number(arg);
}

const OptionSpec* find_option(const std::vector<OptionSpec>& spec, const std::string& name) {
  for (const auto& option : spec) {
    if (option.name == name) return &option;
  }
  return nullptr;
}

// An option name for a message: a very long unknown option is cut, not echoed whole.
std::string option_text(const std::string& name) {
  const std::string quoted = quote(name);  // control bytes escaped, cut after 60 bytes + "..."
  std::string shown = quoted.substr(1, quoted.size() - 2);
  if (shown.size() < name.size()) shown += " (" + std::to_string(name.size()) + " characters)";
  return shown;
}

// Edit distance (insertions, deletions, substitutions, adjacent swaps) of two option names.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

// " (did you mean --film?)" for an unknown option within two edits of a known one (or one the
// typed name starts or is a start of), else "".
std::string did_you_mean(const std::string& name, const std::vector<OptionSpec>& spec) {
  if (name.size() > 64) return "";
  const std::size_t dashes = name.find_first_not_of('-');
  const std::string typed = "--" + (dashes == std::string::npos ? std::string() : name.substr(dashes));
  const OptionSpec* best = nullptr;
  std::size_t best_distance = 3;
  for (const auto& option : spec) {
    std::size_t distance = edit_distance(typed, option.name);
    if (distance > 2 && typed.size() >= 5 && (option.name.rfind(typed, 0) == 0 || typed.rfind(option.name, 0) == 0)) distance = 2;
    if (distance < best_distance) {
      best_distance = distance;
      best = &option;
    }
  }
  return best == nullptr ? "" : " (did you mean " + best->name + "?)";
}

std::string one_line(const std::string& text) {
  std::string out = text;
  std::replace(out.begin(), out.end(), '\n', ' ');
  std::replace(out.begin(), out.end(), '\r', ' ');
  return out;
}

}  // namespace

// ---- value parsers ---------------------------------------------------------------

void check_rows(const std::vector<std::pair<std::string, std::size_t>>& lists) {
  double rows = 1.0;
  std::string names, sizes;
  for (const auto& [option, size] : lists) {
    rows *= static_cast<double>(size);
    names += (names.empty() ? "" : " x ") + option;
    sizes += (sizes.empty() ? "" : " x ") + std::to_string(size);
  }
  if (rows > kMaxRows) {
    std::ostringstream s;
    s << names << ": " << sizes << " = " << rows << " rows is over the limit of " << kMaxRows
      << " rows per run; allowed: fewer values in these lists, or several runs";
    throw InputError(s.str());
  }
}

std::string quoted(const std::string& text) {
  std::string out = quote(text);
  if (text.size() > 60) out += " (" + std::to_string(text.size()) + " bytes)";
  return out;
}

double parse_number(const std::string& text, const std::string& option) {
  const std::string_view trimmed = trim_blanks(text);
  double value = 0.0;
  const NumberStatus status = detail::parse_decimal(trimmed, value);
  if (status != NumberStatus::kOk) {
    fail(option, number_problem(status, trimmed) + "; expected a finite decimal number");
  }
  return value;
}

std::vector<double> parse_list(const std::string& text, const std::string& option) {
  const std::string_view whole = trim_blanks(text);
  if (whole.empty()) fail(option, std::string("empty value; ") + kListExpected);

  if (whole.find(':') != std::string_view::npos) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    for (;;) {
      const std::size_t colon = whole.find(':', start);
      parts.push_back(trim_blanks(whole.substr(start, colon == std::string_view::npos ? colon : colon - start)));
      if (colon == std::string_view::npos) break;
      start = colon + 1;
    }
    if (parts.size() != 3) fail(option, quote(whole) + " is not MIN:MAX:N; " + kListExpected);
    double bounds[2] = {0.0, 0.0};
    const char* names[2] = {"MIN", "MAX"};
    for (int i = 0; i < 2; ++i) {
      const NumberStatus status = detail::parse_decimal(parts[i], bounds[i]);
      if (status != NumberStatus::kOk) {
        fail(option, std::string(names[i]) + " " + (parts[i].empty() ? std::string("is empty") : number_problem(status, parts[i])) +
                         " in " + quote(whole) + "; " + kListExpected);
      }
    }
    const double min = bounds[0];
    const double max = bounds[1];
    // N: plain decimal digits, 1..kMaxListPoints (refuse absurd allocations).
    const std::string_view n_text = parts[2];
    std::size_t count = 0;
    bool n_ok = !n_text.empty() && n_text.size() <= 7;
    for (char c : n_text) {
      if (c < '0' || c > '9') n_ok = false;
    }
    if (n_ok) {
      for (char c : n_text) count = count * 10 + static_cast<std::size_t>(c - '0');
      n_ok = count >= 1 && count <= kMaxListPoints;
    }
    if (!n_ok) {
      fail(option, "N " + quote(n_text) + " in " + quote(whole) + " must be an integer from 1 to " +
                       std::to_string(kMaxListPoints));
    }
    if (!(min > 0.0) || !(max > 0.0)) {
      fail(option, "MIN and MAX of " + quote(whole) + " must be > 0 (the points are log-spaced)");
    }
    if (min > max) fail(option, "MIN " + std::string(parts[0]) + " is larger than MAX " + std::string(parts[1]) + " in " + quote(whole));
    if (count == 1 && min != max) {
      fail(option, "N = 1 in " + quote(whole) + " needs MIN == MAX (one point)");
    }
    std::vector<double> values(count);
    // Base 10 so that decades land exactly (pow(10, integer) is exact): 0.01:100:5 gives 1, not
    // 1.0000000000000009.
    const double log_min = std::log10(min);
    const double log_max = std::log10(max);
    for (std::size_t i = 0; i < count; ++i) {
      const double t = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
      // Clamp: pow(10, log10(x)) may round outside [min, max] by an ulp.
      values[i] = std::clamp(std::pow(10.0, log_min + t * (log_max - log_min)), min, max);
    }
    values.front() = min;  // the end points exactly as given
    values.back() = max;
    return values;
  }

  std::vector<double> values;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = whole.find(',', start);
    const std::string_view item =
        trim_blanks(whole.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (item.empty()) fail(option, quote(whole) + " has an empty item; " + kListExpected);
    double value = 0.0;
    const NumberStatus status = detail::parse_decimal(item, value);
    if (status != NumberStatus::kOk) {
      fail(option, "item " + number_problem(status, item) + " in " + quote(whole) + "; " + kListExpected);
    }
    if (values.size() >= kMaxListPoints) {
      fail(option, "more than " + std::to_string(kMaxListPoints) + " items");
    }
    values.push_back(value);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return values;
}

namespace {

// "v1,v2,..." (each item read by `item`) or "MIN:MAX:N" (MIN and MAX read by `item`, the SI
// bounds spaced by parse_list: exact text of the doubles, so "1e-9:1e-7:3" and "1nm:100nm:3"
// give the same points). Every quantity list of the CLI goes through here.
std::vector<double> parse_si_list(const std::string& text, const std::string& option,
                                  const std::function<double(std::string_view, const std::string&)>& item) {
  const std::string_view whole = trim_blanks(text);
  if (whole.find(':') == std::string_view::npos) {
    if (whole.empty()) fail(option, std::string("empty value; ") + kListExpected);
    std::vector<double> values;
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = whole.find(',', start);
      const std::string_view one = whole.substr(start, comma == std::string_view::npos ? comma : comma - start);
      if (trim_blanks(one).empty()) fail(option, quote(whole) + " has an empty item; " + kListExpected);
      if (values.size() >= kMaxListPoints) fail(option, "more than " + std::to_string(kMaxListPoints) + " items");
      values.push_back(item(one, "value"));
      if (comma == std::string_view::npos) return values;
      start = comma + 1;
    }
  }
  const std::size_t first = whole.find(':');
  const std::size_t second = whole.find(':', first + 1);
  if (second == std::string_view::npos || whole.find(':', second + 1) != std::string_view::npos) {
    fail(option, quote(whole) + " is not MIN:MAX:N; " + kListExpected);
  }
  const double min = item(whole.substr(0, first), "MIN");
  const double max = item(whole.substr(first + 1, second - first - 1), "MAX");
  const std::string si = detail::full_precision(min) + ":" + detail::full_precision(max) + ":" +
                         std::string(whole.substr(second + 1));
  try {
    return parse_list(si, option);
  } catch (const InputError& e) {
    const std::string message = e.what();
    const std::string prefix = option + ": ";
    throw InputError(prefix + "in " + quote(whole) + " (SI " + si + "): " +
                     (message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message));
  }
}

struct TimeUnit {
  const char* name;
  double to_si;
};
constexpr TimeUnit kTimeUnits[] = {{"s", 1.0}, {"ms", 1e-3}, {"min", 60.0}, {"h", 3600.0}};

const char* rate_name(Rate kind) {
  switch (kind) {
    case Rate::kStiffness: return "stiffness";
    case Rate::kSpeed: return "speed";
    case Rate::kForceRate: return "force rate";
  }
  return "rate";
}

const char* rate_units(Rate kind) {
  switch (kind) {
    case Rate::kStiffness: return "N/m, or a force unit over a length unit: N/mm mN/um nN/nm ...";
    case Rate::kSpeed: return "m/s, or a length unit over s ms min: um/s nm/s mm/s ...";
    case Rate::kForceRate: return "N/s, or a force unit over s ms min: mN/s uN/s nN/s ...";
  }
  return "";
}

// Number with an optional "unit/unit" -> SI value > 0.
double parse_rate_impl(std::string_view raw, Rate kind, const std::string& option, const std::string& what) {
  const std::string_view text = trim_blanks(raw);
  const std::string name = std::string(what == "value" ? rate_name(kind) : what.c_str());
  const std::string expected = std::string("expected a number with an optional unit (") + rate_units(kind) + ")";
  if (text.empty()) fail(option, "empty " + name + "; " + expected);
  std::size_t split = 0;
  while (split < text.size()) {
    const char c = text[split];
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-')) break;
    ++split;
  }
  std::string_view unit = text.substr(split);
  if (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
  double value = 0.0;
  const NumberStatus status = detail::parse_decimal(text.substr(0, split), value);
  if (status != NumberStatus::kOk) {
    fail(option, name + " " + (split == 0 ? quote(text) + " is not a number" : number_problem(status, text)) + "; " +
                     expected);
  }
  double si = value;
  if (!unit.empty()) {
    const std::size_t slash = unit.find('/');
    const std::string top(unit.substr(0, slash == std::string_view::npos ? unit.size() : slash));
    const std::string bottom(slash == std::string_view::npos ? "" : unit.substr(slash + 1));
    const auto numerator = find_unit(top);
    double below = 0.0;
    if (kind == Rate::kStiffness) {
      const auto length = find_unit(bottom);
      if (length && length->kind == Quantity::kLength) below = length->to_si;
    } else {
      for (const TimeUnit& t : kTimeUnits) {
        if (bottom == t.name) below = t.to_si;
      }
    }
    const Quantity top_kind = kind == Rate::kSpeed ? Quantity::kLength : Quantity::kForce;
    if (!numerator || numerator->kind != top_kind || below == 0.0) {
      fail(option, "unknown " + std::string(rate_name(kind)) + " unit " + quote(unit) + " in " + quote(text) +
                       "; " + expected);
    }
    si = to_si(value, numerator->to_si);
    si = below < 1.0 ? si * std::round(1.0 / below) : si / below;
  }
  if (!(value > 0.0)) fail(option, name + " " + quote(text) + " must be > 0");
  if (!std::isfinite(si) || !(si >= kMinQuantity && si <= kMaxQuantity)) {
    fail(option, name + " " + quote(text) + " is outside the allowed range [1e-100, 1e100] (SI units)");
  }
  return si;
}

}  // namespace

std::vector<double> parse_quantity_list(const std::string& text, Quantity kind, const std::string& option) {
  return parse_si_list(text, option, [&](std::string_view item, const std::string& what) {
    return parse_quantity_impl(item, kind, option, what == "value" ? std::string(quantity_name(kind)) : what);
  });
}

double parse_rate(const std::string& text, Rate kind, const std::string& option) {
  return parse_rate_impl(text, kind, option, "value");
}

std::vector<double> parse_rate_list(const std::string& text, Rate kind, const std::string& option) {
  return parse_si_list(text, option, [&](std::string_view item, const std::string& what) {
    return parse_rate_impl(item, kind, option, what);
  });
}

double parse_quantity(const std::string& text, Quantity kind, const std::string& option) {
  return parse_quantity_impl(text, kind, option, quantity_name(kind));
}

Material parse_material(const std::string& text, const std::string& option) {
  return parse_material_impl(trim_blanks(text), option);
}

Substrate parse_substrate(const std::string& text, const std::string& option) {
  const std::string_view trimmed = trim_blanks(text);
  Substrate substrate;
  if (trimmed == "rigid") {
    substrate.rigid = true;
    return substrate;
  }
  if (trimmed.find(',') == std::string_view::npos && !trimmed.empty()) {
    fail(option, quote(trimmed) + " is neither E,nu nor 'rigid'");
  }
  substrate.material = parse_material_impl(trimmed, option);
  return substrate;
}

// ---- plausibility notes ---------------------------------------------------------

namespace {

// The number of a bare item ("20", " 1e6 "), or nullopt when it carries a unit or is no number.
std::optional<double> bare_number(std::string_view text) {
  double value = 0.0;
  if (detail::parse_decimal(trim_blanks(text), value) != NumberStatus::kOk) return std::nullopt;
  return value;
}

std::string shortest(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

// Comma-separated items of an option's value.
std::vector<std::string> items_of(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    items.emplace_back(trim_blanks(std::string_view(text).substr(start, comma == std::string::npos ? comma : comma - start)));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

void note_modulus(std::vector<std::string>& notes, const std::string& option, const std::string& item) {
  const auto v = bare_number(item);
  if (v && *v > 0.0 && *v < 1e3) {
    notes.push_back(option + " " + item + " is read as " + item + " Pa (a bare number is SI), softer than any solid "
                    "(below 1 kPa); did you mean " + item + "MPa or " + item + "GPa?");
  }
}

void note_length(std::vector<std::string>& notes, const std::string& option, const std::string& item,
                 const std::string& what) {
  const auto v = bare_number(item);
  if (v && *v > 0.1) {
    notes.push_back(option + " " + item + " is read as a " + what + " of " + item + " m (a bare number is SI), "
                    "above 0.1 m; did you mean " + item + "mm, " + item + "um or " + item + "nm?");
  }
}

}  // namespace

std::vector<std::string> plausibility_notes(const Arguments& args) {
  std::vector<std::string> notes;
  for (const char* option : {"--film", "--substrate", "--indenter"}) {
    if (const auto text = args.get(option)) note_modulus(notes, option, items_of(*text).front());
  }
  for (const std::string& layer : args.get_all("--layer")) {
    const std::vector<std::string> items = items_of(layer);
    note_length(notes, "--layer", items.front(), "thickness");
    if (items.size() >= 2) note_modulus(notes, "--layer", items[1]);
  }
  if (const auto text = args.get("--thickness")) note_length(notes, "--thickness", *text, "thickness");
  if (const auto text = args.get("--radius")) note_length(notes, "--radius", *text, "radius");
  std::optional<std::string> radius_text = args.get("--radius");
  if (const auto shape = args.get("--shape"); shape && shape->rfind("sphere:", 0) == 0) {
    radius_text = shape->substr(7);
    note_length(notes, "--shape", *radius_text, "radius");
  }
  if (const auto text = args.get("--work")) {
    const auto v = bare_number(*text);
    if (v && *v > 1.0) {
      notes.push_back("--work " + *text + " is read as " + *text + " J/m2 (a bare number is SI), above 1 J/m2 "
                      "(far above any adhesion measured between solids); did you mean " + *text + "mJ/m2?");
    }
  }
  // Film thicker than the sphere's radius: valid input, but rarely meant (the thickness and
  // radius in different units).
  if (radius_text && args.has("--thickness")) {
    try {
      const double t = parse_quantity(*args.get("--thickness"), Quantity::kLength, "--thickness");
      const double r = parse_quantity(*radius_text, Quantity::kLength, "--radius");
      if (t > r) {
        notes.push_back("the film thickness t = " + shortest(t) + " m is larger than the sphere radius R = " +
                        shortest(r) + " m; check their units");
      }
    } catch (const InputError&) {
      // The command's own parsing reports the bad value.
    }
  }
  return notes;
}

std::vector<std::pair<std::string, std::string>> report_plausibility(const std::string& command,
                                                                    const Arguments& args) {
  std::vector<std::pair<std::string, std::string>> items;
  for (const std::string& note : plausibility_notes(args)) {
    items.emplace_back("note", note);
    progress_pause();
    std::cerr << "coatcontact " << command << ": note: " << note << "\n";
  }
  return items;
}

// ---- arguments -------------------------------------------------------------------

Arguments::Arguments(const std::vector<std::string>& args, const std::vector<OptionSpec>& spec,
                     std::size_t max_positionals) {
  // --help anywhere (before "--") wins over every other problem: the user asked for usage.
  for (const auto& arg : args) {
    if (arg == "--") break;
    if (arg == "--help" || arg == "-h") {
      help_ = true;
      return;
    }
  }
  bool options_ended = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (options_ended || !looks_like_option(arg)) {
      if (positionals_.size() >= max_positionals) {
        throw InputError(max_positionals == 0
                             ? "unexpected argument " + quote(arg) + " (this command takes only options; see --help)"
                             : "unexpected argument " + quote(arg) + " (at most " +
                                   std::to_string(max_positionals) + " arguments; see --help)");
      }
      positionals_.push_back(arg);
      continue;
    }
    if (arg == "--") {
      options_ended = true;
      continue;
    }
    const std::size_t equals = arg.find('=');
    const std::string name = arg.substr(0, equals);
    const OptionSpec* option = arg.rfind("--", 0) == 0 ? find_option(spec, name) : nullptr;
    if (option == nullptr) {
      const std::string hint = did_you_mean(name, spec);
      throw InputError("unknown option " + option_text(name) + (hint.empty() ? " (see --help)" : hint));
    }
    if (values_.count(name) != 0 && !option->repeatable) {
      throw InputError("option " + option_text(name) + " is given more than once");
    }
    if (option->value_name.empty()) {
      if (equals != std::string::npos) throw InputError("option " + option_text(name) + " takes no value");
      values_[name] = "";
      continue;
    }
    std::string value;
    if (equals != std::string::npos) {
      value = arg.substr(equals + 1);
    } else if (i + 1 < args.size() && !looks_like_option(args[i + 1])) {
      value = args[++i];
    } else {
      throw InputError("option " + name + " needs a value (" + option->value_name + ")");
    }
    if (trim_blanks(value).empty()) {
      throw InputError("option " + name + " has an empty value; expected " + option->value_name);
    }
    if (values_.count(name) == 0) values_[name] = value;
    repeated_[name].push_back(value);
  }
  for (const auto& option : spec) {
    if (option.required && values_.count(option.name) == 0) {
      throw InputError("missing required option " + option.name +
                       (option.value_name.empty() ? "" : " " + option.value_name) + " (see --help)");
    }
  }
}

bool Arguments::has(const std::string& name) const { return values_.count(name) != 0; }

std::optional<std::string> Arguments::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string Arguments::require(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw InputError("missing required option " + name + " (see --help)");
  return it->second;
}

std::vector<std::string> Arguments::get_all(const std::string& name) const {
  const auto it = repeated_.find(name);
  return it == repeated_.end() ? std::vector<std::string>{} : it->second;
}

Indenter parse_indenter(const std::string& text, const std::string& option) {
  const Substrate body = parse_substrate(text, option);  // the same "E,nu" | "rigid" syntax
  return Indenter{body.rigid, body.material};
}

Layer parse_layer(const std::string& text, const std::string& option) {
  const std::string_view whole = trim_blanks(text);
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = whole.find(',', start);
    items.emplace_back(trim_blanks(whole.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  const std::string expected = "; expected h,E,nu or h,E,nu,slip (thickness, Young's modulus, Poisson ratio)";
  if (items.size() < 3 || items.size() > 4) fail(option, quote(whole) + " has " + std::to_string(items.size()) + " items" + expected);
  Layer layer;
  layer.thickness = parse_quantity(items[0], Quantity::kLength, option);
  if (!(layer.thickness > 0.0)) {
    fail(option, "thickness " + quote(items[0]) + " is not allowed; it must be > 0");
  }
  layer.material = parse_material(items[1] + "," + items[2], option);
  if (items.size() == 4) {
    if (items[3] != "slip") fail(option, "fourth item " + quote(items[3]) + " is not 'slip'" + expected);
    layer.slip_below = true;
  }
  return layer;
}

OptionSpec layer_option(bool si) {
  return {"--layer", "h,E,nu[,slip]",
          std::string("a layer, top first, repeated (instead of --film; THEORY.md section 12): ") +
              (si ? "thickness (m, or mm um nm)" : "relative thickness (q, u, a/T, eta use the total T)") +
              ", Young's modulus, Poisson ratio; ',slip' makes the interface below it frictionless",
          false, true};
}

Stack parse_stack(const Arguments& args) {
  // In the order of the synopsis, so the first bad option is the one named.
  const std::vector<std::string> layer_texts = args.get_all("--layer");
  if (!layer_texts.empty() && args.has("--film")) {
    fail("--layer", "cannot be combined with --film (--film E1,nu1 is the one-layer spelling)");
  }
  if (layer_texts.size() > Stack::max_layers) {
    fail("--layer", std::to_string(layer_texts.size()) + " layers given; at most " +
                        std::to_string(Stack::max_layers) + " are supported");
  }
  std::vector<Layer> layers;
  if (layer_texts.empty()) {
    if (!args.has("--film")) {
      throw InputError("missing required option --film E1,nu1 (or --layer h,E,nu[,slip], repeated) (see --help)");
    }
    layers.push_back(Layer{1.0, parse_material(args.require("--film"), "--film")});
  } else {
    for (const std::string& text : layer_texts) layers.push_back(parse_layer(text, "--layer"));
  }
  const Substrate substrate = parse_substrate(args.require("--substrate"), "--substrate");
  const auto indenter_text = args.get("--indenter");
  const Indenter indenter = indenter_text ? parse_indenter(*indenter_text, "--indenter") : Indenter{};
  try {
    return Stack(layers, substrate, indenter);
  } catch (const InputError& e) {
    if (layer_texts.empty()) throw;
    throw InputError(std::string("--layer: ") + e.what());
  }
}

double coating_thickness(const Arguments& args, const Stack& stack) {
  if (args.has("--layer")) {
    if (args.has("--thickness")) {
      fail("--thickness", "cannot be combined with --layer (the layers' thicknesses are lengths; T is their sum)");
    }
    return stack.total_thickness();
  }
  return parse_quantity(args.require("--thickness"), Quantity::kLength, "--thickness");
}

OptionSpec film_option() {
  return {"--film", "E1,nu1",
          "film Young's modulus (Pa, or with a unit: kPa MPa GPa) and Poisson ratio (one layer; or --layer)",
          false};
}

OptionSpec substrate_option() {
  return {"--substrate", "E0,nu0|rigid", "substrate Young's modulus and Poisson ratio, or 'rigid'", true};
}

OptionSpec indenter_option() {
  return {"--indenter", "E2,nu2|rigid",
          "indenter Young's modulus and Poisson ratio, or 'rigid' (default); an elastic indenter "
          "makes E_r (1/E_r = 1/E1* + 1/E2*) the reference modulus",
          false};
}

std::string usage(const std::string& command, const std::string& synopsis,
                  const std::string& description, const std::vector<OptionSpec>& spec) {
  std::ostringstream out;
  out << "usage: coatcontact " << command << (synopsis.empty() ? "" : " ") << synopsis << "\n\n"
      << description << "\n\noptions:\n";
  std::vector<std::pair<std::string, std::string>> rows;
  for (const auto& option : spec) {
    std::string left = option.name + (option.value_name.empty() ? "" : " " + option.value_name);
    rows.emplace_back(left, option.help + (option.required ? " (required)" : ""));
  }
  rows.emplace_back("-h, --help", "show this help and exit");
  std::size_t width = 0;
  for (const auto& row : rows) width = std::max(width, row.first.size());
  for (const auto& row : rows) {
    out << "  " << row.first << std::string(width - row.first.size() + 2, ' ') << row.second << "\n";
  }
  return out.str();
}

// ---- TSV formatting --------------------------------------------------------------

std::string format_parameter(double value, const std::string& name) { return detail::table_parameter(value, name); }

void add_material_header(std::vector<std::pair<std::string, std::string>>& items, const Stack& stack) {
  detail::add_stack_header_items(items, stack);
}

std::string format_value(double value, const std::string& column) { return detail::table_value(value, column); }

OptionSpec strict_option() {
  return {"--strict", "",
          "stop at the first point whose tolerance cannot be met (exit 3, no output); default: write every "
          "other point, that one as a '# not delivered' row",
          false};
}

OptionSpec tol_option(const std::string& default_text) {
  return {"--tol", "T", "relative tolerance of the solver's values, allowed 1e-13..1e-1 (default " + default_text + ")",
          false};
}

void require_some_delivered(const std::vector<PointStatus>& status, const std::string& what) {
  if (status.empty() || failed_points(status) < status.size()) return;
  // One point: its own message, as the strict run gives it.
  if (status.size() == 1) throw NumericalError(status.front().reason);
  throw NumericalError("no " + what + " of " + std::to_string(status.size()) +
                       " could be delivered; the first: " + status.front().reason);
}

void report_not_delivered(std::vector<std::pair<std::string, std::string>>& items, const std::string& command,
                          const std::vector<PointStatus>& status,
                          const std::function<std::string(std::size_t)>& where) {
  const std::size_t failed = failed_points(status);
  if (failed == 0) return;
  std::size_t first = 0;
  while (status[first].delivered) ++first;
  const std::string count = std::to_string(failed) + " of " + std::to_string(status.size());
  items.emplace_back("points not delivered",
                     count + " (each a '# not delivered' row in its place, with its reason; --strict: exit 3 instead)");
  progress_pause();
  std::cerr << "coatcontact " << command << ": warning: " << count << " points not delivered (the first: "
            << where(first) << ": " << one_line(status[first].reason) << "); the others are written\n";
}

void write_not_delivered(std::ostream& out, const std::string& where, const std::string& reason) {
  out << "# not delivered: " << one_line(where) << ": " << one_line(reason) << "\n";
}

void write_header(std::ostream& out, const std::vector<std::pair<std::string, std::string>>& items,
                  const std::vector<std::string>& columns) {
  detail::write_table_header(out, command_line(), items, columns);
}

void write_row(std::ostream& out, const std::vector<double>& values,
               const std::vector<std::string>& columns) {
  if (values.size() != columns.size()) {
    throw std::logic_error("write_row: " + std::to_string(values.size()) + " values for " +
                           std::to_string(columns.size()) + " columns");
  }
  std::string line;  // format all first: a NumericalError leaves no partial row
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i != 0) line += '\t';
    line += format_value(values[i], columns[i]);
  }
  line += '\n';
  out << line;
}

int run_guarded(const std::string& command, const std::function<int()>& body) {
  const std::string prefix = "coatcontact " + command + ": ";
  ProgressScope progress(command);
  try {
    const int code = body();
    progress_pause();
    return code;
  } catch (const InputError& error) {
    progress_pause();
    std::cerr << prefix << "error: " << error.what() << "\n";
    return kExitUsage;
  } catch (const NumericalError& error) {
    progress_pause();
    std::cerr << prefix << "numerical failure: " << error.what() << "\n";
    return kExitNumerical;
  } catch (const std::bad_alloc&) {
    // Inputs are bounded before work starts (check_rows, list and file limits); what is left
    // is a machine with less memory than the request needs: say so, not "std::bad_alloc".
    progress_pause();
    std::cerr << prefix << "not enough memory for this request; nothing was written (ask for fewer points, "
                           "a narrower range, or run on a machine with more memory)\n";
    return kExitNumerical;
  } catch (const std::exception& error) {
    progress_pause();
    std::cerr << prefix << "internal error: " << error.what() << "\n";
    return kExitNumerical;
  } catch (...) {
    std::cerr << prefix << "internal error: unknown exception\n";
    return kExitNumerical;
  }
}

}  // namespace cli
}  // namespace coatcontact
