// The modulus against indentation depth (coatcontact/afm_depth_profile.hpp, THEORY.md section 15).
#include "coatcontact/afm_depth_profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "coatcontact/errors.hpp"

namespace coatcontact::fit {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One fit of the profile: its flag, and the estimates when the flag keeps them.
struct StepFit {
  AfmFlag flag = AfmFlag::kFitted;
  std::string message;
  AfmCurveFit fit;
};

// `limit`: the maximum indentation from the preprocessing's contact point (the range's frame).
StepFit fit_at(const afm::ForceCurve& curve, const AfmCurveRequest& request, double limit) {
  AfmCurveRequest at = request;
  at.range.indentation_max = at.range.indentation_max ? std::min(*at.range.indentation_max, limit) : limit;
  StepFit out;
  try {
    out.fit = afm_fit_curve(curve, at);
    out.flag = out.fit.flag;
    if (!out.fit.flag_warnings.empty()) out.message = out.fit.flag_warnings.front();
  } catch (const AfmCurveInputError& error) {
    out.flag = error.flag();
    out.message = error.what();
  } catch (const AfmCurveNumericalError& error) {
    out.flag = error.flag();
    out.message = error.what();
  }
  return out;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

}  // namespace

std::vector<double> afm_depth_sequence(const AfmCurveFit& reference) {
  const double zc = reference.result.contact_point;
  std::vector<double> depths;
  for (std::size_t i : reference.kept) {
    const double d = zc - reference.z_segment[i];
    if (d > 0.0 && std::isfinite(d)) depths.push_back(d);
  }
  if (depths.size() < kDepthProfileFirstPoints) {
    throw InputError("depth profile: the fit has " + std::to_string(depths.size()) +
                     " points past its contact point; a profile needs at least " + std::to_string(kDepthProfileFirstPoints));
  }
  std::sort(depths.begin(), depths.end());
  const double last = depths.back();
  const double first = std::max(depths[kDepthProfileFirstPoints - 1], last / kDepthProfileSpan);
  if (!(first < last)) return {last};
  std::vector<double> out;
  for (std::size_t k = 0; k < kDepthProfileSteps; ++k) {
    const double x = static_cast<double>(k) / static_cast<double>(kDepthProfileSteps - 1);
    out.push_back(k + 1 == kDepthProfileSteps ? last : first * std::pow(last / first, x));
  }
  return out;
}

AfmDepthProfile afm_depth_profile(const afm::ForceCurve& curve, const AfmCurveRequest& request,
                                  const std::vector<double>& depths) {
  const AfmFitProblem& problem = request.problem;
  if (problem.model != AfmModel::kHertz) {
    throw InputError("depth profile: takes the adhesionless fit (model hertz); the adhesive models fit the retract's pull-off");
  }
  if (!problem.free.modulus) throw InputError("depth profile: the modulus must be free (it is what the profile follows)");
  if (problem.coating && problem.coating->multilayer()) {
    throw InputError("depth profile: takes a half-space or one film (--film); a stack of " +
                     std::to_string(problem.coating->layers.size()) + " layers is fitted whole (without --depth-profile)");
  }
  if (problem.coating && problem.free.thickness) {
    throw InputError("depth profile: t must be fixed on a coating (the depths are read against it)");
  }
  for (double d : depths) {
    if (!(d > 0.0 && std::isfinite(d))) throw InputError("depth profile: a depth " + number(d) + " m is not allowed; depths must be > 0");
  }
  AfmDepthProfile profile;
  profile.reference = afm_fit_curve(curve, request);
  profile.reference_contact_point = profile.reference.result.contact_point;
  // The depths' origin in the range's frame: d from z_c is d - (z_c - z_ref) from z_ref.
  const double shift = profile.reference_contact_point - profile.reference.reference_contact;
  const std::vector<double> asked = depths.empty() ? afm_depth_sequence(profile.reference) : depths;
  profile.coated = problem.coating.has_value();
  profile.modulus_name = profile.coated ? "E1" : "E";
  // The half-space beside a coating: the same request, E free from the film's start value.
  AfmCurveRequest halfspace = request;
  if (profile.coated) {
    profile.thickness = problem.coating->thickness;
    halfspace.problem.coating.reset();
    halfspace.problem.modulus = problem.coating->film.youngs_modulus;
    halfspace.problem.poisson = problem.coating->film.poisson_ratio;
    halfspace.problem.free.thickness = false;
  }
  for (double depth : asked) {
    AfmDepthStep step;
    step.depth = depth;
    const StepFit own = fit_at(curve, request, depth - shift);
    step.flag = own.flag;
    step.message = own.message;
    const bool kept = afm_flag_keeps_estimates(own.flag);
    const AfmFitResult& r = own.fit.result;
    step.max_indentation = kept ? r.max_indentation : kNaN;
    step.modulus = kept ? r.modulus : kNaN;
    step.modulus_error = kept ? r.modulus_error : kNaN;
    step.points = kept ? r.points : 0;
    step.points_in_contact = kept ? r.points_in_contact : 0;
    step.chi2_per_dof = kept ? r.chi2_per_dof : kNaN;
    step.apparent_modulus = step.apparent_modulus_error = kNaN;
    if (profile.coated) {
      const StepFit apparent = fit_at(curve, halfspace, depth - shift);
      step.apparent_flag = apparent.flag;
      if (afm_flag_keeps_estimates(apparent.flag)) {
        step.apparent_modulus = apparent.fit.result.modulus;
        step.apparent_modulus_error = apparent.fit.result.modulus_error;
      }
      step.beyond_thickness_fraction = kept && r.max_indentation > kDepthProfileThicknessFraction * profile.thickness;
      if (step.beyond_thickness_fraction) {
        profile.warnings.push_back("depth " + number(depth) + " m: the fitted indentation " + number(r.max_indentation) +
                                   " m exceeds " + number(kDepthProfileThicknessFraction) + " t = " +
                                   number(kDepthProfileThicknessFraction * profile.thickness) +
                                   " m, where the film's strain leaves the linear model's range (THEORY.md section 15)");
      }
    }
    profile.steps.push_back(step);
  }
  return profile;
}

}  // namespace coatcontact::fit
