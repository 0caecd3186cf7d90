// Material atlas of the reduced-variable solver (issue 29, label physics): real film/substrate
// pairs swept over a/t in [1e-3, 1e3] at radii that avoid round numbers, at the default
// tolerance 1e-8 and at 1e-4. Every radius must return finite, positive values with
// error_estimate <= tol (no NumericalError, the CLI's exit 3), and the estimate must bound the
// true error, checked independently:
//   - THEORY.md section 6, check 1 [EqGde1]: Gamma(1)^2 = d(a E_eq)/da at every
//     kIdentityEvery-th radius at 1e-8, the derivative by the sixth-order finite difference
//     of tests/harden/test_extreme_sweep.cpp (its neighbours at a e^{+-h, +-2h, +-4h} are
//     atlas radii too and must also pass);
//   - at 1e-4, the difference of each of the six values from the 1e-8 solve of the same
//     radius <= the sum of the two estimates (the finer-tolerance solve as the reference).
//
// COATCONTACT_ATLAS_STRIDE=k keeps every k-th radius of each pair (the sanitizer build sets
// 4: every pair, a quarter of the radii); the log says so.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

using namespace coatcontact;

namespace {

struct Pair {
  const char* name;
  double film_e, film_nu;
  double substrate_e, substrate_nu;  // substrate_e = 0: rigid base
  double max_a_over_t;               // the sweep's upper end
};

// Handbook-order moduli (Pa) and Poisson ratios.
const Pair kPairs[] = {
    {"PDMS 1 MPa nu 0.49 on glass", 1e6, 0.49, 70e9, 0.22, 1e3},
    {"PDMS 1 MPa nu 0.5 on glass", 1e6, 0.5, 70e9, 0.22, 1e3},
    {"PDMS 2 MPa nu 0.5 on silicon", 2e6, 0.5, 130e9, 0.28, 1e3},
    {"hydrogel 20 kPa nu 0.45 on glass", 20e3, 0.45, 70e9, 0.22, 1e3},
    {"PDMS 1 MPa nu 0.49 on a rigid base", 1e6, 0.49, 0.0, 0.0, 1e3},
    {"gelatin 5 kPa nu 0.5 on a rigid base", 5e3, 0.5, 0.0, 0.0, 2e2},
    {"polystyrene 3.4 GPa nu 0.34 on silicon", 3.4e9, 0.34, 130e9, 0.28, 1e3},
    {"PMMA 3 GPa nu 0.37 on steel", 3e9, 0.37, 210e9, 0.29, 1e3},
    {"epoxy 3 GPa nu 0.35 on a rigid base", 3e9, 0.35, 0.0, 0.0, 1e3},
    {"DLC 300 GPa nu 0.25 on silicon", 300e9, 0.25, 130e9, 0.28, 1e3},
    {"TiN 450 GPa nu 0.25 on steel", 450e9, 0.25, 210e9, 0.29, 1e3},
    {"gold 79 GPa nu 0.42 on silicon", 79e9, 0.42, 130e9, 0.28, 1e3},
    {"alumina 350 GPa nu 0.22 on PMMA", 350e9, 0.22, 3e9, 0.37, 1e3},
};

constexpr double kMinAOverT = 1e-3;
constexpr int kRadiiPerDecade = 40;  // 240 over six decades
constexpr double kLooseTolerance = 1e-4;
constexpr int kIdentityEvery = 4;
// Identity check as in the extreme sweep: FD step in ln(a/t) and safety on the bound.
constexpr double kStep = 0.02;
constexpr double kSafety = 3.0;

ReducedSolver make_solver(const Pair& p) {
  Material film;
  film.youngs_modulus = p.film_e;
  film.poisson_ratio = p.film_nu;
  Substrate substrate;
  if (p.substrate_e > 0.0) {
    substrate.material.youngs_modulus = p.substrate_e;
    substrate.material.poisson_ratio = p.substrate_nu;
  } else {
    substrate.rigid = true;
  }
  return ReducedSolver(Stack::film_on(film, substrate));
}

// Radii log-spaced over [kMinAOverT, max], shifted off the decade points by an irrational
// fraction of a step that differs from pair to pair.
std::vector<double> radii_of(const Pair& p, int index, int stride) {
  const double decades = std::log10(p.max_a_over_t / kMinAOverT);
  const int count = static_cast<int>(std::lround(decades * kRadiiPerDecade));
  const double shift = std::fmod(0.3819660113 + 0.6180339887 * index, 1.0);
  std::vector<double> radii;
  for (int k = 0; k < count; k += stride) {
    radii.push_back(kMinAOverT * std::pow(10.0, decades * (k + shift) / count));
  }
  return radii;
}

std::string text(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

using Values = std::array<double, 6>;
Values values_of(const ReducedVariables& v) { return {v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1}; }

// Checks one returned point: finite, positive, estimate <= tolerance.
bool check_returned(const ReducedVariables& v, double tolerance, const std::string& where) {
  bool ok = std::isfinite(v.error_estimate) && v.error_estimate >= 0.0;
  for (double x : values_of(v)) ok = ok && std::isfinite(x) && x > 0.0;
  check::that(ok, where + ": finite, positive values and estimate");
  return check::below(v.error_estimate, tolerance, where + ": estimate <= tolerance") && ok;
}

// The sweep; if it throws, every radius alone, each failure named. ok[i] is false for a
// radius that failed.
std::vector<ReducedVariables> solve_all(const ReducedSolver& solver, const std::vector<double>& radii,
                                        double tolerance, const std::string& name, std::vector<bool>& ok,
                                        int& refused) {
  ok.assign(radii.size(), true);
  try {
    return solver.sweep(radii, tolerance);
  } catch (const NumericalError&) {
  }
  std::vector<ReducedVariables> out(radii.size());
  for (std::size_t i = 0; i < radii.size(); ++i) {
    try {
      out[i] = solver.solve(radii[i], tolerance);
    } catch (const NumericalError& e) {
      ok[i] = false;
      ++refused;
      check::that(false, name + ": a/t " + text(radii[i]) + ", tol " + text(tolerance) + ": " + e.what());
    }
  }
  return out;
}

}  // namespace

int main() {
  int stride = 1;
  if (const char* value = std::getenv("COATCONTACT_ATLAS_STRIDE")) {
    stride = std::atoi(value);
    if (stride < 1) {
      std::printf("COATCONTACT_ATLAS_STRIDE='%s' is not an integer >= 1\n", value);
      return 1;
    }
  }
  std::printf("material atlas: %zu pairs, a/t in [%g, max], %d radii per decade%s, tol %g and %g; "
              "identity [EqGde1] at every %d-th radius (FD step %g, safety %g)\n",
              sizeof kPairs / sizeof kPairs[0], kMinAOverT, kRadiiPerDecade,
              stride > 1 ? " (REDUCED: every COATCONTACT_ATLAS_STRIDE-th)" : "", kDefaultTolerance,
              kLooseTolerance, kIdentityEvery, kStep, kSafety);
  const auto start = std::chrono::steady_clock::now();
  int solved = 0, refused = 0, identity_checks = 0;
  double worst_identity = 0.0, worst_loose = 0.0;  // measured / bound
  int index = 0;
  for (const Pair& pair : kPairs) {
    const auto pair_start = std::chrono::steady_clock::now();
    const ReducedSolver solver = make_solver(pair);
    const std::vector<double> radii = radii_of(pair, index++, stride);
    // The checked radii's neighbours for the identity (a e^{k h}, k = -4, -2, -1, 1, 2, 4).
    const int offsets[6] = {-4, -2, -1, 1, 2, 4};
    std::vector<std::size_t> checked;
    std::vector<double> neighbours;
    for (std::size_t i = 0; i < radii.size(); i += kIdentityEvery) {
      checked.push_back(i);
      for (int k : offsets) neighbours.push_back(radii[i] * std::exp(k * kStep));
    }
    std::vector<bool> ok, ok_loose, ok_neighbour;
    const auto fine = solve_all(solver, radii, kDefaultTolerance, pair.name, ok, refused);
    const auto loose = solve_all(solver, radii, kLooseTolerance, pair.name, ok_loose, refused);
    const auto near = solve_all(solver, neighbours, kDefaultTolerance, pair.name, ok_neighbour, refused);
    solved += static_cast<int>(2 * radii.size() + neighbours.size());
    double pair_identity = 0.0, pair_loose = 0.0;
    for (std::size_t i = 0; i < radii.size(); ++i) {
      const std::string where = std::string(pair.name) + ", a/t " + text(radii[i]);
      const bool fine_ok = ok[i] && check_returned(fine[i], kDefaultTolerance, where + ", tol 1e-8");
      const bool loose_ok = ok_loose[i] && check_returned(loose[i], kLooseTolerance, where + ", tol 1e-4");
      if (!fine_ok || !loose_ok) continue;
      // The finer solve as the reference of the looser one.
      const Values f = values_of(fine[i]), l = values_of(loose[i]);
      double worst = 0.0;
      for (std::size_t k = 0; k < f.size(); ++k) worst = std::max(worst, std::abs(l[k] - f[k]) / f[k]);
      const double bound = loose[i].error_estimate + fine[i].error_estimate;
      pair_loose = std::max(pair_loose, worst / bound);
      check::below(worst, bound, where + ": tol 1e-4 values within their estimate of the 1e-8 ones");
    }
    for (std::size_t c = 0; c < checked.size(); ++c) {
      const std::size_t i = checked[c];
      bool all = ok[i];
      double f[6], error[6];
      for (int k = 0; k < 6; ++k) {
        const std::size_t n = 6 * c + static_cast<std::size_t>(k);
        all = all && ok_neighbour[n] &&
              check_returned(near[n], kDefaultTolerance, std::string(pair.name) + ", neighbour a/t " + text(neighbours[n]));
        f[k] = neighbours[n] * near[n].e_eq;
        error[k] = f[k] * near[n].error_estimate;
      }
      if (!all) continue;
      // Samples m4, m2, m1, p1, p2, p4 (tests/harden/test_extreme_sweep.cpp, same formulas).
      const double h = kStep, a = radii[i];
      const double d_h = (8.0 * (f[3] - f[2]) - (f[4] - f[1])) / (12.0 * h);
      const double d_2h = (8.0 * (f[4] - f[1]) - (f[5] - f[0])) / (24.0 * h);
      const double noise_h = (8.0 * (error[3] + error[2]) + (error[4] + error[1])) / (12.0 * h);
      const double noise_2h = (8.0 * (error[4] + error[1]) + (error[5] + error[0])) / (24.0 * h);
      const double d_6 = (16.0 * d_h - d_2h) / 15.0;
      const double noise_6 = (16.0 * noise_h + noise_2h) / 15.0;
      const double truncation = std::abs(d_6 - d_h) + noise_6 + noise_h;
      const double derivative = d_6 / a;
      const double gamma_sq = fine[i].gamma1 * fine[i].gamma1;
      const double bound = 2.0 * gamma_sq * fine[i].error_estimate + (noise_6 + truncation) / a;
      const double difference = std::abs(gamma_sq - derivative);
      ++identity_checks;
      pair_identity = std::max(pair_identity, difference / bound);
      check::below(difference, kSafety * bound,
                   std::string(pair.name) + ", a/t " + text(a) + ": Gamma1^2 = d(a E_eq)/da within " +
                       text(kSafety) + " x its bound (Gamma1^2 " + text(gamma_sq) + ", derivative " +
                       text(derivative) + ")");
    }
    worst_identity = std::max(worst_identity, pair_identity);
    worst_loose = std::max(worst_loose, pair_loose);
    std::printf("  %-40s a/t <= %-5g %3zu radii: identity <= %.3f x bound, tol 1e-4 error <= %.3f x estimate, "
                "%.1f s\n",
                pair.name, pair.max_a_over_t, radii.size(), pair_identity, pair_loose,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - pair_start).count());
  }
  std::printf("atlas: %d solves, %d refused (NumericalError), %d identity checks; worst identity "
              "difference %.3f x bound, worst tol 1e-4 error %.3f x estimate; %.1f s\n",
              solved, refused, identity_checks, worst_identity, worst_loose,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return check::exit_code();
}
