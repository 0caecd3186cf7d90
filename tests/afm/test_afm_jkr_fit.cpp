// Adhesive AFM retract fit: JKR through the cantilever (coatcontact/afm_fit.hpp, THEORY.md
// section 15, "Adhesive retract").
//  - Model, half-space: afm_model_force against a JKR curve written here (delta(a), F(a) of
//    [EqForceJKR, EqPenetrationJKR], a root of delta(a) = delta by bisection) and the jump-off
//    against the quintic of THEORY.md section 10 (its own bisection).
//  - Model, coating: afm_model_force against the library's exact_point (reduced variables
//    solved directly at each a/t) on the spring-stable branch.
//  - Recovery: synthetic retracts made from the library's spring model (fit::model_curve, the
//    branch cut at the minimum of delta + F/k, a uniform piezo grid, so that the jump-off leaves
//    its gap on the tip axis), with Gaussian noise, a contact-point offset, a baseline and a
//    tilt, give E (E1), w, z_c, b and the tilt within 3 standard errors for every seed, on the
//    half-space and on a coating; chi2/dof near 1 with the true noise.
//  - Coating, E1 fixed (one sweep, no interpolation in E1): the fit sweeps a/t only as far as
//    its branches reach (THEORY.md section 15); its model against afm_model_force (a sweep of
//    the whole lattice) at the estimates.
//  - Shared node sweeps: a coating fit (E1 free) after other fits of the same sample, which
//    left the E1 nodes swept (a curve of larger w, reaching further in a/t, among them), equals
//    the same fit from none, bit for bit.
//  - Tabor's mu and Maugis's lambda against their formulas; the warning below lambda = 5.
//  - Bad input: no spring constant, a cone tip, a fixed w <= 0.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "afm_adhesive_problem.hpp"
#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/stack.hpp"

namespace fit = coatcontact::fit;
using coatcontact::InputError;
using coatcontact::NumericalError;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Relative agreement of the fit's branch table (a cubic spline of F against delta over 256
// radii) with a direct evaluation; measured here ~1e-7, bounded at 1e-5.
constexpr double kBranchTable = 1e-5;

struct Truth {
  double radius = 10e-6, modulus = 100e3, poisson = 0.5, work = 10e-3, spring = 1.0;
  double contact = 1.0e-6, baseline = 2e-9, tilt = 0.01;
  bool coated = false;
  double substrate_modulus = 1e6, substrate_poisson = 0.3, thickness = 4e-6;
};

fit::AfmFitProblem problem_of(const Truth& t) { return adhesive_problem(t, fit::AfmModel::kJkr); }

// JKR of a sphere on a half-space, written here: delta(a), F(a) and the root a(delta) on the
// branch a >= a_s.
struct HalfSpaceJkr {
  double radius, reduced, work;
  double delta(double a) const { return a * a / radius - std::sqrt(2 * kPi * a * work / reduced); }
  double force(double a) const {
    return 4 * reduced * a * a * a / (3 * radius) - std::sqrt(8 * kPi * work * reduced * a * a * a);
  }
  double radius_at(double d, double a_low) const {
    double lo = a_low, hi = a_low;
    while (delta(hi) < d) hi *= 2;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (delta(mid) < d ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
};

// a_s / L_a from THEORY.md section 10's quintic 4 sqrt2 x^5 + 2 sqrt2 k x^3 - 6 x^2 - k = 0,
// x = sqrt(a_bar), root in [2^-1/2, (9/8)^(1/6)], by bisection.
double quintic_radius(double k_bar) {
  const double s = std::sqrt(2.0);
  const auto q = [&](double x) { return 4 * s * std::pow(x, 5) + 2 * s * k_bar * x * x * x - 6 * x * x - k_bar; };
  double lo = 1 / s, hi = std::pow(9.0 / 8.0, 1.0 / 6.0);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (q(mid) < 0 ? lo : hi) = mid;
  }
  const double x = 0.5 * (lo + hi);
  return x * x;
}

void check_half_space_model() {
  const Truth t;
  fit::AfmFitProblem p = problem_of(t);
  p.tilt = 0.0;
  p.baseline = 0.0;
  const double reduced = t.modulus / (1 - t.poisson * t.poisson);
  const HalfSpaceJkr jkr{t.radius, reduced, t.work};
  const double length = std::cbrt(kPi * t.work * t.radius * t.radius / reduced);
  const double k_bar = t.spring * (length * length / t.radius) / (kPi * t.work * t.radius);
  const double a_s = quintic_radius(k_bar) * length;
  std::vector<double> z, expected;
  for (int i = 1; i <= 40; ++i) {
    const double a = a_s * (1.0 + 0.1 * i);
    z.push_back(t.contact - jkr.delta(a));
    expected.push_back(jkr.force(a));
  }
  const std::vector<double> model = fit::afm_model_force(p, z);
  double worst = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double a = jkr.radius_at(t.contact - z[i], a_s);
    check::close(jkr.force(a), expected[i], 1e-9, "test's own root of delta(a)", 1e-12);
    worst = std::max(worst, std::abs(model[i] - expected[i]) / std::abs(jkr.force(a_s)));
  }
  std::printf("half-space JKR branch: worst relative error %.3g (of the pull-off force)\n", worst);
  check::below(worst, kBranchTable, "half-space JKR branch vs the curve written here");
  // The jump-off: just inside delta(a_s) the tip pulls with F(a_s); just outside, zero.
  const double d_s = jkr.delta(a_s), f_s = jkr.force(a_s);
  const std::vector<double> edge = fit::afm_model_force(p, {t.contact - d_s - 1e-6 * length, t.contact - d_s + 1e-6 * length});
  check::close(edge[0], f_s, 1e-4, "force at the jump-off (quintic of section 10)");
  check::that(edge[1] == 0.0, "zero force past the jump-off");
}

