// The Maugis-Dugdale cohesive zone for one contact radius (THEORY.md section 13): cohesive
// right-hand sides on the annulus, the regularity condition, the load and the gap h(c) from
// the cancellation-free formula, and the root h(c) = h0 in ln(c/a - 1).
#include "cohesive_zone.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "gauss_legendre.hpp"

namespace coatcontact::detail {

namespace {

using detail::kPi;

// Points and weights in φ on [0, φa] for integrals over the annulus y = c cos φ in [a, c],
// made of Gauss pieces. Pieces are graded in s = c - y toward the places where the integrands
// vary on the kernel's scale (THEORY.md section 13): the zone edge c, the contact edge a and,
// for an inner rule, `center` (the point x of k(x, y)); elsewhere they are as long as their
// distance from the nearest, and no piece spans more than `piece_angle` in φ.
struct AnnulusRule {
  std::vector<double> phi, weight, y;
  std::vector<double> weight_sin2;  // weight sin²φ: the cohesive weight sqrt(c² - y²) dy / c²
  std::vector<double> piece_s;      // piece j covers s in [piece_s[j], piece_s[j + 1]]
  std::vector<double> piece_phi;    // and φ in [piece_phi[j], piece_phi[j + 1]]
  void clear() {
    phi.clear();
    weight.clear();
    y.clear();
    weight_sin2.clear();
    piece_s.clear();
    piece_phi.clear();
  }
};

double phi_of(double c, double s) {  // φ with c - c cos φ = s, without cancellation
  return std::atan2(std::sqrt(s * (2.0 * c - s)), c - s);
}

// Appends the pieces covering s in [s_begin, s_end] (φ in [phi_begin, phi_end]), graded
// toward both ends and toward s_center.
void append_pieces(double c, double s_begin, double phi_begin, double s_end, double phi_end, double s_center,
                   const CohesiveQuadrature& q, AnnulusRule& rule) {
  const GaussRule& gauss = gauss_rule(q.points_per_piece);
  s_center = std::clamp(s_center, s_begin, s_end);
  // Leaving a special point a piece may be as long as its distance behind (ρ >= 3 + sqrt(8));
  // approaching one, half the distance ahead, so that no piece ends on the feature.
  double s = s_begin, phi = phi_begin;
  if (rule.piece_s.empty()) {
    rule.piece_s.push_back(s);
    rule.piece_phi.push_back(phi);
  }
  for (int pieces = 0; s < s_end; ++pieces) {
    if (pieces > 100000) throw NumericalError("cohesive zone: annulus quadrature does not terminate");
    const double behind = s >= s_center ? std::min(s - s_begin, s - s_center) : s - s_begin;
    const double ahead = s < s_center ? std::min(s_end - s, s_center - s) : s_end - s;
    double length = std::max(q.piece_length, std::min(behind, 0.5 * ahead));
    if (s < s_center && s + length > s_center) length = s_center - s;
    double next = s + length;
    if (s_end - next < 0.25 * length) next = s_end;
    double phi_next = next >= s_end ? phi_end : phi_of(c, next);
    if (phi_next - phi > q.piece_angle) {
      phi_next = phi + q.piece_angle;
      next = 2.0 * c * std::sin(0.5 * phi_next) * std::sin(0.5 * phi_next);
      if (phi_next >= phi_end) {
        phi_next = phi_end;
        next = s_end;
      }
    }
    const double mid = 0.5 * (phi + phi_next), half = 0.5 * (phi_next - phi);
    // Grown once per piece and written by index (a push_back per value cost ~5 % of a node).
    const std::size_t first = rule.y.size(), count = static_cast<std::size_t>(q.points_per_piece);
    rule.phi.resize(first + count);
    rule.weight.resize(first + count);
    rule.y.resize(first + count);
    rule.weight_sin2.resize(first + count);
    for (std::size_t k = 0; k < count; ++k) {
      const double f = mid + half * gauss.nodes[k];
      const double weight = half * gauss.weights[k];
      rule.phi[first + k] = f;
      rule.weight[first + k] = weight;
      rule.y[first + k] = c * std::cos(f);
      rule.weight_sin2[first + k] = weight * std::sin(f) * std::sin(f);
    }
    s = next;
    phi = phi_next;
    rule.piece_s.push_back(s);
    rule.piece_phi.push_back(phi);
  }
}

// The rule on the whole annulus s in [0, s_end] (φ in [0, φa]), graded toward c, a and center.
void annulus_rule(double c, double s_end, double phi_end, double center, const CohesiveQuadrature& q,
                  AnnulusRule& rule) {
  rule.clear();
  append_pieces(c, 0.0, 0.0, s_end, phi_end, c - center, q, rule);
}

// sums[i] = Σ_k w_k sin²φ_k [H(x_i - y_k) + H(x_i + y_k)] for one rule and many x; the
// cohesive values are b(x_i) = (c²/π) sums[i].
// u and h: scratch, resized here.
void kernel_sums(const KernelSource& kernel, const AnnulusRule& rule, const double* x, std::size_t count,
                 double* sums, std::vector<double>& u, std::vector<double>& h) {
  const std::size_t m = rule.y.size();
  u.resize(2 * m * count);
  h.resize(2 * m * count);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t k = 0; k < m; ++k) {
      u[2 * (i * m + k)] = x[i] - rule.y[k];
      u[2 * (i * m + k) + 1] = x[i] + rule.y[k];
    }
  }
  kernel.evaluate(u.size(), u.data(), h.data());
  for (std::size_t i = 0; i < count; ++i) {
    double sum = 0.0;
    for (std::size_t k = 0; k < m; ++k) sum += rule.weight_sin2[k] * (h[2 * (i * m + k)] + h[2 * (i * m + k) + 1]);
    sums[i] = sum;
  }
}

