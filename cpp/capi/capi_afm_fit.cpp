// The C interface of the one AFM fit (coatcontact_afm.h): a request built by setters, resolved
// into the library's AfmCurveRequest with the CLI's rules (defaults of the free parameters and
// the segment follow the model and the sample), afm_fit_curve, and the result's accessors.
#include <cmath>
#include <cstdio>
#include <optional>

#include "capi_afm.hpp"
#include "capi_guard.hpp"
#include "capi_handles.hpp"
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/afm_depth_profile.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/stack.hpp"

using coatcontact::InputError;
namespace afm = coatcontact::afm;
namespace fit = coatcontact::fit;
using coatcontact::capi::checked_index;
using coatcontact::capi::copy_out;
using coatcontact::capi::guard;
using coatcontact::capi::require;

struct cc_afm_fit {
  fit::AfmCurveFit fit;
  std::vector<fit::AfmBatchParameter> parameters;
  std::vector<std::string> warnings;  // the model's, then the flag's
  std::vector<std::pair<std::string, std::vector<double>>> arrays;
  std::optional<fit::AfmDepthProfile> profile;  // with the request's depth_profile
  std::vector<std::pair<std::string, std::vector<double>>> profile_arrays;
  std::string profile_modulus;  // "E", or a coating's E<K> (K the free layer), as the results name it
};

namespace {

thread_local std::string last_flag;

std::string text_of(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

std::string quoted(const char* text) { return "'" + std::string(text).substr(0, 60) + "'"; }

cc_afm_request& request_of(cc_afm_request* request, const char* function) {
  require(request, function, "request");
  return *request;
}

// Splits a comma-separated list, items trimmed.
std::vector<std::string> items_of(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    std::string item = text.substr(start, comma - start);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    items.push_back(item);
    start = comma + 1;
  }
  return items;
}

// The free flags of `text` for the model and sample (the CLI's --free rules, from the registry's
// parameter table).
fit::AfmFree free_of(const std::string& text, const fit::AfmModelInfo& info, bool coated) {
  fit::AfmFree free{false, false, false, false, false, false};
  for (const std::string& item : items_of(text)) {
    const fit::AfmParameterInfo* parameter = fit::afm_parameter(info, item, coated);
    if (!parameter) {
      throw InputError("cc_afm_request_set_free: '" + item.substr(0, 60) + "' is not a parameter of this fit (" +
                       (coated ? "coating, " : "half-space, ") + info.name + "); allowed: " + fit::afm_free_allowed(info, coated));
    }
    free.*parameter->free = true;
  }
  return free;
}

// The request's checks that need the whole of it (the CLI's parse_fit_setup rules).
void check_values(const cc_afm_request& r, const fit::AfmFitProblem& p, bool adhesive, const std::string& f) {
  if (adhesive && !p.free.work && !r.has_work) throw InputError(f + ": a fixed w needs cc_afm_request_set(request, \"w\", W)");
  if (!adhesive && r.has_work) throw InputError(f + ": w is set but the model '" + r.model + "' has no adhesion; use jkr, md or dmt");
  if (!adhesive && r.has_tilt) throw InputError(f + ": a fixed tilt needs an adhesive model (jkr, md, dmt); hertz fits it free or subtracts it");
  if (p.free.tilt && r.has_tilt) throw InputError(f + ": tilt is free; drop it from the free list to fix it");
  if (p.free.contact_point && r.has_contact_point) {
    throw InputError(f + ": contact_point is free; drop it from the free list to fix it");
  }
  if (!p.free.contact_point && !r.has_contact_point) {
    throw InputError(f + ": a fixed contact point needs cc_afm_request_set(request, \"contact_point\", Z)");
  }
  if (p.free.baseline && r.has_baseline) {
    throw InputError(f + ": baseline is free; drop it from the free list to fix it");
  }
  if (r.baseline == fit::AfmBaselineModel::kTilt && p.free.tilt) {
    throw InputError(f + ": baseline model tilt with tilt free would count the slope twice; drop one");
  }
  const fit::AfmRange& range = r.request.range;
  if (range.tip_min && range.tip_max && !(*range.tip_min < *range.tip_max)) {
    throw InputError(f + ": tip_min " + text_of(*range.tip_min) + " must be below tip_max " + text_of(*range.tip_max));
  }
  if (range.indentation_min && range.indentation_max && !(*range.indentation_min < *range.indentation_max)) {
    throw InputError(f + ": indentation_min " + text_of(*range.indentation_min) + " must be below indentation_max " +
                     text_of(*range.indentation_max));
  }
}

}  // namespace

