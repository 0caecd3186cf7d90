// Consumer of the installed package, in C++: prints E_eq of one case (see run_install_test.sh).
#include <cstdio>
#include <exception>

#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

// ---- the only call into the library's C++ API ----
// Film E1 = 0.1, nu1 = 0.25 on substrate E0 = 1, nu0 = 0.25, a/t = 1, default tolerance.
static double solve_e_eq() {
  const coatcontact::Material film{0.1, 0.25};
  coatcontact::Substrate substrate;
  substrate.material = coatcontact::Material{1.0, 0.25};
  return coatcontact::ReducedSolver(coatcontact::Stack::film_on(film, substrate)).solve(1.0).e_eq;
}

int main() {
  try {
    std::printf("%.17g\n", solve_e_eq());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "consumer_cxx: %s\n", error.what());
    return 1;
  }
  return 0;
}
