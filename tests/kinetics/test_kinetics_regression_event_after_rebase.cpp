// Regression: an event found in the step right after the ODE's local time was rebased was
// bracketed from the step's start in the old local time (lo > hi): "cannot bracket an event of
// the kinetics". It struck the slow retracts of a 70-degree cone on a 1 MPa film on glass
// (`kinetics --shape cone:70deg ... --retract-speeds 1e-20,1e-18`). The same runs, in SI, are
// also THEORY.md section 14 check 1 for the cone against an independent solver: the slow
// retract's most tensile force equals the load-controlled pull-off of ShapeContact (the shape
// solver's own solves at every radius, not the table the kinetics interpolates).
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <vector>

#include "check.hpp"
#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/shape_contact.hpp"
#include "coatcontact/shape_solver.hpp"

using namespace coatcontact;

namespace {
// The table's interpolation against the shape solver's direct solves, both at tolerance 1e-8,
// plus the slow limit's own deviation (~V^0.46): 3.3e-7 measured at 1e-20 m/s.
constexpr double kTableAgainstSolver = 1e-6;
}  // namespace

int main() {
  Material film{1e6, 0.49};
  Substrate glass;
  glass.material = Material{70e9, 0.22};
  const Stack stack = Stack::film_on(film, glass);
  const double beta = 70.0 * 3.14159265358979323846 / 180.0;
  KineticsSetupSI setup;
  setup.tip = KineticsTip::kCone;
  setup.half_angle = beta;
  setup.thickness = 50e-6;
  setup.work = 0.04;
  setup.v_star = 1e-6;
  setup.n = 0.6;
  setup.spring = 500.0;
  setup.protocol.resize(3);
  setup.protocol[0] = {DriveSegment::Kind::kApproach, 1e-6, 0.0, 1e-3, true};
  setup.protocol[1] = {DriveSegment::Kind::kDwell, 0.0, 1.0, 0.0, false};
  setup.protocol[2] = {DriveSegment::Kind::kRetract, 1e-5, 0.0, 0.0, false};
  const ReducedSolver solver(stack);
  const AdhesiveModel model(solver);
  std::vector<KineticsResultSI> runs;
  bool ran = true;
  try {
    runs = simulate_kinetics_si(model, setup, {1e-20, 1e-18}, false);
  } catch (const std::exception& e) {
    ran = false;
    std::printf("%s\n", e.what());
  }
  check::that(ran, "slow cone retracts run past a rebase of the local time");
  const ShapeSolver shapes(stack);
  const ShapeContact contact(shapes, make_cone(beta), setup.thickness, setup.work, kDefaultTolerance);
  const ShapePulloff qs = contact.pulloff(setup.spring);
  std::printf("ShapeContact: load-control pull-off %.12g N at a = %.6g m; spring jump at a = %.6g m\n", qs.load.force,
              qs.load.radius, qs.spring.radius);
  check::that(qs.spring.radius < qs.load.radius, "the spring's jump lies below the force minimum");
  if (ran) {
    for (const KineticsResultSI& r : runs) {
      std::printf("kinetics, retract %g m/s: pull-off %.12g N at a = %.6g m\n", r.retract_speed, r.pulloff.force,
                  r.pulloff.radius);
      check::close(r.pulloff.force, qs.load.force, kTableAgainstSolver,
                   "cone slow-limit pull-off against ShapeContact");
    }
  }
  return check::exit_code();
}
