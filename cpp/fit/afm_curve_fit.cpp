// The one AFM fit of a force curve (coatcontact/afm_curve_fit.hpp, THEORY.md section 15).
#include "coatcontact/afm_curve_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>

#include "coatcontact/afm_models.hpp"

namespace coatcontact::fit {

const char* afm_flag_name(AfmFlag flag) {
  switch (flag) {
    case AfmFlag::kFitted: return "fitted";
    case AfmFlag::kNoContact: return "no_contact";
    case AfmFlag::kJumpIn: return "jump_in";
    case AfmFlag::kNoConvergence: return "no_convergence";
    case AfmFlag::kEmptySegment: return "empty_segment";
    case AfmFlag::kMissingSegment: return "missing_segment";
    case AfmFlag::kCalibration: return "calibration";
    case AfmFlag::kTooFewPoints: return "too_few_points";
    case AfmFlag::kUnreadable: return "unreadable";
    case AfmFlag::kBadData: return "bad_data";
    case AfmFlag::kUndetermined: return "undetermined";
    case AfmFlag::kNoDetachment: return "no_detachment";
  }
  return "unknown";
}

bool afm_flag_keeps_estimates(AfmFlag flag) {
  return flag == AfmFlag::kFitted || flag == AfmFlag::kUndetermined || flag == AfmFlag::kNoDetachment;
}

double afm_rating(AfmFlag flag, double residual_sigma, double noise_sigma, double model_span, std::size_t points_in_contact,
                  bool warnings) {
  if (!afm_flag_keeps_estimates(flag)) return 0.0;
  if (!(residual_sigma > 0.0) || !std::isfinite(residual_sigma)) return 0.0;
  const double noise = noise_sigma > 0.0 ? noise_sigma : residual_sigma;
  const double s_fit = std::min(1.0, noise / residual_sigma);
  const double s_signal = model_span > noise ? std::min(1.0, std::log10(model_span / noise) / kRatingSignalDecades) : 0.0;
  const double s_contact = std::min(1.0, static_cast<double>(points_in_contact) / kRatingContactPoints);
  double s_flag = flag == AfmFlag::kFitted ? 1.0 : kRatingKeptFlag;
  if (warnings) s_flag *= kRatingWarning;
  return 10.0 * s_fit * s_signal * s_contact * s_flag;
}

const char* afm_baseline_model_name(AfmBaselineModel model) {
  return model == AfmBaselineModel::kTilt ? "tilt" : "offset";
}

namespace {

bool says(const std::string& message, const char* phrase) { return message.find(phrase) != std::string::npos; }

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

// The segment's checks: it exists, the approach exists (baseline, contact point), no segment
// is empty, the force channel is there.
const afm::Segment& checked_segment(const afm::ForceCurve& curve, afm::SegmentKind kind) {
  const std::string& file = curve.metadata.source_file;
  const afm::Segment* segment = curve.find_segment(kind);
  if (segment == nullptr) {
    throw AfmCurveInputError(AfmFlag::kMissingSegment,
                             "--segment: " + file + " has no " + afm::segment_kind_name(kind) + " segment");
  }
  if (curve.find_segment(afm::SegmentKind::kApproach) == nullptr) {
    throw AfmCurveInputError(AfmFlag::kMissingSegment,
                             file + ": no approach segment (the baseline and contact point need it)");
  }
  for (const afm::Segment& s : curve.segments) {
    if (s.size() == 0) throw AfmCurveInputError(AfmFlag::kEmptySegment, file + ": an empty segment");
  }
  if (curve.force.size() != curve.point_count()) {
    throw AfmCurveInputError(AfmFlag::kCalibration, file + ": no force channel (missing calibration)");
  }
  return *segment;
}

afm::PreprocessedCurve preprocessed(const afm::ForceCurve& curve, const afm::PreprocessOptions& options) {
  try {
    return afm::preprocess(curve, options);
  } catch (const InputError& error) {
    const std::string message = error.what();
    if (says(message, "no contact")) throw AfmCurveInputError(AfmFlag::kNoContact, message);
    if (says(message, "spring constant")) throw AfmCurveInputError(AfmFlag::kCalibration, message);
    throw AfmCurveInputError(AfmFlag::kTooFewPoints, message);
  } catch (const NumericalError& error) {
    throw AfmCurveNumericalError(AfmFlag::kNoConvergence, error.what());
  }
}

void check_jump_in(const afm::ForceCurve& curve, const afm::PreprocessedCurve& steps) {
  if (!(steps.baseline_sigma > 0.0)) return;
  const afm::Segment* approach = curve.find_segment(afm::SegmentKind::kApproach);
  const auto first = steps.force_corrected.begin() + static_cast<std::ptrdiff_t>(approach->begin);
  const auto last = steps.force_corrected.begin() + static_cast<std::ptrdiff_t>(approach->end);
  const auto [low, high] = std::minmax_element(first, last);
  if (*low < -kJumpInSigmas * steps.baseline_sigma && -*low > kJumpInFraction * *high) {
    throw AfmCurveInputError(AfmFlag::kJumpIn, "the approach force dips " + std::to_string(-*low / steps.baseline_sigma) +
                                                   " baseline sigmas below its baseline, " +
                                                   std::to_string(-*low / *high) + " of its largest force");
  }
}

// The steps in words, as the headers and Python record them.
std::vector<AfmStep> step_records(const afm::ForceCurve& curve, const afm::PreprocessOptions& options, const AfmCurveFit& f) {
  const afm::PreprocessedCurve& p = f.preprocessed;
  std::vector<AfmStep> steps;
  steps.push_back({"tip position", std::string(curve.tip_position_height_name()) + " + force / spring constant"});
  steps.push_back({"baseline", "force = offset + slope * tip position, least squares on the first " +
                                   std::to_string(p.baseline_points) + " approach points (fraction " +
                                   number(options.baseline_fraction) + "): offset " + number(p.baseline_offset) +
                                   " N, slope " + number(p.baseline_slope) + " N/m, sigma " + number(p.baseline_sigma) + " N"});
  std::string method = afm::contact_point_method_name(p.contact_method);
  if (p.contact_method == afm::ContactPointMethod::kDeviation) method += " (" + number(options.deviation_sigmas) + " baseline sigmas)";
  else method += " (F = A (z_c - z)^" + number(options.piecewise_exponent) + ")";
  steps.push_back({"contact point", method + ": " + number(p.contact_point) + " m (point " + std::to_string(p.contact_index) + ")"});
  steps.push_back({"baseline model",
                   f.baseline == AfmBaselineModel::kTilt
                       ? "tilt: the slope " + number(f.subtracted_tilt) + " N/m times (z - " + number(f.reference_contact) +
                             " m) subtracted from the forces; b is the baseline at the contact point"
                       : std::string("offset: the forces as measured, b constant") +
                             (f.problem.free.tilt ? " (the model's tilt is free)" : "")});
  if (f.problem.weight_cp > 0.0) {
    steps.push_back({"weighting", "nanite's contact-point weights: residuals times min(|z - z_c|/D, 1), D = " +
                                      number(f.problem.weight_cp) + " m"});
  }
  return steps;
}

std::vector<double> slice(const std::vector<double>& v, const afm::Segment& s) {
  return {v.begin() + static_cast<std::ptrdiff_t>(s.begin), v.begin() + static_cast<std::ptrdiff_t>(s.end)};
}

// The spring-constant rule of the adhesive models: the user's value, else the curve's, else an error.
double spring_constant(const afm::ForceCurve& curve, const AfmFitProblem& problem) {
  if (problem.spring_constant > 0.0) return problem.spring_constant;
  const double k = curve.metadata.spring_constant;
  if (!(curve.metadata.spring_constant_source != afm::CalibrationSource::kNone && k > 0.0 && std::isfinite(k))) {
    throw AfmCurveInputError(AfmFlag::kCalibration, curve.metadata.source_file +
                                                        ": the adhesive model needs the cantilever's spring constant; "
                                                        "the file has none (give --spring-constant K)");
  }
  return k;
}

AfmFitResult fitted_result(const std::vector<double>& z, const std::vector<double>& f, const AfmFitProblem& problem) {
  AfmFitResult r;
  try {
    r = afm_fit(z, f, problem);
  } catch (const AfmCurveNumericalError&) {
    throw;
  } catch (const NumericalError& error) {
    const std::string message = error.what();
    throw AfmCurveNumericalError(says(message, "no contact") || says(message, "no point in contact") ? AfmFlag::kNoContact
                                                                                                     : AfmFlag::kNoConvergence,
                                 message);
  } catch (const AfmCurveInputError&) {
    throw;
  } catch (const InputError& error) {
    throw AfmCurveInputError(AfmFlag::kBadData, error.what());
  }
  bool finite = std::isfinite(r.chi2) && std::isfinite(r.contact_point) && std::isfinite(r.residual_sigma);
  for (double v : {r.modulus, r.modulus_error, r.thickness, r.thickness_error, r.baseline, r.baseline_error, r.work,
                   r.work_error, r.tilt, r.tilt_error, r.contact_point_error}) {
    finite = finite && std::isfinite(v);
  }
  if (!finite) throw AfmCurveNumericalError(AfmFlag::kNoConvergence, "the fit gave non-finite estimates or errors");
  return r;
}

// The honest flags of a fit (afm_curve_fit.hpp): a free scale parameter (E, E1, t, w) whose
// standard error exceeds its value is undetermined; a retract fit whose retract does not end
// at the approach's free-cantilever level never detached. The estimates stay.
void check_determined(AfmCurveFit& out) {
  const AfmFitResult& r = out.result;
  const bool coated = out.problem.coating.has_value();
  for (const AfmParameterInfo& p : out.problem.model.info().parameters) {
    // The scale parameters (bounded below by 0: E, E1, t, w), as the model's table lists them.
    if (!(p.lower >= 0.0) || !(out.problem.free.*p.free) || (p.coating_only && !coated)) continue;
    const double value = r.*p.value, error = r.*p.error;
    if (!(error <= std::abs(value))) {
      if (out.flag == AfmFlag::kFitted) out.flag = AfmFlag::kUndetermined;
      out.flag_warnings.push_back("undetermined: " + afm_parameter_name(p, coated) + " = " + number(value) +
                                  " has a standard error " + number(error) + " larger than its value (the estimate is kept)");
    }
  }
}

void check_detachment(const afm::ForceCurve& curve, AfmCurveFit& out) {
  const afm::PreprocessedCurve& p = out.preprocessed;
  const afm::Segment* retract = curve.find_segment(afm::SegmentKind::kRetract);
  const afm::Segment* approach = curve.find_segment(afm::SegmentKind::kApproach);
  if (retract == nullptr || approach == nullptr || !(p.baseline_sigma > 0.0)) return;
  const std::size_t n = retract->size();
  const std::size_t tail = std::max<std::size_t>(3, static_cast<std::size_t>(kDetachmentTailFraction * static_cast<double>(n)));
  if (n < tail) return;
  double mean = 0.0;
  for (std::size_t i = retract->end - tail; i < retract->end; ++i) mean += p.force_corrected[i];
  mean /= static_cast<double>(tail);
  const auto first = p.force_corrected.begin() + static_cast<std::ptrdiff_t>(approach->begin);
  const auto last = p.force_corrected.begin() + static_cast<std::ptrdiff_t>(approach->end);
  const double largest = *std::max_element(first, last);
  if (std::abs(mean) > kDetachmentSigmas * p.baseline_sigma && std::abs(mean) > kDetachmentFraction * largest) {
    out.flag = AfmFlag::kNoDetachment;
    out.flag_warnings.insert(out.flag_warnings.begin(),
                             "no_detachment: the retract ends " + number(mean) + " N off the free-cantilever baseline (" +
                                 number(std::abs(mean) / p.baseline_sigma) + " baseline sigmas): the tip never detached");
  }
}

double model_span(const AfmFitResult& r) {
  if (r.model_force.empty()) return 0.0;
  const auto [low, high] = std::minmax_element(r.model_force.begin(), r.model_force.end());
  return *high - *low;
}

}  // namespace

AfmMeasuredPulloff afm_measured_pulloff(const std::vector<double>& tip_position, const std::vector<double>& force,
                                        double fraction) {
  AfmMeasuredPulloff p;
  const std::size_t n = std::min(tip_position.size(), force.size());
  const auto points = static_cast<std::size_t>(std::floor(fraction * static_cast<double>(n)));
  if (points < 3) return p;
  const std::size_t first = n - points;  // the retract ends with the tip far from the sample
  double cov00 = 0.0, cov01 = 0.0, cov11 = 0.0, sumsq = 0.0;
  if (gsl_fit_linear(tip_position.data() + first, 1, force.data() + first, 1, points, &p.baseline_offset,
                     &p.baseline_slope, &cov00, &cov01, &cov11, &sumsq) != GSL_SUCCESS ||
      !std::isfinite(p.baseline_offset) || !std::isfinite(p.baseline_slope)) {
    return p;  // one tip position (no slope): no baseline to measure against
  }
  p.baseline_points = points;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = force[i] - (p.baseline_offset + p.baseline_slope * tip_position[i]);
    if (!p.found || f < p.force) {
      p.found = true;
      p.force = f;
      p.tip_position = tip_position[i];
      p.index = i;
    }
  }
  return p;
}

