// Adhesionless AFM curve fit (coatcontact/afm_fit.hpp, THEORY.md section 15).
//  - Sneddon's g(delta) = F/E* of a tip: the tabulated path (any IndenterShape) against the
//    closed forms of the paraboloid, the cone and the blunted cone (§11 check).
//  - Global optimum: the fit's residual sum is not above that of a brute-force scan over the
//    contact point written here (its own Hertz force and its own 2x2 normal equations), on
//    synthetic curves and on the real JPK curve; the contact points agree to the scan's step.
//  - Recovery: synthetic curves (library model + Gaussian noise) for the paraboloid, the cone
//    and the pyramid give E, z_c and b within 3 standard errors for every seed, and the
//    standard errors are calibrated (RMS of the z-scores over the seeds in [0.5, 1.6]).
//  - Free tilt: synthetic curves with a tilted baseline, F = b + m (z - z_c) + E* g, give E,
//    z_c, b and m within 3 standard errors for every seed (the tilt fitted with the model, in
//    closed form with E* and b); with the tilt left out, chi2/dof shows the misfit.
//  - Coating (THEORY.md sections 5, 14): the model force against the reduced solver called
//    here at the a/t of each check point (F_H = a^3 E1* Pi_s/(2R) at delta_H = a^2 Delta_s/R),
//    and recovery of E1 (t fixed) and of t (E1 fixed) within 3 standard errors.
//  - Bad input: too few points, a fixed E <= 0, data without contact.
// Usage: test_afm_fit DATA_DIR
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace fit = coatcontact::fit;
namespace afm = coatcontact::afm;
using coatcontact::InputError;
using coatcontact::NumericalError;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Synthetic {
  std::vector<double> z, f;
};

// Tip positions from 4 um down to 0, contact at z_c, baseline b, Gaussian noise sigma.
Synthetic make_curve(const fit::AfmFitProblem& truth, double sigma, unsigned seed, std::size_t n = 1000) {
  Synthetic s;
  for (std::size_t i = 0; i < n; ++i) s.z.push_back(4e-6 * (1.0 - static_cast<double>(i) / static_cast<double>(n - 1)));
  s.f = fit::afm_model_force(truth, s.z);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (double& v : s.f) v += noise(rng);
  return s;
}

// Brute force, independent of the library: Hertz F = b + (4/3) E* sqrt(R) delta^1.5, (E*, b)
// from the 2x2 normal equations at each of `count` contact points over [lo, hi].
struct Scan {
  double rss = 1e300, contact = 0.0, reduced = 0.0, step = 0.0;
};
Scan brute_force(const std::vector<double>& z, const std::vector<double>& f, double radius, double lo, double hi,
                 int count) {
  Scan best;
  best.step = (hi - lo) / (count - 1);
  const double n = static_cast<double>(z.size());
  for (int k = 0; k < count; ++k) {
    const double c = lo + best.step * k;
    double sg = 0, sgg = 0, sf = 0, sgf = 0;
    std::vector<double> g(z.size(), 0.0);
    for (std::size_t i = 0; i < z.size(); ++i) {
      const double d = c - z[i];
      g[i] = d > 0 ? (4.0 / 3.0) * std::sqrt(radius) * std::pow(d, 1.5) : 0.0;
      sg += g[i];
      sgg += g[i] * g[i];
      sf += f[i];
      sgf += g[i] * f[i];
    }
    const double det = n * sgg - sg * sg;
    if (!(det > 0)) continue;
    double e = (n * sgf - sg * sf) / det;
    double b = (sf - e * sg) / n;
    if (e < 0) {
      e = 0;
      b = sf / n;
    }
    double rss = 0;
    for (std::size_t i = 0; i < z.size(); ++i) rss += (f[i] - b - e * g[i]) * (f[i] - b - e * g[i]);
    if (rss < best.rss) best = {rss, c, e, best.step};
  }
  return best;
}

