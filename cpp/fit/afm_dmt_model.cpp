// DMT through the cantilever (THEORY.md section 15, "Adhesive retract: DMT through the
// cantilever"): the adhesionless contact of section 5 (steps 1-2) less the rigid sphere's
// attraction 2 pi w R while in contact; the branch, search and errors are the JKR fit's
// (afm_adhesive_model.cpp), with the law's end a -> 0 as the jump-off for every spring.
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "afm_internal.hpp"
#include "coatcontact/detail/format.hpp"

namespace coatcontact::fit::internal {

namespace {

constexpr double kPi = 3.14159265358979323846;

const ReducedLaw& dmt_law() {
  static const ReducedLaw law{
      "DMT",
      // delta = (a^2/R) Delta_s, F = (a^3 E1*/(2R)) Pi_s - 2 pi w R.
      [](double a, const ReducedAt& v, double reduced, double work, double radius) -> std::pair<double, double> {
        return {a * a / radius * v.delta_s, a * a * a * reduced / (2.0 * radius) * v.pi_s - 2.0 * kPi * work * radius};
      },
      [](double, double work, double radius) -> std::optional<std::pair<double, double>> {
        return std::pair<double, double>{0.0, -2.0 * kPi * work * radius};
      },
      2.0,
      [](const AfmFitProblem& problem, AfmFitResult& r) {
        afm_tabor_maugis(problem, r);
        if (r.maugis_lambda > kDmtMaximumLambda) {
          r.warnings.push_back("Maugis's lambda = " + coatcontact::detail::short_text(r.maugis_lambda) +
                               " (surface-force range z0 = " + coatcontact::detail::short_text(problem.surface_force_range) +
                               " m) is above " + coatcontact::detail::short_text(kDmtMaximumLambda) +
                               ": outside DMT's range; compare the jkr or md fit");
        }
      }};
  return law;
}

AfmFitResult afm_fit_dmt(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                         int free_count) {
  return afm_fit_adhesive(z, force, problem, free_count, nullptr, &dmt_law());
}

std::vector<double> afm_dmt_model_force(const AfmFitProblem& problem, const std::vector<double>& z) {
  return afm_reduced_model_force(problem, z, dmt_law());
}

}  // namespace

const AfmModelInfo& afm_model_dmt() {
  static const AfmModelInfo model{
      "dmt",
      {},
      "DMT",
      "adhesive DMT fit through the cantilever",
      true,
      afm::SegmentKind::kRetract,
      afm_parameter_table({afm_work_parameter()}, true),
      afm_fit_dmt,
      afm_dmt_model_force,
      [](const AfmFitProblem&, bool batch) -> std::string {
        return std::string("F = b + m (z - z_c) + F_DMT(z_c - z), F_DMT: the adhesionless force of the sphere on the sample "
                           "less 2 pi w R while in contact") +
               (batch ? ", 0 past the contact point" : " (0 past the contact point, where any spring lets go)");
      },
      "DMT needs lambda <= " + coatcontact::detail::short_text(kDmtMaximumLambda),
      "the adhesionless contact less 2 pi w R through the cantilever: lambda below ~0.1"};
  return model;
}

}  // namespace coatcontact::fit::internal
