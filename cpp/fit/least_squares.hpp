// The GSL trust-region driver of the fit (private to coatcontact_fit).
#pragma once
#include <string>
#include <vector>

#include "fit_model.hpp"

namespace coatcontact::fit::internal {

struct Minimum {
  Parameters values;
  double cost = 0.0;  // sum of squared scaled residuals at the end
  int iterations = 0;
  std::string stop_reason;  // "small step", "small gradient", ...
};

// Minimizes sum (scale_i (F_model,i - F_i))^2 over ln of the free parameters from `start`
// (gsl_multifit_nlinear, trust region with Levenberg-Marquardt steps). With fit_work_first,
// several free parameters and w among them, w alone is fitted first. NumericalError when it
// does not converge.
Minimum minimize(Model& model, const Problem& problem, const std::vector<int>& free_index,
                 const Parameters& start, const std::vector<double>& scale, bool fit_work_first);

}  // namespace coatcontact::fit::internal
