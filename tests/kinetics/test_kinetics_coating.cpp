// Crack kinetics on the paper's soft film (E1*/E0* = 0.1, nu = 0.25, eta = 1) with the real
// ReducedSolver (THEORY.md section 14, checks 1, 3, 4 on a coating).
#include <cmath>
#include <cstdio>
#include <vector>

#include "check.hpp"
#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/reduced.hpp"

using namespace coatcontact;

namespace {

constexpr double kN = 0.6;
// See test_kinetics_homogeneous.cpp: next-order correction of the difference estimate
// (2.9e-4 measured at V = 1e8..1e10 on this film).
constexpr double kExponentDifferences = 1e-3;
// Energy balance relative to the drive work (1.3e-7 measured).
constexpr double kEnergyBalance = 1e-6;

std::vector<DriveSegment> protocol(double retract) {
  std::vector<DriveSegment> p(3);
  p[0].kind = DriveSegment::Kind::kApproach;
  p[0].rate = 1.0;
  p[0].target_load = 1.0;
  p[1].kind = DriveSegment::Kind::kDwell;
  p[1].duration = 1.0;
  p[2].kind = DriveSegment::Kind::kRetract;
  p[2].rate = retract;
  return p;
}

}  // namespace

int main() {
  Material film{1.0, 0.25};
  Substrate substrate;
  substrate.material = Material{10.0, 0.25};
  const Stack stack = Stack::film_on(film, substrate);
  const ReducedSolver solver(stack);
  const AdhesiveModel model(solver);
  const double eta = 1.0;
  const Pulloff qs = model.pulloff(eta);
  const SpringPulloff jump = model.pulloff_spring(eta, 1.0);
  // Check 1: the spring's jump lies below the P minimum, so the slow reading is P_load.
  check::that(jump.point.a_bar < qs.load_control.a_bar, "k_bar = 1 jump below the P minimum");
  const auto slow = simulate_kinetics(model, eta, KineticLaw{}, 1.0, protocol(1e-12));
  std::printf("slow limit (spring k_bar = 1, V = 1e-12): P = %.12g, quasi-static %.12g\n", slow.pulloff.load,
              qs.load_control.load);
  check::close(slow.pulloff.load, qs.load_control.load, check::tier::kIdentityByDifferences,
               "slow-limit pull-off on the soft film");
  // Check 3: the exponent n/(n+2) over V = 1e8..1e10.
  const auto fast = sweep_kinetics(model, eta, KineticLaw{}, 1.0, protocol(1.0), {1e8, 1e9, 1e10});
  const double differences =
      std::log((fast[2].pulloff.load - fast[1].pulloff.load) / (fast[1].pulloff.load - fast[0].pulloff.load)) /
      std::log(10.0);
  std::printf("fast limit: exponent %.6f, n/(n+2) = %.6f\n", differences, kN / (kN + 2.0));
  check::close(differences, kN / (kN + 2.0), kExponentDifferences, "pull-off exponent on the soft film");
  // Check 4: energy balance on a coating (needs dP_H/da = K dD_H/da, dK/da = 2 Gamma^2 of the table).
  for (double k_bar : {1.0, 0.0}) {
    const auto r = simulate_kinetics(model, eta, KineticLaw{}, k_bar, protocol(1.0));
    const double residual = r.work - (r.energy_end - r.energy_start + r.dissipation);
    std::printf("energy k_bar = %g: W %.12g, residual/W %.3g\n", k_bar, r.work, residual / r.work);
    check::below(std::fabs(residual / r.work), kEnergyBalance, "energy balance on the soft film");
  }
  return check::exit_code();
}
