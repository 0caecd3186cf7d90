// Brent root and minimum through GSL (coatcontact/detail/brent.hpp).
#include "coatcontact/detail/brent.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>

#include <exception>
#include <limits>
#include <memory>

#include "coatcontact/detail/gsl_handler_off.hpp"

namespace coatcontact::detail {

namespace {

// The callee of GSL's gsl_function: calls f, keeps the first exception and returns NaN from
// then on, which makes GSL's next iterate fail (GSL_EBADFUNC), so the loop ends.
struct Callback {
  const std::function<double(double)>& f;
  std::exception_ptr error;

  static double call(double x, void* params) {
    auto* self = static_cast<Callback*>(params);
    if (self->error) return std::numeric_limits<double>::quiet_NaN();
    try {
      return self->f(x);
    } catch (...) {
      self->error = std::current_exception();
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
};

}  // namespace

std::optional<BrentResult> brent_root(const std::function<double(double)>& f, double lo, double hi,
                                      const BrentStop& stop) {
  GslHandlerOff guard;
  Callback callback{f, nullptr};
  gsl_function function{&Callback::call, &callback};
  std::unique_ptr<gsl_root_fsolver, void (*)(gsl_root_fsolver*)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), gsl_root_fsolver_free);
  if (!solver) throw std::bad_alloc();
  const int set = gsl_root_fsolver_set(solver.get(), &function, lo, hi);
  if (callback.error) std::rethrow_exception(callback.error);
  if (set != GSL_SUCCESS) return std::nullopt;
  BrentResult result;
  for (int iteration = 0; iteration < stop.max_iterations && !result.converged; ++iteration) {
    if (gsl_root_fsolver_iterate(solver.get()) != GSL_SUCCESS) break;
    result.converged = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver.get()),
                                              gsl_root_fsolver_x_upper(solver.get()), stop.absolute,
                                              stop.relative) == GSL_SUCCESS;
  }
  if (callback.error) std::rethrow_exception(callback.error);
  result.x = gsl_root_fsolver_root(solver.get());
  result.lower = gsl_root_fsolver_x_lower(solver.get());
  result.upper = gsl_root_fsolver_x_upper(solver.get());
  return result;
}

std::optional<BrentResult> brent_minimum(const std::function<double(double)>& f, double lo, double f_lo,
                                         double mid, double f_mid, double hi, double f_hi,
                                         const BrentStop& stop) {
  GslHandlerOff guard;
  Callback callback{f, nullptr};
  gsl_function function{&Callback::call, &callback};
  std::unique_ptr<gsl_min_fminimizer, void (*)(gsl_min_fminimizer*)> minimiser(
      gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent), gsl_min_fminimizer_free);
  if (!minimiser) throw std::bad_alloc();
  if (gsl_min_fminimizer_set_with_values(minimiser.get(), &function, mid, f_mid, lo, f_lo, hi, f_hi) !=
      GSL_SUCCESS) {
    return std::nullopt;
  }
  BrentResult result;
  for (int iteration = 0; iteration < stop.max_iterations && !result.converged; ++iteration) {
    if (gsl_min_fminimizer_iterate(minimiser.get()) != GSL_SUCCESS) break;
    result.converged = gsl_min_test_interval(gsl_min_fminimizer_x_lower(minimiser.get()),
                                             gsl_min_fminimizer_x_upper(minimiser.get()), stop.absolute,
                                             stop.relative) == GSL_SUCCESS;
  }
  if (callback.error) std::rethrow_exception(callback.error);
  result.x = gsl_min_fminimizer_x_minimum(minimiser.get());
  result.lower = gsl_min_fminimizer_x_lower(minimiser.get());
  result.upper = gsl_min_fminimizer_x_upper(minimiser.get());
  return result;
}

}  // namespace coatcontact::detail