namespace coatcontact::capi {

fit::AfmCurveRequest resolve_request(const cc_afm_request& r, const char* function) {
  const std::string f(function);
  const fit::AfmModelInfo& info = fit::afm_model_by_name(r.model, "cc_afm_request_set_model");
  if (!r.has_tip) throw InputError(f + ": the request has no tip; call cc_afm_request_set_tip or cc_afm_request_set_tip_shape");
  if (!r.has_sample) throw InputError(f + ": the request has no sample; call cc_afm_request_set_sample");
  fit::AfmCurveRequest out = r.request;
  fit::AfmFitProblem& p = out.problem;
  p.model = info.model();
  const bool adhesive = info.needs_spring;
  if (adhesive && p.tip.kind != fit::AfmTip::Kind::kParaboloid) {
    throw InputError(f + ": model " + r.model + " takes a sphere tip (cc_afm_request_set_tip(request, \"sphere\", R)); got " +
                     p.tip.description);
  }
  const std::string modulus = r.coated ? "E1" : "E";
  p.free = free_of(r.free.empty() ? fit::afm_free_default(info, r.coated) : r.free, info, r.coated);
  if (!p.free.modulus && !p.free.contact_point && !p.free.baseline && !p.free.thickness && !p.free.work && !p.free.tilt) {
    throw InputError(f + ": the free list '" + r.free + "' names no parameter");
  }
  check_values(r, p, adhesive, f);
  out.segment = r.segment.value_or(info.segment);
  out.baseline = r.baseline.value_or(fit::kAfmDefaultBaseline);
  out.check_jump_in = r.check_jump_in.value_or(fit::AfmCurveRequest{}.check_jump_in);
  return out;
}

}  // namespace coatcontact::capi

