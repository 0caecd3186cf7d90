// The data of a curve's control plot (coatcontact/afm_batch.hpp, afm_curve_trace).
#include <cmath>
#include <limits>

#include "coatcontact/afm_batch.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit {

std::shared_ptr<const AfmCurveTrace> afm_curve_trace(const afm::ForceCurve& curve, const AfmBatchSettings& settings,
                                                     const AfmCurveFit* fitted) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  auto trace = std::make_shared<AfmCurveTrace>();
  trace->contact_point = fitted != nullptr ? fitted->result.contact_point : kNaN;
  std::vector<double> tip;
  if (fitted != nullptr) {
    tip = fitted->preprocessed.tip_position;
  } else {
    if (curve.force.size() != curve.point_count() || curve.metadata.spring_constant_source == afm::CalibrationSource::kNone) {
      return trace;  // no force or no tip position: nothing to draw
    }
    try {
      tip = curve.tip_position();
    } catch (const InputError&) {
      return trace;
    }
  }
  const bool retract_fit = settings.segment == afm::SegmentKind::kRetract;
  std::vector<double> model;
  if (fitted != nullptr) {
    model = afm_model_force(fitted->fitted, fitted->z_segment);
    for (std::size_t i = 0; i < model.size(); ++i) model[i] += fitted->subtracted_tilt * (fitted->z_segment[i] - fitted->reference_contact);
  }
  // The (first) approach, and the (first) retract of a retract fit.
  for (const afm::Segment* part : {curve.find_segment(afm::SegmentKind::kApproach),
                                   retract_fit ? curve.find_segment(afm::SegmentKind::kRetract) : nullptr}) {
    if (part == nullptr) continue;
    const afm::Segment& s = *part;
    const bool approach = s.kind == afm::SegmentKind::kApproach;
    const bool is_fitted_segment = fitted != nullptr && s.begin == fitted->segment.begin && s.end == fitted->segment.end;
    std::vector<char> kept;
    if (is_fitted_segment) {
      kept.assign(s.size(), 0);
      for (std::size_t k : fitted->kept) kept[k] = 1;
    }
    for (std::size_t i = s.begin; i < s.end && i < tip.size(); ++i) {
      trace->z.push_back(tip[i]);
      trace->force.push_back(curve.force[i]);
      trace->segment.push_back(approach ? 0 : 1);
      trace->model.push_back(is_fitted_segment ? model[i - s.begin] : kNaN);
      trace->fitted.push_back(is_fitted_segment ? kept[i - s.begin] : 0);
    }
  }
  return trace;
}

}  // namespace coatcontact::fit
