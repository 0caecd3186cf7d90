// Gauss-Legendre rules on [-1, 1] (internal to coatcontact_solver).
#pragma once
#include <vector>

namespace coatcontact::detail {

struct GaussRule {
  std::vector<double> nodes;    // ascending, in (-1, 1)
  std::vector<double> weights;  // sum to 2
};

// Largest number of points served by gauss_rule().
constexpr int kMaxGaussPoints = 160;

// The n-point rule, 1 <= n <= kMaxGaussPoints (computed once, then shared read-only;
// safe to call from several threads).
const GaussRule& gauss_rule(int n);

// Legendre polynomials P_0..P_{count-1} at t (three-term recurrence).
inline void legendre_values(double t, int count, double* values) {
  values[0] = 1.0;
  if (count > 1) values[1] = t;
  for (int n = 2; n < count; ++n) {
    values[n] = ((2 * n - 1) * t * values[n - 1] - (n - 1) * values[n - 2]) / n;
  }
}

}  // namespace coatcontact::detail
