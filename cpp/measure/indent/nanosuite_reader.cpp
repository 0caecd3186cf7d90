// Agilent/KLA NanoSuite export (legacy Excel, BIFF8, read through FreeXL): one sheet per test
// ("Test 001"...: row 1 the column names, row 2 their units, then one row per point, the first
// column naming each segment where it begins, "END" after the last point), a "Results" sheet
// (per test the software's E and H averaged over the defined range, the tip's name and
// area-function coefficients), and the inputs sheets "Required Inputs" and "Inputs Editable
// Post Test" (per test Poisson's ratio, frame stiffness corrections, the averaging range).
#include <freexl.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "indent_support.hpp"

namespace coatcontact::indent::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An open workbook; one sheet is active at a time.
class Workbook {
 public:
  explicit Workbook(const std::string& path) : path_(path) {
    const int status = freexl_open(path.c_str(), &handle_);
    if (status != FREEXL_OK) {
      if (handle_ != nullptr) freexl_close(handle_);
      handle_ = nullptr;
      fail(path, "", 0, "not a readable Excel 97-2003 (.xls, BIFF) workbook (FreeXL error " + std::to_string(status) + ")");
    }
  }
  ~Workbook() {
    if (handle_ != nullptr) freexl_close(handle_);
  }
  Workbook(const Workbook&) = delete;
  Workbook& operator=(const Workbook&) = delete;

  unsigned sheets() const {
    unsigned count = 0;
    if (freexl_get_info(handle_, FREEXL_BIFF_SHEET_COUNT, &count) != FREEXL_OK) fail(path_, "", 0, "cannot count the sheets");
    return count;
  }
  std::string sheet_name(unsigned index) const {
    const char* name = nullptr;
    if (freexl_get_worksheet_name(handle_, static_cast<unsigned short>(index), &name) != FREEXL_OK || name == nullptr) return {};
    return name;
  }
  // Makes sheet `index` active; its rows and columns.
  void select(unsigned index, const std::string& name) {
    sheet_ = name;
    if (freexl_select_active_worksheet(handle_, static_cast<unsigned short>(index)) != FREEXL_OK ||
        freexl_worksheet_dimensions(handle_, &rows_, &columns_) != FREEXL_OK) {
      fail(path_, "sheet '" + name + "'", 0, "cannot be read");
    }
  }
  unsigned rows() const { return rows_; }
  unsigned columns() const { return columns_; }
  const std::string& sheet() const { return sheet_; }
  const std::string& path() const { return path_; }

  // A cell as text (numbers in shortest form) and as number; empty / false if absent.
  bool number(unsigned row, unsigned column, double& value) const {
    FreeXL_CellValue cell{};
    if (freexl_get_cell_value(handle_, row, static_cast<unsigned short>(column), &cell) != FREEXL_OK) return false;
    if (cell.type == FREEXL_CELL_INT) value = cell.value.int_value;
    else if (cell.type == FREEXL_CELL_DOUBLE) value = cell.value.double_value;
    else if (cell.type == FREEXL_CELL_TEXT || cell.type == FREEXL_CELL_SST_TEXT) return cell.value.text_value != nullptr && parse_number(cell.value.text_value, value);
    else return false;
    return true;
  }
  std::string text(unsigned row, unsigned column) const {
    FreeXL_CellValue cell{};
    if (freexl_get_cell_value(handle_, row, static_cast<unsigned short>(column), &cell) != FREEXL_OK) return {};
    switch (cell.type) {
      case FREEXL_CELL_INT: return std::to_string(cell.value.int_value);
      case FREEXL_CELL_DOUBLE: return number_text(cell.value.double_value);
      case FREEXL_CELL_NULL: return {};
      default: return cell.value.text_value != nullptr ? std::string(trim(cell.value.text_value)) : std::string();
    }
  }
  bool empty(unsigned row, unsigned column) const {
    FreeXL_CellValue cell{};
    return freexl_get_cell_value(handle_, row, static_cast<unsigned short>(column), &cell) != FREEXL_OK || cell.type == FREEXL_CELL_NULL;
  }
  // "sheet 'Test 001', cell B5" for messages.
  [[noreturn]] void fail_at(unsigned row, unsigned column, const std::string& message) const {
    std::string letters;
    for (unsigned c = column + 1; c > 0; c = (c - 1) / 26) letters.insert(letters.begin(), static_cast<char>('A' + (c - 1) % 26));
    fail(path_, "sheet '" + sheet_ + "', cell " + letters + std::to_string(row + 1), 0, message);
  }

