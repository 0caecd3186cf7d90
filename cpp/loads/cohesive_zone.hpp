// The Maugis-Dugdale cohesive zone on a coated substrate for one contact radius (THEORY.md
// section 13), on the factored system of section 4. Units: film thickness t = 1, E1* = 1,
// sphere radius R (the paraboloid z = r²/2R), γ = 2g/E1*, σ̂ = 2σ0/E1*. For a zone [a, c]:
//   (I + K) γ = δ - x²/R + σ̂ b(x),   b(x) = (1/π) ∫_a^c sqrt(c² - y²) k(x, y) dy,
//   regularity γ(a⁻) = -σ̂ sqrt(c² - a²) fixes δ,
//   F = 2 ∫_0^a γ - σ̂ [c² arccos(a/c) - a sqrt(c² - a²)],
//   h(c) = (2/π) [(c²/2R - δ) φa + (a/2R) sqrt(c² - a²) - σ̂ (c - a) + ∫_0^φa θ_K(c cos φ) dφ],
// φa = arccos(a/c), θ_K(x) = row(x)·γ - σ̂ b(x), k(x, y) = H(x - y) + H(x + y). On the
// annulus y = c cos φ (no square-root end points). a = 0 is the end of the curve: no contact,
// a disk of tension, δ = θ(0) = -σ̂ (c + b(0)).
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "factored_system.hpp"
#include "kernel_source.hpp"

namespace coatcontact::detail {

struct CohesiveQuadrature {
  int points_per_piece = 14;   // Gauss-Legendre points per annulus piece (in φ)
  double piece_length = 1.0;   // piece length in y at the special points (units of t, one film:
                               // H varies on the scale 2; shrunk with a stack's strip)
  double piece_angle = 0.5;    // longest piece in φ (sin² and cos are entire)
};

// The zone at one (a, c) split by its loads (THEORY.md section 13, "The cohesive zone as a
// table"): δ = δ_H + σ̂ d, F = F_H + σ̂ f, h(c) = g_R + σ̂ g_σ at the zone's radius R.
struct CohesiveFunctions {
  double delta_h = 0.0;  // adhesionless penetration δ_H = a² Δ_s(a) R⁻¹      (1-D)
  double force_h = 0.0;  // adhesionless load F_H = a³ Π_s(a)/(2R)            (1-D)
  double d = 0.0;        // penetration per unit σ̂ (edge condition solved for δ)
  double f = 0.0;        // load per unit σ̂
  double g_r = 0.0;      // gap at c of the adhesionless solution
  double g_s = 0.0;      // gap at c per unit σ̂
};

// One state (a, c) of the zone, units as above.
struct CohesiveState {
  double a = 0.0;
  double c = 0.0;
  double excess = 0.0;  // c/a - 1 (a > 0) or c (a = 0), the root variable's exponential
  double delta = 0.0;
  double force = 0.0;
  double gap = 0.0;     // h(c)
};

// An axisymmetric indenter other than the paraboloid (THEORY.md section 13, "Any axisymmetric
// shape"): its load δ0(x) of section 11 in the zone's units (t = 1), defined and smooth on
// [0, c] for every zone edge c asked for.
using ShapeLoad = std::function<double(double x)>;

class CohesiveZone {
 public:
  // a > 0: assembles and factors I + K at ã = a once; a == 0: no system (the curve's end).
  CohesiveZone(const KernelSource& kernel, double a, double radius, const Discretization& disc,
               const CohesiveQuadrature& quadrature = {});
  // The same for the indenter whose load is delta0 (the paraboloid of radius R: x²/R): the shape
  // enters the right-hand side -δ0(x), the edge value and the gap's term ∫_0^φa δ0(c cos φ) dφ,
  // integrated on the annulus rule. The functions() split then holds for this shape (R = 1).
  CohesiveZone(const KernelSource& kernel, double a, ShapeLoad delta0, const Discretization& disc,
               const CohesiveQuadrature& quadrature = {});
  // δ, F and h(c) for the tension σ̂ on [a, c], c = a (1 + excess) (a > 0) or c = excess (a = 0);
  // excess > 0 given directly so that c - a carries no cancellation.
  CohesiveState evaluate(double sigma_hat, double excess) const;
  // The parts of evaluate() per load, from one pass (one annulus rule, one cohesive solve):
  // evaluate(σ̂, e) equals δ_H + σ̂ d, F_H + σ̂ f, g_R + σ̂ g_σ to rounding.
  CohesiveFunctions functions(double excess) const;
  // δ_H and F_H alone (the adhesionless solution at a; no annulus), a > 0.
  CohesiveFunctions adhesionless() const;
  // Solves h(c) = h0 for c by a bracketed Brent root in u = ln(excess); throws NumericalError
  // if no sign change is found for excess in [1e-14, 1e8]. The bracket is searched from the
  // guess in steps of first_step in u, growing threefold up to 1.5 (a close guess, e.g. from
  // a neighbouring contact radius, with a small first step saves evaluations).
  CohesiveState solve(double sigma_hat, double h0, double guess_excess = 1.0, double first_step = 1.5) const;
  double contact_radius() const { return a_; }
  int unknowns() const { return system_ ? static_cast<int>(system_->size()) : 0; }
  // Gap evaluations of the last solve() (cost statistics).
  int last_evaluations() const { return last_evaluations_; }

 private:
  const KernelSource& kernel_;
  double a_;
  double radius_;   // the paraboloid's R (1 with a shape load)
  ShapeLoad shape_;  // empty: the paraboloid z = x²/2R
  CohesiveQuadrature quadrature_;
  std::unique_ptr<FactoredSystem> system_;
  std::vector<double> gamma_fp_, gamma_s_;
  double edge_fp_ = 0.0, edge_s_ = 0.0;
  mutable int last_evaluations_ = 0;

  // What evaluate() and functions() share at one excess: the geometry, the outer rule, the
  // cohesive solution γ_c and its edge value, the kernel rows at the rule's nodes and the
  // kernel sums there.
  struct Pass;
  void pass(double excess, Pass& out) const;
  void factor(const Discretization& disc);
  // ∫_0^φa δ0(c cos φ) dφ on the annulus rule: a shape load's part of the gap h(c) (THEORY.md
  // section 13; the paraboloid's is in closed form).
  double shape_gap(const Pass& p) const;
};

}  // namespace coatcontact::detail
