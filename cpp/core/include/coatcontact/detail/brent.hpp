// GSL's Brent root finder and minimiser behind one pair of functions, for every scalar root and
// minimum of the library. A std::function is passed through GSL's C callback; an exception
// thrown by it stops the iteration and is rethrown to the caller. GSL's error handler is off
// meanwhile (gsl_handler_off.hpp). Library-private: not installed (GSL is a private dependency).
#pragma once

#include <functional>
#include <optional>

namespace coatcontact::detail {

// Stop when the bracket [lower, upper] satisfies GSL's interval test with these tolerances,
// or after max_iterations.
struct BrentStop {
  double absolute = 0.0;
  double relative = 0.0;
  int max_iterations = 200;
};

struct BrentResult {
  double x = 0.0;      // root, or abscissa of the minimum
  double lower = 0.0;  // final bracket
  double upper = 0.0;
  bool converged = false;
};

// Root of f in [lo, hi], where f changes sign. nullopt when GSL refuses the bracket (no sign
// change, a non-finite end value).
std::optional<BrentResult> brent_root(const std::function<double(double)>& f, double lo, double hi,
                                      const BrentStop& stop);

// Minimum of f in [lo, hi] from a point mid with f_mid below f_lo and f_hi (values given, not
// recomputed). nullopt when GSL refuses the triple.
std::optional<BrentResult> brent_minimum(const std::function<double(double)>& f, double lo, double f_lo,
                                         double mid, double f_mid, double hi, double f_hi,
                                         const BrentStop& stop);

}  // namespace coatcontact::detail
