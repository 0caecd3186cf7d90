// Adhesive AFM retract fit: Maugis-Dugdale through the cantilever (coatcontact/afm_fit.hpp,
// THEORY.md section 15, "Maugis-Dugdale through the cantilever").
//  - Model, half-space: afm_model_force against Maugis's closed form written here (THEORY.md
//    section 13, parameterized by m = c/a, the curve's end m -> inf in closed form too) on the
//    branch above the jump-off, the test's own minimum of delta + F/k; the jump-off force
//    against the library's MaugisDugdaleModel::pulloff_spring.
//  - Recovery: synthetic retracts (half-space: the closed form; a coating: the library's MD
//    curve and its spring pull-off, MaugisDugdaleModel::curve and pulloff_spring), with Gaussian
//    noise, a contact-point offset, a baseline and a tilt, give E (E1), w, z_c, b and the tilt
//    within 3 standard errors; chi2/dof near 1 with the true noise.
//  - The JKR limit: on a JKR retract with a range z0 so short that lambda > 1e4, the MD fit's w
//    equals the JKR fit's within kJkrLimit and far inside the standard error; the warning
//    "above 1e4" is given. lambda of the estimates against its formula.
//  - Bad input: a cone tip, no spring constant.
//  - One table per shape (THEORY.md section 15, "One table per shape"): the cohesive-zone table
//    of a film on an elastic base, in Maugis's units (the trial's own L and lambda), is the same
//    for every E1 of one shape E1/E0: P, D, m of the stack (E1, E0) and of (3 E1, 3 E0) at the
//    same (eta, lambda, a_bar) agree to rounding, while a stack of another shape differs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "afm_adhesive_problem.hpp"
#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/stack.hpp"

namespace fit = coatcontact::fit;
using coatcontact::InputError;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The fit's branch (a cubic spline of F against delta on 128 radii from the cohesive-zone
// table) against the closed form, relative to the jump-off force: the homogeneous table equals
// the closed forms to ~1e-10 (THEORY.md section 13), so this is the spline's error.
constexpr double kBranchTable = 1e-4;
// The MD fit at lambda > 1e4 (computed at 1e4, within ~1e-8 of JKR; the table's P to ~1e-4)
// against the JKR fit of the same data: relative difference of w.
constexpr double kJkrLimit = 1e-3;

struct Truth {
  double radius = 20e-9, modulus = 1e9, poisson = 0.3, work = 0.05, spring = 1.0, range = 0.35e-9;
  double contact = 5e-9, baseline = 0.2e-9, tilt = 0.01;
  double deepest = 2e-9;  // indentation at the start of the retract
  bool coated = false;
  double substrate_modulus = 50e9, substrate_poisson = 0.25, thickness = 3e-9;
  double reduced() const { return modulus / (1 - poisson * poisson); }
  double h0() const { return fit::kDugdaleRangeOverZ0 * range; }
  double lambda() const {
    const double k = 4 * reduced() / 3;
    return 2 * (work / h0()) * std::cbrt(radius / (kPi * work * k * k));
  }
};

fit::AfmFitProblem problem_of(const Truth& t) {
  fit::AfmFitProblem p = adhesive_problem(t, fit::AfmModel::kMd);
  p.surface_force_range = t.range;
  return p;
}

struct CurvePoint {
  double delta = 0.0, force = 0.0;
};

