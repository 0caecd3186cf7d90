// JPK force files (.jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series): zip archives of
// Java .properties headers and raw big-endian channels.
//  - Layout: "segments/S/..." for one curve; "index/N/header.properties" and
//    "index/N/segments/S/..." for the curves of a map. "header.properties" at the top holds the
//    file's settings, "shared-data/header.properties" settings that headers refer to.
//  - Indirection: a key "A.M.*=N" (M = lcd-info, force-segment-header-info) stands for every
//    shared key "M.N.rest" as "A.rest"; so a channel's settings appear as "channel.X.data.*"
//    (inline) or "channel.X.*" (through lcd-info), and both spellings are looked up.
//  - A channel's raw numbers (encoder type: signed/unsigned short or integer, or float data
//    without encoder) are scaled to volts by the encoder's offset + multiplier * raw, then by
//    the conversion chain of calibration slots: each slot is offset + multiplier * (its base
//    slot), down to the set's base. vDeflection: volts -> distance (multiplier = sensitivity
//    [m/V]) -> force (multiplier = spring constant [N/m]).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "jpk_reader.hpp"
#include "read_limits.hpp"
#include "read_support.hpp"

namespace coatcontact::afm::detail {

namespace {

Properties read_properties(const ZipArchive& archive, const std::string& name) {
  return parse_properties(archive.read(name, kMaxPropertiesBytes, "a .properties header"));
}

const char* const kPiezoChannels[] = {"height", "head-height"};
const char* const kMeasuredChannels[] = {"strainGaugeHeight", "capacitiveSensorHeight", "measuredHeight"};
constexpr const char* kDeflectionChannel = "vDeflection";

struct Context {
  const std::string& file;
  std::string entry;  // the properties file or channel in question, for messages
};

// Replaces every "A.M.*=N" by the shared keys "M.N.rest" as "A.rest".
void expand_references(Properties& properties, const Properties& shared, const std::string& file, const std::string& entry) {
  std::vector<std::pair<std::string, std::string>> references;
  for (const auto& [key, value] : properties) {
    if (key.size() > 2 && key.compare(key.size() - 2, 2, ".*") == 0) references.emplace_back(key, value);
  }
  for (const auto& [key, value] : references) {
    const std::string stem = key.substr(0, key.size() - 2);  // "channel.height.lcd-info"
    const std::size_t dot = stem.rfind('.');
    if (dot == std::string::npos) continue;
    const std::string head = stem.substr(0, dot);            // "channel.height"
    const std::string mediator = stem.substr(dot + 1);       // "lcd-info"
    const std::string prefix = mediator + "." + std::string(trim(value)) + ".";
    for (auto it = shared.lower_bound(prefix); it != shared.end() && it->first.compare(0, prefix.size(), prefix) == 0; ++it) {
      properties.emplace(head + "." + it->first.substr(prefix.size()), it->second);
      // A header whose references multiply the shared settings (a "properties bomb").
      if (properties.size() > kMaxSettings) {
        fail(file, entry, "more than " + std::to_string(kMaxSettings) + " settings once its references to the shared data are expanded; corrupt or not an instrument's file");
      }
    }
  }
}

const std::string* find(const Properties& p, const std::string& key) {
  const auto it = p.find(key);
  return it == p.end() ? nullptr : &it->second;
}

// A segment's own (expanded) properties over its curve's: looked up in that order, so the
// curve's settings are shared rather than copied into every segment.
struct SegmentProperties {
  Properties own;
  const Properties* curve = nullptr;
};

const std::string* find(const SegmentProperties& p, const std::string& key) {
  if (const std::string* v = find(p.own, key)) return v;
  return find(*p.curve, key);
}

// The first of `keys` present.
template <class P>
const std::string* find_any(const P& p, std::initializer_list<std::string> keys) {
  for (const auto& key : keys) {
    if (const std::string* v = find(p, key)) return v;
  }
  return nullptr;
}

// The value of the first key ending in `suffix` (for settings whose prefix names the file
// type: force-scan-series., quantitative-imaging-series., force-scan-map., ...).
const std::string* find_suffix(const Properties& p, const std::string& suffix) {
  for (const auto& [key, value] : p) {
    if (key.size() >= suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) return &value;
  }
  return nullptr;
}

template <class P>
double number(const P& p, const std::string& key, const Context& where) {
  const std::string* text = find(p, key);
  if (text == nullptr) fail(where.file, where.entry, "property " + key + " is missing");
  double value = 0.0;
  if (!parse_double(*text, value) || !std::isfinite(value)) {
    fail(where.file, where.entry, "property " + key + " = '" + *text + "' is not a finite number");
  }
  return value;
}

bool optional_number(const std::string* text, double& value) {
  return text != nullptr && parse_double(*text, value) && std::isfinite(value);
}

// One linear step: offset + multiplier * base.
struct Scaling {
  double offset = 0.0;
  double multiplier = 1.0;
};

enum class RawType { kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

std::size_t raw_size(RawType type) {
  switch (type) {
    case RawType::kInt16:
    case RawType::kUInt16: return 2;
    case RawType::kInt32:
    case RawType::kUInt32:
    case RawType::kFloat32: return 4;
    case RawType::kFloat64: return 8;
  }
  return 0;
}

double decode(const unsigned char* b, RawType type) {
  switch (type) {
    case RawType::kInt16: return static_cast<std::int16_t>(static_cast<std::uint16_t>((b[0] << 8) | b[1]));
    case RawType::kUInt16: return static_cast<std::uint16_t>((b[0] << 8) | b[1]);
    case RawType::kInt32:
    case RawType::kUInt32:
    case RawType::kFloat32: {
      const std::uint32_t u = (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3];
      if (type == RawType::kInt32) return static_cast<std::int32_t>(u);
      if (type == RawType::kUInt32) return u;
      float f = 0.0f;
      std::memcpy(&f, &u, 4);
      return f;
    }
    case RawType::kFloat64: {
      std::uint64_t u = 0;
      for (int k = 0; k < 8; ++k) u = (u << 8) | b[k];
      double d = 0.0;
      std::memcpy(&d, &u, 8);
      return d;
    }
  }
  return 0.0;
}

// Calibration values the user supplied replace the slot multipliers of vDeflection.
struct SlotOverride {
  std::optional<double> distance_multiplier;  // sensitivity
  std::optional<double> force_multiplier;     // spring constant
};

// The channel in its calibration slot `slot`, in `unit`.
std::vector<double> read_channel(const ZipArchive& archive, const SegmentProperties& p, const std::string& folder,
                                 const std::string& channel, const std::string& slot, const std::string& unit,
                                 std::size_t expected_points, const SlotOverride& overrides, const std::string& file) {
  const std::string c = "channel." + channel + ".";
  Context where{file, folder + "segment-header.properties"};
  const std::string* file_name = find_any(p, {c + "data.file.name", c + "file.name"});
  if (file_name == nullptr) fail(file, where.entry, "no data file named for channel " + channel);
  const std::string entry = folder + *file_name;
  const std::string* encoder = find_any(p, {c + "data.encoder.type", c + "encoder.type"});
  const std::string* data_type = find_any(p, {c + "data.type", c + "type"});
  RawType type = RawType::kInt16;
  bool scaled = true;
  if (encoder != nullptr) {
    if (*encoder == "signedshort") type = RawType::kInt16;
    else if (*encoder == "unsignedshort") type = RawType::kUInt16;
    else if (*encoder == "signedinteger") type = RawType::kInt32;
    else if (*encoder == "unsignedinteger") type = RawType::kUInt32;
    else fail(file, entry, "encoder type '" + *encoder + "' of channel " + channel + " is not supported");
  } else if (data_type != nullptr && (*data_type == "float" || *data_type == "float-data")) {
    type = RawType::kFloat32;
    scaled = false;
  } else if (data_type != nullptr && (*data_type == "double" || *data_type == "double-data")) {
    type = RawType::kFloat64;
    scaled = false;
  } else {
    fail(file, entry, "channel " + channel + " has neither an encoder nor a float data type");
  }
  Scaling encoder_scaling;
  if (scaled) {
    const std::string* off = find_any(p, {c + "data.encoder.scaling.offset", c + "encoder.scaling.offset"});
    const std::string* mul = find_any(p, {c + "data.encoder.scaling.multiplier", c + "encoder.scaling.multiplier"});
    if (!optional_number(off, encoder_scaling.offset) || !optional_number(mul, encoder_scaling.multiplier)) {
      fail(file, where.entry, "encoder scaling (offset, multiplier) of channel " + channel + " is missing or not a number");
    }
  }
  // Conversion chain from `slot` down to the base slot.
  const std::string set = c + "conversion-set.";
  const std::string* base = find(p, set + "conversions.base");
  if (base == nullptr) fail(file, where.entry, "channel " + channel + " has no conversion set");
  std::vector<Scaling> chain;
  std::string current = slot;
  while (current != *base) {
    if (chain.size() > 16) fail(file, where.entry, "conversion slots of channel " + channel + " form a loop");
    const std::string s = set + "conversion." + current + ".";
    const std::string* defined = find(p, s + "defined");
    if (defined == nullptr || *defined != "true") {
      fail(file, where.entry, "calibration slot '" + current + "' of channel " + channel + " is not defined");
    }
    Scaling step;
    step.offset = number(p, s + "scaling.offset", where);
    step.multiplier = number(p, s + "scaling.multiplier", where);
    if (channel == kDeflectionChannel && current == "distance" && overrides.distance_multiplier) {
      step = Scaling{0.0, *overrides.distance_multiplier};
    }
    if (channel == kDeflectionChannel && current == "force" && overrides.force_multiplier) {
      step = Scaling{0.0, *overrides.force_multiplier};
    }
    if (current == slot) {
      const std::string* u = find_any(p, {s + "scaling.unit.unit", s + "scaling.unit"});
      if (u == nullptr || *u != unit) {
        fail(file, where.entry, "slot '" + slot + "' of channel " + channel + " is in '" + (u ? *u : std::string("?")) +
                                    "', expected " + unit);
      }
    }
    chain.push_back(step);
    const std::string* next = find(p, s + "base-calibration-slot");
    if (next == nullptr) fail(file, where.entry, "slot '" + current + "' of channel " + channel + " names no base slot");
    current = *next;
  }
  if (chain.empty()) fail(file, where.entry, "channel " + channel + " has no slot '" + slot + "' above its base");

  if (!archive.has(entry)) fail(file, entry, "channel " + channel + " is missing from the archive");
  const std::size_t size = raw_size(type);
  // The channel holds exactly the header's points: fewer is a truncated channel, more a
  // header whose num-points would read a prefix of the data as the whole segment.
  const std::uint64_t declared = archive.size_of(entry);
  if (declared != expected_points * size) {
    fail(file, entry, std::string(declared < expected_points * size ? "truncated channel: " : "channel longer than its header says: ") +
                          std::to_string(declared) + " bytes hold " + std::to_string(declared / size) + " points of " +
                          std::to_string(size) + " bytes, the segment header's num-points says " + std::to_string(expected_points));
  }
  const std::string bytes = archive.read(entry, expected_points * size, "a channel of the segment's num-points");
  std::vector<double> values(expected_points);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::size_t i = 0; i < expected_points; ++i) {
    double v = decode(data + i * size, type);
    if (scaled) v = encoder_scaling.offset + encoder_scaling.multiplier * v;
    for (auto step = chain.rbegin(); step != chain.rend(); ++step) v = step->offset + step->multiplier * v;
    values[i] = v;
  }
  return values;
}

std::vector<std::string> split_blanks(const std::string& text) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && text[i] == ' ') ++i;
    const std::size_t start = i;
    while (i < text.size() && text[i] != ' ') ++i;
    if (i > start) words.push_back(text.substr(start, i - start));
  }
  return words;
}

