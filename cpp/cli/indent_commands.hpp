// `coatcontact indent <command>`: the sub-subcommands of `indent` and what they share. Each
// command is one entry of kIndentCommands (cmd_indent.cpp) and a function declared here; its
// body lives in its own file (show: cmd_indent.cpp; analyse, calibrate, film:
// cmd_indent_analysis.cpp).
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/indentation.hpp"
#include "commands.hpp"

namespace coatcontact::cli {

struct IndentCommand {
  const char* name;
  int (*run)(const Args& args);
  const char* summary;  // one line of `coatcontact indent --help`
};

int run_indent_show(const Args& args);  // cmd_indent.cpp: the channels of one test as TSV
int run_indent_analyse(const Args& args);    // cmd_indent_analysis.cpp: Oliver-Pharr
int run_indent_calibrate(const Args& args);  // cmd_indent_analysis.cpp: area function and frame
int run_indent_film(const Args& args);       // cmd_indent_analysis.cpp: the film's modulus or thickness

// The options that choose one test of a file: --test NAME, --index N (0-based).
OptionSpec indent_test_option();
OptionSpec indent_index_option();
// The test chosen by --test or --index (not both; the first test without either); InputError
// naming the option, the value and the tests the file holds.
std::size_t choose_indent_test(const std::vector<indent::IndentTest>& tests, const Arguments& arguments,
                               const std::string& path);
// Header lines of a test: file, format, test and the file's other tests, the calibration as
// the file states it, the vendor's results, then every metadata entry.
void add_indent_test_header(std::vector<std::pair<std::string, std::string>>& items,
                            const std::vector<indent::IndentTest>& tests, std::size_t index, const std::string& path);
// A TSV column name of a channel: "LoadCell [m]" -> "LoadCell_m", "X [N/m]" -> "X_N_per_m".
std::string indent_column_name(const std::string& channel);
// "-" for a value the vendor wrote as missing (NaN in the test), else the number (format_value).
std::string indent_cell(double value, const std::string& column);

}  // namespace coatcontact::cli
