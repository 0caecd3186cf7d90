// Adhesive sphere with a Maugis-Dugdale cohesive zone on a coated substrate (THEORY.md
// section 13): beside the JKR law of adhesion.hpp, for a zone of finite size. Unlike JKR it
// needs one solve per contact radius (the zone radius c depends on a, eta and lambda), so it
// is a model of its own rather than a law on the interpolated reduced variables.
//
// Normalization as adhesion.hpp (reference modulus E* of the top layer): a_bar, eta, P, D;
// lambda = 2 sigma0 (R/(pi w K^2))^(1/3) with K = 4E*/3 (Maugis 1992), m = c/a,
// a_bar_M = (4/3)^(1/3) a_bar. lambda -> infinity is JKR, lambda -> 0 DMT.
//
// Thread safety: const member functions may run concurrently.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/limits.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

struct MaugisDugdaleOptions {
  int nodes_per_panel = 14;          // p of the contact discretization (THEORY.md section 4)
  int annulus_points = 14;           // Gauss points per piece of the cohesive annulus
  double quadrature_accuracy = 1e-13;
  // Pull-off scan: a_bar range (<= 0: [1e-3 min(1, r), 10 max(1, r)], r as adhesion.hpp) and
  // grid density; each local minimum on the grid is refined by a Brent minimiser in ln a_bar
  // to `location_tolerance` (relative), then as the root of the derivative differentiated
  // implicitly through c(a) (location ~1e-10; the minimum value to ~1e-13).
  double a_bar_min = 0.0;
  double a_bar_max = 0.0;
  int scan_points_per_decade = 8;
  double location_tolerance = 1e-7;
  // Points from the reduced table of the cohesive zone (THEORY.md section 13, "The cohesive
  // zone as a table"), built per model tile by tile as queries need them, wherever it covers a/t in
  // [table_a_over_t_min, table_a_over_t_max] and the root c/a - 1 (c/t <= 1e4), and at the
  // end a = 0 (c/t in [1e-5, 1e4]); the direct solve elsewhere. Values then differ from the
  // direct ones by the table's error, each within its estimate (MaugisDugdalePoint::*_error;
  // tests/adhesive/test_md_table.cpp: P to ~1.2e-4, D to ~9e-5, m to ~4e-4); the pull-off
  // location is the minimiser's (location_tolerance), without the implicit-derivative
  // refinement. Off here (the library's reference); the CLI and the fit turn it on.
  bool use_table = false;
  double table_a_over_t_min = 1e-4;
  double table_a_over_t_max = 1e2;
  // false: points from the table carry no error estimate (m_error, load_error and
  // penetration_error 0), saving ~20 % of a point; for callers that use values only (the AFM
  // fit's trials). Pull-offs need the estimates: keep true for them.
  bool table_errors = true;
};

// One point of the curve; a_bar = 0 is the end of the curve (contact shrunk to a point at
// finite force: no contact, a disk of tension of radius c), where m is infinite.
struct MaugisDugdalePoint {
  double eta = 0.0;
  double lambda = 0.0;
  double a_bar = 0.0;
  double a_over_t = 0.0;
  double m = 0.0;            // c/a
  double c_bar = 0.0;        // c/(pi w R^2/E*)^(1/3)
  double load = 0.0;         // P
  double penetration = 0.0;  // D
  int gap_evaluations = 0;   // cost of the root c(a)
  // Error estimates of m, P, D: the table's (MaugisDugdaleOptions::use_table), or the direct
  // solve's own (root to 1e-13 in ln(c/a - 1), values ~1e-11 relative).
  double m_error = 0.0, load_error = 0.0, penetration_error = 0.0;
  // At a pull-off (MaugisDugdalePulloffPoint): the estimate of a_bar's error (the location of
  // the minimum), and m, P, D's estimates there include the location's; elsewhere 0.
  double a_bar_error = 0.0;
  bool from_table = false;   // false: the direct per-radius solve
};

struct MaugisDugdalePulloffPoint {
  MaugisDugdalePoint point;
  bool interior = true;  // false: the minimum sits at the end of the curve, a -> 0
  int local_minima = 0;
};

struct MaugisDugdalePulloff {
  double eta = 0.0;
  double lambda = 0.0;
  MaugisDugdalePulloffPoint load_control;          // minimum of P over a_bar
  MaugisDugdalePulloffPoint displacement_control;  // minimum of D over a_bar
  // pulloff_spring with k_bar > 0: the minimum of Z = D + P/k_bar over a_bar (THEORY.md
  // section 10; k_bar = inf: displacement control); k_bar = 0: not computed.
  MaugisDugdalePulloffPoint spring_control;
  double k_bar = 0.0;
  MaugisDugdalePoint curve_end;                    // a -> 0
  double a_bar_scan_min = 0.0, a_bar_scan_max = 0.0;
  int point_evaluations = 0;
  std::vector<std::string> warnings;
};

class MaugisDugdaleModel {
 public:
  // Builds the kernel table of the stack once. An elastic indenter enters through the stack's
  // reference modulus E_r and kernel C' (THEORY.md sections 9 and 13); lambda then takes
  // K = 4E_r/3.
  explicit MaugisDugdaleModel(const Stack& stack, MaugisDugdaleOptions options = {});
  ~MaugisDugdaleModel();
  MaugisDugdaleModel(const MaugisDugdaleModel&) = delete;
  MaugisDugdaleModel& operator=(const MaugisDugdaleModel&) = delete;

  // P, D, m at a_bar >= 0 (0: the end of the curve) for eta, lambda > 0 (InputError otherwise;
  // NumericalError if the root c(a) cannot be found).
  MaugisDugdalePoint point(double eta, double lambda, double a_bar) const;
  std::vector<MaugisDugdalePoint> curve(double eta, double lambda, const std::vector<double>& a_bar) const;
  MaugisDugdalePulloff pulloff(double eta, double lambda) const;
  // pulloff() plus the pull-off through a spring of normalized stiffness k_bar = k L_D/(pi w R)
  // (THEORY.md sections 10 and 13): the minimum of Z = D + P/k_bar along the same curve, or its
  // end a -> 0 when that lies lower; located by the minimiser (~location_tolerance in a_bar).
  MaugisDugdalePulloff pulloff_spring(double eta, double lambda, double k_bar) const;
  // pulloff(eta_i, lambda_i) for each pair, computed in parallel (OpenMP); the same values as
  // one call per pair. The first failing pair's exception is rethrown.
  std::vector<MaugisDugdalePulloff> pulloffs(const std::vector<std::pair<double, double>>& eta_lambda) const;

  const Stack& stack() const;
  const MaugisDugdaleOptions& options() const;
  // With use_table: builds every tile of the table now (otherwise each on first use); the
  // direct solves the tiles built so far rest on, whether solved by this process or read from
  // the solve cache (coatcontact/solve_cache.hpp), and the wall seconds spent building them.
  // Without: nothing, zeros.
  void build_table() const;
  long table_nodes() const;
  // With use_table on a homogeneous half-space (film and substrate of one material): Maugis's
  // closed forms stand for the table (its kernel is zero), no node is solved.
  bool table_in_closed_form() const;
  double table_seconds() const;

 private:
  double refine(double eta, double lambda, double ln_a_bar, bool load, double guess_excess, int& evaluations) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace coatcontact