namespace {

fit::AfmTip tip_of(const std::string& kind, double value) {
  const std::string f = "cc_afm_request_set_tip";
  const bool length = kind == "sphere" || kind == "sneddon-sphere";
  const bool angle = kind == "cone" || kind == "pyramid" || kind == "pyramid3";
  if (!length && !angle) {
    throw InputError(f + ": kind '" + kind.substr(0, 60) + "' is not a tip; allowed: sphere, sneddon-sphere, cone, pyramid, pyramid3");
  }
  if (length && !(value > 0.0 && std::isfinite(value))) {
    throw InputError(f + ": " + kind + " radius " + text_of(value) + " is not allowed; expected a length > 0 [m]");
  }
  if (angle && !(value > 0.0 && value < coatcontact::detail::kPi / 2)) {
    throw InputError(f + ": " + kind + " angle " + text_of(value) + " is not allowed; expected an angle in (0, pi/2) [rad]");
  }
  if (kind == "sphere") return fit::afm_paraboloid(value);
  if (kind == "sneddon-sphere") return fit::afm_sneddon_sphere(value);
  if (kind == "cone") return fit::afm_cone(value);
  if (kind == "pyramid") return fit::afm_pyramid(value);
  return fit::afm_pyramid3(value);
}

// cc_afm_request_set's values: a finite number, a positive one, or a range bound (NaN: none).
void set_value(cc_afm_request& r, const std::string& name, double v) {
  const std::string f = "cc_afm_request_set: " + name + " " + text_of(v) + " is not allowed; expected ";
  fit::AfmFitProblem& p = r.request.problem;
  fit::AfmRange& range = r.request.range;
  const auto finite = [&] {
    if (!std::isfinite(v)) throw InputError(f + "a finite number");
  };
  const auto positive = [&] {
    if (!(v > 0.0 && std::isfinite(v))) throw InputError(f + "a number > 0");
  };
  const auto non_negative = [&] {
    if (!(v >= 0.0 && std::isfinite(v))) throw InputError(f + "a number >= 0");
  };
  const auto bound = [&](std::optional<double>& slot) {
    if (std::isinf(v)) throw InputError(f + "a finite number, or NaN for no bound");
    slot = std::isnan(v) ? std::nullopt : std::optional<double>(v);
  };
  if (name == "contact_point") {
    finite();
    p.contact_point = v;
    r.has_contact_point = true;
  } else if (name == "baseline") {
    finite();
    p.baseline = v;
    r.has_baseline = true;
  } else if (name == "w") {
    positive();
    p.work = v;
    r.has_work = true;
  } else if (name == "tilt") {
    finite();
    p.tilt = v;
    r.has_tilt = true;
  } else if (name == "spring_constant") {
    positive();
    p.spring_constant = v;
  } else if (name == "surface_force_range") {
    positive();
    p.surface_force_range = v;
  } else if (name == "weight_cp") {
    non_negative();
    p.weight_cp = v;
  } else if (name == "noise_sigma") {
    non_negative();
    p.noise_sigma = v;
  } else if (name == "min_points") {
    if (!(v >= 1.0 && v <= 1e9 && v == std::floor(v))) throw InputError(f + "a whole number >= 1");
    r.request.min_points = static_cast<std::size_t>(v);
  } else if (name == "check_jump_in") {
    if (v != 0.0 && v != 1.0) throw InputError(f + "0 or 1");
    r.check_jump_in = v == 1.0;
  } else if (name == "depth_profile") {
    if (v != 0.0 && v != 1.0) throw InputError(f + "0 or 1");
    r.depth_profile = v == 1.0;
  } else if (name == "tip_min") bound(range.tip_min);
  else if (name == "tip_max") bound(range.tip_max);
  else if (name == "indentation_min") bound(range.indentation_min);
  else if (name == "indentation_max") bound(range.indentation_max);
  else if (name == "max_force") bound(range.max_force);
  else {
    throw InputError("cc_afm_request_set: name '" + name.substr(0, 60) +
                     "' is not a setting; allowed: contact_point, baseline, w, tilt, spring_constant, surface_force_range, "
                     "weight_cp, noise_sigma, min_points, check_jump_in, depth_profile, tip_min, tip_max, indentation_min, indentation_max, max_force");
  }
}

const cc_afm_fit& fit_of(const cc_afm_fit* fit, const char* function) {
  require(fit, function, "fit");
  return *fit;
}

// A parameter's estimate and error by name (fixed: its value, error 0).
std::pair<double, double> estimate_of(const cc_afm_fit& f, const std::string& name) {
  const fit::AfmFitResult& r = f.fit.result;
  const bool coated = f.fit.problem.coating.has_value();
  const fit::AfmModelInfo& info = f.fit.problem.model.info();
  for (const fit::AfmParameterInfo& parameter : info.parameters) {  // the results' names (a stack's E<K>)
    if ((coated || !parameter.coating_only) && fit::afm_result_parameter_name(parameter, f.fit.problem) == name) {
      return {r.*parameter.value, r.*parameter.error};
    }
  }
  if (const fit::AfmParameterInfo* parameter = fit::afm_parameter(info, name, coated)) {
    return {r.*parameter->value, r.*parameter->error};
  }
  throw InputError("cc_afm_fit_estimate: name '" + name.substr(0, 60) + "' is not a parameter of this fit; allowed: " +
                   fit::afm_free_allowed(info, coated));
}

void fill_fit(cc_afm_fit& out) {
  const fit::AfmCurveFit& f = out.fit;
  out.parameters = fit::afm_batch_parameters(f.problem);
  out.warnings = f.result.warnings;
  out.warnings.insert(out.warnings.end(), f.flag_warnings.begin(), f.flag_warnings.end());
  std::vector<double> z, force, index;
  for (std::size_t i : f.kept) {
    z.push_back(f.z_segment[i]);
    force.push_back(f.f_segment[i]);
    index.push_back(static_cast<double>(f.segment.begin + i));
  }
  out.arrays = {{"tip_position", z},
                {"force", force},
                {"model_force", f.result.model_force},
                {"residual", f.result.residual},
                {"indentation", f.result.indentation},
                {"index", index}};
}

void fill_profile(cc_afm_fit& out) {
  const fit::AfmDepthProfile& p = *out.profile;
  const fit::AfmFitProblem& problem = out.fit.problem;
  out.profile_modulus = problem.coating ? "E" + std::to_string(problem.coating->free_layer + 1) : p.modulus_name;
  std::vector<double> depth, indentation, modulus, error, apparent, apparent_error, contact, beyond;
  for (const fit::AfmDepthStep& s : p.steps) {
    depth.push_back(s.depth);
    indentation.push_back(s.max_indentation);
    modulus.push_back(s.modulus);
    error.push_back(s.modulus_error);
    apparent.push_back(s.apparent_modulus);
    apparent_error.push_back(s.apparent_modulus_error);
    contact.push_back(static_cast<double>(s.points_in_contact));
    beyond.push_back(s.beyond_thickness_fraction ? 1.0 : 0.0);
  }
  out.profile_arrays = {{"depth", depth},
                        {"max_indentation", indentation},
                        {"modulus", modulus},
                        {"modulus_error", error},
                        {"apparent_modulus", apparent},
                        {"apparent_modulus_error", apparent_error},
                        {"points_in_contact", contact},
                        {"over_thickness_fraction", beyond}};
}

const fit::AfmDepthProfile& profile_of(const cc_afm_fit* fit, const char* function) {
  const cc_afm_fit& f = fit_of(fit, function);
  if (!f.profile) throw InputError(std::string(function) + ": the fit has no depth profile (cc_afm_request_set(request, \"depth_profile\", 1))");
  return *f.profile;
}

}  // namespace

