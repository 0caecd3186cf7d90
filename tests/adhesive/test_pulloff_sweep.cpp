// The pull-off sweep (THEORY.md section 5, "Pull-off sweeps"): the JKR pull-offs of many eta
// read from one verified table over the etas' whole a/t range, against an independent
// computation: each eta's pull-off on its own decade table (the `pulloff --direct` path) at a
// 100x tighter solver tolerance. Every printed quantity (P, a_bar, D under load and
// displacement control) within its *_err estimate plus the reference's own, every row's
// reduced_err <= the requested tolerance, and the estimates finite and non-zero (so the check
// can fail). 3 material pairs x 25 eta over 0.01..100: a soft and a stiff film, a two-layer stack.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "materials.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/reduced_table.hpp"

namespace {

using coatcontact::AdhesiveModel;
using coatcontact::Layer;
using coatcontact::Material;
using coatcontact::Pulloff;
using coatcontact::PulloffPoint;
using coatcontact::Stack;
using coatcontact::Substrate;

constexpr double kTolerance = coatcontact::kDefaultTolerance;
constexpr double kReferenceTolerance = 1e-10;

using coatcontact::test::elastic;
using coatcontact::test::material;

struct Worst {
  double ratio = 0.0;     // largest |difference| / (estimate + reference estimate)
  double relative = 0.0;  // largest estimate / max(1, |value|)
};

void check_point(const std::string& where, const PulloffPoint& sweep, const PulloffPoint& reference, Worst& worst) {
  const double values[3][4] = {{sweep.load, reference.load, sweep.load_err, reference.load_err},
                               {sweep.a_bar, reference.a_bar, sweep.a_bar_err, reference.a_bar_err},
                               {sweep.penetration, reference.penetration, sweep.penetration_err,
                                reference.penetration_err}};
  const char* names[3] = {"P", "a_bar", "D"};
  for (int q = 0; q < 3; ++q) {
    const double difference = std::abs(values[q][0] - values[q][1]);
    const double allowed = values[q][2] + values[q][3];
    check::that(std::isfinite(values[q][2]) && values[q][2] > 0.0, where + " " + names[q] + "_err finite and > 0");
    check::below(difference, allowed, where + " " + names[q] + " within its estimate of the reference");
    worst.ratio = std::max(worst.ratio, difference / allowed);
    worst.relative = std::max(worst.relative, values[q][2] / std::max(1.0, std::abs(values[q][0])));
  }
  check::below(sweep.reduced_err, kTolerance, where + " reduced_err <= tol");
}

void check_pair(const std::string& name, const Stack& stack) {
  std::vector<double> etas;
  for (int i = 0; i < 25; ++i) etas.push_back(std::pow(10.0, -2.0 + 4.0 * i / 24.0));
  const coatcontact::ReducedSolver solver(stack);
  std::string why_not;
  const std::unique_ptr<AdhesiveModel> built = coatcontact::pulloff_sweep_model(solver, kTolerance, etas, &why_not);
  check::that(built != nullptr, name + ": the sweep's table built (" + why_not + ")");
  if (!built) return;
  const AdhesiveModel& sweep = *built;
  check::that(sweep.table().ranged(), name + ": one table over the whole range");
  const AdhesiveModel reference(solver, kReferenceTolerance);  // decades, as each eta reaches them
  Worst worst;
  for (double eta : etas) {
    const Pulloff s = sweep.pulloff(eta);
    const Pulloff r = reference.pulloff(eta);
    const std::string where = name + ", eta " + std::to_string(eta);
    check::that(s.warnings == r.warnings, where + ": the same warnings");
    check_point(where + ", load control:", s.load_control, r.load_control, worst);
    check_point(where + ", displacement control:", s.displacement_control, r.displacement_control, worst);
  }
  // An estimate that is right but useless would pass the above: the solver's 1e-8 carried to a
  // pull-off is a few 1e-8 (THEORY.md), so 1e-6 would mean something is wrong.
  check::below(worst.relative, 1e-6, name + ": largest estimate relative to the value");
  std::printf("%-24s %zu solves (reference %zu); largest difference / allowance %.3f, largest estimate %.2e\n",
              name.c_str(), sweep.table().source_evaluations(), reference.table().source_evaluations(), worst.ratio,
              worst.relative);
}

}  // namespace

int main() {
  check_pair("soft film (E1/E0 = 0.1)", Stack::film_on(material(0.1, 0.25), elastic(1.0, 0.25)));
  check_pair("stiff film (E1/E0 = 10)", Stack::film_on(material(10.0, 0.25), elastic(1.0, 0.25)));
  check_pair("stack 1 + 2 on E0 = 5", coatcontact::test::soft_on_stiff_layers());
  return check::exit_code();
}
