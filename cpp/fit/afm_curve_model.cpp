// The AFM curve model (THEORY.md section 15): Hertz/Sneddon on a half-space with a contact
// point and a baseline, fitted by profiling the residual sum over the contact point with
// (E*, b) solved in closed form at each z_c. See coatcontact/afm_fit.hpp.
#include "coatcontact/afm_fit.hpp"

#include "afm_internal.hpp"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_interp.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_machine.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"

namespace coatcontact::fit {

namespace {

using coatcontact::detail::short_text;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// F(delta) per unit scale and dF/d delta at delta > 0: a tip on a half-space (per E*) or a
// coating (in N).
class PenetrationForce {
 public:
  virtual ~PenetrationForce() = default;
  virtual std::pair<double, double> at(double delta) const = 0;
  virtual double value(double delta) const { return at(delta).first; }
};

// ln F against ln delta through Steffen's monotone spline; below the first node the power law
// of the first two nodes (the small-contact limit), past the last node NumericalError.
class LogLogTable final : public PenetrationForce {
 public:
  // extrapolate: past the last node the power law of the last two nodes (for trial contact
  // points of a search; the caller checks the final indentations against max_penetration()).
  // smooth: a natural cubic spline (smooth data, O(h^4)); else Steffen's monotone one (no
  // overshoot next to a shape's kink).
  LogLogTable(const std::vector<double>& delta, const std::vector<double>& force, std::string what, bool extrapolate = false,
              bool smooth = false)
      : what_(std::move(what)), extrapolate_(extrapolate) {
    for (std::size_t k = 0; k < delta.size(); ++k) {
      if (!(delta[k] > 0.0) || !(force[k] > 0.0)) continue;
      if (!log_delta_.empty() && !(std::log(delta[k]) > log_delta_.back())) continue;
      log_delta_.push_back(std::log(delta[k]));
      log_force_.push_back(std::log(force[k]));
    }
    if (log_delta_.size() < 4) throw NumericalError("afm fit: the force table has too few points (" + what_ + ")");
    first_slope_ = (log_force_[1] - log_force_[0]) / (log_delta_[1] - log_delta_[0]);
    const std::size_t m = log_delta_.size();
    last_slope_ = (log_force_[m - 1] - log_force_[m - 2]) / (log_delta_[m - 1] - log_delta_[m - 2]);
    interp_ = gsl_interp_alloc(smooth ? gsl_interp_cspline : gsl_interp_steffen, log_delta_.size());
    accel_ = gsl_interp_accel_alloc();
    gsl_interp_init(interp_, log_delta_.data(), log_force_.data(), log_delta_.size());
  }
  ~LogLogTable() override {
    gsl_interp_free(interp_);
    gsl_interp_accel_free(accel_);
  }
  LogLogTable(const LogLogTable&) = delete;
  LogLogTable& operator=(const LogLogTable&) = delete;
  double max_penetration() const { return std::exp(log_delta_.back()); }
  // Below this the spline is clear of its natural end condition (the coating's sweep limited
  // to a decade's end: its a/t up to a third of it); past it the whole range is needed.
  double safe_penetration() const { return safe_penetration_; }
  void set_safe_penetration(double delta) { safe_penetration_ = delta; }

  // F alone (the profile's sums need no slope).
  double value(double delta) const override {
    const double x = std::log(delta);
    if (x < log_delta_.front() || x > log_delta_.back()) return at(delta).first;
    return std::exp(gsl_interp_eval(interp_, log_delta_.data(), log_force_.data(), x, accel_));
  }

  std::pair<double, double> at(double delta) const override {
    const double x = std::log(delta);
    if (x < log_delta_.front()) {
      const double g = std::exp(log_force_.front() + first_slope_ * (x - log_delta_.front()));
      return {g, first_slope_ * g / delta};
    }
    if (x > log_delta_.back()) {
      if (extrapolate_) {
        const double g = std::exp(log_force_.back() + last_slope_ * (x - log_delta_.back()));
        return {g, last_slope_ * g / delta};
      }
      throw NumericalError("afm fit: indentation " + short_text(delta) + " m is beyond the model's table (" + what_ + ")");
    }
    const double lg = gsl_interp_eval(interp_, log_delta_.data(), log_force_.data(), x, accel_);
    const double slope = gsl_interp_eval_deriv(interp_, log_delta_.data(), log_force_.data(), x, accel_);
    const double g = std::exp(lg);
    return {g, slope * g / delta};
  }

 private:
  std::string what_;
  bool extrapolate_ = false;
  double safe_penetration_ = std::numeric_limits<double>::infinity();
  std::vector<double> log_delta_, log_force_;
  double first_slope_ = 1.5, last_slope_ = 1.5;
  gsl_interp* interp_ = nullptr;
  gsl_interp_accel* accel_ = nullptr;
};

// A coating's force law resampled for the per-point sums of a fit (THEORY.md section 15, "The
// force law per point"): the cubic Hermite of F in s = sqrt(delta) (sphere) or s = delta (cone)
// on a uniform grid over [0, s(max_delta)], values and slopes from the log-log table (GSL's
// spline and its derivative). A point costs a sqrt, an index and three multiply-adds instead of
// a log, a spline evaluation and an exp. Past the grid: the log-log table itself.
class UniformForceTable final : public PenetrationForce {
 public:
  // Intervals start at kFirstIntervals and double while the estimated largest error exceeds
  // kTolerance x F(max_delta) (at most kMaxIntervals; the estimate says what the grid is worth).
  static constexpr std::size_t kFirstIntervals = 256, kMaxIntervals = 8192;
  static constexpr double kTolerance = 1e-10;

  UniformForceTable(std::unique_ptr<LogLogTable> table, bool sphere, double max_delta)
      : table_(std::move(table)), sphere_(sphere) {
    if (!(max_delta > 0.0)) return;  // no grid: every point from the log-log table
    s_max_ = s_of(max_delta);
    for (std::size_t intervals = kFirstIntervals;; intervals *= 2) {
      build(intervals);
      if (error_estimate_ <= kTolerance || intervals >= kMaxIntervals) break;
    }
  }
  double max_penetration() const { return table_->max_penetration(); }
  double safe_penetration() const { return table_->safe_penetration(); }

  double value(double delta) const override {
    const double x = s_of(delta) * inverse_h_;
    if (!(x >= 0.0 && x < static_cast<double>(intervals_))) return table_->value(delta);
    const auto k = static_cast<std::size_t>(x);
    const double t = x - static_cast<double>(k);
    const double* c = &coefficients_[4 * k];
    return c[0] + t * (c[1] + t * (c[2] + t * c[3]));
  }
  std::pair<double, double> at(double delta) const override {
    const double s = s_of(delta), x = s * inverse_h_;
    if (!(x > 0.0 && x < static_cast<double>(intervals_))) return table_->at(delta);
    const auto k = static_cast<std::size_t>(x);
    const double t = x - static_cast<double>(k);
    const double* c = &coefficients_[4 * k];
    const double slope = (c[1] + t * (2.0 * c[2] + t * 3.0 * c[3])) * inverse_h_;  // dF/ds
    return {c[0] + t * (c[1] + t * (c[2] + t * c[3])), sphere_ ? slope / (2.0 * s) : slope};
  }

 private:
  double s_of(double delta) const { return sphere_ ? std::sqrt(delta) : delta; }
  // F and dF/ds at s > 0 from the log-log table.
  std::pair<double, double> node(double s) const {
    const double delta = sphere_ ? s * s : s;
    const auto [f, df] = table_->at(delta);
    return {f, sphere_ ? df * 2.0 * s : df};
  }
  void build(std::size_t intervals) {
    intervals_ = intervals;
    const double h = s_max_ / static_cast<double>(intervals);
    inverse_h_ = 1.0 / h;
    coefficients_.assign(4 * intervals, 0.0);
    double f0 = 0.0, m0 = 0.0;  // F and dF/ds vanish at s = 0 (F ~ s^3 sphere, s^2 cone)
    for (std::size_t k = 0; k < intervals; ++k) {
      const auto [f1, d1] = node(h * static_cast<double>(k + 1));
      const double m1 = d1 * h;
      double* c = &coefficients_[4 * k];
      c[0] = f0, c[1] = m0, c[2] = 3.0 * (f1 - f0) - 2.0 * m0 - m1, c[3] = 2.0 * (f0 - f1) + m0 + m1;
      f0 = f1, m0 = m1;
    }
    // H''' = 6 c3 / h^3 on an interval; F'''' ~ its jump / h, and |F - H| <= h^4 |F''''| / 384:
    // |c3 jump| / 64 per interval, twice that taken. The first interval holds the table's
    // small-contact power law, not a polynomial in s: checked at its midpoint instead (twice).
    double largest = 2.0 * std::abs(value(sphere_ ? 0.25 * h * h : 0.5 * h) - node(0.5 * h).first);
    for (std::size_t k = 1; k + 1 < intervals; ++k) {
      largest = std::max(largest, std::abs(coefficients_[4 * k + 7] - coefficients_[4 * k + 3]) / 32.0);
    }
    error_estimate_ = f0 > 0.0 ? largest / f0 : 0.0;
  }

