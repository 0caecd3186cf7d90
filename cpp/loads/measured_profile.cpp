// A measured indenter profile (THEORY.md section 11): a cubic spline of z(r) clamped with
// z'(0) = 0 at the apex (a natural spline would force z''(0) = 0, wrong for a rounded tip),
// and δ0(r) = r ∫_0^r z'(s)/sqrt(r² - s²) ds integrated exactly piece by piece (z' is a
// quadratic in s on each piece).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_vector.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/indenter_shape.hpp"

namespace coatcontact {

namespace {

// z'(s) = c0 + c1 s + c2 s² on [r_i, r_{i+1}].
struct Piece {
  double lo, hi, c0, c1, c2;
};

class Spline {
 public:
  Spline(const std::vector<double>& r, const std::vector<double>& z) {
    const std::size_t n = r.size();
    // Slope at the last point: derivative of the cubic through the last four points (O(h³)).
    double end_slope = 0.0;
    {
      const std::size_t k = n - 4;
      const double x = r[n - 1];
      for (std::size_t i = k; i < n; ++i) {
        // d/dx of the Lagrange basis polynomial L_i at x.
        double derivative = 0.0;
        for (std::size_t j = k; j < n; ++j) {
          if (j == i) continue;
          double term = 1.0 / (r[i] - r[j]);
          for (std::size_t m = k; m < n; ++m) {
            if (m != i && m != j) term *= (x - r[m]) / (r[i] - r[m]);
          }
          derivative += term;
        }
        end_slope += z[i] * derivative;
      }
    }
    // Second derivatives M_i from the clamped-spline equations (tridiagonal).
    gsl_vector* diag = gsl_vector_alloc(n);
    gsl_vector* above = gsl_vector_alloc(n - 1);
    gsl_vector* below = gsl_vector_alloc(n - 1);
    gsl_vector* rhs = gsl_vector_alloc(n);
    gsl_vector* m = gsl_vector_alloc(n);
    auto h = [&](std::size_t i) { return r[i + 1] - r[i]; };
    auto slope = [&](std::size_t i) { return (z[i + 1] - z[i]) / h(i); };
    gsl_vector_set(diag, 0, 2 * h(0));
    gsl_vector_set(above, 0, h(0));
    gsl_vector_set(rhs, 0, 6 * (slope(0) - 0.0));  // z'(0) = 0
    for (std::size_t i = 1; i + 1 < n; ++i) {
      gsl_vector_set(below, i - 1, h(i - 1));
      gsl_vector_set(diag, i, 2 * (h(i - 1) + h(i)));
      gsl_vector_set(above, i, h(i));
      gsl_vector_set(rhs, i, 6 * (slope(i) - slope(i - 1)));
    }
    gsl_vector_set(below, n - 2, h(n - 2));
    gsl_vector_set(diag, n - 1, 2 * h(n - 2));
    gsl_vector_set(rhs, n - 1, 6 * (end_slope - slope(n - 2)));
    int status = 0;
    {
      detail::GslHandlerOff guard;
      status = gsl_linalg_solve_tridiag(diag, above, below, rhs, m);
    }
    std::vector<double> second(n);
    for (std::size_t i = 0; i < n; ++i) second[i] = gsl_vector_get(m, i);
    for (gsl_vector* v : {diag, above, below, rhs, m}) gsl_vector_free(v);
    if (status != GSL_SUCCESS) throw NumericalError("measured profile: the spline system is singular");
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double hi = h(i), ri = r[i];
      const double b = slope(i) - hi * (2 * second[i] + second[i + 1]) / 6;
      const double q1 = second[i], q2 = (second[i + 1] - second[i]) / (2 * hi);  // z' = b + q1 t + q2 t²
      pieces_.push_back({ri, r[i + 1], b - q1 * ri + q2 * ri * ri, q1 - 2 * q2 * ri, q2});
    }
  }