extern "C" {

int cc_afm_request_create(cc_afm_request** request) {
  return guard([&] {
    require(request, "cc_afm_request_create", "request");
    *request = new cc_afm_request();
  });
}

void cc_afm_request_destroy(cc_afm_request* request) { delete request; }

int cc_afm_request_set_model(cc_afm_request* request, const char* model) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_model");
    require(model, "cc_afm_request_set_model", "model");
    r.model = fit::afm_model_by_name(model, "cc_afm_request_set_model").name;
  });
}

int cc_afm_request_set_tip(cc_afm_request* request, const char* kind, double value) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_tip");
    require(kind, "cc_afm_request_set_tip", "kind");
    r.request.problem.tip = tip_of(kind, value);
    r.has_tip = true;
  });
}

int cc_afm_request_set_tip_shape(cc_afm_request* request, const cc_shape* shape) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_tip_shape");
    require(shape, "cc_afm_request_set_tip_shape", "shape");
    // A paraboloid is the closed-form sphere tip (as the CLI's --shape sphere:R).
    r.request.problem.tip = shape->sphere_radius > 0.0 ? fit::afm_paraboloid(shape->sphere_radius) : fit::afm_shape(shape->shape);
    r.has_tip = true;
  });
}

int cc_afm_request_set_sample(cc_afm_request* request, const cc_stack* stack) {
  return cc_afm_request_set_sample_layer(request, stack, 0);
}

