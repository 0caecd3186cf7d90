// The AFM curve model (THEORY.md section 14): Hertz/Sneddon on a half-space with a contact
// point and a baseline, fitted by profiling the residual sum over the contact point with
// (E*, b) solved in closed form at each z_c. See coatcontact/afm_fit.hpp.
#include "coatcontact/afm_fit.hpp"

#include <gsl/gsl_integration.h>
#include <gsl/gsl_interp.h>
#include <gsl/gsl_linalg.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <utility>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit {

namespace {

using coatcontact::detail::short_text;
constexpr double kPi = 3.14159265358979323846;

// g(delta) and dg/d delta of a tip; the shape's through a table of log g against log delta.
class TipForce {
 public:
  TipForce(const AfmTip& tip, double max_penetration) : tip_(tip) {
    if (tip.kind == AfmTip::Kind::kShape) build_table(max_penetration);
  }
  ~TipForce() {
    if (interp_) gsl_interp_free(interp_);
    if (accel_) gsl_interp_accel_free(accel_);
  }
  TipForce(const TipForce&) = delete;
  TipForce& operator=(const TipForce&) = delete;

  // g [N/Pa] and g' [N/(Pa m)] at delta > 0.
  std::pair<double, double> at(double delta) const {
    switch (tip_.kind) {
      case AfmTip::Kind::kParaboloid: {
        const double root = std::sqrt(tip_.radius * delta);  // F = (4/3) E* sqrt(R) delta^1.5
        return {(4.0 / 3.0) * root * delta, 2.0 * root};
      }
      case AfmTip::Kind::kCone: {
        const double c = (2.0 / kPi) * std::tan(tip_.angle);  // F = (2/pi) E* tan(beta) delta^2
        return {c * delta * delta, 2.0 * c * delta};
      }
      case AfmTip::Kind::kShape:
        break;
    }
    if (flat_) return {2.0 * punch_radius_ * delta, 2.0 * punch_radius_};
    const double x = std::log(delta);
    if (x < log_delta_.front()) {  // below the table: its first power law
      const double g = std::exp(log_g_.front() + first_slope_ * (x - log_delta_.front()));
      return {g, first_slope_ * g / delta};
    }
    if (x > log_delta_.back()) {
      throw NumericalError("afm fit: indentation " + short_text(delta) + " m is beyond the tip's largest contact radius (" +
                           tip_.description + ")");
    }
    const double lg = gsl_interp_eval(interp_, log_delta_.data(), log_g_.data(), x, accel_);
    const double slope = gsl_interp_eval_deriv(interp_, log_delta_.data(), log_g_.data(), x, accel_);
    const double g = std::exp(lg);
    return {g, slope * g / delta};
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
    gsl_integration_workspace* workspace = gsl_integration_workspace_alloc(200);
    std::function<double(double)> delta0 = [&shape](double r) { return shape.delta0(r); };
    gsl_function gf;
    gf.function = [](double r, void* params) { return (*static_cast<std::function<double(double)>*>(params))(r); };
    gf.params = &delta0;
    double integral = 0.0, previous = 0.0;
    for (int k = 0; k < count; ++k) {
      const double a = a_min * std::pow(a_max / a_min, k / static_cast<double>(count - 1));
      double piece = 0.0, error = 0.0;
      const int status = gsl_integration_qags(&gf, previous, a, 0.0, 1e-10, 200, workspace, &piece, &error);
      if (status != 0) {
        gsl_integration_workspace_free(workspace);
        throw NumericalError("afm fit: the tip's Sneddon integral failed at a = " + short_text(a) + " m");
      }
      integral += piece;
      previous = a;
      const double d = shape.delta0(a);
      const double g = 2.0 * (a * d - integral);
      if (!(d > 0.0) || !(g > 0.0)) continue;
      if (!log_delta_.empty() && !(std::log(d) > log_delta_.back())) continue;
      log_delta_.push_back(std::log(d));
      log_g_.push_back(std::log(g));
    }
    gsl_integration_workspace_free(workspace);
    if (log_delta_.size() < 4) throw NumericalError("afm fit: the tip's table has too few points (" + tip_.description + ")");
    first_slope_ = (log_g_[1] - log_g_[0]) / (log_delta_[1] - log_delta_[0]);
    interp_ = gsl_interp_alloc(gsl_interp_steffen, log_delta_.size());
    accel_ = gsl_interp_accel_alloc();
    gsl_interp_init(interp_, log_delta_.data(), log_g_.data(), log_delta_.size());
  }