// The slot multiplier of vDeflection, if the slot is defined.
const double* slot_multiplier(const SegmentProperties& p, const std::string& slot, double& storage) {
  const std::string s = std::string("channel.") + kDeflectionChannel + ".conversion-set.conversion." + slot + ".";
  const std::string* defined = find(p, s + "defined");
  if (defined == nullptr || *defined != "true") return nullptr;
  if (!optional_number(find(p, s + "scaling.multiplier"), storage)) return nullptr;
  return &storage;
}

std::string format_of(const std::string& file, const Properties& general) {
  const std::string* type = find(general, "type");
  const std::string t = type ? *type : "";
  if (t == "quantitative-imaging-map") return "JPK QI map (.jpk-qi-data)";
  if (t == "quantitative-imaging-series") return "JPK QI curve (.jpk-qi-series)";
  if (t == "force-scan-map") return "JPK force map (.jpk-force-map)";
  (void)file;
  return "JPK force curve (.jpk-force)";
}

}  // namespace

// The segment number S of "segments/S/..." at `at` in `name`, or -1 (not a segment entry, or
// a number past kMaxSegments: then -2, refused by the caller).
int segment_number(const std::string& name, std::size_t at) {
  if (name.compare(at, 9, "segments/") != 0) return -1;
  const std::size_t begin = at + 9, slash = name.find('/', begin);
  if (slash == std::string::npos || slash == begin) return -1;
  long n = 0;
  for (std::size_t i = begin; i < slash; ++i) {
    if (name[i] < '0' || name[i] > '9') return -1;
    n = n * 10 + (name[i] - '0');
    if (n >= kMaxSegments) return -2;
  }
  return static_cast<int>(n);
}

