// Elastic constants of the film and the substrate (THEORY.md section 1).
#pragma once
#include <string>

namespace coatcontact {

struct Material {
  double youngs_modulus = 1.0;  // E [Pa] (or any consistent unit)
  double poisson_ratio = 0.0;   // nu, allowed in (-1, 0.5]
  double reduced_modulus() const { return youngs_modulus / (1.0 - poisson_ratio * poisson_ratio); }
};

struct Substrate {
  bool rigid = false;  // E0 = infinity; `material` is then ignored
  Material material;
};

// Throws InputError naming `what` ("film", "substrate") if E <= 0, E not finite,
// or nu outside (-1, 0.5].
void validate(const Material& material, const std::string& what);
void validate(const Substrate& substrate);

// E1*/E0* (0 for a rigid substrate).
double modulus_ratio(const Material& film, const Substrate& substrate);

}  // namespace coatcontact
