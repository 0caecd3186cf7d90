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

// A soft layer (t = 1, E = 1) on a stiff one (t = 2, E = 20) on E0 = 5: the stack the table
// and sweep tests check beside their film pairs.
inline Stack soft_on_stiff_layers() {
  Layer top, bottom;
  top.thickness = 1.0;
  top.material = material(1.0, 0.3);
  bottom.thickness = 2.0;
  bottom.material = material(20.0, 0.3);
  return Stack({top, bottom}, elastic(5.0, 0.25));
}

}  // namespace coatcontact::test
