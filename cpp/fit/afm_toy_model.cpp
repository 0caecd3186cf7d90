// Seam measurement only: DMT with half the attraction, pi w R (not a physical model).
#include <optional>
#include <string>
#include <utility>

#include "afm_internal.hpp"

namespace coatcontact::fit::internal {

namespace {

constexpr double kPi = 3.14159265358979323846;

const ReducedLaw& toy_law() {
  static const ReducedLaw law{
      "toy",
      [](double a, const ReducedAt& v, double reduced, double work, double radius) -> std::pair<double, double> {
        return {a * a / radius * v.delta_s, a * a * a * reduced / (2.0 * radius) * v.pi_s - kPi * work * radius};
      },
      [](double, double work, double radius) -> std::optional<std::pair<double, double>> {
        return std::pair<double, double>{0.0, -kPi * work * radius};
      },
      1.0, [](const AfmFitProblem& problem, AfmFitResult& r) { afm_tabor_maugis(problem, r); }};
  return law;
}

AfmFitResult fit_toy(const std::vector<double>& z, const std::vector<double>& f, const AfmFitProblem& p, int n) {
  return afm_fit_adhesive(z, f, p, n, nullptr, &toy_law());
}
std::vector<double> toy_force(const AfmFitProblem& p, const std::vector<double>& z) { return afm_reduced_model_force(p, z, toy_law()); }

}  // namespace

const AfmModelInfo& afm_model_toy() {
  static const AfmModelInfo model{
      "toy", {}, "toy", "adhesive toy fit through the cantilever", true, afm::SegmentKind::kRetract,
      afm_parameter_table({afm_work_parameter()}, true), fit_toy, toy_force,
      [](const AfmFitProblem&, bool) -> std::string { return "F = b + m (z - z_c) + F_H(z_c - z) - pi w R in contact"; },
      "toy: no range", "DMT with half the attraction (seam test)"};
  return model;
}

}  // namespace coatcontact::fit::internal
