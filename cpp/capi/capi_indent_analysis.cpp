// The C API of Oliver–Pharr and the film analysis (coatcontact_indent_analysis.h): arrays in, a
// table of named columns and scalars out. Every entry point runs inside capi::guard.
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "capi_guard.hpp"
#include "coatcontact/coatcontact.h"
#include "coatcontact/errors.hpp"
#include "coatcontact/indent_film.hpp"
#include "coatcontact/oliver_pharr.hpp"

using coatcontact::InputError;
namespace ci = coatcontact::indent;

struct cc_indent_result {
  std::vector<std::pair<std::string, std::vector<double>>> columns;
  std::vector<std::pair<std::string, double>> scalars;
};

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class T>
const T& need(const T* p, const char* function, const char* what) {
  if (p == nullptr) throw InputError(std::string(function) + ": " + what + " is NULL");
  return *p;
}

std::vector<double> copy(const double* p, long n) { return p ? std::vector<double>(p, p + n) : std::vector<double>{}; }

ci::IndentTest test_of(const cc_indent_data& d, const char* function) {
  if (d.depth == nullptr || d.load == nullptr || d.points < 1)
    throw InputError(std::string(function) + ": the data need depth and load with points >= 1");
  ci::IndentTest t;
  t.name = "data";
  t.depth = copy(d.depth, d.points);
  t.load = copy(d.load, d.points);
  t.stiffness = copy(d.stiffness, d.points);
  t.hardness = copy(d.hardness, d.points);
  if (d.area_count > 0) t.calibration.area.coefficients = copy(d.area_coefficients, d.area_count);
  t.calibration.poisson = d.poisson;
  t.calibration.range_min = d.range_min;
  t.calibration.range_max = d.range_max;
  return t;
}

ci::OliverPharrOptions options_of(const cc_indent_options& o) {
  ci::OliverPharrOptions r;
  if (o.area_count > 0) r.area.coefficients = copy(o.area_coefficients, o.area_count);
  r.area_from_hardness = o.area_from_hardness != 0;
  r.indenter = o.rigid_indenter ? coatcontact::Indenter{} : coatcontact::Indenter{false, {o.indenter_modulus, o.indenter_poisson}};
  r.poisson = o.poisson;
  r.beta = o.beta;
  r.epsilon = o.epsilon;
  r.frame_stiffness = o.frame_stiffness;
  r.depth_min = o.depth_min;
  r.depth_max = o.depth_max;
  if (o.stiffness < 0 || o.stiffness > 2) throw InputError("cc_indent_options: stiffness must be 0 (auto), 1 (CSM) or 2 (unloading)");
  r.stiffness = static_cast<ci::StiffnessSource>(o.stiffness);
  r.unload_lower = o.unload_lower;
  r.unload_upper = o.unload_upper;
  return r;
}

ci::FilmOptions film_of(const cc_indent_film_options& f) {
  ci::FilmOptions o;
  if (f.layers == nullptr || f.layer_count < 1) throw InputError("cc_indent_film: layers: at least one (the film)");
  for (long k = 0; k < f.layer_count; ++k)
    o.layers.push_back(coatcontact::Layer{f.layers[3 * k], {f.layers[3 * k + 1], f.layers[3 * k + 2]}, false});
  o.substrate = f.substrate_rigid ? coatcontact::Substrate{true, {}} : coatcontact::Substrate{false, {f.substrate_modulus, f.substrate_poisson}};
  o.unknown = f.solve_thickness ? ci::FilmUnknown::kThickness : ci::FilmUnknown::kModulus;
  o.model = ci::film_model_from_name(f.model ? f.model : "exact");
  o.alpha = f.alpha;
  o.contact_depth = f.coated_contact_depth ? ci::ContactDepth::kCoated : ci::ContactDepth::kHalfSpace;
  if (f.max_points < 1) throw InputError("cc_indent_film: max_points must be >= 1");
  o.max_points = static_cast<std::size_t>(f.max_points);
  o.tolerance = f.tolerance;
  return o;
}

std::vector<double> flags(const std::vector<char>& v) { return std::vector<double>(v.begin(), v.end()); }

}  // namespace

