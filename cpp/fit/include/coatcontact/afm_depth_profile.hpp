// The modulus against indentation depth of one AFM curve (THEORY.md section 15, "Modulus against
// depth"): the one-curve fit (afm_fit_curve) repeated with the maximum indentation of its range
// raised step by step, and, on a coating, the half-space fit of the same points beside it (the
// apparent modulus, in which the substrate shows as a drift with depth).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/force_curve.hpp"

namespace coatcontact::fit {

// Depths are indentations from the contact point of the whole-range fit (the reference fit,
// afm_fit_curve of the request as given): the preprocessing's contact point (a power-1.5 law)
// lies late on a coating, whose force rises faster, and would cut the shallow part. The default
// depths (afm_depth_sequence): kDepthProfileSteps depths spaced evenly in log from the
// indentation of the kDepthProfileFirstPoints-th fitted point past that contact point (and at
// least 1/kDepthProfileSpan of the deepest) to the deepest fitted indentation.
constexpr std::size_t kDepthProfileSteps = 10;
constexpr std::size_t kDepthProfileFirstPoints = 10;
constexpr double kDepthProfileSpan = 30.0;
// On a coating a step whose fitted maximum indentation exceeds this fraction of t is marked
// (THEORY.md section 15, "Modulus against depth": the film's strain under a contact wider than
// the film is about delta/t, and the model's linear elasticity is off by about that strain).
constexpr double kDepthProfileThicknessFraction = 0.1;

struct AfmDepthStep {
  double depth = 0.0;  // [m] the maximum indentation asked, from the reference fit's contact point
  AfmFlag flag = AfmFlag::kFitted;  // of the fit at this depth (a flag without estimates: the values are NaN)
  std::string message;              // why, for a flag
  double max_indentation = 0.0;     // [m] the deepest fitted indentation, from the fitted contact point
  double modulus = 0.0, modulus_error = 0.0;  // E (half-space) or E1 (coating) [Pa]
  std::size_t points = 0, points_in_contact = 0;
  double chi2_per_dof = 0.0;
  // A coating only: the half-space fit of the same request without the coating (E free, the
  // film's nu): the apparent modulus.
  AfmFlag apparent_flag = AfmFlag::kFitted;
  double apparent_modulus = 0.0, apparent_modulus_error = 0.0;  // [Pa]
  bool beyond_thickness_fraction = false;  // coating: max_indentation > kDepthProfileThicknessFraction t
};

struct AfmDepthProfile {
  std::string modulus_name;  // "E" or "E1"
  bool coated = false;
  double thickness = 0.0;    // [m] the coating's t (fixed in the profile)
  double reference_contact_point = 0.0;  // [m] of the whole-range fit (the depths' origin)
  AfmCurveFit reference;     // the whole-range fit
  std::vector<AfmDepthStep> steps;
  std::vector<std::string> warnings;  // the steps beyond the fraction of t, in words
};

// The default depths of a whole-range fit (InputError when it has fewer than
// kDepthProfileFirstPoints fitted points past its contact point).
std::vector<double> afm_depth_sequence(const AfmCurveFit& reference);

// Fits the curve at each depth d (afm_fit_curve with the range's maximum indentation, which is
// relative to the preprocessing's contact point z_ref, set to d - (z_c - z_ref), z_c the
// reference fit's contact point; and kept below the request's own), in the order given; empty
// `depths`: afm_depth_sequence. A depth whose fit fails is a step with its flag (the others go
// on); a failing reference fit throws as afm_fit_curve does.
// InputError for a request the profile cannot take: a model other than hertz, a fixed modulus,
// a free thickness (t is the length the profile is read against), an empty or non-positive depth.
AfmDepthProfile afm_depth_profile(const afm::ForceCurve& curve, const AfmCurveRequest& request,
                                  const std::vector<double>& depths);

}  // namespace coatcontact::fit