void check_tip_tables() {
  std::vector<double> delta;
  for (int k = 0; k <= 40; ++k) delta.push_back(1e-9 * std::pow(10.0, k / 10.0));  // 1 nm .. 10 um
  const double radius = 10e-6, beta = 70.0 * kPi / 180.0;
  const auto closed_sphere = fit::afm_force_per_modulus(fit::afm_paraboloid(radius), delta);
  const auto table_sphere = fit::afm_force_per_modulus(fit::afm_shape(coatcontact::make_paraboloid(radius)), delta);
  const auto closed_cone = fit::afm_force_per_modulus(fit::afm_cone(beta), delta);
  const auto table_cone = fit::afm_force_per_modulus(fit::afm_shape(coatcontact::make_cone(beta)), delta);
  double worst_sphere = 0, worst_cone = 0;
  for (std::size_t i = 0; i < delta.size(); ++i) {
    check::close(closed_sphere[i], (4.0 / 3.0) * std::sqrt(radius) * std::pow(delta[i], 1.5), check::tier::kMachine,
                 "paraboloid closed form is Hertz");
    worst_sphere = std::max(worst_sphere, std::abs(table_sphere[i] / closed_sphere[i] - 1));
    worst_cone = std::max(worst_cone, std::abs(table_cone[i] / closed_cone[i] - 1));
  }
  // The table: log-log Steffen interpolation, 64 nodes per decade of a (measured ~1e-7).
  check::below(worst_sphere, 1e-6, "Sneddon table of the paraboloid vs Hertz");
  check::below(worst_cone, 1e-6, "Sneddon table of the cone vs (2/pi) tan(beta) delta^2");
  std::printf("tip tables: paraboloid %.2e, cone %.2e (max relative difference)\n", worst_sphere, worst_cone);
  // Blunted cone against its closed form (THEORY.md section 11): g at delta0(a) vs F/E*(a).
  const auto blunted = coatcontact::make_blunted_cone(50e-9, beta);
  double worst_blunted = 0;
  for (double a : {10e-9, 40e-9, 100e-9, 1e-6}) {
    const double g = fit::afm_force_per_modulus(fit::afm_shape(blunted), {blunted->delta0(a)})[0];
    worst_blunted = std::max(worst_blunted, std::abs(g / coatcontact::blunted_cone_force_over_modulus(50e-9, beta, a) - 1));
  }
  check::below(worst_blunted, 1e-6, "Sneddon table of the blunted cone vs its closed form");
  // Pyramid: the cone of equal area, tan(beta) = 2 tan(theta)/sqrt(pi).
  const double theta = 35.0 * kPi / 180.0;
  check::close(fit::afm_pyramid(theta).angle, std::atan(2 * std::tan(theta) / std::sqrt(kPi)), check::tier::kMachine,
               "pyramid's equivalent cone");
}

void check_global_optimum_synthetic() {
  fit::AfmFitProblem truth;
  truth.tip = fit::afm_paraboloid(10e-6);
  truth.modulus = 2e3;
  truth.poisson = 0.5;
  truth.contact_point = 2.2e-6;
  truth.baseline = 5e-11;
  for (unsigned seed : {3u, 17u}) {
    const Synthetic s = make_curve(truth, 2e-11, seed);
    fit::AfmFitProblem problem = truth;
    const fit::AfmFitResult r = fit::afm_fit(s.z, s.f, problem);
    const Scan scan = brute_force(s.z, s.f, 10e-6, 0.0, 5e-6, 50001);
    std::printf("seed %u: fit rss %.9e  E %.6e  z_c %.6e | scan rss %.9e  E %.6e  z_c %.6e\n", seed, r.rss, r.modulus,
                r.contact_point, scan.rss, scan.reduced * 0.75, scan.contact);
    check::that(r.rss <= scan.rss * (1 + 1e-12), "fit's RSS not above the brute-force scan's");
    check::below(std::abs(r.contact_point - scan.contact), scan.step, "contact point within one scan step");
    // E moves with z_c along the valley: within what one scan step in z_c changes it.
    check::close(r.modulus, scan.reduced * 0.75, 1e-3, "E at the brute-force minimum");
  }
}

struct ZScores {
  double sum_sq = 0;
  int count = 0;
  void add(double z) {
    sum_sq += z * z;
    ++count;
  }
  double rms() const { return std::sqrt(sum_sq / count); }
};

