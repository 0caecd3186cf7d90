// Reduced-variable solver: discretization, assembly, LAPACK solve and refinement
// (THEORY.md sections 4-5; the reduction to γ is derived in docs/solver.md).
#include "reduced_core.hpp"

#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <vector>

#include "coatcontact/errors.hpp"
#include "gauss_legendre.hpp"

namespace coatcontact::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Safety factor in the quadrature error model: Gauss error ~ M ρ^{-2m} where M, the size of
// H on the Bernstein ellipse, grows near the poles of H (order 3 for C - 1 ~ q² e^{-2q}).
// The ellipse is taken through 0.8 of the strip half-width, where M stays below ~1e3 |H|.
constexpr double kStripFraction = 0.8;
constexpr double kQuadratureSafety = 1e3;

std::string describe(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

struct Panel {
  double lo = 0.0;
  double hi = 0.0;
  double mid() const { return 0.5 * (lo + hi); }
  double half() const { return 0.5 * (hi - lo); }
};

// Panels graded geometrically toward the edge x = ã: the edge panel has length
// `edge_panel`; each further panel is `growth` times the distance of its outer end from ã,
// so every panel sees the edge singularities of γ (at ã ± 2i) under the same angle.
std::vector<Panel> make_panels(double a, const Discretization& disc) {
  if (a <= disc.single_panel_limit) return {Panel{0.0, a}};
  std::vector<Panel> panels;
  double inner = a - disc.edge_panel;
  panels.push_back(Panel{inner, a});
  for (;;) {
    const double next = disc.growth * (a - inner);
    // ~log2(ã) panels; the cap only guards against ã so large that a - 1 == a.
    if (panels.size() > 200 || !(next > 0.0)) {
      throw NumericalError("reduced solver: a/t = " + describe(a) + " is too large to grade");
    }
    // The innermost panel takes the rest when that is at most 1.5 regular lengths.
    if (inner <= 1.5 * next) {
      panels.push_back(Panel{0.0, inner});
      break;
    }
    panels.push_back(Panel{inner - next, inner});
    inner -= next;
  }
  std::reverse(panels.begin(), panels.end());
  return panels;
}

// Bernstein-ellipse parameter of the point c + i*height seen from `panel`: an analytic
// integrand whose nearest singularity is there is integrated by m-point Gauss with error
// ~ ρ^{-2m}.
double ellipse_rho(double c, double height, double mid, double half) {
  const std::complex<double> z((c - mid) / half, height / half);
  return std::abs(z + std::sqrt(z - 1.0) * std::sqrt(z + 1.0));
}

struct Layout {
  int p = 0;
  std::vector<Panel> panels;
  std::vector<double> x;  // all nodes, panel by panel
  std::vector<double> w;  // their quadrature weights on the panel
  const GaussRule* rule = nullptr;
  // Maps Legendre moments μ_n = ∫_panel P_n(t(y)) H dy to weights on the node values:
  // from_moments[k*p + n] = w_k (2n+1)/2 P_n(t_k) (discrete Legendre transform, exact for
  // the interpolating polynomial of degree p - 1).
  std::vector<double> from_moments;
};

Layout make_layout(double a, const Discretization& disc) {
  Layout layout;
  layout.p = disc.nodes_per_panel;
  layout.panels = make_panels(a, disc);
  layout.rule = &gauss_rule(layout.p);
  const int p = layout.p;
  for (const Panel& panel : layout.panels) {
    for (int k = 0; k < p; ++k) {
      layout.x.push_back(panel.mid() + panel.half() * layout.rule->nodes[k]);
      layout.w.push_back(panel.half() * layout.rule->weights[k]);
    }
  }
  layout.from_moments.assign(static_cast<std::size_t>(p * p), 0.0);
  std::vector<double> legendre(static_cast<std::size_t>(p));
  for (int k = 0; k < p; ++k) {
    legendre_values(layout.rule->nodes[k], p, legendre.data());
    for (int n = 0; n < p; ++n) {
      layout.from_moments[static_cast<std::size_t>(k * p + n)] =
          layout.rule->weights[k] * (2.0 * n + 1.0) / 2.0 * legendre[static_cast<std::size_t>(n)];
    }
  }
  return layout;
}

// Builds one row of the integral operator: row[j] = (1/π) ∫ ℓ_j(y) [H(x - y) + H(x + y)] dy
// over all panels, ℓ_j the Lagrange basis function of node j on its panel. Both terms are
// H(c - y) with c = x and c = -x (H is even). All H values of a row are evaluated in one
// batch.
class RowBuilder {
 public:
  RowBuilder(const KernelSource& kernel, const Layout& layout, const Discretization& disc)
      : kernel_(kernel),
        layout_(layout),
        height_(kStripFraction * kernel.analytic_half_width()),
        unit_(0.5 * kernel.analytic_half_width()),
        log_budget_(std::log(kQuadratureSafety / disc.quadrature_accuracy)),
        rho_needed_(std::exp(log_budget_ / (2.0 * layout.p))) {
    moments_.resize(static_cast<std::size_t>(layout.p));
    // P_n = a_n t P_{n-1} - b_n P_{n-2}, a_n = (2n-1)/n, b_n = (n-1)/n.
    recurrence_a_.assign(static_cast<std::size_t>(layout.p) + 1, 0.0);
    recurrence_b_.assign(static_cast<std::size_t>(layout.p) + 1, 0.0);
    for (int n = 2; n <= layout.p; ++n) {
      recurrence_a_[static_cast<std::size_t>(n)] = (2.0 * n - 1.0) / n;
      recurrence_b_[static_cast<std::size_t>(n)] = (n - 1.0) / n;
    }
  }

  // `h_minus`/`h_plus`, if given, hold H(x - x_j) and H(x + x_j) for every node j (the
  // Nyström values, computed once for the symmetric pair (i, j)).
  void build(double x, double* row, const double* h_minus = nullptr,
             const double* h_plus = nullptr) {
    tasks_.clear();
    used_ = 0;
    const std::size_t p = static_cast<std::size_t>(layout_.p);
    for (std::size_t panel_index = 0; panel_index < layout_.panels.size(); ++panel_index) {
      const Panel& panel = layout_.panels[panel_index];
      for (const double c : {x, -x}) {
        Task task;
        task.panel = panel_index;
        task.begin = used_;
        task.product = !nystrom_accurate(c, panel);
        const double* known = c == x ? h_minus : h_plus;
        if (task.product) {
          add_product_points(c, panel);
        } else if (known != nullptr) {
          task.known = known + panel_index * p;
        } else {
          // Nyström: the panel's own Gauss rule is accurate for γ(y) H(c - y).
          for (std::size_t k = 0; k < p; ++k) {
            append(c - layout_.x[panel_index * p + k], 0.0, layout_.w[panel_index * p + k]);
          }
        }
        task.end = used_;
        tasks_.push_back(task);
      }
    }
    if (h_.size() < used_) h_.resize(used_);
    if (scratch_.size() < 3 * used_) scratch_.resize(3 * used_);
    kernel_.evaluate(used_, u_.data(), h_.data());
    points_ += used_;

    std::fill(row, row + layout_.x.size(), 0.0);
    for (const Task& task : tasks_) {
      double* block = row + task.panel * p;
      if (task.known != nullptr) {
        const double* w = &layout_.w[task.panel * p];
        for (std::size_t k = 0; k < p; ++k) block[k] += w[k] * task.known[k] / kPi;
        continue;
      }
      if (!task.product) {
        for (std::size_t k = 0; k < p; ++k) {
          block[k] += weight_[task.begin + k] * h_[task.begin + k] / kPi;
        }
        continue;
      }
      // Legendre moments μ_n = Σ_i w_i H_i P_n(t_i): recurrence in n with the points as the
      // inner (vectorisable) loop.
      const std::size_t count = task.end - task.begin;
      const double* t = &t_[task.begin];
      double* previous = &scratch_[0];
      double* current = &scratch_[count];
      double* wh = &scratch_[2 * count];
      double m0 = 0.0, m1 = 0.0;
      for (std::size_t i = 0; i < count; ++i) {
        wh[i] = weight_[task.begin + i] * h_[task.begin + i];
        previous[i] = 1.0;
        current[i] = t[i];
        m0 += wh[i];
        m1 += wh[i] * t[i];
      }
      moments_[0] = m0;
      if (p > 1) moments_[1] = m1;
      for (std::size_t n = 2; n < p; ++n) {
        const double alpha = recurrence_a_[n];
        const double beta = recurrence_b_[n];
        double sum = 0.0;
        for (std::size_t i = 0; i < count; ++i) {
          const double next = alpha * t[i] * current[i] - beta * previous[i];
          previous[i] = next;  // swap via the pointer exchange below
          sum += wh[i] * next;
        }
        std::swap(previous, current);
        moments_[n] = sum;
      }
      for (std::size_t k = 0; k < p; ++k) {
        const double* f = &layout_.from_moments[k * p];
        double sum = 0.0;
        for (std::size_t n = 0; n < p; ++n) sum += f[n] * moments_[n];
        block[k] += sum / kPi;
      }
    }
  }

  // 2p ln ρ >= log budget, with a cheap sufficient test first: ρ of the real point c alone
  // (outside the panel, z = 1 + d/half) is a lower bound of ρ for c + i height.
  bool nystrom_accurate(double c, const Panel& panel) const {
    const double d = std::abs(c - panel.mid()) - panel.half();
    if (d > 0.0) {
      const double z = 1.0 + d / panel.half();
      if (z + std::sqrt(z * z - 1.0) >= rho_needed_) return true;
    }
    return ellipse_rho(c, height_, panel.mid(), panel.half()) >= rho_needed_;
  }

  // Kernel evaluations so far (cost statistics).
  std::size_t points() const { return points_; }

 private:
  struct Task {
    std::size_t panel = 0;
    std::size_t begin = 0;
    std::size_t end = 0;
    bool product = false;
    const double* known = nullptr;  // precomputed Nyström values
  };

  // Composite Gauss points for ∫_panel P_n(t(y)) H(c - y) dy: pieces graded away from c
  // (length <= max(unit, distance to c)), each with enough points for the degree p - 1
  // polynomial times H to reach the quadrature accuracy.
  void append(double u, double t, double weight) {
    if (used_ == u_.size()) {
      const std::size_t size = std::max<std::size_t>(1024, 2 * used_);
      u_.resize(size);
      t_.resize(size);
      weight_.resize(size);
    }
    u_[used_] = u;
    t_[used_] = t;
    weight_[used_] = weight;
    ++used_;
  }

  void add_product_points(double c, const Panel& panel) {
    if (c < panel.hi) walk(c, std::max(c, panel.lo), panel.hi, +1.0, panel);
    if (c > panel.lo) walk(c, std::min(c, panel.hi), panel.lo, -1.0, panel);
  }

  void walk(double c, double start, double stop, double direction, const Panel& panel) {
    double s = start;
    while ((stop - s) * direction > 0.0) {
      const double length = std::max(unit_, std::abs(s - c));
      double e = s + direction * length;
      if ((stop - e) * direction < 0.25 * length) e = stop;  // no slivers
      add_piece(c, std::min(s, e), std::max(s, e), panel);
      s = e;
    }
  }

  void add_piece(double c, double lo, double hi, const Panel& panel) {
    const double mid = 0.5 * (lo + hi);
    const double half = 0.5 * (hi - lo);
    const double rho = ellipse_rho(c, height_, mid, half);
    int m = static_cast<int>(std::ceil(0.5 * (layout_.p - 1 + log_budget_ / std::log(rho))));
    m = std::clamp(m, 2, kMaxGaussPoints);
    const GaussRule& rule = gauss_rule(m);
    for (int l = 0; l < m; ++l) {
      const double y = mid + half * rule.nodes[static_cast<std::size_t>(l)];
      append(c - y, (y - panel.mid()) / panel.half(), half * rule.weights[static_cast<std::size_t>(l)]);
    }
  }

  const KernelSource& kernel_;
  const Layout& layout_;
  double height_;     // imaginary distance of the (shrunk) strip edge
  double unit_;       // smallest piece length near c
  double log_budget_; // ln(safety / quadrature accuracy)
  double rho_needed_; // smallest ρ for which the panel's p-point Gauss rule is accurate
  std::vector<Task> tasks_;
  std::size_t used_ = 0;
  std::size_t points_ = 0;
  std::vector<double> u_, h_, t_, weight_, moments_, scratch_;
  std::vector<double> recurrence_a_, recurrence_b_;
};

double max_relative_difference(const ReducedValues& coarse, const ReducedValues& fine) {
  double worst = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    const double scale = std::max(std::abs(fine[i]), 1e-300);
    worst = std::max(worst, std::abs(fine[i] - coarse[i]) / scale);
  }
  return worst;
}

}  // namespace