// Whether z (in the plane in which the piece is [-1, 1]) lies outside the Bernstein ellipse
// ρ; the ellipse lies within |z| <= (ρ + 1/ρ)/2, which decides most points without roots.
bool outside_ellipse(std::complex<double> z, double rho) {
  const double semi_major = 0.5 * (rho + 1.0 / rho);
  if (std::norm(z) > semi_major * semi_major) return true;
  const std::complex<double> w = z + std::sqrt(z - 1.0) * std::sqrt(z + 1.0);
  return std::max(std::abs(w), 1.0 / std::abs(w)) >= rho;
}

// The kernel sums of kernel_sums at the rule's own nodes, x = y_k. k(y_k, y) = H(y_k - y) +
// H(y_k + y) is singular where y_k - y or y_k + y reaches the edge ±i w of H's strip, in φ at
// arccos((±y_k + i w)/c). Each term integrates over a piece with the piece's own nodes when its
// point lies outside the piece's Bernstein ellipse ρ = 4 (Gauss error ~ρ^-2p, 1e-17 for p = 14,
// ~2e-10 for the table's 8: THEORY.md section 13); otherwise the piece is split into pieces
// graded toward y_k for that term (in practice the near term H(y_k - y) on the pieces around
// y_k; the mirror term only where y_k lies within ~w of 0). The node-to-node values are
// evaluated once per pair, and only for the pairs and terms that some node reads.
void kernel_sums_at_nodes(const KernelSource& kernel, double c, const AnnulusRule& rule,
                          const CohesiveQuadrature& q, double* sums) {
  constexpr double kRhoMin = 4.0;
  enum : char { kPlain = 0, kSplitNear = 1, kSplitBoth = 2 };
  const std::size_t m = rule.y.size();
  const std::size_t p = static_cast<std::size_t>(q.points_per_piece);
  const std::size_t pieces = rule.piece_s.size() - 1;
  const double w = kernel.analytic_half_width();
  // how[k * pieces + j]: how node k integrates piece j. Scratch per thread (a table node
  // calls this once; the allocations were ~2 % of it).
  thread_local std::vector<char> how;
  thread_local std::vector<double> u, h, minus, plus, cosh_limit;
  thread_local AnnulusRule sub;
  how.resize(m * pieces);
  // Most pairs are decided without the complex arccosines (2/3 of this classification's cost):
  // both points have |Im| = β, cosh β = (|ζ + 1| + |ζ - 1|)/2 at ζ = (y_k + i w)/c, and β >
  // semi-major axis x half puts both outside piece j's ellipse (THEORY.md section 13, "The
  // classification's shortcut"); the margin 1e-9 on cosh keeps every decision the full test's.
  constexpr double kSemiMajor = 0.5 * (kRhoMin + 1.0 / kRhoMin);
  cosh_limit.resize(pieces);
  for (std::size_t j = 0; j < pieces; ++j) {
    cosh_limit[j] = std::cosh(kSemiMajor * 0.5 * (rule.piece_phi[j + 1] - rule.piece_phi[j])) * (1.0 + 1e-9);
  }
  for (std::size_t k = 0; k < m; ++k) {
    const double re = rule.y[k] / c, im = w / c;
    const double cosh_beta =
        0.5 * (std::sqrt((re + 1.0) * (re + 1.0) + im * im) + std::sqrt((re - 1.0) * (re - 1.0) + im * im));
    std::complex<double> near, mirror;
    bool have_points = false;
    for (std::size_t j = 0; j < pieces; ++j) {
      if (cosh_beta > cosh_limit[j]) {
        how[k * pieces + j] = kPlain;
        continue;
      }
      if (!have_points) {
        near = std::acos(std::complex<double>(rule.y[k], w) / c);
        mirror = std::acos(std::complex<double>(-rule.y[k], w) / c);
        have_points = true;
      }
      const double mid = 0.5 * (rule.piece_phi[j] + rule.piece_phi[j + 1]);
      const double half = 0.5 * (rule.piece_phi[j + 1] - rule.piece_phi[j]);
      const bool near_out = outside_ellipse((near - mid) / half, kRhoMin);
      const bool mirror_out = outside_ellipse((mirror - mid) / half, kRhoMin);
      how[k * pieces + j] = !mirror_out ? kSplitBoth : near_out ? kPlain : kSplitNear;
    }
  }
  auto minus_read = [&](std::size_t k, std::size_t l) {
    return how[k * pieces + l / p] == kPlain || how[l * pieces + k / p] == kPlain;
  };
  auto plus_read = [&](std::size_t k, std::size_t l) {
    return how[k * pieces + l / p] != kSplitBoth || how[l * pieces + k / p] != kSplitBoth;
  };
  u.clear();
  for (std::size_t k = 0; k < m; ++k) {
    for (std::size_t l = 0; l <= k; ++l) {
      if (minus_read(k, l)) u.push_back(rule.y[k] - rule.y[l]);
      if (plus_read(k, l)) u.push_back(rule.y[k] + rule.y[l]);
    }
  }
  h.resize(u.size());
  kernel.evaluate(u.size(), u.data(), h.data());
  minus.resize(m * m);  // H(y_k - y_l), entries no node reads left unset
  plus.resize(m * m);   // H(y_k + y_l)
  std::size_t at = 0;
  for (std::size_t k = 0; k < m; ++k) {
    for (std::size_t l = 0; l <= k; ++l) {
      if (minus_read(k, l)) minus[k * m + l] = minus[l * m + k] = h[at++];
      if (plus_read(k, l)) plus[k * m + l] = plus[l * m + k] = h[at++];
    }
  }
  for (std::size_t k = 0; k < m; ++k) {
    const double s_k = c - rule.y[k];
    double sum = 0.0;
    for (std::size_t j = 0; j < pieces; ++j) {
      const char rule_j = how[k * pieces + j];
      if (rule_j == kPlain) {
        for (std::size_t l = j * p; l < (j + 1) * p; ++l) {
          sum += rule.weight_sin2[l] * (minus[k * m + l] + plus[k * m + l]);
        }
        continue;
      }
      sub.clear();
      append_pieces(c, rule.piece_s[j], rule.piece_phi[j], rule.piece_s[j + 1], rule.piece_phi[j + 1], s_k, q, sub);
      if (rule_j == kSplitBoth) {
        double part = 0.0;
        kernel_sums(kernel, sub, &rule.y[k], 1, &part, u, h);
        sum += part;
        continue;
      }
      // The mirror term on the piece's own nodes, the near term on the split rule.
      double part = 0.0;
      for (std::size_t l = j * p; l < (j + 1) * p; ++l) part += rule.weight_sin2[l] * plus[k * m + l];
      const std::size_t n = sub.y.size();
      u.resize(n);
      h.resize(n);
      for (std::size_t i = 0; i < n; ++i) u[i] = rule.y[k] - sub.y[i];
      kernel.evaluate(n, u.data(), h.data());
      for (std::size_t i = 0; i < n; ++i) part += sub.weight_sin2[i] * h[i];
      sum += part;
    }
    sums[k] = sum;
  }
}

