// Minimal checking helpers for the solver tests: every failed check is printed and counted,
// and main() returns the failure count (non-zero = test failure).
#pragma once
#include <cmath>
#include <cstdio>
#include <string>

#include "coatcontact/stack.hpp"

namespace coatcontact::test {

// Material pairs for the tests: film or substrate constants, and the two substrate kinds.
inline Material material(double e, double nu) {
  Material m;
  m.youngs_modulus = e;
  m.poisson_ratio = nu;
  return m;
}

inline Substrate rigid() {
  Substrate s;
  s.rigid = true;
  return s;
}

inline Substrate elastic(double e, double nu) {
  Substrate s;
  s.material = material(e, nu);
  return s;
}

inline int& failures() {
  static int count = 0;
  return count;
}

// |actual - expected| <= tolerance * max(|expected|, floor).
inline bool check_relative(const std::string& what, double actual, double expected,
                           double tolerance, double floor = 0.0) {
  const double error = std::abs(actual - expected) / std::max(std::abs(expected), floor);
  const bool ok = std::isfinite(actual) && error <= tolerance;
  if (!ok) {
    ++failures();
    std::printf("FAIL %s: %.17g vs %.17g (relative error %.3g > %.3g)\n", what.c_str(), actual,
                expected, error, tolerance);
  }
  return ok;
}

inline bool check(const std::string& what, bool condition) {
  if (!condition) {
    ++failures();
    std::printf("FAIL %s\n", what.c_str());
  }
  return condition;
}

inline int finish(const char* name) {
  if (failures() == 0) {
    std::printf("%s: all checks passed\n", name);
    return 0;
  }
  std::printf("%s: %d check(s) failed\n", name, failures());
  return 1;
}

}  // namespace coatcontact::test
