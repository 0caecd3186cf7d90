// The error vocabulary of the compiled module _core, shared by its sources (core.cpp on the C
// API, kinetics.cpp on the C++ library): bad input raises ValueError, a result that cannot be
// delivered raises coatcontact.NumericalError (a RuntimeError; core.cpp registers the type).
#pragma once
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "coatcontact/coatcontact.h"
#include "coatcontact/errors.hpp"

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

// Runs `body` (calls of the C++ library) without the GIL; its InputError and NumericalError
// are raised as above once the GIL is held again.
template <class Body>
void without_gil(Body&& body) {
  int status = CC_OK;
  std::string message;
  {
    pybind11::gil_scoped_release release;
    try {
      body();
    } catch (const coatcontact::InputError& e) {
      status = CC_INPUT_ERROR;
      message = e.what();
    } catch (const coatcontact::NumericalError& e) {
      status = CC_NUMERICAL_ERROR;
      message = e.what();
    }
  }
  check(status, message);
}
// The same, for functions handed the module's NumericalError class (the type registered for
// NumericalError above).
template <class Body>
void without_gil(const pybind11::object& /*numerical_error*/, Body&& body) {
  without_gil(std::forward<Body>(body));
}

}  // namespace coatcontact_python