void check_coating_model() {
  Truth t;
  t.coated = true;
  fit::AfmFitProblem p = problem_of(t);
  p.tilt = 0.0;
  p.baseline = 0.0;
  fit::Problem lib;
  lib.sphere_radius = t.radius;
  lib.film = {t.modulus, t.poisson};
  lib.substrate.material = {t.substrate_modulus, t.substrate_poisson};
  lib.thickness = t.thickness;
  lib.work = t.work;
  // The branch start: the minimum of delta + F/k over a dense scan of exact points.
  double a_s = 0.0, best = 1e300;
  for (int i = 0; i <= 400; ++i) {
    const double a = 0.3e-6 * std::pow(20.0, i / 400.0);
    const fit::CurvePoint c = fit::exact_point(lib, a);
    if (c.penetration + c.force / t.spring < best) best = c.penetration + c.force / t.spring, a_s = a;
  }
  std::vector<double> z, expected;
  for (int i = 1; i <= 30; ++i) {
    const fit::CurvePoint c = fit::exact_point(lib, a_s * (1.05 + 0.1 * i));
    z.push_back(t.contact - c.penetration);
    expected.push_back(c.force);
  }
  const std::vector<double> model = fit::afm_model_force(p, z);
  double worst = 0.0, scale = 0.0;
  for (double f : expected) scale = std::max(scale, std::abs(f));
  for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(model[i] - expected[i]) / scale);
  std::printf("coating JKR branch: worst relative error %.3g (of the largest force)\n", worst);
  check::below(worst, kBranchTable, "coating JKR branch vs the library's exact points");
}

struct Synthetic {
  std::vector<double> z, f;
};

// A retract from the library's spring model: the curve (delta, F)(a) of fit::model_curve, cut
// at the minimum of Z = delta + F/k; for each piezo height h of a uniform grid the tip sits
// where Z = z_c - h (linear interpolation on 20000 radii), else (past the jump) off at z = h.
Synthetic make_retract(const Truth& t, double sigma, unsigned seed, std::size_t n) {
  fit::Problem lib;
  lib.sphere_radius = t.radius;
  lib.film = {t.modulus, t.poisson};
  if (t.coated) {
    lib.substrate.material = {t.substrate_modulus, t.substrate_poisson};
    lib.thickness = t.thickness;
  } else {  // a film on its own material: the half-space
    lib.substrate.material = {t.modulus, t.poisson};
    lib.thickness = 1e-3;
  }
  lib.work = t.work;
  const std::vector<fit::CurvePoint> curve = fit::model_curve(lib, 0.3e-6, 12e-6, 20000);
  std::size_t s = 0;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const double zj = curve[j].penetration + curve[j].force / t.spring;
    if (zj < curve[s].penetration + curve[s].force / t.spring) s = j;
  }
  const double z_jump = curve[s].penetration + curve[s].force / t.spring;
  const double deepest = 1.2e-6;  // indentation at the start of the retract
  std::size_t top = s;
  while (top + 1 < curve.size() && curve[top].penetration < deepest) ++top;
  const double z_top = curve[top].penetration + curve[top].force / t.spring;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Synthetic out;
  const double h_lo = t.contact - z_top, h_hi = t.contact + 4e-6;
  std::size_t j = top;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = h_lo + (h_hi - h_lo) * static_cast<double>(i) / static_cast<double>(n - 1);
    const double target = t.contact - h;  // Z along the branch
    double z = h, f = 0.0;
    if (target >= z_jump) {
      while (j > s && curve[j - 1].penetration + curve[j - 1].force / t.spring >= target) --j;
      const fit::CurvePoint& a = curve[j - 1 < s ? s : j - 1];
      const fit::CurvePoint& b = curve[j];
      const double za = a.penetration + a.force / t.spring, zb = b.penetration + b.force / t.spring;
      const double x = zb > za ? (target - za) / (zb - za) : 1.0;
      const double delta = a.penetration + x * (b.penetration - a.penetration);
      f = a.force + x * (b.force - a.force);
      z = t.contact - delta;
    }
    out.z.push_back(z);
    out.f.push_back(f + t.baseline + t.tilt * (z - t.contact) + noise(rng));
  }
  return out;
}

