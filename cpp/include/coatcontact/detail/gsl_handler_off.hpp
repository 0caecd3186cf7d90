// GSL calls in this library report errors through return codes; the default GSL handler
// would abort the process. The guard switches the handler off for its lifetime and restores
// the previous one (not thread-safe, like the rest of the GSL error-handler API).
#pragma once
#include <gsl/gsl_errno.h>

namespace coatcontact::detail {

class GslHandlerOff {
 public:
  GslHandlerOff() : previous_(gsl_set_error_handler_off()) {}
  ~GslHandlerOff() { gsl_set_error_handler(previous_); }
  GslHandlerOff(const GslHandlerOff&) = delete;
  GslHandlerOff& operator=(const GslHandlerOff&) = delete;

 private:
  gsl_error_handler_t* previous_;
};

}  // namespace coatcontact::detail
