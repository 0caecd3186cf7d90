// Compiled part of coatcontact.afm (module coatcontact._afm) over the C API only
// (coatcontact/coatcontact_afm.h, cc_afm_*): the readers (each curve a dict of NumPy arrays
// under the names of the Python AFM tools, with its metadata and segments), preprocessing, the
// one-curve fit, the fit of given arrays and the batch of many curves. This file is compiled
// with the C API's public include folder only (python/CMakeLists.txt), so it cannot reach the
// library's C++ headers. InputError -> ValueError; a numerical failure -> RuntimeError
// ("numerical failure: ..."), which coatcontact.afm raises as NumericalError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "coatcontact/coatcontact.h"

namespace py = pybind11;

namespace {

using Segments = std::vector<std::tuple<std::string, std::size_t, std::size_t>>;

template <class T>
py::array_t<T> to_array(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

template <class T>
py::array_t<T> converted(const std::vector<double>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) out.mutable_data()[i] = static_cast<T>(values[i]);
  return out;
}

// The C API names its functions and the CLI's options in messages; Python callers pass the
// keywords of coatcontact.afm.
std::string python_message(std::string text) {
  static const std::pair<const char*, const char*> prefixes[] = {
      {"cc_afm_request_set_free: ", "free: "},           {"cc_afm_request_set_tip_shape: ", "shape: "},
      {"cc_afm_request_set_tip: ", "shape: "},           {"cc_afm_request_set_model: ", ""},
      {"cc_afm_request_set_sample: ", "sample: "},       {"cc_afm_request_set_segment: segment ", "segment: "},
      {"cc_afm_request_set_baseline_model: model ", "baseline_model: "},
      {"cc_afm_request_set: ", ""},                      {"cc_afm_fit_curve: ", ""},
      {"cc_afm_fit_arrays: ", ""},                       {"cc_afm_fit_batch: ", ""},
      {"cc_afm_fit_curves: ", ""},                       {"cc_afm_survey_files: ", ""},
      {"cc_afm_expand_paths: ", ""},                     {"cc_afm_open: ", ""},
      {"cc_afm_preprocess: ", ""}};
  for (const auto& [prefix, keyword] : prefixes) {
    const std::string p(prefix);
    if (text.compare(0, p.size(), p) == 0) {
      text.replace(0, p.size(), keyword);
      break;
    }
  }
  for (const auto& [option, keyword] : {std::pair<std::string, std::string>{"--spring-constant", "spring_constant"},
                                        {"--sensitivity", "sensitivity"}}) {
    for (std::size_t at = text.find(option + ": "); at != std::string::npos; at = text.find(option + ": ")) {
      text.replace(at, option.size(), keyword);
    }
  }
  return text;
}

// Ctrl-C during a long C call (issue 40): the thread's progress hook (cc_set_progress_hook),
// called between units of work (curves, chunks of curves), takes the GIL and runs Python's
// signal handlers; a KeyboardInterrupt stops the call (CC_INTERRUPTED) and is raised by
// rethrow() once the call has returned. A Python exception of a sink is kept the same way.
struct SignalCheck {
  std::exception_ptr error;
  bool operator()() {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (...) {
      error = std::current_exception();
      return false;
    }
    return true;
  }
  static int hook(void* user, long, long) { return (*static_cast<SignalCheck*>(user))() ? 0 : 1; }
  void rethrow() const {
    if (error) std::rethrow_exception(error);
  }
};

// The hook installed on this thread for one call.
struct ScopedHook {
  explicit ScopedHook(SignalCheck& signals) { cc_set_progress_hook(&SignalCheck::hook, &signals); }
  ~ScopedHook() { cc_set_progress_hook(nullptr, nullptr); }
  ScopedHook(const ScopedHook&) = delete;
  ScopedHook& operator=(const ScopedHook&) = delete;
};

// A C status as the module's exception (the message read on the calling thread).
void check(int status, const SignalCheck* signals = nullptr) {
  if (status == CC_OK) return;
  const std::string message = python_message(cc_last_error_message());
  if (status == CC_INTERRUPTED && signals) signals->rethrow();
  if (status == CC_INPUT_ERROR) throw py::value_error(message);
  if (status == CC_NUMERICAL_ERROR) throw std::runtime_error("numerical failure: " + message);
  throw std::runtime_error(message.empty() ? "coatcontact: internal error" : message);
}

// A C call without the GIL; the status is checked with it.
template <typename Call>
void released(Call&& call, const SignalCheck* signals = nullptr) {
  int status;
  {
    py::gil_scoped_release release;
    status = call();
  }
  check(status, signals);
}

template <class T, void (*Destroy)(T*)>
struct Deleter {
  void operator()(T* p) const { Destroy(p); }
};
using CurveHandle = std::unique_ptr<cc_afm_curve, Deleter<cc_afm_curve, cc_afm_curve_destroy>>;
using FileHandle = std::unique_ptr<cc_afm_file, Deleter<cc_afm_file, cc_afm_file_destroy>>;
using RequestHandle = std::unique_ptr<cc_afm_request, Deleter<cc_afm_request, cc_afm_request_destroy>>;
using FitHandle = std::unique_ptr<cc_afm_fit, Deleter<cc_afm_fit, cc_afm_fit_destroy>>;
using RowsHandle = std::unique_ptr<cc_afm_rows, Deleter<cc_afm_rows, cc_afm_rows_destroy>>;
using StackHandle = std::unique_ptr<cc_stack, Deleter<cc_stack, cc_stack_destroy>>;
using ShapeHandle = std::unique_ptr<cc_shape, Deleter<cc_shape, cc_shape_destroy>>;
using FileListHandle = std::unique_ptr<cc_afm_file_list, Deleter<cc_afm_file_list, cc_afm_file_list_destroy>>;

std::vector<double> to_vector(const py::object& array) {
  if (array.is_none()) return {};
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 1) throw py::value_error("channels must be one-dimensional arrays of numbers");
  return std::vector<double>(a.data(), a.data() + a.size());
}

// A channel or array of a handle, copied out (the length asked first).
template <typename Get>
std::vector<double> array_of(Get&& get) {
  long length = 0;
  check(get(nullptr, 0L, &length));
  std::vector<double> values(static_cast<std::size_t>(length));
  check(get(values.data(), length, &length));
  return values;
}

const char* segment_kind_name(int kind) {
  return kind == CC_AFM_APPROACH ? "approach" : kind == CC_AFM_PAUSE ? "pause" : "retract";
}

// ---- reading ---------------------------------------------------------------------------------