// Brent's root finder (zeroin) on a sign-changing bracket; f must not throw mid-way.
template <typename F>
double brent_root(F&& f, double lo, double hi, double f_lo, double f_hi, double tolerance) {
  double a = lo, b = hi, fa = f_lo, fb = f_hi;
  double c = a, fc = fa, d = b - a, e = d;
  for (int iter = 0; iter < 200; ++iter) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b; b = c; c = a;
      fa = fb; fb = fc; fc = fa;
    }
    const double tol = 2.0 * 2.2e-16 * std::abs(b) + 0.5 * tolerance;
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || fb == 0.0) return b;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      double p, q, r;
      const double s = fb / fa;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        q = fa / fc;
        r = fb / fc;
        p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0));
        q = (q - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q; else p = -p;
      if (2.0 * p < std::min(3.0 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tol ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
  }
  return b;
}

}  // namespace

CohesiveZone::CohesiveZone(const KernelSource& kernel, double a, double radius, const Discretization& disc,
                           const CohesiveQuadrature& quadrature)
    : kernel_(kernel), a_(a), radius_(radius), quadrature_(quadrature) {
  factor(disc);
}

CohesiveZone::CohesiveZone(const KernelSource& kernel, double a, ShapeLoad delta0, const Discretization& disc,
                           const CohesiveQuadrature& quadrature)
    : kernel_(kernel), a_(a), radius_(1.0), shape_(std::move(delta0)), quadrature_(quadrature) {
  if (!shape_) throw InputError("cohesive zone: no shape load given");
  factor(disc);
}

