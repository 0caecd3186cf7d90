// Assembly and factorization of the reduced-variable solver's linear system
// (THEORY.md section 4; the reduction to γ is derived in docs/solver.md).
#include "factored_system.hpp"

#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::detail {

static_assert(std::is_same_v<lapack_int, int>, "pivots_ (factored_system.hpp) are stored as int");

namespace {

using detail::kPi;

// Safety factor in the quadrature error model: Gauss error ~ M ρ^{-2m} where M, the size of
// H on the Bernstein ellipse, grows near the poles of H (order 3 for C - 1 ~ q² e^{-2q}).
// The ellipse is taken through 0.8 of the strip half-width, where M stays below ~1e3 |H|.
constexpr double kStripFraction = 0.8;
constexpr double kQuadratureSafety = 1e3;

std::string describe(double value) { return short_text(value); }

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
// (Real form: ρ = s + sqrt(s² - 1), s = (|z - 1| + |z + 1|)/2 the ellipse's semi-major axis;
// the same ρ as |z + sqrt(z - 1) sqrt(z + 1)| up to rounding, without complex square roots
// and hypot. ρ only feeds integer decisions (Nyström or product integration, points per
// piece); none differs from the complex form's over the full test suite and the checked sweeps.)
double ellipse_rho(double c, double height, double mid, double half) {
  const double x = (c - mid) / half;
  const double y = height / half;
  const double s = 0.5 * (std::sqrt((x - 1.0) * (x - 1.0) + y * y) + std::sqrt((x + 1.0) * (x + 1.0) + y * y));
  return s + std::sqrt(std::max(0.0, (s - 1.0) * (s + 1.0)));
}

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
      std::size_t n = 2;
      // Four degrees per pass over the points: four independent sums (each still added in
      // point order, so the moments are the same to the last bit), a quarter of the loads.
      for (; n + 4 <= p; n += 4) {
        const double a0 = recurrence_a_[n], a1 = recurrence_a_[n + 1];
        const double a2 = recurrence_a_[n + 2], a3 = recurrence_a_[n + 3];
        const double b0 = recurrence_b_[n], b1 = recurrence_b_[n + 1];
        const double b2 = recurrence_b_[n + 2], b3 = recurrence_b_[n + 3];
        double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
        for (std::size_t i = 0; i < count; ++i) {
          const double ti = t[i], w = wh[i];
          const double q0 = a0 * ti * current[i] - b0 * previous[i];
          const double q1 = a1 * ti * q0 - b1 * current[i];
          const double q2 = a2 * ti * q1 - b2 * q0;
          const double q3 = a3 * ti * q2 - b3 * q1;
          s0 += w * q0;
          s1 += w * q1;
          s2 += w * q2;
          s3 += w * q3;
          previous[i] = q2;
          current[i] = q3;
        }
        moments_[n] = s0;
        moments_[n + 1] = s1;
        moments_[n + 2] = s2;
        moments_[n + 3] = s3;
      }
      for (; n < p; ++n) {
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
  std::vector<double> u_, h_, t_, weight_, moments_, scratch_;
  std::vector<double> recurrence_a_, recurrence_b_;
};

}  // namespace

// H(x_i - x_j) and H(x_i + x_j) into h_minus/h_plus[i n + j] for the pairs that a row reads:
// row i takes panel P's Nyström values where P's own rule is accurate for c = x_i (resp. -x_i)
// and evaluates product points elsewhere, so a pair is needed if row i reads it at j's panel
// or row j at i's. H(x_i ∓ x_j) is symmetric in (i, j): each pair is evaluated once (the
// pairs both rows integrate by product rules, within and next to the diagonal panels, not at
// all).
static void nystrom_values(const KernelSource& kernel, const Layout& layout, const RowBuilder& builder,
                           double* h_minus, double* h_plus) {
  const std::size_t n = layout.x.size(), p = static_cast<std::size_t>(layout.p), panels = layout.panels.size();
  std::vector<char> minus_read(n * panels), plus_read(n * panels);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t q = 0; q < panels; ++q) {
      minus_read[i * panels + q] = builder.nystrom_accurate(layout.x[i], layout.panels[q]);
      plus_read[i * panels + q] = builder.nystrom_accurate(-layout.x[i], layout.panels[q]);
    }
  }
  auto minus_needed = [&](std::size_t i, std::size_t j) {
    return minus_read[i * panels + j / p] || minus_read[j * panels + i / p];
  };
  auto plus_needed = [&](std::size_t i, std::size_t j) {
    return plus_read[i * panels + j / p] || plus_read[j * panels + i / p];
  };
  std::vector<double> u, h;
  u.reserve(n * (n + 1));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      if (minus_needed(i, j)) u.push_back(layout.x[i] - layout.x[j]);
      if (plus_needed(i, j)) u.push_back(layout.x[i] + layout.x[j]);
    }
  }
  h.resize(u.size());
  kernel.evaluate(u.size(), u.data(), h.data());
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      if (minus_needed(i, j)) h_minus[i * n + j] = h_minus[j * n + i] = h[k++];
      if (plus_needed(i, j)) h_plus[i * n + j] = h_plus[j * n + i] = h[k++];
    }
  }
}

// The panels' lengths are set for H analytic in |Im u| < 2 (one film); a stack's H is
// analytic only in |Im u| < 2 h_top/T (THEORY.md section 12), so its edge singularities of
// gamma are nearer the axis and the panels shrink with the strip (unchanged for one film).
static Discretization scaled_to_strip(const KernelSource& kernel, const Discretization& disc) {
  const double scale = strip_scale(kernel);
  if (scale == 1.0) return disc;
  Discretization scaled = disc;
  scaled.edge_panel *= scale;
  scaled.single_panel_limit *= scale;
  return scaled;
}

