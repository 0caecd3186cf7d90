// The fit problem of a synthetic adhesive retract from its true parameters, shared by the JKR
// and Maugis-Dugdale retract tests (test_afm_jkr_fit.cpp, test_afm_md_fit.cpp). Truth holds
// radius, modulus, poisson, work, spring, contact, baseline, tilt, coated, substrate_modulus,
// substrate_poisson and thickness (SI); the start values are the truth.
#pragma once
#include "coatcontact/afm_fit.hpp"

template <class Truth>
coatcontact::fit::AfmFitProblem adhesive_problem(const Truth& t, coatcontact::fit::AfmModel model) {
  namespace fit = coatcontact::fit;
  fit::AfmFitProblem p;
  p.model = model;
  p.tip = fit::afm_paraboloid(t.radius);
  p.modulus = t.modulus;
  p.poisson = t.poisson;
  p.work = t.work;
  p.spring_constant = t.spring;
  p.contact_point = t.contact;
  p.baseline = t.baseline;
  p.tilt = t.tilt;
  if (t.coated) {
    fit::AfmCoating c;
    c.film = {t.modulus, t.poisson};
    c.substrate.material = {t.substrate_modulus, t.substrate_poisson};
    c.thickness = t.thickness;
    p.coating = c;
  }
  return p;
}