void CohesiveZone::factor(const Discretization& disc) {
  const double a = a_, radius = radius_;
  quadrature_.piece_length *= strip_scale(kernel_);  // H varies on the scale of its strip
  if (!(a >= 0.0) || !std::isfinite(a) || !(radius > 0.0)) {
    throw InputError("cohesive zone: contact radius a/t = " + short_text(a) + " not allowed");
  }
  if (a == 0.0) return;
  // The zone uses the solutions alone: no condition estimate.
  system_ = std::make_unique<FactoredSystem>(kernel_, a, disc, false);
  const std::size_t n = system_->size();
  const Layout& layout = system_->layout();
  // Flat punch θ = 1 and the shape θ = -δ0(x) (sphere: -x²/R; THEORY.md sections 5 and 11),
  // solved once per radius.
  auto load = [&](double x) { return shape_ ? shape_(x) : x * x / radius; };
  std::vector<double> rhs(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    rhs[i] = 1.0;
    rhs[n + i] = -load(layout.x[i]);
  }
  system_->solve(rhs.data(), 2);
  gamma_fp_.assign(rhs.begin(), rhs.begin() + static_cast<long>(n));
  gamma_s_.assign(rhs.begin() + static_cast<long>(n), rhs.end());
  edge_fp_ = system_->edge_value(gamma_fp_.data(), 1.0);
  edge_s_ = system_->edge_value(gamma_s_.data(), -load(a));
}

