// Compiled part of coatcontact.afm (module coatcontact._afm): the library's AFM readers, each
// curve returned as a dict of NumPy arrays under the names of the Python AFM tools plus its
// metadata and segments. InputError (unreadable file, missing calibration) -> ValueError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <tuple>
#include <string>
#include <vector>

#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"

namespace py = pybind11;
namespace afm = coatcontact::afm;

namespace {

template <class T>
py::array_t<T> to_array(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::dict metadata_of(const afm::ForceCurve& curve) {
  const afm::CurveMetadata& m = curve.metadata;
  py::dict d;
  if (m.spring_constant_source != afm::CalibrationSource::kNone) d["spring constant"] = m.spring_constant;
  if (m.sensitivity_source != afm::CalibrationSource::kNone) d["sensitivity"] = m.sensitivity;
  d["spring constant source"] = afm::calibration_source_name(m.spring_constant_source);
  d["sensitivity source"] = afm::calibration_source_name(m.sensitivity_source);
  d["vendor"] = m.vendor;
  d["format"] = m.format;
  if (!m.instrument.empty()) d["instrument"] = m.instrument;
  if (!m.date.empty()) d["date"] = m.date;
  if (!m.time.empty()) d["time"] = m.time;
  d["path"] = m.source_file;
  if (!m.entry.empty()) d["archive entry"] = m.entry;
  d["curve index"] = m.curve_index;
  d["curve count"] = m.curve_count;
  if (m.grid_index_x) d["grid index x"] = *m.grid_index_x;
  if (m.grid_index_y) d["grid index y"] = *m.grid_index_y;
  if (m.grid_shape_x) d["grid shape x"] = *m.grid_shape_x;
  if (m.grid_shape_y) d["grid shape y"] = *m.grid_shape_y;
  if (m.position_x) d["position x"] = *m.position_x;
  if (m.position_y) d["position y"] = *m.position_y;
  d["point count"] = curve.point_count();
  for (const auto& [key, value] : m.details) d[py::str(key)] = value;
  return d;
}

py::list read_curves(const std::string& path, std::optional<double> spring_constant, std::optional<double> sensitivity) {
  afm::Calibration calibration;
  calibration.spring_constant = spring_constant;
  calibration.sensitivity = sensitivity;
  std::vector<afm::ForceCurve> curves;
  std::string error;
  {
    py::gil_scoped_release release;
    try {
      curves = afm::read_force_curves(path, calibration);
    } catch (const coatcontact::InputError& e) {
      error = e.what();
    }
  }
  if (!error.empty()) {
    // The library names the CLI's options; Python callers pass keywords of the same names.
    for (const auto& [option, keyword] : {std::pair<std::string, std::string>{"--spring-constant", "spring_constant"},
                                          {"--sensitivity", "sensitivity"}}) {
      for (std::size_t at = error.find(option + ": "); at != std::string::npos; at = error.find(option + ": ")) {
        error.replace(at, option.size(), keyword);
      }
    }
    throw py::value_error(error);
  }
  py::list out;
  for (const auto& curve : curves) {
    py::dict d;
    d["force"] = to_array(curve.force);
    if (curve.has_height_piezo()) d["height (piezo)"] = to_array(curve.height_piezo);
    if (curve.has_height_measured()) d["height (measured)"] = to_array(curve.height_measured);
    if (curve.metadata.spring_constant_source != afm::CalibrationSource::kNone) {
      d["tip position"] = to_array(curve.tip_position());
    }
    d["segment"] = to_array(curve.segment);
    if (!curve.time.empty()) d["time"] = to_array(curve.time);
    py::list segments;
    for (const auto& s : curve.segments) {
      py::dict seg;
      seg["kind"] = afm::segment_kind_name(s.kind);
      seg["begin"] = s.begin;
      seg["end"] = s.end;
      seg["name"] = s.name;
      if (s.duration > 0.0) seg["duration"] = s.duration;
      segments.append(seg);
    }
    d["segments"] = segments;
    d["metadata"] = metadata_of(curve);
    out.append(d);
  }
  return out;
}

std::vector<double> to_vector(const py::object& array) {
  if (array.is_none()) return {};
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 1) throw py::value_error("channels must be one-dimensional arrays of numbers");
  return std::vector<double>(a.data(), a.data() + a.size());
}

// Preprocessing steps of one curve given as arrays; segments as (kind, begin, end) triples.
py::dict preprocess_arrays(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                           const std::vector<std::tuple<std::string, std::size_t, std::size_t>>& segments,
                           double spring_constant, const std::string& contact_point, double baseline_fraction,
                           double deviation_sigmas, const std::string& name) {
  afm::ForceCurve curve;
  curve.force = to_vector(force);
  curve.height_piezo = to_vector(height_piezo);
  curve.height_measured = to_vector(height_measured);
  const std::size_t n = curve.force.size();
  if ((curve.has_height_piezo() && curve.height_piezo.size() != n) || (curve.has_height_measured() && curve.height_measured.size() != n) ||
      (!curve.has_height_piezo() && !curve.has_height_measured())) {
    throw py::value_error("a height channel as long as the force is needed");
  }
  std::size_t expected = 0;
  for (const auto& [kind, begin, end] : segments) {
    afm::Segment s;
    if (kind == "approach") s.kind = afm::SegmentKind::kApproach;
    else if (kind == "pause") s.kind = afm::SegmentKind::kPause;
    else if (kind == "retract") s.kind = afm::SegmentKind::kRetract;
    else throw py::value_error("segment kind '" + kind + "' is not approach, pause or retract");
    if (begin != expected || end <= begin || end > n) throw py::value_error("segments must cover the points in order");
    s.begin = begin;
    s.end = end;
    expected = end;
    curve.segments.push_back(s);
  }
  if (expected != n) throw py::value_error("segments must cover the points in order");
  curve.segment.assign(n, 0);
  for (std::size_t k = 0; k < curve.segments.size(); ++k) {
    for (std::size_t i = curve.segments[k].begin; i < curve.segments[k].end; ++i) curve.segment[i] = static_cast<int>(k);
  }
  if (!(std::isfinite(spring_constant) && spring_constant > 0.0)) throw py::value_error("spring_constant must be a finite number > 0");
  curve.metadata.spring_constant = spring_constant;
  curve.metadata.spring_constant_source = afm::CalibrationSource::kUser;
  curve.metadata.source_file = name;
  afm::PreprocessOptions options;
  if (contact_point == "piecewise-fit") options.contact_method = afm::ContactPointMethod::kPiecewiseFit;
  else if (contact_point == "deviation") options.contact_method = afm::ContactPointMethod::kDeviation;
  else throw py::value_error("contact_point: '" + contact_point + "' is not a method; expected piecewise-fit or deviation");
  options.baseline_fraction = baseline_fraction;
  options.deviation_sigmas = deviation_sigmas;
  afm::PreprocessedCurve p;
  try {
    py::gil_scoped_release release;
    p = afm::preprocess(curve, options);
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  }
  py::dict out;
  out["tip position"] = to_array(p.tip_position);
  out["force (corrected)"] = to_array(p.force_corrected);
  out["baseline offset"] = p.baseline_offset;
  out["baseline slope"] = p.baseline_slope;
  out["baseline offset error"] = p.baseline_offset_error;
  out["baseline slope error"] = p.baseline_slope_error;
  out["baseline sigma"] = p.baseline_sigma;
  out["baseline points"] = p.baseline_points;
  out["contact point method"] = afm::contact_point_method_name(p.contact_method);
  out["contact point"] = p.contact_point;
  out["contact index"] = p.contact_index;
  return out;
}

}  // namespace

PYBIND11_MODULE(_afm, m) {
  m.doc() = "Compiled AFM readers of coatcontact; use coatcontact.afm.";
  m.def("read", &read_curves, py::arg("path"), py::arg("spring_constant") = py::none(), py::arg("sensitivity") = py::none());
  m.def("preprocess", &preprocess_arrays, py::arg("force"), py::arg("height_piezo"), py::arg("height_measured"),
        py::arg("segments"), py::arg("spring_constant"), py::arg("contact_point"), py::arg("baseline_fraction"),
        py::arg("deviation_sigmas"), py::arg("name"));
}