  std::unique_ptr<LogLogTable> table_;
  bool sphere_;
  // error_estimate_: the estimated largest |H - F| over the grid relative to F(max_delta).
  double s_max_ = 0.0, inverse_h_ = 0.0, error_estimate_ = 0.0;
  std::size_t intervals_ = 0;
  std::vector<double> coefficients_;  // per interval c0..c3 of H = c0 + c1 t + c2 t^2 + c3 t^3
};

// Sneddon's exact sphere (afm_fit.hpp): g = F/E* and dg/d delta = 2a at delta > 0. With
// x = a/R: delta = a atanh(x), g = R^2 [(1 + x^2) atanh(x) - x]; below x = 0.1 the series
// sum_k 4k/(4k^2 - 1) x^(2k+1) (the closed form loses (R/a)^2 of its digits there).
std::pair<double, double> sneddon_sphere_force(double radius, double delta) {
  constexpr double kMaxX = 1.0 - 1e-8;
  const auto g_of = [radius](double a) {
    const double x = a / radius;
    if (x >= 0.1) return radius * radius * ((1.0 + x * x) * std::atanh(x) - x);
    double sum = 0.0, power = x * x * x;
    for (int k = 1; k <= 12; ++k, power *= x * x) sum += 4.0 * k / (4.0 * k * k - 1.0) * power;
    return radius * radius * sum;
  };
  const double a_max = kMaxX * radius, delta_max = a_max * std::atanh(kMaxX);
  if (delta >= delta_max) return {g_of(a_max) + 2.0 * a_max * (delta - delta_max), 2.0 * a_max};
  const auto found = coatcontact::detail::brent_root([&](double a) { return a * std::atanh(a / radius) - delta; }, 0.0,
                                                     a_max, {0.0, 1e-15, 200});
  if (!found) throw NumericalError("afm fit: Sneddon's sphere: no contact radius at delta = " + short_text(delta));
  return {g_of(found->x), 2.0 * found->x};
}

// g(delta) = F/E* of a tip on a half-space and dg/d delta: closed forms, or Sneddon's table.
class TipForce final : public PenetrationForce {
 public:
  TipForce(const AfmTip& tip, double max_penetration) : tip_(tip) {
    if (tip.kind == AfmTip::Kind::kShape) build_table(max_penetration);
  }

  std::pair<double, double> at(double delta) const override {
    switch (tip_.kind) {
      case AfmTip::Kind::kParaboloid: {
        const double root = std::sqrt(tip_.radius * delta);  // F = (4/3) E* sqrt(R) delta^1.5
        return {(4.0 / 3.0) * root * delta, 2.0 * root};
      }
      case AfmTip::Kind::kCone: {
        const double c = (2.0 / kPi) * std::tan(tip_.angle);  // F = (2/pi) E* tan(beta) delta^2
        return {c * delta * delta, 2.0 * c * delta};
      }
      case AfmTip::Kind::kSneddonSphere:
        return sneddon_sphere_force(tip_.radius, delta);
      case AfmTip::Kind::kShape:
        break;
    }
    if (flat_) return {2.0 * punch_radius_ * delta, 2.0 * punch_radius_};
    return table_->at(delta);
  }

 private:
  // Sneddon on a half-space (§11): delta = delta0(a), F/E* = 2 [a delta0(a) - int_0^a delta0].
  void build_table(double max_penetration) {
    const IndenterShape& shape = *tip_.shape;
    if (shape.flat()) {
      flat_ = true;
      punch_radius_ = shape.max_contact_radius();
      return;
    }
    // a_max: delta0(a_max) >= max_penetration (doubling), within the shape's reach.
    const double reach = shape.max_contact_radius();
    double a_max = 1e-9;
    while (shape.delta0(a_max) < max_penetration) {
      if (a_max >= reach) {
        throw NumericalError("afm fit: indentation " + short_text(max_penetration) +
                             " m is beyond the tip's largest contact radius (" + tip_.description + ")");
      }
      a_max = std::min(2.0 * a_max, reach);
      if (a_max > 1.0) throw NumericalError("afm fit: the tip reaches no indentation of " + short_text(max_penetration) + " m");
    }
    const double a_min = a_max * 1e-5;
    constexpr int kPerDecade = 64;
    const int count = 5 * kPerDecade + 1;
    coatcontact::detail::GslHandlerOff handler_off;
    std::unique_ptr<gsl_integration_workspace, void (*)(gsl_integration_workspace*)> workspace(
        gsl_integration_workspace_alloc(200), gsl_integration_workspace_free);
    std::function<double(double)> delta0 = [&shape](double r) { return shape.delta0(r); };
    gsl_function gf;
    gf.function = [](double r, void* params) { return (*static_cast<std::function<double(double)>*>(params))(r); };
    gf.params = &delta0;
    double integral = 0.0, previous = 0.0;
    std::vector<double> delta, force;
    for (int k = 0; k < count; ++k) {
      const double a = a_min * std::pow(a_max / a_min, k / static_cast<double>(count - 1));
      double piece = 0.0, error = 0.0;
      if (gsl_integration_qags(&gf, previous, a, 0.0, 1e-10, 200, workspace.get(), &piece, &error) != 0) {
        throw NumericalError("afm fit: the tip's Sneddon integral failed at a = " + short_text(a) + " m");
      }
      integral += piece;
      previous = a;
      const double d = shape.delta0(a);
      delta.push_back(d);
      force.push_back(2.0 * (a * d - integral));
    }
    table_ = std::make_unique<LogLogTable>(delta, force, tip_.description);
  }

  const AfmTip& tip_;
  bool flat_ = false;
  double punch_radius_ = 0.0;
  std::unique_ptr<LogLogTable> table_;
};

// The adhesionless force of the tip on a coating (THEORY.md sections 5, 14): per film modulus
// E1 one sweep of the reduced solver over a/t (kept), per thickness t its force table in N.
class CoatingForces {
 public:
  explicit CoatingForces(const AfmFitProblem& problem) : problem_(problem), coating_(*problem.coating) {
    if (problem.tip.kind == AfmTip::Kind::kShape || problem.tip.kind == AfmTip::Kind::kSneddonSphere) {
      throw InputError("afm fit: a coating takes a sphere (--radius), a cone or a pyramid tip (got " + problem.tip.description + ")");
    }
    const double decades = std::log10(kCoatingAOverT[1] / kCoatingAOverT[0]);
    const int count = static_cast<int>(std::lround(decades * kCoatingPerDecade)) + 1;
    for (int k = 0; k < count; ++k) {
      a_over_t_.push_back(kCoatingAOverT[0] * std::pow(10.0, decades * k / (count - 1)));
    }
    if (!coating_.direct) {
      a_over_t_.back() = kCoatingAOverT[1];  // inside the table's range despite rounding
      table_ = internal::afm_coated_table(coating_);
    }
  }
  long solver_calls() const { return table_ ? static_cast<long>(table_->source_solves()) : solver_calls_; }
  // Tabled: the sweep stops at a/t = a_over_t_max (a decade's end: the table builds no decade
  // above it); widen() restores the whole range. Returns whether it changed the sweep.
  bool limit_reach(double a_over_t_max) {
    if (!table_ || !(a_over_t_max < a_over_t_.back())) return false;
    std::vector<double> kept;
    for (double v : a_over_t_) {
      if (v <= a_over_t_max * (1 + 1e-9)) kept.push_back(std::min(v, a_over_t_max));
    }
    if (kept.size() < 8) return false;
    full_ = a_over_t_;
    a_over_t_ = std::move(kept);
    sweeps_.clear();
    return true;
  }
  bool limited() const { return !full_.empty(); }
  // E1 only scales the force (a film on a rigid base, tabled): F(E1) = (E1*/E1_ref*) F(E1_ref).
  bool scale_free() const { return table_ && table_->scale_free(); }

