// Statistics of a converged fit (private to coatcontact_fit): residuals, R^2, linearized
// standard errors and correlations, and the checks that refuse a meaningless result.
#pragma once
#include <vector>

#include "coatcontact/fit.hpp"

namespace coatcontact::fit::internal {

// Fills result.residual, residual_norm, residual_sigma, r_squared, standard_error and
// correlation from the model forces and the Jacobian columns d F_model / d ln p (one column
// per entry of free_index; result.value must hold the estimates). inv_sigma: 1/sigma_eff per
// point (weighted fit: covariance (J^T W J)^-1, chi2 filled), or empty (unweighted:
// covariance s^2 (J^T J)^-1). NumericalError when the
// parameters are not identifiable, a standard error is not smaller than its value, or
// R^2 < kMinimumRSquared.
void fill_statistics(const Measurements& data, const std::vector<double>& model_force,
                     const std::vector<std::vector<double>>& jacobian, const std::vector<int>& free_index,
                     const std::vector<double>& inv_sigma, Result& result);

}  // namespace coatcontact::fit::internal
