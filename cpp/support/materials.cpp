// Material validation (THEORY.md section 1: film E1, nu1 on substrate E0, nu0).
#include "coatcontact/materials.hpp"

#include <cmath>

#include "coatcontact/errors.hpp"
#include "number_text.hpp"

namespace coatcontact {

void validate(const Material& material, const std::string& what) {
  const double e = material.youngs_modulus;
  const double nu = material.poisson_ratio;
  if (!std::isfinite(e) || !(e > 0.0)) {
    throw InputError(what + ": Young's modulus " + detail::number_string(e) +
                     " is not allowed; it must be finite and > 0");
  }
  // nu = -1 would make E* = E/(1 - nu^2) infinite; nu > 0.5 is thermodynamically impossible.
  if (!std::isfinite(nu) || !(nu > -1.0) || !(nu <= 0.5)) {
    throw InputError(what + ": Poisson ratio " + detail::number_string(nu) +
                     " is outside the allowed range (-1, 0.5]");
  }
  if (!std::isfinite(material.reduced_modulus())) {
    throw InputError(what + ": Young's modulus " + detail::number_string(e) +
                     " is too large (E/(1 - nu^2) overflows)");
  }
}

void validate(const Substrate& substrate) {
  if (!substrate.rigid) validate(substrate.material, "substrate");
}

double modulus_ratio(const Material& film, const Substrate& substrate) {
  if (substrate.rigid) return 0.0;
  return film.reduced_modulus() / substrate.material.reduced_modulus();
}

}  // namespace coatcontact
