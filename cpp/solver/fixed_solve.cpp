// The flat punch and any indenter shape on one factored system (THEORY.md section 5,
// docs/solver.md): right-hand sides, functionals and the kernel-table error bound.
#include "fixed_solve.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "factored_system.hpp"

namespace coatcontact::detail {

namespace {

using detail::kPi;

std::string describe(double value) { return short_text(value); }

// Product-integration weights W_j with Σ_j W_j f_j = ∫_0^ã θ(x/ã) f̃(x) dx for f̃ the panels'
// interpolating polynomials of node values f_j (THEORY.md section 11): per panel, the Legendre
// moments of θ by composite Gauss on pieces split at, and graded geometrically toward, the
// shape's singular points, then mapped to nodes by Layout::from_moments.
std::vector<double> product_weights(const Shape& shape, const Layout& layout, double a) {
  const int p = layout.p;
  const GaussRule& rule = gauss_rule(20);
  std::vector<double> singular;
  for (double xi : shape.singular_points()) singular.push_back(xi * a);
  const int levels = shape.grading_levels();
  std::vector<double> weights(layout.x.size(), 0.0);
  std::vector<double> moments(static_cast<std::size_t>(p));
  std::vector<double> legendre(static_cast<std::size_t>(p));
  for (std::size_t panel_index = 0; panel_index < layout.panels.size(); ++panel_index) {
    const Panel& panel = layout.panels[panel_index];
    // Break points inside the panel; the ends graded when a singular point is at or near them.
    std::vector<double> cuts = {panel.lo, panel.hi};
    bool grade_lo = false, grade_hi = false;
    const double length = panel.hi - panel.lo;
    for (double x : singular) {
      if (x > panel.lo && x < panel.hi) {
        cuts.push_back(x);
      } else if (x <= panel.lo && panel.lo - x < length) {
        grade_lo = true;
      } else if (x >= panel.hi && x - panel.hi < length) {
        grade_hi = true;
      }
    }
    std::sort(cuts.begin(), cuts.end());
    std::fill(moments.begin(), moments.end(), 0.0);
    auto integrate = [&](double lo, double hi) {
      const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
      for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
        const double x = mid + half * rule.nodes[k];
        const double value = half * rule.weights[k] * shape.theta(x / a);
        legendre_values((x - panel.mid()) / panel.half(), p, legendre.data());
        for (int n = 0; n < p; ++n) moments[static_cast<std::size_t>(n)] += value * legendre[static_cast<std::size_t>(n)];
      }
    };
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
      const double lo = cuts[c], hi = cuts[c + 1];
      const bool from_lo = c > 0 || grade_lo || std::find(singular.begin(), singular.end(), lo) != singular.end();
      const bool from_hi = c + 2 < cuts.size() || grade_hi ||
                           std::find(singular.begin(), singular.end(), hi) != singular.end();
      if (!from_lo && !from_hi) {
        integrate(lo, hi);
        continue;
      }
      // Halve toward each graded end: pieces [lo + d/2^{j+1}, lo + d/2^j] (and mirrored).
      const double split = from_lo && from_hi ? 0.5 * (lo + hi) : (from_lo ? hi : lo);
      if (from_lo) {
        double right = split;
        for (int j = 0; j < levels; ++j) {
          const double left = lo + 0.5 * (right - lo);
          integrate(left, right);
          right = left;
        }
        integrate(lo, right);
      }
      if (from_hi) {
        double left = split;
        for (int j = 0; j < levels; ++j) {
          const double right = hi - 0.5 * (hi - left);
          integrate(left, right);
          left = right;
        }
        integrate(left, hi);
      }
    }
    for (int k = 0; k < p; ++k) {
      double w = 0.0;
      for (int n = 0; n < p; ++n) {
        w += layout.from_moments[static_cast<std::size_t>(k * p + n)] * moments[static_cast<std::size_t>(n)];
      }
      weights[panel_index * static_cast<std::size_t>(p) + static_cast<std::size_t>(k)] = w;
    }
  }
  return weights;
}

}  // namespace