  const AfmTip& tip_;
  bool flat_ = false;
  double punch_radius_ = 0.0;
  std::vector<double> log_delta_, log_g_;
  double first_slope_ = 1.5;
  gsl_interp* interp_ = nullptr;
  gsl_interp_accel* accel_ = nullptr;
};

// At one z_c: the closed-form (E*, b) (E* >= 0) and the residual sum of squares. Forces are
// centred on their mean (b is then relative to it) to keep the sums well conditioned.
struct LinearFit {
  double reduced_modulus = 0.0, baseline = 0.0, rss = 0.0;
};

class Profile {
 public:
  Profile(const std::vector<double>& z, const std::vector<double>& f, const AfmFitProblem& problem,
          const TipForce& tip)
      : z_(z), problem_(problem), tip_(tip) {
    mean_ = std::accumulate(f.begin(), f.end(), 0.0) / static_cast<double>(f.size());
    centred_.resize(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) centred_[i] = f[i] - mean_;
    for (double v : centred_) sff_ += v * v;
    fixed_reduced_ = problem.modulus / (1.0 - problem.poisson * problem.poisson);
  }

  LinearFit at(double contact_point) const {
    ++evaluations_;
    double sg = 0.0, sgg = 0.0, sgf = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i) {
      const double delta = contact_point - z_[i];
      if (delta <= 0.0) continue;
      const double g = tip_.at(delta).first;
      sg += g;
      sgg += g * g;
      sgf += g * centred_[i];
    }
    const double n = static_cast<double>(z_.size());
    const bool free_e = problem_.free.modulus, free_b = problem_.free.baseline;
    double e = fixed_reduced_, b = problem_.baseline - mean_;
    if (free_e && free_b) {
      const double var = sgg - sg * sg / n;
      e = var > 0.0 ? std::max(0.0, sgf / var) : 0.0;  // sum F' = 0: cov = sgf
      b = -e * sg / n;
    } else if (free_e) {
      e = sgg > 0.0 ? std::max(0.0, (sgf - b * sg) / sgg) : 0.0;
    } else if (free_b) {
      b = -e * sg / n;
    }
    // sum (F' - b - e g)^2 with sum F' = 0.
    const double rss = sff_ + n * b * b + e * e * sgg - 2.0 * e * sgf + 2.0 * b * e * sg;
    return {e, b + mean_, std::max(0.0, rss)};
  }
  int evaluations() const { return evaluations_; }

 private:
  const std::vector<double>& z_;
  const AfmFitProblem& problem_;
  const TipForce& tip_;
  std::vector<double> centred_;
  double mean_ = 0.0, sff_ = 0.0, fixed_reduced_ = 0.0;
  mutable int evaluations_ = 0;
};