// read()'s metadata dict, in the order and with the types of the Python AFM tools.
py::dict metadata_of(const cc_afm_curve* curve, long points) {
  long count = 0;
  check(cc_afm_curve_metadata_count(curve, &count));
  std::map<std::string, std::string> fixed;  // the first 13 entries (coatcontact_afm.h)
  std::vector<std::pair<std::string, std::string>> details;
  for (long i = 0; i < count; ++i) {
    const char *key = nullptr, *value = nullptr;
    check(cc_afm_curve_metadata_entry(curve, i, &key, &value));
    if (i < 13) fixed[key] = value;
    else details.emplace_back(key, value);
  }
  py::dict d;
  if (fixed["spring_constant_source"] != "none") d["spring constant"] = std::strtod(fixed["spring_constant"].c_str(), nullptr);
  if (fixed["sensitivity_source"] != "none") d["sensitivity"] = std::strtod(fixed["sensitivity"].c_str(), nullptr);
  d["spring constant source"] = fixed["spring_constant_source"];
  d["sensitivity source"] = fixed["sensitivity_source"];
  d["vendor"] = fixed["vendor"];
  d["format"] = fixed["format"];
  for (const auto& [key, name] : {std::pair<const char*, const char*>{"instrument", "instrument"}, {"date", "date"}, {"time", "time"}}) {
    if (!fixed[key].empty()) d[name] = fixed[key];
  }
  d["path"] = fixed["source_file"];
  if (!fixed["entry"].empty()) d["archive entry"] = fixed["entry"];
  d["curve index"] = std::stoull(fixed["curve_index"]);
  d["curve count"] = std::stoull(fixed["curve_count"]);
  cc_afm_grid grid{};
  check(cc_afm_curve_grid(curve, &grid));
  if (grid.has_index) {
    d["grid index x"] = grid.index_x;
    d["grid index y"] = grid.index_y;
  }
  if (grid.has_shape) {
    d["grid shape x"] = grid.shape_x;
    d["grid shape y"] = grid.shape_y;
  }
  if (grid.has_position) {
    d["position x"] = grid.position_x;
    d["position y"] = grid.position_y;
  }
  d["point count"] = static_cast<std::size_t>(points);
  for (const auto& [key, value] : details) d[py::str(key)] = value;
  return d;
}

// One curve of read(): its channels under the tools' names, segments and metadata.
py::dict curve_dict(const cc_afm_curve* curve) {
  long points = 0, channels = 0, segments = 0;
  check(cc_afm_curve_points(curve, &points));
  check(cc_afm_curve_channel_count(curve, &channels));
  std::map<std::string, std::vector<double>> data;
  for (long c = 0; c < channels; ++c) {
    const char* name = nullptr;
    check(cc_afm_curve_channel_name(curve, c, &name));
    data[name] = array_of([&](double* v, long cap, long* len) { return cc_afm_curve_channel(curve, name, v, cap, len); });
  }
  py::dict d;
  d["force"] = to_array(data["force"]);
  if (data.count("height_piezo")) d["height (piezo)"] = to_array(data["height_piezo"]);
  if (data.count("height_measured")) d["height (measured)"] = to_array(data["height_measured"]);
  if (data.count("tip_position")) d["tip position"] = to_array(data["tip_position"]);
  d["segment"] = converted<int>(data["segment"]);
  if (data.count("time")) d["time"] = to_array(data["time"]);
  check(cc_afm_curve_segment_count(curve, &segments));
  py::list parts;
  for (long k = 0; k < segments; ++k) {
    cc_afm_segment s{};
    check(cc_afm_curve_segment(curve, k, &s));
    py::dict seg;
    seg["kind"] = segment_kind_name(s.kind);
    seg["begin"] = static_cast<std::size_t>(s.begin);
    seg["end"] = static_cast<std::size_t>(s.end);
    seg["name"] = s.name ? s.name : "";
    if (s.duration > 0.0) seg["duration"] = s.duration;
    parts.append(seg);
  }
  d["segments"] = parts;
  d["metadata"] = metadata_of(curve, points);
  return d;
}

py::list read_curves(const std::string& path, std::optional<double> spring_constant, std::optional<double> sensitivity) {
  const cc_afm_calibration calibration{spring_constant.value_or(0.0), sensitivity.value_or(0.0), 0};
  std::vector<CurveHandle> curves;
  std::vector<std::string> unreadable;  // curves of a map that cannot be read, with why
  std::string error;
  SignalCheck signals;
  {
    py::gil_scoped_release release;
    // Curve by curve, so that Ctrl-C stops the reading of a large map between curves, and a
    // corrupt curve of a map costs that curve only (as in `afm show`).
    cc_afm_file* opened = nullptr;
    long count = 0;
    if (cc_afm_open(path.c_str(), &calibration, &opened) != CC_OK || cc_afm_file_count(opened, &count) != CC_OK) {
      error = cc_last_error_message();
    }
    const FileHandle file(opened);
    for (long i = 0; error.empty() && i < count; ++i) {
      if (!signals()) break;
      cc_afm_curve* curve = nullptr;
      const int status = cc_afm_curve_read(file.get(), i, &curve);
      if (status == CC_OK) {
        curves.emplace_back(curve);
      } else if (status == CC_INPUT_ERROR && count > 1) {
        unreadable.push_back("curve " + std::to_string(i) + ": " + cc_last_error_message());
      } else {
        error = cc_last_error_message();
      }
    }
    if (error.empty() && curves.empty() && !unreadable.empty()) error = "no curve of the file can be read; " + unreadable.front();
  }
  signals.rethrow();
  if (!error.empty()) throw py::value_error(python_message(error));
  for (const auto& why : unreadable) {
    const std::string text = path + ": " + why + " (left out; the others keep their \"curve index\")";
    if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 2) != 0) throw py::error_already_set();
  }
  py::list out;
  for (const auto& curve : curves) out.append(curve_dict(curve.get()));
  return out;
}

// A curve given as arrays; segments as (kind, begin, end) triples covering the points in order.
CurveHandle curve_of(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                     const Segments& segments, double spring_constant, const std::string& name) {
  const std::vector<double> f = to_vector(force), piezo = to_vector(height_piezo), measured = to_vector(height_measured);
  const std::size_t n = f.size();
  if ((!piezo.empty() && piezo.size() != n) || (!measured.empty() && measured.size() != n) || (piezo.empty() && measured.empty())) {
    throw py::value_error("a height channel as long as the force is needed");
  }
  std::vector<cc_afm_segment> parts;
  std::size_t expected = 0;
  for (const auto& [kind, begin, end] : segments) {
    cc_afm_segment s{};
    if (kind == "approach") s.kind = CC_AFM_APPROACH;
    else if (kind == "pause") s.kind = CC_AFM_PAUSE;
    else if (kind == "retract") s.kind = CC_AFM_RETRACT;
    else throw py::value_error("segment kind '" + kind + "' is not approach, pause or retract");
    if (begin != expected || end <= begin || end > n) throw py::value_error("segments must cover the points in order");
    s.begin = static_cast<long>(begin);
    s.end = static_cast<long>(end);
    s.name = "";
    expected = end;
    parts.push_back(s);
  }
  if (expected != n) throw py::value_error("segments must cover the points in order");
  if (!(std::isfinite(spring_constant) && spring_constant > 0.0)) throw py::value_error("spring_constant must be a finite number > 0");
  cc_afm_curve* curve = nullptr;
  check(cc_afm_curve_create(static_cast<long>(n), f.data(), piezo.empty() ? nullptr : piezo.data(),
                            measured.empty() ? nullptr : measured.data(), nullptr, static_cast<long>(parts.size()),
                            parts.data(), spring_constant, name.c_str(), &curve));
  return CurveHandle(curve);
}