  // The fits' tables are resampled on [0, max_delta] (UniformForceTable); 0: not resampled.
  void resample_up_to(double max_delta) { resample_delta_ = max_delta; }

  std::unique_ptr<UniformForceTable> force(double film_modulus, double thickness) {
    const std::vector<ReducedVariables>& sweep = sweep_of(film_modulus);
    // A stack: a/T and the top layer's E* (AfmCoating; one film: t and E1*).
    const double reduced = coating_.reference_modulus(film_modulus);
    const double length = coating_.total_thickness(thickness);
    std::vector<double> delta, force;
    const bool sphere = problem_.tip.kind == AfmTip::Kind::kParaboloid;
    const double radius = problem_.tip.radius, cot = 1.0 / std::tan(problem_.tip.angle);
    for (const ReducedVariables& v : sweep) {
      const double a = v.a_over_t * length;
      if (sphere) {
        delta.push_back(a * a / radius * v.delta_s);
        force.push_back(a * a * a * reduced / (2.0 * radius) * v.pi_s);
      } else {
        delta.push_back(kPi * a * cot / 2.0 * v.delta_c);
        force.push_back(kPi * a * a * reduced * cot / 4.0 * v.pi_c);
      }
    }
    auto table = std::make_unique<LogLogTable>(delta, force, "coating, a/t up to " + short_text(kCoatingAOverT[1]), true, true);
    if (limited()) {  // the natural spline's end effect decays ~0.27x a node: 7 nodes in (A/3, A]
      std::size_t k = 0;
      while (k + 1 < sweep.size() && sweep[k + 1].a_over_t <= sweep.back().a_over_t / 3.0) ++k;
      table->set_safe_penetration(delta[k]);
    }
    return std::make_unique<UniformForceTable>(std::move(table), sphere, resample_delta_);
  }

 private:
  const std::vector<ReducedVariables>& sweep_of(double film_modulus) {
    auto it = sweeps_.find(film_modulus);
    if (it != sweeps_.end()) return it->second;
    if (table_) {  // the tabled force law: lookups, no solve
      const std::vector<CoatedValues> values = table_->at(film_modulus, a_over_t_, node_cache_);
      std::vector<ReducedVariables> sweep(values.size());
      for (std::size_t k = 0; k < values.size(); ++k) {
        static_cast<ReducedValues&>(sweep[k]) = values[k].point;
        sweep[k].a_over_t = a_over_t_[k];
        sweep[k].error_estimate = values[k].error_estimate;
      }
      if (sweeps_.size() > 64) sweeps_.clear();
      return sweeps_.emplace(film_modulus, std::move(sweep)).first->second;
    }
    const ReducedSolver solver(coating_.stack_with(film_modulus, coating_.thickness));
    std::vector<ReducedVariables> sweep = solver.sweep(a_over_t_, coating_.solver_tolerance);
    solver_calls_ += static_cast<long>(a_over_t_.size());
    if (sweeps_.size() > 64) sweeps_.clear();
    return sweeps_.emplace(film_modulus, std::move(sweep)).first->second;
  }

  const AfmFitProblem& problem_;
  const AfmCoating& coating_;
  std::vector<double> a_over_t_, full_;  // full_: the whole range while limited
  std::map<double, std::vector<ReducedVariables>> sweeps_;
  long solver_calls_ = 0;
  double resample_delta_ = 0.0;
  std::shared_ptr<const CoatedTable> table_;  // null: the direct path
  CoatedSweepCache node_cache_;  // the nodes at a_over_t_: a trial E1 only sums across them
};

// The a/t a coated fit's indentations up to max_delta can reach, rounded up to a decade's end:
// a = sqrt(R delta / Delta_s) (sphere), 2 delta tan(beta) / (pi Delta_c) (cone), Delta >= 1/4
// (1/2 for a thin film on a rigid base; 1 on a half-space; above 1 for a stiff film).
double coating_reach(const AfmFitProblem& problem, double max_delta) {
  const double t = problem.coating->thickness;
  const double a = problem.tip.kind == AfmTip::Kind::kParaboloid ? 2.0 * std::sqrt(problem.tip.radius * max_delta)
                                                                  : 8.0 * max_delta * std::tan(problem.tip.angle) / kPi;
  return std::pow(10.0, std::max(0.0, std::ceil(std::log10(a / t) - 1e-9)));
}

// At one z_c: the closed-form (E*, b) (E* >= 0) and the residual sum of squares. Forces are
// centred on their mean (b is then relative to it) to keep the sums well conditioned.
struct LinearFit {
  double reduced_modulus = 0.0, baseline = 0.0, rss = 0.0, tilt = 0.0;
};

class Profile {
 public:
  // free_scale: E* (the factor of `force`) in closed form, else fixed_scale; likewise b.
  Profile(const std::vector<double>& z, const std::vector<double>& f, const PenetrationForce& force, bool free_scale,
          double fixed_scale, bool free_baseline, double fixed_baseline)
      : force_(force), uniform_(dynamic_cast<const UniformForceTable*>(&force)), free_scale_(free_scale),
        free_baseline_(free_baseline), fixed_scale_(fixed_scale) {
    mean_ = std::accumulate(f.begin(), f.end(), 0.0) / static_cast<double>(f.size());
    fixed_baseline_ = fixed_baseline - mean_;
    // Sorted by tip position: the points in contact (z < z_c) are a prefix.
    std::vector<std::size_t> order(z.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return z[a] < z[b]; });
    z_.reserve(z.size());
    centred_.reserve(z.size());
    for (std::size_t i : order) {
      z_.push_back(z[i]);
      centred_.push_back(f[i] - mean_);
    }
    for (double v : centred_) sff_ += v * v;
  }
  // A free baseline tilt m: F = b + m (z - z_c) + E* g (THEORY.md section 15, "Free tilt").
  void free_tilt() {
    free_tilt_ = true;
    origin_ = 0.5 * (z_.front() + z_.back());
    for (std::size_t i = 0; i < z_.size(); ++i) {
      const double x = z_[i] - origin_;
      sx_ += x, sxx_ += x * x, sxf_ += x * centred_[i];
    }
  }

  // nanite's contact-point weights (AfmFitProblem::weight_cp), D > 0.
  void weight_cp(double distance) { weight_cp_ = distance; }

  LinearFit at(double contact_point) const {
    ++evaluations_;
    if (free_tilt_) return at_with_tilt(contact_point);
    if (weight_cp_ > 0.0) return at_weighted(contact_point);
    const auto [sg, sgg, sgf] = uniform_ ? sums(contact_point, *uniform_) : sums(contact_point, force_);
    const double n = static_cast<double>(z_.size());
    double e = fixed_scale_, b = fixed_baseline_;
    if (free_scale_ && free_baseline_) {
      const double var = sgg - sg * sg / n;
      e = var > 0.0 ? std::max(0.0, sgf / var) : 0.0;  // sum F' = 0: cov = sgf
      b = -e * sg / n;
    } else if (free_scale_) {
      e = sgg > 0.0 ? std::max(0.0, (sgf - b * sg) / sgg) : 0.0;
    } else if (free_baseline_) {
      b = -e * sg / n;
    }
    // sum (F' - b - e g)^2 with sum F' = 0.
    const double rss = sff_ + n * b * b + e * e * sgg - 2.0 * e * sgf + 2.0 * b * e * sg;
    return {e, b + mean_, std::max(0.0, rss)};
  }
  int evaluations() const { return evaluations_; }

