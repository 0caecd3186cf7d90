// Gauss-Legendre nodes by Newton iteration on the Legendre recurrence (accurate to a few
// ulps for n <= 160, which is all the solver uses).
#include "gauss_legendre.hpp"

#include "coatcontact/detail/constants.hpp"

#include <array>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace coatcontact::detail {

namespace {

GaussRule compute_rule(int n) {
  GaussRule rule;
  rule.nodes.assign(n, 0.0);
  rule.weights.assign(n, 0.0);
  for (int k = 0; k < (n + 1) / 2; ++k) {
    // Tricomi's initial guess for the k-th largest root, then Newton.
    double x = std::cos(detail::kPi * (k + 0.75) / (n + 0.5)) *
               (1.0 - (n - 1.0) / (8.0 * n * n * n));
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int m = 2; m <= n; ++m) {
        const double p2 = ((2 * m - 1) * x * p1 - (m - 1) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      const double step = p1 / (n * (x * p1 - p0) / (x * x - 1.0));
      x -= step;
      if (std::abs(step) < 1e-15) break;  // quadratic convergence: the next step is < 1e-30
    }
    // Derivative at the converged root for the weight.
    double p0 = 1.0, p1 = x;
    for (int m = 2; m <= n; ++m) {
      const double p2 = ((2 * m - 1) * x * p1 - (m - 1) * p0) / m;
      p0 = p1;
      p1 = p2;
    }
    const double derivative = n * (x * p1 - p0) / (x * x - 1.0);
    const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    rule.nodes[n - 1 - k] = x;
    rule.nodes[k] = -x;
    rule.weights[n - 1 - k] = weight;
    rule.weights[k] = weight;
  }
  if (n % 2 == 1) rule.nodes[n / 2] = 0.0;
  return rule;
}

// Each rule is computed on first use (std::call_once: thread-safe, then read-only).
struct RuleTable {
  std::array<GaussRule, kMaxGaussPoints + 1> rules;
  std::array<std::once_flag, kMaxGaussPoints + 1> once;
};

}  // namespace

const GaussRule& gauss_rule(int n) {
  static RuleTable table;
  if (n < 1 || n > kMaxGaussPoints) {
    throw std::logic_error("gauss_rule: unsupported number of points");
  }
  const auto index = static_cast<std::size_t>(n);
  std::call_once(table.once[index], [&] { table.rules[index] = compute_rule(n); });
  return table.rules[index];
}

}  // namespace coatcontact::detail
