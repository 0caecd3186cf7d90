// GSL calls in this library report errors through return codes; GSL's default handler would
// abort the host process. While any guard is alive the handler is off; the last guard to end
// restores the handler that was installed before the first began. A process-wide counter
// under a mutex makes nested guards and guards in several threads safe (GSL's handler is one
// global pointer, so the host's own GSL calls in other threads also see it off meanwhile).
#pragma once

namespace coatcontact::detail {

class GslHandlerOff {
 public:
  GslHandlerOff();
  ~GslHandlerOff();
  GslHandlerOff(const GslHandlerOff&) = delete;
  GslHandlerOff& operator=(const GslHandlerOff&) = delete;
};

}  // namespace coatcontact::detail
