// The indentation handle's layout, for the C API files that work on read tests (not public).
#pragma once
#include <string>
#include <vector>

#include "coatcontact/coatcontact_indent.h"
#include "coatcontact/indentation.hpp"

struct cc_indent_tests {
  std::vector<coatcontact::indent::IndentTest> tests;
  std::vector<std::vector<std::string>> channel_names;  // per test, the order of coatcontact_indent.h
};

namespace coatcontact::capi {
// Test `index` of `tests`; InputError naming `function` if the handle is NULL or the index out of range.
const indent::IndentTest& indent_test(const cc_indent_tests* tests, long index, const char* function);
}  // namespace coatcontact::capi