AfmCurveFit afm_fit_curve(const afm::ForceCurve& curve, const AfmCurveRequest& request) {
  AfmCurveFit out;
  out.segment = checked_segment(curve, request.segment);
  out.preprocessed = preprocessed(curve, request.preprocess);
  const afm::PreprocessedCurve& steps = out.preprocessed;
  if (request.check_jump_in && request.segment == afm::SegmentKind::kApproach) check_jump_in(curve, steps);
  out.problem = request.problem;
  if (!(out.problem.noise_sigma > 0.0)) out.problem.noise_sigma = steps.baseline_sigma;
  if (out.problem.model.info().needs_spring) out.problem.spring_constant = spring_constant(curve, request.problem);
  // A free tilt is the model's: the baseline step is then the offset (never counted twice).
  out.baseline = out.problem.free.tilt ? AfmBaselineModel::kOffset : request.baseline;
  out.subtracted_tilt = out.baseline == AfmBaselineModel::kTilt ? steps.baseline_slope : 0.0;
  out.reference_contact = steps.contact_point;
  out.reference_baseline = steps.baseline_offset + steps.baseline_slope * steps.contact_point;
  out.steps = step_records(curve, request.preprocess, out);

  const std::vector<double>& tip = steps.tip_position;
  out.z_segment = slice(tip, out.segment);
  out.f_segment = slice(curve.force, out.segment);
  for (std::size_t i = 0; i < out.f_segment.size(); ++i) out.f_segment[i] -= out.subtracted_tilt * (out.z_segment[i] - out.reference_contact);
  out.kept = afm_select(out.z_segment, out.f_segment, request.range, out.reference_contact, out.reference_baseline);
  const std::string kind_name = afm::segment_kind_name(request.segment);
  if (out.kept.size() < request.min_points) {
    throw AfmCurveInputError(AfmFlag::kTooFewPoints, "the range options leave " + std::to_string(out.kept.size()) +
                                                         " points of the " + kind_name + " segment (" +
                                                         std::to_string(out.z_segment.size()) + "; need " +
                                                         std::to_string(request.min_points) + "); widen them");
  }
  std::vector<double> z, f;
  z.reserve(out.kept.size());
  f.reserve(out.kept.size());
  for (std::size_t i : out.kept) {
    z.push_back(out.z_segment[i]);
    f.push_back(out.f_segment[i]);
  }
  out.result = fitted_result(z, f, out.problem);
  const AfmFitResult& r = out.result;
  out.fitted = out.problem;
  out.fitted.modulus = r.modulus;
  out.fitted.contact_point = r.contact_point;
  out.fitted.baseline = r.baseline;
  out.fitted.work = r.work;
  out.fitted.tilt = r.tilt;
  if (out.fitted.coating) {
    out.fitted.coating->film.youngs_modulus = r.modulus;
    out.fitted.coating->thickness = r.thickness;
  }
  if (const afm::Segment* retract = curve.find_segment(afm::SegmentKind::kRetract)) {
    out.pulloff = afm_measured_pulloff(slice(tip, *retract), slice(curve.force, *retract), request.preprocess.baseline_fraction);
    if (out.pulloff.found) out.pulloff.index += retract->begin;
  }
  check_determined(out);
  if (request.segment == afm::SegmentKind::kRetract) check_detachment(curve, out);
  out.rating = afm_rating(out.flag, r.residual_sigma, out.problem.noise_sigma, model_span(r), r.points_in_contact,
                          !r.warnings.empty());
  return out;
}

}  // namespace coatcontact::fit
