// SolverSource: the ReducedSolver as a ReducedSource. Kept in its own file so that code using
// other sources does not pull in the solver.
#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/adhesive.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

SolverSource::SolverSource(const ReducedSolver& solver, double tolerance)
    : solver_(solver), tolerance_(tolerance) {
  // Same range as ReducedSolver::solve, checked here so the message names the adhesive layer.
  if (!(tolerance >= 1e-13 && tolerance <= 1e-1)) {
    throw InputError("solver tolerance " + std::to_string(tolerance) + " not allowed (1e-13..1e-1)");
  }
}

std::vector<ReducedVariables> SolverSource::evaluate(const std::vector<double>& a_over_t) const {
  return solver_.sweep(a_over_t, tolerance_);
}

const Material& SolverSource::film() const { return solver_.film(); }
const Substrate& SolverSource::substrate() const { return solver_.substrate(); }

// Defined here (not in adhesive_model.cpp) so that the model links without the solver.
AdhesiveModel::AdhesiveModel(const ReducedSolver& solver, double tolerance, TableOptions table,
                             PulloffOptions pulloff)
    : AdhesiveModel(std::make_shared<SolverSource>(solver, tolerance), table, pulloff) {}

}  // namespace coatcontact