struct CohesiveZone::Pass {
  double c = 0.0, c_minus_a = 0.0, root = 0.0, phi_end = 0.0;
  AnnulusRule outer;
  std::vector<double> gamma_c;  // (I + K) γ_c = b (a > 0)
  double edge_c = 0.0;          // edge value of γ_c (a > 0)
  double b0 = 0.0;              // b(0) (a = 0)
  std::vector<double> rows;     // kernel rows at the outer nodes (a > 0), m x n
  std::vector<double> sums;     // kernel sums at the outer nodes, m
};

void CohesiveZone::pass(double excess, Pass& p) const {
  const double a = a_;
  // c - a, sqrt(c² - a²) and φa = arccos(a/c) from the excess, free of cancellation.
  if (a > 0.0) {
    p.c = a * (1.0 + excess);
    p.c_minus_a = a * excess;
    p.root = a * std::sqrt(excess * (2.0 + excess));
    p.phi_end = std::atan(std::sqrt(excess * (2.0 + excess)));
  } else {
    p.c = excess;
    p.c_minus_a = p.c;
    p.root = p.c;
    p.phi_end = 0.5 * kPi;
  }
  const double c = p.c;
  annulus_rule(c, p.c_minus_a, p.phi_end, a, quadrature_, p.outer);
  const std::size_t m = p.outer.y.size();
  const std::size_t n = system_ ? system_->size() : 0;
  if (system_) {
    // H(x_i ∓ y_k) at the contact nodes x_i (and x = a) serve twice: the cohesive right-hand
    // side b(x_i) (kernel_sums' values, summed in the same order) and, H being even, the
    // Nyström part of the kernel rows at y_k. Per k: n + 1 values of H(x_i - y_k), then n + 1
    // of H(x_i + y_k).
    const Layout& layout = system_->layout();
    const std::size_t stride = 2 * (n + 1);
    thread_local std::vector<double> u, h;  // scratch per thread, as kernel_sums_at_nodes'
    u.resize(m * stride);
    h.resize(m * stride);
    for (std::size_t k = 0; k < m; ++k) {
      double* minus = &u[k * stride];
      const double y = p.outer.y[k];
      for (std::size_t i = 0; i < n; ++i) {
        minus[i] = layout.x[i] - y;
        minus[n + 1 + i] = layout.x[i] + y;
      }
      minus[n] = a - y;
      minus[2 * n + 1] = a + y;
    }
    kernel_.evaluate(u.size(), u.data(), h.data());
    std::vector<double> b(n + 1, 0.0);
    for (std::size_t k = 0; k < m; ++k) {
      const double* minus = &h[k * stride];
      const double w = p.outer.weight_sin2[k];
      for (std::size_t i = 0; i <= n; ++i) b[i] += w * (minus[i] + minus[n + 1 + i]);
    }
    for (double& value : b) value *= c * c / kPi;
    p.gamma_c.assign(b.begin(), b.begin() + static_cast<long>(n));
    system_->solve(p.gamma_c.data(), 1);
    p.edge_c = system_->edge_value(p.gamma_c.data(), b[n]);
    p.rows.resize(m * n);
    system_->kernel_rows(p.outer.y.data(), m, p.rows.data(), h.data(), h.data() + n + 1, stride);
  } else {
    const double zero = 0.0;
    std::vector<double> u, h;
    kernel_sums(kernel_, p.outer, &zero, 1, &p.b0, u, h);
    p.b0 *= c * c / kPi;
  }
  p.sums.resize(m);
  kernel_sums_at_nodes(kernel_, c, p.outer, quadrature_, p.sums.data());
}