// Preprocessing steps of one curve given as arrays; segments as (kind, begin, end) triples.
py::dict preprocess_arrays(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                           const Segments& segments, double spring_constant, const std::string& contact_point,
                           double baseline_fraction, double deviation_sigmas, const std::string& name) {
  const CurveHandle curve = curve_of(force, height_piezo, height_measured, segments, spring_constant, name);
  cc_afm_preprocess_options options{};
  check(cc_afm_preprocess_defaults(&options));
  if (contact_point == "piecewise-fit") options.contact_method = CC_AFM_CONTACT_PIECEWISE_FIT;
  else if (contact_point == "deviation") options.contact_method = CC_AFM_CONTACT_DEVIATION;
  else throw py::value_error("contact_point: '" + contact_point + "' is not a method; expected piecewise-fit or deviation");
  options.baseline_fraction = baseline_fraction;
  options.deviation_sigmas = deviation_sigmas;
  long points = 0;
  check(cc_afm_curve_points(curve.get(), &points));
  std::vector<double> z(static_cast<std::size_t>(points)), corrected(static_cast<std::size_t>(points));
  cc_afm_preprocessed p{};
  released([&] { return cc_afm_preprocess(curve.get(), &options, &p, z.data(), corrected.data(), points); });
  py::dict out;
  out["tip position"] = to_array(z);
  out["force (corrected)"] = to_array(corrected);
  out["baseline offset"] = p.baseline_offset;
  out["baseline slope"] = p.baseline_slope;
  out["baseline offset error"] = p.baseline_offset_error;
  out["baseline slope error"] = p.baseline_slope_error;
  out["baseline sigma"] = p.baseline_sigma;
  out["baseline points"] = static_cast<std::size_t>(p.baseline_points);
  out["contact point method"] = p.contact_method == CC_AFM_CONTACT_PIECEWISE_FIT ? "piecewise-fit" : "deviation";
  out["contact point"] = p.contact_point;
  out["contact index"] = static_cast<std::size_t>(p.contact_index);
  return out;
}

// ---- the registry and the request ------------------------------------------------------------

// The registry's models for the Python layer: name, aliases, whether it needs the spring
// constant, its default segment, and its parameters (name, unit, free by default) per sample.
py::list model_list() {
  long count = 0;
  check(cc_afm_model_count(&count));
  py::list models;
  for (long m = 0; m < count; ++m) {
    cc_afm_model_info info{};
    check(cc_afm_model_get(m, &info));
    py::dict d;
    d["name"] = info.name;
    py::list aliases;
    for (std::string rest = info.aliases; !rest.empty();) {
      const std::size_t comma = rest.find(',');
      aliases.append(rest.substr(0, comma));
      rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    }
    d["aliases"] = aliases;
    d["title"] = info.title;
    d["spring"] = info.needs_spring != 0;
    d["segment"] = info.segment;
    for (const int coated : {0, 1}) {
      long n = 0;
      check(cc_afm_model_parameter_count(m, coated, &n));
      py::list parameters;
      for (long k = 0; k < n; ++k) {
        const char *name = nullptr, *unit = nullptr;
        int free = 0;
        check(cc_afm_model_parameter(m, coated, k, &name, &unit, &free));
        py::dict q;
        q["name"] = name;
        q["unit"] = unit;
        q["free"] = free != 0;
        parameters.append(q);
      }
      d[coated ? "coating_parameters" : "parameters"] = parameters;
      d[coated ? "coating_default_free" : "default_free"] = coated ? info.coating_default_free : info.default_free;
    }
    models.append(d);
  }
  return models;
}

bool model_needs_spring(const std::string& model) {
  long count = 0;
  check(cc_afm_model_count(&count));
  for (long m = 0; m < count; ++m) {
    cc_afm_model_info info{};
    check(cc_afm_model_get(m, &info));
    if (model == info.name) return info.needs_spring != 0;
  }
  return false;
}

// The tip of coatcontact.afm.fit: ("sphere", R), ("cone", beta), ("pyramid", theta), ("pyramid3", theta),
// ("sneddon-sphere", R), ("punch", A), ("power", n, R), ("blunted-cone", R, beta), ("profile", r, z);
// angles in rad.
void set_tip(cc_afm_request* request, const py::tuple& spec) {
  if (spec.size() < 2) throw py::value_error("shape: expected a tuple (kind, parameters...)");
  const std::string kind = py::str(spec[0]);
  const auto number = [&](std::size_t i) { return spec[i].cast<double>(); };
  const auto count = [&](std::size_t n) {
    if (spec.size() != n + 1) throw py::value_error("shape: '" + kind + "' takes " + std::to_string(n) + " parameter(s)");
  };
  if (kind == "sphere" || kind == "cone" || kind == "pyramid" || kind == "pyramid3" || kind == "sneddon-sphere") {
    count(1);
    return check(cc_afm_request_set_tip(request, kind.c_str(), number(1)));
  }
  cc_shape* shape = nullptr;
  if (kind == "punch") count(1), check(cc_shape_flat_punch(number(1), &shape));
  else if (kind == "power") count(2), check(cc_shape_power_law(number(1), number(2), &shape));
  else if (kind == "blunted-cone") count(2), check(cc_shape_blunted_cone(number(1), number(2), &shape));
  else if (kind == "profile") {
    count(2);
    const std::vector<double> r = to_vector(spec[1]), z = to_vector(spec[2]);
    if (r.size() != z.size()) throw py::value_error("shape profile: r and z differ in length");
    check(cc_shape_profile(static_cast<int>(r.size()), r.data(), z.data(), &shape));
  } else {
    throw py::value_error("shape: '" + kind + "' is not a tip; allowed: sphere, cone, pyramid, pyramid3, sneddon-sphere, punch, power, blunted-cone, profile");
  }
  const ShapeHandle owned(shape);
  check(cc_afm_request_set_tip_shape(request, owned.get()));
}

// The sample: a half-space (E, nu), or coating (E1, nu1, substrate (E0, nu0) or None for rigid,
// t[, layers ((h, E, nu, slip), ...), free layer]) (coatcontact.afm._stack_coating).
void set_sample(cc_afm_request* request, double modulus, double poisson, const py::object& coating) {
  cc_stack* made = nullptr;
  check(cc_stack_create(&made));
  const StackHandle stack(made);
  long free_layer = 0;
  if (coating.is_none()) {
    check(cc_stack_set_substrate(stack.get(), modulus, poisson));
  } else {
    const py::tuple c = coating.cast<py::tuple>();
    if (c.size() > 5) {
      for (const py::handle& row : c[4].cast<py::tuple>()) {
        const py::tuple l = row.cast<py::tuple>();
        check(cc_stack_add_layer(stack.get(), l[0].cast<double>(), l[1].cast<double>(), l[2].cast<double>(), l[3].cast<bool>()));
      }
      free_layer = c[5].cast<long>();
    } else {
      check(cc_stack_add_layer(stack.get(), c[3].cast<double>(), c[0].cast<double>(), c[1].cast<double>(), 0));
    }
    if (c[2].is_none()) {
      check(cc_stack_set_rigid_substrate(stack.get()));
    } else {
      const py::tuple sub = c[2].cast<py::tuple>();
      check(cc_stack_set_substrate(stack.get(), sub[0].cast<double>(), sub[1].cast<double>()));
    }
  }
  check(cc_afm_request_set_sample_layer(request, stack.get(), free_layer));
}

