// `pulloff --spring-bar LIST` (THEORY.md section 10): the pull-off through a spring of each
// normalized stiffness, as extra columns of the pulloff table (one row per (eta, k_bar)).
#pragma once
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/cli_support.hpp"

namespace coatcontact::cli {

OptionSpec spring_bar_option();

// Every k_bar >= 0, "inf" allowed; "v1,v2,..." or "MIN:MAX:N" (log-spaced, MIN > 0).
std::vector<double> parse_spring_bar(const std::string& text, const std::string& option);

// The spring pull-offs of every eta and k_bar (empty without --spring-bar).
class SpringRows {
 public:
  SpringRows(const Arguments& args, const AdhesiveModel& model, const std::vector<double>& etas);
  bool empty() const { return k_bars_.empty(); }
  // Header lines (k_bar list, criterion, warnings) and the four extra columns.
  void describe(std::vector<std::pair<std::string, std::string>>& header) const;
  void extend(std::vector<std::string>& columns) const;
  // The rows of eta number `index`: `base` (the existing columns) followed by k_bar, P, a_bar, D
  // and `tail` (columns after the spring's, the same on every row of the eta).
  void write(std::ostream& out, std::size_t index, const std::vector<double>& base,
             const std::vector<std::string>& columns, const std::vector<double>& tail = {}) const;

 private:
  std::vector<double> k_bars_;
  std::vector<std::vector<SpringPulloff>> rows_;  // [eta][k_bar]
};

}  // namespace coatcontact::cli
