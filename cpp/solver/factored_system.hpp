// The discretized integral operator of the reduced-variable solver (internal to the library):
// panels graded toward the contact edge, assembly of I + K by Nyström sums and product
// integration (reduced_core.hpp explains the scheme), one LU factorization, then any number
// of right-hand sides. THEORY.md section 4.
#pragma once
#include <cstddef>
#include <vector>

#include "gauss_legendre.hpp"
#include "kernel_source.hpp"

namespace coatcontact::detail {

struct Panel {
  double lo = 0.0;
  double hi = 0.0;
  double mid() const { return 0.5 * (lo + hi); }
  double half() const { return 0.5 * (hi - lo); }
};

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

// I + K for one contact radius ã, factored once (LAPACK dgetf2, dgetrf for large systems).
class FactoredSystem {
 public:
  // Throws NumericalError if the matrix is singular or its condition cannot be estimated.
  // estimate_condition = false: no dgecon (a user of the solutions alone, as the cohesive
  // zone's table nodes: ~8 % of a factorization); inverse_norm() and reciprocal_condition()
  // are then NaN.
  FactoredSystem(const KernelSource& kernel, double a, const Discretization& disc, bool estimate_condition = true);

  std::size_t size() const { return layout_.x.size(); }
  const Layout& layout() const { return layout_; }
  double contact_radius() const { return a_; }
  // Solves (I + K) γ = θ in place for `count` columns of size() values each, one after another.
  void solve(double* columns, std::size_t count) const;
  // γ(ã) = θ(ã) - (1/π) ∫ γ k_e: the edge value from γ at the nodes.
  double edge_value(const double* gamma, double theta_at_edge) const;
  // k_e(x_i) = H(x_i - ã) + H(x_i + ã): its solution w gives every edge value by
  // reciprocity, γ_θ(ã) = θ(ã) - (1/π) ∫ θ w.
  const std::vector<double>& edge_kernel() const { return edge_kernel_; }
  // rows[k*size() + j] = (1/π) ∫ ℓ_j(y) [H(x_k - y) + H(x_k + y)] dy at any points x_k, also
  // outside [0, ã]: θ_K(x_k) = row_k · γ (the cohesive zone, THEORY.md section 13).
  void kernel_rows(const double* x, std::size_t count, double* rows) const;
  // The same with H(x_k - x_j) and H(x_k + x_j) already known for every node j, at
  // h_minus[k * stride + j] and h_plus[k * stride + j] (the Nyström values: no kernel
  // evaluation for the panels they serve; the rows are the same to the last bit).
  void kernel_rows(const double* x, std::size_t count, double* rows, const double* h_minus, const double* h_plus,
                   std::size_t stride) const;
  double inverse_norm() const { return 1.0 / (rcond_ * norm_inf_); }
  double reciprocal_condition() const { return rcond_; }
  int panels() const { return static_cast<int>(layout_.panels.size()); }

 private:
  double a_;
  const KernelSource* kernel_;
  Discretization disc_;
  Layout layout_;
  std::vector<double> lu_;
  std::vector<int> pivots_;
  std::vector<double> edge_row_;
  std::vector<double> edge_kernel_;
  double norm_inf_ = 0.0;
  double rcond_ = 0.0;
};

}  // namespace coatcontact::detail