int cc_afm_request_set_sample_layer(cc_afm_request* request, const cc_stack* stack, long free_layer) {
  return guard([&] {
    const std::string f = "cc_afm_request_set_sample";
    cc_afm_request& r = request_of(request, f.c_str());
    require(stack, f.c_str(), "stack");
    if (!stack->has_substrate) throw InputError(f + ": the stack has no substrate (the half-space, or the coating's substrate)");
    if (!stack->indenter.rigid) throw InputError(f + ": the AFM tip is rigid; the stack has an elastic indenter");
    const std::size_t n = stack->layers.size();
    if (free_layer < 0 || (n > 0 && static_cast<std::size_t>(free_layer) >= n) || (n == 0 && free_layer != 0)) {
      throw InputError(f + ": free layer " + std::to_string(free_layer) + " is not allowed; the stack's layers are 0.." +
                       std::to_string(n == 0 ? 0 : n - 1) + " (top first)");
    }
    fit::AfmFitProblem& p = r.request.problem;
    if (n == 0) {
      if (stack->substrate.rigid) throw InputError(f + ": a half-space sample (no layer) needs an elastic substrate, not a rigid one");
      coatcontact::Stack({coatcontact::Layer{1.0, stack->substrate.material, false}}, stack->substrate);  // checks E, nu
      p.coating.reset();
      p.modulus = stack->substrate.material.youngs_modulus;
      p.poisson = stack->substrate.material.poisson_ratio;
      r.coated = false;
    } else {
      if (n == 1 && stack->layers.front().slip_below) {
        throw InputError(f + ": the film slides on its substrate (slip_below); the AFM fit takes a bonded film");
      }
      // The stack's layers, top first; layer free_layer's modulus is the fit's E1 (AfmCoating).
      const coatcontact::Stack checked(stack->layers, stack->substrate);  // checks the constants
      p.coating = fit::afm_coating(checked, static_cast<std::size_t>(free_layer));
      p.poisson = p.coating->film.poisson_ratio;
      r.coated = true;
    }
    r.has_sample = true;
  });
}

int cc_afm_request_set_free(cc_afm_request* request, const char* names) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_free");
    require(names, "cc_afm_request_set_free", "names");
    for (const std::string& item : items_of(names)) {
      if (item != "E" && item != "E1" && item != "t" && item != "w" && item != "tilt" && item != "contact_point" && item != "baseline") {
        throw InputError("cc_afm_request_set_free: '" + item.substr(0, 60) +
                         "' is not a parameter; allowed: E (half-space), E1, t (coating), w (adhesive models), tilt, "
                         "contact_point, baseline");
      }
    }
    r.free = names;
  });
}

int cc_afm_request_set_segment(cc_afm_request* request, const char* segment) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_segment");
    require(segment, "cc_afm_request_set_segment", "segment");
    const std::string s(segment);
    if (s == "approach") r.segment = afm::SegmentKind::kApproach;
    else if (s == "retract") r.segment = afm::SegmentKind::kRetract;
    else throw InputError("cc_afm_request_set_segment: segment " + quoted(segment) + " is not allowed; expected approach or retract");
  });
}

int cc_afm_request_set_baseline_model(cc_afm_request* request, const char* model) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_baseline_model");
    require(model, "cc_afm_request_set_baseline_model", "model");
    const std::string s(model);
    if (s == "tilt") r.baseline = fit::AfmBaselineModel::kTilt;
    else if (s == "offset") r.baseline = fit::AfmBaselineModel::kOffset;
    else throw InputError("cc_afm_request_set_baseline_model: model " + quoted(model) + " is not allowed; expected tilt or offset");
  });
}

int cc_afm_request_set_preprocess(cc_afm_request* request, const cc_afm_preprocess_options* options) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set_preprocess");
    require(options, "cc_afm_request_set_preprocess", "options");
    r.request.preprocess = coatcontact::capi::afm_preprocess_options(*options, "cc_afm_request_set_preprocess");
  });
}

