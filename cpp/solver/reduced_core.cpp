// The reduced variables (reduced_core.hpp): the sphere and the cone as load cases.
#include "reduced_core.hpp"

#include <vector>

namespace coatcontact::detail {

namespace {

const std::vector<const Shape*>& sphere_and_cone() {
  static const SphereShape sphere;
  static const ConeShape cone;
  static const std::vector<const Shape*> shapes{&sphere, &cone};
  return shapes;
}

}  // namespace

FixedSolve solve_fixed(const KernelSource& kernel, double a, const Discretization& disc) {
  return solve_shapes(kernel, a, disc, sphere_and_cone());
}

AdaptiveSolve solve_adaptive(const KernelSource& kernel, double a, double tolerance,
                             const IndependentKernel& independent, double bound_limit) {
  RefinementRules rules;
  rules.bound_limit = bound_limit;
  return refine(kernel, a, sphere_and_cone(), tolerance, independent, rules);
}

}  // namespace coatcontact::detail