void set_number(cc_afm_request* request, const char* name, double value) { check(cc_afm_request_set(request, name, value)); }

void set_bound(cc_afm_request* request, const char* name, const py::object& value) {
  if (!value.is_none()) set_number(request, name, value.cast<double>());
}

// The request of fit, fit_map: tip, sample, model (adhesion: (w, k, z0, tilt, model), k 0: each
// curve's; None: hertz), free parameters and fixed values.
RequestHandle request_of(const py::tuple& shape, double modulus, double poisson, const std::vector<std::string>& free,
                         double contact_point, double baseline, const py::object& coating, const py::object& adhesion) {
  cc_afm_request* made = nullptr;
  check(cc_afm_request_create(&made));
  RequestHandle request(made);
  const auto is_free = [&](const char* name) { return std::find(free.begin(), free.end(), name) != free.end(); };
  if (!adhesion.is_none()) {
    const py::tuple a = adhesion.cast<py::tuple>();
    check(cc_afm_request_set_model(request.get(), a.size() > 4 ? a[4].cast<std::string>().c_str() : "jkr"));
    if (a[0].cast<double>() > 0.0) set_number(request.get(), "w", a[0].cast<double>());
    if (a[1].cast<double>() > 0.0) set_number(request.get(), "spring_constant", a[1].cast<double>());
    set_number(request.get(), "surface_force_range", a[2].cast<double>());
    if (!is_free("tilt")) set_number(request.get(), "tilt", a[3].cast<double>());
  }
  set_tip(request.get(), shape);
  set_sample(request.get(), modulus, poisson, coating);
  std::string names;
  for (const auto& name : free) names += (names.empty() ? "" : ",") + name;
  check(cc_afm_request_set_free(request.get(), names.c_str()));
  if (!is_free("contact_point")) set_number(request.get(), "contact_point", contact_point);
  if (!is_free("baseline")) set_number(request.get(), "baseline", baseline);
  return request;
}

// The request of fit_curve and the maps: request_of with the segment, range and baseline model.
RequestHandle settings_of(const py::tuple& shape, double modulus, double poisson, const std::vector<std::string>& free,
                          double contact_point, double baseline, const py::object& coating, const std::string& segment,
                          const py::object& tip_min, const py::object& tip_max, const py::object& indentation_min,
                          const py::object& indentation_max, const py::object& max_force, const py::object& adhesion,
                          const std::string& baseline_model, double weight_cp) {
  RequestHandle request = request_of(shape, modulus, poisson, free, contact_point, baseline, coating, adhesion);
  if (segment != "approach" && segment != "retract") {
    throw py::value_error("segment: '" + segment + "' is not allowed; expected 'approach' or 'retract'");
  }
  check(cc_afm_request_set_segment(request.get(), segment.c_str()));
  set_bound(request.get(), "tip_min", tip_min);
  set_bound(request.get(), "tip_max", tip_max);
  set_bound(request.get(), "indentation_min", indentation_min);
  set_bound(request.get(), "indentation_max", indentation_max);
  set_bound(request.get(), "max_force", max_force);
  if (!baseline_model.empty()) {
    if (baseline_model != "tilt" && baseline_model != "offset") {
      throw py::value_error("baseline_model: '" + baseline_model + "' is not allowed; expected 'tilt' or 'offset'");
    }
    check(cc_afm_request_set_baseline_model(request.get(), baseline_model.c_str()));
  }
  set_number(request.get(), "weight_cp", weight_cp);
  return request;
}

// ---- one fit ---------------------------------------------------------------------------------

// The modulus as the results name it: E, or on a coating E<K> after the free layer K (one
// film: E1), as the C API's free parameters and a map's columns.
std::string modulus_key(const cc_afm_fit_details& details) {
  return details.coated ? "E" + std::to_string(details.free_layer + 1) : "E";
}

std::vector<double> fit_array(const cc_afm_fit* fit, const char* name) {
  return array_of([&](double* v, long cap, long* len) { return cc_afm_fit_array(fit, name, v, cap, len); });
}

// The result dict of one fit (fit_arrays, fit_curve): estimates, errors and units by name,
// statistics, and the fitted points (index: into the caller's arrays).
py::dict result_dict(const cc_afm_fit* fit, bool weighted) {
  cc_afm_fit_details details{};
  cc_afm_fit_summary summary{};
  check(cc_afm_fit_get_details(fit, &details));
  check(cc_afm_fit_get_summary(fit, &summary));
  const bool coated = details.coated != 0;
  const bool jkr = model_needs_spring(details.model);  // the adhesive models
  long free_count = 0;
  check(cc_afm_fit_parameter_count(fit, &free_count));
  std::vector<std::string> free_names;
  for (long k = 0; k < free_count; ++k) {
    const char* name = nullptr;
    check(cc_afm_fit_parameter_name(fit, k, &name, nullptr));
    free_names.push_back(name);
  }
  const auto is_free = [&](const std::string& n) { return std::find(free_names.begin(), free_names.end(), n) != free_names.end(); };
  // (the C API's name, the Python key, the unit)
  std::vector<std::tuple<std::string, std::string, std::string>> parameters = {{coated ? "E1" : "E", modulus_key(details), "Pa"}};
  if (coated) parameters.emplace_back("t", "t", "m");
  if (jkr) parameters.emplace_back("w", "w", "J/m2");
  parameters.emplace_back("contact_point", "contact_point", "m");
  parameters.emplace_back("baseline", "baseline", "N");
  if (jkr || is_free("tilt")) parameters.emplace_back("tilt", "tilt", "N/m");
  py::dict out, estimates, errors, units;
  py::list names, free_list;
  // units: the optional parameters' first, then the modulus, contact point and baseline (the
  // order the module has always given)
  for (const auto& [name, key, unit] : parameters) {
    if (key == "t" || key == "w" || key == "tilt") units[py::str(key)] = unit;
  }
  for (const auto& [name, key, unit] : parameters) {
    double value = 0.0, error = 0.0;
    check(cc_afm_fit_estimate(fit, name.c_str(), &value, &error));
    names.append(key);
    estimates[py::str(key)] = value;
    errors[py::str(key)] = error;
    units[py::str(key)] = unit;
    if (is_free(key)) free_list.append(key);
  }
  out["names"] = names;
  out["estimates"] = estimates;
  out["errors"] = errors;
  out["units"] = units;
  out["free"] = free_list;
  out["reduced_modulus"] = summary.reduced_modulus;
  out["points"] = static_cast<std::size_t>(summary.points);
  out["points_in_contact"] = static_cast<std::size_t>(summary.points_in_contact);
  out["residual_norm"] = std::sqrt(summary.rss);
  out["residual_sigma"] = summary.residual_sigma;
  out["r_squared"] = summary.r_squared;
  out["weighted"] = false;
  out["chi2"] = weighted ? py::object(py::float_(summary.chi2)) : py::object(py::none());
  out["chi2_per_dof"] = weighted ? py::object(py::float_(summary.chi2_per_dof)) : py::object(py::none());
  out["max_indentation"] = summary.max_indentation;
  out["index"] = converted<long>(fit_array(fit, "index"));
  out["tip_position"] = to_array(fit_array(fit, "tip_position"));
  out["F"] = to_array(fit_array(fit, "force"));
  out["indentation"] = to_array(fit_array(fit, "indentation"));
  out["F_model"] = to_array(fit_array(fit, "model_force"));
  out["residual"] = to_array(fit_array(fit, "residual"));
  out["profile_evaluations"] = static_cast<std::size_t>(details.profile_evaluations);
  out["solver_calls"] = static_cast<std::size_t>(details.solver_calls);
  out["seconds"] = details.seconds;
  out["tip"] = details.tip;
  out["model"] = details.model;
  if (jkr) {
    out["spring_constant"] = summary.spring_constant;
    out["surface_force_range"] = details.surface_force_range;
    out["tabor_mu"] = summary.tabor_mu;
    out["maugis_lambda"] = summary.maugis_lambda;
    py::dict jump;
    jump["F"] = summary.jump_off_force;
    jump["indentation"] = summary.jump_off_indentation;
    out["jump_off"] = jump;
    py::list warnings;
    for (long w = 0; w < details.model_warnings; ++w) {
      const char* text = nullptr;
      check(cc_afm_fit_warning(fit, w, &text));
      warnings.append(text);
    }
    out["warnings"] = warnings;
    out["model_evaluations"] = static_cast<std::size_t>(details.model_evaluations);
  }
  return out;
}

