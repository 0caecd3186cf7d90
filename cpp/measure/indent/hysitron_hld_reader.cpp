// Hysitron HighLoad .hld: "key: value" header lines (transducer calibration, segments with
// their times), then blocks "<Name> Data Points: N", a tab-separated line of columns named
// "<quantity>_<unit>" (Time_s, Disp_nm, Force_µN, ...) and N lines of numbers. The "Test Data"
// block is the test; the others (approach, drift) are counted in the metadata.
#include <algorithm>
#include <cmath>

#include "indent_support.hpp"

namespace coatcontact::indent::detail {

namespace {

constexpr std::string_view kDataPoints = " Data Points";

// A header key seen again ("Segment Time" once per segment) gets " (2)", " (3)", ...
void add_metadata(IndentTest& test, const std::string& key, const std::string& value) {
  std::string name = key;
  for (int k = 2; test.metadata.count(name) != 0; ++k) name = key + " (" + std::to_string(k) + ")";
  test.metadata[name] = value;
}

// The leading number of "4.67914 s"; false if none.
bool leading_number(std::string_view value, double& out) {
  value = trim(value);
  const auto space = value.find(' ');
  return parse_number(value.substr(0, space), out);
}

// The segment of each time: the last segment that begins at or before it (the header's
// "Segment Begin Time" and "Segment Number" lines, in order).
void assign_segments(IndentTest& test, const std::vector<double>& begins, const std::vector<int>& numbers) {
  if (begins.empty() || begins.size() != numbers.size() || test.time.empty()) return;
  test.segment.resize(test.time.size());
  for (std::size_t i = 0; i < test.time.size(); ++i) {
    std::size_t k = 0;
    while (k + 1 < begins.size() && begins[k + 1] <= test.time[i]) ++k;
    test.segment[i] = numbers[k];
  }
}

struct Block {
  std::string name;
  std::size_t points = 0;
};

// The test block's columns into the test's channels; the data lines follow.
void read_test_block(Lines& lines, const Block& block, IndentTest& test, const std::string& file, std::size_t bytes) {
  std::string_view line;
  if (!lines.next(line)) fail(file, "", lines.number(), "the test data block has no column names");
  const std::size_t header_line = lines.number();
  const auto names = split(line, '\t');
  std::vector<std::vector<double>*> target(names.size());
  std::vector<double> factor(names.size(), 1.0);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string column = to_utf8(trim(names[k]));
    const auto cut = column.rfind('_');
    const std::string quantity = cut == std::string::npos ? column : column.substr(0, cut);
    SiUnit si;
    if (cut == std::string::npos || !si_unit(column.substr(cut + 1), si)) {
      target[k] = &test.extra[column];  // no unit we know: kept as named
      continue;
    }
    factor[k] = si.factor;
    if (quantity == "Disp" && si.name == "m") target[k] = &test.depth;
    else if (quantity == "Force" && si.name == "N") target[k] = &test.load;
    else if (quantity == "Time" && si.name == "s") target[k] = &test.time;
    else target[k] = &test.extra[quantity + " [" + si.name + "]"];
  }
  const std::size_t room = std::min(block.points, bytes / (2 * names.size()) + 1);
  for (auto* t : target) t->reserve(room);
  for (std::size_t i = 0; i < block.points; ++i) {
    if (!lines.next(line)) fail(file, "", lines.number(), "the test data block ends after " + std::to_string(i) + " of its " + std::to_string(block.points) + " points (truncated?)");
    const auto fields = split(line, '\t');
    if (fields.size() != names.size()) {
      fail(file, "", lines.number(), std::to_string(fields.size()) + " fields, the block's header (line " + std::to_string(header_line) + ") names " + std::to_string(names.size()));
    }
    for (std::size_t k = 0; k < fields.size(); ++k) {
      double value = 0.0;
      if (!parse_number(fields[k], value)) fail(file, "", lines.number(), "field " + std::to_string(k + 1) + " is not a number");
      target[k]->push_back(scale(value, factor[k]));
    }
  }
  if (test.depth.empty() || test.load.empty()) fail(file, "", header_line, "the test data block has no Disp_nm and Force_µN columns");
}

}  // namespace

std::vector<IndentTest> read_hysitron_hld(const std::string& text, const std::string& file) {
  IndentTest test;
  Lines lines(text);
  std::string_view line;
  std::vector<double> begins;
  std::vector<int> numbers;
  bool have_test = false;
  while (lines.next(line)) {
    const auto t = trim(line);
    if (t.empty()) continue;
    const auto colon = t.find(':');
    if (colon == std::string_view::npos) fail(file, "", lines.number(), "neither 'key: value' nor a data block");
    const std::string key = to_utf8(trim(t.substr(0, colon)));
    const std::string value = to_utf8(trim(t.substr(colon + 1)));
    if (ends_with(key, kDataPoints)) {
      double n = 0.0;
      if (!parse_number(value, n) || n < 0 || n > static_cast<double>(kMaxPoints) || n != std::floor(n)) {
        fail(file, "", lines.number(), "'" + key + "': not a whole number of points in 0.." + std::to_string(kMaxPoints));
      }
      const Block block{key.substr(0, key.size() - kDataPoints.size()), static_cast<std::size_t>(n)};
      add_metadata(test, key, value);
      if (block.name == "Test") {
        if (have_test) fail(file, "", lines.number(), "a second test data block");
        read_test_block(lines, block, test, file, text.size());
        have_test = true;
      } else {
        for (std::size_t i = 0; i <= block.points; ++i) {  // its column names and its points
          if (!lines.next(line)) fail(file, "", lines.number(), "the block '" + block.name + "' ends early (truncated?)");
        }
      }
      continue;
    }
    add_metadata(test, key, value);
    double number = 0.0;
    if (key == "Segment Begin Time" && leading_number(value, number)) begins.push_back(number);
    if (key == "Segment Number" && leading_number(value, number) && std::fabs(number) < 1e6) {
      numbers.push_back(static_cast<int>(number));
    }
  }
  if (!have_test) fail(file, "", 0, "no 'Test Data Points' block: not a Hysitron .hld test");
  assign_segments(test, begins, numbers);
  test.name = file.substr(file.find_last_of('/') + 1);
  if (ends_with(test.name, ".hld")) test.name.resize(test.name.size() - 4);
  test.metadata["format"] = indent_format_name(IndentFormat::kHysitronHld);
  finish_test(test, file, "");
  std::vector<IndentTest> tests;
  tests.push_back(std::move(test));
  return tests;
}

}  // namespace coatcontact::indent::detail
