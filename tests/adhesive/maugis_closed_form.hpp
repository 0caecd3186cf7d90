// Maugis's (1992) homogeneous closed form, solved here in the tests (THEORY.md section 13):
//   1 = (λ ā²/2)[sqrt(m²-1) + (m²-2) arccos(1/m)] + (4λ²ā/3)[sqrt(m²-1) arccos(1/m) - m + 1]
//   P = ā³ - λ ā² [sqrt(m²-1) + m² arccos(1/m)],   Δ_M = ā² - (4/3) λ ā sqrt(m²-1)
// with ā = ā_M. Written in e = m - 1 (sqrt(m²-1) = sqrt(e(2+e)), arccos(1/m) = atan of it) so
// that m -> 1 carries no cancellation; the root is bisected in ln e to the last bit.
#pragma once
#include <cmath>

namespace maugis {

struct State {
  double m = 0.0;
  double load = 0.0;         // P
  double penetration = 0.0;  // Δ_M
};

inline double residual(double lambda, double a, double e) {
  const double s = std::sqrt(e * (2.0 + e));
  const double acm = std::atan(s);
  const double m2 = (1.0 + e) * (1.0 + e);
  return 0.5 * lambda * a * a * (s + (m2 - 2.0) * acm) + 4.0 * lambda * lambda * a / 3.0 * (s * acm - e) - 1.0;
}

// a = ā_M > 0. The residual grows monotonically with e from -1 (e = 0).
inline State solve(double lambda, double a) {
  double lo = std::log(1e-300), hi = std::log(1e30);
  for (int i = 0; i < 400 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (residual(lambda, a, std::exp(mid)) > 0.0 ? hi : lo) = mid;
  }
  const double e = std::exp(0.5 * (lo + hi));
  const double s = std::sqrt(e * (2.0 + e));
  const double m2 = (1.0 + e) * (1.0 + e);
  State st;
  st.m = 1.0 + e;
  st.load = a * a * a - lambda * a * a * (s + m2 * std::atan(s));
  st.penetration = a * a - 4.0 / 3.0 * lambda * a * s;
  return st;
}

// The end of the curve a -> 0: c_M = m a stays finite,
// (λ π/4) c² + (4λ²/3)(π/2 - 1) c = 1, P = -λ (π/2) c², Δ_M = -(4/3) λ c.
inline State end_of_curve(double lambda) {
  const double A = lambda * M_PI / 4.0, B = 4.0 * lambda * lambda / 3.0 * (M_PI / 2.0 - 1.0);
  const double c = 2.0 / (B + std::sqrt(B * B + 4.0 * A));
  State st;
  st.m = INFINITY;
  st.load = -lambda * M_PI / 2.0 * c * c;
  st.penetration = -4.0 / 3.0 * lambda * c;
  return st;
}

// Load-controlled pull-off: golden-section minimum of P over ln ā_M on [lo, hi].
inline double pulloff_load(double lambda, double lo = 1e-3, double hi = 3.0) {
  double a = std::log(lo), b = std::log(hi);
  // Coarse scan for the global minimum, then golden section in its cell.
  const int n = 400;
  int best = 0;
  double best_value = INFINITY;
  for (int k = 0; k <= n; ++k) {
    const double v = solve(lambda, std::exp(a + (b - a) * k / n)).load;
    if (v < best_value) best_value = v, best = k;
  }
  double x0 = a + (b - a) * std::max(0, best - 1) / n, x1 = a + (b - a) * std::min(n, best + 1) / n;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 200 && x1 - x0 > 1e-12; ++i) {
    const double l = x1 - g * (x1 - x0), r = x0 + g * (x1 - x0);
    if (solve(lambda, std::exp(l)).load < solve(lambda, std::exp(r)).load) x1 = r; else x0 = l;
  }
  return std::min(solve(lambda, std::exp(0.5 * (x0 + x1))).load, end_of_curve(lambda).load);
}

// Location ā_M of the load-controlled pull-off: root of dP/dā_M (central differences of the
// closed form, which carries no root-finder noise beyond the last bit) by bisection.
inline double pulloff_location(double lambda, double lo, double hi) {
  auto slope = [&](double a) {
    const double h = 1e-5 * a;
    return (solve(lambda, a + h).load - solve(lambda, a - h).load) / (2.0 * h);
  };
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (slope(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace maugis