// The numbers N of the archive's "index/N/" folders, sorted, and each curve's segment count
// (largest S + 1 of its "segments/S/" entries); `single` when the archive has a top-level
// segments/ folder. The entries of one curve are adjacent in the archive, so a number is kept
// once per run of its entries and the few repeats are merged after sorting (no set node per
// curve: a 256 x 256 map's set cost 3 MB).
void list_curves(const ZipArchive& archive, const std::string& file, JpkLayout& layout) {
  std::vector<std::pair<long, int>> numbers;  // (N, segment count)
  bool segments = false;
  int single_segments = 0;
  const auto note_segment = [&](int s, int& count, const std::string& name) {
    if (s == -2) fail(file, name, "segment number past the limit of " + std::to_string(kMaxSegments) + " segments per curve");
    if (s >= 0) count = std::max(count, s + 1);
  };
  archive.for_each_name([&](const std::string& name) {
    if (name.rfind("segments/", 0) == 0) {
      segments = true;
      note_segment(segment_number(name, 0), single_segments, name);
    }
    if (name.rfind("index/", 0) == 0) {
      const std::size_t slash = name.find('/', 6);
      const std::string digits = name.substr(6, slash == std::string::npos ? std::string::npos : slash - 6);
      if (!digits.empty() && digits.size() < 10 && std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
        const long n = std::stol(digits);
        if (numbers.empty() || numbers.back().first != n) numbers.emplace_back(n, 0);
        if (slash != std::string::npos) note_segment(segment_number(name, slash + 1), numbers.back().second, name);
      }
    }
  });
  std::sort(numbers.begin(), numbers.end());
  layout.curve_numbers.clear();
  layout.segment_counts.clear();
  for (const auto& [n, count] : numbers) {
    if (!layout.curve_numbers.empty() && layout.curve_numbers.back() == n) {
      layout.segment_counts.back() = std::max(layout.segment_counts.back(), count);
      continue;
    }
    layout.curve_numbers.push_back(n);
    layout.segment_counts.push_back(count);
  }
  layout.curve_numbers.shrink_to_fit();
  layout.segment_counts.shrink_to_fit();
  layout.single = layout.curve_numbers.empty() && segments;
  layout.single_segments = single_segments;
  if (layout.curve_numbers.empty() && !segments) fail(file, "", "a zip archive without JPK segments (no segments/ or index/ folders)");
}

