// One AFM force curve in SI units, whatever instrument wrote it (cpp/measure/afm/ reads the
// vendors' files into this type). Channels are point-aligned arrays over all segments; each
// segment is a contiguous index range with its kind. Conventions follow the AFM tools of the
// field: force > 0 pushes the cantilever up (repulsion); heights are the cantilever base
// position, decreasing towards the sample; tip position = height + force / k.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace coatcontact::afm {

enum class SegmentKind { kApproach, kPause, kRetract };
// "approach", "pause", "retract".
const char* segment_kind_name(SegmentKind kind);

struct Segment {
  SegmentKind kind = SegmentKind::kApproach;
  std::size_t begin = 0;  // first point
  std::size_t end = 0;    // one past the last point
  std::string name;       // the file's own name of the segment ("extend-spm", ...), may be empty
  double duration = 0.0;  // [s]; 0 when the file does not say
  std::size_t size() const { return end - begin; }
};

// Where a calibration constant came from.
enum class CalibrationSource { kNone, kFile, kUser };
const char* calibration_source_name(CalibrationSource source);  // "none", "file", "user"

struct CurveMetadata {
  double spring_constant = 0.0;  // [N/m]; meaningful when spring_constant_source != kNone
  CalibrationSource spring_constant_source = CalibrationSource::kNone;
  double sensitivity = 0.0;      // [m/V] (NT-MDT: m per unit of the deflection signal)
  CalibrationSource sensitivity_source = CalibrationSource::kNone;
  std::string vendor;      // "JPK", "Asylum Research", "AFM Workshop", "NT-MDT"
  std::string format;      // e.g. "JPK force map (.jpk-force-map)"
  std::string instrument;  // may be empty
  std::string date;        // as the file writes it (ISO when the file does); may be empty
  std::string time;
  std::string source_file;
  std::string entry;           // archive member or folder of this curve; empty for single files
  std::size_t curve_index = 0;  // position in the file's list of curves
  std::size_t curve_count = 1;
  std::optional<long> grid_index_x, grid_index_y;  // map and QI grids
  std::optional<long> grid_shape_x, grid_shape_y;
  std::optional<double> position_x, position_y;    // [m]
  // Vendor details worth keeping (channel names used, calibration slots), in file order.
  std::vector<std::pair<std::string, std::string>> details;
};

struct ForceCurve {
  std::vector<double> force;            // [N]; empty only when read without a needed calibration
  std::vector<double> height_piezo;     // [m]; empty when the file records none
  std::vector<double> height_measured;  // [m]; empty when the file records none
  std::vector<double> time;             // [s]; empty when the file records no time base
  std::vector<int> segment;             // index into segments, per point
  std::vector<Segment> segments;
  CurveMetadata metadata;

  std::size_t point_count() const { return segment.size(); }
  bool has_force() const { return !force.empty(); }
  bool has_height_piezo() const { return !height_piezo.empty(); }
  bool has_height_measured() const { return !height_measured.empty(); }
  // The first segment of `kind`, or nullptr.
  const Segment* find_segment(SegmentKind kind) const;
  // height (measured, else piezo) + force / spring constant [m]: the vertical tip position.
  // InputError if the curve has no spring constant.
  std::vector<double> tip_position() const;
  // "height (measured)" or "height (piezo)": the channel tip_position() starts from.
  const char* tip_position_height_name() const;
};

}  // namespace coatcontact::afm