FactoredSystem::FactoredSystem(const KernelSource& kernel, double a, const Discretization& disc,
                               bool estimate_condition)
    : a_(a), kernel_(&kernel), disc_(disc), layout_(make_layout(a, scaled_to_strip(kernel, disc))) {
  const std::size_t n = layout_.x.size();
  const lapack_int nn = static_cast<lapack_int>(n);
  RowBuilder builder(kernel, layout_, disc);

  // A = I + K (column-major), and the row of K at the edge x = ã for the edge values.
  // (Not zeroed: every entry a row reads is written.)
  std::unique_ptr<double[]> h_minus(new double[n * n]), h_plus(new double[n * n]);
  nystrom_values(kernel, layout_, builder, h_minus.get(), h_plus.get());
  lu_.resize(n * n);
  std::vector<double> row(n);
  for (std::size_t i = 0; i < n; ++i) {
    builder.build(layout_.x[i], row.data(), &h_minus[i * n], &h_plus[i * n]);
    row[i] += 1.0;
    for (std::size_t j = 0; j < n; ++j) lu_[i + j * n] = row[j];
  }
  edge_row_.resize(n);
  builder.build(a, edge_row_.data());

  bool has_nan = false;
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += std::abs(lu_[i + j * n]);
    has_nan = has_nan || std::isnan(sum);
    norm_inf_ = std::max(norm_inf_, sum);
  }
  {
    std::vector<double> u(2 * n), h(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      u[i] = layout_.x[i] - a;
      u[n + i] = layout_.x[i] + a;
    }
    kernel.evaluate(2 * n, u.data(), h.data());
    edge_kernel_.resize(n);
    for (std::size_t i = 0; i < n; ++i) edge_kernel_[i] = h[i] + h[n + i];
  }

  std::vector<lapack_int> pivots(n);
  // LAPACKE's NaN scans of the matrix (before dgetrf and dgecon) are done here once, as the
  // row sums above (LAPACKE_dgetrf reports a NaN as info -4). The unblocked dgetf2: below
  // LAPACK's block size dgetrf runs the recursive dgetrf2, whose small dtrsm and dgemm calls
  // cost 1.2-2.5x dgetf2's rank-1 updates at these sizes (n = 14-170, reference BLAS; the same
  // factors to the last bit there, the same updates in the same order). Large systems keep
  // the blocked dgetrf.
  constexpr std::size_t kUnblockedLimit = 256;
  lapack_int info = has_nan          ? -4
                    : n <= kUnblockedLimit ? LAPACKE_dgetf2_work(LAPACK_COL_MAJOR, nn, nn, lu_.data(), nn, pivots.data())
                                           : LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, nn, nn, lu_.data(), nn, pivots.data());
  if (info != 0) {
    throw NumericalError("reduced solver: singular linear system at a/t = " + describe(a) +
                         " (LU info " + std::to_string(info) + ")");
  }
  if (!estimate_condition) {
    rcond_ = std::numeric_limits<double>::quiet_NaN();
  } else {
    std::vector<double> work(4 * n);
    std::vector<lapack_int> iwork(n);
    info = LAPACKE_dgecon_work(LAPACK_COL_MAJOR, 'I', nn, lu_.data(), nn, norm_inf_, &rcond_,
                               work.data(), iwork.data());
  }
  if (estimate_condition && (info != 0 || !(rcond_ > 0.0))) {
    throw NumericalError("reduced solver: condition estimate failed at a/t = " + describe(a));
  }
  pivots_.assign(pivots.begin(), pivots.end());
}

void FactoredSystem::solve(double* columns, std::size_t count) const {
  const lapack_int nn = static_cast<lapack_int>(size());
  // The _work form: LAPACKE_dgetrs scans the factors and the right-hand sides for NaN at
  // every call (~1.5 % of a Maugis-Dugdale fit, one call per table node); the factors were
  // checked once before dgetrf, and a NaN right-hand side gives a NaN solution, which every
  // caller rejects as a non-finite result.
  const lapack_int info = LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', nn, static_cast<lapack_int>(count),
                                              lu_.data(), nn, reinterpret_cast<const lapack_int*>(pivots_.data()),
                                              columns, nn);
  if (info != 0) {
    throw NumericalError("reduced solver: dgetrs failed at a/t = " + describe(a_));
  }
}

void FactoredSystem::kernel_rows(const double* x, std::size_t count, double* rows) const {
  RowBuilder builder(*kernel_, layout_, disc_);
  for (std::size_t k = 0; k < count; ++k) builder.build(x[k], rows + k * size());
}

void FactoredSystem::kernel_rows(const double* x, std::size_t count, double* rows, const double* h_minus,
                                 const double* h_plus, std::size_t stride) const {
  RowBuilder builder(*kernel_, layout_, disc_);
  for (std::size_t k = 0; k < count; ++k) {
    builder.build(x[k], rows + k * size(), h_minus + k * stride, h_plus + k * stride);
  }
}

double FactoredSystem::edge_value(const double* gamma, double theta_at_edge) const {
  double edge = theta_at_edge;
  for (std::size_t j = 0; j < size(); ++j) edge -= edge_row_[j] * gamma[j];
  return edge;
}

}  // namespace coatcontact::detail