// The headers of segment folders 0 .. count - 1 of a curve: every folder the archive holds
// must have its header, so a missing or misnumbered header is an error, not the curve's end.
std::vector<SegmentProperties> segment_properties_of(const ZipArchive& archive, const std::string& folder, int count,
                                                     const Properties& curve_properties, const Properties& shared,
                                                     const std::string& file) {
  std::vector<SegmentProperties> segment_properties;
  for (int s = 0; s < count; ++s) {
    const std::string header = folder + "segments/" + std::to_string(s) + "/segment-header.properties";
    if (!archive.has(header)) {
      fail(file, header, "segment header missing from the archive (the curve has segment folders 0 to " + std::to_string(count - 1) +
                             "; a segment without its header would be dropped with every later one)");
    }
    SegmentProperties p;
    p.own = read_properties(archive, header);
    expand_references(p.own, shared, file, header);
    p.curve = &curve_properties;
    segment_properties.push_back(std::move(p));
  }
  if (segment_properties.empty()) fail(file, folder + "segments/", "no segment headers in the archive");
  // The curve's own count of segments, where its header states one, must match.
  double stated = 0.0;
  if (optional_number(find_suffix(curve_properties, "force-settings.segments.size"), stated) && stated != count) {
    fail(file, folder + "segments/", "the archive holds " + std::to_string(count) + " segment folders, the header's force-settings.segments.size says " + number_text(stated));
  }
  return segment_properties;
}

