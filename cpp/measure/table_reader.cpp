// Reader for measured data tables (format described in data_file.hpp): the measure floor's
// table of numbers, below every reader of a particular kind of measurement.
#include "coatcontact/data_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <iterator>
#include <string_view>

#include "coatcontact/units.hpp"
#include "number_text.hpp"

namespace coatcontact {
namespace {

using detail::NumberStatus;
using detail::quote;
using detail::trim_blanks;

// The separator of a line: ',' when it has one, else ';' (the CSV of spreadsheets set to a
// decimal-comma locale), else runs of blanks (0).
char separator_of(std::string_view line) {
  if (line.find(',') != std::string_view::npos) return ',';
  if (line.find(';') != std::string_view::npos) return ';';
  return 0;
}

std::vector<std::string_view> split_fields(std::string_view line, bool& has_empty_field) {
  std::vector<std::string_view> fields;
  has_empty_field = false;
  if (const char separator = separator_of(line); separator != 0) {
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = line.find(separator, start);
      const std::string_view field =
          trim_blanks(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
      if (field.empty()) has_empty_field = true;
      fields.push_back(field);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return fields;
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

class Reader {
 public:
  Reader(const std::string& name, std::size_t expected_columns, const std::vector<bool>& nonnegative,
         const std::vector<std::optional<Quantity>>& kinds)
      : name_(name), columns_(expected_columns), nonnegative_(nonnegative), kinds_(kinds) {
    if (!nonnegative.empty() && nonnegative.size() != expected_columns) {
      throw std::invalid_argument("read_data: nonnegative flags do not match expected_columns");
    }
    if (!kinds.empty() && kinds.size() != expected_columns) {
      throw std::invalid_argument("read_data: column kinds do not match expected_columns");
    }
    table_.columns.resize(expected_columns);
  }

  DataTable read(std::string_view text) {
    if (text.size() > kMaxDataFileBytes) {
      throw InputError(name_ + ": larger than " + std::to_string(kMaxDataFileBytes / (1024 * 1024)) +
                       " MB; refusing to read it");
    }
    if (text.substr(0, 3) == "\xef\xbb\xbf") text.remove_prefix(3);  // UTF-8 byte-order mark
    int line_number = 0;
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      std::string_view line = text.substr(start, end - start);
      start = end + 1;
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      read_line(line, line_number);
    }
    if (table_.rows() == 0) throw InputError(name_ + ": no data rows");
    apply_units();
    return std::move(table_);
  }

 private:
  [[noreturn]] void fail(int line_number, const std::string& what) const {
    throw InputError(name_ + ":" + std::to_string(line_number) + ": " + what);
  }

  std::string column_label(std::size_t c) const {
    std::string label = "column " + std::to_string(c + 1);
    if (c < table_.column_names.size()) label += " (" + table_.column_names[c] + ")";
    return label;
  }

  void read_line(std::string_view line, int line_number) {
    const std::string_view trimmed = trim_blanks(line);
    if (trimmed.empty()) return;
    if (trimmed.front() == '#') {
      read_comment(trimmed.substr(1), line_number);
      return;
    }
    const std::size_t hash = line.find('#');  // trailing comment
    if (hash != std::string_view::npos) line = line.substr(0, hash);

    bool has_empty_field = false;
    const std::vector<std::string_view> fields = split_fields(trim_blanks(line), has_empty_field);
    std::vector<double> values(fields.size());
    std::vector<NumberStatus> status(fields.size());
    std::size_t numeric = 0;
    for (std::size_t c = 0; c < fields.size(); ++c) {
      status[c] = detail::parse_decimal(fields[c], values[c]);
      if (status[c] == NumberStatus::kOk) ++numeric;
    }

    const bool first_content_line = !seen_content_;
    seen_content_ = true;
    if (first_content_line && numeric == 0 && !has_empty_field &&
        !any_status(status, NumberStatus::kNotFinite) && !any_status(status, NumberStatus::kOutOfRange) &&
        !any_status(status, NumberStatus::kSubnormal)) {
      // Header: names only.
      adopt_column_count(fields.size());
      if (fields.size() != columns_) {
        fail(line_number, "header has " + std::to_string(fields.size()) + " column names, expected " +
                              std::to_string(columns_));
      }
      for (const auto& field : fields) table_.column_names.emplace_back(field);
      return;
    }

    if (has_empty_field) fail(line_number, "empty field (two separators in a row or at the end of the line)");
    adopt_column_count(fields.size());
    if (fields.size() != columns_) {
      fail(line_number, "expected " + std::to_string(columns_) + " columns, found " +
                            std::to_string(fields.size()));
    }
    for (std::size_t c = 0; c < columns_; ++c) {
      switch (status[c]) {
        case NumberStatus::kOk: break;
        case NumberStatus::kNotFinite:
          fail(line_number, column_label(c) + ": " + quote(fields[c]) + " is not a finite number");
        case NumberStatus::kOutOfRange:
          fail(line_number, column_label(c) + ": " + quote(fields[c]) + " is outside the range of a double");
        case NumberStatus::kNotNumber:
          fail(line_number, column_label(c) + ": " + quote(fields[c]) + " is not a number");
        case NumberStatus::kSubnormal:
          fail(line_number, column_label(c) + ": " + quote(fields[c]) +
                                " is too small (nonzero values need a magnitude of at least 2.2250738585072014e-308)");
      }
      if (!nonnegative_.empty() && nonnegative_[c] && values[c] < 0.0) {
        fail(line_number, column_label(c) + ": value " + std::string(fields[c]) + " must be >= 0");
      }
    }
    if (table_.rows() >= kMaxDataRows) {
      fail(line_number, "more than " + std::to_string(kMaxDataRows) + " data rows; refusing to read more");
    }
    for (std::size_t c = 0; c < columns_; ++c) table_.columns[c].push_back(values[c]);
    table_.line_numbers.push_back(line_number);
  }

  // expected_columns 0: the first header, units line or data row sets the count.
  void adopt_column_count(std::size_t count) {
    if (columns_ != 0) return;
    columns_ = count;
    table_.columns.resize(count);
  }

  static bool any_status(const std::vector<NumberStatus>& status, NumberStatus wanted) {
    for (auto s : status) {
      if (s == wanted) return true;
    }
    return false;
  }

  // "# units: um mN" (after the '#'); "# columns: a F" is remembered (not enforced here).
  void read_comment(std::string_view comment, int line_number) {
    comment = trim_blanks(comment);
    constexpr std::string_view kColumnsKey = "columns:";
    if (comment.substr(0, kColumnsKey.size()) == kColumnsKey && table_.declared_columns.empty()) {
      bool has_empty = false;
      for (const auto name : split_fields(trim_blanks(comment.substr(kColumnsKey.size())), has_empty)) {
        table_.declared_columns.emplace_back(name);
      }
      table_.declared_columns_line = line_number;
      return;
    }
    // "units:" in any letter case: a "# Units:" line silently ignored would leave um as m.
    constexpr std::string_view kKey = "units:";
    if (comment.size() < kKey.size()) return;
    for (std::size_t i = 0; i < kKey.size(); ++i) {
      const char c = comment[i];
      if ((c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c) != kKey[i]) return;
    }
    if (!table_.units.empty()) fail(line_number, "units are declared a second time (first on line " + std::to_string(units_line_) + ")");
    bool has_empty_field = false;
    const std::vector<std::string_view> units = split_fields(trim_blanks(comment.substr(kKey.size())), has_empty_field);
    if (has_empty_field) fail(line_number, "empty unit in the units line");
    adopt_column_count(units.size());
    if (units.size() != columns_) {
      fail(line_number, "units line has " + std::to_string(units.size()) + " units, expected " +
                            std::to_string(columns_) + " (one per column)");
    }
    factors_.assign(columns_, 1.0);
    for (std::size_t c = 0; c < columns_; ++c) {
      const std::string unit(units[c]);
      // has_kind: the caller says what column c is; dimensionless when kind is absent.
      const bool checked = !kinds_.empty();
      const bool has_kind = checked && kinds_[c].has_value();
      const Quantity kind = has_kind ? kinds_[c].value() : Quantity::kLength;
      if (unit == "-" || unit == "1") {
        if (has_kind) {
          fail(line_number, "column " + std::to_string(c + 1) + " is a " + quantity_name(kind) +
                                ", it needs a unit (" + unit_list(kind) + "), not " + quote(unit));
        }
        continue;
      }
      const auto info = find_unit(unit);
      if (!info) fail(line_number, "unknown unit " + quote(unit) + " for column " + std::to_string(c + 1));
      if (checked && (!has_kind || info->kind != kind)) {
        fail(line_number, "unit " + quote(unit) + " of column " + std::to_string(c + 1) + " is a " +
                              quantity_name(info->kind) + " unit, expected " +
                              (has_kind ? std::string(quantity_name(kind)) + " (" + unit_list(kind) + ")"
                                        : std::string("a dimensionless column ('-')")));
      }
      factors_[c] = info->to_si;
    }
    for (const auto& unit : units) table_.units.emplace_back(unit);
    units_line_ = line_number;
  }

  void apply_units() {
    if (factors_.empty()) return;
    for (std::size_t c = 0; c < columns_; ++c) {
      for (std::size_t r = 0; r < table_.rows(); ++r) {
        const double si = to_si(table_.columns[c][r], factors_[c]);
        if (!std::isfinite(si)) {
          fail(table_.line_numbers[r], column_label(c) + ": value " + detail::number_string(table_.columns[c][r]) +
                                           " " + table_.units[c] + " is too large in SI units");
        }
        table_.columns[c][r] = si;
      }
    }
  }

  std::string name_;
  std::size_t columns_;
  std::vector<bool> nonnegative_;
  std::vector<std::optional<Quantity>> kinds_;
  DataTable table_;
  std::vector<double> factors_;
  int units_line_ = 0;
  bool seen_content_ = false;
};

}  // namespace

DataTable read_data_text(const std::string& text, const std::string& name,
                         std::size_t expected_columns, const std::vector<bool>& nonnegative,
                         const std::vector<std::optional<Quantity>>& kinds) {
  return Reader(name, expected_columns, nonnegative, kinds).read(text);
}

std::string read_file_text(const std::string& path) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) {
    throw InputError(short_name(path) + ": cannot read data file: " + std::strerror(errno));
  }
  if (!S_ISREG(info.st_mode)) throw InputError(short_name(path) + ": not a regular file");
  if (static_cast<unsigned long long>(info.st_size) > kMaxDataFileBytes) {
    throw InputError(short_name(path) + ": larger than " + std::to_string(kMaxDataFileBytes / (1024 * 1024)) +
                     " MB; refusing to read it");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(short_name(path) + ": cannot open data file: " + std::strerror(errno));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(short_name(path) + ": read error");
  return text;
}

std::string read_stream_text(std::istream& in, const std::string& name) {
  // Read in pieces and stop one byte past the limit: an endless stream (cat /dev/zero) is
  // refused after 100 MB, not read until memory runs out.
  std::string text;
  std::vector<char> piece(1 << 16);
  while (in) {
    in.read(piece.data(), static_cast<std::streamsize>(piece.size()));
    text.append(piece.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxDataFileBytes) {
      throw InputError(name + ": larger than " + std::to_string(kMaxDataFileBytes / (1024 * 1024)) +
                       " MB; refusing to read more");
    }
  }
  if (in.bad()) throw InputError(name + ": read error");
  return text;
}

std::string short_name(const std::string& text) {
  constexpr std::size_t kMaxShown = 200;
  if (text.size() <= kMaxShown) return text;
  return text.substr(0, kMaxShown / 2) + "...(" + std::to_string(text.size()) + " characters)..." +
         text.substr(text.size() - kMaxShown / 2);
}

DataTable read_data_file(const std::string& path, std::size_t expected_columns,
                         const std::vector<bool>& nonnegative,
                         const std::vector<std::optional<Quantity>>& kinds) {
  return read_data_text(read_file_text(path), short_name(path), expected_columns, nonnegative, kinds);
}

}  // namespace coatcontact
