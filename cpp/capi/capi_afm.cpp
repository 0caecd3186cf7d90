// The C interface of the AFM readers and preprocessing (coatcontact_afm.h): a file handle over
// afm::CurveSource, a curve handle holding one ForceCurve with its channels and metadata as
// the header lists them. Every entry point runs inside capi::guard.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "capi_afm.hpp"
#include "capi_guard.hpp"
#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/errors.hpp"

using coatcontact::InputError;
namespace afm = coatcontact::afm;

namespace coatcontact::capi {

void require(const void* pointer, const char* function, const char* argument) {
  if (pointer == nullptr) throw InputError(std::string(function) + ": " + argument + " is NULL");
}

std::size_t checked_index(long index, std::size_t size, const char* function, const char* argument) {
  if (index < 0 || static_cast<std::size_t>(index) >= size) {
    throw InputError(std::string(function) + ": " + argument + " " + std::to_string(index) + " is out of range" +
                     (size == 0 ? " (there is none)" : " 0.." + std::to_string(static_cast<long>(size) - 1)));
  }
  return static_cast<std::size_t>(index);
}

void copy_out(const std::vector<double>& data, double* values, long capacity, long* length, const char* function,
              const std::string& what) {
  require(length, function, "length");
  if (values != nullptr) {
    if (capacity < static_cast<long>(data.size())) {
      throw InputError(std::string(function) + ": capacity " + std::to_string(capacity) + " is below the " +
                       std::to_string(data.size()) + " values of '" + what + "'");
    }
    if (!data.empty()) std::memcpy(values, data.data(), data.size() * sizeof(double));
  }
  *length = static_cast<long>(data.size());
}

}  // namespace coatcontact::capi

using coatcontact::capi::checked_index;
using coatcontact::capi::copy_out;
using coatcontact::capi::guard;
using coatcontact::capi::require;

