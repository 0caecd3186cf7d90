// The AFM force models (THEORY.md section 15) as entries of one registry: each model is one
// file (cpp/fit/afm_<name>_model.cpp) that fills an AfmModelInfo (its parameter table, its fit
// and model force, its header texts) and one line in afm_model_registry.cpp's list. The CLI
// (--model, --free, help), the batch (columns), the C API and Python take the names and the
// parameter facts from here.
#pragma once
#include <string>
#include <vector>

#include "coatcontact/afm_fit.hpp"
#include "coatcontact/force_curve.hpp"

namespace coatcontact::fit {

// One parameter of a model: its name as --free and Python's free= take it ("E" is "E1" on a
// coating: afm_parameter_name), its SI unit, free by default or fixed, the open interval of
// allowed values, and where AfmFree, AfmFitResult hold it.
struct AfmParameterInfo {
  std::string name;
  std::string unit;
  bool free_by_default = false;
  double lower = 0.0, upper = 0.0;
  bool coating_only = false;  // t: a parameter of a coating's fit only
  bool own = false;           // the force law's own (w), not the sample's or the curve's
  bool AfmFree::*free = nullptr;
  double AfmFitResult::*value = nullptr;
  double AfmFitResult::*error = nullptr;
};

struct AfmModelInfo {
  std::string name;                  // as --model and model= take it: "hertz", "jkr", ...
  std::vector<std::string> aliases;  // other names accepted ("maugis-dugdale")
  std::string title;                 // "JKR", "Maugis-Dugdale" (headers, messages)
  std::string summary;               // "adhesive JKR fit through the cantilever" (headers)
  // Through the cantilever: the spring constant k (the user's, else the curve's, else flag
  // calibration), a sphere tip, w, z0 and the tilt options; the jump-off, mu and lambda reported.
  bool needs_spring = false;
  afm::SegmentKind segment = afm::SegmentKind::kApproach;  // fitted by default
  // Columns of a batch in this order; E, t, contact_point, baseline first, tilt last.
  std::vector<AfmParameterInfo> parameters;
  // The fit (afm_fit has checked the data and counted the free parameters) and the model force
  // at tip positions z for the problem's values.
  AfmFitResult (*fit)(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                      int free_count) = nullptr;
  std::vector<double> (*model_force)(const AfmFitProblem& problem, const std::vector<double>& z) = nullptr;
  // The headers' "model" line (batch: a map's header) and, for adhesive models, the note on
  // Maugis's lambda (the model's range).
  std::string (*formula)(const AfmFitProblem& problem, bool batch) = nullptr;
  std::string lambda_note;
  std::string help;  // one phrase for --model's help ("adhesionless Hertz/Sneddon, any tip, default")

  AfmModel model() const { return AfmModel(name.c_str()); }
};

// Every model, in the registry's order.
const std::vector<const AfmModelInfo*>& afm_models();
// The model named `name` (or an alias). InputError "<option>: '<name>' is not a model; allowed:
// hertz, jkr, ..." (with " (did you mean X?)" within two edits of one).
const AfmModelInfo& afm_model_by_name(const std::string& name, const std::string& option = "model");
// "hertz, jkr, md, dmt" (separator ", "), or with another separator and quotes ("'hertz', ...").
std::string afm_model_names(const std::string& separator = ", ", const std::string& quote = "");
// The adhesive models' names ("jkr, md or dmt").
std::string afm_spring_model_names();

// A parameter's name in a fit of this sample: "E1" for the modulus on a coating.
std::string afm_parameter_name(const AfmParameterInfo& p, bool coated);
// The model's parameter `name` in a fit of this sample, or null.
const AfmParameterInfo* afm_parameter(const AfmModelInfo& model, const std::string& name, bool coated);
// "E, contact_point, baseline, tilt": the names --free may list (the sample's).
std::string afm_free_allowed(const AfmModelInfo& model, bool coated);
// "E,w,contact_point,baseline,tilt": the free-by-default parameters, the modulus and the law's
// own first.
std::string afm_free_default(const AfmModelInfo& model, bool coated);
// The number of free parameters of the model in `free` (parameters it lacks are not counted).
int afm_free_count(const AfmModelInfo& model, const AfmFree& free);

}  // namespace coatcontact::fit
