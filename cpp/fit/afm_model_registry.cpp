// The registry of AFM force models (coatcontact/afm_models.hpp): the list, the lookup by name
// and the parameter tables' shared rows.
#include "coatcontact/afm_models.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>

#include "afm_internal.hpp"
#include "coatcontact/errors.hpp"

// The models, one line each (a new model: its line above the last): the model's file defines
// internal::afm_model_<name>(); the list's order is the order of help texts and error messages.
#define COATCONTACT_AFM_MODELS(X) \
  X(hertz)                        \
  X(jkr)                          \
  X(md)                           \
  X(dmt)                          \
  /* end of the list */

namespace coatcontact::fit {

namespace internal {
#define COATCONTACT_DECLARE(name) const AfmModelInfo& afm_model_##name();
COATCONTACT_AFM_MODELS(COATCONTACT_DECLARE)
#undef COATCONTACT_DECLARE

std::vector<AfmParameterInfo> afm_parameter_table(const std::vector<AfmParameterInfo>& own, bool tilt_free) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<AfmParameterInfo> table = {
      {"E", "Pa", true, 0.0, inf, false, false, &AfmFree::modulus, &AfmFitResult::modulus, &AfmFitResult::modulus_error},
      {"t", "m", false, 0.0, inf, true, false, &AfmFree::thickness, &AfmFitResult::thickness, &AfmFitResult::thickness_error},
      {"contact_point", "m", true, -inf, inf, false, false, &AfmFree::contact_point, &AfmFitResult::contact_point,
       &AfmFitResult::contact_point_error},
      {"baseline", "N", true, -inf, inf, false, false, &AfmFree::baseline, &AfmFitResult::baseline, &AfmFitResult::baseline_error},
  };
  table.insert(table.end(), own.begin(), own.end());
  table.push_back({"tilt", "N/m", tilt_free, -inf, inf, false, false, &AfmFree::tilt, &AfmFitResult::tilt, &AfmFitResult::tilt_error});
  return table;
}

AfmParameterInfo afm_work_parameter() {
  return {"w", "J/m2", true, 0.0, std::numeric_limits<double>::infinity(), false, true, &AfmFree::work, &AfmFitResult::work,
          &AfmFitResult::work_error};
}

}  // namespace internal

const std::vector<const AfmModelInfo*>& afm_models() {
#define COATCONTACT_ENTRY(name) &internal::afm_model_##name(),
  static const std::vector<const AfmModelInfo*> models = {COATCONTACT_AFM_MODELS(COATCONTACT_ENTRY)};
#undef COATCONTACT_ENTRY
  return models;
}

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

const AfmModelInfo& afm_model_by_name(const std::string& name, const std::string& option) {
  const AfmModelInfo* best = nullptr;
  std::size_t best_distance = 3;
  for (const AfmModelInfo* model : afm_models()) {
    if (model->name == name || std::count(model->aliases.begin(), model->aliases.end(), name) > 0) return *model;
    const std::size_t distance = name.size() > 64 ? best_distance : edit_distance(name, model->name);
    if (distance < best_distance && distance < model->name.size()) best_distance = distance, best = model;
  }
  throw InputError(option + ": '" + name.substr(0, 60) + "' is not a model; allowed: " + afm_model_names() +
                   (best ? " (did you mean " + best->name + "?)" : ""));
}

const AfmModelInfo& AfmModel::info() const { return afm_model_by_name(name_); }

std::string afm_model_names(const std::string& separator, const std::string& quote) {
  std::string text;
  for (const AfmModelInfo* model : afm_models()) text += (text.empty() ? "" : separator) + quote + model->name + quote;
  return text;
}

std::string afm_spring_model_names() {
  std::vector<std::string> names;
  for (const AfmModelInfo* model : afm_models()) {
    if (model->needs_spring) names.push_back(model->name);
  }
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k) text += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return text;
}

std::string afm_parameter_name(const AfmParameterInfo& p, bool coated) {
  return coated && p.free == &AfmFree::modulus ? p.name + "1" : p.name;
}

const AfmParameterInfo* afm_parameter(const AfmModelInfo& model, const std::string& name, bool coated) {
  for (const AfmParameterInfo& p : model.parameters) {
    if ((coated || !p.coating_only) && afm_parameter_name(p, coated) == name) return &p;
  }
  return nullptr;
}

std::string afm_free_allowed(const AfmModelInfo& model, bool coated) {
  std::string text;
  for (const AfmParameterInfo& p : model.parameters) {
    if (coated || !p.coating_only) text += (text.empty() ? "" : ", ") + afm_parameter_name(p, coated);
  }
  return text;
}

std::string afm_free_default(const AfmModelInfo& model, bool coated) {
  std::vector<const AfmParameterInfo*> order;
  for (int pass = 0; pass < 3; ++pass) {  // the modulus, the law's own, the others
    for (const AfmParameterInfo& p : model.parameters) {
      const bool modulus = p.free == &AfmFree::modulus;
      if (p.free_by_default && (coated || !p.coating_only) && (pass == 0 ? modulus : pass == 1 ? p.own && !modulus : !p.own && !modulus)) {
        order.push_back(&p);
      }
    }
  }
  std::string text;
  for (const AfmParameterInfo* p : order) text += (text.empty() ? "" : ",") + afm_parameter_name(*p, coated);
  return text;
}

int afm_free_count(const AfmModelInfo& model, const AfmFree& free) {
  int count = 0;
  for (const AfmParameterInfo& p : model.parameters) count += int(free.*p.free);
  return count;
}

}  // namespace coatcontact::fit
