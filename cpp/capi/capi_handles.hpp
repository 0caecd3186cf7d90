// The layouts of the C API's handles that more than one of its files reads (capi.cpp makes
// them; capi_afm_fit.cpp takes a stack and a shape into an AFM request). Not a public header.
#pragma once
#include <memory>
#include <vector>

#include "coatcontact/coatcontact.h"
#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/stack.hpp"

// A stack under construction: checked piecewise by the setters, as a whole by build().
struct cc_stack {
  std::vector<coatcontact::Layer> layers;
  bool has_substrate = false;
  coatcontact::Substrate substrate;
  coatcontact::Indenter indenter;  // rigid
};

struct cc_shape {
  std::shared_ptr<const coatcontact::IndenterShape> shape;
  double sphere_radius = 0.0;  // R of a paraboloid (its validity limits are a sphere's), else 0
};