// The channels present in every segment decide which heights a curve has (piezo, measured).
void choose_height_channels(const std::vector<SegmentProperties>& segment_properties, const std::string& folder,
                            const std::string& file, std::string& piezo, std::string& measured) {
  std::vector<std::set<std::string>> lists;
  for (const auto& p : segment_properties) {
    const std::string* list = find(p, "channels.list");
    std::set<std::string> names;
    if (list) for (auto& w : split_blanks(*list)) names.insert(w);
    lists.push_back(std::move(names));
  }
  const auto in_all = [&](const std::string& name) {
    return std::all_of(lists.begin(), lists.end(), [&](const std::set<std::string>& l) { return l.count(name) > 0; });
  };
  for (std::size_t s = 0; s < lists.size(); ++s) {
    if (lists[s].count(kDeflectionChannel) == 0) {
      fail(file, folder + "segments/" + std::to_string(s) + "/", "missing channel vDeflection (the cantilever deflection)");
    }
  }
  for (const char* name : kPiezoChannels) if (piezo.empty() && in_all(name)) piezo = name;
  for (const char* name : kMeasuredChannels) if (measured.empty() && in_all(name)) measured = name;
  if (piezo.empty() && measured.empty()) {
    fail(file, folder + "segments/", "missing channel: no height (height, head-height) and no measured height (strainGaugeHeight, capacitiveSensorHeight, measuredHeight) in every segment");
  }
}

// A file lacking a calibration slot the user supplied: the chain volts -> distance -> force is
// built from the user's value alone.
void complete_missing_slots(std::vector<SegmentProperties>& segment_properties, bool has_distance, bool has_force) {
  for (auto& p : segment_properties) {
    const std::string set = std::string("channel.") + kDeflectionChannel + ".conversion-set.conversion.";
    if (!has_distance) {
      p.own[set + "distance.defined"] = "true";
      p.own[set + "distance.base-calibration-slot"] = "volts";
      p.own[set + "distance.scaling.offset"] = "0";
      p.own[set + "distance.scaling.multiplier"] = "1";
      p.own[set + "distance.scaling.unit.unit"] = "m";
    }
    if (!has_force) {
      p.own[set + "force.defined"] = "true";
      p.own[set + "force.base-calibration-slot"] = "distance";
      p.own[set + "force.scaling.offset"] = "0";
      p.own[set + "force.scaling.multiplier"] = "1";
      p.own[set + "force.scaling.unit.unit"] = "N";
    }
  }
}

