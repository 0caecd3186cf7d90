// Adhesive AFM retract fit: DMT through the cantilever (coatcontact/afm_fit.hpp, THEORY.md
// section 15, "Adhesive retract: DMT through the cantilever").
//  - Pull-off on the half-space: the model force just inside the contact point is -2 pi w R
//    (1e-9) through a stiff spring (k = 1e3 N/m) and a soft one (1e-2 N/m) alike, and the
//    baseline just outside it (the jump-off is the curve's end for every spring).
//  - Model: F_DMT(delta) + 2 pi w R against the Hertz force (4/3) E* sqrt(R) delta^1.5 written
//    here, to the branch table's accuracy (a cubic spline over 256 radii).
//  - Recovery: synthetic DMT retracts written here (a uniform piezo grid through the spring,
//    delta from delta + F/k = z_c - h by bisection, the jump at the contact point), with
//    Gaussian noise, a baseline, a tilt and the contact point away from the start, give E, w,
//    z_c, b and the tilt within 3 standard errors for every seed; chi2/dof near 1.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "afm_adhesive_problem.hpp"
#include "check.hpp"
#include "coatcontact/afm_fit.hpp"

namespace fit = coatcontact::fit;

namespace {

constexpr double kPi = 3.14159265358979323846;
// The branch table's agreement with a direct evaluation (as the JKR test's kBranchTable).
constexpr double kBranchTable = 1e-5;

struct Truth {
  double radius = 10e-6, modulus = 100e3, poisson = 0.5, work = 10e-3, spring = 1.0;
  double contact = 1.0e-6, baseline = 2e-9, tilt = 0.01;
  bool coated = false;
  double substrate_modulus = 1e6, substrate_poisson = 0.3, thickness = 4e-6;
  double reduced() const { return modulus / (1 - poisson * poisson); }
  // DMT on the half-space, written here: Hertz less 2 pi w R in contact.
  double force(double delta) const {
    return 4.0 / 3.0 * reduced() * std::sqrt(radius) * std::pow(delta, 1.5) - 2 * kPi * work * radius;
  }
};

void check_pulloff() {
  for (double spring : {1e3, 1e-2}) {
    Truth t;
    t.spring = spring;
    fit::AfmFitProblem p = adhesive_problem(t, fit::AfmModel::kDmt);
    const std::vector<double> z = {t.contact - 1e-14, t.contact + 1e-9, t.contact - 0.5e-6};
    std::vector<double> f = fit::afm_model_force(p, z);
    for (std::size_t i = 0; i < z.size(); ++i) f[i] -= t.baseline + t.tilt * (z[i] - t.contact);
    const double pulloff = -2 * kPi * t.work * t.radius;
    std::printf("k = %g N/m: F(z_c - 1e-14 m) = %.12g N, -2 pi w R = %.12g N; F(z_c + 1 nm) = %g N\n", spring, f[0],
                pulloff, f[1]);
    // 1e-9: the Hertz part at delta = 1e-14 m is ~1e-12 of 2 pi w R.
    check::close(f[0], pulloff, 1e-9, "DMT pull-off through k = " + std::to_string(spring) + " N/m is -2 pi w R");
    check::that(f[1] == 0.0, "DMT: no force past the contact point");
    check::close(f[2], t.force(0.5e-6), kBranchTable, "DMT force at 0.5 um against Hertz - 2 pi w R");
  }
  Truth t;
  fit::AfmFitProblem p = adhesive_problem(t, fit::AfmModel::kDmt);
  double worst = 0.0;
  for (int k = 1; k <= 40; ++k) {
    const double delta = 1e-6 * k / 40.0;
    const double f = fit::afm_model_force(p, {t.contact - delta})[0] - t.baseline + t.tilt * delta;
    worst = std::max(worst, std::abs(f - t.force(delta)) / (2 * kPi * t.work * t.radius));
  }
  std::printf("DMT branch vs Hertz - 2 pi w R over 0..1 um: worst %.3g of the pull-off\n", worst);
  check::below(worst, kBranchTable, "DMT branch against the Hertz force written here");
}

struct Synthetic {
  std::vector<double> z, f;
};

Synthetic make_retract(const Truth& t, double sigma, unsigned seed, std::size_t n) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const double hold = 2 * kPi * t.work * t.radius / t.spring;  // Z at the jump: -2 pi w R/k
  const double h_lo = t.contact - 1.5e-6, h_hi = t.contact + 4e-6;
  Synthetic out;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = h_lo + (h_hi - h_lo) * static_cast<double>(i) / static_cast<double>(n - 1);
    const double target = t.contact - h;  // Z = delta + F/k
    double z = h, f = 0.0;
    if (target >= -hold) {
      double lo = 0.0, hi = std::max(target + hold, 1e-15);
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (mid + t.force(mid) / t.spring < target ? lo : hi) = mid;
      }
      const double delta = 0.5 * (lo + hi);
      f = t.force(delta);
      z = t.contact - delta;
    }
    out.z.push_back(z);
    out.f.push_back(f + t.baseline + t.tilt * (z - t.contact) + noise(rng));
  }
  return out;
}

void check_recovery(int seeds) {
  const Truth t;
  for (int seed = 1; seed <= seeds; ++seed) {
    const double sigma = 5e-9;
    const Synthetic s = make_retract(t, sigma, static_cast<unsigned>(seed), 1500);
    const fit::AfmFitResult r = fit_from_far_start(adhesive_problem(t, fit::AfmModel::kDmt), sigma, s.z, s.f);
    const RecoveryScores z = scores_of(r, t);
    std::printf("DMT seed %d: E %.6g (%.2f SE) w %.6g (%.2f SE) z_c %.2f SE b %.2f SE tilt %.2f SE chi2/dof %.3f, "
                "jump-off %.6g N (-2 pi w R %.6g N)\n",
                seed, r.modulus, z.modulus, r.work, z.work, z.contact, z.baseline, z.tilt, r.chi2_per_dof, r.jump_off_force,
                -2 * kPi * r.work * t.radius);
    const std::string tag = "DMT seed " + std::to_string(seed);
    check_within_3_se(z, tag);
    check::below(std::abs(r.chi2_per_dof - 1.0), 0.15, tag + ": chi2/dof near 1 with the true noise");
    check::close(r.jump_off_force, -2 * kPi * r.work * t.radius, 1e-12, tag + ": the model's jump-off is -2 pi w R");
  }
}

}  // namespace

int main() {
  check_pulloff();
  check_recovery(4);
  return check::exit_code();
}
