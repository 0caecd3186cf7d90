// Analytic test kernels and an independent brute-force solver for the reduced equation
//   θ(x) = γ(x) + (1/π) ∫_0^ã γ(y) [H(x - y) + H(x + y)] dy
// (tests only; THEORY.md section 4 with H replaced by closed forms).
#pragma once
#include <lapacke.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "reduced_core.hpp"

namespace coatcontact::test {

// f(q) = C(q) - 1 = c e^{-bq}:  H(u) = c b / (b² + u²)  (simple poles at ±ib, C(0) = 1 + c).
class LorentzKernel : public detail::KernelSource {
 public:
  LorentzKernel(double c, double b) : c_(c), b_(b) {}
  void evaluate(std::size_t n, const double* u, double* h) const override {
    for (std::size_t i = 0; i < n; ++i) h[i] = c_ * b_ / (b_ * b_ + u[i] * u[i]);
  }
  double analytic_half_width() const override { return b_; }
  double absolute_accuracy() const override { return 1e-16 * std::abs(c_) / b_; }

 private:
  double c_, b_;
};

// f(q) = c q e^{-bq}:  H(u) = c (b² - u²) / (b² + u²)²  (double poles at ±ib, C(0) = 1).
class DoublePoleKernel : public detail::KernelSource {
 public:
  DoublePoleKernel(double c, double b) : c_(c), b_(b) {}
  void evaluate(std::size_t n, const double* u, double* h) const override {
    for (std::size_t i = 0; i < n; ++i) {
      const double s = b_ * b_ + u[i] * u[i];
      h[i] = c_ * (b_ * b_ - u[i] * u[i]) / (s * s);
    }
  }
  double analytic_half_width() const override { return b_; }
  double absolute_accuracy() const override { return 1e-16 * std::abs(c_) / (b_ * b_); }

 private:
  double c_, b_;
};

// H ≡ 0 (homogeneous half-space).
class ZeroKernel : public detail::KernelSource {
 public:
  void evaluate(std::size_t n, const double*, double* h) const override {
    for (std::size_t i = 0; i < n; ++i) h[i] = 0.0;
  }
  double analytic_half_width() const override { return 2.0; }
  double absolute_accuracy() const override { return 0.0; }
};

// Brute force, written independently of the solver: uniform panels of length <= `panel`
// with `points` Gauss nodes each (plain Nyström everywhere, no grading, no product
// integration), edge value by Nyström interpolation. Returns the six reduced variables in
// the solver's order (Π_s, Δ_s, Π_c, Δ_c, E_eq, Γ1).
inline std::array<double, 6> brute_force(const detail::KernelSource& kernel, double a,
                                         double panel, int points) {
  // Gauss-Legendre by Golub-Welsch-free Newton iteration (own copy, independent).
  std::vector<double> t(static_cast<std::size_t>(points)), wt(static_cast<std::size_t>(points));
  const double pi = std::acos(-1.0);
  for (int k = 0; k < points; ++k) {
    double x = std::cos(pi * (k + 0.75) / (points + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 200; ++it) {
      double p0 = 1.0, p1 = x;
      for (int m = 2; m <= points; ++m) {
        const double p2 = ((2.0 * m - 1.0) * x * p1 - (m - 1.0) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      dp = points * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    t[static_cast<std::size_t>(k)] = x;
    wt[static_cast<std::size_t>(k)] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  const int panels = static_cast<int>(std::ceil(a / panel));
  const double len = a / panels;
  std::vector<double> x, w;
  for (int j = 0; j < panels; ++j) {
    for (int k = 0; k < points; ++k) {
      x.push_back((j + 0.5) * len + 0.5 * len * t[static_cast<std::size_t>(k)]);
      w.push_back(0.5 * len * wt[static_cast<std::size_t>(k)]);
    }
  }
  const std::size_t n = x.size();
  auto kernel_row = [&](double xi, std::vector<double>& row) {
    std::vector<double> u(2 * n), h(2 * n);
    for (std::size_t j = 0; j < n; ++j) {
      u[j] = xi - x[j];
      u[n + j] = xi + x[j];
    }
    kernel.evaluate(2 * n, u.data(), h.data());
    row.resize(n);
    for (std::size_t j = 0; j < n; ++j) row[j] = w[j] * (h[j] + h[n + j]) / pi;
  };
  std::vector<double> m(n * n), rhs(3 * n), row;
  for (std::size_t i = 0; i < n; ++i) {
    kernel_row(x[i], row);
    for (std::size_t j = 0; j < n; ++j) m[i + j * n] = row[j] + (i == j ? 1.0 : 0.0);
    rhs[i] = 1.0;
    rhs[n + i] = -x[i] * x[i];
    rhs[2 * n + i] = -x[i];
  }
  std::vector<lapack_int> piv(n);
  const lapack_int nn = static_cast<lapack_int>(n);
  if (LAPACKE_dgesv(LAPACK_COL_MAJOR, nn, 3, m.data(), nn, piv.data(), rhs.data(), nn) != 0) {
    throw std::runtime_error("brute_force: singular system");
  }
  kernel_row(a, row);
  double edge[3], integral[3];
  const double theta[3] = {1.0, -a * a, -a};
  for (int r = 0; r < 3; ++r) {
    const double* g = &rhs[static_cast<std::size_t>(r) * n];
    double kg = 0.0, s = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      kg += row[j] * g[j];
      s += w[j] * g[j];
    }
    edge[r] = theta[r] - kg;
    integral[r] = s;
  }
  // THEORY.md section 5 in units of t: δ'_H = -γ_2(ã)/γ_fp(ã), γ_H = δ'_H γ_fp + γ_2.
  const double dh_s = -edge[1] / edge[0];
  const double dh_c = -edge[2] / edge[0];
  std::array<double, 6> v{};
  v[detail::kEEq] = integral[0] / a;
  v[detail::kGamma1] = edge[0];
  v[detail::kDeltaS] = dh_s / (a * a);
  v[detail::kPiS] = 4.0 * (dh_s * integral[0] + integral[1]) / (a * a * a);
  v[detail::kDeltaC] = dh_c / a;
  v[detail::kPiC] = 4.0 * (dh_c * integral[0] + integral[2]) / (a * a);
  return v;
}

}  // namespace coatcontact::test