FixedSolve solve_fixed(const KernelSource& kernel, double a, const Discretization& disc) {
  const Layout layout = make_layout(a, disc);
  const std::size_t n = layout.x.size();
  const lapack_int nn = static_cast<lapack_int>(n);
  RowBuilder builder(kernel, layout, disc);

  // A = I + K (column-major), and the row of K at the edge x = ã for the edge values.
  // H(x_i - x_j) and H(x_i + x_j) are symmetric in (i, j): evaluate each pair once.
  std::vector<double> h_minus(n * n), h_plus(n * n);
  {
    std::vector<double> u, h;
    u.reserve(n * (n + 1));
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i; j < n; ++j) {
        u.push_back(layout.x[i] - layout.x[j]);
        u.push_back(layout.x[i] + layout.x[j]);
      }
    }
    h.resize(u.size());
    kernel.evaluate(u.size(), u.data(), h.data());
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i; j < n; ++j, k += 2) {
        h_minus[i * n + j] = h_minus[j * n + i] = h[k];
        h_plus[i * n + j] = h_plus[j * n + i] = h[k + 1];
      }
    }
  }
  std::vector<double> matrix(n * n);
  std::vector<double> row(n);
  for (std::size_t i = 0; i < n; ++i) {
    builder.build(layout.x[i], row.data(), &h_minus[i * n], &h_plus[i * n]);
    row[i] += 1.0;
    for (std::size_t j = 0; j < n; ++j) matrix[i + j * n] = row[j];
  }
  std::vector<double> edge_row(n);
  builder.build(a, edge_row.data());

  double norm_inf = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += std::abs(matrix[i + j * n]);
    norm_inf = std::max(norm_inf, sum);
  }

  // Right-hand sides (columns): flat punch θ = 1; sphere θ = -(x/ã)²; cone θ = -(x/ã)
  // (scaled by ã² and ã so that Δ and Π come out without powers of ã); and the edge kernel
  // k_e(x) = H(x - ã) + H(x + ã), whose solution w gives every edge value by reciprocity:
  //   γ_θ(ã) = θ(ã) - (1/π) ∫ γ_θ k_e = θ(ã) - (1/π) ∫ θ w.
  // The cone uses this form: its θ = -|x|/ã has a kink at the apex x = 0, so γ_cone is not
  // smooth there (poles at ±2i) and is poorly resolved by the long central panel, while w,
  // γ_fp and γ_sphere are smooth at x = 0.
  constexpr std::size_t kColumns = 4;
  std::vector<double> rhs(n * kColumns);
  {
    std::vector<double> u(2 * n), h(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      u[i] = layout.x[i] - a;
      u[n + i] = layout.x[i] + a;
    }
    kernel.evaluate(2 * n, u.data(), h.data());
    for (std::size_t i = 0; i < n; ++i) {
      const double xi = layout.x[i] / a;
      rhs[i] = 1.0;
      rhs[i + n] = -xi * xi;
      rhs[i + 2 * n] = -xi;
      rhs[i + 3 * n] = h[i] + h[n + i];
    }
  }
  std::vector<lapack_int> pivots(n);
  lapack_int info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, nn, nn, matrix.data(), nn, pivots.data());
  if (info != 0) {
    throw NumericalError("reduced solver: singular linear system at a/t = " + describe(a) +
                         " (dgetrf info " + std::to_string(info) + ")");
  }
  double rcond = 0.0;
  info = LAPACKE_dgecon(LAPACK_COL_MAJOR, 'I', nn, matrix.data(), nn, norm_inf, &rcond);
  if (info != 0 || !(rcond > 0.0)) {
    throw NumericalError("reduced solver: condition estimate failed at a/t = " + describe(a));
  }
  info = LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', nn, static_cast<lapack_int>(kColumns),
                        matrix.data(), nn, pivots.data(), rhs.data(), nn);
  if (info != 0) {
    throw NumericalError("reduced solver: dgetrs failed at a/t = " + describe(a));
  }
  const double* gamma_fp = &rhs[0];
  const double* gamma_sphere = &rhs[n];
  const double* gamma_cone = &rhs[2 * n];
  const double* w = &rhs[3 * n];

  // Quadratures (exact for the interpolating polynomials): means, L1 norms, reciprocity.
  double sum_fp = 0.0, sum_sphere = 0.0, cone_by_reciprocity = 0.0;
  double norm_fp = 0.0, norm_sphere = 0.0, norm_cone = 0.0, norm_w = 0.0;
  double edge_fp_direct = 1.0, edge_sphere = -1.0, w_fp = 0.0, w_cone = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double xi = layout.x[j] / a;
    const double weight = layout.w[j];
    sum_fp += weight * gamma_fp[j];
    sum_sphere += weight * gamma_sphere[j];
    cone_by_reciprocity -= weight * xi * gamma_fp[j];  // ∫ γ_cone = ∫ θ_cone γ_fp
    norm_fp += weight * std::abs(gamma_fp[j]);
    norm_sphere += weight * std::abs(gamma_sphere[j]);
    norm_cone += weight * std::abs(gamma_cone[j]);
    norm_w += weight * std::abs(w[j]);
    edge_fp_direct -= edge_row[j] * gamma_fp[j];
    edge_sphere -= edge_row[j] * gamma_sphere[j];
    w_fp += weight * w[j];
    w_cone += weight * xi * w[j];
  }
  const double edge_fp = edge_fp_direct;            // γ_fp(ã) = 1 - (1/π) ∫ γ_fp k_e
  const double edge_fp_adjoint = 1.0 - w_fp / kPi;  // the same by reciprocity (a check)
  const double edge_cone = -1.0 + w_cone / kPi;     // γ_cone(ã) = θ(ã) - (1/π) ∫ θ w

  FixedSolve result;
  result.unknowns = static_cast<int>(n);
  result.panels = static_cast<int>(layout.panels.size());
  result.inverse_norm = 1.0 / (rcond * norm_inf);
  result.kernel_evaluations = builder.points() + n * (n + 1) + 2 * n;
  if (!(edge_fp > 0.0) || !std::isfinite(edge_fp)) {
    throw NumericalError("reduced solver: flat-punch edge value " + describe(edge_fp) +
                         " is not positive at a/t = " + describe(a));
  }
  ReducedValues& v = result.values;
  const double mean_fp = sum_fp / a;
  const double mean_sphere = sum_sphere / a;
  const double mean_cone = cone_by_reciprocity / a;
  v[kEEq] = mean_fp;                  // E_eq = (1/ã) ∫ γ_fp
  v[kGamma1] = edge_fp;               // Γ(1) = γ_fp(ã)
  v[kDeltaS] = -edge_sphere / edge_fp;  // Δ_s = δ'_H / ã²
  v[kPiS] = 4.0 * (v[kDeltaS] * mean_fp + mean_sphere);
  v[kDeltaC] = -edge_cone / edge_fp;    // Δ_c = δ'_c / ã
  v[kPiC] = 4.0 * (v[kDeltaC] * mean_fp + mean_cone);
  for (double value : v) {
    if (!std::isfinite(value)) {
      throw NumericalError("reduced solver: non-finite result at a/t = " + describe(a));
    }
  }
  result.consistency = std::abs(edge_fp - edge_fp_adjoint) / edge_fp;

  // Kernel accuracy ε (|δH| <= ε for every u): the coherent worst-case bound. It was the
  // solver's only kernel term until it was measured to be 4-5 orders of magnitude above the
  // real effect of the table's errors (which oscillate on the grid scale and cancel in the
  // integrals) where it grows like ã E_eq: rigid substrates and very soft films at large ã
  // (docs/solver.md). solve_adaptive now uses it only when it is already small, and replaces
  // it otherwise by an a-posteriori two-table estimate. To first order a mean ⟨θ, γ_fp⟩/ã moves by
  // ⟨γ_fp, δK γ_θ⟩/ã and an edge value by ⟨γ_θ, δk_e⟩/π - ⟨w, δK γ_θ⟩/π, with
  // |δK γ|(x) <= (2/π) ε |γ|_1 and |δk_e| <= 2ε. Written for the adhesionless solutions
  // γ_H = Δ γ_fp + γ_θ (edge value 0), which avoids adding up cancelling terms:
  //   |δE_eq| <= (2/π) ε |γ_fp|_1² / ã,       |δΓ1| <= (2/π) ε |γ_fp|_1 (1 + |w|_1/π),
  //   |δΔ| <= (2/π) ε |γ_H|_1 (1 + |w|_1/π) / Γ1,
  //   |δΠ|/4 <= E_eq |δΔ| / Δ ... (written out below) + (2/π) ε |γ_fp|_1 |γ_H|_1 / ã.
  // No condition number enters these bounds.
  double norm_h_sphere = 0.0, norm_h_cone = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    norm_h_sphere += layout.w[j] * std::abs(v[kDeltaS] * gamma_fp[j] + gamma_sphere[j]);
    norm_h_cone += layout.w[j] * std::abs(v[kDeltaC] * gamma_fp[j] + gamma_cone[j]);
  }
  const double eps = kernel.absolute_accuracy();
  const double c = 2.0 / kPi * eps;
  const double edge_factor = 1.0 + norm_w / kPi;
  auto relative = [](double error, double value) { return error / std::max(std::abs(value), 1e-300); };
  const double d_e_eq = c * norm_fp * norm_fp / a;
  const double d_gamma1 = c * norm_fp * edge_factor;
  const double d_delta_s = c * norm_h_sphere * edge_factor / edge_fp;
  const double d_delta_c = c * norm_h_cone * edge_factor / edge_fp;
  // Π/4 = Δ m_fp + m_θ: δ(Π/4) = δΔ m_fp + ⟨γ_fp, δK γ_H⟩/ã.
  const double d_pi_s = 4.0 * (d_delta_s * mean_fp + c * norm_fp * norm_h_sphere / a);
  const double d_pi_c = 4.0 * (d_delta_c * mean_fp + c * norm_fp * norm_h_cone / a);
  double kernel_error = std::max({relative(d_e_eq, v[kEEq]), relative(d_gamma1, v[kGamma1]),
                                  relative(d_delta_s, v[kDeltaS]), relative(d_delta_c, v[kDeltaC]),
                                  relative(d_pi_s, v[kPiS]), relative(d_pi_c, v[kPiC])});
  // The bounds are first order: they need |A^{-1}| |δK| small ((2/π) ε ã bounds |δK|_inf).
  const double perturbation = result.inverse_norm * c * a;
  if (perturbation > 0.1) kernel_error = std::max(kernel_error, perturbation);
  result.kernel_error = kernel_error;
  // Rounding in the assembly and the LU solve: ε_machine cond_inf(A). (It was the worst-case
  // 10 n ε_machine cond, which exceeds 1e-8 from ã ~ 30 for an incompressible film on a rigid
  // substrate.) Measured against a long-double LU of the same matrix and against random
  // relative perturbations ε_machine of every entry: the output errors are 0.003-0.08 of
  // ε_machine cond for cond from 1e2 to 3e9 (docs/solver.md). The two-table solve of
  // solve_adaptive, a second assembly and LU, also samples this noise.
  result.rounding_error = 2.220446049250313e-16 / rcond;
  return result;
}