double CohesiveZone::shape_gap(const Pass& p) const {
  double sum = 0.0;
  for (std::size_t k = 0; k < p.outer.y.size(); ++k) sum += p.outer.weight[k] * shape_(p.outer.y[k]);
  return sum;
}

CohesiveState CohesiveZone::evaluate(double sigma_hat, double excess) const {
  const double a = a_;
  const double R = radius_;
  Pass p;
  pass(excess, p);
  const double c = p.c, c_minus_a = p.c_minus_a, root = p.root, phi_end = p.phi_end;
  CohesiveState st;
  st.a = a;
  st.excess = excess;
  st.c = c;
  const std::size_t m = p.outer.y.size();

  // Interior: γ = δ γ_fp + γ_s + σ̂ γ_c with (I + K) γ_c = b; regularity fixes δ.
  const std::size_t n = system_ ? system_->size() : 0;
  std::vector<double> gamma(n);
  double integral = 0.0;  // ∫_0^a γ
  if (system_) {
    const Layout& layout = system_->layout();
    st.delta = -(edge_s_ + sigma_hat * (p.edge_c + root)) / edge_fp_;
    for (std::size_t i = 0; i < n; ++i) {
      gamma[i] = st.delta * gamma_fp_[i] + gamma_s_[i] + sigma_hat * p.gamma_c[i];
      integral += layout.w[i] * gamma[i];
    }
  } else {
    st.delta = -sigma_hat * (c + p.b0);  // θ(0) = γ(0) + θ_K(0)
  }

  // ∫_0^φa θ_K(c cos φ) dφ, θ_K(x) = row(x)·γ - σ̂ b(x), b at the outer nodes themselves.
  double theta_integral = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    double theta = 0.0;
    for (std::size_t j = 0; j < n; ++j) theta += p.rows[k * n + j] * gamma[j];
    theta_integral += p.outer.weight[k] * (theta - sigma_hat * c * c / kPi * p.sums[k]);
  }
  st.force = 2.0 * integral - sigma_hat * (c * c * phi_end - a * root);
  // The paraboloid's shape term in closed form.
  st.gap = shape_ ? 2.0 / kPi * (shape_gap(p) - st.delta * phi_end - sigma_hat * c_minus_a + theta_integral)
                  : 2.0 / kPi *
                        ((c * c / (2.0 * R) - st.delta) * phi_end + a / (2.0 * R) * root - sigma_hat * c_minus_a +
                         theta_integral);
  if (!std::isfinite(st.delta) || !std::isfinite(st.force) || !std::isfinite(st.gap)) {
    throw NumericalError("cohesive zone: non-finite state at a/t = " + short_text(a) +
                         ", c/t = " + short_text(c));
  }
  return st;
}