int cc_afm_request_set(cc_afm_request* request, const char* name, double value) {
  return guard([&] {
    cc_afm_request& r = request_of(request, "cc_afm_request_set");
    require(name, "cc_afm_request_set", "name");
    cc_afm_request changed = r;  // unchanged on failure
    set_value(changed, name, value);
    r = std::move(changed);
  });
}

const char* cc_afm_last_flag(void) { return last_flag.c_str(); }

int cc_afm_fit_curve(const cc_afm_curve* curve, const cc_afm_request* request, cc_afm_fit** fit) {
  last_flag.clear();
  return guard([&] {
    require(curve, "cc_afm_fit_curve", "curve");
    require(request, "cc_afm_fit_curve", "request");
    require(fit, "cc_afm_fit_curve", "fit");
    const fit::AfmCurveRequest resolved = coatcontact::capi::resolve_request(*request, "cc_afm_fit_curve");
    auto made = std::make_unique<cc_afm_fit>();
    try {
      if (request->depth_profile) {
        made->profile = fit::afm_depth_profile(curve->curve, resolved, {});
        made->fit = made->profile->reference;  // the whole-range fit: the result as without the profile
        fill_profile(*made);
      } else {
        made->fit = fit::afm_fit_curve(curve->curve, resolved);
      }
    } catch (const fit::AfmCurveInputError& e) {
      last_flag = fit::afm_flag_name(e.flag());
      throw;
    } catch (const fit::AfmCurveNumericalError& e) {
      last_flag = fit::afm_flag_name(e.flag());
      throw;
    }
    fill_fit(*made);
    *fit = made.release();
  });
}

void cc_afm_fit_destroy(cc_afm_fit* fit) { delete fit; }

int cc_afm_fit_parameter_count(const cc_afm_fit* fit, long* count) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_parameter_count");
    require(count, "cc_afm_fit_parameter_count", "count");
    *count = static_cast<long>(f.parameters.size());
  });
}

int cc_afm_fit_parameter_name(const cc_afm_fit* fit, long parameter, const char** name, const char** unit) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_parameter_name");
    require(name, "cc_afm_fit_parameter_name", "name");
    const auto& p = f.parameters[checked_index(parameter, f.parameters.size(), "cc_afm_fit_parameter_name", "parameter")];
    *name = p.name.c_str();
    if (unit) *unit = p.unit.c_str();
  });
}

int cc_afm_fit_estimate(const cc_afm_fit* fit, const char* name, double* value, double* error) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_estimate");
    require(name, "cc_afm_fit_estimate", "name");
    require(value, "cc_afm_fit_estimate", "value");
    const auto [v, e] = estimate_of(f, name);
    *value = v;
    if (error) *error = e;
  });
}

int cc_afm_fit_flag(const cc_afm_fit* fit, const char** flag) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_flag");
    require(flag, "cc_afm_fit_flag", "flag");
    *flag = fit::afm_flag_name(f.fit.flag);
  });
}

int cc_afm_fit_warning_count(const cc_afm_fit* fit, long* count) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_warning_count");
    require(count, "cc_afm_fit_warning_count", "count");
    *count = static_cast<long>(f.warnings.size());
  });
}

int cc_afm_fit_warning(const cc_afm_fit* fit, long warning, const char** text) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_warning");
    require(text, "cc_afm_fit_warning", "text");
    *text = f.warnings[checked_index(warning, f.warnings.size(), "cc_afm_fit_warning", "warning")].c_str();
  });
}

int cc_afm_fit_step_count(const cc_afm_fit* fit, long* count) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_step_count");
    require(count, "cc_afm_fit_step_count", "count");
    *count = static_cast<long>(f.fit.steps.size());
  });
}

