// The elastic system of a contact problem (THEORY.md sections 1, 9, 12): the layers of the
// coating, top first, on an elastic half-space or a rigid base, pressed by an indenter.
// Every floor above the kernel receives a Stack, never loose moduli: the reference modulus
// that makes P, D, a_bar, eta and the reduced variables dimensionless is the stack's.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace coatcontact {

struct Material {
  double youngs_modulus = 1.0;  // E [Pa] (or any consistent unit)
  double poisson_ratio = 0.0;   // nu, allowed in (-1, 0.5]
  // E* = E/(1 - nu^2), the plane-strain modulus.
  double reduced_modulus() const { return youngs_modulus / (1.0 - poisson_ratio * poisson_ratio); }
};

// The half-space below the coating.
struct Substrate {
  bool rigid = false;  // E0 = infinity; `material` is then ignored
  Material material;
};

struct Layer {
  double thickness = 1.0;  // any unit; only ratios to the total thickness enter C(q)
  Material material;
  // The interface BELOW this layer is frictionless (THEORY.md section 12); below the last
  // layer on a rigid base: a frictionless rigid base (u_z = 0, s_rz = 0).
  bool slip_below = false;
};

// The indenter's elastic constants: rigid (the paper's case) or a homogeneous elastic
// half-space (THEORY.md section 9).
struct Indenter {
  bool rigid = true;
  Material material;
};

class Stack {
 public:
  // A film bonded to `substrate` (the paper's system); the film thickness is the unit length.
  static Stack film_on(const Material& film, const Substrate& substrate,
                       const Indenter& indenter = {});
  // Up to max_layers layers, top first (THEORY.md section 12). Normalization: lengths by the
  // TOTAL thickness T, moduli by the TOP layer's E* (E_r with an elastic indenter).
  // Validates every constant (InputError naming the layer, the value and the allowed range).
  static constexpr std::size_t max_layers = 1000;
  Stack(std::vector<Layer> layers, const Substrate& substrate, const Indenter& indenter = {});

  const std::vector<Layer>& layers() const { return layers_; }
  const Material& top() const { return layers_.front().material; }
  const Substrate& substrate() const { return substrate_; }
  const Indenter& indenter() const { return indenter_; }
  double total_thickness() const;
  // The modulus of the normalization (THEORY.md sections 5, 9): the top layer's E* for a
  // rigid indenter, else E_r with 1/E_r = 1/E1* + 1/E2*.
  double reference_modulus() const;
  // rho = E1*/E2* (0 for a rigid indenter): the kernel sees C' = (C + rho)/(1 + rho) (section 9).
  double indenter_ratio() const;
  // E_top*/E_base*, the stack's C(0) (0 for a rigid base).
  double modulus_ratio() const;
  // More than one layer or a slip flag: the kernel is section 12's (else section 3's, whose
  // numbers are kept bit for bit).
  bool is_multilayer() const;
  // Length scale of the reduced-variable curves' default ranges: C'(0)^(1/3) = (E_r/E_r,base)^(1/3),
  // 1 when the base is rigid.
  double substrate_length_ratio() const;

 private:
  std::vector<Layer> layers_;
  Substrate substrate_;
  Indenter indenter_;
};

// Throws InputError naming `what` ("film", "substrate") if E <= 0, E not finite,
// or nu outside (-1, 0.5].
void validate(const Material& material, const std::string& what);
void validate(const Substrate& substrate);
void validate(const Indenter& indenter);

}  // namespace coatcontact
