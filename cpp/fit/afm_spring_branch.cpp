// The adhesive branch a cantilever holds (THEORY.md sections 10 and 15), shared by the JKR and
// the Maugis-Dugdale retract fits: the jump-off as the lowest minimum of Z = delta + F/k along
// the curve (or its end a -> 0), and F(delta) tabulated on the branch above it.
#include <gsl/gsl_interp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <utility>

#include "afm_internal.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {

using coatcontact::detail::short_text;

SplinePieces::SplinePieces(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
  const std::size_t n = x_.size();
  std::unique_ptr<gsl_interp, void (*)(gsl_interp*)> spline(gsl_interp_alloc(gsl_interp_cspline, n), gsl_interp_free);
  std::unique_ptr<gsl_interp_accel, void (*)(gsl_interp_accel*)> accel(gsl_interp_accel_alloc(), gsl_interp_accel_free);
  gsl_interp_init(spline.get(), x_.data(), y_.data(), n);
  std::vector<double> slope(n);
  for (std::size_t k = 0; k < n; ++k) slope[k] = gsl_interp_eval_deriv(spline.get(), x_.data(), y_.data(), x_[k], accel.get());
  // The cubic of [x_k, x_k+1] from its end values and slopes (Hermite): the spline's piece.
  b_.assign(n, 0.0), c_.assign(n, 0.0), d_.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double h = x_[k + 1] - x_[k], secant = (y_[k + 1] - y_[k]) / h;
    b_[k] = slope[k];
    c_[k] = (3.0 * secant - 2.0 * slope[k] - slope[k + 1]) / h;
    d_[k] = (slope[k] + slope[k + 1] - 2.0 * secant) / (h * h);
  }
}

std::size_t SplinePieces::interval(double v) const {
  const std::size_t last = x_.size() - 2;
  if (uniform_) {
    const double at = (v - x_.front()) / (x_.back() - x_.front()) * static_cast<double>(x_.size() - 1);
    if (!(at > 0.0)) return 0;  // (NaN too)
    return std::min(last, static_cast<std::size_t>(at));
  }
  const auto it = std::upper_bound(x_.begin(), x_.end(), v);
  if (it == x_.begin()) return 0;
  return std::min(last, static_cast<std::size_t>(it - x_.begin()) - 1);
}

SpringBranch::SpringBranch(const CurvePoint& point, double scale, double lo, double hi, int per_decade, double spring,
                           double max_indentation, double a_top_guess, int nodes,
                           std::optional<std::pair<double, double>> end, double reduced_modulus)
    : reduced_(reduced_modulus) {
  // a_s: the global minimum of Z = delta + F/k on the scan, polished by Brent.
  const int count = static_cast<int>(std::ceil(std::log10(hi / lo) * per_decade)) + 1;
  std::vector<double> grid(count), z(count);
  int best = 0;
  for (int k = 0; k < count; ++k) {
    grid[k] = scale * lo * std::pow(hi / lo, k / (count - 1.0));
    const auto [d, f] = point(grid[k]);
    z[k] = d + f / spring;
    if (z[k] < z[best]) best = k;
  }
  const double z_end = end ? end->first + end->second / spring : 0.0;
  if (best + 1 == count || (best == 0 && !end)) {
    throw NumericalError("afm fit: delta + F/k has no minimum in a/L_a [" + short_text(lo) + ", " + short_text(hi) +
                         "] (no jump-off through the spring)");
  }
  const auto zof = [&](double a) {
    const auto [d, f] = point(a);
    return d + f / spring;
  };
  double a_s = grid[best];
  if (best > 0) {
    const auto found = coatcontact::detail::brent_minimum(zof, grid[best - 1], z[best - 1], grid[best], z[best],
                                                          grid[best + 1], z[best + 1], {0.0, 1e-10, 100});
    if (found) a_s = found->x;
  }
  if (end && (best == 0 || z_end < zof(a_s))) {
    // The contact shrinks to a point before Z turns (THEORY.md section 15, Maugis-Dugdale).
    jump_at_end_ = true;
    std::tie(jump_delta_, jump_force_) = *end;
    delta_.push_back(jump_delta_);
    force_.push_back(jump_force_);
    a_s = grid[0];
  } else {
    std::tie(jump_delta_, jump_force_) = point(a_s);
  }
  // The top radius: delta(a_top) >= the deepest indentation (bounded doubling).
  double a_top = std::max(2.0 * a_s, a_top_guess);
  for (int k = 0; k < 80 && point(a_top).first < max_indentation; ++k) a_top *= 2.0;
  a_top_ = a_top;
  for (int k = 0; k < nodes; ++k) {
    const double a = a_s * std::pow(a_top / a_s, k / (nodes - 1.0));
    const auto [d, f] = point(a);
    if (!std::isfinite(d) || !std::isfinite(f)) throw NumericalError("afm fit: the adhesive branch is not finite");
    if (!delta_.empty() && !(d > delta_.back())) continue;  // a second minimum of delta: keep the monotone part
    delta_.push_back(d);
    force_.push_back(f);
    a_max_ = a;
  }
  if (delta_.size() < 8) throw NumericalError("afm fit: the adhesive branch has too few monotone nodes");
  const std::size_t n = delta_.size();
  const double d1 = delta_[n - 1] - jump_delta_, d0 = delta_[n - 2] - jump_delta_;
  last_slope_ = force_[n - 1] > 0.0 && force_[n - 2] > 0.0 && d0 > 0.0
                    ? std::log(force_[n - 1] / force_[n - 2]) / std::log(d1 / d0)
                    : 1.5;
  spline_ = SplinePieces(delta_, force_);
}

SpringBranch::~SpringBranch() = default;

std::pair<double, double> SpringBranch::at(double delta) const {
  if (delta <= jump_delta_) return {0.0, 0.0};
  if (delta < delta_.front()) return {force_.front(), 0.0};  // rounding next to a_s
  if (delta >= delta_.back()) {
    const double x = (delta - jump_delta_) / (delta_.back() - jump_delta_);
    const double g = force_.back() * std::pow(x, last_slope_);
    return {g, last_slope_ * g / (delta - jump_delta_)};
  }
  const std::size_t k = spline_.interval(delta);
  return {spline_.value(delta, k), spline_.slope(delta, k)};
}

double SpringBranch::value(double delta) const {
  if (delta <= jump_delta_) return 0.0;
  if (delta < delta_.front()) return force_.front();
  if (delta >= delta_.back()) return force_.back() * std::pow((delta - jump_delta_) / (delta_.back() - jump_delta_), last_slope_);
  return spline_.value(delta);
}

void SpringBranch::values(double contact, const double* z, std::size_t count, double* out) const {
  std::size_t k = delta_.size() - 1;  // the knot at or below the current indentation
  for (std::size_t i = 0; i < count; ++i) {
    const double delta = contact - z[i];
    if (delta >= delta_.back() || delta < delta_.front()) {
      out[i] = value(delta);
      continue;
    }
    while (delta < delta_[k]) --k;
    out[i] = spline_.value(delta, std::min(k, delta_.size() - 2));
  }
}

void lagrange_weights(double x, long j0, double weight[4]) {
  for (int a = 0; a < 4; ++a) {
    weight[a] = 1.0;
    for (int b = 0; b < 4; ++b) {
      if (b != a) weight[a] *= (x - static_cast<double>(j0 + b)) / static_cast<double>(a - b);
    }
  }
}

}  // namespace coatcontact::fit::internal
