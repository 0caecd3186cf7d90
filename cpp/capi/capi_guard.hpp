// The C API's one exception barrier, shared by its files (capi.cpp, capi_indent.cpp): runs
// `body`, turns InputError / NumericalError / Interrupted / other failures into status codes
// and the thread's cc_last_error_message(). Not a public header.
#pragma once
#include <functional>

namespace coatcontact::capi {

int guard(const std::function<void()>& body);

}  // namespace coatcontact::capi
