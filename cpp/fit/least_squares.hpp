// The GSL trust-region driver of the fit (private to coatcontact_fit).
#pragma once
#include <string>
#include <vector>

#include "fit_model.hpp"

namespace coatcontact::fit::internal {

struct Minimum {
  Parameters values;
  int iterations = 0;
  std::string stop_reason;  // "small step", "small gradient", ...
};

// Minimizes the sum of squared force residuals over ln of the free parameters
// (gsl_multifit_nlinear, trust region with Levenberg-Marquardt steps). With several free
// parameters and w among them, w alone is fitted first. NumericalError when it does not converge.
Minimum minimize(Model& model, const Measurements& data, const Problem& problem,
                 const std::vector<int>& free_index);

}  // namespace coatcontact::fit::internal