void check_recovery(const fit::AfmTip& tip, double modulus, const char* name) {
  fit::AfmFitProblem truth;
  truth.tip = tip;
  truth.modulus = modulus;
  truth.poisson = 0.5;
  truth.contact_point = 2.0e-6;
  truth.baseline = -3e-11;
  ZScores zs;
  const double sigma = 3e-11;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const Synthetic s = make_curve(truth, sigma, seed);
    fit::AfmFitProblem problem = truth;
    problem.modulus = 1.0;  // free: not a start value
    problem.noise_sigma = sigma;
    const fit::AfmFitResult r = fit::afm_fit(s.z, s.f, problem);
    const double ze = (r.modulus - modulus) / r.modulus_error;
    const double zc = (r.contact_point - truth.contact_point) / r.contact_point_error;
    const double zb = (r.baseline - truth.baseline) / r.baseline_error;
    check::below(std::abs(ze), 3.0, std::string(name) + ": E within 3 standard errors");
    check::below(std::abs(zc), 3.0, std::string(name) + ": contact point within 3 standard errors");
    check::below(std::abs(zb), 3.0, std::string(name) + ": baseline within 3 standard errors");
    check::below(std::abs(r.chi2_per_dof - 1.0), 0.15, std::string(name) + ": chi2/dof near 1 with the true noise");
    zs.add(ze);
    zs.add(zc);
    zs.add(zb);
  }
  std::printf("%s: RMS z-score %.3f over %d estimates\n", name, zs.rms(), zs.count);
  check::that(zs.rms() > 0.5 && zs.rms() < 1.6, std::string(name) + ": standard errors calibrated");
}

void check_tilt_recovery(const fit::AfmTip& tip, double modulus, const char* name) {
  fit::AfmFitProblem truth;
  truth.tip = tip;
  truth.modulus = modulus;
  truth.poisson = 0.5;
  truth.contact_point = 2.0e-6;
  truth.baseline = -3e-11;
  const double sigma = 3e-11, tilt = 3e-4;  // 1.2e-9 N over the 4 um curve: 40 sigma
  ZScores zs;
  double least_untilted_chi2 = 1e300;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    Synthetic s = make_curve(truth, sigma, seed);
    for (std::size_t i = 0; i < s.z.size(); ++i) s.f[i] += tilt * (s.z[i] - truth.contact_point);
    fit::AfmFitProblem problem = truth;
    problem.modulus = 1.0;  // free: not a start value
    problem.noise_sigma = sigma;
    problem.free.tilt = true;
    const fit::AfmFitResult r = fit::afm_fit(s.z, s.f, problem);
    const double ze = (r.modulus - modulus) / r.modulus_error;
    const double zc = (r.contact_point - truth.contact_point) / r.contact_point_error;
    const double zb = (r.baseline - truth.baseline) / r.baseline_error;
    const double zm = (r.tilt - tilt) / r.tilt_error;
    std::printf("%s, free tilt, seed %u: E %.2f SE, z_c %.2f SE, b %.2f SE, tilt %.4g (%.2f SE), chi2/dof %.3f\n", name,
                seed, ze, zc, zb, r.tilt, zm, r.chi2_per_dof);
    const std::string tag = std::string(name) + ", free tilt";
    check::below(std::abs(ze), 3.0, tag + ": E within 3 standard errors");
    check::below(std::abs(zc), 3.0, tag + ": contact point within 3 standard errors");
    check::below(std::abs(zb), 3.0, tag + ": baseline within 3 standard errors");
    check::below(std::abs(zm), 3.0, tag + ": tilt within 3 standard errors");
    check::below(std::abs(r.chi2_per_dof - 1.0), 0.15, tag + ": chi2/dof near 1 with the true noise");
    check::that(r.free_count == 4, tag + ": four free parameters");
    zs.add(ze), zs.add(zc), zs.add(zb), zs.add(zm);
    problem.free.tilt = false;
    const fit::AfmFitResult flat = fit::afm_fit(s.z, s.f, problem);
    least_untilted_chi2 = std::min(least_untilted_chi2, flat.chi2_per_dof);
  }
  std::printf("%s, free tilt: RMS z-score %.3f over %d estimates; tilt left out: chi2/dof >= %.3f\n", name, zs.rms(),
              zs.count, least_untilted_chi2);
  check::that(zs.rms() > 0.5 && zs.rms() < 1.6, std::string(name) + ", free tilt: standard errors calibrated");
  check::that(least_untilted_chi2 > 1.15, std::string(name) + ": the tilt matters (chi2/dof > 1.15 without it)");
}

