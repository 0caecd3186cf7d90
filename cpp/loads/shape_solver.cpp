// ShapeSolver (coatcontact/shape_solver.hpp): an IndenterShape at one contact radius as a
// load case of solve_shapes, refined as the reduced solver's loop (THEORY.md sections 5, 11;
// docs/solver.md): level differences + kernel-table term + rounding <= tolerance.
#include "coatcontact/shape_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "reduced_core.hpp"
#include "shape_solve.hpp"
#include "table_kernel.hpp"

namespace coatcontact {

namespace {

// θ(ξ) = -δ0(ξ a)/δ0(a): the shape seen at one contact radius (θ(1) = -1).
class ScaledShape final : public Shape {
 public:
  ScaledShape(const IndenterShape& shape, double a) : shape_(shape), a_(a), scale_(shape.delta0(a)) {
    for (double k : shape.kinks()) {
      if (k < a) singular_.push_back(k / a);
    }
    smooth_ = shape.smooth_at_apex() && singular_.empty();
    if (!shape.smooth_at_apex()) singular_.insert(singular_.begin(), 0.0);
  }
  double theta(double xi) const override { return -shape_.delta0(xi * a_) / scale_; }
  bool smooth_at_apex() const override { return smooth_; }
  std::string name() const override { return "shape"; }
  std::vector<double> singular_points() const override {
    // A smooth apex with kinks inside still needs the product integrals: mark the apex as a
    // (harmless) graded point so that the reciprocity path is taken.
    if (!smooth_ && singular_.empty()) return {0.0};
    return singular_;
  }
  int grading_levels() const override { return shape_.kink_grading_levels(); }

 private:
  const IndenterShape& shape_;
  double a_, scale_;
  bool smooth_ = true;
  std::vector<double> singular_;
};

// A stand-in for the flat punch: θ = -ξ² (its Π, Δ are not used).
class PunchOnly final : public Shape {
 public:
  double theta(double xi) const override { return -xi * xi; }
  bool smooth_at_apex() const override { return true; }
  std::string name() const override { return "punch"; }
};

std::array<double, 4> values_of(const detail::ShapeSolve& s) {
  return {s.e_eq, s.gamma1, s.shapes[0].pi, s.shapes[0].delta};
}

double max_difference(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(a[i] - b[i]) / std::max(std::abs(b[i]), 1e-300));
  }
  return worst;
}

}  // namespace

struct ShapeSolver::Impl {
  explicit Impl(const Stack& s) : stack(s), kernel(stack) {}
  Stack stack;
  detail::TableKernel kernel;
  std::once_flag independent_once;
  std::array<std::unique_ptr<detail::TableKernel>, detail::kIndependentTables> independent;
  bool have_independent = false;

  bool build_independent() {
    std::call_once(independent_once, [this] {
      try {
        for (int k = 0; k < detail::kIndependentTables; ++k) {
          independent[static_cast<std::size_t>(k)] = std::make_unique<detail::TableKernel>(stack, k + 1);
        }
        have_independent = true;
      } catch (const NumericalError&) {
        have_independent = false;
      }
    });
    return have_independent;
  }
};

ShapeSolver::ShapeSolver(const Stack& stack) : impl_(std::make_unique<Impl>(stack)) {}
ShapeSolver::~ShapeSolver() = default;
ShapeSolver::ShapeSolver(ShapeSolver&&) noexcept = default;
ShapeSolver& ShapeSolver::operator=(ShapeSolver&&) noexcept = default;
const Stack& ShapeSolver::stack() const { return impl_->stack; }