// Instrument, position and map grid of a curve from the general and the curve's headers.
void set_position_metadata(CurveMetadata& m, const Properties& general, const Properties& curve_properties,
                           const std::string& folder) {
  if (const std::string* v = find_suffix(general, "description.instrument")) m.instrument = *v;
  if (m.instrument.empty()) if (const std::string* v = find_suffix(curve_properties, "description.instrument")) m.instrument = *v;
  double value = 0.0;
  if (optional_number(find_suffix(curve_properties, "header.position.x"), value)) m.position_x = value;
  if (optional_number(find_suffix(curve_properties, "header.position.y"), value)) m.position_y = value;
  double ilength = 0.0, jlength = 0.0, position_index = 0.0;
  if (!folder.empty() && optional_number(find_suffix(general, "position-pattern.grid.ilength"), ilength) &&
      optional_number(find_suffix(general, "position-pattern.grid.jlength"), jlength) &&
      optional_number(find_suffix(curve_properties, "header.position-index"), position_index) && ilength >= 1 &&
      jlength >= 1 && ilength <= 1e6 && jlength <= 1e6 && position_index >= 0 && position_index < ilength * jlength) {
    const long i = static_cast<long>(ilength), index = static_cast<long>(position_index);
    m.grid_shape_x = i;
    m.grid_shape_y = static_cast<long>(jlength);
    const long row = index / i;
    m.grid_index_y = row;
    // A back-and-forth (meander) pattern runs every odd row backwards.
    const std::string* meander = find_suffix(general, "position-pattern.back-and-forth");
    const bool backwards = meander != nullptr && trim(*meander) == "true" && row % 2 == 1;
    m.grid_index_x = backwards ? i - 1 - index % i : index % i;
  }
}

// What the segments of one curve share while they are read one after the other.
struct SegmentReading {
  const ZipArchive& archive;
  const std::string& file;
  const std::string& folder;
  const std::string& piezo;
  const std::string& measured;
  const CalibrationChoice& calibration;
  const SlotOverride& overrides;
  std::size_t segment_count;
};