 private:
  std::string path_, sheet_;
  const void* handle_ = nullptr;
  unsigned rows_ = 0;
  unsigned short columns_ = 0;
};

// NanoSuite writes DBL_MAX where a quantity has no value (before contact, during unloading).
double vendor_value(double value) { return value >= DBL_MAX ? kNaN : value; }

// The "Test NNN" number of a sheet name or a Results/inputs row; -1 if none.
long test_number(const std::string& text) {
  std::string digits = text.rfind("Test ", 0) == 0 ? text.substr(5) : text;
  double value = 0.0;
  if (!parse_number(digits, value) || value < 0 || value > 1e9 || value != std::floor(value)) return -1;
  return static_cast<long>(value);
}

// The column's unit into SI, as a factor and the SI unit's name.
SiUnit unit_of(const Workbook& book, unsigned column) {
  SiUnit si;
  const std::string unit = book.text(1, column);
  if (unit.empty() || !si_unit(unit, si)) si = SiUnit{1.0, unit};
  return si;
}

void read_test_sheet(Workbook& book, IndentTest& test) {
  const unsigned columns = book.columns();
  if (book.rows() < 3 || columns < 2) book.fail_at(0, 0, "a test sheet needs the column names, their units and data rows");
  std::vector<std::vector<double>*> target(columns, nullptr);
  std::vector<double> factor(columns, 1.0);
  bool segments = false;
  for (unsigned c = 0; c < columns; ++c) {
    const std::string name = book.text(0, c);
    if (c == 0 && name == "Segment") {
      segments = true;
      continue;
    }
    if (name.empty()) continue;
    const SiUnit si = unit_of(book, c);
    factor[c] = si.factor;
    const auto is = [&](const char* column, const char* unit) { return name == column && si.name == unit; };
    if (is("Displacement Into Surface", "m")) target[c] = &test.depth;
    else if (is("Load On Sample", "N")) target[c] = &test.load;
    else if (is("Time On Sample", "s")) target[c] = &test.time;
    else if (is("Harmonic Contact Stiffness", "N/m")) target[c] = &test.stiffness;
    else if (is("Hardness", "Pa")) target[c] = &test.hardness;
    else if (is("Modulus", "Pa")) target[c] = &test.modulus;
    else target[c] = &test.extra[si.name.empty() ? name : name + " [" + si.name + "]"];
  }
  if (std::find(target.begin(), target.end(), &test.depth) == target.end() ||
      std::find(target.begin(), target.end(), &test.load) == target.end()) {
    book.fail_at(0, 0, "no 'Displacement Into Surface' [nm] and 'Load On Sample' [mN] columns");
  }
  for (auto* t : target) if (t != nullptr) t->reserve(book.rows());
  int segment = 0;
  for (unsigned r = 2; r < book.rows(); ++r) {
    const std::string label = segments ? book.text(r, 0) : std::string();
    if (label == "END") break;
    if (!label.empty()) test.metadata["segment " + std::to_string(++segment)] = label;
    bool blank = true;
    for (unsigned c = segments ? 1 : 0; c < columns && blank; ++c) blank = book.empty(r, c);
    if (blank) continue;
    for (unsigned c = 0; c < columns; ++c) {
      if (target[c] == nullptr) continue;
      double value = kNaN;
      if (!book.empty(r, c) && !book.number(r, c, value)) book.fail_at(r, c, "not a number");
      value = vendor_value(value);
      target[c]->push_back(std::isnan(value) ? value : scale(value, factor[c]));
    }
    if (segments) test.segment.push_back(segment);
  }
}

