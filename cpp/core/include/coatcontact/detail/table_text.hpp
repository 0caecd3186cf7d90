// The text of the TSV tables every output writes (the CLI's commands, the AFM batch table of
// the fit floor and the C API): numbers in columns and header lines, the "# key: value" header
// and the stack's material lines. One spelling for every writer.
#pragma once
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/stack.hpp"

namespace coatcontact::detail {

using HeaderItems = std::vector<std::pair<std::string, std::string>>;

// A number for a TSV column: "%.17g". NumericalError (naming `column`) if not finite, so no
// NaN/inf is ever printed as a result.
std::string table_value(double value, const std::string& column);

// Shortest decimal text that reads back to the same double ("0.1"): for parameters echoed in
// header lines. NumericalError (naming `name`) if not finite.
std::string table_parameter(double value, const std::string& name);

// `text` with its line ends as spaces (a header value or a cell stays on its line).
std::string table_one_line(const std::string& text);

// "# command: ..." (when command_line is not empty; an item "command" then gives way), the
// "# key: value" lines, the sign convention of an SI force column, and "# columns: a\tb...".
void write_table_header(std::ostream& out, const std::string& command_line, const HeaderItems& items,
                        const std::vector<std::string>& columns);

// The header lines of the film and the substrate (or each layer of a stack), the same in every
// output (cli_support.hpp's add_material_header).
void add_stack_header_items(HeaderItems& items, const Stack& stack);

}  // namespace coatcontact::detail