AdaptiveSolve solve_adaptive(const KernelSource& kernel, double a, double tolerance,
                             const IndependentKernel& independent) {
  Discretization disc;
  disc.quadrature_accuracy = std::clamp(1e-4 * tolerance, 1e-14, 1e-11);
  // Measured convergence: the error falls by ~6.5 per node per panel, from ~10 at p = 0 for
  // the largest ã (docs/solver.md); start where that model meets the tolerance. The level
  // difference then estimates the coarser level's error, and the returned finer level is
  // better by a further factor ~6.5² = 40.
  const int start = std::clamp(
      static_cast<int>(std::ceil(std::log(10.0 / tolerance) / std::log(6.5))), 4, kMaxNodesPerPanel - 2);
  const int step = 2;
  disc.nodes_per_panel = start;
  FixedSolve previous = solve_fixed(kernel, a, disc);
  AdaptiveSolve result;
  double previous_two_table = std::numeric_limits<double>::infinity();
  for (int p = start + step; p <= kMaxNodesPerPanel; p += step) {
    disc.nodes_per_panel = p;
    FixedSolve current = solve_fixed(kernel, a, disc);
    result.values = current.values;
    result.discretization_error = max_relative_difference(previous.values, current.values);
    result.discretization_error = std::max(result.discretization_error, current.consistency);
    result.kernel_bound = current.kernel_error;
    result.rounding_error = current.rounding_error;
    result.unknowns = current.unknowns;
    result.nodes_per_panel = p;
    // Kernel term: the cheap coherent bound when it is small; else, once the discretization
    // and rounding terms fit, the effect of the table's errors measured a posteriori: the
    // same discretization re-assembled and re-solved with tables on independent grids.
    std::array<const KernelSource*, kIndependentTables> others{};
    if (current.kernel_error > 0.1 * tolerance && independent) {
      for (int k = 0; k < kIndependentTables; ++k) others[static_cast<std::size_t>(k)] = independent(k);
    }
    if (others[0] == nullptr || others[1] == nullptr) {
      result.kernel_error_kind = KernelErrorKind::kCoherentBound;
      result.kernel_error = current.kernel_error;
    } else if (result.discretization_error + result.rounding_error <= tolerance) {
      double difference = 0.0;
      for (const KernelSource* other : others) {
        const FixedSolve check = solve_fixed(*other, a, disc);
        difference = std::max(difference, max_relative_difference(check.values, current.values));
      }
      result.kernel_error_kind = KernelErrorKind::kTwoTable;
      result.kernel_error = kTwoTableSafety * difference;
    } else {
      result.kernel_error_kind = KernelErrorKind::kNotEvaluated;
      result.kernel_error = 0.0;
    }
    result.error_estimate =
        result.discretization_error + result.kernel_error + result.rounding_error;
    if (result.error_estimate <= tolerance &&
        result.kernel_error_kind != KernelErrorKind::kNotEvaluated) {
      result.converged = true;
      return result;
    }
    // The rounding term and the coherent bound do not shrink with p: stop when they alone are
    // too large. The two-table difference also carries the quadrature's sampling of the
    // table's grid-scale errors, which falls with p (measured: 1e-8 at p = 20, 8e-10 at 24,
    // incompressible film on a rigid substrate, a/t = 300): refine while it halves per level.
    if (result.rounding_error > tolerance) return result;
    if (result.kernel_error_kind == KernelErrorKind::kCoherentBound &&
        result.kernel_error + result.rounding_error > tolerance) {
      return result;
    }
    if (result.kernel_error_kind == KernelErrorKind::kTwoTable &&
        result.kernel_error + result.rounding_error > tolerance) {
      if (!(result.kernel_error < 0.5 * previous_two_table)) return result;
      previous_two_table = result.kernel_error;
    }
    previous = current;
  }
  return result;
}

}  // namespace coatcontact::detail
