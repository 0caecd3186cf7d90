// JKR through the cantilever (THEORY.md section 15, "Adhesive retract"): JKR of a sphere on the
// half-space or a coating (section 5, steps 3-4) as a law on the reduced variables; the branch
// the spring holds, the search and the errors are the shared adhesive fit's (afm_adhesive_model.cpp).
#include <cmath>
#include <utility>

#include "afm_internal.hpp"
#include "coatcontact/detail/format.hpp"

namespace coatcontact::fit::internal {

namespace {
constexpr double kPi = 3.14159265358979323846;
using coatcontact::detail::short_text;
}  // namespace

void afm_jkr_lambda(const AfmFitProblem& problem, AfmFitResult& r) {
  afm_tabor_maugis(problem, r);
  const double z0 = problem.surface_force_range;
  if (r.maugis_lambda < kJkrMinimumLambda) {
    r.warnings.push_back("Maugis's lambda = " + short_text(r.maugis_lambda) + " (Tabor's mu = " + short_text(r.tabor_mu) +
                         ", surface-force range z0 = " + short_text(z0) + " m) is below " + short_text(kJkrMinimumLambda) +
                         ": outside JKR's range; fit the Maugis-Dugdale model (--model md)");
  }
}

const ReducedLaw& jkr_law() {
  static const ReducedLaw law{
      "JKR",
      // (delta, F) at contact radius a [THEORY.md section 5, steps 3-4].
      [](double a, const ReducedAt& v, double reduced, double work, double radius) -> std::pair<double, double> {
        const double fp = -std::sqrt(2.0 * kPi * a * work / reduced) / v.gamma1;  // delta_fp
        return {a * a / radius * v.delta_s + fp, a * a * a * reduced / (2.0 * radius) * v.pi_s + 2.0 * a * reduced * v.e_eq * fp};
      },
      nullptr, 1.5, [](const AfmFitProblem& p, AfmFitResult& r) { afm_jkr_lambda(p, r); }};
  return law;
}

std::vector<double> afm_jkr_model_force(const AfmFitProblem& problem, const std::vector<double>& z) {
  return afm_reduced_model_force(problem, z, jkr_law());
}

AfmFitResult afm_fit_jkr(const std::vector<double>& z_data, const std::vector<double>& f_data, const AfmFitProblem& problem,
                         int free_count) {
  return afm_fit_adhesive(z_data, f_data, problem, free_count, nullptr);
}

const AfmModelInfo& afm_model_jkr() {
  static const AfmModelInfo model{
      "jkr",
      {},
      "JKR",
      "adhesive JKR fit through the cantilever",
      true,
      afm::SegmentKind::kRetract,
      afm_parameter_table({afm_work_parameter()}, true),
      afm_fit_jkr,
      afm_jkr_model_force,
      [](const AfmFitProblem&, bool batch) -> std::string {
        return std::string("F = b + m (z - z_c) + F_JKR(z_c - z), F_JKR: JKR of the sphere on the sample on the branch stable ") +
               (batch ? "under the cantilever's spring k (each curve's), 0 past its jump-off" : "under the spring k (0 past its jump-off)");
      },
      "JKR needs lambda >= " + short_text(kJkrMinimumLambda),
      "adhesive: JKR of a sphere on the half-space or the coating through the cantilever's spring k, the stable branch "
      "and its jump-off; default segment retract"};
  return model;
}

}  // namespace coatcontact::fit::internal
