// Java .properties text (the JPK headers): key=value, key:value or key value lines, '#' and '!'
// comments, backslash escapes (\uXXXX to UTF-8) and continuation lines.
#pragma once
#include <map>
#include <string>

namespace coatcontact::afm::detail {

using Properties = std::map<std::string, std::string>;
Properties parse_properties(const std::string& text);

}  // namespace coatcontact::afm::detail