 private:
  // The least squares of w F' = w (b + e g), w = min(|z - z_c|/D, 1), at this z_c.
  LinearFit at_weighted(double contact_point) const {
    double sw = 0.0, sf = 0.0, sff = 0.0, sg = 0.0, sgg = 0.0, sgf = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i) {
      const double w = std::min(std::abs(z_[i] - contact_point) / weight_cp_, 1.0), ww = w * w;
      const double f = centred_[i], delta = contact_point - z_[i];
      sw += ww, sf += ww * f, sff += ww * f * f;
      if (delta <= 0.0) continue;
      const double g = g_at(delta);
      sg += ww * g, sgg += ww * g * g, sgf += ww * g * f;
    }
    double e = fixed_scale_, b = fixed_baseline_;
    if (free_scale_ && free_baseline_ && sw > 0.0) {
      const double var = sgg - sg * sg / sw;
      e = var > 0.0 ? std::max(0.0, (sgf - sg * sf / sw) / var) : 0.0;
      b = (sf - e * sg) / sw;
    } else if (free_scale_) {
      if (free_baseline_) b = 0.0;
      e = sgg > 0.0 ? std::max(0.0, (sgf - b * sg) / sgg) : 0.0;
    } else if (free_baseline_ && sw > 0.0) {
      b = (sf - e * sg) / sw;
    }
    const double rss = sff + sw * b * b + e * e * sgg - 2.0 * e * sgf - 2.0 * b * sf + 2.0 * b * e * sg;
    return {e, b + mean_, std::max(0.0, rss)};
  }

  // The least squares of F' = b + m u + e g (u = z - z_c) over the free ones of (e, b, m), the
  // others at their fixed values (m free here), e >= 0: the normal equations of the free
  // columns; a negative e is clamped at 0 and (b, m) solved again.
  LinearFit at_with_tilt(double contact_point) const {
    double sg = 0.0, sgg = 0.0, sgf = 0.0, sxg = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i) {
      const double delta = contact_point - z_[i];
      if (delta <= 0.0) break;
      const double g = g_at(delta);
      sg += g, sgg += g * g, sgf += g * centred_[i], sxg += (z_[i] - origin_) * g;
    }
    const double n = static_cast<double>(z_.size()), c = contact_point - origin_;
    // Sums over u = x - c.
    const double su = sx_ - n * c, suu = sxx_ - 2.0 * c * sx_ + n * c * c, suf = sxf_, sug = sxg - c * sg;
    // Columns 0: g, 1: 1, 2: u; gram[a][b] and right side r[a] = column . F'.
    const double gram[3][3] = {{sgg, sg, sug}, {sg, n, su}, {sug, su, suu}};
    const double right[3] = {sgf, 0.0, suf};
    const auto solve = [&](bool with_scale, double e_fixed) {
      std::vector<int> cols;
      if (with_scale) cols.push_back(0);
      if (free_baseline_) cols.push_back(1);
      cols.push_back(2);
      double fixed[3] = {with_scale ? 0.0 : e_fixed, free_baseline_ ? 0.0 : fixed_baseline_, 0.0};
      const std::size_t k = cols.size();
      double a[3][4];
      for (std::size_t i = 0; i < k; ++i) {
        for (std::size_t j = 0; j < k; ++j) a[i][j] = gram[cols[i]][cols[j]];
        a[i][k] = right[cols[i]];
        for (int f = 0; f < 3; ++f) a[i][k] -= gram[cols[i]][f] * fixed[f];
      }
      // Gaussian elimination with partial pivoting (k <= 3).
      for (std::size_t p = 0; p < k; ++p) {
        std::size_t best = p;
        for (std::size_t i = p + 1; i < k; ++i) {
          if (std::abs(a[i][p]) > std::abs(a[best][p])) best = i;
        }
        for (std::size_t j = 0; j <= k; ++j) std::swap(a[p][j], a[best][j]);
        if (!(std::abs(a[p][p]) > 0.0)) return std::optional<std::array<double, 3>>{};
        for (std::size_t i = p + 1; i < k; ++i) {
          const double m = a[i][p] / a[p][p];
          for (std::size_t j = p; j <= k; ++j) a[i][j] -= m * a[p][j];
        }
      }
      double x[3] = {0.0, 0.0, 0.0};
      for (std::size_t p = k; p-- > 0;) {
        double v = a[p][k];
        for (std::size_t j = p + 1; j < k; ++j) v -= a[p][j] * x[j];
        x[p] = v / a[p][p];
      }
      std::array<double, 3> out = {fixed[0], fixed[1], fixed[2]};
      for (std::size_t i = 0; i < k; ++i) out[static_cast<std::size_t>(cols[i])] = x[i];
      return std::optional<std::array<double, 3>>{out};
    };
    std::optional<std::array<double, 3>> v = solve(free_scale_, fixed_scale_);
    if (v && free_scale_ && !((*v)[0] >= 0.0)) v = solve(false, 0.0);
    if (!v) return {0.0, 0.0, kInfinity, 0.0};
    const double e = (*v)[0], b = (*v)[1], m = (*v)[2];
    // sum (F' - e g - b - m u)^2
    const double rss = sff_ + e * e * sgg + n * b * b + m * m * suu - 2.0 * e * sgf - 2.0 * m * suf + 2.0 * e * b * sg +
                       2.0 * e * m * sug + 2.0 * b * m * su;
    return {e, b + mean_, std::max(0.0, rss), m};
  }

  // sum g, sum g^2, sum g F' over the points in contact (a prefix: z sorted). Instantiated for a
  // coating's resampled table apart, its calls then direct and inlined (the class is final).
  template <class Force>
  std::array<double, 3> sums(double contact_point, const Force& force) const {
    double sg = 0.0, sgg = 0.0, sgf = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i) {
      const double delta = contact_point - z_[i];
      if (delta <= 0.0) break;
      const double g = force.value(delta);
      sg += g;
      sgg += g * g;
      sgf += g * centred_[i];
    }
    return {sg, sgg, sgf};
  }
  // The per-point force: a coating's resampled table called directly (inlined, the class is final).
  double g_at(double delta) const { return uniform_ ? uniform_->value(delta) : force_.value(delta); }

  const PenetrationForce& force_;
  const UniformForceTable* uniform_;
  bool free_scale_, free_baseline_;
  double fixed_scale_, fixed_baseline_ = 0.0;
  std::vector<double> z_, centred_;
  double mean_ = 0.0, sff_ = 0.0;
  bool free_tilt_ = false;
  double weight_cp_ = 0.0;
  double origin_ = 0.0, sx_ = 0.0, sxx_ = 0.0, sxf_ = 0.0;
  mutable int evaluations_ = 0;
};

struct ContactSearch {
  double contact_point = 0.0;
  LinearFit linear;
  int evaluations = 0;
};

// The contact point: grid over [z_lo, c_hi], then Brent on the brackets of the three lowest
// grid minima (the profile has a kink where a point enters contact and may have several
// minima; the grid keeps the global one, Brent polishes it). Fixed: the problem's value.
ContactSearch search_contact(const Profile& profile, const AfmFitProblem& problem, double z_lo, double c_hi,
                             std::size_t grid_points, double relative_tolerance = 1e-12, std::size_t polished = 3) {
  ContactSearch out;
  double contact = problem.contact_point;
  if (problem.free.contact_point) {
    const double span = c_hi - z_lo;
    const std::size_t m = std::max<std::size_t>(grid_points, 16);
    std::vector<double> grid(m), cost(m);
    for (std::size_t k = 0; k < m; ++k) {
      grid[k] = z_lo + span * static_cast<double>(k) / static_cast<double>(m - 1);
      cost[k] = profile.at(grid[k]).rss;
    }
    std::vector<std::size_t> minima;
    for (std::size_t k = 0; k < m; ++k) {
      const bool left = k == 0 || cost[k] <= cost[k - 1];
      const bool right = k + 1 == m || cost[k] <= cost[k + 1];
      if (left && right) minima.push_back(k);
    }
    std::sort(minima.begin(), minima.end(), [&](std::size_t a, std::size_t b) { return cost[a] < cost[b]; });
    if (minima.size() > polished) minima.resize(polished);
    double best = cost[minima.front()];
    contact = grid[minima.front()];
    const auto rss = [&](double c) { return profile.at(c).rss; };
    // GSL's Brent steps no closer than sqrt(eps)|x| to its best point, so its bracket stalls at
    // 2 sqrt(eps)|x| (measured): a tolerance below that is never met and only runs out the
    // iterations (~200 evaluations per minimum). 3 sqrt(eps)|x| is the finest it reaches.
    const double reachable = 3.0 * GSL_SQRT_DBL_EPSILON * std::max(std::abs(z_lo), std::abs(c_hi));
    for (std::size_t k : minima) {
      if (k == 0 || k + 1 == m) continue;
      const auto found = coatcontact::detail::brent_minimum(rss, grid[k - 1], cost[k - 1], grid[k], cost[k], grid[k + 1], cost[k + 1],
                                                            {std::max(span * relative_tolerance, reachable), 0.0, 200});
      if (!found) continue;
      const double value = rss(found->x);
      if (value < best) {
        best = value;
        contact = found->x;
      }
    }
  }
  out.contact_point = contact;
  out.linear = profile.at(contact);
  out.evaluations = profile.evaluations();
  return out;
}

