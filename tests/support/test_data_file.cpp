// Unit tests of the data file reader (read_data_text, read_data_file): formats, headers,
// units, and every malformed case with its line number.
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/data_file.hpp"

using coatcontact::DataTable;
using coatcontact::InputError;
using coatcontact::read_data_file;
using coatcontact::read_data_text;
using coatcontact::Quantity;

namespace {

// Unit conversion is one correctly rounded operation.
using check::tier::kRounding;

const std::vector<bool> kBothNonnegative = {true, true};
const std::vector<std::optional<Quantity>> kDepthLoad = {Quantity::kLength, Quantity::kForce};

void test_formats() {
  const DataTable tsv = read_data_text("# load-depth curve\n0\t0\n1.5\t2e-3\n\n3\t4\n", "a.tsv", 2);
  check::that(tsv.rows() == 3 && tsv.columns.size() == 2, "tsv.rows() == 3 && tsv.columns.size() == 2");
  check::that(tsv.columns[0][1] == 1.5 && tsv.columns[1][1] == 2e-3 && tsv.columns[1][2] == 4.0,
              "tsv.columns[0][1] == 1.5 && tsv.columns[1][1] == 2e-3 && tsv.columns[1][2] == 4.0");
  check::that(tsv.line_numbers == std::vector<int>({2, 3, 5}),
              "tsv.line_numbers == std::vector<int>({2, 3, 5})");
  check::that(tsv.column_names.empty() && tsv.units.empty(), "tsv.column_names.empty() && tsv.units.empty()");

  const DataTable csv = read_data_text("depth,load\n1, 2\n3 ,4\r\n", "a.csv", 2);
  check::that(csv.column_names == std::vector<std::string>({"depth", "load"}),
              "csv.column_names == std::vector<std::string>({'depth', 'load'})");
  check::that(csv.rows() == 2 && csv.columns[0][1] == 3.0 && csv.columns[1][1] == 4.0,
              "csv.rows() == 2 && csv.columns[0][1] == 3.0 && csv.columns[1][1] == 4.0");

  const DataTable spaces = read_data_text("  1   2  # trailing comment\n\t3 \t 4\n", "a.txt", 2);
  check::that(spaces.rows() == 2 && spaces.columns[1][0] == 2.0 && spaces.columns[0][1] == 3.0,
              "spaces.rows() == 2 && spaces.columns[1][0] == 2.0 && spaces.columns[0][1] == 3.0");

  const DataTable bom = read_data_text("\xef\xbb\xbf" "1 2\n", "bom.txt", 2);
  check::that(bom.rows() == 1 && bom.columns[0][0] == 1.0, "bom.rows() == 1 && bom.columns[0][0] == 1.0");

  const DataTable no_final_newline = read_data_text("1 2", "x", 2);
  check::that(no_final_newline.rows() == 1, "no_final_newline.rows() == 1");

  const DataTable one_column = read_data_text("5\n-6\n", "x", 1);
  check::that(one_column.rows() == 2 && one_column.columns[0][1] == -6.0,
              "one_column.rows() == 2 && one_column.columns[0][1] == -6.0");
}

void test_units() {
  const DataTable table = read_data_text("# units: um mN\ndepth\tload\n1.5\t2\n", "u.tsv", 2,
                                         kBothNonnegative, kDepthLoad);
  check::that(table.units == std::vector<std::string>({"um", "mN"}),
              "table.units == std::vector<std::string>({'um', 'mN'})");
  check::close(table.columns[0][0], 1.5e-6, kRounding, "1.5 um");
  check::close(table.columns[1][0], 2e-3, kRounding, "2 mN");
  // Units declared after the data still apply to all rows; no kinds given: any known unit.
  const DataTable late = read_data_text("1 2\n#units: nm N\n3 4\n", "late", 2);
  check::close(late.columns[0][0], 1e-9, kRounding, "late units, column 1");
  check::that(late.columns[1][1] == 4.0, "late units, column 2");
  const DataTable capital = read_data_text("# Units: mm N\n2 3\n", "c", 2);
  check::close(capital.columns[0][0], 2e-3, kRounding, "# Units: 2 mm");
  // Dimensionless columns.
  const DataTable dimensionless = read_data_text("# units: - 1\n2 3\n", "d", 2);
  check::that(dimensionless.columns[0][0] == 2.0 && dimensionless.columns[1][0] == 3.0,
              "dimensionless.columns[0][0] == 2.0 && dimensionless.columns[1][0] == 3.0");
  const DataTable micro = read_data_text("# units: \xc2\xb5m \xc2\xb5N\n2 3\n", "m", 2, {}, kDepthLoad);
  check::close(micro.columns[0][0], 2e-6, kRounding, "2 micro-m (U+00B5)");

  check::throws<InputError>([&] { (void)(read_data_text("# units: furlong mN\n1 2\n", "u.tsv", 2)); },
                            {"u.tsv:1:", "unknown unit 'furlong'"});
  check::throws<InputError>([&] { (void)(read_data_text("# units: um\n1 2\n", "u.tsv", 2)); },
                            {"u.tsv:1:", "1 units, expected 2"});
  check::throws<InputError>(
      [&] { (void)(read_data_text("# units: mN um\n1 2\n", "u.tsv", 2, {}, kDepthLoad)); },
      {"u.tsv:1:", "'mN' of column 1 is a force unit, expected length"});
  check::throws<InputError>(
      [&] { (void)(read_data_text("# units: - mN\n1 2\n", "u.tsv", 2, {}, kDepthLoad)); },
      {"u.tsv:1:", "column 1 is a length"});
  check::throws<InputError>(
      [&] { (void)(read_data_text("1 2\n# units: um mN\n# units: um mN\n", "u.tsv", 2)); },
      {"u.tsv:3:", "second time"});
  check::throws<InputError>([&] { (void)(read_data_text("# units: um GPa\n1 1e308\n", "u.tsv", 2)); },
                            {"u.tsv:2:", "too large"});
  check::throws<InputError>([&] { (void)(read_data_text("# units: um,,mN\n1 2\n", "u.tsv", 2)); },
                            {"u.tsv:1:", "empty unit"});
}

void test_malformed_lines() {
  const std::string good = "# header comment\ndepth load\n1 2\n";
  check::throws<InputError>([&] { (void)(read_data_text(good + "3 abc\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "column 2 (load): 'abc' is not a number"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "3\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "expected 2 columns, found 1"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "3 4 5\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "expected 2 columns, found 3"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "nan 4\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "column 1 (depth)", "not a finite number"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "1 inf\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "not a finite number"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "1 1e400\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "outside the range"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "0x10 4\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "'0x10'"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "1,,2\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "empty field"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "1,2,\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "empty field"});
  check::throws<InputError>([&] { (void)(read_data_text(good + "-1 2\n", "f.tsv", 2, kBothNonnegative)); },
                            {"f.tsv:4:", "column 1 (depth): value -1 must be >= 0"});
  // The flag is per column: a negative value in an unrestricted column is fine.
  check::that(read_data_text(good + "1 -2\n", "f.tsv", 2, {true, false}).columns[1][1] == -2.0,
              "read_data_text(good + '1 -2n', 'f.tsv', 2, {true, false}).columns[1][1] == -2.0");
  check::throws<InputError>([&] { (void)(read_data_text(good + "depth load\n", "f.tsv", 2)); },
                            {"f.tsv:4:", "'depth'"});
  check::throws<InputError>([&] { (void)(read_data_text("a b c\n1 2\n", "h.tsv", 2)); },
                            {"h.tsv:1:", "header has 3 column names"});
  check::throws<InputError>([&] { (void)(read_data_text("abc 2\n", "h.tsv", 2)); },
                            {"h.tsv:1:", "column 1: 'abc' is not a number"});
  check::throws<InputError>([&] { (void)(read_data_text(std::string("1 2\n3 \0\n", 8), "z.tsv", 2)); },
                            {"z.tsv:2:", "\\x00"});
  check::throws<InputError>([&] { (void)(read_data_text("", "e.tsv", 2)); }, {"e.tsv", "no data rows"});
  check::throws<InputError>([&] { (void)(read_data_text("# only comments\ndepth load\n\n", "e.tsv", 2)); },
                            {"e.tsv", "no data rows"});
}

void test_limits() {
  // 1e6 rows are allowed, one more is refused (with its line number).
  std::string rows;
  rows.reserve(4 * 1000001);
  for (int i = 0; i < 1000000; ++i) rows += "1 2\n";
  check::that(read_data_text(rows, "big", 2).rows() == 1000000,
              "read_data_text(rows, 'big', 2).rows() == 1000000");
  rows += "1 2\n";
  check::throws<InputError>([&] { (void)(read_data_text(rows, "big", 2)); },
                            {"big:1000001:", "more than 1000000 data rows"});
  const std::string huge(coatcontact::kMaxDataFileBytes + 1, '\n');
  check::throws<InputError>([&] { (void)(read_data_text(huge, "huge", 2)); }, {"huge", "larger than 100 MB"});
}

void test_files() {
  const char* base = std::getenv("TMPDIR");
  std::string path = std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/cc_data_test.XXXXXX";
  const int fd = mkstemp(path.data());
  check::that(fd >= 0, "fd >= 0");
  close(fd);
  {
    std::ofstream(path) << "# units: nm uN\n10\t20\n30 x\n";
  }
  check::throws<InputError>([&] { (void)(read_data_file(path, 2)); },
                            {(path + ":3:").c_str(), "'x' is not a number"});
  {
    std::ofstream(path) << "# units: nm uN\n10\t20\n";
  }
  const DataTable table = read_data_file(path, 2, kBothNonnegative, kDepthLoad);
  check::close(table.columns[0][0], 1e-8, kRounding, "file: 10 nm");
  check::close(table.columns[1][0], 2e-5, kRounding, "file: 20 uN");
  unlink(path.c_str());
  check::throws<InputError>([&] { (void)(read_data_file(path, 2)); }, {path.c_str(), "No such file"});
  check::throws<InputError>([&] { (void)(read_data_file("/", 2)); }, "not a regular file");
}

}  // namespace

int main() {
  test_formats();
  test_units();
  test_malformed_lines();
  test_limits();
  test_files();
  return check::exit_code();
}