ShapeVariables ShapeSolver::solve(const IndenterShape& shape, double contact_radius, double thickness,
                                  double tolerance) const {
  check_tolerance(tolerance);
  const double a = contact_radius / thickness;
  if (!(std::isfinite(a) && a > 0.0 && a <= kMaximumAOverT)) {
    throw InputError("a/t = " + detail::full_precision(a) + " is not allowed; it must be > 0 and <= " +
                     detail::full_precision(kMaximumAOverT));
  }
  if (contact_radius > shape.max_contact_radius() * (1.0 + 1e-12)) {
    throw InputError("contact radius " + detail::full_precision(contact_radius) + " m exceeds the shape's " +
                     detail::full_precision(shape.max_contact_radius()) + " m");
  }
  const PunchOnly punch;
  const ScaledShape scaled(shape, contact_radius);
  const Shape* load = shape.flat() ? static_cast<const Shape*>(&punch) : &scaled;

  detail::Discretization disc;
  disc.quadrature_accuracy = std::clamp(1e-4 * tolerance, 1e-14, 1e-11);
  // A level whose discrete operator is singular or nearly so (non-positive flat-punch edge
  // value: an unresolved coarse level, docs/solver.md, Refinement) is skipped as in the
  // reduced solver's loop; its NumericalError is reported only if no level resolves.
  std::exception_ptr last_failure;
  auto solve_level = [&](int p) -> std::optional<detail::ShapeSolve> {
    disc.nodes_per_panel = p;
    try {
      return detail::solve_shapes(impl_->kernel, a, disc, {load});
    } catch (const NumericalError&) {
      last_failure = std::current_exception();
      return std::nullopt;
    }
  };
  int coarse_p = detail::first_refinement_level(tolerance);
  std::optional<detail::ShapeSolve> previous = solve_level(coarse_p);
  double estimate = std::numeric_limits<double>::infinity();
  bool any_pair = false;
  for (int p = coarse_p + detail::kRefinementStep; p <= detail::kMaxNodesPerPanel;) {
    if (!previous) {  // an unresolved coarse level: the next level starts the pair
      previous = solve_level(p);
      coarse_p = p;
      p += detail::kRefinementStep;
      continue;
    }
    const std::optional<detail::ShapeSolve> solved = solve_level(p);
    if (!solved) {  // an unresolved fine level: a fresh pair above it
      previous.reset();
      coarse_p = p;
      p += detail::kRefinementStep;
      continue;
    }
    any_pair = true;
    const detail::ShapeSolve& current = *solved;
    const double discretization = std::max(max_difference(values_of(*previous), values_of(current)),
                                           current.consistency);
    double kernel_term = current.kernel_error;
    if (kernel_term > 0.1 * tolerance && discretization + current.rounding_error <= tolerance &&
        impl_->build_independent()) {
      // The coherent bound is too pessimistic here: measure the table's effect (docs/solver.md).
      double difference = 0.0;
      for (const auto& other : impl_->independent) {
        const detail::ShapeSolve check = detail::solve_shapes(*other, a, disc, {load});
        difference = std::max(difference, max_difference(values_of(check), values_of(current)));
      }
      kernel_term = detail::kTwoTableSafety * difference;
    }
    estimate = discretization + kernel_term + current.rounding_error;
    if (estimate <= tolerance && detail::conditioned_alike(previous->rounding_error, current.rounding_error)) {
      ShapeVariables v;
      v.a_over_t = a;
      v.e_eq = current.e_eq;
      v.gamma1 = current.gamma1;
      if (!shape.flat()) {
        v.pi = current.shapes[0].pi;
        v.delta = current.shapes[0].delta;
      }
      v.error_estimate = estimate;
      v.unknowns = current.unknowns;
      return v;
    }
    const int next = detail::next_coarse_level(coarse_p, p, discretization, tolerance);
    if (next > p) {  // a fresh pair further on
      previous = solve_level(next);
    } else {
      previous = current;
    }
    coarse_p = next;
    p = next + detail::kRefinementStep;
  }
  if (!any_pair && last_failure) std::rethrow_exception(last_failure);
  std::ostringstream message;
  message.precision(3);
  message << "shape solve at a/t = " << detail::full_precision(a) << ": the error estimate " << estimate
          << " exceeds the tolerance " << tolerance << " (use a larger tolerance)";
  throw NumericalError(message.str());
}

}  // namespace coatcontact