int cc_afm_fit_step(const cc_afm_fit* fit, long step, const char** name, const char** parameters) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_step");
    require(name, "cc_afm_fit_step", "name");
    require(parameters, "cc_afm_fit_step", "parameters");
    const auto& s = f.fit.steps[checked_index(step, f.fit.steps.size(), "cc_afm_fit_step", "step")];
    *name = s.name.c_str();
    *parameters = s.parameters.c_str();
  });
}

int cc_afm_fit_get_summary(const cc_afm_fit* fit, cc_afm_fit_summary* summary) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_get_summary");
    require(summary, "cc_afm_fit_get_summary", "summary");
    const fit::AfmFitResult& r = f.fit.result;
    cc_afm_fit_summary s{};
    s.points = static_cast<long>(r.points);
    s.points_in_contact = static_cast<long>(r.points_in_contact);
    s.free_count = r.free_count;
    s.rss = r.rss;
    s.residual_sigma = r.residual_sigma;
    s.chi2 = r.chi2;
    s.chi2_per_dof = r.chi2_per_dof;
    s.r_squared = r.r_squared;
    s.reduced_modulus = r.reduced_modulus;
    s.max_indentation = r.max_indentation;
    s.rating = f.fit.rating;
    s.spring_constant = f.fit.problem.spring_constant;
    s.noise_sigma = f.fit.problem.noise_sigma;
    s.tabor_mu = r.tabor_mu;
    s.maugis_lambda = r.maugis_lambda;
    s.jump_off_indentation = r.jump_off_indentation;
    s.jump_off_force = r.jump_off_force;
    s.has_pulloff = f.fit.pulloff.found;
    s.pulloff_force = f.fit.pulloff.force;
    s.pulloff_position = f.fit.pulloff.tip_position;
    s.subtracted_tilt = f.fit.subtracted_tilt;
    s.reference_contact = f.fit.reference_contact;
    s.reference_baseline = f.fit.reference_baseline;
    s.segment_begin = static_cast<long>(f.fit.segment.begin);
    s.segment_end = static_cast<long>(f.fit.segment.end);
    *summary = s;
  });
}

int cc_afm_fit_array(const cc_afm_fit* fit, const char* name, double* values, long capacity, long* length) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_array");
    require(name, "cc_afm_fit_array", "name");
    for (const auto& [array, data] : f.arrays) {
      if (array == name) return copy_out(data, values, capacity, length, "cc_afm_fit_array", array);
    }
    throw InputError("cc_afm_fit_array: name " + quoted(name) +
                     " is not an array of the fit; allowed: tip_position, force, model_force, residual, indentation, index");
  });
}

int cc_afm_fit_arrays(long n, const double* tip_position, const double* force, const cc_afm_request* request,
                      double reference_contact, double reference_baseline, cc_afm_fit** fit) {
  return guard([&] {
    const char* f = "cc_afm_fit_arrays";
    require(tip_position, f, "tip_position");
    require(force, f, "force");
    require(request, f, "request");
    require(fit, f, "fit");
    if (n < 1) throw InputError(std::string(f) + ": n " + std::to_string(n) + " is not allowed; expected >= 1 points");
    if (request->depth_profile) throw InputError(std::string(f) + ": a depth profile needs a curve (cc_afm_fit_curve)");
    const fit::AfmCurveRequest resolved = coatcontact::capi::resolve_request(*request, f);
    auto made = std::make_unique<cc_afm_fit>();
    fit::AfmCurveFit& c = made->fit;
    c.problem = resolved.problem;
    c.baseline = fit::AfmBaselineModel::kOffset;
    c.z_segment.assign(tip_position, tip_position + n);
    c.f_segment.assign(force, force + n);
    c.segment.begin = 0;
    c.segment.end = static_cast<std::size_t>(n);
    c.kept = fit::afm_select(c.z_segment, c.f_segment, resolved.range, reference_contact, reference_baseline);
    std::vector<double> z, fz;
    for (std::size_t i : c.kept) {
      z.push_back(c.z_segment[i]);
      fz.push_back(c.f_segment[i]);
    }
    c.result = fit::afm_fit(z, fz, c.problem);
    c.reference_contact = reference_contact;
    c.reference_baseline = reference_baseline;
    fill_fit(*made);
    *fit = made.release();
  });
}

