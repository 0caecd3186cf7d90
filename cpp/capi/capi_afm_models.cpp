// The C interface of the AFM force-model registry (coatcontact_afm.h: cc_afm_model_*): each
// model's name, aliases, default segment, whether it needs the spring constant, and its
// parameter table on a half-space and on a coating, read from fit::afm_models() so that a
// binding's vocabulary follows the registry. Runs inside capi::guard.
#include <memory>
#include <string>
#include <vector>

#include "capi_afm.hpp"
#include "capi_guard.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/force_curve.hpp"

namespace fit = coatcontact::fit;
using coatcontact::capi::checked_index;
using coatcontact::capi::guard;
using coatcontact::capi::require;

namespace {

// The strings the C structs point to, made once from the registry (which does not change).
struct ModelText {
  std::string aliases, default_free, coating_default_free;
  std::vector<std::string> names[2];  // the parameters' names on a half-space, a coating
  std::vector<const fit::AfmParameterInfo*> parameters[2];
};

const std::vector<ModelText>& model_texts() {
  static const std::vector<ModelText> texts = [] {
    std::vector<ModelText> out;
    for (const fit::AfmModelInfo* m : fit::afm_models()) {
      ModelText t;
      for (const std::string& a : m->aliases) t.aliases += (t.aliases.empty() ? "" : ",") + a;
      t.default_free = fit::afm_free_default(*m, false);
      t.coating_default_free = fit::afm_free_default(*m, true);
      for (const bool coated : {false, true}) {
        for (const fit::AfmParameterInfo& p : m->parameters) {
          if (p.coating_only && !coated) continue;
          t.names[coated].push_back(fit::afm_parameter_name(p, coated));
          t.parameters[coated].push_back(&p);
        }
      }
      out.push_back(std::move(t));
    }
    return out;
  }();
  return texts;
}

std::size_t model_index(long model, const char* function) {
  return checked_index(model, fit::afm_models().size(), function, "model");
}

void check_coated(int coated, const char* function) {
  if (coated != 0 && coated != 1) {
    throw coatcontact::InputError(std::string(function) + ": coated " + std::to_string(coated) +
                                  " is not allowed; expected 0 (half-space) or 1 (coating)");
  }
}

}  // namespace

extern "C" {

int cc_afm_model_count(long* count) {
  return guard([&] {
    require(count, "cc_afm_model_count", "count");
    *count = static_cast<long>(fit::afm_models().size());
  });
}

int cc_afm_model_get(long model, cc_afm_model_info* info) {
  return guard([&] {
    const std::size_t k = model_index(model, "cc_afm_model_get");
    require(info, "cc_afm_model_get", "info");
    const fit::AfmModelInfo& m = *fit::afm_models()[k];
    const ModelText& t = model_texts()[k];
    cc_afm_model_info o{};
    o.name = m.name.c_str();
    o.title = m.title.c_str();
    o.aliases = t.aliases.c_str();
    o.segment = coatcontact::afm::segment_kind_name(m.segment);
    o.needs_spring = m.needs_spring;
    o.default_free = t.default_free.c_str();
    o.coating_default_free = t.coating_default_free.c_str();
    *info = o;
  });
}

int cc_afm_model_parameter_count(long model, int coated, long* count) {
  return guard([&] {
    const std::size_t k = model_index(model, "cc_afm_model_parameter_count");
    check_coated(coated, "cc_afm_model_parameter_count");
    require(count, "cc_afm_model_parameter_count", "count");
    *count = static_cast<long>(model_texts()[k].names[coated].size());
  });
}

int cc_afm_model_parameter(long model, int coated, long parameter, const char** name, const char** unit, int* free_by_default) {
  return guard([&] {
    const char* f = "cc_afm_model_parameter";
    const std::size_t k = model_index(model, f);
    check_coated(coated, f);
    require(name, f, "name");
    const ModelText& t = model_texts()[k];
    const std::size_t p = checked_index(parameter, t.names[coated].size(), f, "parameter");
    *name = t.names[coated][p].c_str();
    if (unit) *unit = t.parameters[coated][p]->unit.c_str();
    if (free_by_default) *free_by_default = t.parameters[coated][p]->free_by_default;
  });
}

}  // extern "C"
