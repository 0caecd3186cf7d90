// The GSL trust-region adapter of the fit floor (trust_region.hpp).
#include "trust_region.hpp"

#include <gsl/gsl_errno.h>

#include <utility>

#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {

TrustRegion::TrustRegion(std::size_t n, std::size_t p, Residuals residuals, Jacobian jacobian)
    : residuals_(std::move(residuals)), jacobian_(std::move(jacobian)), work_(nullptr, gsl_multifit_nlinear_free) {
  fdf_.f = residual_callback;
  fdf_.df = jacobian_callback;
  fdf_.fvv = nullptr;
  fdf_.n = n;
  fdf_.p = p;
  fdf_.params = this;
  gsl_multifit_nlinear_parameters parameters = gsl_multifit_nlinear_default_parameters();
  work_.reset(gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &parameters, n, p));
  if (!work_) throw NumericalError("out of memory allocating the fit workspace");
}

namespace {

// GSL_SUCCESS, or GSL_EBADFUNC with the exception kept for start() and run() to rethrow.
template <class Body>
int captured(std::exception_ptr& error, Body&& body) {
  try {
    body();
    return GSL_SUCCESS;
  } catch (...) {
    error = std::current_exception();
    return GSL_EBADFUNC;
  }
}

}  // namespace

int TrustRegion::residual_callback(const gsl_vector* x, void* self, gsl_vector* f) {
  auto* region = static_cast<TrustRegion*>(self);
  return captured(region->error_, [&] { region->residuals_(x, f); });
}

int TrustRegion::jacobian_callback(const gsl_vector* x, void* self, gsl_matrix* jacobian) {
  auto* region = static_cast<TrustRegion*>(self);
  return captured(region->error_, [&] { region->jacobian_(x, jacobian); });
}

bool TrustRegion::start() {
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> x0(gsl_vector_alloc(fdf_.p), gsl_vector_free);
  if (!x0) throw NumericalError("out of memory allocating the fit workspace");
  gsl_vector_set_all(x0.get(), kLogOffset);
  error_ = nullptr;
  if (gsl_multifit_nlinear_init(x0.get(), &fdf_, work_.get()) == GSL_SUCCESS) return true;
  if (error_) std::rethrow_exception(error_);
  return false;
}

int TrustRegion::run(int max_iterations, double xtol, double gtol, double ftol, int* info) {
  const int status = gsl_multifit_nlinear_driver(static_cast<std::size_t>(max_iterations), xtol, gtol, ftol, nullptr,
                                                 nullptr, info, work_.get());
  if (error_) std::rethrow_exception(error_);
  return status;
}

int TrustRegion::iterations() const { return static_cast<int>(gsl_multifit_nlinear_niter(work_.get())); }
const gsl_vector* TrustRegion::position() const { return gsl_multifit_nlinear_position(work_.get()); }
const gsl_vector* TrustRegion::residual() const { return gsl_multifit_nlinear_residual(work_.get()); }
const gsl_matrix* TrustRegion::jacobian() const { return gsl_multifit_nlinear_jac(work_.get()); }

}  // namespace coatcontact::fit::internal