int cc_afm_fit_get_details(const cc_afm_fit* fit, cc_afm_fit_details* details) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_get_details");
    require(details, "cc_afm_fit_get_details", "details");
    const fit::AfmFitProblem& p = f.fit.problem;
    const fit::AfmFitResult& r = f.fit.result;
    cc_afm_fit_details d{};
    d.model = p.model.name();
    d.tip = p.tip.description.c_str();
    d.baseline_model = fit::afm_baseline_model_name(f.fit.baseline);
    d.surface_force_range = p.surface_force_range;
    d.profile_evaluations = static_cast<long>(r.profile_evaluations);
    d.solver_calls = static_cast<long>(r.solver_calls);
    d.model_evaluations = static_cast<long>(r.model_evaluations);
    d.seconds = r.seconds;
    d.model_warnings = static_cast<long>(r.warnings.size());
    d.pulloff_baseline_offset = f.fit.pulloff.baseline_offset;
    d.pulloff_baseline_slope = f.fit.pulloff.baseline_slope;
    d.coated = p.coating.has_value();
    d.free_layer = p.coating ? static_cast<long>(p.coating->free_layer) : 0;
    *details = d;
  });
}

int cc_afm_fit_depth_profile(const cc_afm_fit* fit, cc_afm_depth_profile_info* info) {
  return guard([&] {
    const cc_afm_fit& f = fit_of(fit, "cc_afm_fit_depth_profile");
    require(info, "cc_afm_fit_depth_profile", "info");
    cc_afm_depth_profile_info o{};
    o.modulus_name = "";
    if (f.profile) {
      o.steps = static_cast<long>(f.profile->steps.size());
      o.coated = f.profile->coated;
      o.modulus_name = f.profile_modulus.c_str();
      o.thickness_fraction = fit::kDepthProfileThicknessFraction;
      o.warning_count = static_cast<long>(f.profile->warnings.size());
    }
    *info = o;
  });
}

int cc_afm_fit_depth_profile_array(const cc_afm_fit* fit, const char* name, double* values, long capacity, long* length) {
  return guard([&] {
    const char* fn = "cc_afm_fit_depth_profile_array";
    profile_of(fit, fn);
    require(name, fn, "name");
    for (const auto& [array, data] : fit->profile_arrays) {
      if (array == name) return copy_out(data, values, capacity, length, fn, array);
    }
    throw InputError(std::string(fn) + ": name " + quoted(name) +
                     " is not an array of the profile; allowed: depth, max_indentation, modulus, modulus_error, "
                     "apparent_modulus, apparent_modulus_error, points_in_contact, over_thickness_fraction");
  });
}

int cc_afm_fit_depth_profile_flag(const cc_afm_fit* fit, long step, const char** flag) {
  return guard([&] {
    const char* fn = "cc_afm_fit_depth_profile_flag";
    const fit::AfmDepthProfile& p = profile_of(fit, fn);
    require(flag, fn, "flag");
    *flag = fit::afm_flag_name(p.steps[checked_index(step, p.steps.size(), fn, "step")].flag);
  });
}

int cc_afm_fit_depth_profile_warning(const cc_afm_fit* fit, long warning, const char** text) {
  return guard([&] {
    const char* fn = "cc_afm_fit_depth_profile_warning";
    const fit::AfmDepthProfile& p = profile_of(fit, fn);
    require(text, fn, "text");
    *text = p.warnings[checked_index(warning, p.warnings.size(), fn, "warning")].c_str();
  });
}

}  // extern "C"
