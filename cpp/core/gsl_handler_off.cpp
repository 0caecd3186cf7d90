// The GSL error-handler guard (coatcontact/detail/gsl_handler_off.hpp).
#include "coatcontact/detail/gsl_handler_off.hpp"

#include <gsl/gsl_errno.h>

#include <mutex>

namespace coatcontact::detail {

namespace {
std::mutex guard_mutex;
int active_guards = 0;
gsl_error_handler_t* saved_handler = nullptr;
}  // namespace

GslHandlerOff::GslHandlerOff() {
  std::lock_guard<std::mutex> lock(guard_mutex);
  if (active_guards++ == 0) saved_handler = gsl_set_error_handler_off();
}

GslHandlerOff::~GslHandlerOff() {
  std::lock_guard<std::mutex> lock(guard_mutex);
  if (--active_guards == 0) gsl_set_error_handler(saved_handler);
}

}  // namespace coatcontact::detail
