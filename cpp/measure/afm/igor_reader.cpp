// Asylum Research force curves in Igor binary waves (.ibw, version 5, either byte order).
// Layout: a 64-byte BinHeader5 (sizes of the parts), a 320-byte WaveHeader5 (type, nDim,
// sfA/sfB scaling), the data (column-major, nDim[0] points x nDim[1] columns), then the
// formula, the note ("Key: value" lines separated by CR), the extended units and the
// dimension labels (32 bytes each: the dimension's own label, then one per column).
// Columns: Raw (piezo height [m]), Defl (deflection [m]), ZSnsr (measured height [m]). Heights
// are negated so that they decrease towards the sample (the JPK convention); force =
// Defl * k. The note gives SpringConstant [N/m], InvOLS [m/V] (the sensitivity Defl was made
// with), Indexes (segment ends) and Direction (1 approach, -1 retract, 0 pause).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>

#include "read_support.hpp"

namespace coatcontact::afm::detail {

namespace {

constexpr std::size_t kBinHeaderSize = 64;
constexpr std::size_t kWaveHeaderSize = 320;
constexpr std::size_t kLabelSize = 32;

struct Reader {
  const std::string& bytes;
  bool little;
  const std::string& file;
  std::uint32_t u32(std::size_t at) const {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
    return little ? (std::uint32_t{b[3]} << 24) | (std::uint32_t{b[2]} << 16) | (std::uint32_t{b[1]} << 8) | b[0]
                  : (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3];
  }
  std::int32_t i32(std::size_t at) const { return static_cast<std::int32_t>(u32(at)); }
  std::uint16_t u16(std::size_t at) const {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
    return static_cast<std::uint16_t>(little ? (b[1] << 8) | b[0] : (b[0] << 8) | b[1]);
  }
  std::uint64_t u64(std::size_t at) const {
    const std::uint64_t lo = u32(at), hi = u32(at + 4);
    return little ? (hi << 32) | lo : (lo << 32) | hi;
  }
  double f64(std::size_t at) const {
    const std::uint64_t u = u64(at);
    double d = 0.0;
    std::memcpy(&d, &u, 8);
    return d;
  }
  float f32(std::size_t at) const {
    const std::uint32_t u = u32(at);
    float f = 0.0f;
    std::memcpy(&f, &u, 4);
    return f;
  }
};

std::map<std::string, std::string> parse_note(const std::string& note) {
  std::map<std::string, std::string> values;
  std::size_t pos = 0;
  while (pos <= note.size()) {
    std::size_t end = note.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = note.size();
    const std::string line = note.substr(pos, end - pos);
    const std::size_t colon = line.find(':');
    if (colon != std::string::npos) values.emplace(std::string(trim(line.substr(0, colon))), std::string(trim(line.substr(colon + 1))));
    pos = end + 1;
  }
  return values;
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t comma = text.find(',', pos);
    if (comma == std::string::npos) comma = text.size();
    const std::string item(trim(text.substr(pos, comma - pos)));
    if (!item.empty()) items.push_back(item);
    pos = comma + 1;
  }
  return items;
}

}  // namespace

// Segments of a curve of n points from the note's Indexes (the last point of each segment) and
// Direction; one segment when the note has no Indexes.
void set_segments_from_note(ForceCurve& curve, const std::map<std::string, std::string>& note, std::size_t n, const std::string& file) {
  const auto indexes_it = note.find("Indexes");
  const auto direction_it = note.find("Direction");
  if (indexes_it != note.end()) {
    const auto ends = split_commas(indexes_it->second);
    const auto directions = direction_it != note.end() ? split_commas(direction_it->second) : std::vector<std::string>{};
    std::size_t begin = 0;
    for (std::size_t k = 1; k < ends.size(); ++k) {
      double last = 0.0;
      if (!parse_double(ends[k], last) || last < 0 || last >= static_cast<double>(n) || last != std::floor(last)) {
        fail(file, "", "note Indexes '" + indexes_it->second + "' does not fit the " + std::to_string(n) + " points");
      }
      Segment segment;
      segment.begin = begin;
      segment.end = static_cast<std::size_t>(last) + 1;
      double direction = 0.0;
      const bool known = k < directions.size() && parse_double(directions[k], direction);
      segment.kind = !known ? (k == 1 ? SegmentKind::kApproach : SegmentKind::kRetract)
                            : direction > 0 ? SegmentKind::kApproach
                            : direction < 0 ? SegmentKind::kRetract : SegmentKind::kPause;
      if (segment.end <= segment.begin) fail(file, "", "empty segment " + std::to_string(k - 1) + " in note Indexes '" + indexes_it->second + "'");
      if (!curve.time.empty()) segment.duration = static_cast<double>(segment.size()) * (curve.time.size() > 1 ? curve.time[1] : 0.0);
      curve.segments.push_back(segment);
      begin = segment.end;
    }
    if (begin != n) fail(file, "", "note Indexes '" + indexes_it->second + "' do not end at the last point");
  } else {
    Segment segment;
    segment.begin = 0;
    segment.end = n;
    curve.segments.push_back(segment);
  }

}