// Maugis's half-space MD curve in SI at m = c/a (m = inf: the end a = 0), THEORY.md section 13:
// a_M from the quadratic (lambda A/2) a^2 + (4 lambda^2 B/3) a - 1 = 0, then P, Delta_M.
CurvePoint maugis(const Truth& t, double m) {
  const double lam = t.lambda(), k = 4 * t.reduced() / 3;
  const double force_scale = kPi * t.work * t.radius;
  const double delta_scale = std::cbrt(kPi * kPi * t.work * t.work * t.radius / (k * k));
  if (std::isinf(m)) {  // a m -> c finite: 1 = lambda pi c^2/4 + (4 lambda^2/3)(pi/2 - 1) c
    const double qa = lam * kPi / 4, qb = 4 * lam * lam / 3 * (kPi / 2 - 1);
    const double c = (-qb + std::sqrt(qb * qb + 4 * qa)) / (2 * qa);
    return {-(4.0 / 3.0) * lam * c * delta_scale, -lam * c * c * kPi / 2 * force_scale};
  }
  const double s = std::sqrt(m * m - 1), ac = std::acos(1 / m);
  const double qa = lam / 2 * (s + (m * m - 2) * ac), qb = 4 * lam * lam / 3 * (s * ac - m + 1);
  const double a = qa > 0 ? (-qb + std::sqrt(qb * qb + 4 * qa)) / (2 * qa) : 1 / qb;
  const double p = a * a * a - lam * a * a * (s + m * m * ac);
  const double d = a * a - (4.0 / 3.0) * lam * a * s;
  return {d * delta_scale, p * force_scale};
}

// The half-space curve ordered by growing contact radius, the end first.
std::vector<CurvePoint> half_space_curve(const Truth& t, int n) {
  std::vector<CurvePoint> out = {maugis(t, INFINITY)};
  for (int i = n - 1; i >= 0; --i) out.push_back(maugis(t, 1 + std::pow(10.0, -10.0 + 16.0 * i / (n - 1.0))));
  return out;
}

// The coating's curve from the library's model (its cohesive-zone table), the end first, and
// the spring-control jump-off index from its pulloff_spring.
std::vector<CurvePoint> coating_curve(const Truth& t, int n, double* a_bar_jump, bool* at_end) {
  coatcontact::Material film{t.modulus, t.poisson};
  coatcontact::Substrate substrate;
  substrate.material = {t.substrate_modulus, t.substrate_poisson};
  coatcontact::MaugisDugdaleOptions o;
  o.use_table = true;
  const coatcontact::MaugisDugdaleModel md(coatcontact::Stack::film_on(film, substrate), o);
  const double length = std::cbrt(kPi * t.work * t.radius * t.radius / t.reduced());
  const double eta = t.thickness / length, lam = t.lambda();
  const double k_bar = t.spring * (length * length / t.radius) / (kPi * t.work * t.radius);
  const coatcontact::MaugisDugdalePulloff pull = md.pulloff_spring(eta, lam, k_bar);
  *a_bar_jump = pull.spring_control.point.a_bar;
  *at_end = !pull.spring_control.interior;
  std::vector<double> a_bar = {0.0};
  for (int i = 0; i < n; ++i) a_bar.push_back(1e-3 * std::pow(1e4, i / (n - 1.0)));
  std::vector<CurvePoint> out;
  for (const auto& p : md.curve(eta, lam, a_bar)) {
    out.push_back({p.penetration * length * length / t.radius, p.load * kPi * t.work * t.radius});
  }
  return out;
}

// Index of the minimum of Z = delta + F/k (the jump-off through the spring, THEORY.md section 10).
std::size_t jump_index(const std::vector<CurvePoint>& c, double k) {
  std::size_t s = 0;
  for (std::size_t j = 0; j < c.size(); ++j) {
    if (c[j].delta + c[j].force / k < c[s].delta + c[s].force / k) s = j;
  }
  return s;
}

struct Synthetic {
  std::vector<double> z, f;
};

