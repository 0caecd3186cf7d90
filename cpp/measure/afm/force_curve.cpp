// ForceCurve helpers: names of segment kinds and calibration sources, the tip position.
#include "coatcontact/force_curve.hpp"

#include "coatcontact/errors.hpp"

namespace coatcontact::afm {

const char* segment_kind_name(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::kApproach: return "approach";
    case SegmentKind::kPause: return "pause";
    case SegmentKind::kRetract: return "retract";
  }
  return "unknown";
}

const char* calibration_source_name(CalibrationSource source) {
  switch (source) {
    case CalibrationSource::kNone: return "none";
    case CalibrationSource::kFile: return "file";
    case CalibrationSource::kUser: return "user";
  }
  return "unknown";
}

const Segment* ForceCurve::find_segment(SegmentKind kind) const {
  for (const auto& s : segments) {
    if (s.kind == kind) return &s;
  }
  return nullptr;
}

const char* ForceCurve::tip_position_height_name() const {
  return has_height_measured() ? "height (measured)" : "height (piezo)";
}

std::vector<double> ForceCurve::tip_position() const {
  if (force.empty() || metadata.spring_constant_source == CalibrationSource::kNone || !(metadata.spring_constant > 0.0)) {
    throw InputError(metadata.source_file + ": the tip position needs a spring constant; give it with "
                     "--spring-constant K[N/m] (Python: spring_constant=)");
  }
  const std::vector<double>& height = has_height_measured() ? height_measured : height_piezo;
  std::vector<double> tip(height.size());
  for (std::size_t i = 0; i < height.size(); ++i) tip[i] = height[i] + force[i] / metadata.spring_constant;
  return tip;
}

}  // namespace coatcontact::afm