// Metadata of the wave from its note and the channels found.
void set_igor_metadata(ForceCurve& curve, const std::map<std::string, std::string>& note, const CalibrationChoice& calibration, bool has_raw,
                       bool has_zsensor, const std::string& file) {
  CurveMetadata& m = curve.metadata;
  set_calibration(m, calibration);
  m.vendor = "Asylum Research";
  m.format = "Igor binary wave (.ibw)";
  if (auto it = note.find("MicroscopeModel"); it != note.end()) m.instrument = it->second;
  if (auto it = note.find("Date"); it != note.end()) m.date = it->second;
  if (auto it = note.find("Time"); it != note.end()) m.time = it->second;
  m.source_file = file;
  double position = 0.0;
  if (auto it = note.find("XLVDT"); it != note.end() && parse_double(it->second, position)) m.position_x = position;
  if (auto it = note.find("YLVDT"); it != note.end() && parse_double(it->second, position)) m.position_y = position;
  m.details.emplace_back("force channel", "Defl [m] x spring constant");
  if (has_raw) m.details.emplace_back("height (piezo) channel", "-Raw");
  if (has_zsensor) m.details.emplace_back("height (measured) channel", "-ZSnsr");
}

std::vector<ForceCurve> read_igor(const std::string& bytes, const std::string& file, const Calibration& user) {
  if (bytes.size() < kBinHeaderSize + kWaveHeaderSize) fail(file, "", "truncated Igor binary wave (shorter than its headers)");
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool little = b[0] == 5 && b[1] == 0;
  const bool big = b[0] == 0 && b[1] == 5;
  if (!little && !big) fail(file, "", "not an Igor binary wave of version 5");
  const Reader r{bytes, little, file};
  const std::int64_t wfm_size = r.i32(4), formula_size = r.i32(8), note_size = r.i32(12), data_units_size = r.i32(16);
  std::int64_t dim_units_total = 0, dim_labels_size[4];
  for (int d = 0; d < 4; ++d) {
    const std::int64_t u = r.i32(20 + 4 * d);
    dim_labels_size[d] = r.i32(36 + 4 * d);
    if (u < 0 || dim_labels_size[d] < 0) fail(file, "", "corrupt header (negative sizes)");
    dim_units_total += u;
  }
  if (wfm_size < static_cast<std::int64_t>(kWaveHeaderSize) || formula_size < 0 || note_size < 0 || data_units_size < 0) {
    fail(file, "", "corrupt header (sizes)");
  }
  const std::size_t wave = kBinHeaderSize;
  const std::int16_t type = static_cast<std::int16_t>(r.u16(wave + 16));
  std::int64_t n_dim[4];
  for (int d = 0; d < 4; ++d) n_dim[d] = r.i32(wave + 68 + 4 * d);
  const double time_step = r.f64(wave + 84);  // sfA[0]
  const std::int64_t rows = n_dim[0];
  const std::int64_t columns = n_dim[1] == 0 ? 1 : n_dim[1];
  if (rows <= 0 || columns <= 0 || rows > (1 << 28) || columns > 64 || n_dim[2] > 1 || n_dim[3] > 1) {
    fail(file, "", "unexpected wave shape (" + std::to_string(rows) + " x " + std::to_string(columns) + ")");
  }
  std::size_t element = 0;
  if (type == 2) element = 4;        // NT_FP32
  else if (type == 4) element = 8;   // NT_FP64
  else fail(file, "", "wave data type " + std::to_string(type) + " is not a real float (expected 32- or 64-bit)");
  const std::size_t data_at = kBinHeaderSize + kWaveHeaderSize;
  const std::size_t data_bytes = static_cast<std::size_t>(rows * columns) * element;
  if (static_cast<std::int64_t>(data_bytes) > wfm_size - static_cast<std::int64_t>(kWaveHeaderSize) + 16) {
    fail(file, "", "wave data larger than the header's wave size");
  }
  const std::size_t note_at = kBinHeaderSize + static_cast<std::size_t>(wfm_size) + static_cast<std::size_t>(formula_size);
  const std::size_t labels_at = note_at + static_cast<std::size_t>(note_size) + static_cast<std::size_t>(data_units_size) +
                                static_cast<std::size_t>(dim_units_total) + static_cast<std::size_t>(dim_labels_size[0]);
  const std::size_t end = labels_at + static_cast<std::size_t>(dim_labels_size[1]);
  if (data_at + data_bytes > bytes.size() || end > bytes.size()) {
    fail(file, "", "truncated Igor binary wave (" + std::to_string(bytes.size()) + " bytes, the headers need " +
                       std::to_string(std::max(end, data_at + data_bytes)) + ")");
  }
  const auto note = parse_note(bytes.substr(note_at, static_cast<std::size_t>(note_size)));
  // Column labels: skip the dimension's own label.
  std::map<std::string, std::int64_t> column_of;
  const std::int64_t label_count = dim_labels_size[1] / static_cast<std::int64_t>(kLabelSize);
  for (std::int64_t j = 1; j < label_count && j - 1 < columns; ++j) {
    const char* at = bytes.data() + labels_at + static_cast<std::size_t>(j) * kLabelSize;
    column_of.emplace(std::string(at, strnlen(at, kLabelSize)), j - 1);
  }
  const auto column = [&](std::initializer_list<const char*> names) -> std::int64_t {
    for (const char* n : names) {
      const auto it = column_of.find(n);
      if (it != column_of.end()) return it->second;
    }
    return -1;
  };
  const std::int64_t defl = column({"Defl", "Deflection"});
  const std::int64_t raw = column({"Raw", "Height"});
  const std::int64_t zsensor = column({"ZSnsr", "ZSensor"});
  if (defl < 0) fail(file, "", "missing channel: no Defl (deflection) column in the wave's labels");
  if (raw < 0 && zsensor < 0) fail(file, "", "missing channel: no Raw (piezo height) and no ZSnsr (measured height) column");

  const auto note_number = [&](const char* key, double& value) {
    const auto it = note.find(key);
    return it != note.end() && parse_double(it->second, value) && std::isfinite(value) && value > 0.0;
  };
  double file_k = 0.0, file_s = 0.0;
  const bool has_k = note_number("SpringConstant", file_k);
  const bool has_s = note_number("InvOLS", file_s);
  // Defl is already in metres: the sensitivity is needed only to rescale it to a user's value.
  const CalibrationChoice calibration = choose_calibration(user, has_k ? &file_k : nullptr, has_s ? &file_s : nullptr,
                                                           true, user.sensitivity.has_value(), file, "",
                                                           "note keys SpringConstant and InvOLS");
  if (calibration.sensitivity_source == CalibrationSource::kUser && !has_s) {
    fail(file, "", "the note has no InvOLS, so the deflection cannot be rescaled to the --sensitivity given");
  }
  const double deflection_scale = calibration.sensitivity_source == CalibrationSource::kUser ? calibration.sensitivity / file_s : 1.0;

  const auto value = [&](std::int64_t col, std::int64_t row) {
    const std::size_t at = data_at + static_cast<std::size_t>(col * rows + row) * element;
    return element == 4 ? static_cast<double>(r.f32(at)) : r.f64(at);
  };
  ForceCurve curve;
  const auto n = static_cast<std::size_t>(rows);
  if (calibration.complete) curve.force.resize(n);
  for (std::size_t i = 0; i < curve.force.size(); ++i) curve.force[i] = value(defl, static_cast<std::int64_t>(i)) * deflection_scale * calibration.spring_constant;
  if (raw >= 0) {
    curve.height_piezo.resize(n);
    for (std::size_t i = 0; i < n; ++i) curve.height_piezo[i] = -value(raw, static_cast<std::int64_t>(i));
  }
  if (zsensor >= 0) {
    curve.height_measured.resize(n);
    for (std::size_t i = 0; i < n; ++i) curve.height_measured[i] = -value(zsensor, static_cast<std::int64_t>(i));
  }
  double rate = 0.0;
  if (std::isfinite(time_step) && time_step > 0.0) {
    curve.time.resize(n);
    for (std::size_t i = 0; i < n; ++i) curve.time[i] = static_cast<double>(i) * time_step;
  } else if (note_number("NumPtsPerSec", rate)) {
    curve.time.resize(n);
    for (std::size_t i = 0; i < n; ++i) curve.time[i] = static_cast<double>(i) / rate;
  }

  set_segments_from_note(curve, note, n, file);
  set_igor_metadata(curve, note, calibration, raw >= 0, zsensor >= 0, file);
  finish_curve(curve, file, "");
  return {curve};
}

}  // namespace coatcontact::afm::detail
