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
  // A map's curve folders "index/N/" by their numbers N, sorted (8 bytes per curve: a map
  // holds up to 65536 curves); empty with `single` for a single curve (folder "").
  std::vector<long> curve_numbers;
  // The number of segment folders "segments/S/" of each curve (the largest S + 1 among the
  // archive's entries), so that a missing or misnumbered segment header is an error rather than
  // the end of the curve; `single_segments` for a single curve.
  std::vector<int> segment_counts;
  int single_segments = 0;
  bool single = false;
  std::size_t size() const { return single ? 1 : curve_numbers.size(); }
  std::string folder(std::size_t index) const;  // "" or "index/N/"; std::out_of_range past size()
  int segment_count(std::size_t index) const { return single ? single_segments : segment_counts.at(index); }
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