// Minimum over ln p of `cost` (one free coating parameter): a log grid within
// kCoatingSearchFactor of `hint`, widened by a decade at a time (at most two) while the best
// grid point is at an end, then Brent in its bracket.
// strict = false (an inner search inside another): the best end point instead of the error.
double minimize_log(const std::function<double(double)>& cost, double hint, const std::string& name, bool strict = true) {
  const double half = std::log(kCoatingSearchFactor);
  const double step = std::log(10.0) / kCoatingSearchPointsPerDecade;
  std::map<double, double> values;  // ln p -> cost
  const auto eval = [&](double u) {
    auto it = values.find(u);
    if (it != values.end()) return it->second;
    const double c = cost(std::exp(u));
    values[u] = c;
    return c;
  };
  double lo = std::log(hint) - half, hi = std::log(hint) + half;
  for (int widen = 0;; ++widen) {
    for (double u = lo; u <= hi + 1e-9; u += step) eval(u);
    const auto best = std::min_element(values.begin(), values.end(), [](auto& a, auto& b) { return a.second < b.second; });
    const bool at_low = best == values.begin(), at_high = std::next(best) == values.end();
    if (!at_low && !at_high) {
      const auto left = std::prev(best), right = std::next(best);
      const auto found = coatcontact::detail::brent_minimum(
          [&](double u) { return cost(std::exp(u)); }, left->first, left->second, best->first, best->second, right->first,
          right->second, {1e-7, 0.0, 100});
      if (found && cost(std::exp(found->x)) <= best->second) return std::exp(found->x);
      return std::exp(best->first);
    }
    if (widen == 2) {
      if (!strict) return std::exp(best->first);
      throw NumericalError("afm fit: " + name + " runs out of its search range (best at " + short_text(std::exp(best->first)) +
                           "); the data do not determine it, or its given value is far off");
    }
    if (at_low) lo -= std::log(10.0);
    if (at_high) hi += std::log(10.0);
  }
}

void check_tip(const AfmTip& tip) {
  switch (tip.kind) {
    case AfmTip::Kind::kParaboloid:
    case AfmTip::Kind::kSneddonSphere:
      if (!(tip.radius > 0.0) || !std::isfinite(tip.radius)) throw InputError("afm fit: the tip radius must be > 0 (got " + short_text(tip.radius) + ")");
      return;
    case AfmTip::Kind::kCone:
      if (!(tip.angle > 0.0 && tip.angle < kPi / 2)) throw InputError("afm fit: the cone's half angle must be in (0, 90) degrees");
      return;
    case AfmTip::Kind::kShape:
      if (!tip.shape) throw InputError("afm fit: no tip shape");
      return;
  }
}

}  // namespace

AfmTip afm_paraboloid(double radius) {
  AfmTip tip;
  tip.kind = AfmTip::Kind::kParaboloid;
  tip.radius = radius;
  tip.description = "paraboloid, R = " + short_text(radius) + " m";
  check_tip(tip);
  return tip;
}

AfmTip afm_cone(double half_angle) {
  AfmTip tip;
  tip.kind = AfmTip::Kind::kCone;
  tip.angle = half_angle;
  tip.description = "cone, half angle " + short_text(half_angle * 180.0 / kPi) + " deg";
  check_tip(tip);
  return tip;
}

AfmTip afm_pyramid(double face_half_angle) {
  if (!(face_half_angle > 0.0 && face_half_angle < kPi / 2)) {
    throw InputError("afm fit: the pyramid's face half angle must be in (0, 90) degrees");
  }
  AfmTip tip = afm_cone(std::atan(2.0 * std::tan(face_half_angle) / std::sqrt(kPi)));
  tip.description = "four-sided pyramid, face half angle " + short_text(face_half_angle * 180.0 / kPi) +
                    " deg, as the cone of equal area (half angle " + short_text(tip.angle * 180.0 / kPi) + " deg)";
  return tip;
}

AfmTip afm_pyramid3(double face_angle) {
  if (!(face_angle > 0.0 && face_angle < kPi / 2)) {
    throw InputError("afm fit: the three-sided pyramid's face angle must be in (0, 90) degrees");
  }
  AfmTip tip = afm_cone(std::atan(0.5 * kPi * 0.8887 * std::tan(face_angle)));
  tip.description = "three-sided pyramid, face angle " + short_text(face_angle * 180.0 / kPi) +
                    " deg (nanite hertz_pyr3s, F = 0.8887 tan(theta) E* delta^2)";
  return tip;
}

AfmTip afm_sneddon_sphere(double radius) {
  AfmTip tip;
  tip.kind = AfmTip::Kind::kSneddonSphere;
  tip.radius = radius;
  tip.description = "sphere (Sneddon, exact), R = " + short_text(radius) + " m";
  check_tip(tip);
  return tip;
}

AfmTip afm_shape(std::shared_ptr<const IndenterShape> shape) {
  AfmTip tip;
  tip.kind = AfmTip::Kind::kShape;
  tip.description = shape ? shape->description() : std::string();
  tip.shape = std::move(shape);
  check_tip(tip);
  return tip;
}

std::vector<double> afm_force_per_modulus(const AfmTip& tip, const std::vector<double>& penetration) {
  check_tip(tip);
  double max_delta = 0.0;
  for (double d : penetration) max_delta = std::max(max_delta, d);
  const TipForce force(tip, max_delta > 0.0 ? max_delta : 1e-9);
  std::vector<double> g(penetration.size(), 0.0);
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (penetration[i] > 0.0) g[i] = force.at(penetration[i]).first;
  }
  return g;
}

std::vector<double> afm_model_force(const AfmFitProblem& problem, const std::vector<double>& tip_position) {
  check_tip(problem.tip);
  return problem.model.info().model_force(problem, tip_position);
}

std::vector<double> internal::afm_hertz_model_force(const AfmFitProblem& problem, const std::vector<double>& tip_position) {
  std::vector<double> delta(tip_position.size());
  for (std::size_t i = 0; i < delta.size(); ++i) delta[i] = std::max(0.0, problem.contact_point - tip_position[i]);
  std::vector<double> f(delta.size(), problem.baseline);
  // The baseline's tilt (0 unless a fit estimated it).
  for (std::size_t i = 0; i < f.size(); ++i) f[i] += problem.tilt * (tip_position[i] - problem.contact_point);
  if (problem.coating) {
    // Only the decades of a/t these indentations reach (the whole range if they pass them).
    CoatingForces forces(problem);
    const double max_delta = *std::max_element(delta.begin(), delta.end());
    if (max_delta > 0.0) forces.limit_reach(coating_reach(problem, max_delta));
    auto table = forces.force(problem.coating->film.youngs_modulus, problem.coating->thickness);
    if (max_delta > table->safe_penetration()) {
      CoatingForces whole(problem);
      table = whole.force(problem.coating->film.youngs_modulus, problem.coating->thickness);
    }
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (delta[i] > 0.0) f[i] += table->at(delta[i]).first;
    }
    return f;
  }
  const std::vector<double> g = afm_force_per_modulus(problem.tip, delta);
  const double reduced = problem.modulus / (1.0 - problem.poisson * problem.poisson);
  for (std::size_t i = 0; i < f.size(); ++i) f[i] += reduced * g[i];
  return f;
}