void check_tip(const AfmTip& tip) {
  switch (tip.kind) {
    case AfmTip::Kind::kParaboloid:
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
  std::vector<double> delta(tip_position.size());
  for (std::size_t i = 0; i < delta.size(); ++i) delta[i] = std::max(0.0, problem.contact_point - tip_position[i]);
  const std::vector<double> g = afm_force_per_modulus(problem.tip, delta);
  const double reduced = problem.modulus / (1.0 - problem.poisson * problem.poisson);
  std::vector<double> f(delta.size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = problem.baseline + reduced * g[i];
  return f;
}

AfmFitResult afm_fit(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem) {
  const auto start = std::chrono::steady_clock::now();
  check_tip(problem.tip);
  if (z.size() != force.size()) throw InputError("afm fit: tip position and force differ in length");
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!std::isfinite(z[i]) || !std::isfinite(force[i])) {
      throw InputError("afm fit: point " + std::to_string(i) + " is not finite");
    }
  }
  if (!(problem.poisson > -1.0 && problem.poisson <= 0.5)) {
    throw InputError("afm fit: Poisson's ratio must be in (-1, 0.5] (got " + short_text(problem.poisson) + ")");
  }
  if (!problem.free.modulus && !(problem.modulus > 0.0 && std::isfinite(problem.modulus))) {
    throw InputError("afm fit: a fixed E must be > 0 (got " + short_text(problem.modulus) + ")");
  }
  const int free_count = int(problem.free.modulus) + int(problem.free.contact_point) + int(problem.free.baseline);
  const std::size_t n = z.size();
  if (n < static_cast<std::size_t>(free_count) + 2) {
    throw InputError("afm fit: " + std::to_string(n) + " points in the fitted range; " + std::to_string(free_count) +
                     " free parameters need at least " + std::to_string(free_count + 2));
  }
  const auto [z_lo_it, z_hi_it] = std::minmax_element(z.begin(), z.end());
  const double z_lo = *z_lo_it, z_hi = *z_hi_it, span = z_hi - z_lo;
  if (problem.free.contact_point && !(span > 0.0)) throw InputError("afm fit: the fitted points have one tip position only");
  const double c_hi = problem.free.contact_point ? z_hi + kContactBeyond * span : problem.contact_point;
  const TipForce tip(problem.tip, std::max(c_hi - z_lo, 1e-12));
  const Profile profile(z, force, problem, tip);

  // The contact point: grid over [z_lo, c_hi], then Brent on the brackets of the three lowest
  // grid minima (the profile has a kink where a point enters contact and may have several
  // minima; the grid keeps the global one, Brent polishes it).
  double contact = problem.contact_point;
  if (problem.free.contact_point) {
    const std::size_t m = std::max<std::size_t>(problem.profile_points, 16);
    std::vector<double> grid(m), cost(m);
    for (std::size_t k = 0; k < m; ++k) {
      grid[k] = z_lo + (c_hi - z_lo) * static_cast<double>(k) / static_cast<double>(m - 1);
      cost[k] = profile.at(grid[k]).rss;
    }
    std::vector<std::size_t> minima;
    for (std::size_t k = 0; k < m; ++k) {
      const bool left = k == 0 || cost[k] <= cost[k - 1];
      const bool right = k + 1 == m || cost[k] <= cost[k + 1];
      if (left && right) minima.push_back(k);
    }
    std::sort(minima.begin(), minima.end(), [&](std::size_t a, std::size_t b) { return cost[a] < cost[b]; });
    if (minima.size() > 3) minima.resize(3);
    double best = cost[minima.front()];
    contact = grid[minima.front()];
    const auto rss = [&](double c) { return profile.at(c).rss; };
    for (std::size_t k : minima) {
      if (k == 0 || k + 1 == m) continue;
      const auto found = coatcontact::detail::brent_minimum(rss, grid[k - 1], cost[k - 1], grid[k], cost[k], grid[k + 1],
                                                            cost[k + 1], {span * 1e-12, 0.0, 200});
      if (!found) continue;
      const double value = rss(found->x);
      if (value < best) {
        best = value;
        contact = found->x;
      }
    }
  }
  const LinearFit linear = profile.at(contact);
  if (!(linear.reduced_modulus > 0.0)) {
    throw NumericalError("afm fit: the data show no contact in the fitted range (the best modulus is 0); "
                         "widen the range or check the segment");
  }

  AfmFitResult r;
  const double nu_factor = 1.0 - problem.poisson * problem.poisson;
  r.reduced_modulus = linear.reduced_modulus;
  r.modulus = linear.reduced_modulus * nu_factor;
  r.contact_point = contact;
  r.baseline = linear.baseline;
  r.points = n;
  r.free_count = free_count;
  r.profile_evaluations = profile.evaluations();
  r.model_force.resize(n);
  r.residual.resize(n);
  r.indentation.resize(n);
  double mean = std::accumulate(force.begin(), force.end(), 0.0) / static_cast<double>(n), tss = 0.0;
  // Jacobian columns of the free parameters (E, z_c, b) at the optimum.
  std::vector<std::vector<double>> columns;
  std::vector<double> col_e(n, 0.0), col_c(n, 0.0), col_b(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = std::max(0.0, contact - z[i]);
    double g = 0.0, slope = 0.0;
    if (delta > 0.0) std::tie(g, slope) = tip.at(delta);
    r.indentation[i] = contact - z[i];
    if (delta > 0.0) ++r.points_in_contact;
    r.max_indentation = std::max(r.max_indentation, delta);
    r.model_force[i] = r.baseline + r.reduced_modulus * g;
    r.residual[i] = r.model_force[i] - force[i];
    r.rss += r.residual[i] * r.residual[i];
    tss += (force[i] - mean) * (force[i] - mean);
    col_e[i] = g / nu_factor;
    col_c[i] = r.reduced_modulus * slope;
  }
  if (problem.free.modulus) columns.push_back(col_e);
  if (problem.free.contact_point) columns.push_back(col_c);
  if (problem.free.baseline) columns.push_back(col_b);
  const double dof = static_cast<double>(n) - free_count;
  r.residual_sigma = std::sqrt(r.rss / dof);
  r.r_squared = tss > 0.0 ? 1.0 - r.rss / tss : 0.0;
  if (problem.noise_sigma > 0.0) {
    r.chi2 = r.rss / (problem.noise_sigma * problem.noise_sigma);
    r.chi2_per_dof = r.chi2 / dof;
  }

  // Standard errors: s^2 (J^T J)^-1, by Cholesky on the column-scaled normal matrix.
  const std::size_t p = columns.size();
  if (p > 0) {
    std::vector<double> scale(p, 0.0);
    for (std::size_t a = 0; a < p; ++a) {
      for (double v : columns[a]) scale[a] += v * v;
      scale[a] = std::sqrt(scale[a]);
      if (!(scale[a] > 0.0)) throw NumericalError("afm fit: a free parameter does not change the model at the optimum");
    }
    coatcontact::detail::GslHandlerOff handler_off;
    gsl_matrix* normal = gsl_matrix_alloc(p, p);
    for (std::size_t a = 0; a < p; ++a) {
      for (std::size_t b = 0; b < p; ++b) {
        double s = 0.0;
        for (std::size_t i = 0; i < n; ++i) s += columns[a][i] * columns[b][i];
        gsl_matrix_set(normal, a, b, s / (scale[a] * scale[b]));
      }
    }
    const int status = gsl_linalg_cholesky_decomp1(normal);
    if (status != 0) {
      gsl_matrix_free(normal);
      throw NumericalError("afm fit: the free parameters are not identifiable from the fitted points");
    }
    gsl_linalg_cholesky_invert(normal);
    std::vector<double> errors(p);
    for (std::size_t a = 0; a < p; ++a) {
      errors[a] = r.residual_sigma * std::sqrt(gsl_matrix_get(normal, a, a)) / scale[a];
    }
    gsl_matrix_free(normal);
    std::size_t a = 0;
    if (problem.free.modulus) r.modulus_error = errors[a++];
    if (problem.free.contact_point) r.contact_point_error = errors[a++];
    if (problem.free.baseline) r.baseline_error = errors[a++];
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
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

AfmPulloff afm_pulloff(const std::vector<double>& tip_position, const std::vector<double>& force, double baseline) {
  AfmPulloff out;
  if (force.empty()) return out;
  const auto it = std::min_element(force.begin(), force.end());
  const auto i = static_cast<std::size_t>(it - force.begin());
  out.found = true;
  out.force = *it - baseline;
  out.tip_position = tip_position[i];
  out.index = i;
  return out;
}

}  // namespace coatcontact::fit
