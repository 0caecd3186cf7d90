// The registry of AFM force models (coatcontact/afm_models.hpp, THEORY.md section 15): every
// model listed once with a consistent parameter table, the models that need the spring constant
// exactly the adhesive ones (checked on the model force itself: a tensile force past contact),
// and an unknown name an InputError naming the value and the allowed names.
#include <set>
#include <string>
#include <vector>

#include "../common/check.hpp"
#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/errors.hpp"

namespace fit = coatcontact::fit;
using coatcontact::InputError;

namespace {

// The most tensile model force (less the baseline) of the model on a soft half-space under a
// 10 um sphere with w = 10 mJ/m2 through a 0.1 N/m lever, over indentations 0..50 nm.
double most_tensile(const fit::AfmModelInfo& model) {
  fit::AfmFitProblem p;
  p.model = model.model();
  p.tip = fit::afm_paraboloid(10e-6);
  p.modulus = 1e6;
  p.poisson = 0.5;
  p.work = 10e-3;
  p.spring_constant = 0.1;
  p.contact_point = 0.0;
  p.baseline = 1e-9;
  std::vector<double> z;
  for (int i = 0; i <= 50; ++i) z.push_back(-1e-9 * i);
  double least = 0.0;
  for (double f : fit::afm_model_force(p, z)) least = std::min(least, f - p.baseline);
  return least;
}

}  // namespace

int main() {
  const std::vector<const fit::AfmModelInfo*>& models = fit::afm_models();
  check::that(models.size() >= 4, "the registry holds the four built-in models");

  // Every name and alias once; each built-in constant finds its entry.
  std::set<std::string> names;
  for (const fit::AfmModelInfo* m : models) {
    check::that(names.insert(m->name).second, "model name unique: " + m->name);
    for (const std::string& alias : m->aliases) check::that(names.insert(alias).second, "alias unique: " + alias);
  }
  for (const fit::AfmModel& builtin : {fit::AfmModel::kHertz, fit::AfmModel::kJkr, fit::AfmModel::kMd, fit::AfmModel::kDmt}) {
    check::that(builtin.info().name == builtin.name(), std::string("built-in model listed: ") + builtin.name());
    check::that(&fit::afm_model_by_name(builtin.name()) == &builtin.info(), "lookup by name gives the same entry");
  }
  check::that(&fit::afm_model_by_name("maugis-dugdale") == &fit::AfmModel::kMd.info(), "alias maugis-dugdale is md");

  for (const fit::AfmModelInfo* m : models) {
    const std::string tag = m->name + ": ";
    check::that(m->fit != nullptr && m->model_force != nullptr && m->formula != nullptr, tag + "entry points set");
    check::that(!m->title.empty() && !m->summary.empty() && !m->help.empty(), tag + "texts set");
    std::set<std::string> parameter_names;
    bool has_work = false;
    for (const fit::AfmParameterInfo& p : m->parameters) {
      check::that(parameter_names.insert(p.name).second, tag + "parameter name unique: " + p.name);
      check::that(p.lower < p.upper, tag + p.name + ": bounds ordered");
      check::that(!p.unit.empty(), tag + p.name + ": has a unit");
      check::that(p.free != nullptr && p.value != nullptr && p.error != nullptr, tag + p.name + ": where it is held");
      has_work = has_work || p.free == &fit::AfmFree::work;
    }
    for (const char* shared : {"E", "t", "contact_point", "baseline", "tilt"}) {
      check::that(parameter_names.count(shared) == 1, tag + "the shared parameter " + shared);
    }
    check::that(m->parameters.front().name == "E" && m->parameters.back().name == "tilt", tag + "E first, tilt last");
    // The default free list names parameters of the table that are free by default, each once.
    for (const bool coated : {false, true}) {
      const std::string list = fit::afm_free_default(*m, coated);
      std::size_t start = 0, count = 0;
      while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const fit::AfmParameterInfo* p = fit::afm_parameter(*m, list.substr(start, comma - start), coated);
        check::that(p != nullptr && p->free_by_default, tag + "default free '" + list.substr(start, comma - start) + "'");
        ++count;
        start = comma + 1;
      }
      std::size_t expected = 0;
      for (const fit::AfmParameterInfo& p : m->parameters) expected += p.free_by_default && (coated || !p.coating_only);
      check::that(count == expected, tag + "default free list complete");
    }
    // Needs the spring <=> adhesive: has w, and its force turns tensile past contact (the
    // adhesionless force is never below the baseline).
    const double tensile = most_tensile(*m);
    check::that(m->needs_spring == has_work, tag + "needs the spring exactly when w is a parameter");
    check::that(m->needs_spring == (tensile < -1e-12), tag + "needs the spring exactly when the force turns tensile (" +
                                                           std::to_string(tensile) + " N)");
    check::that(m->needs_spring == (m->segment == coatcontact::afm::SegmentKind::kRetract),
                tag + "adhesive models fit the retract by default");
  }

  // The batch's columns follow the table: every free parameter, in table order, E1 on a coating.
  fit::AfmFitProblem p;
  p.model = fit::AfmModel::kJkr;
  p.free = {true, true, true, false, true, true};
  p.coating = fit::AfmCoating{};
  std::vector<std::string> columns;
  for (const fit::AfmBatchParameter& c : fit::afm_batch_parameters(p)) columns.push_back(c.name + " [" + c.unit + "]");
  check::that(columns == std::vector<std::string>{"E1 [Pa]", "contact_point [m]", "baseline [N]", "w [J/m2]", "tilt [N/m]"},
              "batch columns of a coated jkr fit");
  check::that(fit::afm_free_allowed(fit::AfmModel::kHertz.info(), false) == "E, contact_point, baseline, tilt",
              "hertz on a half-space: --free names");

  // Unknown names: the option, the value and the allowed names (and the near miss).
  check::throws<InputError>([] { fit::afm_model_by_name("lj", "--model"); },
                            {"--model: 'lj' is not a model; allowed: ", fit::afm_model_names()});
  check::throws<InputError>([] { fit::afm_model_by_name("jrk"); }, {"'jrk'", "did you mean jkr?"});
  check::throws<InputError>(
      [] {
        fit::AfmFitProblem toy;
        toy.model = fit::AfmModel("toy");
        toy.tip = fit::afm_paraboloid(1e-6);
        fit::afm_fit({0.0, -1e-9, -2e-9, -3e-9, -4e-9}, {0.0, 0.0, 1e-9, 2e-9, 3e-9}, toy);
      },
      {"'toy' is not a model", "hertz"});
  return check::exit_code();
}
