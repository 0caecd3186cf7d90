// ShapeSolver (coatcontact/shape_solver.hpp): an IndenterShape at one contact radius as a
// load case of the solver's refinement loop (THEORY.md sections 5, 11; docs/solver.md):
// level differences + kernel-table term + rounding <= tolerance.
#include "coatcontact/shape_solver.hpp"

#include <cmath>
#include <sstream>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "load_case.hpp"
#include "refinement.hpp"
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

}  // namespace

struct ShapeSolver::Impl {
  explicit Impl(const Stack& s) : stack(s), kernel(stack) {}
  Stack stack;
  detail::TableKernel kernel;
  detail::IndependentTables independent{stack};
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
  const SphereShape punch;  // a stand-in load case for the flat punch (its Π, Δ are not used)
  const ScaledShape scaled(shape, contact_radius);
  const Shape* load = shape.flat() ? static_cast<const Shape*>(&punch) : &scaled;

  // The loop refines on to its finest level where the kernel term stalls (RefinementRules).
  detail::RefinementRules rules;
  rules.stop_when_kernel_term_stalls = false;
  const detail::AdaptiveSolve solution =
      detail::refine(impl_->kernel, a, {load}, tolerance, impl_->independent.source(), rules);
  if (solution.converged) {
    ShapeVariables v;
    v.a_over_t = a;
    v.e_eq = solution.values[2];
    v.gamma1 = solution.values[3];
    if (!shape.flat()) {
      v.pi = solution.values[0];
      v.delta = solution.values[1];
    }
    v.error_estimate = solution.error_estimate;
    v.unknowns = solution.unknowns;
    return v;
  }
  // The coherent bound stands for the kernel term where the two-table estimate was not made.
  const double estimate = solution.kernel_error_kind == detail::KernelErrorKind::kNotEvaluated
                              ? solution.discretization_error + solution.kernel_bound + solution.rounding_error
                              : solution.error_estimate;
  std::ostringstream message;
  message.precision(3);
  message << "shape solve at a/t = " << detail::full_precision(a) << ": the error estimate " << estimate
          << " exceeds the tolerance " << tolerance << " (use a larger tolerance)";
  throw NumericalError(message.str());
}

}  // namespace coatcontact
