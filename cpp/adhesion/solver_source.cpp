// SolverSource: the ReducedSolver as a ReducedSource. Kept in its own file so that code using
// other sources does not pull in the solver.
#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

SolverSource::SolverSource(const ReducedSolver& solver, double tolerance)
    : solver_(solver), tolerance_(tolerance) {
  check_tolerance(tolerance);
}

std::vector<ReducedVariables> SolverSource::evaluate(const std::vector<double>& a_over_t) const {
  return solver_.sweep(a_over_t, tolerance_);
}

const Stack& SolverSource::stack() const { return solver_.stack(); }

// Defined here (not in adhesive_model.cpp) so that the model links without the solver.
AdhesiveModel::AdhesiveModel(const ReducedSolver& solver, double tolerance, TableOptions table,
                             PulloffOptions pulloff)
    : AdhesiveModel(std::make_shared<SolverSource>(solver, tolerance), table, pulloff) {}

std::unique_ptr<AdhesiveModel> pulloff_sweep_model(const ReducedSolver& solver, double tolerance,
                                                   const std::vector<double>& etas, std::string* why_not) {
  check_tolerance(tolerance);
  if (etas.size() < 2) {
    if (why_not != nullptr) *why_not = "one eta";
    return nullptr;
  }
  auto model = std::make_unique<AdhesiveModel>(solver, kPulloffNodeShare * tolerance,
                                               pulloff_sweep_table_options(tolerance));
  try {
    model->prepare_pulloff_range(etas);
  } catch (const NumericalError& e) {
    if (why_not != nullptr) *why_not = e.what();
    return nullptr;
  }
  return model;
}

}  // namespace coatcontact
