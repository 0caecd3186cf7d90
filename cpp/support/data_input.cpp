// A command's data files: read by the measure floor, registered as inputs so that no output of
// the command replaces them (cli_support.hpp).
#include <iostream>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/data_file.hpp"

namespace coatcontact::cli {

DataTable read_data_file(const std::string& path, std::size_t expected_columns, const std::vector<bool>& nonnegative,
                         const std::vector<std::optional<Quantity>>& kinds) {
  if (path == "-") {  // "-": standard input, as `fit -`
    return read_data_text(read_stream_text(std::cin, "stdin"), "stdin", expected_columns, nonnegative, kinds);
  }
  const std::string text = read_file_text(path);
  register_input(path, "data file");
  return read_data_text(text, short_name(path), expected_columns, nonnegative, kinds);
}

std::string read_input_text(const std::string& path) {
  if (path == "-") return read_stream_text(std::cin, "stdin");
  std::string text = read_file_text(path);
  register_input(path, "data file");
  return text;
}

}  // namespace coatcontact::cli
