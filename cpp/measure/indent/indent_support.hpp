// Internal helpers of the nanoindentation readers (not a public header): messages naming the
// file, sheet or entry and line; numbers (decimal point or comma); vendor units into SI; the
// readers' entry points (one file each, dispatched by indent_readers.cpp).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "coatcontact/indentation.hpp"

namespace coatcontact::indent::detail {

// Files above this are refused before they are read (the largest vendor export seen is 2.5 MB).
constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;
// Points per test and tests per file: a declared count above these is an error, not an allocation.
constexpr std::size_t kMaxPoints = std::size_t{50} << 20;
constexpr std::size_t kMaxTests = 100000;

// InputError "<file>: [<where>: ][line <n>: ]<message>" (`where`: sheet or archive entry;
// line 0: no line).
[[noreturn]] void fail(const std::string& file, const std::string& where, std::size_t line, const std::string& message);

// The whole file, bounded by kMaxFileBytes; InputError if missing, not regular, empty, too big.
std::string read_file(const std::string& path);

// A decimal number filling `text` (blanks around it ignored); `comma`: ',' is the decimal mark.
bool parse_number(std::string_view text, double& value, bool comma = false);
std::string_view trim(std::string_view text);
// `text` cut at `separator` (empty fields kept).
std::vector<std::string_view> split(std::string_view text, char separator);
bool ends_with(std::string_view text, std::string_view tail);

// The text's lines without their '\r\n' / '\n' ends.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  // The next line; false at the end. number() is the line's 1-based number.
  bool next(std::string_view& line);
  std::size_t number() const { return number_; }
  // Puts the last line back (one step).
  void unread() { pos_ = last_; --number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, last_ = 0, number_ = 0;
};

// ISO-8859-1 text (Hysitron, Fischer) as UTF-8; valid UTF-8 is returned unchanged.
std::string to_utf8(std::string_view text);

// A vendor unit: the factor into SI and the SI unit's name ("nm" -> 1e-9, "m"); "uN", "µN" in
// UTF-8 or Latin-1 alike. false if unknown.
struct SiUnit {
  double factor = 1.0;
  std::string name;
};
bool si_unit(std::string unit, SiUnit& out);
// value * factor with the decimal prefixes exact (coatcontact/units.hpp's to_si).
double scale(double value, double factor);

// Shortest round-trip text of a double (metadata values).
std::string number_text(double value);

// Checks a finished test: depth and load present and of equal length, other channels of the
// same length or empty; segment numbers filled.
void finish_test(IndentTest& test, const std::string& file, const std::string& where);

// The readers on the file's bytes (the NanoSuite one on the file itself: FreeXL reads paths).
std::vector<IndentTest> read_nanosuite_xls(const std::string& path);
std::vector<IndentTest> read_hysitron_txt(const std::string& text, const std::string& file);
std::vector<IndentTest> read_hysitron_hld(const std::string& text, const std::string& file);
std::vector<IndentTest> read_micromaterials_zip(const std::string& bytes, const std::string& file);
std::vector<IndentTest> read_fischerscope_txt(const std::string& text, const std::string& file);
// One Micromaterials text (the archive's entry `entry`): time [s], depth [nm], load [mN].
IndentTest read_micromaterials_text(const std::string& text, const std::string& file, const std::string& entry);

IndentFormat detect_format_of(const std::string& bytes, const std::string& file);

}  // namespace coatcontact::indent::detail
