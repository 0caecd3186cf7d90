// The error vocabulary of the compiled module _core's sources on the C API (core.cpp,
// kinetics.cpp): bad input raises ValueError, a result that cannot be delivered raises
// coatcontact.NumericalError (a RuntimeError; core.cpp registers the type).
#pragma once
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

#include "coatcontact/coatcontact.h"

namespace coatcontact_python {

struct NumericalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// C status -> exception, with the library's message (the CLI prints the same text).
inline void check(int status, const std::string& message) {
  switch (status) {
    case CC_OK: return;
    case CC_INPUT_ERROR: throw pybind11::value_error(message);
    case CC_NUMERICAL_ERROR: throw NumericalError(message);
    default: throw std::runtime_error(message.empty() ? "coatcontact: internal error" : message);
  }
}

// Runs a C call without the GIL; the message is read in the same thread, before the GIL
// comes back (it is per thread and valid until the thread's next call).
template <typename Call>
void call_released(Call&& call) {
  int status;
  std::string message;
  {
    pybind11::gil_scoped_release release;
    status = call();
    if (status != CC_OK) message = cc_last_error_message();
  }
  check(status, message);
}

// A C call that returns at once (handles, sizes), with the GIL held.
template <typename Call>
void call_held(Call&& call) {
  const int status = call();
  check(status, status == CC_OK ? std::string() : std::string(cc_last_error_message()));
}

}  // namespace coatcontact_python
