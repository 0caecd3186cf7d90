// Reader for measured data tables (the measure floor, cpp/measure/: load-depth curves for the
// fit, profiles of indenter shapes).
//
// Format (TSV, CSV or whitespace-separated text):
//  - blank lines and lines whose first non-blank character is '#' are ignored; text after a
//    '#' on a data line is a trailing comment;
//  - a line containing a comma is split at commas, else one containing a semicolon at
//    semicolons (blanks around fields ignored, an empty field is an error); any other line is
//    split at runs of blanks (spaces, tabs);
//  - an optional header line of column names: the first non-comment line, if none of its
//    fields is a number;
//  - an optional unit declaration, a comment line "# units: um mN" ("units:" in any letter
//    case, at most once, anywhere in the file) with one unit per column
//    (spellings of find_unit, units.hpp; "-" or "1" for a dimensionless column). Values of a column
//    with a unit are converted to SI;
//  - CRLF line ends and a UTF-8 byte-order mark are accepted.
//  - a comment line "# columns: a F" (as written by coatcontact itself) is kept in
//    DataTable::declared_columns, so a caller can compare it with what it was told;
// Every data line must have exactly `expected_columns` finite decimal numbers (no NaN/inf,
// no hex). Any malformed line throws InputError "<file>:<line>: <what was wrong>"; nothing
// partial is ever returned. Limits: 100 MB of text, 1e6 data rows, at least one data row.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <iosfwd>

#include "coatcontact/errors.hpp"
#include "coatcontact/units.hpp"

namespace coatcontact {

struct DataTable {
  std::vector<std::string> column_names;     // from the header line; empty if there is none
  std::vector<std::vector<double>> columns;  // columns[c][row], SI if units were declared
  std::vector<std::string> units;            // as declared in "# units:"; empty if none
  std::vector<std::string> declared_columns; // from a "# columns: a F" comment; empty if none
  int declared_columns_line = 0;
  std::vector<int> line_numbers;             // 1-based source line of each row
  std::size_t rows() const { return line_numbers.size(); }
};

constexpr std::size_t kMaxDataFileBytes = 100u * 1024u * 1024u;
constexpr std::size_t kMaxDataRows = 1000000u;

// nonnegative[c]: values of column c must be >= 0 (empty vector: no column restricted).
// kinds[c]: the physical quantity of column c; a declared unit must be of that kind
// (nullopt: the column is dimensionless, its unit must be "-" or "1"). Empty vector: any
// known unit is accepted. Both vectors, when not empty, have `expected_columns` entries.
// expected_columns 0: as many columns as the first header, units line or data row has (then
// both vectors are empty).
DataTable read_data_file(const std::string& path, std::size_t expected_columns,
                         const std::vector<bool>& nonnegative = {},
                         const std::vector<std::optional<Quantity>>& kinds = {});

// Same, from text in memory; `name` stands for the file name in messages.
DataTable read_data_text(const std::string& text, const std::string& name,
                         std::size_t expected_columns, const std::vector<bool>& nonnegative = {},
                         const std::vector<std::optional<Quantity>>& kinds = {});

// The text of a regular file of at most kMaxDataFileBytes (InputError naming the file
// otherwise); the text of a stream (stdin), refused as soon as it passes that limit.
std::string read_file_text(const std::string& path);
std::string read_stream_text(std::istream& in, const std::string& name);

// A path or argument for a message: long ones keep their two ends.
std::string short_name(const std::string& text);

}  // namespace coatcontact
