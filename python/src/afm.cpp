// Compiled part of coatcontact.afm (module coatcontact._afm): the library's AFM readers, each
// curve returned as a dict of NumPy arrays under the names of the Python AFM tools plus its
// metadata and segments. InputError (unreadable file, missing calibration) -> ValueError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <sys/stat.h>

#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_depth_profile.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/progress.hpp"
#include "coatcontact/indenter_shape.hpp"

namespace py = pybind11;
namespace afm = coatcontact::afm;

namespace {

template <class T>
py::array_t<T> to_array(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// Ctrl-C during a long library call (issue 40): called between units of work (curves, a
// chunk's curves, a sweep's radii) on the calling thread, it takes the GIL and runs Python's
// signal handlers; a KeyboardInterrupt stops the call (the library's Interrupted) and is raised
// by rethrow() once the call has returned.
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
  void rethrow() const {
    if (error) std::rethrow_exception(error);
  }
};

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
  std::vector<std::string> unreadable;  // curves of a map that cannot be read, with why
  std::string error;
  {
    SignalCheck signals;
    py::gil_scoped_release release;
    try {
      // Curve by curve, so that Ctrl-C stops the reading of a large map between curves, and a
      // corrupt curve of a map costs that curve only (as in `afm show`).
      const afm::CurveSource source(path, calibration);
      for (std::size_t i = 0; i < source.size(); ++i) {
        if (!signals()) break;
        try {
          curves.push_back(source.read(i));
        } catch (const coatcontact::InputError& e) {
          if (source.size() == 1) throw;
          unreadable.push_back("curve " + std::to_string(i) + ": " + e.what());
        }
      }
      if (curves.empty() && !unreadable.empty()) error = "no curve of the file can be read; " + unreadable.front();
    } catch (const coatcontact::InputError& e) {
      error = e.what();
    }
    py::gil_scoped_acquire gil;
    signals.rethrow();
  }
  if (error.empty()) {
    for (const auto& why : unreadable) {
      const std::string text = path + ": " + why + " (left out; the others keep their \"curve index\")";
      if (PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 2) != 0) throw py::error_already_set();
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

// A curve given as arrays; segments as (kind, begin, end) triples covering the points in order.
afm::ForceCurve curve_of(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                         const std::vector<std::tuple<std::string, std::size_t, std::size_t>>& segments,
                         double spring_constant, const std::string& name) {
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
  return curve;
}

// Preprocessing steps of one curve given as arrays; segments as (kind, begin, end) triples.
py::dict preprocess_arrays(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                           const std::vector<std::tuple<std::string, std::size_t, std::size_t>>& segments,
                           double spring_constant, const std::string& contact_point, double baseline_fraction,
                           double deviation_sigmas, const std::string& name) {
  afm::ForceCurve curve = curve_of(force, height_piezo, height_measured, segments, spring_constant, name);
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

// The tip of coatcontact.afm.fit: ("sphere", R), ("cone", beta), ("pyramid", theta), ("pyramid3", theta),
// ("sneddon-sphere", R),
// ("punch", A), ("power", n, R), ("blunted-cone", R, beta), ("profile", r, z); angles in rad.
coatcontact::fit::AfmTip tip_of(const py::tuple& spec) {
  namespace cc = coatcontact;
  if (spec.size() < 2) throw py::value_error("shape: expected a tuple (kind, parameters...)");
  const std::string kind = py::str(spec[0]);
  const auto number = [&](std::size_t i) { return spec[i].cast<double>(); };
  const auto count = [&](std::size_t n) {
    if (spec.size() != n + 1) throw py::value_error("shape: '" + kind + "' takes " + std::to_string(n) + " parameter(s)");
  };
  if (kind == "sphere") return count(1), cc::fit::afm_paraboloid(number(1));
  if (kind == "cone") return count(1), cc::fit::afm_cone(number(1));
  if (kind == "pyramid") return count(1), cc::fit::afm_pyramid(number(1));
  if (kind == "pyramid3") return count(1), cc::fit::afm_pyramid3(number(1));
  if (kind == "sneddon-sphere") return count(1), cc::fit::afm_sneddon_sphere(number(1));
  if (kind == "punch") return count(1), cc::fit::afm_shape(cc::make_flat_punch(number(1)));
  if (kind == "power") return count(2), cc::fit::afm_shape(cc::make_power_law(number(1), number(2)));
  if (kind == "blunted-cone") return count(2), cc::fit::afm_shape(cc::make_blunted_cone(number(1), number(2)));
  if (kind == "profile") {
    count(2);
    return cc::fit::afm_shape(cc::make_measured_profile(to_vector(spec[1]), to_vector(spec[2]), "shape profile"));
  }
  throw py::value_error("shape: '" + kind + "' is not a tip; allowed: sphere, cone, pyramid, pyramid3, sneddon-sphere, punch, power, blunted-cone, profile");
}

// The registry's models for the Python layer: name, aliases, whether it needs the spring
// constant, its default segment, and its parameters (name, unit, free by default) per sample.
py::list model_list() {
  namespace fit = coatcontact::fit;
  py::list models;
  for (const fit::AfmModelInfo* m : fit::afm_models()) {
    py::dict d;
    d["name"] = m->name;
    d["aliases"] = m->aliases;
    d["title"] = m->title;
    d["spring"] = m->needs_spring;
    d["segment"] = coatcontact::afm::segment_kind_name(m->segment);
    for (const bool coated : {false, true}) {
      py::list parameters;
      for (const fit::AfmParameterInfo& p : m->parameters) {
        if (p.coating_only && !coated) continue;
        py::dict q;
        q["name"] = fit::afm_parameter_name(p, coated);
        q["unit"] = p.unit;
        q["free"] = p.free_by_default;
        parameters.append(q);
      }
      d[coated ? "coating_parameters" : "parameters"] = parameters;
      d[coated ? "coating_default_free" : "default_free"] = fit::afm_free_default(*m, coated);
    }
    models.append(d);
  }
  return models;
}

std::optional<double> optional_number(const py::object& v) {
  if (v.is_none()) return std::nullopt;
  return v.cast<double>();
}

// The problem of coatcontact.afm.fit and fit_map: tip, sample (coating: (E1, nu1, substrate
// (E0, nu0) or None for rigid, t)), free parameters and fixed values. InputError when not allowed.
coatcontact::fit::AfmFitProblem problem_of(const py::tuple& shape, double modulus, double poisson,
                                           const std::vector<std::string>& free, double contact_point, double baseline,
                                           const py::object& coating, const py::object& adhesion) {
  namespace fit = coatcontact::fit;
  fit::AfmFitProblem problem;
  problem.tip = tip_of(shape);
  problem.modulus = modulus;
  problem.poisson = poisson;
  // coating: (E1, nu1, substrate (E0, nu0) or None for rigid, t)
  const bool coated = !coating.is_none();
  if (coated) {
    const py::tuple c = coating.cast<py::tuple>();
    fit::AfmCoating layer;
    layer.film.youngs_modulus = c[0].cast<double>();
    layer.film.poisson_ratio = c[1].cast<double>();
    if (c[2].is_none()) {
      layer.substrate.rigid = true;
    } else {
      const py::tuple sub = c[2].cast<py::tuple>();
      layer.substrate.material.youngs_modulus = sub[0].cast<double>();
      layer.substrate.material.poisson_ratio = sub[1].cast<double>();
    }
    layer.thickness = c[3].cast<double>();
    if (c.size() > 5) {  // a stack: ((h, E, nu, slip), ...) and the free layer (coatcontact.afm._stack_coating)
      std::vector<coatcontact::Layer> layers;
      for (const py::handle& row : c[4].cast<py::tuple>()) {
        const py::tuple l = row.cast<py::tuple>();
        layers.push_back({l[0].cast<double>(), {l[1].cast<double>(), l[2].cast<double>()}, l[3].cast<bool>()});
      }
      layer = fit::afm_coating(coatcontact::Stack(layers, layer.substrate), c[5].cast<std::size_t>());
    }
    problem.coating = layer;
    problem.poisson = layer.film.poisson_ratio;
  }
  // adhesion: (w, k, z0, tilt, model) of the adhesive model, "jkr" or "md" (k 0: each curve's),
  // or None (Hertz/Sneddon)
  const bool jkr = !adhesion.is_none();
  if (jkr) {
    const py::tuple a = adhesion.cast<py::tuple>();
    problem.model = fit::afm_model_by_name(a.size() > 4 ? a[4].cast<std::string>() : "jkr").model();
    problem.work = a[0].cast<double>();
    problem.spring_constant = a[1].cast<double>();
    problem.surface_force_range = a[2].cast<double>();
    problem.tilt = a[3].cast<double>();
  }
  const fit::AfmModelInfo& info = problem.model.info();
  const std::string allowed = fit::afm_free_allowed(info, coated);
  problem.free = {false, false, false, false};
  for (const auto& name : free) {
    const fit::AfmParameterInfo* parameter = fit::afm_parameter(info, name, coated);
    if (!parameter) throw coatcontact::InputError("free: '" + name + "' is not a parameter of this fit; allowed: " + allowed);
    problem.free.*parameter->free = true;
  }
  if (fit::afm_free_count(info, problem.free) == 0) throw coatcontact::InputError("free: names no parameter; allowed: " + allowed);
  problem.contact_point = contact_point;
  problem.baseline = baseline;
  return problem;
}

// The result dict of one fit (fit_arrays, fit_curve): estimates, errors and units by name,
// statistics, and the fitted points (index: into the caller's arrays).
py::dict result_dict(const coatcontact::fit::AfmFitProblem& problem, const coatcontact::fit::AfmFitResult& r,
                     const std::vector<double>& z, const std::vector<double>& f, const std::vector<long>& index,
                     bool weighted) {
  namespace fit = coatcontact::fit;
  const bool coated = problem.coating.has_value();
  const bool jkr = problem.model.info().needs_spring;  // the adhesive models
  const std::string modulus_name = coated ? "E1" : "E";
  py::dict out;
    std::vector<std::string> names = {modulus_name, "contact_point", "baseline"};
    std::vector<double> values = {r.modulus, r.contact_point, r.baseline};
    std::vector<double> errors = {r.modulus_error, r.contact_point_error, r.baseline_error};
    std::vector<bool> is_free = {problem.free.modulus, problem.free.contact_point, problem.free.baseline};
    py::dict estimates, error_dict, units;
    if (coated) {
      names.insert(names.begin() + 1, "t");
      values.insert(values.begin() + 1, r.thickness);
      errors.insert(errors.begin() + 1, r.thickness_error);
      is_free.insert(is_free.begin() + 1, problem.free.thickness);
      units["t"] = "m";
    }
    if (jkr) {
      names.insert(names.begin() + (coated ? 2 : 1), "w");
      values.insert(values.begin() + (coated ? 2 : 1), r.work);
      errors.insert(errors.begin() + (coated ? 2 : 1), r.work_error);
      is_free.insert(is_free.begin() + (coated ? 2 : 1), problem.free.work);
      units["w"] = "J/m2";
    }
    if (jkr || problem.free.tilt) {
      names.push_back("tilt");
      values.push_back(r.tilt);
      errors.push_back(r.tilt_error);
      is_free.push_back(problem.free.tilt);
      units["tilt"] = "N/m";
    }
    py::list free_names;
    for (std::size_t k = 0; k < names.size(); ++k) {
      estimates[py::str(names[k])] = values[k];
      error_dict[py::str(names[k])] = errors[k];
      if (is_free[k]) free_names.append(names[k]);
    }
    units[py::str(modulus_name)] = "Pa";
    units["contact_point"] = "m";
    units["baseline"] = "N";
    out["names"] = names;
    out["estimates"] = estimates;
    out["errors"] = error_dict;
    out["units"] = units;
    out["free"] = free_names;
    out["reduced_modulus"] = r.reduced_modulus;
    out["points"] = r.points;
    out["points_in_contact"] = r.points_in_contact;
    out["residual_norm"] = std::sqrt(r.rss);
    out["residual_sigma"] = r.residual_sigma;
    out["r_squared"] = r.r_squared;
    out["weighted"] = false;
    if (weighted) {
      out["chi2"] = r.chi2;
      out["chi2_per_dof"] = r.chi2_per_dof;
    } else {
      out["chi2"] = py::none();
      out["chi2_per_dof"] = py::none();
    }
    out["max_indentation"] = r.max_indentation;
    out["index"] = to_array(index);
    out["tip_position"] = to_array(z);
    out["F"] = to_array(f);
    out["indentation"] = to_array(r.indentation);
    out["F_model"] = to_array(r.model_force);
    out["residual"] = to_array(r.residual);
    out["profile_evaluations"] = r.profile_evaluations;
    out["solver_calls"] = r.solver_calls;
    out["seconds"] = r.seconds;
    out["tip"] = problem.tip.description;
    if (jkr) {
      out["model"] = problem.model.name();
      out["spring_constant"] = problem.spring_constant;
      out["surface_force_range"] = problem.surface_force_range;
      out["tabor_mu"] = r.tabor_mu;
      out["maugis_lambda"] = r.maugis_lambda;
      py::dict jump;
      jump["F"] = r.jump_off_force;
      jump["indentation"] = r.jump_off_indentation;
      out["jump_off"] = jump;
      out["warnings"] = r.warnings;
      out["model_evaluations"] = r.model_evaluations;
    } else {
      out["model"] = problem.model.name();
    }
  return out;
}

// One fit of (z, F) arrays; the Python layer chooses the segment and the reference estimates.
py::dict fit_arrays(const py::object& tip_position, const py::object& force, const py::tuple& shape, double modulus,
                    double poisson, const std::vector<std::string>& free, double contact_point, double baseline,
                    double noise, const py::object& tip_min, const py::object& tip_max, const py::object& indentation_min,
                    const py::object& indentation_max, const py::object& max_force, double reference_contact,
                    double reference_baseline, const py::object& coating, const py::object& adhesion, double weight_cp) {
  namespace fit = coatcontact::fit;
  const std::vector<double> z_all = to_vector(tip_position), f_all = to_vector(force);
  if (z_all.size() != f_all.size()) throw py::value_error("tip position and force differ in length");
  fit::AfmFitProblem problem;
  py::dict out;
  try {
    problem = problem_of(shape, modulus, poisson, free, contact_point, baseline, coating, adhesion);
    problem.noise_sigma = noise;
    problem.weight_cp = weight_cp;
    fit::AfmRange range;
    range.tip_min = optional_number(tip_min);
    range.tip_max = optional_number(tip_max);
    range.indentation_min = optional_number(indentation_min);
    range.indentation_max = optional_number(indentation_max);
    range.max_force = optional_number(max_force);
    const std::vector<std::size_t> kept = fit::afm_select(z_all, f_all, range, reference_contact, reference_baseline);
    std::vector<double> z, f;
    for (std::size_t i : kept) {
      z.push_back(z_all[i]);
      f.push_back(f_all[i]);
    }
    fit::AfmFitResult r;
    {
      py::gil_scoped_release release;
      r = fit::afm_fit(z, f, problem);
    }
    out = result_dict(problem, r, z, f, std::vector<long>(kept.begin(), kept.end()), noise > 0.0);
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  } catch (const coatcontact::NumericalError& e) {
    throw std::runtime_error(std::string("numerical failure: ") + e.what());
  }
  return out;
}


// ---- fit_map: one row per curve (coatcontact/afm_batch.hpp) --------------------------------

afm::Calibration calibration_of(const py::object& spring_constant, const py::object& sensitivity) {
  afm::Calibration calibration;
  if (!spring_constant.is_none()) calibration.spring_constant = spring_constant.cast<double>();
  if (!sensitivity.is_none()) calibration.sensitivity = sensitivity.cast<double>();
  return calibration;
}

// baseline_model= of fit and fit_map: "tilt" (the default), "offset", or "" for the default.
coatcontact::fit::AfmBaselineModel baseline_model_of(const std::string& name, const coatcontact::fit::AfmFitProblem& problem) {
  namespace fit = coatcontact::fit;
  if (name.empty()) return fit::kAfmDefaultBaseline;
  if (name == "offset") return fit::AfmBaselineModel::kOffset;
  if (name != "tilt") throw coatcontact::InputError("baseline_model: '" + name + "' is not allowed; expected 'tilt' or 'offset'");
  if (problem.free.tilt) throw coatcontact::InputError("baseline_model: 'tilt' with \"tilt\" in free would count the slope twice; drop one");
  return fit::AfmBaselineModel::kTilt;
}

coatcontact::fit::AfmBatchSettings settings_of(const py::tuple& shape, double modulus, double poisson,
                                               const std::vector<std::string>& free, double contact_point,
                                               double baseline, const py::object& coating, const std::string& segment,
                                               const py::object& tip_min, const py::object& tip_max,
                                               const py::object& indentation_min, const py::object& indentation_max,
                                               const py::object& max_force, const py::object& adhesion) {
  coatcontact::fit::AfmBatchSettings settings;
  settings.problem = problem_of(shape, modulus, poisson, free, contact_point, baseline, coating, adhesion);
  if (segment == "approach") settings.segment = afm::SegmentKind::kApproach;
  else if (segment == "retract") settings.segment = afm::SegmentKind::kRetract;
  else throw coatcontact::InputError("segment: '" + segment + "' is not allowed; expected 'approach' or 'retract'");
  settings.range.tip_min = optional_number(tip_min);
  settings.range.tip_max = optional_number(tip_max);
  settings.range.indentation_min = optional_number(indentation_min);
  settings.range.indentation_max = optional_number(indentation_max);
  settings.range.max_force = optional_number(max_force);
  return settings;
}

// The rows as columns (the CLI table's): NaN (floats) and -1 (grid indices) where a curve has no
// value. Rows are added chunk by chunk (a run never holds its AfmCurveRow's, only these ~100
// bytes per curve); the file and reason cells of equal text are one Python string (a map's
// rows share their file), which also keeps them once in a pickle sent from a Dask worker.
class Columns {
 public:
  explicit Columns(const coatcontact::fit::AfmBatchSettings& settings)
      : parameters_(coatcontact::fit::afm_batch_parameters(settings.problem)),
        contact_column_(!settings.problem.free.contact_point),
        value_(parameters_.size()),
        error_(parameters_.size()) {}

  // Called with the GIL held (the Python strings).
  void add(const std::vector<coatcontact::fit::AfmCurveRow>& rows) {
    namespace fit = coatcontact::fit;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const fit::AfmCurveRow& r : rows) {
      const bool fitted = fit::afm_flag_keeps_estimates(r.flag);
      if (!last_file_ || r.source_file != last_file_text_) {
        last_file_text_ = r.source_file;
        last_file_ = py::str(r.source_file);
      }
      file_.append(*last_file_);
      reason_.append(reason_name(r.flag));
      curve_.push_back(static_cast<long>(r.curve_index));
      grid_x_.push_back(r.grid_x.value_or(-1));
      grid_y_.push_back(r.grid_y.value_or(-1));
      x_.push_back(r.position_x.value_or(nan));
      y_.push_back(r.position_y.value_or(nan));
      flag_.push_back(static_cast<int>(r.flag));
      for (std::size_t p = 0; p < parameters_.size(); ++p) {
        value_[p].push_back(fitted ? r.estimates[p] : nan);
        error_[p].push_back(fitted ? r.errors[p] : nan);
      }
      contact_.push_back(fitted ? r.contact_point : nan);
      chi2_.push_back(fitted ? r.chi2 : nan);
      chi2_per_dof_.push_back(fitted ? r.chi2_per_dof : nan);
      sigma_.push_back(fitted ? r.residual_sigma : nan);
      pulloff_.push_back(fitted ? r.pulloff_force.value_or(nan) : nan);
      pulloff_position_.push_back(fitted ? r.pulloff_position.value_or(nan) : nan);
      jump_force_.push_back(fitted ? r.model_jump_off_force.value_or(nan) : nan);
      jump_indentation_.push_back(fitted ? r.model_jump_off_indentation.value_or(nan) : nan);
      points_.push_back(fitted ? static_cast<long>(r.points) : 0);
      rating_.push_back(r.rating);
      tabor_mu_.push_back(r.tabor_mu.value_or(nan));
      maugis_lambda_.push_back(r.maugis_lambda.value_or(nan));
      warnings_.append(py::str(r.warnings));
    }
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
      put(parameters_[p].name, to_array(value_[p]));
      put(parameters_[p].name + "_error", to_array(error_[p]));
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
  py::str reason_name(coatcontact::fit::AfmFlag flag) {
    auto& name = reasons_[static_cast<std::size_t>(flag)];
    if (!name) name = py::str(coatcontact::fit::afm_flag_name(flag));
    return *name;
  }

  std::vector<coatcontact::fit::AfmBatchParameter> parameters_;
  bool contact_column_;
  py::list file_, reason_, warnings_;
  std::optional<py::str> last_file_;
  std::string last_file_text_;
  std::optional<py::str> reasons_[coatcontact::fit::kAfmFlagCount];
  std::vector<long> curve_, grid_x_, grid_y_, points_;
  std::vector<int> flag_;
  std::vector<double> x_, y_, chi2_, chi2_per_dof_, sigma_, pulloff_, pulloff_position_, contact_;
  std::vector<double> rating_, tabor_mu_, maugis_lambda_, jump_force_, jump_indentation_;
  std::vector<std::vector<double>> value_, error_;
};

// The files of `paths` (a folder: its AFM files by extension, sorted), in order.
std::vector<std::string> expand_paths(const std::vector<std::string>& paths) {
  std::vector<std::string> files;
  try {
    for (const auto& p : paths) {
      struct stat info {};
      if (::stat(p.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
        for (auto& f : afm::afm_files_in_folder(p)) files.push_back(std::move(f));
      } else {
        files.push_back(p);
      }
    }
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  }
  return files;
}

// (curves, why unreadable or "", flag of its row) of each file (afm_survey_files): with `tolerate` a file that
// cannot be read is one flagged row of the run instead of a ValueError.
std::vector<std::tuple<std::size_t, std::string, int>> survey_files(const std::vector<std::string>& files,
                                                              const py::object& spring_constant,
                                                              const py::object& sensitivity, bool tolerate) {
  std::vector<std::tuple<std::size_t, std::string, int>> out;
  try {
    const afm::Calibration calibration = calibration_of(spring_constant, sensitivity);
    py::gil_scoped_release release;
    for (auto& s : coatcontact::fit::afm_survey_files(files, calibration, tolerate)) out.emplace_back(s.curves, std::move(s.unreadable), static_cast<int>(s.flag));
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  }
  return out;
}

// One control-plot page of fit_map(curve_plots=): the row's place, flag, rating and estimates,
// and its trace (afm_curve_trace: "z", "force", "model", "segment", "fitted", "contact_point";
// absent for a curve without data). Called with the GIL held.
py::dict trace_dict(const coatcontact::fit::AfmCurveRow& row, const std::vector<coatcontact::fit::AfmBatchParameter>& parameters) {
  namespace fit = coatcontact::fit;
  py::dict d;
  d["file"] = row.source_file;
  d["curve"] = row.curve_index;
  d["grid"] = row.grid_x && row.grid_y ? py::object(py::make_tuple(*row.grid_x, *row.grid_y)) : py::object(py::none());
  d["flag"] = fit::afm_flag_name(row.flag);
  d["rating"] = row.rating;
  d["message"] = row.message;
  py::list estimates;
  if (fit::afm_flag_keeps_estimates(row.flag)) {
    for (std::size_t p = 0; p < parameters.size() && p < row.estimates.size(); ++p) {
      estimates.append(py::make_tuple(parameters[p].name, row.estimates[p], row.errors[p], parameters[p].unit));
    }
    d["chi2_per_dof"] = row.chi2_per_dof;
  }
  d["estimates"] = estimates;
  if (row.trace && !row.trace->z.empty()) {
    const fit::AfmCurveTrace& t = *row.trace;
    d["z"] = to_array(t.z);
    d["force"] = to_array(t.force);
    d["model"] = to_array(t.model);
    d["segment"] = to_array(t.segment);
    std::vector<int> fitted(t.fitted.begin(), t.fitted.end());
    d["fitted"] = to_array(fitted);
    d["contact_point"] = t.contact_point;
  }
  return d;
}

// Curves [first, first + count) of the run over `files`, fitted with `jobs` threads (0: cores).
py::dict fit_map_files(const std::vector<std::string>& files, const py::tuple& shape, double modulus, double poisson,
                       const std::vector<std::string>& free, double contact_point, double baseline, const py::object& coating,
                       const std::string& segment, const py::object& tip_min, const py::object& tip_max,
                       const py::object& indentation_min, const py::object& indentation_max, const py::object& max_force,
                       const py::object& spring_constant, const py::object& sensitivity, unsigned jobs, std::size_t first,
                       const py::object& count, const py::object& survey, bool tolerate,
                       const py::object& adhesion, const std::string& baseline_model, double weight_cp,
                       const py::object& trace_sink) {
  namespace fit = coatcontact::fit;
  fit::AfmBatchSettings settings;
  std::optional<Columns> columns;
  try {
    settings = settings_of(shape, modulus, poisson, free, contact_point, baseline, coating, segment, tip_min, tip_max,
                           indentation_min, indentation_max, max_force, adhesion);
    settings.baseline = baseline_model_of(baseline_model, settings.problem);
    settings.problem.weight_cp = weight_cp;
    settings.keep_traces = !trace_sink.is_none();
    const std::vector<fit::AfmBatchParameter> parameters = fit::afm_batch_parameters(settings.problem);
    columns.emplace(settings);
    const afm::Calibration calibration = calibration_of(spring_constant, sensitivity);
    fit::AfmBatchOptions options;
    options.jobs = jobs;
    options.skip = first;
    if (!count.is_none()) options.count = count.cast<std::size_t>();
    if (!survey.is_none()) {
      for (auto& [curves, why, flag] : survey.cast<std::vector<std::tuple<std::size_t, std::string, int>>>()) {
        options.survey.push_back({curves, std::move(why), static_cast<fit::AfmFlag>(flag)});
      }
    }
    options.unreadable_file_rows = tolerate;
    // The sink runs on the calling thread, which holds no GIL during the batch.
    options.sink = [&](const std::vector<fit::AfmCurveRow>& chunk) {
      py::gil_scoped_acquire acquire;
      columns->add(chunk);
      if (!trace_sink.is_none()) {
        for (const fit::AfmCurveRow& row : chunk) trace_sink(trace_dict(row, parameters));  // a page each, as they come
      }
    };
    SignalCheck signals;
    options.progress = [&](std::size_t, std::size_t) { return signals(); };
    try {
      py::gil_scoped_release release;
      fit::afm_fit_batch(files, calibration, settings, options);
    } catch (const coatcontact::Interrupted&) {
      signals.rethrow();
      throw;
    }
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  } catch (const coatcontact::NumericalError& e) {
    throw std::runtime_error(std::string("numerical failure: ") + e.what());
  }
  return columns->dict();
}

// afm_depth_profile as a dict of arrays: "depth", "max_indentation" [m], the modulus ("E" or
// "E1") and its "_error" [Pa], "flag" (names), "points_in_contact", and on a coating
// "E_apparent", "E_apparent_error" [Pa] (the half-space fit) and "over_thickness_fraction"; NaN
// where a depth has no estimate. Scalars: "modulus_name", "thickness_fraction", "warnings".
py::dict depth_profile_dict(const coatcontact::fit::AfmDepthProfile& profile) {
  namespace fit = coatcontact::fit;
  std::vector<double> depth, indentation, modulus, error, apparent, apparent_error;
  std::vector<long> contact;
  std::vector<bool> beyond;
  py::list flags;
  for (const fit::AfmDepthStep& s : profile.steps) {
    depth.push_back(s.depth);
    indentation.push_back(s.max_indentation);
    modulus.push_back(s.modulus);
    error.push_back(s.modulus_error);
    apparent.push_back(s.apparent_modulus);
    apparent_error.push_back(s.apparent_modulus_error);
    contact.push_back(static_cast<long>(s.points_in_contact));
    beyond.push_back(s.beyond_thickness_fraction);
    flags.append(fit::afm_flag_name(s.flag));
  }
  py::dict d;
  d["depth"] = to_array(depth);
  d["max_indentation"] = to_array(indentation);
  d[py::str(profile.modulus_name)] = to_array(modulus);
  d[py::str(profile.modulus_name + "_error")] = to_array(error);
  d["points_in_contact"] = to_array(contact);
  d["flag"] = flags;
  d["modulus_name"] = profile.modulus_name;
  if (profile.coated) {
    d["E_apparent"] = to_array(apparent);
    d["E_apparent_error"] = to_array(apparent_error);
    py::array_t<bool> marks(static_cast<py::ssize_t>(beyond.size()));
    for (std::size_t i = 0; i < beyond.size(); ++i) marks.mutable_data()[i] = beyond[i];
    d["over_thickness_fraction"] = marks;
    d["thickness_fraction"] = fit::kDepthProfileThicknessFraction;
  }
  d["warnings"] = profile.warnings;
  return d;
}

// One curve given as arrays through the library's one-curve pipeline (afm_fit_curve): the
// segment, the preprocessing steps, the baseline model, the range, the fit and the pull-off,
// as `afm fit` and each row of fit_map. noise > 0 replaces the baseline's sigma in chi2.
py::dict fit_curve(const py::object& force, const py::object& height_piezo, const py::object& height_measured,
                   const std::vector<std::tuple<std::string, std::size_t, std::size_t>>& segments, double spring_constant,
                   const std::string& name, const py::tuple& shape, double modulus, double poisson,
                   const std::vector<std::string>& free, double contact_point, double baseline, const py::object& coating,
                   const std::string& segment, const py::object& tip_min, const py::object& tip_max,
                   const py::object& indentation_min, const py::object& indentation_max, const py::object& max_force,
                   const py::object& adhesion, const std::string& baseline_model, double noise, double weight_cp,
                   bool depth_profile) {
  namespace fit = coatcontact::fit;
  const afm::ForceCurve curve = curve_of(force, height_piezo, height_measured, segments, spring_constant, name);
  py::dict out;
  try {
    fit::AfmCurveRequest request = settings_of(shape, modulus, poisson, free, contact_point, baseline, coating, segment,
                                               tip_min, tip_max, indentation_min, indentation_max, max_force, adhesion);
    request.check_jump_in = false;
    request.problem.noise_sigma = noise;
    request.problem.weight_cp = weight_cp;
    request.baseline = baseline_model_of(baseline_model, request.problem);
    fit::AfmCurveFit fitted;
    std::optional<fit::AfmDepthProfile> profile;
    SignalCheck signals;
    try {
      py::gil_scoped_release release;
      const coatcontact::ScopedProgressHook hook([&](std::size_t, std::size_t) { return signals(); });
      if (depth_profile) {
        profile = fit::afm_depth_profile(curve, request, {});
        fitted = profile->reference;  // the whole-range fit: the result as without the profile
      } else {
        fitted = fit::afm_fit_curve(curve, request);
      }
    } catch (const coatcontact::Interrupted&) {
      signals.rethrow();
      throw;
    }
    std::vector<double> z, f;
    std::vector<long> index;
    for (std::size_t i : fitted.kept) {
      z.push_back(fitted.z_segment[i]);
      f.push_back(fitted.f_segment[i]);
      index.push_back(static_cast<long>(fitted.segment.begin + i));
    }
    out = result_dict(fitted.problem, fitted.result, z, f, index, true);
    py::list steps;
    for (const fit::AfmStep& step : fitted.steps) steps.append(py::make_tuple(step.name, step.parameters));
    out["steps"] = steps;
    out["baseline_model"] = fit::afm_baseline_model_name(fitted.baseline);
    out["reference_contact_point"] = fitted.reference_contact;
    // The flag (fitted, or undetermined / no_detachment with the estimates kept), its reasons
    // and the model's warnings, and the curve rating (afm_curve_fit.hpp).
    out["flag"] = fit::afm_flag_name(fitted.flag);
    out["rating"] = fitted.rating;
    py::list warnings;
    for (const std::string& w : fitted.flag_warnings) warnings.append(w);
    for (const std::string& w : fitted.result.warnings) warnings.append(w);
    out["warnings"] = warnings;
    if (fitted.pulloff.found) {
      py::dict pulloff;
      pulloff["F"] = fitted.pulloff.force;
      pulloff["z"] = fitted.pulloff.tip_position;
      pulloff["baseline_offset"] = fitted.pulloff.baseline_offset;
      pulloff["baseline_slope"] = fitted.pulloff.baseline_slope;
      out["pulloff"] = pulloff;
    } else {
      out["pulloff"] = py::none();
    }
    if (profile) out["depth_profile"] = depth_profile_dict(*profile);
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  } catch (const coatcontact::NumericalError& e) {
    throw std::runtime_error(std::string("numerical failure: ") + e.what());
  }
  return out;
}

// The measured pull-off of a retract given as arrays (afm_measured_pulloff): a dict, or None.
py::object measured_pulloff(const py::object& tip_position, const py::object& force, double fraction) {
  const auto p = coatcontact::fit::afm_measured_pulloff(to_vector(tip_position), to_vector(force), fraction);
  if (!p.found) return py::none();
  py::dict out;
  out["F"] = p.force;
  out["z"] = p.tip_position;
  out["baseline_offset"] = p.baseline_offset;
  out["baseline_slope"] = p.baseline_slope;
  return out;
}

// Curves given as arrays: (force, height_piezo, height_measured, segments, spring_constant,
// name, curve_index, grid_x, grid_y, x, y), each fitted as a curve of a file would be.
py::dict fit_map_curves(const py::list& curves, const py::tuple& shape, double modulus, double poisson,
                        const std::vector<std::string>& free, double contact_point, double baseline,
                        const py::object& coating, const std::string& segment, const py::object& tip_min,
                        const py::object& tip_max, const py::object& indentation_min, const py::object& indentation_max,
                        const py::object& max_force, const py::object& adhesion, const std::string& baseline_model,
                        double weight_cp, const py::object& trace_sink) {
  namespace fit = coatcontact::fit;
  fit::AfmBatchSettings settings;
  std::vector<fit::AfmCurveRow> rows;
  try {
    settings = settings_of(shape, modulus, poisson, free, contact_point, baseline, coating, segment, tip_min, tip_max,
                           indentation_min, indentation_max, max_force, adhesion);
    settings.baseline = baseline_model_of(baseline_model, settings.problem);
    settings.problem.weight_cp = weight_cp;
    settings.keep_traces = !trace_sink.is_none();
    for (const py::handle item : curves) {
      const py::tuple c = py::reinterpret_borrow<py::tuple>(item);
      afm::ForceCurve curve = curve_of(c[0], c[1], c[2], c[3].cast<std::vector<std::tuple<std::string, std::size_t, std::size_t>>>(),
                                       c[4].cast<double>(), c[5].cast<std::string>());
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C between curves
      afm::CurveMetadata& m = curve.metadata;
      m.curve_index = c[6].cast<std::size_t>();
      if (!c[7].is_none()) m.grid_index_x = c[7].cast<long>();
      if (!c[8].is_none()) m.grid_index_y = c[8].cast<long>();
      if (!c[9].is_none()) m.position_x = c[9].cast<double>();
      if (!c[10].is_none()) m.position_y = c[10].cast<double>();
      {
        py::gil_scoped_release release;
        rows.push_back(fit::afm_fit_curve_row(curve, settings));
      }
      if (!trace_sink.is_none()) {
        trace_sink(trace_dict(rows.back(), fit::afm_batch_parameters(settings.problem)));
        rows.back().trace.reset();  // drawn: the page holds it now
      }
    }
  } catch (const coatcontact::InputError& e) {
    throw py::value_error(e.what());
  }
  Columns columns(settings);
  columns.add(rows);
  return columns.dict();
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