// One fit of (z, F) arrays; the Python layer chooses the segment and the reference estimates.
py::dict fit_arrays(const py::object& tip_position, const py::object& force, const py::tuple& shape, double modulus,
                    double poisson, const std::vector<std::string>& free, double contact_point, double baseline,
                    double noise, const py::object& tip_min, const py::object& tip_max, const py::object& indentation_min,
                    const py::object& indentation_max, const py::object& max_force, double reference_contact,
                    double reference_baseline, const py::object& coating, const py::object& adhesion, double weight_cp) {
  const std::vector<double> z = to_vector(tip_position), f = to_vector(force);
  if (z.size() != f.size()) throw py::value_error("tip position and force differ in length");
  const RequestHandle request = request_of(shape, modulus, poisson, free, contact_point, baseline, coating, adhesion);
  set_number(request.get(), "noise_sigma", noise);
  set_number(request.get(), "weight_cp", weight_cp);
  set_bound(request.get(), "tip_min", tip_min);
  set_bound(request.get(), "tip_max", tip_max);
  set_bound(request.get(), "indentation_min", indentation_min);
  set_bound(request.get(), "indentation_max", indentation_max);
  set_bound(request.get(), "max_force", max_force);
  cc_afm_fit* made = nullptr;
  released([&] {
    return cc_afm_fit_arrays(static_cast<long>(z.size()), z.data(), f.data(), request.get(), reference_contact,
                             reference_baseline, &made);
  });
  const FitHandle fit(made);
  return result_dict(fit.get(), noise > 0.0);
}

// The depth profile of a fit as a dict of arrays: "depth", "max_indentation" [m], the modulus
// ("E" or "E1") and its "_error" [Pa], "flag" (names), "points_in_contact", and on a coating
// "E_apparent", "E_apparent_error" [Pa] and "over_thickness_fraction"; NaN where a depth has no
// estimate. Scalars: "modulus_name", "thickness_fraction", "warnings".
py::dict depth_profile_dict(const cc_afm_fit* fit) {
  cc_afm_depth_profile_info info{};
  check(cc_afm_fit_depth_profile(fit, &info));
  const auto profile = [&](const char* name) {
    return array_of([&](double* v, long cap, long* len) { return cc_afm_fit_depth_profile_array(fit, name, v, cap, len); });
  };
  const std::string modulus = info.modulus_name;
  py::list flags, warnings;
  for (long s = 0; s < info.steps; ++s) {
    const char* flag = nullptr;
    check(cc_afm_fit_depth_profile_flag(fit, s, &flag));
    flags.append(flag);
  }
  for (long w = 0; w < info.warning_count; ++w) {
    const char* text = nullptr;
    check(cc_afm_fit_depth_profile_warning(fit, w, &text));
    warnings.append(text);
  }
  py::dict d;
  d["depth"] = to_array(profile("depth"));
  d["max_indentation"] = to_array(profile("max_indentation"));
  d[py::str(modulus)] = to_array(profile("modulus"));
  d[py::str(modulus + "_error")] = to_array(profile("modulus_error"));
  d["points_in_contact"] = converted<long>(profile("points_in_contact"));
  d["flag"] = flags;
  d["modulus_name"] = modulus;
  if (info.coated) {
    d["E_apparent"] = to_array(profile("apparent_modulus"));
    d["E_apparent_error"] = to_array(profile("apparent_modulus_error"));
    d["over_thickness_fraction"] = converted<bool>(profile("over_thickness_fraction"));
    d["thickness_fraction"] = info.thickness_fraction;
  }
  d["warnings"] = warnings;
  return d;
}

// One curve given as arrays through the library's one-curve pipeline (cc_afm_fit_curve): the
// segment, the preprocessing steps, the baseline model, the range, the fit and the pull-off,
// as `afm fit` and each row of fit_map. noise > 0 replaces the baseline's sigma in chi2.
py::dict fit_curve(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                   const Segments& segments, double spring_constant, const std::string& name, const py::tuple& shape,
                   double modulus, double poisson, const std::vector<std::string>& free, double contact_point,
                   double baseline, const py::object& coating, const std::string& segment, const py::object& tip_min,
                   const py::object& tip_max, const py::object& indentation_min, const py::object& indentation_max,
                   const py::object& max_force, const py::object& adhesion, const std::string& baseline_model,
                   double noise, double weight_cp, bool depth_profile) {
  const CurveHandle curve = curve_of(force, height_piezo, height_measured, segments, spring_constant, name);
  const RequestHandle request = settings_of(shape, modulus, poisson, free, contact_point, baseline, coating, segment, tip_min,
                                            tip_max, indentation_min, indentation_max, max_force, adhesion, baseline_model,
                                            weight_cp);
  set_number(request.get(), "noise_sigma", noise);
  if (depth_profile) set_number(request.get(), "depth_profile", 1.0);
  cc_afm_fit* made = nullptr;
  SignalCheck signals;
  released(
      [&] {
        const ScopedHook hook(signals);
        return cc_afm_fit_curve(curve.get(), request.get(), &made);
      },
      &signals);
  const FitHandle fit(made);
  py::dict out = result_dict(fit.get(), true);
  long steps = 0, warning_count = 0;
  check(cc_afm_fit_step_count(fit.get(), &steps));
  py::list step_list;
  for (long s = 0; s < steps; ++s) {
    const char *step = nullptr, *parameters = nullptr;
    check(cc_afm_fit_step(fit.get(), s, &step, &parameters));
    step_list.append(py::make_tuple(step, parameters));
  }
  out["steps"] = step_list;
  cc_afm_fit_details details{};
  cc_afm_fit_summary summary{};
  check(cc_afm_fit_get_details(fit.get(), &details));
  check(cc_afm_fit_get_summary(fit.get(), &summary));
  out["baseline_model"] = details.baseline_model;
  out["reference_contact_point"] = summary.reference_contact;
  // The flag (fitted, or undetermined / no_detachment with the estimates kept), its reasons
  // and the model's warnings, and the curve rating (afm_curve_fit.hpp).
  const char* flag = nullptr;
  check(cc_afm_fit_flag(fit.get(), &flag));
  out["flag"] = flag;
  out["rating"] = summary.rating;
  check(cc_afm_fit_warning_count(fit.get(), &warning_count));
  py::list warnings;
  for (long k = 0; k < warning_count; ++k) {  // the flag's reasons first, then the model's
    const long w = (details.model_warnings + k) % warning_count;
    const char* text = nullptr;
    check(cc_afm_fit_warning(fit.get(), w, &text));
    warnings.append(text);
  }
  out["warnings"] = warnings;
  if (summary.has_pulloff) {
    py::dict pulloff;
    pulloff["F"] = summary.pulloff_force;
    pulloff["z"] = summary.pulloff_position;
    pulloff["baseline_offset"] = details.pulloff_baseline_offset;
    pulloff["baseline_slope"] = details.pulloff_baseline_slope;
    out["pulloff"] = pulloff;
  } else {
    out["pulloff"] = py::none();
  }
  if (depth_profile) out["depth_profile"] = depth_profile_dict(fit.get());
  return out;
}