namespace {

std::string text_of(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

afm::Calibration calibration_of(const cc_afm_calibration* c, const char* function) {
  afm::Calibration calibration;
  if (c == nullptr) return calibration;
  for (const auto& [value, name] : {std::pair{c->spring_constant, "spring_constant"}, std::pair{c->sensitivity, "sensitivity"}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw InputError(std::string(function) + ": calibration " + name + " " + text_of(value) +
                       " is not allowed; expected a value > 0, or 0 for the file's");
    }
  }
  if (c->spring_constant > 0.0) calibration.spring_constant = c->spring_constant;
  if (c->sensitivity > 0.0) calibration.sensitivity = c->sensitivity;
  calibration.allow_missing = c->allow_missing != 0;
  return calibration;
}

// The channels of coatcontact_afm.h, in its order, those the curve has.
void fill_channels(cc_afm_curve& c) {
  const afm::ForceCurve& curve = c.curve;
  for (const auto& [name, data] : {std::pair<const char*, const std::vector<double>*>{"force", &curve.force},
                                   {"height_piezo", &curve.height_piezo},
                                   {"height_measured", &curve.height_measured},
                                   {"time", &curve.time}}) {
    if (!data->empty()) c.channels.emplace_back(name, *data);
  }
  c.channels.emplace_back("segment", std::vector<double>(curve.segment.begin(), curve.segment.end()));
  const bool has_k = curve.metadata.spring_constant_source != afm::CalibrationSource::kNone;
  if (curve.has_force() && has_k && (curve.has_height_measured() || curve.has_height_piezo())) {
    c.channels.emplace_back("tip_position", curve.tip_position());
  }
}

void fill_metadata(cc_afm_curve& c) {
  const afm::CurveMetadata& m = c.curve.metadata;
  const bool k = m.spring_constant_source != afm::CalibrationSource::kNone;
  const bool s = m.sensitivity_source != afm::CalibrationSource::kNone;
  c.metadata = {{"vendor", m.vendor},
                {"format", m.format},
                {"instrument", m.instrument},
                {"date", m.date},
                {"time", m.time},
                {"source_file", m.source_file},
                {"entry", m.entry},
                {"curve_index", std::to_string(m.curve_index)},
                {"curve_count", std::to_string(m.curve_count)},
                {"spring_constant", k ? text_of(m.spring_constant) : ""},
                {"spring_constant_source", afm::calibration_source_name(m.spring_constant_source)},
                {"sensitivity", s ? text_of(m.sensitivity) : ""},
                {"sensitivity_source", afm::calibration_source_name(m.sensitivity_source)}};
  for (const auto& detail : m.details) c.metadata.push_back(detail);
}

// cc_afm_curve_create's curve, checked: lengths, segments contiguous over 0..n, a height.
afm::ForceCurve curve_of_arrays(long n, const double* force, const double* height_piezo, const double* height_measured,
                                const double* time, long segment_count, const cc_afm_segment* segments,
                                double spring_constant, const std::string& source) {
  const std::string f = "cc_afm_curve_create: ";
  if (n < 1) throw InputError(f + "n " + std::to_string(n) + " is not allowed; expected >= 1 points");
  require(force, "cc_afm_curve_create", "force");
  if (!height_piezo && !height_measured) throw InputError(f + "height_piezo and height_measured are NULL; give at least one");
  if (segment_count < 1) throw InputError(f + "segment_count " + std::to_string(segment_count) + " is not allowed; expected >= 1");
  require(segments, "cc_afm_curve_create", "segments");
  if (!(spring_constant >= 0.0) || !std::isfinite(spring_constant)) {
    throw InputError(f + "spring_constant " + text_of(spring_constant) + " is not allowed; expected > 0 [N/m], or 0 for none");
  }
  afm::ForceCurve c;
  const auto copy = [n](const double* p) { return p ? std::vector<double>(p, p + n) : std::vector<double>(); };
  c.force = copy(force);
  c.height_piezo = copy(height_piezo);
  c.height_measured = copy(height_measured);
  c.time = copy(time);
  long expected_begin = 0;
  for (long k = 0; k < segment_count; ++k) {
    const cc_afm_segment& s = segments[k];
    const std::string which = "segments[" + std::to_string(k) + "]";
    if (s.kind != CC_AFM_APPROACH && s.kind != CC_AFM_PAUSE && s.kind != CC_AFM_RETRACT) {
      throw InputError(f + which + ".kind " + std::to_string(s.kind) + " is not allowed; expected CC_AFM_APPROACH (0), CC_AFM_PAUSE (1) or CC_AFM_RETRACT (2)");
    }
    if (s.begin != expected_begin || s.end < s.begin || s.end > n) {
      throw InputError(f + which + " [" + std::to_string(s.begin) + ", " + std::to_string(s.end) + ") is not allowed; expected begin " +
                       std::to_string(expected_begin) + " (contiguous from 0) and begin <= end <= n = " + std::to_string(n));
    }
    afm::Segment segment;
    segment.kind = s.kind == CC_AFM_APPROACH ? afm::SegmentKind::kApproach
                   : s.kind == CC_AFM_PAUSE  ? afm::SegmentKind::kPause
                                             : afm::SegmentKind::kRetract;
    segment.begin = static_cast<std::size_t>(s.begin);
    segment.end = static_cast<std::size_t>(s.end);
    segment.name = s.name ? s.name : "";
    segment.duration = s.duration;
    c.segments.push_back(segment);
    c.segment.insert(c.segment.end(), segment.size(), static_cast<int>(k));
    expected_begin = s.end;
  }
  if (expected_begin != n) {
    throw InputError(f + "the segments end at point " + std::to_string(expected_begin) + "; they must cover all n = " + std::to_string(n));
  }
  c.metadata.source_file = source;
  c.metadata.format = "arrays";
  if (spring_constant > 0.0) {
    c.metadata.spring_constant = spring_constant;
    c.metadata.spring_constant_source = afm::CalibrationSource::kUser;
  }
  return c;
}

const cc_afm_curve& curve_of(const cc_afm_curve* curve, const char* function) {
  require(curve, function, "curve");
  return *curve;
}

afm::PreprocessOptions preprocess_options(const cc_afm_preprocess_options& o, const char* function) {
  const std::string f(function);
  if (!(o.baseline_fraction > 0.0 && o.baseline_fraction < 1.0)) {
    throw InputError(f + ": baseline_fraction " + text_of(o.baseline_fraction) + " is not allowed; expected a number in (0, 1)");
  }
  if (o.contact_method != CC_AFM_CONTACT_DEVIATION && o.contact_method != CC_AFM_CONTACT_PIECEWISE_FIT) {
    throw InputError(f + ": contact_method " + std::to_string(o.contact_method) +
                     " is not allowed; expected CC_AFM_CONTACT_DEVIATION (0) or CC_AFM_CONTACT_PIECEWISE_FIT (1)");
  }
  if (!(o.deviation_sigmas > 0.0) || !std::isfinite(o.deviation_sigmas)) {
    throw InputError(f + ": deviation_sigmas " + text_of(o.deviation_sigmas) + " is not allowed; expected a number > 0");
  }
  if (!(o.piecewise_exponent > 0.0) || !std::isfinite(o.piecewise_exponent)) {
    throw InputError(f + ": piecewise_exponent " + text_of(o.piecewise_exponent) + " is not allowed; expected a number > 0");
  }
  afm::PreprocessOptions options;
  options.baseline_fraction = o.baseline_fraction;
  options.contact_method = o.contact_method == CC_AFM_CONTACT_DEVIATION ? afm::ContactPointMethod::kDeviation
                                                                        : afm::ContactPointMethod::kPiecewiseFit;
  options.deviation_sigmas = o.deviation_sigmas;
  options.piecewise_exponent = o.piecewise_exponent;
  return options;
}

}  // namespace

namespace coatcontact::capi {
// For capi_afm_fit.cpp: the library's preprocessing options of the C struct, checked.
afm::PreprocessOptions afm_preprocess_options(const cc_afm_preprocess_options& options, const char* function) {
  return preprocess_options(options, function);
}
afm::Calibration afm_calibration(const cc_afm_calibration* calibration, const char* function) {
  return calibration_of(calibration, function);
}
}  // namespace coatcontact::capi

extern "C" {

int cc_afm_open(const char* path, const cc_afm_calibration* calibration, cc_afm_file** file) {
  return guard([&] {
    require(path, "cc_afm_open", "path");
    require(file, "cc_afm_open", "file");
    auto made = std::make_unique<cc_afm_file>();
    made->source = std::make_unique<afm::CurveSource>(path, calibration_of(calibration, "cc_afm_open"));
    *file = made.release();
  });
}

void cc_afm_file_destroy(cc_afm_file* file) { delete file; }

int cc_afm_file_count(const cc_afm_file* file, long* count) {
  return guard([&] {
    require(file, "cc_afm_file_count", "file");
    require(count, "cc_afm_file_count", "count");
    *count = static_cast<long>(file->source->size());
  });
}

int cc_afm_file_format(const cc_afm_file* file, const char** name) {
  return guard([&] {
    require(file, "cc_afm_file_format", "file");
    require(name, "cc_afm_file_format", "name");
    *name = afm::file_format_name(file->source->format());
  });
}

int cc_afm_curve_read(const cc_afm_file* file, long index, cc_afm_curve** curve) {
  return guard([&] {
    require(file, "cc_afm_curve_read", "file");
    require(curve, "cc_afm_curve_read", "curve");
    const std::size_t i = checked_index(index, file->source->size(), "cc_afm_curve_read", "index");
    auto made = std::make_unique<cc_afm_curve>();
    made->curve = file->source->read(i);
    fill_channels(*made);
    fill_metadata(*made);
    *curve = made.release();
  });
}

void cc_afm_curve_destroy(cc_afm_curve* curve) { delete curve; }

int cc_afm_curve_create(long n, const double* force, const double* height_piezo, const double* height_measured,
                        const double* time, long segment_count, const cc_afm_segment* segments, double spring_constant,
                        const char* source, cc_afm_curve** curve) {
  return guard([&] {
    require(curve, "cc_afm_curve_create", "curve");
    auto made = std::make_unique<cc_afm_curve>();
    made->curve = curve_of_arrays(n, force, height_piezo, height_measured, time, segment_count, segments, spring_constant,
                                  source ? source : "arrays");
    fill_channels(*made);
    fill_metadata(*made);
    *curve = made.release();
  });
}

int cc_afm_measured_pulloff(long n, const double* tip_position, const double* force, double fraction, cc_afm_pulloff* out) {
  return guard([&] {
    const char* f = "cc_afm_measured_pulloff";
    require(tip_position, f, "tip_position");
    require(force, f, "force");
    require(out, f, "out");
    if (n < 1) throw InputError(std::string(f) + ": n " + std::to_string(n) + " is not allowed; expected >= 1");
    if (!(fraction > 0.0 && fraction < 1.0)) {
      throw InputError(std::string(f) + ": fraction " + text_of(fraction) + " is not allowed; expected a number in (0, 1)");
    }
    const auto p = coatcontact::fit::afm_measured_pulloff(std::vector<double>(tip_position, tip_position + n),
                                                          std::vector<double>(force, force + n), fraction);
    cc_afm_pulloff result{};
    result.found = p.found;
    result.force = p.force;
    result.tip_position = p.tip_position;
    result.index = static_cast<long>(p.index);
    result.baseline_offset = p.baseline_offset;
    result.baseline_slope = p.baseline_slope;
    result.baseline_points = static_cast<long>(p.baseline_points);
    *out = result;
  });
}

int cc_afm_curve_points(const cc_afm_curve* curve, long* points) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_points");
    require(points, "cc_afm_curve_points", "points");
    *points = static_cast<long>(c.curve.point_count());
  });
}