fit::AfmFitProblem coated_truth() {
  fit::AfmFitProblem truth;
  truth.tip = fit::afm_paraboloid(10e-6);
  fit::AfmCoating c;
  c.film = {5e3, 0.5};
  c.substrate.material = {1e6, 0.3};
  c.thickness = 2e-6;
  truth.coating = c;
  truth.contact_point = 2e-6;
  truth.baseline = 1e-10;
  return truth;
}

void check_coating_model() {
  const fit::AfmFitProblem truth = coated_truth();
  const coatcontact::ReducedSolver solver(coatcontact::Stack::film_on(truth.coating->film, truth.coating->substrate));
  const double radius = 10e-6, t = truth.coating->thickness, reduced = 5e3 / 0.75;
  double worst = 0.0;
  for (double a_over_t : {0.05, 0.3, 1.0, 2.5, 7.0}) {
    const coatcontact::ReducedVariables v = solver.solve(a_over_t, 1e-10);
    const double a = a_over_t * t;
    const double delta = a * a / radius * v.delta_s, force = a * a * a * reduced / (2 * radius) * v.pi_s;
    const double model = fit::afm_model_force(truth, {truth.contact_point - delta})[0] - truth.baseline;
    worst = std::max(worst, std::abs(model / force - 1));
  }
  std::printf("coating model vs direct solves: max relative difference %.2e\n", worst);
  // The log-log cubic spline at 16 nodes per decade of a/t: measured 8.3e-6 at these points.
  check::below(worst, 2e-5, "coating force table vs the reduced solver at the same a/t");
}

void check_coating_recovery() {
  const fit::AfmFitProblem truth = coated_truth();
  std::vector<double> z;
  for (int i = 0; i < 300; ++i) z.push_back(4e-6 * (1.0 - i / 299.0));
  for (unsigned seed : {1u, 2u}) {
    std::vector<double> f = fit::afm_model_force(truth, z);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, 2e-11);
    for (double& v : f) v += noise(rng);
    for (int mode = 0; mode < 2; ++mode) {  // 0: E1 free (t fixed); 1: t free (E1 fixed)
      fit::AfmFitProblem p = truth;
      p.free.modulus = mode == 0;
      p.free.thickness = mode == 1;
      if (mode == 0) p.coating->film.youngs_modulus = 2e4;  // a start 4x off
      else p.coating->thickness = 5e-6;
      p.noise_sigma = 2e-11;
      const fit::AfmFitResult r = fit::afm_fit(z, f, p);
      std::printf("coating seed %u mode %d: E1 %.6g +- %.3g, t %.6g +- %.3g, z_c %.8g +- %.3g, chi2/dof %.3f, %.2f s\n", seed,
                  mode, r.modulus, r.modulus_error, r.thickness, r.thickness_error, r.contact_point, r.contact_point_error,
                  r.chi2_per_dof, r.seconds);
      if (mode == 0) check::below(std::abs(r.modulus - 5e3) / r.modulus_error, 3.0, "coating: E1 within 3 standard errors");
      else check::below(std::abs(r.thickness - 2e-6) / r.thickness_error, 3.0, "coating: t within 3 standard errors");
      check::below(std::abs(r.contact_point - 2e-6) / r.contact_point_error, 3.0, "coating: contact point within 3 SE");
      check::below(std::abs(r.baseline - 1e-10) / r.baseline_error, 3.0, "coating: baseline within 3 SE");
    }
  }
}

