// Internal helpers shared by the data file reader (measure floor), the CLI's value parsers
// and its subcommands (not a public header).
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace coatcontact::detail {

// kSubnormal: nonzero but below the smallest normal double (2.2e-308), where arithmetic
// loses precision and 1/x overflows; refused rather than computed with.
enum class NumberStatus { kOk, kNotNumber, kNotFinite, kOutOfRange, kSubnormal };

// Strict, locale-independent decimal number occupying all of `text` (no blanks, no hex,
// no nan/inf; an optional leading '+' is accepted). `value` is set only on kOk.
NumberStatus parse_decimal(std::string_view text, double& value);

// `text` without leading and trailing spaces and tabs.
std::string_view trim_blanks(std::string_view text);
std::string trim(std::string_view text);  // the same, as a string

// `text` cut at every `separator`: n separators give n + 1 items, empty ones included (so ""
// gives one empty item, which the list parsers report as an empty item).
std::vector<std::string> split(std::string_view text, char separator);

// `text` in single quotes for a message: non-printable bytes as \xNN, cut after 60 bytes.
std::string quote(std::string_view text);

// "%.17g" of `value`, locale-independent (for messages).
std::string number_string(double value);

}  // namespace coatcontact::detail
