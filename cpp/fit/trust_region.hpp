// One GSL trust-region least-squares solve (gsl_multifit_nlinear: Levenberg-Marquardt steps,
// More scaling, QR) over variables x_j = kLogOffset + ln(p_j / p_start_j), shared by the force
// fit (least_squares.cpp) and the kinetics fit (kinetics_model.cpp).
#pragma once
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>

#include <cstddef>
#include <exception>
#include <functional>
#include <memory>

namespace coatcontact::fit::internal {

// GSL's relative step test |dx| <= xtol (|x| + xtol) then acts on the relative change of p_j.
constexpr double kLogOffset = 10.0;

class TrustRegion {
 public:
  // Scaled residuals f(x) (n values) and their Jacobian J(x) (n x p). An exception from either
  // stops the solve and is rethrown by start() or run(): GSL's C callbacks cannot carry it.
  using Residuals = std::function<void(const gsl_vector* x, gsl_vector* f)>;
  using Jacobian = std::function<void(const gsl_vector* x, gsl_matrix* jacobian)>;

  TrustRegion(std::size_t n, std::size_t p, Residuals residuals, Jacobian jacobian);

  // Evaluates the residuals at x_j = kLogOffset (the start values); false when they cannot be.
  bool start();
  // GSL's driver from the start: its status (GSL_SUCCESS, GSL_ENOPROG, GSL_EMAXITER, ...) and
  // in *info why it converged (1 small step, 2 small gradient).
  int run(int max_iterations, double xtol, double gtol, double ftol, int* info);

  int iterations() const;
  const gsl_vector* position() const;
  const gsl_vector* residual() const;
  const gsl_matrix* jacobian() const;

 private:
  static int residual_callback(const gsl_vector* x, void* self, gsl_vector* f);
  static int jacobian_callback(const gsl_vector* x, void* self, gsl_matrix* jacobian);

  Residuals residuals_;
  Jacobian jacobian_;
  gsl_multifit_nlinear_fdf fdf_{};
  std::unique_ptr<gsl_multifit_nlinear_workspace, void (*)(gsl_multifit_nlinear_workspace*)> work_;
  std::exception_ptr error_;
};

}  // namespace coatcontact::fit::internal