// Segment s of a curve: its kind, name, duration and time stamp, and its channels appended to
// the curve's (start_time: the segment's first time, advanced past it).
void read_segment(const SegmentReading& r, const SegmentProperties& p, std::size_t s, ForceCurve& curve,
                  double& start_time) {
  const std::string seg_folder = r.folder + "segments/" + std::to_string(s) + "/";
  const Context where{r.file, seg_folder + "segment-header.properties"};
  const double points = number(p, "force-segment-header.num-points", where);
  if (!(points >= 0) || points != std::floor(points)) fail(r.file, where.entry, "num-points is not a valid count");
  if (points > static_cast<double>(kMaxSegmentPoints)) {
    fail(r.file, where.entry, "num-points = " + number_text(points) + " exceeds the limit of " + std::to_string(kMaxSegmentPoints) + " points per segment");
  }
  const auto n = static_cast<std::size_t>(points);
  const std::size_t before = curve.segments.empty() ? 0 : curve.segments.back().end;
  if (before + n > kMaxCurvePoints) {
    fail(r.file, where.entry, "the curve's segments hold more than " + std::to_string(kMaxCurvePoints) + " points (the limit per curve)");
  }
  if (n == 0) throw EmptySegment(r.file + ": " + where.entry + ": empty segment " + std::to_string(s) + " (num-points = 0)");
  Segment segment;
  segment.begin = curve.segments.empty() ? 0 : curve.segments.back().end;
  segment.end = segment.begin + n;
  const std::string* style = find_any(p, {"force-segment-header.settings.style", "force-segment-header.settings.segment-settings.style"});
  if (style && *style == "extend") segment.kind = SegmentKind::kApproach;
  else if (style && *style == "retract") segment.kind = SegmentKind::kRetract;
  else if (style && *style == "pause") segment.kind = SegmentKind::kPause;
  else if (s == 0) segment.kind = SegmentKind::kApproach;
  else if (s + 1 == r.segment_count) segment.kind = SegmentKind::kRetract;
  else segment.kind = SegmentKind::kPause;
  if (const std::string* name = find(p, "force-segment-header.name.name")) segment.name = *name;
  if (!optional_number(find_any(p, {"force-segment-header.duration", "force-segment-header.settings.segment-settings.duration"}), segment.duration) ||
      !(segment.duration > 0.0)) {
    fail(r.file, where.entry, "no segment duration (force-segment-header.duration), so no time axis");
  }
  if (s == 0) {
    if (const std::string* stamp = find(p, "force-segment-header.time-stamp")) {
      const std::size_t blank = stamp->find(' ');
      curve.metadata.date = stamp->substr(0, blank);
      if (blank != std::string::npos) {
        const std::size_t second = stamp->find(' ', blank + 1);
        curve.metadata.time = stamp->substr(blank + 1, second == std::string::npos ? std::string::npos : second - blank - 1);
      }
    }
  }
  // Per-channel point counts may be given; they must agree with the segment's.
  for (const std::string& ch : {std::string(kDeflectionChannel), r.piezo, r.measured}) {
    if (ch.empty()) continue;
    double channel_points = 0.0;
    if (optional_number(find(p, "channel." + ch + ".data.num-points"), channel_points) && channel_points != points) {
      fail(r.file, where.entry, "channel " + ch + " has " + number_text(channel_points) + " points, the segment " + number_text(points));
    }
  }
  if (r.calibration.complete) {
    const auto force = read_channel(r.archive, p, seg_folder, kDeflectionChannel, "force", "N", n, r.overrides, r.file);
    curve.force.insert(curve.force.end(), force.begin(), force.end());
  }
  if (!r.piezo.empty()) {
    const std::string set = "channel." + r.piezo + ".conversion-set.conversion.";
    const std::string* calibrated = find(p, set + "calibrated.defined");
    const std::string slot = (calibrated && *calibrated == "true") ? "calibrated" : "nominal";
    const auto h = read_channel(r.archive, p, seg_folder, r.piezo, slot, "m", n, r.overrides, r.file);
    curve.height_piezo.insert(curve.height_piezo.end(), h.begin(), h.end());
  }
  if (!r.measured.empty()) {
    const auto h = read_channel(r.archive, p, seg_folder, r.measured, "nominal", "m", n, r.overrides, r.file);
    curve.height_measured.insert(curve.height_measured.end(), h.begin(), h.end());
  }
  for (std::size_t i = 0; i < n; ++i) {
    curve.time.push_back(start_time + segment.duration * static_cast<double>(i) / static_cast<double>(n));
  }
  start_time += segment.duration;
  curve.segments.push_back(segment);
}

std::string JpkLayout::folder(std::size_t index) const {
  if (single) {
    if (index != 0) throw std::out_of_range("JpkLayout::folder: a single curve has only curve 0");
    return "";
  }
  return "index/" + std::to_string(curve_numbers.at(index)) + "/";
}

JpkLayout jpk_layout(const ZipArchive& archive, const std::string& file) {
  JpkLayout layout;
  list_curves(archive, file, layout);
  if (archive.has("header.properties")) {
    layout.general = read_properties(archive, "header.properties");
  } else if (layout.single) {
    fail(file, "header.properties", "entry missing from the archive");
  }
  if (archive.has("shared-data/header.properties")) layout.shared = read_properties(archive, "shared-data/header.properties");
  layout.format = format_of(file, layout.general);
  return layout;
}

