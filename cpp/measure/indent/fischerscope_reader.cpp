// Helmut Fischer FischerScope text export of a .hap application: a header ("<value> <tab>
// <description>" lines, the test parameters "F = ...", per-block tables and statistics), then
// per test a header ("<app>.hap  <date> <time>", "HM <F>/<t>/<..>= <HM>", "Block : b  Value : v",
// "x= .. y= ..", the works We and Wr, "Epsilon = ..") and the lines "F <tab> h <tab> t" with
// decimal commas: force [mN], indentation depth [µm], time [s] (the instrument's units, which
// the file does not name; the header's "F = ESP n 300.000mN" and its HM agree with them).
#include <algorithm>

#include "indent_support.hpp"

namespace coatcontact::indent::detail {

namespace {

bool starts_with(std::string_view text, std::string_view head) { return text.substr(0, head.size()) == head; }

// "x=    44.65  y=     6.01" -> metadata "x", "y".
void read_position(std::string_view line, IndentTest& test) {
  const auto y = line.find("y=");
  test.metadata["x"] = std::string(trim(line.substr(2, y == std::string_view::npos ? std::string_view::npos : y - 2)));
  if (y != std::string_view::npos) test.metadata["y"] = std::string(trim(line.substr(y + 2)));
}

// A vendor result "name <tab> [unit] <tab> value": in SI into vendor_results, pressures under
// their name ("HIT", "EIT/(1-vs^2)"), other quantities with their SI unit ("hmax [m]").
void read_result(const std::string& key, const std::vector<std::string_view>& fields, IndentTest& test) {
  if (fields.size() < 3) return;
  std::string_view unit = trim(fields[1]);
  double value = 0.0;
  SiUnit si;
  if (unit.size() < 2 || unit.front() != '[' || unit.back() != ']' || !parse_number(fields[2], value) ||
      !si_unit(std::string(unit.substr(1, unit.size() - 2)), si)) {
    return;
  }
  test.vendor_results[si.name == "Pa" ? key : key + " [" + si.name + "]"] = scale(value, si.factor);
}

// One line of a test's header (before its "F h t" line).
void read_test_header(std::string_view line, IndentTest& test, const std::string& file, std::size_t number) {
  const auto t = trim(line);
  if (t.empty()) return;
  if (starts_with(t, "Block :")) {
    const auto value = t.find("Value :");
    std::string block(trim(t.substr(7, value == std::string_view::npos ? std::string_view::npos : value - 7)));
    test.name = "Block " + block;
    if (value != std::string_view::npos) test.name += " Value " + std::string(trim(t.substr(value + 7)));
  } else if (starts_with(t, "HM ")) {
    test.metadata["HM"] = to_utf8(trim(t.substr(2)));
    const auto eq = t.rfind('=');
    double hm = 0.0;
    if (eq != std::string_view::npos && parse_number(t.substr(eq + 1), hm)) test.vendor_results["HM"] = scale(hm, 1e6);  // N/mm^2
  } else if (starts_with(t, "x=")) {
    read_position(t, test);
  } else if (t.find("Epsilon =") != std::string_view::npos) {
    const auto at = t.find("Epsilon =");
    double eps = 0.0;
    if (!parse_number(t.substr(at + 9), eps)) fail(file, test.name, number, "Epsilon is not a number");
    test.calibration.eps = eps;
    test.calibration.source = "the file's power-law tangent line";
    test.metadata["tangent range"] = std::string(trim(t.substr(0, at)));
  } else if (t.find('\t') != std::string_view::npos) {  // "HIT <tab> [N/mm²] <tab> 8289.9", "We <tab> [µJ] <tab> 0.1 <tab> 79%"
    const auto fields = split(t, '\t');
    std::string value;
    for (std::size_t k = 1; k < fields.size(); ++k) value += (k > 1 ? " " : "") + std::string(trim(fields[k]));
    const std::string key = to_utf8(trim(fields[0]));
    test.metadata[key] = to_utf8(value);
    read_result(key, fields, test);
  } else {
    const auto colon = t.find(':');
    if (colon != std::string_view::npos) {
      test.metadata[to_utf8(trim(t.substr(0, colon)))] = to_utf8(trim(t.substr(colon + 1)));
    } else {
      int notes = 1;
      while (test.metadata.count("note " + std::to_string(notes)) != 0) ++notes;
      test.metadata["note " + std::to_string(notes)] = to_utf8(t);
    }
  }
}

// A file header line: "<value> <tab> <description>" or "F = ...".
void read_file_header(std::string_view line, std::map<std::string, std::string>& header) {
  const auto t = trim(line);
  const auto fields = split(t, '\t');
  if (fields.size() == 2) {
    header[to_utf8(trim(fields[1]))] = to_utf8(trim(fields[0]));
  } else if (fields.size() == 1 && t.size() > 3 && t[1] == ' ' && t[2] == '=') {
    header["parameter " + std::string(1, t[0])] = to_utf8(trim(t.substr(3)));
  }
}

}  // namespace

std::vector<IndentTest> read_fischerscope_txt(const std::string& text, const std::string& file) {
  std::vector<IndentTest> tests;
  std::map<std::string, std::string> header;
  Lines lines(text);
  std::string_view line;
  bool data = false;
  const auto finish = [&]() {
    if (tests.empty()) return;
    if (!data) fail(file, tests.back().name, lines.number(), "the test ends before its 'F h t' data lines");
    finish_test(tests.back(), file, tests.back().name);
  };
  while (lines.next(line)) {
    const bool test_start = line.find(".hap") != std::string_view::npos && line.find('\t') == std::string_view::npos;
    if (test_start) {
      finish();
      if (tests.size() >= kMaxTests) fail(file, "", lines.number(), "more than " + std::to_string(kMaxTests) + " tests");
      tests.emplace_back();
      IndentTest& test = tests.back();
      test.metadata = header;
      test.metadata["format"] = indent_format_name(IndentFormat::kFischerScopeTxt);
      test.metadata["date"] = to_utf8(trim(line.substr(line.find(".hap") + 4)));
      test.name = "test " + std::to_string(tests.size());
      data = false;
      continue;
    }
    if (tests.empty()) {
      read_file_header(line, header);
      continue;
    }
    IndentTest& test = tests.back();
    if (!data) {
      if (trim(line) == "F\th\tt") data = true;
      else read_test_header(line, test, file, lines.number());
      continue;
    }
    if (trim(line).empty()) continue;
    const auto fields = split(trim(line), '\t');
    double v[3];
    if (fields.size() != 3) fail(file, test.name, lines.number(), std::to_string(fields.size()) + " fields; three expected (F [mN], h [µm], t [s])");
    for (int k = 0; k < 3; ++k) {
      if (!parse_number(fields[k], v[k], true)) fail(file, test.name, lines.number(), "field " + std::to_string(k + 1) + " is not a number with a decimal comma");
    }
    if (test.depth.size() >= kMaxPoints) fail(file, test.name, lines.number(), "more than " + std::to_string(kMaxPoints) + " points");
    test.load.push_back(scale(v[0], 1e-3));
    test.depth.push_back(scale(v[1], 1e-6));
    test.time.push_back(v[2]);
  }
  finish();
  if (tests.empty()) fail(file, "", lines.number(), "no test ('<application>.hap <date> <time>' line): not a FischerScope export");
  return tests;
}

}  // namespace coatcontact::indent::detail
