// The fit problem of a synthetic adhesive retract from its true parameters, the recovery fit and
// its 3-standard-error checks, shared by the JKR and Maugis-Dugdale retract tests (test_afm_jkr_fit.cpp, test_afm_md_fit.cpp). Truth holds
// radius, modulus, poisson, work, spring, contact, baseline, tilt, coated, substrate_modulus,
// substrate_poisson and thickness (SI); the start values are the truth.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "check.hpp"
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

// The recovery fit: from a start away from the truth (E, or E1, 2.5 times off; w from the
// data; no tilt), with E, w, z_c, b and the tilt free and the noise sigma known.
inline coatcontact::fit::AfmFitResult fit_from_far_start(coatcontact::fit::AfmFitProblem p, double sigma,
                                                         const std::vector<double>& z, const std::vector<double>& f) {
  if (p.coating) p.coating->film.youngs_modulus *= 2.5;
  p.modulus *= 2.5;
  p.work = 0.0;
  p.tilt = 0.0;
  p.free = {true, true, true, false, true, true};
  p.noise_sigma = sigma;
  return coatcontact::fit::afm_fit(z, f, p);
}

// Each estimate's distance from the truth in its standard errors.
struct RecoveryScores {
  double modulus, work, contact, baseline, tilt;
};
template <class Truth>
RecoveryScores scores_of(const coatcontact::fit::AfmFitResult& r, const Truth& t) {
  return {(r.modulus - t.modulus) / r.modulus_error, (r.work - t.work) / r.work_error,
          (r.contact_point - t.contact) / r.contact_point_error, (r.baseline - t.baseline) / r.baseline_error,
          (r.tilt - t.tilt) / r.tilt_error};
}
inline void check_within_3_se(const RecoveryScores& z, const std::string& tag) {
  check::below(std::abs(z.modulus), 3.0, tag + ": E within 3 SE");
  check::below(std::abs(z.work), 3.0, tag + ": w within 3 SE");
  check::below(std::abs(z.contact), 3.0, tag + ": contact point within 3 SE");
  check::below(std::abs(z.baseline), 3.0, tag + ": baseline within 3 SE");
  check::below(std::abs(z.tilt), 3.0, tag + ": tilt within 3 SE");
}