namespace {

void check_fit_input(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                     int free_count) {
  check_tip(problem.tip);
  if (z.size() != force.size()) throw InputError("afm fit: tip position and force differ in length");
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!std::isfinite(z[i]) || !std::isfinite(force[i])) {
      throw InputError("afm fit: point " + std::to_string(i) + " is not finite");
    }
  }
  if (!(problem.weight_cp >= 0.0 && std::isfinite(problem.weight_cp))) {
    throw InputError("afm fit: the contact-point weighting distance must be >= 0 m (got " + short_text(problem.weight_cp) + ")");
  }
  if (problem.weight_cp > 0.0 && (problem.coating || problem.free.tilt || problem.model != AfmModel::kHertz)) {
    throw InputError("afm fit: contact-point weighting takes the adhesionless half-space fit without a free tilt");
  }
  if (problem.coating) {
    const AfmCoating& c = *problem.coating;
    if (!(c.film.youngs_modulus > 0.0 && std::isfinite(c.film.youngs_modulus))) {
      throw InputError("afm fit: the film's E1 must be > 0 (got " + short_text(c.film.youngs_modulus) + ")");
    }
    if (!(c.thickness > 0.0 && std::isfinite(c.thickness))) {
      throw InputError("afm fit: the film thickness must be > 0 (got " + short_text(c.thickness) + ")");
    }
  } else {
    if (!(problem.poisson > -1.0 && problem.poisson <= 0.5)) {
      throw InputError("afm fit: Poisson's ratio must be in (-1, 0.5] (got " + short_text(problem.poisson) + ")");
    }
    if (!problem.free.modulus && !(problem.modulus > 0.0 && std::isfinite(problem.modulus))) {
      throw InputError("afm fit: a fixed E must be > 0 (got " + short_text(problem.modulus) + ")");
    }
    if (problem.free.thickness) throw InputError("afm fit: t is free only on a coating");
  }
  const std::size_t n = z.size();
  if (n < static_cast<std::size_t>(free_count) + 2) {
    throw InputError("afm fit: " + std::to_string(n) + " points in the fitted range; " + std::to_string(free_count) +
                     " free parameters need at least " + std::to_string(free_count + 2));
  }
}

}  // namespace

namespace internal {

// s^2 (J^T J)^-1 on the column-scaled normal matrix (Cholesky): the standard errors.
std::vector<double> afm_standard_errors(const std::vector<std::vector<double>>& columns, double sigma) {
  const std::size_t p = columns.size();
  if (p == 0) return {};
  const std::size_t n = columns.front().size();
  std::vector<double> scale(p, 0.0);
  for (std::size_t a = 0; a < p; ++a) {
    for (double v : columns[a]) scale[a] += v * v;
    scale[a] = std::sqrt(scale[a]);
    if (!(scale[a] > 0.0)) throw NumericalError("afm fit: a free parameter does not change the model at the optimum");
  }
  coatcontact::detail::GslHandlerOff handler_off;
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> normal(gsl_matrix_alloc(p, p), gsl_matrix_free);
  for (std::size_t a = 0; a < p; ++a) {
    for (std::size_t b = 0; b < p; ++b) {
      double s = 0.0;
      for (std::size_t i = 0; i < n; ++i) s += columns[a][i] * columns[b][i];
      gsl_matrix_set(normal.get(), a, b, s / (scale[a] * scale[b]));
    }
  }
  if (gsl_linalg_cholesky_decomp1(normal.get()) != 0) {
    throw NumericalError("afm fit: the free parameters are not identifiable from the fitted points");
  }
  gsl_linalg_cholesky_invert(normal.get());
  std::vector<double> errors(p);
  for (std::size_t a = 0; a < p; ++a) errors[a] = sigma * std::sqrt(gsl_matrix_get(normal.get(), a, a)) / scale[a];
  return errors;
}

void afm_residual_statistics(AfmFitResult& r, const std::vector<double>& force, double noise_sigma, int free_count,
                             double contact_threshold, const std::string& no_contact) {
  const std::size_t n = force.size();
  const double mean = std::accumulate(force.begin(), force.end(), 0.0) / static_cast<double>(n);
  double tss = 0.0;
  r.residual.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (r.indentation[i] > contact_threshold) ++r.points_in_contact;
    r.max_indentation = std::max(r.max_indentation, r.indentation[i]);
    r.residual[i] = r.model_force[i] - force[i];
    r.rss += r.residual[i] * r.residual[i];
    tss += (force[i] - mean) * (force[i] - mean);
  }
  if (r.points_in_contact == 0) throw NumericalError("afm fit: " + no_contact);
  const double dof = static_cast<double>(n) - free_count;
  r.residual_sigma = std::sqrt(r.rss / dof);
  r.r_squared = tss > 0.0 ? 1.0 - r.rss / tss : 0.0;
  if (noise_sigma > 0.0) {
    r.chi2 = r.rss / (noise_sigma * noise_sigma);
    r.chi2_per_dof = r.chi2 / dof;
  }
}

}  // namespace internal

namespace {

// The statistics of a fit found: indentations, residuals, and the free parameters' standard
// errors from their Jacobian `columns` (in the order of `error_slots`), under nanite's
// contact-point weights when the problem has them.
void finish_fit(AfmFitResult& r, const std::vector<double>& z, const std::vector<double>& force,
                const AfmFitProblem& problem, int free_count, std::vector<std::vector<double>>& columns,
                const std::vector<double*>& error_slots) {
  const std::size_t n = z.size();
  if (problem.free.tilt) r.tilt_origin = r.contact_point;
  r.indentation.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.indentation[i] = r.contact_point - z[i];
  internal::afm_residual_statistics(r, force, problem.noise_sigma, free_count, 0.0,
                                    "the data show no contact in the fitted range; widen the range or check the segment");
  double sigma = r.residual_sigma;
  if (problem.weight_cp > 0.0) {  // the weighted problem's Jacobian and residual sigma
    double rss = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double w = std::min(std::abs(z[i] - r.contact_point) / problem.weight_cp, 1.0);
      for (std::vector<double>& column : columns) column[i] *= w;
      rss += w * w * r.residual[i] * r.residual[i];
    }
    sigma = std::sqrt(rss / (static_cast<double>(n) - free_count));
  }
  const std::vector<double> errors = internal::afm_standard_errors(columns, sigma);
  for (std::size_t a = 0; a < errors.size(); ++a) *error_slots[a] = errors[a];
}

