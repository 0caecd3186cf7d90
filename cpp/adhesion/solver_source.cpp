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

}  // namespace coatcontact