// The measured pull-off of a retract given as arrays (cc_afm_measured_pulloff): a dict, or None.
py::object measured_pulloff(const py::object& tip_position, const py::object& force, double fraction) {
  const std::vector<double> z = to_vector(tip_position), f = to_vector(force);
  if (z.size() != f.size()) throw py::value_error("tip position and force differ in length");
  cc_afm_pulloff p{};
  check(cc_afm_measured_pulloff(static_cast<long>(z.size()), z.data(), f.data(), fraction, &p));
  if (!p.found) return py::none();
  py::dict out;
  out["F"] = p.force;
  out["z"] = p.tip_position;
  out["baseline_offset"] = p.baseline_offset;
  out["baseline_slope"] = p.baseline_slope;
  return out;
}

// ---- fit_map: one row per curve (cc_afm_fit_batch, cc_afm_fit_curves) ------------------------

// The rows as columns (the CLI table's): NaN (floats) and -1 (grid indices) where a curve has no
// value. Rows are added chunk by chunk (a run never holds its rows, only these ~100 bytes per
// curve); the file and reason cells of equal text are one Python string (a map's rows share
// their file), which also keeps them once in a pickle sent from a Dask worker.
class Columns {
 public:
  explicit Columns(const cc_afm_rows* rows) {
    long count = 0;
    check(cc_afm_rows_parameter_count(rows, &count));
    for (long p = 0; p < count; ++p) {
      const char *name = nullptr, *unit = nullptr;
      check(cc_afm_rows_parameter_name(rows, p, &name, &unit));
      parameters_.emplace_back(name, unit);
    }
    value_.resize(parameters_.size());
    error_.resize(parameters_.size());
  }
  void set_contact_column(bool on) { contact_column_ = on; }
  const std::vector<std::pair<std::string, std::string>>& parameters() const { return parameters_; }

  // Called with the GIL held (the Python strings).
  void add(const cc_afm_row& r) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const bool fitted = r.has_estimates != 0;
    if (!last_file_ || r.file != last_file_text_) {
      last_file_text_ = r.file;
      last_file_ = py::str(r.file);
    }
    file_.append(*last_file_);
    reason_.append(reason_name(r.flag, r.flag_name));
    curve_.push_back(r.curve);
    grid_x_.push_back(r.grid_x_or_none);
    grid_y_.push_back(r.grid_y_or_none);
    x_.push_back(r.position_x_or_nan);
    y_.push_back(r.position_y_or_nan);
    flag_.push_back(r.flag);
    for (std::size_t p = 0; p < parameters_.size(); ++p) {
      value_[p].push_back(fitted && r.estimates ? r.estimates[p] : nan);
      error_[p].push_back(fitted && r.errors ? r.errors[p] : nan);
    }
    contact_.push_back(fitted ? r.contact_point : nan);
    chi2_.push_back(fitted ? r.chi2 : nan);
    chi2_per_dof_.push_back(fitted ? r.chi2_per_dof : nan);
    sigma_.push_back(fitted ? r.residual_sigma : nan);
    pulloff_.push_back(fitted && r.has_pulloff ? r.pulloff_force : nan);
    pulloff_position_.push_back(fitted && r.has_pulloff ? r.pulloff_position : nan);
    jump_force_.push_back(fitted && r.has_model_jump_off ? r.model_jump_off_force : nan);
    jump_indentation_.push_back(fitted && r.has_model_jump_off ? r.model_jump_off_indentation : nan);
    points_.push_back(fitted ? r.points : 0);
    rating_.push_back(r.rating);
    tabor_mu_.push_back(r.has_adhesion ? r.tabor_mu : nan);
    maugis_lambda_.push_back(r.has_adhesion ? r.maugis_lambda : nan);
    warnings_.append(py::str(r.warnings));
  }

  py::dict dict() const {
    py::dict out;
    py::list names;
    const auto put = [&](const std::string& name, py::object column) {
      out[py::str(name)] = column;
      names.append(name);
    };
    put("file", file_);
    put("curve", to_array(curve_));
    put("grid_x", to_array(grid_x_));
    put("grid_y", to_array(grid_y_));
    put("x", to_array(x_));
    put("y", to_array(y_));
    put("flag", to_array(flag_));
    put("reason", reason_);
    for (std::size_t p = 0; p < parameters_.size(); ++p) {
      put(parameters_[p].first, to_array(value_[p]));
      put(parameters_[p].first + "_error", to_array(error_[p]));
    }
    if (contact_column_) put("contact_point", to_array(contact_));
    put("chi2", to_array(chi2_));
    put("chi2_per_dof", to_array(chi2_per_dof_));
    put("residual_sigma", to_array(sigma_));
    put("pulloff", to_array(pulloff_));
    put("pulloff_position", to_array(pulloff_position_));
    put("model_jump_off_force", to_array(jump_force_));
    put("model_jump_off_indentation", to_array(jump_indentation_));
    put("points", to_array(points_));
    put("rating", to_array(rating_));
    put("tabor_mu", to_array(tabor_mu_));
    put("maugis_lambda", to_array(maugis_lambda_));
    put("warnings", warnings_);
    out["names"] = names;
    return out;
  }

 private:
  py::str reason_name(int flag, const char* name) {
    auto& cached = reasons_[flag];
    if (!cached) cached = py::str(name);
    return *cached;
  }

  std::vector<std::pair<std::string, std::string>> parameters_;  // (name, unit)
  bool contact_column_ = false;
  py::list file_, reason_, warnings_;
  std::optional<py::str> last_file_;
  std::string last_file_text_;
  std::map<int, std::optional<py::str>> reasons_;
  std::vector<long> curve_, grid_x_, grid_y_, points_;
  std::vector<int> flag_;
  std::vector<double> x_, y_, chi2_, chi2_per_dof_, sigma_, pulloff_, pulloff_position_, contact_;
  std::vector<double> rating_, tabor_mu_, maugis_lambda_, jump_force_, jump_indentation_;
  std::vector<std::vector<double>> value_, error_;
};