int cc_afm_curve_segment_count(const cc_afm_curve* curve, long* count) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_segment_count");
    require(count, "cc_afm_curve_segment_count", "count");
    *count = static_cast<long>(c.curve.segments.size());
  });
}

int cc_afm_curve_segment(const cc_afm_curve* curve, long segment, cc_afm_segment* out) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_segment");
    require(out, "cc_afm_curve_segment", "out");
    const afm::Segment& s = c.curve.segments[checked_index(segment, c.curve.segments.size(), "cc_afm_curve_segment", "segment")];
    cc_afm_segment result{};
    result.kind = s.kind == afm::SegmentKind::kApproach ? CC_AFM_APPROACH
                  : s.kind == afm::SegmentKind::kPause   ? CC_AFM_PAUSE
                                                         : CC_AFM_RETRACT;
    result.begin = static_cast<long>(s.begin);
    result.end = static_cast<long>(s.end);
    result.name = s.name.c_str();
    result.duration = s.duration;
    *out = result;
  });
}

int cc_afm_curve_channel_count(const cc_afm_curve* curve, long* count) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_channel_count");
    require(count, "cc_afm_curve_channel_count", "count");
    *count = static_cast<long>(c.channels.size());
  });
}

int cc_afm_curve_channel_name(const cc_afm_curve* curve, long channel, const char** name) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_channel_name");
    require(name, "cc_afm_curve_channel_name", "name");
    *name = c.channels[checked_index(channel, c.channels.size(), "cc_afm_curve_channel_name", "channel")].first.c_str();
  });
}

