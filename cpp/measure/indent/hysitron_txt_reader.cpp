// Hysitron (Bruker TI) text export: a date line, "Number of Points = N", a tab-separated header
// "Depth (nm)  Load (µN)  Time (s)  Depth (V)  Load (V)", then N lines of numbers, a blank line
// between segments (numbered from 0 here).
#include <algorithm>
#include <cmath>

#include "indent_support.hpp"

namespace coatcontact::indent::detail {

namespace {

// "Depth (nm)" -> name "Depth", unit "nm"; no parentheses: unit "".
void name_and_unit(std::string_view column, std::string& name, std::string& unit) {
  column = trim(column);
  const auto open = column.rfind('(');
  if (open == std::string_view::npos || column.back() != ')') {
    name = std::string(column);
    unit.clear();
    return;
  }
  name = std::string(trim(column.substr(0, open)));
  unit = std::string(column.substr(open + 1, column.size() - open - 2));
}

struct Column {
  std::vector<double>* target = nullptr;  // depth, load, time or an extra channel
  double factor = 1.0;
};

}  // namespace

std::vector<IndentTest> read_hysitron_txt(const std::string& text, const std::string& file) {
  IndentTest test;
  Lines lines(text);
  std::string_view line;
  std::size_t declared = 0;
  bool have_count = false;
  // The lines before the column names: the date and "Number of Points = N".
  while (lines.next(line)) {
    const auto t = trim(line);
    if (t.empty()) continue;
    const auto eq = t.find('=');
    if (t.rfind("Number of Points", 0) == 0 && eq != std::string_view::npos) {
      double n = 0.0;
      if (!parse_number(t.substr(eq + 1), n) || n < 1 || n > static_cast<double>(kMaxPoints) || n != std::floor(n)) {
        fail(file, "", lines.number(), "the number of points is not a whole number in 1.." + std::to_string(kMaxPoints));
      }
      declared = static_cast<std::size_t>(n);
      have_count = true;
      continue;
    }
    if (t.find('\t') != std::string_view::npos && t.find('(') != std::string_view::npos) break;  // column names
    if (test.metadata.count("date") == 0) test.metadata["date"] = to_utf8(t);
  }
  if (!have_count) fail(file, "", 0, "no 'Number of Points = N' line: not a Hysitron text export");
  const auto names = split(line, '\t');
  const std::size_t header_line = lines.number();
  std::vector<Column> columns(names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::string name, unit;
    name_and_unit(names[k], name, unit);
    SiUnit si;
    if (!si_unit(unit, si)) {
      if (name == "Depth" || name == "Load" || name == "Time") {
        fail(file, "", header_line, "column '" + to_utf8(name) + "': unknown unit '" + to_utf8(unit) + "'");
      }
      si = SiUnit{1.0, to_utf8(unit)};  // kept as written
    }
    columns[k].factor = si.factor;
    if (name == "Depth" && si.name == "m") columns[k].target = &test.depth;
    else if (name == "Load" && si.name == "N") columns[k].target = &test.load;
    else if (name == "Time" && si.name == "s") columns[k].target = &test.time;
    else columns[k].target = &test.extra[to_utf8(name) + " [" + si.name + "]"];
  }
  // Reserve no more than the bytes can hold (a declared count does not drive the allocation).
  const std::size_t room = std::min(declared, text.size() / (2 * names.size()) + 1);
  for (auto& c : columns) c.target->reserve(room);
  test.segment.reserve(room);
  std::size_t count = 0;
  int segment = 0;
  bool after_blank = false;
  while (lines.next(line)) {
    if (trim(line).empty()) {  // a blank line ends a segment (load, hold, unload, ...)
      after_blank = count > 0;
      continue;
    }
    if (after_blank) ++segment;
    after_blank = false;
    const auto fields = split(line, '\t');
    if (fields.size() != columns.size()) {
      fail(file, "", lines.number(), std::to_string(fields.size()) + " fields, the header names " + std::to_string(columns.size()));
    }
    if (++count > declared) fail(file, "", lines.number(), "more data lines than the " + std::to_string(declared) + " points declared");
    for (std::size_t k = 0; k < fields.size(); ++k) {
      double value = 0.0;
      if (!parse_number(fields[k], value)) fail(file, "", lines.number(), "field " + std::to_string(k + 1) + " is not a number");
      columns[k].target->push_back(scale(value, columns[k].factor));
    }
    test.segment.push_back(segment);
  }
  if (count != declared) {
    fail(file, "", lines.number(), "the file declares " + std::to_string(declared) + " points and holds " +
                                       std::to_string(count) + " (truncated?)");
  }
  if (test.depth.empty() || test.load.empty()) fail(file, "", header_line, "no 'Depth (nm)' and 'Load (µN)' columns");
  test.name = file.substr(file.find_last_of('/') + 1);
  if (ends_with(test.name, ".txt")) test.name.resize(test.name.size() - 4);
  test.metadata["format"] = indent_format_name(IndentFormat::kHysitronTxt);
  test.metadata["Number of Points"] = std::to_string(declared);
  finish_test(test, file, "");
  std::vector<IndentTest> tests;
  tests.push_back(std::move(test));
  return tests;
}

}  // namespace coatcontact::indent::detail
