// Material pairs for the tests: film or substrate constants, and the two substrate kinds.
#pragma once
#include "coatcontact/stack.hpp"

namespace coatcontact::test {

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

}  // namespace coatcontact::test
