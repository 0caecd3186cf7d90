// coatcontact::ReducedSolver (cpp/include/coatcontact/reduced.hpp): input checks, the kernel
// table of the material pair, and the refinement loop of reduced_core.
#include "coatcontact/reduced.hpp"

#include <cmath>
#include <exception>
#include <sstream>
#include <utility>

#include "coatcontact/errors.hpp"
#include "reduced_core.hpp"
#include "table_kernel.hpp"

namespace coatcontact {

struct ReducedSolver::Impl {
  Material film;
  Substrate substrate;
  std::unique_ptr<detail::TableKernel> kernel;
};

namespace {

std::string number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

void check_arguments(double a_over_t, double tolerance) {
  if (!std::isfinite(a_over_t) || !(a_over_t > 0.0) || !(a_over_t <= kMaximumAOverT)) {
    throw InputError("a/t " + number(a_over_t) + " is not allowed; it must be > 0 and <= " +
                     number(kMaximumAOverT));
  }
  if (!std::isfinite(tolerance) || !(tolerance >= kMinimumTolerance) ||
      !(tolerance <= kMaximumTolerance)) {
    throw InputError("tolerance " + number(tolerance) + " is outside the allowed range [" +
                     number(kMinimumTolerance) + ", " + number(kMaximumTolerance) + "]");
  }
}

}  // namespace

ReducedSolver::ReducedSolver(const Material& film, const Substrate& substrate)
    : impl_(std::make_unique<Impl>()) {
  validate(film, "film");
  validate(substrate);
  impl_->film = film;
  impl_->substrate = substrate;
  impl_->kernel = std::make_unique<detail::TableKernel>(film, substrate);
}

ReducedSolver::~ReducedSolver() = default;
ReducedSolver::ReducedSolver(ReducedSolver&&) noexcept = default;
ReducedSolver& ReducedSolver::operator=(ReducedSolver&&) noexcept = default;

const Material& ReducedSolver::film() const { return impl_->film; }
const Substrate& ReducedSolver::substrate() const { return impl_->substrate; }

ReducedVariables ReducedSolver::solve(double a_over_t, double tolerance) const {
  check_arguments(a_over_t, tolerance);
  const detail::AdaptiveSolve solution = detail::solve_adaptive(*impl_->kernel, a_over_t, tolerance);
  if (!solution.converged) {
    std::ostringstream message;
    message.precision(3);
    message << "reduced variables at a/t = " << number(a_over_t) << ": the error estimate "
            << solution.error_estimate << " exceeds the tolerance " << tolerance
            << " (discretization " << solution.discretization_error << " at "
            << solution.unknowns << " unknowns, kernel-table accuracy "
            << solution.kernel_error << ", rounding " << solution.rounding_error << "; ";
    if (solution.kernel_error + solution.rounding_error > tolerance) {
      message << "the last two do not shrink with refinement: use a larger tolerance)";
    } else {
      message << "no convergence within " << detail::kMaxNodesPerPanel << " nodes per panel)";
    }
    throw NumericalError(message.str());
  }
  ReducedVariables v;
  v.a_over_t = a_over_t;
  v.pi_s = solution.values[detail::kPiS];
  v.delta_s = solution.values[detail::kDeltaS];
  v.pi_c = solution.values[detail::kPiC];
  v.delta_c = solution.values[detail::kDeltaC];
  v.e_eq = solution.values[detail::kEEq];
  v.gamma1 = solution.values[detail::kGamma1];
  v.error_estimate = solution.error_estimate;
  v.unknowns = solution.unknowns;
  return v;
}

std::vector<ReducedVariables> ReducedSolver::sweep(const std::vector<double>& a_over_t,
                                                   double tolerance) const {
  // Check everything first, so that bad input fails before any work.
  for (double a : a_over_t) check_arguments(a, tolerance);
  const long count = static_cast<long>(a_over_t.size());
  std::vector<ReducedVariables> results(a_over_t.size());
  std::vector<std::exception_ptr> errors(a_over_t.size());
  // Each radius is independent and deterministic: the parallel result equals the serial one.
#pragma omp parallel for schedule(dynamic, 1)
  for (long i = 0; i < count; ++i) {
    try {
      results[static_cast<std::size_t>(i)] = solve(a_over_t[static_cast<std::size_t>(i)], tolerance);
    } catch (...) {
      errors[static_cast<std::size_t>(i)] = std::current_exception();
    }
  }
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);  // the first failing radius, as in a serial loop
  }
  return results;
}

}  // namespace coatcontact
