// Error types shared by the library and the CLI. The CLI maps them to exit codes:
// InputError -> 2 (bad usage or input), NumericalError -> 3 (numerical failure).
#pragma once
#include <stdexcept>
#include <string>

namespace coatcontact {

// A value given by the user is not allowed. The message names the value and the allowed range.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The computation could not deliver a result to the requested accuracy (never a silent NaN).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A long call stopped by its progress hook (coatcontact/progress.hpp), e.g. on Ctrl-C in Python.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum ExitCode : int { kExitSuccess = 0, kExitUsage = 2, kExitNumerical = 3 };

}  // namespace coatcontact
