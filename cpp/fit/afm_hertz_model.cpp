// Hertz/Sneddon (THEORY.md section 15): the adhesionless force of any tip on the half-space or
// a coating, F = b + E* g(z_c - z) (+ a free tilt); the fit and the force are afm_curve_model.cpp's,
// beside the tip and coating tables the adhesive models share.
#include "afm_internal.hpp"

namespace coatcontact::fit::internal {

const AfmModelInfo& afm_model_hertz() {
  static const AfmModelInfo model{
      "hertz",
      {},
      "Hertz/Sneddon",
      "adhesionless Hertz/Sneddon fit",
      false,
      afm::SegmentKind::kApproach,
      afm_parameter_table({}, false),
      afm_fit_hertz,
      afm_hertz_model_force,
      [](const AfmFitProblem& problem, bool batch) -> std::string {
        if (!problem.free.tilt) return "F = b + E/(1 - nu^2) g(z_c - z), g: Hertz/Sneddon force per reduced modulus (0 out of contact)";
        return std::string("F = b + m (z - z_c) + E/(1 - nu^2) g(z_c - z), g: Hertz/Sneddon force per reduced modulus (0 out of contact)") +
               (batch ? "; the tilt m fitted, not subtracted" : "");
      },
      "",
      "adhesionless Hertz/Sneddon, any tip, default"};
  return model;
}

}  // namespace coatcontact::fit::internal