// The files of `paths` (a folder: its AFM files by extension, sorted), in order.
std::vector<std::string> expand_paths(const std::vector<std::string>& paths) {
  if (paths.empty()) return {};
  std::vector<const char*> items;
  for (const auto& p : paths) items.push_back(p.c_str());
  cc_afm_file_list* made = nullptr;
  check(cc_afm_expand_paths(items.data(), static_cast<long>(items.size()), &made));
  const FileListHandle list(made);
  long count = 0;
  check(cc_afm_file_list_count(list.get(), &count));
  std::vector<std::string> files;
  for (long i = 0; i < count; ++i) {
    cc_afm_file_survey s{};
    check(cc_afm_file_list_get(list.get(), i, &s));
    files.emplace_back(s.path);
  }
  return files;
}

cc_afm_calibration calibration_of(const py::object& spring_constant, const py::object& sensitivity) {
  return {spring_constant.is_none() ? 0.0 : spring_constant.cast<double>(), sensitivity.is_none() ? 0.0 : sensitivity.cast<double>(), 0};
}

// (curves, why unreadable or "", flag of its row) of each file (cc_afm_survey_files): with
// `tolerate` a file that cannot be read is one flagged row of the run instead of a ValueError.
std::vector<std::tuple<std::size_t, std::string, int>> survey_files(const std::vector<std::string>& files,
                                                                    const py::object& spring_constant,
                                                                    const py::object& sensitivity, bool tolerate) {
  std::vector<std::tuple<std::size_t, std::string, int>> out;
  if (files.empty()) return out;
  std::vector<const char*> items;
  for (const auto& f : files) items.push_back(f.c_str());
  const cc_afm_calibration calibration = calibration_of(spring_constant, sensitivity);
  cc_afm_file_list* made = nullptr;
  released([&] { return cc_afm_survey_files(items.data(), static_cast<long>(items.size()), &calibration, tolerate, &made); });
  const FileListHandle list(made);
  for (std::size_t i = 0; i < files.size(); ++i) {
    cc_afm_file_survey s{};
    check(cc_afm_file_list_get(list.get(), static_cast<long>(i), &s));
    out.emplace_back(static_cast<std::size_t>(s.curves), s.unreadable, s.flag);
  }
  return out;
}

// One control-plot page of fit_map(curve_plots=): the row's place, flag, rating and estimates,
// and its trace ("z", "force", "model", "segment", "fitted", "contact_point"; absent for a
// curve without data). Called with the GIL held.
py::dict trace_dict(const cc_afm_rows* rows, long index, const cc_afm_row& row,
                    const std::vector<std::pair<std::string, std::string>>& parameters) {
  py::dict d;
  d["file"] = row.file;
  d["curve"] = static_cast<std::size_t>(row.curve);
  d["grid"] = row.has_grid ? py::object(py::make_tuple(row.grid_x, row.grid_y)) : py::object(py::none());
  d["flag"] = row.flag_name;
  d["rating"] = row.rating;
  d["message"] = row.message;
  py::list estimates;
  if (row.has_estimates) {
    for (std::size_t p = 0; p < parameters.size() && row.estimates; ++p) {
      estimates.append(py::make_tuple(parameters[p].first, row.estimates[p], row.errors[p], parameters[p].second));
    }
    d["chi2_per_dof"] = row.chi2_per_dof;
  }
  d["estimates"] = estimates;
  if (row.has_trace) {
    const auto trace = [&](const char* name) {
      return array_of([&](double* v, long cap, long* len) { return cc_afm_rows_trace(rows, index, name, v, cap, len); });
    };
    d["z"] = to_array(trace("z"));
    d["force"] = to_array(trace("force"));
    d["model"] = to_array(trace("model"));
    d["segment"] = converted<int>(trace("segment"));
    d["fitted"] = converted<int>(trace("fitted"));
    d["contact_point"] = row.trace_contact_point;
  }
  return d;
}

// The sink of a run: each chunk's rows into the columns (and the trace pages), with the GIL.
struct RowsSink {
  std::optional<Columns> columns;
  py::object trace_sink;
  bool contact_column = false;
  SignalCheck signals;  // a Python exception of a page (or Ctrl-C) stops the run

  static int call(void* user, const cc_afm_rows* chunk) {
    auto* self = static_cast<RowsSink*>(user);
    py::gil_scoped_acquire gil;
    try {
      self->add(chunk);
    } catch (...) {
      self->signals.error = std::current_exception();
      return 1;
    }
    return 0;
  }
  void add(const cc_afm_rows* chunk) {
    if (!columns) {
      columns.emplace(chunk);
      columns->set_contact_column(contact_column);
    }
    long count = 0;
    check(cc_afm_rows_count(chunk, &count));
    for (long i = 0; i < count; ++i) {
      cc_afm_row row{};
      check(cc_afm_rows_get(chunk, i, &row));
      columns->add(row);
      if (!trace_sink.is_none()) trace_sink(trace_dict(chunk, i, row, columns->parameters()));  // a page each, as they come
    }
  }
  // The columns (those of the returned handle when no row came).
  py::dict dict(const cc_afm_rows* rows) {
    if (!columns) {
      columns.emplace(rows);
      columns->set_contact_column(contact_column);
    }
    return columns->dict();
  }
};

// Curves [first, first + count) of the run over `files`, fitted with `jobs` threads (0: cores).
py::dict fit_map_files(const std::vector<std::string>& files, const py::tuple& shape, double modulus, double poisson,
                       const std::vector<std::string>& free, double contact_point, double baseline, const py::object& coating,
                       const std::string& segment, const py::object& tip_min, const py::object& tip_max,
                       const py::object& indentation_min, const py::object& indentation_max, const py::object& max_force,
                       const py::object& spring_constant, const py::object& sensitivity, unsigned jobs, std::size_t first,
                       const py::object& count, const py::object& survey, bool tolerate,
                       const py::object& adhesion, const std::string& baseline_model, double weight_cp,
                       const py::object& trace_sink) {
  const RequestHandle request = settings_of(shape, modulus, poisson, free, contact_point, baseline, coating, segment, tip_min,
                                            tip_max, indentation_min, indentation_max, max_force, adhesion, baseline_model,
                                            weight_cp);
  const cc_afm_calibration calibration = calibration_of(spring_constant, sensitivity);
  std::vector<std::string> why;  // the survey's texts, alive through the run
  std::vector<cc_afm_file_survey> entries;
  if (!survey.is_none()) {
    const auto given = survey.cast<std::vector<std::tuple<std::size_t, std::string, int>>>();
    for (const auto& entry : given) why.push_back(std::get<1>(entry));
    for (std::size_t i = 0; i < given.size(); ++i) {
      entries.push_back({"", static_cast<long>(std::get<0>(given[i])), why[i].c_str(), std::get<2>(given[i])});
    }
  }
  RowsSink sink;
  sink.trace_sink = trace_sink;
  sink.contact_column = std::find(free.begin(), free.end(), "contact_point") == free.end();
  cc_afm_batch_options options{};
  options.jobs = jobs;
  options.unreadable_file_rows = tolerate;
  options.skip = static_cast<long>(first);
  options.count = count.is_none() ? 0 : count.cast<long>();
  options.survey_count = static_cast<long>(entries.size());
  options.survey = entries.empty() ? nullptr : entries.data();
  options.keep_traces = !trace_sink.is_none();
  options.sink = &RowsSink::call;
  options.sink_user = &sink;
  std::vector<const char*> items;
  for (const auto& f : files) items.push_back(f.c_str());
  cc_afm_rows* made = nullptr;
  SignalCheck& signals = sink.signals;
  released(
      [&] {
        const ScopedHook hook(signals);
        // No file (an empty folder): no row, the columns of the request.
        if (items.empty()) return cc_afm_fit_curves(nullptr, 0, request.get(), &options, &made);
        return cc_afm_fit_batch(items.data(), static_cast<long>(items.size()), &calibration, request.get(), &options, &made);
      },
      &signals);
  const RowsHandle rows(made);
  return sink.dict(rows.get());
}