  // δ0(r) = r Σ ∫ (c0 + c1 s + c2 s²)/sqrt(r² - s²) ds over the pieces below r.
  double delta0(double r) const {
    if (!(r > 0.0)) return 0.0;
    double sum = 0.0;
    const double r2 = r * r;
    // Antiderivatives at s: J0 = asin(s/r), J1 = -sqrt(r² - s²), J2 = (r²/2) asin - (s/2) sqrt.
    auto primitive = [&](const Piece& p, double s) {
      const double x = std::min(1.0, s / r);
      const double phi = std::asin(x);
      const double root = r * std::sqrt(std::max(0.0, (1.0 - x) * (1.0 + x)));
      return p.c0 * phi - p.c1 * root + p.c2 * (0.5 * r2 * phi - 0.5 * s * root);
    };
    for (const Piece& p : pieces_) {
      if (p.lo >= r) break;
      const double hi = std::min(p.hi, r);
      sum += primitive(p, hi) - primitive(p, p.lo);
    }
    return r * sum;
  }

 private:
  std::vector<Piece> pieces_;
};

class MeasuredProfile final : public IndenterShape {
 public:
  MeasuredProfile(const std::vector<double>& r, const std::vector<double>& z, std::string source)
      : spline_(r, z), r_(r), source_(std::move(source)) {
    // Error estimate: the spline of every other point (keeping the last), whose O(h³) error is
    // ~8 times larger: error ≈ |difference|/7, relative to δ0, over the points past the first.
    std::vector<double> rc, zc;
    for (std::size_t i = 0; i < r.size(); i += 2) {
      rc.push_back(r[i]);
      zc.push_back(z[i]);
    }
    if (rc.back() != r.back()) {
      rc.push_back(r.back());
      zc.push_back(z.back());
    }
    if (rc.size() >= 5) {
      const Spline coarse(rc, zc);
      double worst = 0.0;
      for (std::size_t i = 1; i < r.size(); ++i) {
        for (double x : {r[i], 0.5 * (r[i - 1] + r[i])}) {
          const double fine = spline_.delta0(x);
          if (fine > 0.0) worst = std::max(worst, std::abs(fine - coarse.delta0(x)) / fine);
        }
      }
      error_ = worst / 7.0;
    } else {
      error_ = 1.0;  // too few points to tell
    }
  }
  double delta0(double r) const override { return spline_.delta0(r); }
  bool smooth_at_apex() const override { return false; }  // z''' jumps: reciprocity
  std::vector<double> kinks() const override { return std::vector<double>(r_.begin() + 1, r_.end()); }
  int kink_grading_levels() const override { return 6; }  // δ0 is C^2 at the knots
  double max_contact_radius() const override { return r_.back(); }
  double interpolation_error() const override { return error_; }
  std::string description() const override {
    return "measured profile " + source_ + ": " + std::to_string(r_.size()) +
           " points, r up to " + detail::short_text(r_.back()) +
           " m, cubic spline clamped z'(0) = 0, delta0 integrated exactly";
  }

 private:
  Spline spline_;
  std::vector<double> r_;
  std::string source_;
  double error_ = 0.0;
};

}  // namespace

std::shared_ptr<const IndenterShape> make_measured_profile(const std::vector<double>& r,
                                                           const std::vector<double>& z,
                                                           const std::string& source,
                                                           const std::vector<int>& lines) {
  auto where = [&](std::size_t i) {
    return source + (i < lines.size() ? ":" + std::to_string(lines[i]) : " point " + std::to_string(i + 1));
  };
  if (r.size() != z.size()) throw InputError(source + ": r and z have different lengths");
  if (r.size() < 5) {
    throw InputError(source + ": " + std::to_string(r.size()) +
                     " points; a profile needs at least 5 (r = 0 first, then increasing r)");
  }
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!std::isfinite(r[i]) || !std::isfinite(z[i])) throw InputError(where(i) + ": not a finite number");
  }
  if (r[0] != 0.0) {
    throw InputError(where(0) + ": the profile must start at r = 0 (the apex), not r = " +
                     detail::full_precision(r[0]));
  }
  for (std::size_t i = 1; i < r.size(); ++i) {
    if (!(r[i] > r[i - 1])) {
      throw InputError(where(i) + ": r = " + detail::full_precision(r[i]) +
                       " does not increase (the profile must be sorted by r, without repeats)");
    }
    if (z[i] < z[i - 1]) {
      throw InputError(where(i) + ": z = " + detail::full_precision(z[i]) +
                       " decreases; the profile must be monotonic (z non-decreasing in r)");
    }
  }
  return std::make_shared<MeasuredProfile>(r, z, source);
}

}  // namespace coatcontact