void check_bad_input() {
  fit::AfmFitProblem problem;
  problem.tip = fit::afm_paraboloid(1e-6);
  check::throws<InputError>([&] { fit::afm_fit({1e-6, 2e-6, 3e-6, 4e-6}, {0, 0, 0, 0}, problem); }, {"points"});
  problem.free.modulus = false;
  problem.modulus = 0;
  check::throws<InputError>([&] { fit::afm_fit({1, 2, 3, 4, 5, 6}, {0, 1, 2, 3, 4, 5}, problem); }, {"fixed E"});
  problem.free.modulus = true;
  // Force falling as the tip goes down: no contact anywhere (best E* clamps at 0).
  std::vector<double> z, f;
  for (int i = 0; i < 50; ++i) {
    z.push_back(1e-6 * (50 - i) / 50.0);
    f.push_back(-1e-9 * i / 50.0);
  }
  check::throws<NumericalError>([&] { fit::afm_fit(z, f, problem); }, {"no contact"});
  check::throws<InputError>([&] { fit::afm_paraboloid(-1.0); }, {"radius"});
}

// The real JPK curves (spot3 and the hydrogel, as a 10 um sphere on a soft half-space): a fit
// whose RSS is not above the brute-force scan's, with the contact point in the approach range.
void check_real(const std::string& dir, const std::string& file, const char* name) {
  const auto curves = afm::read_force_curves(dir + "/" + file);
  const afm::ForceCurve& c = curves.at(0);
  const afm::Segment* seg = c.find_segment(afm::SegmentKind::kApproach);
  check::that(seg != nullptr, "approach segment");
  const std::vector<double> tip_all = c.tip_position();
  const std::vector<double> z(tip_all.begin() + seg->begin, tip_all.begin() + seg->end);
  const std::vector<double> f(c.force.begin() + seg->begin, c.force.begin() + seg->end);
  fit::AfmFitProblem problem;
  problem.tip = fit::afm_paraboloid(10e-6);
  problem.poisson = 0.5;
  const fit::AfmFitResult r = fit::afm_fit(z, f, problem);
  const auto [lo, hi] = std::minmax_element(z.begin(), z.end());
  const Scan scan = brute_force(z, f, 10e-6, *lo, *hi, 20001);
  std::printf("%s: E = %.6g +- %.3g Pa, z_c = %.9g +- %.3g m, b = %.4g N, sigma = %.3g N, R2 = %.5f, %d evals, %.2f ms\n",
              name, r.modulus, r.modulus_error, r.contact_point, r.contact_point_error, r.baseline, r.residual_sigma,
              r.r_squared, r.profile_evaluations, 1e3 * r.seconds);
  std::printf("%s scan: rss %.9e (fit %.9e), z_c %.9g, E %.6g\n", name, scan.rss, r.rss, scan.contact, scan.reduced * 0.75);
  check::that(r.rss <= scan.rss * (1 + 1e-12), "real curve: fit's RSS not above the brute-force scan's");
  check::below(std::abs(r.contact_point - scan.contact), scan.step, "real curve: contact point within one scan step");
  check::that(r.contact_point > *lo && r.contact_point < *hi, "real curve: contact point inside the approach");
  check::that(r.r_squared > 0.9, "real curve: the Hertz model explains the approach");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: test_afm_fit DATA_DIR\n");
    return 2;
  }
  check_tip_tables();
  check_global_optimum_synthetic();
  check_recovery(fit::afm_paraboloid(10e-6), 2e3, "paraboloid");
  check_recovery(fit::afm_cone(70.0 * kPi / 180.0), 5e3, "cone");
  check_recovery(fit::afm_pyramid(35.0 * kPi / 180.0), 5e3, "pyramid");
  check_tilt_recovery(fit::afm_paraboloid(10e-6), 2e3, "paraboloid");
  check_tilt_recovery(fit::afm_cone(70.0 * kPi / 180.0), 5e3, "cone");
  check_coating_model();
  check_coating_recovery();
  check_bad_input();
  check_real(argv[1], "fmt-jpk-fd_spot3-0192.jpk-force", "spot3");
  check_real(argv[1], "fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force", "hydrogel");
  return check::exit_code();
}