// A retract along `curve` from index s (the jump-off) up: for each piezo height h of a uniform
// grid the tip sits where Z = z_c - h (linear interpolation), else (past the jump) off at z = h.
Synthetic make_retract(const Truth& t, const std::vector<CurvePoint>& curve, std::size_t s, double sigma,
                       unsigned seed, std::size_t n) {
  const auto zof = [&](std::size_t j) { return curve[j].delta + curve[j].force / t.spring; };
  std::size_t top = s;
  while (top + 1 < curve.size() && curve[top].delta < t.deepest) ++top;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Synthetic out;
  const double h_lo = t.contact - zof(top), h_hi = t.contact + 15e-9;
  std::size_t j = top;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = h_lo + (h_hi - h_lo) * static_cast<double>(i) / static_cast<double>(n - 1);
    const double target = t.contact - h;
    double z = h, f = 0.0;
    if (target >= zof(s)) {
      while (j > s + 1 && zof(j - 1) >= target) --j;
      const CurvePoint& a = curve[j - 1];
      const CurvePoint& b = curve[j];
      const double za = zof(j - 1), zb = zof(j);
      const double x = zb > za ? std::clamp((target - za) / (zb - za), 0.0, 1.0) : 1.0;
      f = a.force + x * (b.force - a.force);
      z = t.contact - (a.delta + x * (b.delta - a.delta));
    }
    out.z.push_back(z);
    out.f.push_back(f + t.baseline + t.tilt * (z - t.contact) + noise(rng));
  }
  return out;
}

void check_half_space_model() {
  Truth t;
  fit::AfmFitProblem p = problem_of(t);
  p.tilt = 0.0;
  p.baseline = 0.0;
  const std::vector<CurvePoint> curve = half_space_curve(t, 40000);
  const std::size_t s = jump_index(curve, t.spring);
  check::that(s > 0, "the half-space case jumps off from a finite contact (an interior minimum)");
  // The library's spring pull-off of the homogeneous stack (eta = 1, any t) against the test's.
  coatcontact::MaugisDugdaleOptions o;
  o.use_table = true;
  const coatcontact::Material m{t.modulus, t.poisson};
  coatcontact::Substrate same;
  same.material = m;
  const coatcontact::MaugisDugdaleModel md(coatcontact::Stack::film_on(m, same), o);
  const double length = std::cbrt(kPi * t.work * t.radius * t.radius / t.reduced());
  const double k_bar = t.spring * (length * length / t.radius) / (kPi * t.work * t.radius);
  const auto pull = md.pulloff_spring(1.0, t.lambda(), k_bar);
  std::printf("half-space lambda %.4g, k_bar %.4g: jump-off F %.6g N (test), %.6g N (pulloff_spring)\n", t.lambda(),
              k_bar, curve[s].force, pull.spring_control.point.load * kPi * t.work * t.radius);
  check::close(pull.spring_control.point.load * kPi * t.work * t.radius, curve[s].force, 1e-4,
               "spring pull-off: the library's against the closed form's minimum of delta + F/k");
  std::vector<double> z, expected;
  for (std::size_t j = s + 1; j < curve.size() && curve[j].delta < 3 * t.deepest; j += 97) {
    z.push_back(t.contact - curve[j].delta);
    expected.push_back(curve[j].force);
  }
  const std::vector<double> model = fit::afm_model_force(p, z);
  double worst = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) worst = std::max(worst, std::abs(model[i] - expected[i]) / std::abs(curve[s].force));
  std::printf("half-space MD branch: %zu points, worst relative error %.3g (of the jump-off force)\n", z.size(), worst);
  check::below(worst, kBranchTable, "half-space MD branch vs Maugis's closed form");
  // Just inside the jump-off (1 % of delta_s: the minimum of Z is flat, its location from the
  // table is known to ~1e-4 relative) the tip pulls with F(a_s) less k times that step; outside, zero.
  const double d_s = curve[s].delta, span = 1e-2 * std::abs(d_s);
  const std::vector<double> edge = fit::afm_model_force(p, {t.contact - d_s - span, t.contact - d_s + span});
  check::close(edge[0], curve[s].force, 3e-3, "force just inside the jump-off");
  check::that(edge[1] == 0.0, "zero force past the jump-off");
}