void check_recovery(const Truth& t, const char* name, int seeds) {
  for (int seed = 1; seed <= seeds; ++seed) {
    const double sigma = 5e-9;
    const Synthetic s = make_retract(t, sigma, static_cast<unsigned>(seed), 1500);
    const fit::AfmFitProblem p = problem_of(t);
    const fit::AfmFitResult r = fit_from_far_start(p, sigma, s.z, s.f);
    const RecoveryScores z = scores_of(r, t);
    std::printf("%s seed %d: E %.6g (%.2f SE) w %.6g (%.2f SE) z_c %.2f SE b %.2f SE tilt %.2f SE chi2/dof %.3f "
                "lambda %.3g, %.1f ms, %d tables, %d profile evaluations\n",
                name, seed, r.modulus, z.modulus, r.work, z.work, z.contact, z.baseline, z.tilt, r.chi2_per_dof,
                r.maugis_lambda, r.seconds * 1e3,
                r.model_evaluations, r.profile_evaluations);
    const std::string tag = std::string(name) + " seed " + std::to_string(seed);
    check_within_3_se(z, tag);
    check::below(std::abs(r.chi2_per_dof - 1.0), 0.15, tag + ": chi2/dof near 1 with the true noise");
    check::that(r.points_in_contact > 100 && r.points_in_contact < s.z.size(), tag + ": contact and free points");
    // The fit's own model (a coating: E1 between sweep nodes, interpolated) against the model
    // at the estimates from a sweep at that E1.
    fit::AfmFitProblem at = p;
    at.modulus = r.modulus;
    at.work = r.work;
    at.contact_point = r.contact_point;
    at.baseline = r.baseline;
    at.tilt = r.tilt;
    if (at.coating) at.coating->film.youngs_modulus = r.modulus;
    const std::vector<double> direct = fit::afm_model_force(at, s.z);
    double worst = 0.0;
    for (std::size_t i = 0; i < direct.size(); ++i) worst = std::max(worst, std::abs(direct[i] - r.model_force[i]));
    std::printf("%s seed %d: fit's model vs direct, worst %.3g N (noise %.3g N)\n", name, seed, worst, sigma);
    check::below(worst, 0.1 * sigma, tag + ": the fit's model within a tenth of the noise of the direct model");
  }
}

void check_lambda() {
  const Truth t;
  const Synthetic s = make_retract(t, 5e-9, 7, 800);
  fit::AfmFitProblem p = problem_of(t);
  p.free = {true, true, true, false, true, true};
  p.surface_force_range = 0.5e-9;
  const fit::AfmFitResult r = fit::afm_fit(s.z, s.f, p);
  const double reduced = r.modulus / (1 - t.poisson * t.poisson), z0 = p.surface_force_range;
  check::close(r.tabor_mu, std::cbrt(t.radius * r.work * r.work / (reduced * reduced * z0 * z0 * z0)), check::tier::kMachine,
               "Tabor's mu of the estimates");
  const double sigma0 = r.work / (0.97 * z0), k = 4 * reduced / 3;
  check::close(r.maugis_lambda, 2 * sigma0 * std::cbrt(t.radius / (kPi * r.work * k * k)), check::tier::kMachine,
               "Maugis's lambda of the estimates");
  check::that(r.maugis_lambda > 5.0 && r.warnings.empty(), "a soft adhesive sphere is in JKR's range: no warning");
  // The same fit with a long range z0 = 200 nm: lambda below 5 and a warning naming it.
  p.surface_force_range = 200e-9;
  const fit::AfmFitResult wide = fit::afm_fit(s.z, s.f, p);
  check::that(wide.maugis_lambda < 5.0, "lambda below 5 for z0 = 200 nm");
  check::that(wide.warnings.size() == 1 && wide.warnings[0].find("lambda") != std::string::npos &&
                  wide.warnings[0].find("Maugis-Dugdale") != std::string::npos,
              "warning: outside JKR's range");
  check::close(wide.modulus, r.modulus, 1e-9, "the range z0 does not change the fit");
}