ForceCurve read_jpk_curve(const ZipArchive& archive, const JpkLayout& layout, std::size_t ci, const std::string& file,
                          const Calibration& user) {
  const Properties& general = layout.general;
  const Properties& shared = layout.shared;
  const std::string folder = layout.folder(ci);
  Properties curve_properties = general;
  if (!folder.empty()) {
    if (!archive.has(folder + "header.properties")) fail(file, folder + "header.properties", "entry missing from the archive");
    Properties own = read_properties(archive, folder + "header.properties");
    for (auto& [k, v] : own) curve_properties[k] = v;
  }
  expand_references(curve_properties, shared, file, folder + "header.properties");
  std::vector<SegmentProperties> segment_properties =
      segment_properties_of(archive, folder, layout.segment_count(ci), curve_properties, shared, file);
  std::string piezo, measured;
  choose_height_channels(segment_properties, folder, file, piezo, measured);

  // Calibration from the first segment's vDeflection slots; the user's values override them.
  double k_storage = 0.0, s_storage = 0.0;
  const double* file_k = slot_multiplier(segment_properties.front(), "force", k_storage);
  const double* file_s = slot_multiplier(segment_properties.front(), "distance", s_storage);
  const CalibrationChoice calibration = choose_calibration(
      user, file_k, file_s, true, true, file, folder.empty() ? "" : folder,
      "vDeflection calibration slots 'distance' and 'force'");
  SlotOverride overrides;
  if (calibration.sensitivity_source == CalibrationSource::kUser) overrides.distance_multiplier = calibration.sensitivity;
  if (calibration.spring_constant_source == CalibrationSource::kUser) overrides.force_multiplier = calibration.spring_constant;
  complete_missing_slots(segment_properties, file_s != nullptr, file_k != nullptr);

  ForceCurve curve;
  CurveMetadata& m = curve.metadata;
  set_calibration(m, calibration);
  m.vendor = "JPK";
  m.format = layout.format;
  m.source_file = file;
  m.entry = folder;
  m.curve_index = ci;
  m.curve_count = layout.size();
  set_position_metadata(m, general, curve_properties, folder);
  m.details.emplace_back("force channel", "vDeflection (slot force)");
  if (!piezo.empty()) m.details.emplace_back("height (piezo) channel", piezo + " (slot calibrated, else nominal)");
  if (!measured.empty()) m.details.emplace_back("height (measured) channel", measured + " (slot nominal)");

  const SegmentReading reading{archive, file, folder, piezo, measured, calibration, overrides, segment_properties.size()};
  double start_time = 0.0;
  for (std::size_t s = 0; s < segment_properties.size(); ++s) {
    read_segment(reading, segment_properties[s], s, curve, start_time);
  }
  finish_curve(curve, file, folder);
  return curve;
}

CurveMetadata jpk_curve_place(const ZipArchive& archive, const JpkLayout& layout, std::size_t ci, const std::string& file) {
  const std::string folder = layout.folder(ci);
  CurveMetadata m;
  m.source_file = file;
  m.entry = folder;
  m.curve_index = ci;
  m.curve_count = layout.size();
  Properties curve_properties = layout.general;
  if (!folder.empty()) {
    for (auto& [k, v] : read_properties(archive, folder + "header.properties")) curve_properties[k] = v;
  }
  expand_references(curve_properties, layout.shared, file, folder + "header.properties");
  set_position_metadata(m, layout.general, curve_properties, folder);
  return m;
}

std::vector<ForceCurve> read_jpk(const std::string& bytes, const std::string& file, const Calibration& user) {
  const ZipArchive archive(bytes, file);
  const JpkLayout layout = jpk_layout(archive, file);
  std::vector<ForceCurve> curves;
  for (std::size_t ci = 0; ci < layout.size(); ++ci) curves.push_back(read_jpk_curve(archive, layout, ci, file, user));
  return curves;
}

}  // namespace coatcontact::afm::detail