extern "C" {

void cc_indent_options_default(cc_indent_options* o) {
  if (o == nullptr) return;
  *o = cc_indent_options{};
  o->indenter_modulus = 1141e9;
  o->indenter_poisson = 0.07;
  o->poisson = o->frame_stiffness = o->depth_min = o->depth_max = kNaN;
  o->beta = 1.0;
  o->epsilon = 0.75;
  o->unload_lower = 0.5;
  o->unload_upper = 0.95;
}

void cc_indent_film_options_default(cc_indent_film_options* f) {
  if (f == nullptr) return;
  *f = cc_indent_film_options{};
  f->model = "exact";
  f->alpha = kNaN;
  f->max_points = 200;
  f->tolerance = 1e-8;
}

int cc_indent_analyse(const cc_indent_data* data, const cc_indent_options* options, cc_indent_result** result) {
  return coatcontact::capi::guard([&] {
    need(result, "cc_indent_analyse", "result");
    const ci::OliverPharrResult r =
        ci::oliver_pharr(test_of(need(data, "cc_indent_analyse", "data"), "cc_indent_analyse"),
                         options_of(need(options, "cc_indent_analyse", "options")));
    auto t = std::make_unique<cc_indent_result>();
    t->columns = {{"depth", r.depth}, {"load", r.load}, {"stiffness", r.stiffness}, {"contact_depth", r.contact_depth},
                  {"area", r.area}, {"contact_radius", r.contact_radius}, {"reduced_modulus", r.reduced_modulus},
                  {"modulus", r.modulus}, {"hardness", r.hardness}, {"in_range", flags(r.in_range)}};
    t->scalars = {{"E_mean", r.modulus_mean}, {"E_sd", r.modulus_sd}, {"H_mean", r.hardness_mean}, {"H_sd", r.hardness_sd},
                  {"range_points", static_cast<double>(r.range_points)}, {"range_min", r.range_min}, {"range_max", r.range_max},
                  {"poisson", r.poisson}, {"dropped", static_cast<double>(r.dropped)}, {"csm", r.csm ? 1.0 : 0.0}};
    if (!r.csm)
      t->scalars.insert(t->scalars.end(), {{"unload_alpha", r.unloading.alpha}, {"unload_final_depth", r.unloading.final_depth},
                                           {"unload_exponent", r.unloading.exponent}, {"unload_stiffness", r.unloading.stiffness}});
    *result = t.release();
  });
}

int cc_indent_film(const cc_indent_data* data, const cc_indent_options* options, const cc_indent_film_options* film,
                   cc_indent_result** result) {
  return coatcontact::capi::guard([&] {
    need(result, "cc_indent_film", "result");
    const ci::FilmResult r = ci::film(test_of(need(data, "cc_indent_film", "data"), "cc_indent_film"),
                                      options_of(need(options, "cc_indent_film", "options")),
                                      film_of(need(film, "cc_indent_film", "film")));
    std::vector<double> delivered;
    for (const auto& s : r.status) delivered.push_back(s.delivered ? 1.0 : 0.0);
    auto t = std::make_unique<cc_indent_result>();
    t->columns = {{"depth", r.depth}, {"load", r.load}, {"stiffness", r.stiffness}, {"contact_depth", r.contact_depth},
                  {"contact_radius", r.contact_radius}, {"a_over_t", r.a_over_t}, {"E_apparent", r.apparent_modulus},
                  {"value", r.value}, {"value_error", r.value_error}, {"in_range", flags(r.in_range)}, {"delivered", delivered}};
    t->scalars = {{"mean", r.mean}, {"mean_error", r.mean_error}, {"points", static_cast<double>(r.points)},
                  {"rms_relative", r.rms_relative}, {"alpha", r.alpha}, {"range_min", r.range_min}, {"range_max", r.range_max}};
    *result = t.release();
  });
}

void cc_indent_result_destroy(cc_indent_result* result) { delete result; }

int cc_indent_result_rows(const cc_indent_result* result, long* rows) {
  return coatcontact::capi::guard([&] {
    const auto& r = need(result, "cc_indent_result_rows", "result");
    need(rows, "cc_indent_result_rows", "rows");
    *rows = r.columns.empty() ? 0 : static_cast<long>(r.columns.front().second.size());
  });
}

int cc_indent_result_column_count(const cc_indent_result* result, long* count) {
  return coatcontact::capi::guard([&] {
    need(count, "cc_indent_result_column_count", "count");
    *count = static_cast<long>(need(result, "cc_indent_result_column_count", "result").columns.size());
  });
}

int cc_indent_result_column_name(const cc_indent_result* result, long column, const char** name) {
  return coatcontact::capi::guard([&] {
    const auto& r = need(result, "cc_indent_result_column_name", "result");
    need(name, "cc_indent_result_column_name", "name");
    if (column < 0 || column >= static_cast<long>(r.columns.size()))
      throw InputError("cc_indent_result_column_name: column " + std::to_string(column) + " is out of range");
    *name = r.columns[column].first.c_str();
  });
}

int cc_indent_result_column(const cc_indent_result* result, const char* name, double* values, long capacity, long* length) {
  return coatcontact::capi::guard([&] {
    const auto& r = need(result, "cc_indent_result_column", "result");
    need(name, "cc_indent_result_column", "name");
    need(length, "cc_indent_result_column", "length");
    for (const auto& [n, v] : r.columns) {
      if (n != name) continue;
      *length = static_cast<long>(v.size());
      if (capacity < *length || (values == nullptr && !v.empty()))
        throw InputError("cc_indent_result_column: capacity " + std::to_string(capacity) + " < " + std::to_string(v.size()) + " rows");
      for (std::size_t i = 0; i < v.size(); ++i) values[i] = v[i];
      return;
    }
    throw InputError(std::string("cc_indent_result_column: no column '") + name + "'");
  });
}

int cc_indent_result_scalar_count(const cc_indent_result* result, long* count) {
  return coatcontact::capi::guard([&] {
    need(count, "cc_indent_result_scalar_count", "count");
    *count = static_cast<long>(need(result, "cc_indent_result_scalar_count", "result").scalars.size());
  });
}

int cc_indent_result_scalar(const cc_indent_result* result, long entry, const char** name, double* value) {
  return coatcontact::capi::guard([&] {
    const auto& r = need(result, "cc_indent_result_scalar", "result");
    need(name, "cc_indent_result_scalar", "name");
    need(value, "cc_indent_result_scalar", "value");
    if (entry < 0 || entry >= static_cast<long>(r.scalars.size()))
      throw InputError("cc_indent_result_scalar: entry " + std::to_string(entry) + " is out of range");
    *name = r.scalars[entry].first.c_str();
    *value = r.scalars[entry].second;
  });
}

}  // extern "C"