// Curves given as arrays: (force, height_piezo, height_measured, segments, spring_constant,
// name, curve_index, grid_x, grid_y, x, y), each fitted as a curve of a file would be.
py::dict fit_map_curves(const py::list& curves, const py::tuple& shape, double modulus, double poisson,
                        const std::vector<std::string>& free, double contact_point, double baseline,
                        const py::object& coating, const std::string& segment, const py::object& tip_min,
                        const py::object& tip_max, const py::object& indentation_min, const py::object& indentation_max,
                        const py::object& max_force, const py::object& adhesion, const std::string& baseline_model,
                        double weight_cp, const py::object& trace_sink) {
  const RequestHandle request = settings_of(shape, modulus, poisson, free, contact_point, baseline, coating, segment, tip_min,
                                            tip_max, indentation_min, indentation_max, max_force, adhesion, baseline_model,
                                            weight_cp);
  std::vector<CurveHandle> handles;
  for (const py::handle item : curves) {
    const py::tuple c = py::reinterpret_borrow<py::tuple>(item);
    handles.push_back(curve_of(c[0], c[1], c[2], c[3].cast<Segments>(), c[4].cast<double>(), c[5].cast<std::string>()));
    cc_afm_grid grid{};
    grid.has_index = !c[7].is_none() && !c[8].is_none();
    if (grid.has_index) grid.index_x = c[7].cast<long>(), grid.index_y = c[8].cast<long>();
    grid.has_position = !c[9].is_none() && !c[10].is_none();
    if (grid.has_position) grid.position_x = c[9].cast<double>(), grid.position_y = c[10].cast<double>();
    check(cc_afm_curve_set_place(handles.back().get(), c[6].cast<long>(), &grid));
  }
  std::vector<const cc_afm_curve*> pointers;
  for (const auto& h : handles) pointers.push_back(h.get());
  RowsSink sink;
  sink.trace_sink = trace_sink;
  sink.contact_column = std::find(free.begin(), free.end(), "contact_point") == free.end();
  cc_afm_batch_options options{};
  options.keep_traces = !trace_sink.is_none();
  options.sink = &RowsSink::call;
  options.sink_user = &sink;
  cc_afm_rows* made = nullptr;
  SignalCheck& signals = sink.signals;
  released(
      [&] {
        const ScopedHook hook(signals);
        return cc_afm_fit_curves(pointers.data(), static_cast<long>(pointers.size()), request.get(), &options, &made);
      },
      &signals);
  const RowsHandle rows(made);
  return sink.dict(rows.get());
}

}  // namespace

void register_afm(py::module_& root) {
  py::module_ m = root.def_submodule("_afm", "Compiled AFM readers and fits of coatcontact; use coatcontact.afm.");
  m.def("models", &model_list);
  m.def("read", &read_curves, py::arg("path"), py::arg("spring_constant") = py::none(), py::arg("sensitivity") = py::none());
  m.def("preprocess", &preprocess_arrays, py::arg("force"), py::arg("height_piezo"), py::arg("height_measured"),
        py::arg("segments"), py::arg("spring_constant"), py::arg("contact_point"), py::arg("baseline_fraction"),
        py::arg("deviation_sigmas"), py::arg("name"));
  m.def("fit", &fit_arrays, py::arg("tip_position"), py::arg("force"), py::arg("shape"), py::arg("modulus"),
        py::arg("poisson"), py::arg("free"), py::arg("contact_point"), py::arg("baseline"), py::arg("noise"),
        py::arg("tip_min"), py::arg("tip_max"), py::arg("indentation_min"), py::arg("indentation_max"),
        py::arg("max_force"), py::arg("reference_contact"), py::arg("reference_baseline"), py::arg("coating") = py::none(), py::arg("adhesion") = py::none(),
        py::arg("weight_cp") = 0.0);
  m.def("fit_curve", &fit_curve, py::arg("force"), py::arg("height_piezo"), py::arg("height_measured"), py::arg("segments"),
        py::arg("spring_constant"), py::arg("name"), py::arg("shape"), py::arg("modulus"), py::arg("poisson"), py::arg("free"),
        py::arg("contact_point"), py::arg("baseline"), py::arg("coating"), py::arg("segment"), py::arg("tip_min"),
        py::arg("tip_max"), py::arg("indentation_min"), py::arg("indentation_max"), py::arg("max_force"),
        py::arg("adhesion"), py::arg("baseline_model"), py::arg("noise"), py::arg("weight_cp") = 0.0,
        py::arg("depth_profile") = false);
  m.def("measured_pulloff", &measured_pulloff, py::arg("tip_position"), py::arg("force"), py::arg("fraction") = 0.5);
  m.def("expand_paths", &expand_paths, py::arg("paths"));
  m.def("survey_files", &survey_files, py::arg("files"), py::arg("spring_constant"), py::arg("sensitivity"),
        py::arg("tolerate"));
  m.def("fit_map_files", &fit_map_files, py::arg("files"), py::arg("shape"), py::arg("modulus"), py::arg("poisson"),
        py::arg("free"), py::arg("contact_point"), py::arg("baseline"), py::arg("coating"), py::arg("segment"),
        py::arg("tip_min"), py::arg("tip_max"), py::arg("indentation_min"), py::arg("indentation_max"),
        py::arg("max_force"), py::arg("spring_constant"), py::arg("sensitivity"), py::arg("jobs"), py::arg("first"),
        py::arg("count"), py::arg("survey") = py::none(), py::arg("tolerate") = false,
        py::arg("adhesion") = py::none(), py::arg("baseline_model") = "", py::arg("weight_cp") = 0.0,
        py::arg("trace_sink") = py::none());
  m.def("fit_map_curves", &fit_map_curves, py::arg("curves"), py::arg("shape"), py::arg("modulus"), py::arg("poisson"),
        py::arg("free"), py::arg("contact_point"), py::arg("baseline"), py::arg("coating"), py::arg("segment"),
        py::arg("tip_min"), py::arg("tip_max"), py::arg("indentation_min"), py::arg("indentation_max"),
        py::arg("max_force"), py::arg("adhesion") = py::none(), py::arg("baseline_model") = "", py::arg("weight_cp") = 0.0,
        py::arg("trace_sink") = py::none());
}
