// The --spring-bar option of `pulloff` (THEORY.md section 10).
#include "pulloff_spring.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace coatcontact::cli {

namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

}  // namespace

OptionSpec spring_bar_option() {
  return {"--spring-bar", "LIST",
          "pull-off through a spring of normalized stiffness k_bar = k (pi^2 w^2 R/E*^2)^(1/3)/(pi w R), "
          "each >= 0 or inf (0: load control, inf: displacement control): v1,v2,... or MIN:MAX:N",
          false};
}

std::vector<double> parse_spring_bar(const std::string& text, const std::string& option) {
  if (text.find(':') != std::string::npos) return parse_list(text, option);  // log-spaced, > 0
  std::vector<double> values;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const std::string value = trim(item);
    if (value == "inf") {
      values.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    const double k = parse_number(value, option);  // names the option and the value
    if (!(k >= 0.0)) {
      throw InputError(option + ": value " + quoted(value) + " not allowed (k_bar must be >= 0, or inf)");
    }
    values.push_back(k);
  }
  if (values.empty() || text.back() == ',') {
    throw InputError(option + ": " + quoted(text) + " is not a list of stiffnesses (e.g. 0,0.1,1,inf)");
  }
  return values;
}

SpringRows::SpringRows(const Arguments& args, const AdhesiveModel& model, const std::vector<double>& etas) {
  const auto text = args.get("--spring-bar");
  if (!text) return;
  k_bars_ = parse_spring_bar(*text, "--spring-bar");
  for (double eta : etas) {
    std::vector<SpringPulloff> row;
    for (double k : k_bars_) row.push_back(model.pulloff_spring(eta, k));
    rows_.push_back(std::move(row));
  }
}

void SpringRows::describe(std::vector<std::pair<std::string, std::string>>& header) const {
  if (empty()) return;
  std::string list;
  for (double k : k_bars_) list += (list.empty() ? "" : ",") + (std::isinf(k) ? std::string("inf") : format_parameter(k, "k_bar"));
  header.emplace_back("k_bar", list);
  header.emplace_back("spring control",
                      "jump where dP/dD = -k_bar: minimum of Z = D + P/k_bar over a_bar, root of dZ/da_bar "
                      "(THEORY.md section 10); k_bar = 0 and inf are the load and displacement values");
  for (const auto& row : rows_) {
    for (const auto& p : row) {
      if (std::isinf(p.k_bar) || p.k_bar == 0.0) continue;  // the limits' warnings are listed already
      for (const auto& w : p.warnings) header.emplace_back("warning", w);
    }
  }
}

void SpringRows::extend(std::vector<std::string>& columns) const {
  if (empty()) return;
  for (const char* c : {"k_bar", "P_spring", "a_bar_spring", "D_spring"}) columns.emplace_back(c);
}

void SpringRows::write(std::ostream& out, std::size_t index, const std::vector<double>& base,
                       const std::vector<std::string>& columns, const std::vector<double>& tail) const {
  for (const SpringPulloff& p : rows_[index]) {
    std::vector<double> values = base;
    // k_bar = inf is printed as its own line of text: write_row refuses non-finite values.
    values.insert(values.end(), {std::isinf(p.k_bar) ? 0.0 : p.k_bar, p.point.load, p.point.a_bar,
                                 p.point.penetration});
    values.insert(values.end(), tail.begin(), tail.end());
    if (!std::isinf(p.k_bar)) {
      write_row(out, values, columns);
      continue;
    }
    std::ostringstream line;
    write_row(line, values, columns);
    // Replace the k_bar field (column base.size()) by "inf".
    std::string text = line.str();
    std::size_t start = 0;
    for (std::size_t c = 0; c < base.size(); ++c) start = text.find('\t', start) + 1;
    const std::size_t end = text.find('\t', start);
    out << text.substr(0, start) << "inf" << text.substr(end);
  }
}

}  // namespace coatcontact::cli