CohesiveFunctions CohesiveZone::functions(double excess) const {
  const double a = a_;
  const double R = radius_;
  thread_local Pass p;  // its vectors kept per thread: pass() sets every field this reads
  pass(excess, p);
  const double c = p.c, root = p.root, phi_end = p.phi_end;
  const std::size_t m = p.outer.y.size();
  const std::size_t n = system_ ? system_->size() : 0;
  CohesiveFunctions out;
  // Integrals of γ_fp, γ_s, γ_c over [0, a] and of θ_K's parts over [0, φa].
  double i_fp = 0.0, i_s = 0.0, i_c = 0.0;
  if (system_) {
    const Layout& layout = system_->layout();
    out.delta_h = -edge_s_ / edge_fp_;
    out.d = -(p.edge_c + root) / edge_fp_;
    for (std::size_t i = 0; i < n; ++i) {
      i_fp += layout.w[i] * gamma_fp_[i];
      i_s += layout.w[i] * gamma_s_[i];
      i_c += layout.w[i] * p.gamma_c[i];
    }
  } else {
    out.d = -(c + p.b0);
  }
  double t_fp = 0.0, t_s = 0.0, t_c = 0.0, t_b = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    double r_fp = 0.0, r_s = 0.0, r_c = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double row = p.rows[k * n + j];
      r_fp += row * gamma_fp_[j];
      r_s += row * gamma_s_[j];
      r_c += row * p.gamma_c[j];
    }
    const double w = p.outer.weight[k];
    t_fp += w * r_fp;
    t_s += w * r_s;
    t_c += w * r_c;
    t_b += w * c * c / kPi * p.sums[k];
  }
  out.force_h = 2.0 * (i_s + out.delta_h * i_fp);
  out.f = 2.0 * (i_c + out.d * i_fp) - (c * c * phi_end - a * root);
  out.g_r = shape_ ? 2.0 / kPi * (shape_gap(p) - out.delta_h * phi_end + t_s + out.delta_h * t_fp)
                   : 2.0 / kPi * ((c * c / (2.0 * R) - out.delta_h) * phi_end + a / (2.0 * R) * root + t_s +
                                  out.delta_h * t_fp);
  out.g_s = 2.0 / kPi * (-out.d * phi_end - p.c_minus_a + out.d * t_fp + t_c - t_b);
  if (!std::isfinite(out.d) || !std::isfinite(out.f) || !std::isfinite(out.g_r) || !std::isfinite(out.g_s)) {
    throw NumericalError("cohesive zone: non-finite state at a/t = " + short_text(a) + ", c/t = " + short_text(c));
  }
  return out;
}

CohesiveFunctions CohesiveZone::adhesionless() const {
  CohesiveFunctions out;
  if (!system_) return out;
  const Layout& layout = system_->layout();
  double i_fp = 0.0, i_s = 0.0;
  for (std::size_t i = 0; i < system_->size(); ++i) {
    i_fp += layout.w[i] * gamma_fp_[i];
    i_s += layout.w[i] * gamma_s_[i];
  }
  out.delta_h = -edge_s_ / edge_fp_;
  out.force_h = 2.0 * (i_s + out.delta_h * i_fp);
  return out;
}

CohesiveState CohesiveZone::solve(double sigma_hat, double h0, double guess_excess, double first_step) const {
  last_evaluations_ = 0;
  const double u_min = std::log(1e-14), u_max = std::log(1e8);
  // Every state evaluated, so that the root (always one of the evaluated points) is not
  // evaluated a second time.
  std::vector<std::pair<double, CohesiveState>> seen;
  auto f = [&](double u) {
    ++last_evaluations_;
    seen.emplace_back(u, evaluate(sigma_hat, std::exp(u)));
    return seen.back().second.gap - h0;
  };
  double u0 = std::clamp(std::log(guess_excess > 0.0 && std::isfinite(guess_excess) ? guess_excess : 1.0),
                         u_min, u_max);
  double f0 = f(u0);
  double u1 = u0, f1 = f0;
  double step = std::clamp(first_step, 1e-6, 1.5);
  // Expand away from the guess until the sign changes (h grows with c, h -> 0 as c -> a).
  for (bool first = true; (f0 > 0.0) == (f1 > 0.0); first = false) {
    if (!first) step = std::min(1.5, 3.0 * step);
    u0 = u1;
    f0 = f1;
    u1 = f0 > 0.0 ? u1 - step : u1 + step;
    if (u1 < u_min || u1 > u_max) {
      throw NumericalError("cohesive zone: no root of h(c) = h0 for c/a - 1 in [1e-14, 1e8] at a/t = " +
                           short_text(a_));
    }
    f1 = f(u1);
  }
  const double u = brent_root(f, u0, u1, f0, f1, 1e-13);
  for (auto it = seen.rbegin(); it != seen.rend(); ++it) {
    if (it->first == u) return it->second;
  }
  return evaluate(sigma_hat, std::exp(u));
}

}  // namespace coatcontact::detail
