// A JPK archive read curve by curve (internal to the AFM readers): its layout once, then any
// curve on demand, so a map is never held whole (afm::CurveSource).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "coatcontact/afm_readers.hpp"
#include "java_properties.hpp"
#include "zip_archive.hpp"

namespace coatcontact::afm::detail {

struct JpkLayout {
  std::vector<std::string> curve_folders;  // "" for a single curve, "index/N/" for a map's
  bool single = false;
  Properties general, shared;  // header.properties, shared-data/header.properties
  std::string format;
};
JpkLayout jpk_layout(const ZipArchive& archive, const std::string& file);

// Curve `index` of the archive (InputError, MissingCalibration or EmptySegment for that curve).
ForceCurve read_jpk_curve(const ZipArchive& archive, const JpkLayout& layout, std::size_t index, const std::string& file,
                          const Calibration& user);

// The place of curve `index` (grid index, position, entry) from its header alone, for a curve
// whose segments cannot be read; InputError if the header cannot be read either.
CurveMetadata jpk_curve_place(const ZipArchive& archive, const JpkLayout& layout, std::size_t index, const std::string& file);

}  // namespace coatcontact::afm::detail