int cc_afm_curve_channel(const cc_afm_curve* curve, const char* name, double* values, long capacity, long* length) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_channel");
    require(name, "cc_afm_curve_channel", "name");
    std::string names;
    for (const auto& [channel, data] : c.channels) {
      if (channel == name) return copy_out(data, values, capacity, length, "cc_afm_curve_channel", channel);
      names += (names.empty() ? "" : ", ") + channel;
    }
    throw InputError(std::string("cc_afm_curve_channel: name '") + std::string(name).substr(0, 60) +
                     "' is not a channel of this curve; it has " + names);
  });
}

int cc_afm_curve_metadata_count(const cc_afm_curve* curve, long* count) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_metadata_count");
    require(count, "cc_afm_curve_metadata_count", "count");
    *count = static_cast<long>(c.metadata.size());
  });
}

int cc_afm_curve_metadata_entry(const cc_afm_curve* curve, long entry, const char** key, const char** value) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_curve_metadata_entry");
    require(key, "cc_afm_curve_metadata_entry", "key");
    require(value, "cc_afm_curve_metadata_entry", "value");
    const auto& item = c.metadata[checked_index(entry, c.metadata.size(), "cc_afm_curve_metadata_entry", "entry")];
    *key = item.first.c_str();
    *value = item.second.c_str();
  });
}