// E1 of the coated Hertz fit on an elastic base, t fixed (THEORY.md section 15, "Tabled coated
// force laws", "The search"): the fixed point of E1 <- (closed-form scale) E1, each step one
// contact-point search with the shape at the current E1 (the half-space's search), secant-
// accelerated; then Gauss-Newton on (ln E1, z_c, b, m) with the shape's ln E1-derivative by
// central differences, to the least squares itself (the fixed point is not it). nullopt: no
// convergence (the caller runs the nested search).
struct ProfiledModulus {
  double modulus = 0.0, contact_point = 0.0, contact_point_error = 0.0;
};
std::optional<ProfiledModulus> profiled_film_modulus(CoatingForces& forces, const std::vector<double>& z,
                                            const std::vector<double>& force, const AfmFitProblem& problem, double z_lo,
                                            double c_hi, double t, int& evaluations) {
  const double ln10 = std::log(10.0), start = std::log(problem.coating->film.youngs_modulus);
  const std::size_t grid = std::max<std::size_t>(problem.profile_points / 4, 16);
  double u = start, u_prev = 0.0, psi_prev = 0.0, psi = 0.0;
  ContactSearch found;
  for (int k = 0;; ++k) {
    if (k == 30) return std::nullopt;
    const auto table = forces.force(std::exp(u), t);
    Profile profile(z, force, *table, true, 1.0, problem.free.baseline, problem.baseline);
    if (problem.free.tilt) profile.free_tilt();
    // After the first step z_c moves little: a window of a tenth of the range around the last
    // one (the final search on the full grid checks it is the global minimum).
    const double window = 0.05 * (c_hi - z_lo);
    found = k == 0 ? search_contact(profile, problem, z_lo, c_hi, grid, 1e-9)
                   : search_contact(profile, problem, std::max(z_lo, found.contact_point - window),
                                    std::min(c_hi, found.contact_point + window), 16, 1e-9, 1);
    evaluations += found.evaluations;
    if (!(found.linear.reduced_modulus > 0.0)) return std::nullopt;
    psi = std::log(found.linear.reduced_modulus);  // the scale s: F = s F(E1), E1 implied s E1
    if (std::abs(psi) < 1e-3) break;
    double next = u + psi;  // contracts at the rate |d ln g / d ln r| < 1
    const double slope = k > 0 ? (psi - psi_prev) / (u - u_prev) : 0.0;
    if (slope < -1e-3 && std::isfinite(slope)) next = u - psi / slope;  // secant on psi(ln E1) = 0
    next = std::clamp(next, u - ln10, u + ln10);
    if (std::abs(next - start) > 3.0 * ln10) {
      throw NumericalError("afm fit: " + problem.coating->free_modulus_name() + " runs out of its search range (best at " + short_text(std::exp(next)) +
                           "); the data do not determine it, or its given value is far off");
    }
    u_prev = u, psi_prev = psi, u = next;
  }
  // Gauss-Newton from the fixed point's neighbour (u + psi, its z_c, b, m).
  u += psi;
  const std::size_t n = z.size();
  double zc = found.contact_point, b = found.linear.baseline, m = found.linear.tilt;
  std::vector<std::size_t> slot;  // parameter of each column: 0 ln E1, 1 z_c, 2 b, 3 m
  slot.push_back(0);
  if (problem.free.contact_point) slot.push_back(1);
  if (problem.free.baseline) slot.push_back(2);
  if (problem.free.tilt) slot.push_back(3);
  const std::size_t p = slot.size();
  if (n <= p) return std::nullopt;
  coatcontact::detail::GslHandlerOff handler_off;
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> x(gsl_matrix_alloc(n, p), gsl_matrix_free);
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> cov(gsl_matrix_alloc(p, p), gsl_matrix_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> y(gsl_vector_alloc(n), gsl_vector_free), c(gsl_vector_alloc(p), gsl_vector_free);
  std::unique_ptr<gsl_multifit_linear_workspace, void (*)(gsl_multifit_linear_workspace*)> work(
      gsl_multifit_linear_alloc(n, p), gsl_multifit_linear_free);
  const auto rss_at = [&](double uu, double zz, double bb, double mm) {
    const auto table = forces.force(std::exp(uu), t);
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double delta = zz - z[i];
      const double r = force[i] - bb - mm * (z[i] - zz) - (delta > 0.0 ? table->value(delta) : 0.0);
      sum += r * r;
    }
    return sum;
  };
  constexpr double h = 1e-4;
  double rss = rss_at(u, zc, b, m);
  for (int iteration = 0; iteration < 20; ++iteration) {
    const double e = std::exp(u);
    const auto mid = forces.force(e, t), lo = forces.force(e * (1 - h), t), hi = forces.force(e * (1 + h), t);
    for (std::size_t i = 0; i < n; ++i) {
      const double delta = zc - z[i];
      double g = 0.0, dg = 0.0, du = 0.0;
      if (delta > 0.0) {
        std::tie(g, dg) = mid->at(delta);
        du = (hi->value(delta) - lo->value(delta)) / (2 * h);
      }
      const double columns[4] = {du, dg - m, 1.0, z[i] - zc};
      for (std::size_t a = 0; a < p; ++a) gsl_matrix_set(x.get(), i, a, columns[slot[a]]);
      gsl_vector_set(y.get(), i, force[i] - b - m * (z[i] - zc) - g);
    }
    double chi2 = 0.0;
    if (gsl_multifit_linear(x.get(), y.get(), c.get(), cov.get(), &chi2, work.get()) != 0) return std::nullopt;
    double step[4] = {0.0, 0.0, 0.0, 0.0}, se[4] = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t a = 0; a < p; ++a) {
      step[slot[a]] = gsl_vector_get(c.get(), a);
      se[slot[a]] = std::sqrt(gsl_matrix_get(cov.get(), a, a));  // GSL's cov carries chi2/(n - p)
    }
    // Halve a step that raises the sum (the kink of z_c where points enter contact).
    double factor = 1.0, trial = rss_at(u + step[0], zc + step[1], b + step[2], m + step[3]);
    for (int k = 0; k < 8 && !(trial <= rss * (1 + 1e-12)); ++k) {
      factor *= 0.5;
      trial = rss_at(u + factor * step[0], zc + factor * step[1], b + factor * step[2], m + factor * step[3]);
    }
    if (!(trial <= rss * (1 + 1e-12))) return std::nullopt;
    u += factor * step[0], zc += factor * step[1], b += factor * step[2], m += factor * step[3];
    rss = trial;
    // Converged: the step a thousandth of the standard errors of ln E1 and z_c.
    if (std::abs(step[0]) <= 1e-3 * se[0] && std::abs(step[1]) <= 1e-3 * se[1] + 1e-15) {
      return ProfiledModulus{std::exp(u), zc, se[1]};
    }
  }
  return std::nullopt;
}

}  // namespace

AfmFitResult afm_fit(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem) {
  const AfmModelInfo& model = problem.model.info();
  const int free_count = afm_free_count(model, problem.free);
  check_fit_input(z, force, problem, free_count);
  internal::check_afm_coating(problem);
  if (problem.free.work && afm_free_count(model, AfmFree{false, false, false, false, true, false}) == 0) {
    throw InputError("afm fit: w is a parameter of the adhesive (" + afm_spring_model_names() + ") models only");
  }
  return model.fit(z, force, problem, free_count);
}

AfmFitResult internal::afm_fit_hertz(const std::vector<double>& z, const std::vector<double>& force,
                                     const AfmFitProblem& problem, int free_count) {
  return afm_fit_hertz(z, force, problem, free_count, CoatedE1Search::kProfiled);
}

namespace {

// A coated fit whose indentations pass the reach its sweep was limited to: fitted again on the
// whole a/t range.
struct WiderReach {};

// The half-space: E* and b in closed form at each z_c (Profile), z_c searched; r and the
// Jacobian columns of the free parameters (in result order) filled.
void fit_halfspace(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                   double z_lo, double c_hi, double max_delta, AfmFitResult& r, std::vector<std::vector<double>>& columns,
                   std::vector<double*>& error_slots) {
  const std::size_t n = z.size();
  const TipForce tip(problem.tip, max_delta);
  const double nu_factor = 1.0 - problem.poisson * problem.poisson;
  Profile profile(z, force, tip, problem.free.modulus, problem.modulus / nu_factor, problem.free.baseline,
                  problem.baseline);
  if (problem.free.tilt) profile.free_tilt();
  if (problem.weight_cp > 0.0) profile.weight_cp(problem.weight_cp);
  const ContactSearch found = search_contact(profile, problem, z_lo, c_hi, problem.profile_points);
  if (!(found.linear.reduced_modulus > 0.0)) {
    throw NumericalError("afm fit: the data show no contact in the fitted range (the best modulus is 0); "
                         "widen the range or check the segment");
  }
  r.reduced_modulus = found.linear.reduced_modulus;
  r.modulus = r.reduced_modulus * nu_factor;
  r.contact_point = found.contact_point;
  r.baseline = found.linear.baseline;
  r.tilt = found.linear.tilt;
  r.profile_evaluations = found.evaluations;
  std::vector<double> col_e(n, 0.0), col_c(n, 0.0), col_b(n, 1.0), col_m(n, 0.0);
  r.model_force.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = r.contact_point - z[i];
    double g = 0.0, slope = 0.0;
    if (delta > 0.0) std::tie(g, slope) = tip.at(delta);
    r.model_force[i] = r.baseline + r.reduced_modulus * g;
    col_e[i] = g / nu_factor;
    col_c[i] = r.reduced_modulus * slope;
    if (problem.free.tilt) {
      r.model_force[i] += r.tilt * (z[i] - r.contact_point);
      col_c[i] -= r.tilt;
      col_m[i] = z[i] - r.contact_point;
    }
  }
  if (problem.free.modulus) columns.push_back(col_e), error_slots.push_back(&r.modulus_error);
  if (problem.free.contact_point) columns.push_back(col_c), error_slots.push_back(&r.contact_point_error);
  if (problem.free.baseline) columns.push_back(col_b), error_slots.push_back(&r.baseline_error);
  if (problem.free.tilt) columns.push_back(col_m), error_slots.push_back(&r.tilt_error);
}