void check_bad_input() {
  const Truth t;
  const Synthetic s = make_retract(t, 5e-9, 3, 300);
  fit::AfmFitProblem p = problem_of(t);
  p.free = {true, true, true, false, true, true};
  p.spring_constant = 0.0;
  check::throws<InputError>([&] { fit::afm_fit(s.z, s.f, p); }, {"spring constant"});
  p = problem_of(t);
  p.tip = fit::afm_cone(0.3);
  check::throws<InputError>([&] { fit::afm_fit(s.z, s.f, p); }, {"sphere"});
  p = problem_of(t);
  p.free = {true, true, true, false, false, false};
  p.work = -1.0;
  check::throws<InputError>([&] { fit::afm_fit(s.z, s.f, p); }, {"fixed w"});
  // Flat data (no contact anywhere): a numerical failure, not a hang or NaN.
  std::vector<double> flat(s.z.size(), 0.0);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 1e-9);
  for (double& v : flat) v = noise(rng);
  p = problem_of(t);
  p.free = {true, true, true, false, true, true};
  bool refused = false;
  try {
    const fit::AfmFitResult r = fit::afm_fit(s.z, flat, p);
    refused = std::isfinite(r.modulus) && std::isfinite(r.work);  // finite answers are allowed (noise fitted)
  } catch (const NumericalError&) {
    refused = true;
  }
  check::that(refused, "flat data: a finite result or NumericalError");
}
// The fit's sweep covers the a/t the branches reach, not the whole lattice: with E1 fixed the
// model at the estimates differs from afm_model_force's (whole lattice) only by the spline's
// end conditions there; measured 5e-15 N, bounded at a thousandth of the noise.
void check_swept_range() {
  Truth t;
  t.coated = true;
  const double sigma = 5e-9;
  const Synthetic s = make_retract(t, sigma, 1u, 1500);
  fit::AfmFitProblem p = problem_of(t);
  p.work = 0.0;
  p.tilt = 0.0;
  p.free = {false, true, true, false, true, true};
  const fit::AfmFitResult r = fit::afm_fit(s.z, s.f, p);
  fit::AfmFitProblem at = p;
  at.work = r.work;
  at.contact_point = r.contact_point;
  at.baseline = r.baseline;
  at.tilt = r.tilt;
  const std::vector<double> direct = fit::afm_model_force(at, s.z);
  double worst = 0.0;
  for (std::size_t i = 0; i < direct.size(); ++i) worst = std::max(worst, std::abs(direct[i] - r.model_force[i]));
  std::printf("coating, E1 fixed: %ld solves (lattice 65), fit's model vs whole-lattice model, worst %.3g N\n",
              r.solver_calls, worst);
  check::that(r.solver_calls < 65, "the sweep stops short of a/t = 100 for indentations of a/t ~ 2");
  check::below(worst, 1e-3 * sigma, "the fit's model on its swept a/t within a thousandth of the noise of the whole lattice's");
}

// The E1 nodes' sweeps are kept for later fits (coatcontact/afm_fit.hpp); each fit uses its own
// prefix of them, so the result cannot depend on which fits ran before.
void check_shared_sweeps() {
  Truth t;
  t.coated = true;
  const double sigma = 5e-9;
  fit::AfmFitProblem p = problem_of(t);
  p.coating->film.youngs_modulus = t.modulus * 2.5;
  p.work = 0.0;
  p.tilt = 0.0;
  p.free = {true, true, true, false, true, true};
  const Synthetic first = make_retract(t, sigma, 11u, 800);
  Truth deeper = t;
  deeper.work = 30e-3;  // a larger w: larger contact radii
  const Synthetic other = make_retract(deeper, sigma, 12u, 800);
  fit::afm_clear_shared_sweeps();
  const fit::AfmFitResult cold = fit::afm_fit(first.z, first.f, p);
  (void)fit::afm_fit(other.z, other.f, p);
  const fit::AfmFitResult warm = fit::afm_fit(first.z, first.f, p);
  std::printf("shared sweeps: cold E1 %.17g w %.17g rss %.17g (%.1f ms), warm (%.1f ms)\n", cold.modulus, cold.work, cold.rss,
              cold.seconds * 1e3, warm.seconds * 1e3);
  check::that(cold.modulus == warm.modulus && cold.work == warm.work && cold.contact_point == warm.contact_point &&
                  cold.rss == warm.rss && cold.modulus_error == warm.modulus_error,
              "a fit after others of the same sample equals the fit from no shared sweeps, bit for bit");
}

}  // namespace

int main() {
  check_half_space_model();
  check_coating_model();
  check_swept_range();
  check_shared_sweeps();
  Truth half;
  check_recovery(half, "half-space", 4);
  Truth coated;
  coated.coated = true;
  check_recovery(coated, "coating", 3);
  check_lambda();
  check_bad_input();
  return check::exit_code();
}
