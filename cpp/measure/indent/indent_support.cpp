// Shared helpers of the nanoindentation readers: messages, bounded file reading, numbers with
// a decimal point or comma, lines, Latin-1 text, vendor units into SI, the test's checks.
#include "indent_support.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sys/stat.h>

#include "coatcontact/units.hpp"
#include "number_text.hpp"

namespace coatcontact::indent::detail {

void fail(const std::string& file, const std::string& where, std::size_t line, const std::string& message) {
  std::string text = file + ": ";
  if (!where.empty()) text += where + ": ";
  if (line > 0) text += "line " + std::to_string(line) + ": ";
  throw InputError(text + message);
}

std::string read_file(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw InputError(path + ": cannot open the file (no such file)");
  if (!S_ISREG(info.st_mode)) throw InputError(path + ": not a regular file");
  if (static_cast<unsigned long long>(info.st_size) > kMaxFileBytes) {
    throw InputError(path + ": the file is larger than " + std::to_string(kMaxFileBytes >> 20) +
                     " MB, more than any indentation export; refused");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": read error");
  if (bytes.empty()) throw InputError(path + ": empty file");
  return bytes;
}

std::string_view trim(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

bool parse_number(std::string_view text, double& value, bool comma) {
  text = trim(text);
  if (text.empty() || text.size() > 64) return false;
  std::string copy(text);
  if (comma) {
    for (char& c : copy) {
      if (c == '.') return false;  // a point in a decimal-comma file is not a number here
      if (c == ',') c = '.';
    }
  }
  return coatcontact::detail::parse_decimal(copy, value) == coatcontact::detail::NumberStatus::kOk;
}

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = text.find(separator, start);
    if (end == std::string_view::npos) {
      out.push_back(text.substr(start));
      return out;
    }
    out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
}

bool ends_with(std::string_view text, std::string_view tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

bool Lines::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  last_ = pos_;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end + 1;
  ++number_;
  return true;
}

namespace {

bool valid_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t more = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : 9;
    if (more == 9 || i + more >= text.size()) return false;
    for (std::size_t k = 1; k <= more; ++k) {
      if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2) return false;
    }
    i += more + 1;
  }
  return true;
}

}  // namespace

std::string to_utf8(std::string_view text) {
  if (valid_utf8(text)) return std::string(text);
  std::string out;
  out.reserve(text.size() + 8);
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

namespace {

struct ExtraUnit {
  const char* unit;
  double factor;
  const char* si;
};
// The vendors' units the shared unit table (units.hpp: pressure, length, force) does not hold,
// looked up first: "N/m" is a stiffness here, not the table's energy per area.
constexpr ExtraUnit kExtraUnits[] = {
    {"s", 1.0, "s"},         {"ms", 1e-3, "s"},       {"N/m", 1.0, "N/m"},    {"nm/s", 1e-9, "m/s"},
    {"V", 1.0, "V"},         {"Hz", 1.0, "Hz"},       {"1/s", 1.0, "1/s"},    {"%", 1.0, "%"},
    {"N/mm2", 1e6, "Pa"},    {"N/mm^2", 1e6, "Pa"},   {"N/mm\xc2\xb2", 1e6, "Pa"}, {"um/N", 1e-6, "m/N"},   {"uJ", 1e-6, "J"},      {"nJ", 1e-9, "J"},
    {"mJ", 1e-3, "J"},       {"J", 1.0, "J"},         {"N/V", 1.0, "N/V"},    {"m/V", 1.0, "m/V"},
};

}  // namespace

bool si_unit(std::string unit, SiUnit& out) {
  unit = std::string(trim(to_utf8(unit)));
  // micro: U+00B5 and U+03BC as "u"
  for (const char* mu : {"\xc2\xb5", "\xce\xbc"}) {
    const auto at = unit.find(mu);
    if (at != std::string::npos) unit.replace(at, 2, "u");
  }
  for (const auto& row : kExtraUnits) {
    if (unit == row.unit) {
      out.factor = row.factor;
      out.name = row.si;
      return true;
    }
  }
  if (const auto found = find_unit(unit)) {
    static const char* const kSi[] = {"Pa", "m", "J/m2", "N"};
    out.factor = found->to_si;
    out.name = kSi[static_cast<int>(found->kind)];
    return true;
  }
  return false;
}

double scale(double value, double factor) { return factor == 1.0 ? value : to_si(value, factor); }

std::string number_text(double value) {
  char buffer[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

void finish_test(IndentTest& test, const std::string& file, const std::string& where) {
  const std::size_t n = test.depth.size();
  if (n == 0) fail(file, where, 0, "no data points (a depth and a load per line expected)");
  if (test.load.size() != n) fail(file, where, 0, "the load and depth channels differ in length");
  const auto check = [&](std::size_t size, const char* name) {
    if (size != 0 && size != n) fail(file, where, 0, std::string("the ") + name + " channel differs in length from depth");
  };
  check(test.time.size(), "time");
  check(test.stiffness.size(), "stiffness");
  check(test.hardness.size(), "hardness");
  check(test.modulus.size(), "modulus");
  check(test.segment.size(), "segment");
  for (const auto& [name, values] : test.extra) check(values.size(), name.c_str());
  test.metadata["test"] = test.name;
  test.metadata["file"] = file;
}

}  // namespace coatcontact::indent::detail