AfmFitResult fit_hertz(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                       int free_count, internal::CoatedE1Search search, bool whole_reach) {
  const auto start = std::chrono::steady_clock::now();
  // The Hertz model's tilt is free or 0 (afm_fit_curve's baseline model subtracts the preprocessing's).
  const std::size_t n = z.size();
  const auto [z_lo_it, z_hi_it] = std::minmax_element(z.begin(), z.end());
  const double z_lo = *z_lo_it, z_hi = *z_hi_it, span = z_hi - z_lo;
  if (problem.free.contact_point && !(span > 0.0)) throw InputError("afm fit: the fitted points have one tip position only");
  const double c_hi = problem.free.contact_point ? z_hi + kContactBeyond * span : problem.contact_point;
  const double max_delta = std::max(c_hi - z_lo, 1e-12);

  AfmFitResult r;
  r.points = n;
  r.free_count = free_count;
  std::vector<std::vector<double>> columns;  // Jacobian of the free parameters, in result order
  std::vector<double*> error_slots;
  if (!problem.coating) {
    fit_halfspace(z, force, problem, z_lo, c_hi, max_delta, r, columns, error_slots);
  } else {
    // A coating: E1 and/or t by a log search (t inside E1 when both are free: a new E1 needs a
    // sweep of the solver, a new t only a rescaled table), z_c and b profiled as above.
    CoatingForces forces(problem);
    const AfmCoating& coating = *problem.coating;
    // (a free t moves a/t: the whole range)
    if (!whole_reach && !problem.free.thickness) forces.limit_reach(coating_reach(problem, max_delta));
    forces.resample_up_to(max_delta);
    int evaluations = 0;
    // A trial whose indentations leave the table (a/t too large: t small) costs +infinity in
    // the search; at the optimum it is an error.
    // Film on a rigid base, tabled: E1 is a pure scale, F = (E1*/E1_ref*) F(E1_ref), so it is
    // profiled in closed form with b (the half-space's search) instead of searched.
    const bool linear_e1 = forces.scale_free() && problem.free.modulus;
    const double e_ref = coating.film.youngs_modulus;
    const auto fit_at = [&](double e1, double t, bool final) {
      const auto table = forces.force(linear_e1 ? e_ref : e1, t);
      Profile profile(z, force, *table, linear_e1, 1.0, problem.free.baseline, problem.baseline);
      if (problem.free.tilt) profile.free_tilt();
      // Trials of the E1/t search localize z_c on a quarter of the grid (Brent polishes it);
      // the final fit on the full grid.
      const std::size_t grid = final ? problem.profile_points : std::max<std::size_t>(problem.profile_points / 4, 16);
      // (a trial's z_c to 1e-9 of the range: its RSS is then exact to ~1e-18 relative, the
      // minimum being quadratic, far below what the E1/t search resolves)
      ContactSearch found = search_contact(profile, problem, z_lo, c_hi, grid, final ? 1e-12 : 1e-9);
      evaluations += found.evaluations;
      if (final && found.contact_point - z_lo > table->safe_penetration()) throw WiderReach{};
      if (final && found.contact_point - z_lo > table->max_penetration()) {
        throw NumericalError("afm fit: the indentations reach " + short_text(found.contact_point - z_lo) +
                             " m, past the " + short_text(table->max_penetration()) + " m at which the contact radius reaches " +
                             short_text(kCoatingAOverT[1]) + " film thicknesses (t = " + short_text(t) +
                             " m), as far as the coating model is tabulated; a thicker film or a shallower --indentation-range");
      }
      return found;
    };
    const auto best_t = [&](double e1, bool strict) {
      if (!problem.free.thickness) return coating.thickness;
      return minimize_log([&](double t) { return fit_at(e1, t, false).linear.rss; }, coating.thickness, "t", strict);
    };
    double e1 = coating.film.youngs_modulus;
    std::optional<ProfiledModulus> profiled;
    if (problem.free.modulus && !linear_e1) {
      if (search == internal::CoatedE1Search::kProfiled && !problem.free.thickness && !coating.direct) {
        profiled = profiled_film_modulus(forces, z, force, problem, z_lo, c_hi, coating.thickness, evaluations);
      }
      e1 = profiled ? profiled->modulus
                    : minimize_log([&](double e) { return fit_at(e, best_t(e, false), false).linear.rss; }, e1, coating.free_modulus_name());
    }
    const double t = best_t(e1, true);
    ContactSearch found = fit_at(e1, t, true);
    // The profiled search is local in z_c: if the full grid finds another minimum at its E1,
    // the nested search (global in both) decides.
    if (profiled && problem.free.contact_point &&
        !(std::abs(found.contact_point - profiled->contact_point) <= 1e-2 * profiled->contact_point_error)) {
      e1 = minimize_log([&](double e) { return fit_at(e, t, false).linear.rss; }, coating.film.youngs_modulus, coating.free_modulus_name());
      found = fit_at(e1, t, true);
    }
    if (linear_e1) {
      if (!(found.linear.reduced_modulus > 0.0)) {
        throw NumericalError("afm fit: the data show no contact in the fitted range (the best " + coating.free_modulus_name() + " is 0); "
                             "widen the range or check the segment");
      }
      e1 = e_ref * found.linear.reduced_modulus;
    }
    r.modulus = e1;
    r.thickness = t;
    Material film = coating.film;
    film.youngs_modulus = e1;
    r.reduced_modulus = film.reduced_modulus();
    r.contact_point = found.contact_point;
    r.baseline = found.linear.baseline;
    r.tilt = found.linear.tilt;
    r.profile_evaluations = evaluations;
    const auto table = forces.force(e1, t);
    const auto model_at = [&](const PenetrationForce& tab, std::vector<double>* slope) {
      std::vector<double> f(n, r.baseline);
      for (std::size_t i = 0; i < n; ++i) {
        const double delta = r.contact_point - z[i];
        f[i] += r.tilt * (z[i] - r.contact_point);
        if (delta <= 0.0) continue;
        const auto [g, dg] = tab.at(delta);
        f[i] += g;
        if (slope) (*slope)[i] = dg;
      }
      return f;
    };
    std::vector<double> col_c(n, 0.0), col_b(n, 1.0);
    r.model_force = model_at(*table, &col_c);
    // d F/d p by central differences at fixed z_c, b (relative step h: truncation ~h^2).
    constexpr double h = 1e-4;
    const auto difference = [&](double e_lo, double t_lo, double e_hi, double t_hi, double width) {
      const std::vector<double> lo = model_at(*forces.force(e_lo, t_lo), nullptr);
      const std::vector<double> hi = model_at(*forces.force(e_hi, t_hi), nullptr);
      std::vector<double> col(n);
      for (std::size_t i = 0; i < n; ++i) col[i] = (hi[i] - lo[i]) / width;
      return col;
    };
    if (problem.free.modulus) {
      columns.push_back(difference(e1 * (1 - h), t, e1 * (1 + h), t, 2 * h * e1));
      error_slots.push_back(&r.modulus_error);
    }
    if (problem.free.thickness) {
      columns.push_back(difference(e1, t * (1 - h), e1, t * (1 + h), 2 * h * t));
      error_slots.push_back(&r.thickness_error);
    }
    std::vector<double> col_m(n);
    for (std::size_t i = 0; i < n; ++i) col_c[i] -= r.tilt, col_m[i] = z[i] - r.contact_point;
    if (problem.free.contact_point) columns.push_back(col_c), error_slots.push_back(&r.contact_point_error);
    if (problem.free.baseline) columns.push_back(col_b), error_slots.push_back(&r.baseline_error);
    if (problem.free.tilt) columns.push_back(col_m), error_slots.push_back(&r.tilt_error);
    r.solver_calls = forces.solver_calls();
  }

  finish_fit(r, z, force, problem, free_count, columns, error_slots);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace

AfmFitResult internal::afm_fit_hertz(const std::vector<double>& z, const std::vector<double>& force,
                                     const AfmFitProblem& problem, int free_count, CoatedE1Search search) {
  try {
    return fit_hertz(z, force, problem, free_count, search, false);
  } catch (const WiderReach&) {
    return fit_hertz(z, force, problem, free_count, search, true);
  }
}

std::vector<std::size_t> afm_select(const std::vector<double>& z, const std::vector<double>& force, const AfmRange& range,
                                    double reference_contact, double reference_baseline) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double delta = reference_contact - z[i];
    if (range.tip_min && z[i] < *range.tip_min) continue;
    if (range.tip_max && z[i] > *range.tip_max) continue;
    if (range.indentation_min && delta < *range.indentation_min) continue;
    if (range.indentation_max && delta > *range.indentation_max) continue;
    if (range.max_force && force[i] - reference_baseline > *range.max_force) continue;
    kept.push_back(i);
  }
  return kept;
}

}  // namespace coatcontact::fit