FixedSolve solve_shapes(const KernelSource& kernel, double a, const Discretization& disc,
                        const std::vector<const Shape*>& shapes) {
  const FactoredSystem system(kernel, a, disc);
  const Layout& layout = system.layout();
  const std::size_t n = system.size();
  const std::size_t m = shapes.size();

  // Columns: flat punch θ = 1, each shape's θ (scaled so that θ(ã) = -1: Δ and Π come out
  // without powers of ã), and the edge kernel k_e. A shape with a kink at the apex still gets
  // its column (its L1 norm enters the kernel-error bound) but its values come by reciprocity.
  std::vector<double> rhs(n * (m + 2));
  std::vector<double> theta(n * m);
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = layout.x[i] / a;
    rhs[i] = 1.0;
    for (std::size_t s = 0; s < m; ++s) {
      theta[s * n + i] = shapes[s]->theta(xi);
      rhs[i + (s + 1) * n] = theta[s * n + i];
    }
    rhs[i + (m + 1) * n] = system.edge_kernel()[i];
  }
  system.solve(rhs.data(), m + 2);
  const double* gamma_fp = &rhs[0];
  const double* w = &rhs[(m + 1) * n];

  // Quadratures (exact for the interpolating polynomials): means, L1 norms, reciprocity.
  double sum_fp = 0.0, norm_fp = 0.0, norm_w = 0.0, w_fp = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double weight = layout.w[j];
    sum_fp += weight * gamma_fp[j];
    norm_fp += weight * std::abs(gamma_fp[j]);
    norm_w += weight * std::abs(w[j]);
    w_fp += weight * w[j];
  }
  const double edge_fp = system.edge_value(gamma_fp, 1.0);  // γ_fp(ã) = 1 - (1/π) ∫ γ_fp k_e
  const double edge_fp_adjoint = 1.0 - w_fp / kPi;          // the same by reciprocity (a check)

  FixedSolve result;
  result.unknowns = static_cast<int>(n);
  result.panels = system.panels();
  if (!(edge_fp > 0.0) || !std::isfinite(edge_fp)) {
    throw NumericalError("reduced solver: flat-punch edge value " + describe(edge_fp) +
                         " is not positive at a/t = " + describe(a));
  }
  const double mean_fp = sum_fp / a;
  const double e_eq = mean_fp;   // E_eq = (1/ã) ∫ γ_fp
  const double gamma1 = edge_fp;  // Γ(1) = γ_fp(ã)
  result.consistency = std::abs(edge_fp - edge_fp_adjoint) / edge_fp;

  // Kernel accuracy ε (|δH| <= ε for every u): the coherent worst-case bound. It is 4-5
  // orders of magnitude above the real effect of the table's errors (which oscillate on the
  // grid scale and cancel in the integrals) where it grows like ã E_eq: rigid substrates and
  // very soft films at large ã (docs/solver.md). solve_adaptive uses it only when it is
  // already small, and an a-posteriori two-table estimate otherwise. To first order a mean ⟨θ, γ_fp⟩/ã moves by
  // ⟨γ_fp, δK γ_θ⟩/ã and an edge value by ⟨γ_θ, δk_e⟩/π - ⟨w, δK γ_θ⟩/π, with
  // |δK γ|(x) <= (2/π) ε |γ|_1 and |δk_e| <= 2ε. Written for the adhesionless solutions
  // γ_H = Δ γ_fp + γ_θ (edge value 0), which avoids adding up cancelling terms:
  //   |δE_eq| <= (2/π) ε |γ_fp|_1² / ã,       |δΓ1| <= (2/π) ε |γ_fp|_1 (1 + |w|_1/π),
  //   |δΔ| <= (2/π) ε |γ_H|_1 (1 + |w|_1/π) / Γ1,
  //   |δΠ|/4 <= E_eq |δΔ| / Δ ... (written out below) + (2/π) ε |γ_fp|_1 |γ_H|_1 / ã.
  // No condition number enters these bounds.
  const double eps = kernel.absolute_accuracy();
  const double c = 2.0 / kPi * eps;
  const double edge_factor = 1.0 + norm_w / kPi;
  auto relative = [](double error, double value) { return error / std::max(std::abs(value), 1e-300); };
  double kernel_error = std::max(relative(c * norm_fp * norm_fp / a, e_eq),
                                 relative(c * norm_fp * edge_factor, gamma1));
  for (std::size_t s = 0; s < m; ++s) {
    const double* th = &theta[s * n];
    const double* gamma = &rhs[(s + 1) * n];
    double sum = 0.0, edge = 0.0;
    if (shapes[s]->smooth_at_apex()) {
      for (std::size_t j = 0; j < n; ++j) sum += layout.w[j] * gamma[j];
      edge = system.edge_value(gamma, -1.0);
    } else if (!shapes[s]->singular_points().empty()) {
      const std::vector<double> weights = product_weights(*shapes[s], layout, a);
      double theta_w = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        sum += weights[j] * gamma_fp[j];  // ∫ γ_θ = ∫ θ γ_fp
        theta_w += weights[j] * w[j];
      }
      edge = shapes[s]->theta(1.0) - theta_w / kPi;
    } else {
      double theta_w = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        sum += layout.w[j] * th[j] * gamma_fp[j];  // ∫ γ_θ = ∫ θ γ_fp
        theta_w += layout.w[j] * th[j] * w[j];
      }
      edge = -1.0 - theta_w / kPi;  // γ_θ(ã) = θ(ã) - (1/π) ∫ θ w
    }
    const double delta = -edge / edge_fp;
    const double pi = 4.0 * (delta * mean_fp + sum / a);
    double norm_h = 0.0;
    for (std::size_t j = 0; j < n; ++j) norm_h += layout.w[j] * std::abs(delta * gamma_fp[j] + gamma[j]);
    const double d_delta = c * norm_h * edge_factor / edge_fp;
    // Π/4 = Δ m_fp + m_θ: δ(Π/4) = δΔ m_fp + ⟨γ_fp, δK γ_H⟩/ã.
    const double d_pi = 4.0 * (d_delta * mean_fp + c * norm_fp * norm_h / a);
    kernel_error = std::max({kernel_error, relative(d_delta, delta), relative(d_pi, pi)});
    result.values.push_back(pi);
    result.values.push_back(delta);
  }
  result.values.push_back(e_eq);
  result.values.push_back(gamma1);
  for (double value : result.values) {
    if (!std::isfinite(value)) {
      throw NumericalError("reduced solver: non-finite result at a/t = " + describe(a));
    }
  }
  // The bounds are first order: they need |A^{-1}| |δK| small ((2/π) ε ã bounds |δK|_inf).
  const double perturbation = system.inverse_norm() * c * a;
  if (perturbation > 0.1) kernel_error = std::max(kernel_error, perturbation);
  result.kernel_error = kernel_error;
  // Rounding in the assembly and the LU solve: ε_machine cond_inf(A) (the worst case
  // 10 n ε_machine cond would exceed 1e-8 from ã ~ 30 for an incompressible film on a rigid
  // substrate). Measured against a long-double LU of the same matrix and against random
  // relative perturbations ε_machine of every entry: the output errors are 0.003-0.08 of
  // ε_machine cond for cond from 1e2 to 3e9 (docs/solver.md). The two-table solve of
  // solve_adaptive, a second assembly and LU, also samples this noise.
  result.rounding_error = 2.220446049250313e-16 / system.reciprocal_condition();
  return result;
}

}  // namespace coatcontact::detail
