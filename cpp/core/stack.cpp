// Validation of the elastic constants and the derived moduli of a Stack (THEORY.md section 1).
#include "coatcontact/stack.hpp"

#include <cmath>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

void validate(const Material& material, const std::string& what) {
  const double e = material.youngs_modulus;
  const double nu = material.poisson_ratio;
  if (!std::isfinite(e) || !(e > 0.0)) {
    throw InputError(what + ": Young's modulus " + detail::full_precision(e) +
                     " is not allowed; it must be finite and > 0");
  }
  // nu = -1 would make E* = E/(1 - nu^2) infinite; nu > 0.5 is thermodynamically impossible.
  if (!std::isfinite(nu) || !(nu > -1.0) || !(nu <= 0.5)) {
    throw InputError(what + ": Poisson ratio " + detail::full_precision(nu) +
                     " is outside the allowed range (-1, 0.5]");
  }
  if (!std::isfinite(material.reduced_modulus())) {
    throw InputError(what + ": Young's modulus " + detail::full_precision(e) +
                     " is too large (E/(1 - nu^2) overflows)");
  }
}

void validate(const Substrate& substrate) {
  if (!substrate.rigid) validate(substrate.material, "substrate");
}

void validate(const Indenter& indenter) {
  if (!indenter.rigid) validate(indenter.material, "indenter");
}

Stack Stack::film_on(const Material& film, const Substrate& substrate, const Indenter& indenter) {
  return Stack({Layer{1.0, film}}, substrate, indenter);
}

Stack::Stack(std::vector<Layer> layers, const Substrate& substrate, const Indenter& indenter)
    : layers_(std::move(layers)), substrate_(substrate), indenter_(indenter) {
  // THEORY.md section 12: 1 .. 1000 layers (the kernel's limit), top first.
  if (layers_.empty() || layers_.size() > max_layers) {
    throw InputError("stack: " + std::to_string(layers_.size()) +
                     " layers given; between 1 and " + std::to_string(max_layers) +
                     " are supported");
  }
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    // One layer keeps the historical name "film" in messages.
    const std::string what =
        layers_.size() == 1 ? std::string("film") : "layer " + std::to_string(i + 1);
    validate(layers_[i].material, what);
    const double h = layers_[i].thickness;
    if (!(h > 0.0) || !std::isfinite(h)) {
      throw InputError(what + ": thickness " + detail::full_precision(h) +
                       " is not allowed; it must be finite and > 0");
    }
  }
  if (!std::isfinite(total_thickness())) {
    throw InputError("stack: the total thickness overflows");
  }
  validate(substrate_);
  validate(indenter_);
}

double Stack::indenter_ratio() const {
  if (indenter_.rigid) return 0.0;
  return top().reduced_modulus() / indenter_.material.reduced_modulus();
}

double Stack::reference_modulus() const {
  // E_r = E1*/(1 + rho): the two bodies' compliances add (THEORY.md section 9).
  return top().reduced_modulus() / (1.0 + indenter_ratio());
}

double Stack::total_thickness() const {
  double sum = 0.0;
  for (const Layer& layer : layers_) sum += layer.thickness;
  return sum;
}

bool Stack::is_multilayer() const {
  return layers_.size() > 1 || layers_.front().slip_below;
}

double Stack::modulus_ratio() const {
  if (substrate_.rigid) return 0.0;
  return top().reduced_modulus() / substrate_.material.reduced_modulus();
}

double Stack::substrate_length_ratio() const {
  const double rho = indenter_ratio();
  return substrate_.rigid ? 1.0 : std::cbrt((modulus_ratio() + rho) / (1.0 + rho));
}

}  // namespace coatcontact
