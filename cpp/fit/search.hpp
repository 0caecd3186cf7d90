// The coarse global search that gives the trust-region solve its start (private to
// coatcontact_fit): a grid over log-parameters within the search ranges of fit.hpp.
#pragma once
#include <vector>

#include "fit_model.hpp"

namespace coatcontact::fit::internal {

struct SearchResult {
  Parameters best;
  double best_cost = 0.0;
  bool has_second = false;  // a second local minimum of the grid
  Parameters second;
  double second_cost = 0.0;
  int evaluations = 0;  // model evaluations at the data
};

// 1/sigma_eff per point from the data's sigmas and the model's dF/dx at `m`; empty when the
// data carry no sigma (unweighted fit).
std::vector<double> inverse_sigma(const Measurements& data, const ModelAtData& m);

// Grid over ln t and ln E1 (when free); w is profiled out for a,F data (F = A - B sqrt(w) at
// fixed a and t: one weighted linear fit per grid point) and gridded for delta,F data. `hint`
// (the user's values) is evaluated too. NumericalError when no grid point can be evaluated.
SearchResult global_search(Model& model, const std::vector<int>& free_index, const Parameters& hint);

}  // namespace coatcontact::fit::internal