void check_recovery(const Truth& t, const Synthetic& s, const char* name, int seed, double sigma) {
  const fit::AfmFitResult r = fit_from_far_start(problem_of(t), sigma, s.z, s.f);
  const RecoveryScores z = scores_of(r, t);
  std::printf("%s seed %d: E %.6g (%.2f SE) w %.6g (%.2f SE) z_c %.2f SE b %.2f SE tilt %.2f SE chi2/dof %.3f "
              "lambda %.3g (true %.3g), %.0f ms, %d tables, %ld table solves\n",
              name, seed, r.modulus, z.modulus, r.work, z.work, z.contact, z.baseline, z.tilt, r.chi2_per_dof,
              r.maugis_lambda, t.lambda(),
              r.seconds * 1e3, r.model_evaluations, r.solver_calls);
  for (const auto& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
  const std::string tag = std::string(name) + " seed " + std::to_string(seed);
  check_within_3_se(z, tag);
  check::below(std::abs(r.chi2_per_dof - 1.0), 0.15, tag + ": chi2/dof near 1 with the true noise");
  const double reduced = r.modulus / (1 - t.poisson * t.poisson), k = 4 * reduced / 3;
  check::close(r.maugis_lambda, 2 * (r.work / t.h0()) * std::cbrt(t.radius / (kPi * r.work * k * k)), check::tier::kMachine,
               tag + ": lambda of the estimates (h0 = 0.97 z0)");
  check::that(r.maugis_lambda > 1e-3 && r.maugis_lambda < 1e4, tag + ": lambda in the table's range");
}

// The JKR curve of a sphere on a half-space (as test_afm_jkr_fit.cpp), ordered by radius.
std::vector<CurvePoint> jkr_curve(const Truth& t, int n) {
  std::vector<CurvePoint> out;
  const double length = std::cbrt(kPi * t.work * t.radius * t.radius / t.reduced());
  for (int i = 0; i < n; ++i) {
    const double a = length * 0.05 * std::pow(400.0, i / (n - 1.0));
    out.push_back({a * a / t.radius - std::sqrt(2 * kPi * a * t.work / t.reduced()),
                   4 * t.reduced() * a * a * a / (3 * t.radius) - std::sqrt(8 * kPi * t.work * t.reduced() * a * a * a)});
  }
  return out;
}

void check_jkr_limit() {
  Truth t;
  t.range = 1e-14;  // lambda ~ 4e4 (1.15 at 0.35 nm): computed at 1e4
  const double sigma = 20e-12;
  const std::vector<CurvePoint> curve = jkr_curve(t, 40000);
  const Synthetic s = make_retract(t, curve, jump_index(curve, t.spring), sigma, 11, 1500);
  fit::AfmFitProblem p = problem_of(t);
  p.work = 0.0;
  p.free = {true, true, true, false, true, true};
  p.noise_sigma = sigma;
  const fit::AfmFitResult md = fit::afm_fit(s.z, s.f, p);
  p.model = fit::AfmModel::kJkr;
  const fit::AfmFitResult jkr = fit::afm_fit(s.z, s.f, p);
  const double rel = std::abs(md.work - jkr.work) / jkr.work;
  std::printf("JKR limit (lambda %.3g): w MD %.8g, JKR %.8g (SE %.3g): relative %.3g; E MD %.8g JKR %.8g; %.0f ms\n",
              md.maugis_lambda, md.work, jkr.work, jkr.work_error, rel, md.modulus, jkr.modulus, md.seconds * 1e3);
  check::below(rel, kJkrLimit, "MD fit's w at lambda > 1e4 equals the JKR fit's");
  check::below(std::abs(md.work - jkr.work), 0.1 * jkr.work_error, "the difference is far inside the standard error");
  check::below(std::abs(md.modulus - jkr.modulus) / jkr.modulus, kJkrLimit, "MD fit's E equals the JKR fit's");
  bool warned = false;
  for (const auto& w : md.warnings) warned = warned || w.find("above 10000") != std::string::npos;
  check::that(md.maugis_lambda > 1e4 && warned, "lambda > 1e4 is reported with its warning (use jkr)");
}

void check_bad_input() {
  Truth t;
  const std::vector<CurvePoint> curve = half_space_curve(t, 4000);
  const Synthetic s = make_retract(t, curve, jump_index(curve, t.spring), 20e-12, 3, 300);
  fit::AfmFitProblem p = problem_of(t);
  p.free = {true, true, true, false, true, true};
  p.spring_constant = 0.0;
  check::throws<InputError>([&] { fit::afm_fit(s.z, s.f, p); }, {"Maugis-Dugdale", "spring constant"});
  p = problem_of(t);
  p.tip = fit::afm_cone(0.3);
  check::throws<InputError>([&] { fit::afm_fit(s.z, s.f, p); }, {"Maugis-Dugdale", "sphere"});
  p = problem_of(t);
  p.surface_force_range = -1.0;
  check::throws<InputError>([&] { fit::afm_fit(s.z, s.f, p); }, {"surface-force range"});
}

void check_one_table_per_shape() {
  coatcontact::MaugisDugdaleOptions o;
  o.use_table = true;
  o.table_errors = false;
  const auto model_of = [&](double film, double base) {
    coatcontact::Substrate substrate;
    substrate.material = {base, 0.25};
    return std::make_unique<coatcontact::MaugisDugdaleModel>(coatcontact::Stack::film_on({film, 0.5}, substrate), o);
  };
  const auto shape = model_of(20e3, 10e3), scaled = model_of(60e3, 30e3), other = model_of(60e3, 10e3);
  double worst = 0.0, apart = 0.0;
  for (double eta : {0.5, 2.0}) {
    for (double lambda : {0.05, 1.0, 20.0}) {
      for (double a_bar : {0.0, 0.3, 1.0, 3.0}) {
        const auto p = shape->point(eta, lambda, a_bar), q = scaled->point(eta, lambda, a_bar), r = other->point(eta, lambda, a_bar);
        for (const auto& [x, y, z] : {std::tuple{p.load, q.load, r.load}, std::tuple{p.penetration, q.penetration, r.penetration}}) {
          worst = std::max(worst, std::abs(x - y) / std::max(std::abs(x), 1e-3));
          apart = std::max(apart, std::abs(x - z) / std::max(std::abs(x), 1e-3));
        }
        if (a_bar > 0.0) worst = std::max(worst, std::abs(p.m - q.m) / p.m);
      }
    }
  }
  std::printf("one table per shape: (E1, E0) against (3 E1, 3 E0): largest relative difference of P, D, m %.3g; "
              "against (3 E1, E0), another shape: %.3g\n",
              worst, apart);
  check::below(worst, check::tier::kInterpolation, "the table of one shape E1/E0 is the same for every E1 (Maugis's units)");
  check::below(1e-3, apart, "a stack of another shape has another table");
}

}  // namespace

int main() {
  check_one_table_per_shape();
  check_half_space_model();
  const double sigma = 20e-12;
  {
    const Truth t;
    const std::vector<CurvePoint> curve = half_space_curve(t, 40000);
    const std::size_t s = jump_index(curve, t.spring);
    for (int seed = 1; seed <= 3; ++seed) {
      check_recovery(t, make_retract(t, curve, s, sigma, static_cast<unsigned>(seed), 1500), "half-space", seed, sigma);
    }
  }
  {
    Truth t;
    t.coated = true;
    double a_bar_jump = 0.0;
    bool at_end = false;
    const std::vector<CurvePoint> curve = coating_curve(t, 6000, &a_bar_jump, &at_end);
    const std::size_t s = jump_index(curve, t.spring);
    check::that(!at_end && s > 0, "the coating case jumps off from a finite contact (pulloff_spring: interior)");
    for (int seed = 1; seed <= 2; ++seed) {
      check_recovery(t, make_retract(t, curve, s, sigma, static_cast<unsigned>(seed), 1500), "coating", seed, sigma);
    }
  }
  check_jkr_limit();
  check_bad_input();
  return check::exit_code();
}