// A per-test table (Results, the inputs sheets): row 1 names, row 2 units, then rows whose first
// cell is the test's number (or a summary: "Mean", "Std. Dev.", "% COV").
void read_results(const Workbook& book, std::map<long, IndentTest*>& by_number, std::map<std::string, std::string>& summary) {
  for (unsigned r = 2; r < book.rows(); ++r) {
    const std::string first = book.text(r, 0);
    const long number = test_number(first);
    const auto found = by_number.find(number);
    for (unsigned c = 1; c < book.columns(); ++c) {
      const std::string name = book.text(0, c);
      const std::string unit = book.text(1, c);
      if (name.empty() || book.empty(r, c)) continue;
      double value = 0.0;
      const bool numeric = book.number(r, c, value);
      if (found == by_number.end()) {  // a summary row
        if (!first.empty()) summary[book.sheet() + ": " + first + ": " + name + (unit.empty() ? "" : " [" + unit + "]")] = book.text(r, c);
        continue;
      }
      IndentTest& test = *found->second;
      Calibration& cal = test.calibration;
      const SiUnit si = unit_of(book, c);
      const double si_value = numeric ? scale(value, si.factor) : kNaN;
      if (name == "E Average Over Defined Range" && numeric) test.vendor_results["E_mean"] = si_value;
      else if (name == "H Average Over Defined Range" && numeric) test.vendor_results["H_mean"] = si_value;
      else if (name == "Tip Name") cal.tip = book.text(r, c);
      else if (name.rfind("Area Coefficient ", 0) == 0 && numeric) {
        const long k = test_number(name.substr(17));
        if (k < 1 || k > 16) book.fail_at(0, c, "area coefficients are numbered 1..16");
        if (cal.area.coefficients.size() < static_cast<std::size_t>(k)) cal.area.coefficients.resize(k, 0.0);
        cal.area.coefficients[k - 1] = value;
      } else if (name == "Poissons Ratio" && numeric) cal.poisson = value;
      else if (name == "Minimum Calculation Depth" && numeric) cal.range_min = si_value;
      else if (name == "Maximum Calculation Depth" && numeric) cal.range_max = si_value;
      // every column also as the file states it
      test.metadata[name + (unit.empty() ? "" : " [" + unit + "]")] = book.text(r, c);
    }
  }
}

}  // namespace

std::vector<IndentTest> read_nanosuite_xls(const std::string& path) {
  Workbook book(path);
  const unsigned count = book.sheets();
  std::vector<IndentTest> tests;
  std::vector<unsigned> tables;
  for (unsigned s = 0; s < count; ++s) {
    const std::string name = book.sheet_name(s);
    if (name.rfind("Test ", 0) == 0 && test_number(name) >= 0) {
      if (tests.size() >= kMaxTests) fail(path, "", 0, "more than " + std::to_string(kMaxTests) + " test sheets");
      book.select(s, name);
      tests.emplace_back();
      tests.back().name = name;
      read_test_sheet(book, tests.back());
    } else if (name == "Results" || name == "Required Inputs" || name == "Inputs Editable Post Test") {
      tables.push_back(s);
    }
  }
  if (tests.empty()) fail(path, "", 0, "no 'Test NNN' sheet: not a NanoSuite export");
  // NanoSuite writes the last test's sheet first; the tests go out in the order of their numbers.
  std::stable_sort(tests.begin(), tests.end(), [](const IndentTest& a, const IndentTest& b) { return test_number(a.name) < test_number(b.name); });
  std::map<long, IndentTest*> by_number;
  for (auto& test : tests) by_number[test_number(test.name)] = &test;
  std::map<std::string, std::string> summary;
  for (unsigned s : tables) {
    book.select(s, book.sheet_name(s));
    if (book.rows() >= 3) read_results(book, by_number, summary);
  }
  for (auto& test : tests) {
    test.metadata.insert(summary.begin(), summary.end());
    test.metadata["format"] = indent_format_name(IndentFormat::kNanoSuiteXls);
    if (!tables.empty()) test.calibration.source = "NanoSuite Results and inputs sheets";
    finish_test(test, path, "sheet '" + test.name + "'");
  }
  return tests;
}

}  // namespace coatcontact::indent::detail