int cc_afm_curve_grid(const cc_afm_curve* curve, cc_afm_grid* grid) {
  return guard([&] {
    const auto& m = curve_of(curve, "cc_afm_curve_grid").curve.metadata;
    require(grid, "cc_afm_curve_grid", "grid");
    cc_afm_grid out{};
    out.has_index = m.grid_index_x && m.grid_index_y;
    if (out.has_index) {
      out.index_x = *m.grid_index_x;
      out.index_y = *m.grid_index_y;
    }
    out.has_shape = m.grid_shape_x && m.grid_shape_y;
    if (out.has_shape) {
      out.shape_x = *m.grid_shape_x;
      out.shape_y = *m.grid_shape_y;
    }
    out.has_position = m.position_x && m.position_y;
    if (out.has_position) {
      out.position_x = *m.position_x;
      out.position_y = *m.position_y;
    }
    *grid = out;
  });
}

int cc_afm_curve_set_place(cc_afm_curve* curve, long curve_index, const cc_afm_grid* grid) {
  return guard([&] {
    const char* f = "cc_afm_curve_set_place";
    require(curve, f, "curve");
    if (curve_index < 0) throw InputError(std::string(f) + ": curve_index " + std::to_string(curve_index) + " is not allowed; expected >= 0");
    if (grid && grid->has_position && !(std::isfinite(grid->position_x) && std::isfinite(grid->position_y))) {
      throw InputError(std::string(f) + ": position (" + text_of(grid->position_x) + ", " + text_of(grid->position_y) +
                       ") is not allowed; expected finite numbers [m]");
    }
    afm::CurveMetadata& m = curve->curve.metadata;
    m.curve_index = static_cast<std::size_t>(curve_index);
    m.grid_index_x.reset();
    m.grid_index_y.reset();
    m.position_x.reset();
    m.position_y.reset();
    if (grid && grid->has_index) {
      m.grid_index_x = grid->index_x;
      m.grid_index_y = grid->index_y;
    }
    if (grid && grid->has_position) {
      m.position_x = grid->position_x;
      m.position_y = grid->position_y;
    }
    fill_metadata(*curve);
  });
}

int cc_afm_preprocess_defaults(cc_afm_preprocess_options* options) {
  return guard([&] {
    require(options, "cc_afm_preprocess_defaults", "options");
    const afm::PreprocessOptions d;
    options->baseline_fraction = d.baseline_fraction;
    options->contact_method =
        d.contact_method == afm::ContactPointMethod::kDeviation ? CC_AFM_CONTACT_DEVIATION : CC_AFM_CONTACT_PIECEWISE_FIT;
    options->deviation_sigmas = d.deviation_sigmas;
    options->piecewise_exponent = d.piecewise_exponent;
  });
}

int cc_afm_preprocess(const cc_afm_curve* curve, const cc_afm_preprocess_options* options, cc_afm_preprocessed* out,
                      double* tip_position, double* force_corrected, long capacity) {
  return guard([&] {
    const auto& c = curve_of(curve, "cc_afm_preprocess");
    require(out, "cc_afm_preprocess", "out");
    const afm::PreprocessOptions o = options ? preprocess_options(*options, "cc_afm_preprocess") : afm::PreprocessOptions{};
    const long points = static_cast<long>(c.curve.point_count());
    if ((tip_position || force_corrected) && capacity < points) {
      throw InputError("cc_afm_preprocess: capacity " + std::to_string(capacity) + " is below the curve's " +
                       std::to_string(points) + " points");
    }
    const afm::PreprocessedCurve p = afm::preprocess(c.curve, o);
    cc_afm_preprocessed result{};
    result.baseline_offset = p.baseline_offset;
    result.baseline_slope = p.baseline_slope;
    result.baseline_offset_error = p.baseline_offset_error;
    result.baseline_slope_error = p.baseline_slope_error;
    result.baseline_sigma = p.baseline_sigma;
    result.baseline_points = static_cast<long>(p.baseline_points);
    result.contact_method =
        p.contact_method == afm::ContactPointMethod::kDeviation ? CC_AFM_CONTACT_DEVIATION : CC_AFM_CONTACT_PIECEWISE_FIT;
    result.contact_point = p.contact_point;
    result.contact_index = static_cast<long>(p.contact_index);
    long length = 0;
    if (tip_position) copy_out(p.tip_position, tip_position, capacity, &length, "cc_afm_preprocess", "tip_position");
    if (force_corrected) copy_out(p.force_corrected, force_corrected, capacity, &length, "cc_afm_preprocess", "force_corrected");
    *out = result;
  });
}

}  // extern "C"
